!> contact_zones: the zone of a chain of nodes (chain_zone) on nodal values
!> made from closed forms, so that the right answer is known exactly:
!>   - a Hertz profile p = sqrt(a^2 - x^2) on a uniform chain, the edge a
!>     between nodes: the ends by the square-root rule within 10 % of the
!>     spacing h of +-a (p^2 = (a - x)(a + x) is linear in x near the edge up
!>     to its curvature: the rule's offset d past the last node x_b is off by
!>     d (a - x_{b-1}) / (x_b + x_{b-1}), 7 % of h here);
!>   - the same profile shifted, the chain run backward: the same ends swapped;
!>   - a stick zone on the same nodes, next to open ones: the contact zone's
!>     ends (by the pressure, not its own margin);
!>   - a flat punch profile (rising toward the ends): the ends on the last
!>     nodes in contact;
!>   - a single node in contact: the ends half-way to its neighbours;
!>   - two disjoint zones: count 2, each one's ends and length in order
!>     along the chain, the total the sum of the two; each node's zone;
!>   - a zone on the chain's end node: that node is the end;
!>   - a closed curve (a circle) all round: both ends the first node, the
!>     length the perimeter; a zone across the first node: one zone, its ends
!>     by the rule on either side of it; with a second zone further round,
!>     the one across node 1 comes first.
program test_contact_zones
  use kinds, only: dp
  use contact_zones, only: zone_t, chain_zone
  use testing, only: check, check_small, finish_tests
  implicit none
  integer, parameter :: n = 41
  real(dp), parameter :: h = 0.05_dp, a = 0.537_dp
  real(dp) :: s(n), x(2, n), p(n), pi
  logical :: inside(n)
  type(zone_t) :: z
  integer :: i, m

  pi = acos(-1.0_dp)
  do i = 1, n
    s(i) = (i - 1) * h
    x(:, i) = [-1.0_dp + (i - 1) * h, 0.25_dp]
  end do

  ! Hertz: the edges at -a and a
  p = sqrt(max(0.0_dp, a**2 - x(1, :)**2))
  inside = p > 0.0_dp
  call chain_zone(s, x, inside, p, .false., z)
  call check(z%count == 1, 'hertz: one zone')
  call check_small((z%x0(1, 1) + a) / h, 0.1_dp, 'hertz: start at -a within 10% of h')
  call check_small((z%x1(1, 1) - a) / h, 0.1_dp, 'hertz: end at a within 10% of h')
  call check_small(z%x0(2, 1) - 0.25_dp, 1.0e-15_dp, 'hertz: the ends on the chain (y)')
  call check_small((z%length(1) - 2 * a) / h, 0.2_dp, 'hertz: length 2a')
  call check_small(z%total - z%length(1), 1.0e-15_dp, 'hertz: one zone, total = length')
  ! a stick zone on the same nodes (a margin of another shape): next to the
  ! open nodes its ends are the contact zone's, by the pressure
  block
    type(zone_t) :: zc
    zc = z
    call chain_zone(s, x, inside, 0.3_dp * p**3, .false., z, .not. inside, p)
    call check_small(maxval(abs(z%x0 - zc%x0)) + maxval(abs(z%x1 - zc%x1)), 1.0e-15_dp, &
                     'stick zone up to the open nodes: the contact zone''s ends')
    call chain_zone(s, x, inside, 0.3_dp * p**3, .false., z)
    call check(abs(z%x1(1, 1) - zc%x1(1, 1)) > 0.01_dp * h, 'the same by its own margin: other ends (the test can fail)')
  end block

  ! shifted by 0.1 and walked backward: start near 0.1 + a, end near 0.1 - a
  p = sqrt(max(0.0_dp, a**2 - (x(1, n:1:-1) - 0.1_dp)**2))
  inside = p > 0.0_dp
  call chain_zone(s, x(:, n:1:-1), inside, p, .false., z)
  call check_small((z%x0(1, 1) - (0.1_dp + a)) / h, 0.1_dp, 'backward: start at 0.1 + a')
  call check_small((z%x1(1, 1) - (0.1_dp - a)) / h, 0.1_dp, 'backward: end at 0.1 - a')

  ! flat punch on |x| <= 0.5 (nodes at +-0.5): p = 1 / sqrt(1 - (x/0.55)^2) rises to the ends
  inside = abs(x(1, :)) <= 0.5_dp + 1.0e-12_dp
  p = merge(1.0_dp / sqrt(1.0_dp - (x(1, :) / 0.55_dp)**2), 0.0_dp, inside)
  call chain_zone(s, x, inside, p, .false., z)
  call check_small(z%x0(1, 1) + 0.5_dp, 1.0e-12_dp, 'punch: start on the last node in contact')
  call check_small(z%x1(1, 1) - 0.5_dp, 1.0e-12_dp, 'punch: end on the last node in contact')

  ! one node in contact (node 21, x = 0): the ends half-way to its neighbours
  inside = .false.
  inside(21) = .true.
  p = merge(1.0_dp, 0.0_dp, inside)
  call chain_zone(s, x, inside, p, .false., z)
  call check(z%count == 1, 'one node: one zone')
  call check_small(z%x0(1, 1) + h / 2, 1.0e-12_dp, 'one node: start half-way to the open neighbour')
  call check_small(z%x1(1, 1) - h / 2, 1.0e-12_dp, 'one node: end half-way')

  ! two zones: Hertz profiles of half-width 0.2 around -0.5 and 0.5
  p = sqrt(max(0.0_dp, 0.2_dp**2 - (abs(x(1, :)) - 0.5_dp)**2))
  inside = p > 0.0_dp
  call chain_zone(s, x, inside, p, .false., z)
  call check(z%count == 2, 'two zones: counted')
  call check_small((z%x0(1, 1) + 0.7_dp) / h, 0.02_dp, 'two zones: the first one''s start')
  call check_small((z%x1(1, 1) + 0.3_dp) / h, 0.02_dp, 'two zones: the first one''s end')
  call check_small((z%x0(1, 2) - 0.3_dp) / h, 0.02_dp, 'two zones: the second one''s start')
  call check_small((z%x1(1, 2) - 0.7_dp) / h, 0.02_dp, 'two zones: the second one''s end')
  call check_small((z%length(1) - 0.4_dp) / h, 0.04_dp, 'two zones: the first one''s length')
  call check_small((z%length(2) - 0.4_dp) / h, 0.04_dp, 'two zones: the second one''s length')
  call check_small((z%total - 0.8_dp) / h, 0.08_dp, 'two zones: total = the sum of the two')
  block
    integer :: member(n)
    call chain_zone(s, x, inside, p, .false., z, member=member)
    call check(all(member == merge(merge(1, 2, x(1, :) < 0.0_dp), 0, inside)), 'two zones: each node''s zone')
  end block

  ! a zone reaching the chain's last node: it ends there
  inside = x(1, :) > 0.6_dp
  p = merge(1.0_dp, 0.0_dp, inside)
  call chain_zone(s, x, inside, p, .false., z)
  call check_small(z%x1(1, 1) - 1.0_dp, 1.0e-12_dp, 'chain end: the end node')

  ! nothing inside: count 0
  inside = .false.
  call chain_zone(s, x, inside, p, .false., z)
  call check(z%count == 0 .and. size(z%length) == 0 .and. z%total == 0.0_dp, 'no node inside: count 0, no zone')

  ! closed: a unit circle of m = 40 segments, node m + 1 = node 1
  m = 40
  block
    real(dp) :: sc(m + 1), xc(2, m + 1), pc(m + 1), th, ac
    logical :: ic(m + 1)
    do i = 1, m + 1
      th = 2 * pi * (i - 1) / m
      xc(:, i) = [cos(th), sin(th)]
      sc(i) = (i - 1) * 2 * sin(pi / m)
    end do
    ic = .true.
    pc = 1.0_dp
    call chain_zone(sc, xc, ic, pc, .true., z)
    call check(z%count == 1, 'closed all round: one zone')
    call check_small(maxval(abs(z%x0(:, 1) - xc(:, 1))) + maxval(abs(z%x1(:, 1) - xc(:, 1))), 1.0e-15_dp, &
                     'closed all round: both ends the first node')
    call check_small(z%length(1) - sc(m + 1), 1.0e-14_dp, 'closed all round: length the perimeter')
    ! a zone across node 1: |angle| < ac, p^2 linear in the arc there
    ac = 2 * pi * 3.4_dp / m
    do i = 1, m + 1
      th = 2 * pi * (i - 1) / m
      if (i > m / 2) th = th - 2 * pi
      pc(i) = sqrt(max(0.0_dp, ac - abs(th)))
    end do
    ic = pc > 0.0_dp
    call chain_zone(sc, xc, ic, pc, .true., z)
    call check(z%count == 1, 'closed, across node 1: one zone')
    call check_small((z%total - 2 * ac * sc(2) / (2 * pi / m)) / sc(2), 1.0e-9_dp, &
                     'closed, across node 1: length 2 x 3.4 segments (p^2 linear in the arc)')
    call check(z%x0(2, 1) < 0.0_dp .and. z%x1(2, 1) > 0.0_dp, 'closed, across node 1: from below the first node to above it')
    ! and a second zone round the opposite node (angle pi), its edges at pi +- ac:
    ! the zone across node 1 first, then that one
    do i = 1, m + 1
      th = 2 * pi * (i - 1) / m
      pc(i) = pc(i) + sqrt(max(0.0_dp, ac - abs(th - pi)))
    end do
    ic = pc > 0.0_dp
    call chain_zone(sc, xc, ic, pc, .true., z)
    call check(z%count == 2, 'closed, two zones: counted')
    call check(z%x0(2, 1) < 0.0_dp .and. z%x1(2, 1) > 0.0_dp .and. z%x0(1, 1) > 0.0_dp, &
               'closed, two zones: the one across node 1 first')
    call check(z%x0(2, 2) > 0.0_dp .and. z%x1(2, 2) < 0.0_dp .and. z%x0(1, 2) < 0.0_dp, &
               'closed, two zones: the one round angle pi second')
    call check_small((z%length(2) - 2 * ac * sc(2) / (2 * pi / m)) / sc(2), 1.0e-9_dp, &
                     'closed, two zones: the second one''s length 2 x 3.4 segments')
  end block
  call finish_tests()
end program test_contact_zones
