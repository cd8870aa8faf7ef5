!> contact_zones: the engineering results of a contact pair read off its
!> solved multipliers, zone by zone — where each zone in contact ends, its
!> length, its peak pressure and where it is, its centre of pressure, and with
!> friction the stick zones (doc/outputs.md, "Contact zones").
!>
!> A zone's end lies between the last slave node in contact and the first
!> open one.  The discrete pressure there is a nodal value per node, and the
!> first open node has none (p = 0), so a plain linear interpolation of p
!> would put every end on the open node.  Near a smooth edge the pressure
!> goes as the square root of the distance to it (Hertz: p = p0 sqrt(1 -
!> x^2/a^2)), so p^2 is linear there: the end is where the line through p^2
!> at the last two nodes in contact reaches 0, held inside the element to
!> the first open node.  Where the pressure does not fall toward the end (a
!> punch's corner) the end is the last node in contact; a zone of one node
!> ends half-way to its open neighbours.  The stick zone's ends follow the
!> same rule on the friction margin mu p - |q| (Tresca: bound - |q|), which
!> also goes as a square root at the stick-slip edge (Cattaneo-Mindlin: mu
!> p0/a sqrt(c^2 - x^2) inside |x| < c); a stick zone that reaches the edge
!> of contact (its next node open, not slipping) ends where the contact zone
!> does.
!>
!> Several disjoint zones (a cylinder in a V-groove touches both flanks
!> through one pair): each is reported, in order along the slave boundary
!> (its own node order), with the count of zones and the sum of their
!> lengths beside.  A closed slave curve in contact all round has no ends:
!> both are its first node and the length is the curve's; a zone across the
!> curve's first node is one zone, and the first one.
!>
!> Programming interface
!>   type(zone_t)        the zones' ends x0(:, k), x1(:, k), lengths, their count and total length
!>   type(pair_zones_t)  contact zones, stick zones, each contact zone's peak pressure (p, x, y)
!>                       and centre of pressure
!>   chain_zone(s, x, inside, f, closed, zone)      the zones of one chain of nodes (the rule above)
!>   pair_zones(cs, ip, mu, status, tau, fstate, z) the results of pair ip
!>   true_runs(mask, first, last, nrun)             the runs of true entries of a mask
module contact_zones
  use kinds, only: dp
  use contact_set, only: contact_set_t, row_of_node, node_rows, node_traction, has_friction
  implicit none
  private
  public :: zone_t, pair_zones_t, chain_zone, pair_zones, true_runs

  !> The zones along the slave boundary (contact or stick), in order.
  type :: zone_t
    integer :: count = 0                    !< disjoint zones (0: none)
    real(dp), allocatable :: x0(:,:)        !< (2, count) each zone's start (reference coordinates)
    real(dp), allocatable :: x1(:,:)        !< (2, count) each zone's end
    real(dp), allocatable :: length(:)      !< (count) each zone's arc length along the slave boundary
    real(dp) :: total = 0.0_dp              !< the sum of the zones' lengths
  end type zone_t

  !> What a pair reports (doc/outputs.md).
  type :: pair_zones_t
    type(zone_t) :: contact                 !< the slave nodes in contact
    logical :: friction = .false.           !< the pair has friction: stick is set
    type(zone_t) :: stick                   !< the slave nodes that stick
    real(dp), allocatable :: peak(:,:)      !< (3, contact%count) each zone's largest nodal
                                            !< pressure, the node's x, y
    real(dp), allocatable :: centre(:,:)    !< (2, contact%count) each zone's centre of pressure:
                                            !< its nodes' positions weighted by their normal forces
  end type pair_zones_t

contains

  !> The zones of the nodes marked inside along one chain (module header).
  !>   s      (in)  (n) arc length of each node along the chain, increasing
  !>   x      (in)  (2, n) the nodes' reference coordinates
  !>   inside (in)  (n) the node is in a zone
  !>   f      (in)  (n) the quantity that vanishes at a zone's edge, >= 0 inside
  !>                (pressure, friction margin); only its values inside are used
  !>   closed (in)  node n is node 1 again (a closed curve; inside(n) = inside(1))
  !>   zone   (out) the zones in order along the chain; count 0 when no node is inside
  !>   outer  (in, optional) (n) the nodes outside an enclosing zone (the stick
  !>                zone's: the open nodes, outside the contact zone)
  !>   g      (in, optional) (n) the enclosing zone's quantity (the pressure): an
  !>                end next to an outer node is the enclosing zone's end, by g
  !>   member (out, optional) (n) the zone of each node, 1 .. count (0: not inside)
  pure subroutine chain_zone(s, x, inside, f, closed, zone, outer, g, member)
    real(dp), intent(in) :: s(:), x(:,:), f(:)
    logical, intent(in) :: inside(:), closed
    type(zone_t), intent(out) :: zone
    logical, intent(in), optional :: outer(:)
    real(dp), intent(in), optional :: g(:)
    integer, intent(out), optional :: member(:)
    integer :: n, k, j, open_node
    integer, allocatable :: order(:), in_zone(:)
    real(dp), allocatable :: sr(:), ge(:)
    logical, allocatable :: edge(:)
    n = size(s)
    allocate(zone%x0(2, 0), zone%x1(2, 0), zone%length(0), in_zone(n))
    in_zone = 0
    if (present(member)) member = 0
    if (n == 0 .or. .not. any(inside)) return
    allocate(edge(n), ge(n))
    edge = .false.
    ge = f
    if (present(outer) .and. present(g)) then
      edge = outer
      ge = g
    end if
    if (.not. closed) then
      call open_chain_zone(s, x, inside, f, edge, ge, zone, in_zone)
      if (present(member)) member = in_zone
      return
    end if
    if (all(inside(1:n - 1))) then                 ! all round: no ends
      zone%count = 1
      zone%x0 = reshape(x(:, 1), [2, 1])
      zone%x1 = zone%x0
      zone%length = [s(n) - s(1)]
      zone%total = zone%length(1)
      if (present(member)) member = 1
      return
    end if
    ! start the chain at an open node, so that no zone crosses its ends
    open_node = 1
    do k = 1, n - 1
      if (.not. inside(k)) then
        open_node = k
        exit
      end if
    end do
    allocate(order(n), sr(n))
    do j = 1, n
      order(j) = mod(open_node - 1 + j - 1, n - 1) + 1
    end do
    sr(1) = 0.0_dp
    do j = 2, n
      if (order(j) > order(j - 1)) then
        sr(j) = sr(j - 1) + s(order(j)) - s(order(j - 1))
      else                                          ! across node 1: the closing segment
        sr(j) = sr(j - 1) + s(n) - s(order(j - 1))
      end if
    end do
    call open_chain_zone(sr, x(:, order), inside(order), f(order), edge(order), ge(order), zone, in_zone)
    if (inside(1)) then
      ! the zone across node 1 came last from the open node on: it holds
      ! node 1, so it is the first along the curve
      zone%x0 = cshift(zone%x0, -1, dim=2)
      zone%x1 = cshift(zone%x1, -1, dim=2)
      zone%length = cshift(zone%length, -1)
      where (in_zone > 0) in_zone = mod(in_zone, zone%count) + 1
    end if
    if (present(member)) then
      member(order(1:n - 1)) = in_zone(1:n - 1)
      member(n) = member(1)
    end if
  end subroutine chain_zone

  !> chain_zone on an open chain; at an end next to an edge node the zone's
  !> quantity is g, not f.  in_zone (n) is each node's zone (0: none).
  pure subroutine open_chain_zone(s, x, inside, f, edge, g, zone, in_zone)
    real(dp), intent(in) :: s(:), x(:,:), f(:), g(:)
    logical, intent(in) :: inside(:), edge(:)
    type(zone_t), intent(inout) :: zone
    integer, intent(out) :: in_zone(:)
    integer, allocatable :: first(:), last(:)
    integer :: n, r, nrun
    real(dp) :: sa, sb
    n = size(s)
    call true_runs(inside, first, last, nrun)
    zone%count = nrun
    deallocate(zone%x0, zone%x1, zone%length)
    allocate(zone%x0(2, nrun), zone%x1(2, nrun), zone%length(nrun))
    in_zone = 0
    zone%total = 0.0_dp
    do r = 1, nrun
      call zone_end(first(r), -1, sa, zone%x0(:, r))
      call zone_end(last(r), +1, sb, zone%x1(:, r))
      zone%length(r) = sb - sa
      zone%total = zone%total + zone%length(r)
      in_zone(first(r):last(r)) = r
    end do

  contains

    !> The end of the zone at its last node m, looking in direction dir
    !> (+1 along the chain, -1 against it): arc position se and point xe.
    pure subroutine zone_end(m, dir, se, xe)
      integer, intent(in) :: m, dir
      real(dp), intent(out) :: se, xe(2)
      integer :: nxt, prv
      real(dp) :: t, slope, h, fm, fp
      nxt = m + dir
      prv = m - dir
      if (nxt < 1 .or. nxt > n) then                ! the chain's end
        se = s(m)
        xe = x(:, m)
        return
      end if
      t = 0.5_dp                                    ! a zone of one node
      if (prv >= 1 .and. prv <= n) then
        if (inside(prv)) then
          ! the zero of the line through f^2 at prv and m, beyond m
          if (edge(nxt)) then
            fm = max(g(m), 0.0_dp); fp = max(g(prv), 0.0_dp)
          else
            fm = max(f(m), 0.0_dp); fp = max(f(prv), 0.0_dp)
          end if
          h = abs(s(nxt) - s(m))
          if (fm >= fp .or. h <= 0.0_dp .or. abs(s(m) - s(prv)) <= 0.0_dp) then
            t = 0.0_dp                              ! not falling toward the end: a corner
          else
            slope = (fm**2 - fp**2) / abs(s(m) - s(prv))
            t = min(1.0_dp, fm**2 / (-slope) / h)
          end if
        end if
      end if
      se = s(m) + t * (s(nxt) - s(m))
      xe = x(:, m) + t * (x(:, nxt) - x(:, m))
    end subroutine zone_end

  end subroutine open_chain_zone

  !> The runs of consecutive true entries of mask, in order: run r is
  !> mask(first(r):last(r)); the zones here, the zones of contact_checks.
  !>   mask        (in)  (n) the entries
  !>   first, last (out) (n) the runs' first and last entries, 1 .. nrun
  !>   nrun        (out) how many runs
  pure subroutine true_runs(mask, first, last, nrun)
    logical, intent(in) :: mask(:)
    integer, allocatable, intent(out) :: first(:), last(:)
    integer, intent(out) :: nrun
    integer :: n, a, b
    n = size(mask)
    allocate(first(n), last(n))
    nrun = 0
    a = 1
    do while (a <= n)
      if (.not. mask(a)) then
        a = a + 1
        cycle
      end if
      b = a
      do while (b < n)
        if (.not. mask(b + 1)) exit
        b = b + 1
      end do
      nrun = nrun + 1
      first(nrun) = a
      last(nrun) = b
      a = b + 1
    end do
  end subroutine true_runs

  !> The contact zones, each one's peak pressure and centre of pressure, and
  !> (friction) the stick zones of pair ip, from the multipliers of a solved
  !> state.
  !>   cs     (in)  the contact set
  !>   ip     (in)  the pair, 1 .. cs%npair
  !>   mu     (in)  (nrow) normal multipliers (nodal forces); size 0: no contact solved
  !>   status (in)  (nrow) 1 in contact, 0 open
  !>   tau    (in)  (ntan) tangential multipliers (size 0 without friction)
  !>   fstate (in)  (ntan) 0 open, 1 stick, 2 slip (size 0 without friction)
  !>   z      (out) the pair's results (counts 0 and arrays of size 0 when nothing is in contact)
  subroutine pair_zones(cs, ip, mu, status, tau, fstate, z)
    type(contact_set_t), intent(in) :: cs
    integer, intent(in) :: ip
    real(dp), intent(in) :: mu(:), tau(:)
    integer, intent(in) :: status(:), fstate(:)
    type(pair_zones_t), intent(out) :: z
    integer :: ns, i, r, t, rows(3), nr, k, j, nz
    integer, allocatable :: tan_of(:), member(:)
    real(dp), allocatable :: p(:), margin(:), tforce(:), force(:)
    logical, allocatable :: touch(:), stick(:)
    logical :: closed
    allocate(z%peak(3, 0), z%centre(2, 0))
    if (size(mu) == 0) return
    deallocate(z%peak, z%centre)
    associate(pr => cs%pair(ip))
      ns = size(pr%snode)
      z%friction = has_friction(pr%spec) .and. size(fstate) > 0
      allocate(p(ns), margin(ns), touch(ns), stick(ns), tan_of(cs%nrow), tforce(cs%nrow), member(ns))
      p = 0.0_dp; margin = 0.0_dp; touch = .false.; stick = .false.
      tan_of = 0
      tforce = 0.0_dp
      if (z%friction) then
        do t = 1, size(fstate)
          tan_of(cs%tan_row(t)) = t
          tforce(cs%tan_row(t)) = -tau(t)             ! the force on the slave is -tau t
        end do
      end if
      do i = 1, ns
        call node_rows(cs, ip, i, rows, nr)
        if (nr == 0) cycle
        p(i) = node_traction(cs, ip, i, mu)
        touch(i) = any(status(rows(1:nr)) == 1)
        if (.not. z%friction) cycle
        r = row_of_node(cs, ip, i)
        t = tan_of(r)
        if (t == 0) cycle
        stick(i) = touch(i) .and. fstate(t) == 1
        if (pr%spec%tresca > 0.0_dp) then
          margin(i) = pr%spec%tresca - abs(node_traction(cs, ip, i, tforce))
        else
          margin(i) = pr%spec%mu * p(i) - abs(node_traction(cs, ip, i, tforce))
        end if
      end do
      closed = ns > 1 .and. pr%snode(1) == pr%snode(ns)
      if (closed) then
        ! the first node twice: its row is on one of the two (contact table)
        k = merge(ns, 1, row_of_node(cs, ip, ns) > 0)
        p([1, ns]) = p(k); touch([1, ns]) = touch(k); stick([1, ns]) = stick(k); margin([1, ns]) = margin(k)
      end if
      call chain_zone(pr%mortar%arc, pr%xs, touch, p, closed, z%contact, member=member)
      if (z%friction) call chain_zone(pr%mortar%arc, pr%xs, stick, margin, closed, z%stick, .not. touch, p)
      nz = z%contact%count
      allocate(z%peak(3, nz), z%centre(2, nz), force(nz))
      do j = 1, nz
        k = maxloc(p, dim=1, mask=touch .and. member == j)
        z%peak(:, j) = [p(k), pr%xs(:, k)]
      end do
      force = 0.0_dp
      z%centre = 0.0_dp
      do r = pr%row0 + 1, pr%row0 + pr%nrow
        if (status(r) /= 1) cycle
        j = member(cs%row_node(r))
        if (j == 0) cycle
        force(j) = force(j) + mu(r)
        z%centre(:, j) = z%centre(:, j) + mu(r) * pr%xs(:, cs%row_node(r))
      end do
      do j = 1, nz
        if (force(j) > 0.0_dp) z%centre(:, j) = z%centre(:, j) / force(j)
      end do
    end associate
  end subroutine pair_zones

end module contact_zones
