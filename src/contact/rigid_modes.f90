!> rigid_modes: the rigid-body modes that a body's Dirichlet data leave free.
!>
!> A body held by FIX statements in too few directions (say, the upper block
!> of the patch test loaded by a pressure on top instead of a prescribed
!> displacement) has a singular stiffness K: its free rigid modes R satisfy
!> K R = 0.  contact2d handles them exactly, as in FETI's natural coarse
!> space: K is factorized with k well-chosen "pinned" dofs held at zero, which
!> gives a generalized inverse K^# (K K^# b = b for every b in range(K)), and
!>     u = K^# (f - B' mu) + R alpha,     R' (f - B' mu) = 0,
!> the second equation being the body's equilibrium along its free modes,
!> which the contact forces must supply.  No spring is added anywhere.
!>
!> The modes of body b: the three rigid motions (two translations, a rotation
!> about the centroid scaled by the body's size), restricted to the fixed dofs
!> as C (nfixed x 3); the right singular vectors of C with zero singular value
!> span the free modes.  A body's springs (SPRING) are in K too: a rigid
!> motion r3 c that strains a spring is no null vector of K, and since the
!> springs' matrix K_s is positive semi-definite, K_s r3 c = 0 exactly when
!> c' G c = 0, G = r3' K_s r3 (3 x 3).  G, scaled to a largest entry of 1,
!> joins C's rows: a mode any spring resists is held (a body on springs
!> alone floats in no direction they reach; a point spring kx holds one
!> combination of the translation x and the rotation, and contact or FIX the
!> others).  The pinned dofs are the first k pivots of a QR
!> factorization with column pivoting (dgeqp3) of R_b' over the free dofs, so
!> R_b(pinned, :) is well conditioned.
!>
!> Programming interface
!>   type(floating_t)                          k modes, R, their bodies, pinned dofs
!>   find_floating_modes(bodies, fixed, fl)    fixed (ndof): Dirichlet dofs
!>   mode_name(fl, j)                          'translation x', 'rotation', ...
!>   describe_motion(fl, c, kind, point)       the rigid motion R c of one body: a rotation
!>                                             about a point, or a translation along a direction
!>   motion_name(fl, c)                        'rotation about (x, y)', 'translation along (dx, dy)'
!>   remove_motions(fl, c, u)                  u <- u minus its components along R c(:, i)
module rigid_modes
  use kinds, only: dp
  use lapack_interfaces, only: dgeqp3, dgesvd, dsysv
  use body, only: body_t
  use foundation, only: spring_set_t
  implicit none
  private
  public :: floating_t, find_floating_modes, mode_name, describe_motion, motion_name, remove_motions

  type :: floating_t
    integer :: k = 0                         !< number of free rigid modes, all bodies
    real(dp), allocatable :: r(:,:)          !< (ndof, k) the modes, zero on fixed dofs, unit length
    integer, allocatable :: mode_body(:)     !< (k) body of each mode
    real(dp), allocatable :: coef(:,:)       !< (3, k) mode = coef(1) tx + coef(2) ty + coef(3) rotation
    integer, allocatable :: pin(:)           !< (k) dofs held at zero in the factorization
    real(dp), allocatable :: centre(:,:)     !< (2, k) centroid of the mode's body (its rotation centre)
    real(dp), allocatable :: length(:)       !< (k) size of the body (rotation scale)
    real(dp), allocatable :: norm(:)         !< (k) |r3 coef| before normalization: mode = r3 coef / norm
  end type floating_t


contains

  !> Free rigid modes of every body and the dofs pinned to factorize K^#.
  !>   bodies (in)  the bodies, dof0 set
  !>   fixed  (in)  (ndof) Dirichlet dofs
  !>   fl     (out) the modes (fl%k = 0 when every body is held by its FIX)
  subroutine find_floating_modes(bodies, fixed, fl)
    type(body_t), intent(in) :: bodies(:)
    logical, intent(in) :: fixed(:)
    type(floating_t), intent(out) :: fl
    integer :: b, nb, kb, ndof, j
    real(dp), allocatable :: modes(:,:), coefs(:,:), norms(:)
    integer, allocatable :: pins(:)
    real(dp), allocatable :: r(:,:), c(:,:), xc(:,:), lb(:), nr(:)
    integer, allocatable :: mb(:), pn(:)
    real(dp) :: centre(2), length

    ndof = size(fixed)
    allocate(r(ndof, 0), c(3, 0), mb(0), pn(0), xc(2, 0), lb(0), nr(0))
    nb = size(bodies)
    do b = 1, nb
      call body_modes(bodies(b), fixed, modes, coefs, pins, norms, centre, length)
      kb = size(modes, 2)
      if (kb == 0) cycle
      r = reshape([r, [(0.0_dp, j = 1, ndof * kb)]], [ndof, size(r, 2) + kb])
      r(bodies(b)%dof0 + 1:bodies(b)%dof0 + 2 * bodies(b)%mesh%nnode, size(r, 2) - kb + 1:) = modes
      c = reshape([c, coefs], [3, size(c, 2) + kb])
      mb = [mb, [(b, j = 1, kb)]]
      pn = [pn, bodies(b)%dof0 + pins]
      xc = reshape([xc, [(centre, j = 1, kb)]], [2, size(xc, 2) + kb])
      lb = [lb, [(length, j = 1, kb)]]
      nr = [nr, norms]
    end do
    fl%k = size(mb)
    call move_alloc(r, fl%r)
    call move_alloc(c, fl%coef)
    call move_alloc(mb, fl%mode_body)
    call move_alloc(pn, fl%pin)
    call move_alloc(xc, fl%centre)
    call move_alloc(lb, fl%length)
    call move_alloc(nr, fl%norm)
  end subroutine find_floating_modes

  !> Free modes of one body: modes (2 nnode, kb), coefs (3, kb), pins (kb)
  !> as dofs local to the body, norms (kb) |r3 coef| before normalization,
  !> xc the centroid and size_b the size that scale the rotation.
  subroutine body_modes(bd, fixed, modes, coefs, pins, norms, xc, size_b)
    type(body_t), intent(in) :: bd
    logical, intent(in) :: fixed(:)
    real(dp), allocatable, intent(out) :: modes(:,:), coefs(:,:), norms(:)
    integer, allocatable, intent(out) :: pins(:)
    real(dp), intent(out) :: xc(2), size_b
    real(dp), allocatable :: r3(:,:), cmat(:,:), a(:,:), tau(:), work(:)
    real(dp) :: s(3), u(1, 1), vt(3, 3), wq(1), g(3, 3)
    integer :: n, nd, a_, i, nfix, m, info, kb, j, lwork
    integer, allocatable :: fdofs(:), free(:), jpvt(:)

    n = bd%mesh%nnode
    nd = 2 * n
    xc = sum(bd%mesh%x, dim=2) / n
    size_b = max(maxval(bd%mesh%x(1, :)) - minval(bd%mesh%x(1, :)), &
                 maxval(bd%mesh%x(2, :)) - minval(bd%mesh%x(2, :)))
    allocate(r3(nd, 3))
    do a_ = 1, n                                  ! tx, ty, rotation / size
      r3(2 * a_ - 1, :) = [1.0_dp, 0.0_dp, -(bd%mesh%x(2, a_) - xc(2)) / size_b]
      r3(2 * a_, :) = [0.0_dp, 1.0_dp, (bd%mesh%x(1, a_) - xc(1)) / size_b]
      if (allocated(bd%axes)) then                ! a node in local axes: (r.n, r.t), the solver basis
        if (any(bd%axes(:, a_) /= 0.0_dp)) r3(2 * a_ - 1:2 * a_, :) = matmul(reshape([bd%axes(1, a_), &
          -bd%axes(2, a_), bd%axes(2, a_), bd%axes(1, a_)], [2, 2]), r3(2 * a_ - 1:2 * a_, :))
      end if
    end do
    fdofs = pack([(i, i = 1, nd)], fixed(bd%dof0 + 1:bd%dof0 + nd))
    nfix = size(fdofs)
    ! null space of C = r3(fixed dofs, :); a solid of revolution (x = r) has
    ! one rigid motion, the translation along the axis: its C also holds the
    ! r translation and the rotation (rows e_1', e_3'), which strain the hoop
    g = spring_modes(bd%springs, bd%mesh%x, xc, size_b)
    if (nfix == 0 .and. .not. bd%axisymmetric .and. all(g == 0.0_dp)) then
      vt = reshape([1.0_dp, 0.0_dp, 0.0_dp, 0.0_dp, 1.0_dp, 0.0_dp, 0.0_dp, 0.0_dp, 1.0_dp], [3, 3])
      s = 0.0_dp
      kb = 3
    else
      m = nfix
      cmat = r3(fdofs, :)
      if (bd%axisymmetric) then
        m = nfix + 2
        cmat = reshape([cmat(:, 1), 1.0_dp, 0.0_dp, cmat(:, 2), 0.0_dp, 0.0_dp, cmat(:, 3), 0.0_dp, 1.0_dp], [m, 3])
      end if
      if (any(g /= 0.0_dp)) then                  ! the springs' rows: G / max |G|
        g = g / maxval(abs(g))
        cmat = reshape([cmat(:, 1), g(:, 1), cmat(:, 2), g(:, 2), cmat(:, 3), g(:, 3)], [m + 3, 3])
        m = m + 3
      end if
      call dgesvd('N', 'A', m, 3, cmat, m, s, u, 1, vt, 3, wq, -1, info)
      lwork = int(wq(1))
      allocate(work(lwork))
      s = 0.0_dp
      call dgesvd('N', 'A', m, 3, cmat, m, s, u, 1, vt, 3, work, lwork, info)
      deallocate(work)
      ! singular values beyond min(m, 3) are zero; tolerance relative to s(1) >= 1
      kb = count(s(1:3) <= 1.0e-10_dp * max(s(1), 1.0_dp))
    end if
    allocate(modes(nd, kb), coefs(3, kb), pins(kb), norms(kb))
    if (kb == 0) return
    ! the last kb right singular vectors span the null space
    coefs = transpose(vt(3 - kb + 1:3, :))
    modes = matmul(r3, coefs)
    do j = 1, kb
      modes(fdofs, j) = 0.0_dp
      norms(j) = norm2(modes(:, j))
      modes(:, j) = modes(:, j) / norms(j)
    end do
    ! pinned dofs: QR with column pivoting of modes' over the free dofs
    free = pack([(i, i = 1, nd)], .not. fixed(bd%dof0 + 1:bd%dof0 + nd))
    a = transpose(modes(free, :))
    allocate(jpvt(size(free)), tau(kb))
    jpvt = 0
    call dgeqp3(kb, size(free), a, kb, jpvt, tau, wq, -1, info)
    lwork = int(wq(1))
    allocate(work(lwork))
    call dgeqp3(kb, size(free), a, kb, jpvt, tau, work, lwork, info)
    pins = free(jpvt(1:kb))
  end subroutine body_modes

  !> G = r3' K_s r3 (3 x 3): the springs' stiffness against the three rigid
  !> motions of body_modes (in x, y components, as the springs' matrices).
  !>   springs (in) the body's springs;  x (in) (2, nnode) its nodes
  !>   xc, size_b (in) the rotation's centre and scale (body_modes')
  pure function spring_modes(springs, x, xc, size_b) result(g)
    type(spring_set_t), intent(in) :: springs
    real(dp), intent(in) :: x(:,:), xc(2), size_b
    real(dp) :: g(3, 3)
    real(dp) :: re(6, 3)
    integer :: i, a, n, node
    g = 0.0_dp
    do i = 1, springs%n
      n = springs%nen(i)
      do a = 1, n
        node = springs%nodes(a, i)
        re(2 * a - 1, :) = [1.0_dp, 0.0_dp, -(x(2, node) - xc(2)) / size_b]
        re(2 * a, :) = [0.0_dp, 1.0_dp, (x(1, node) - xc(1)) / size_b]
      end do
      g = g + matmul(transpose(re(1:2 * n, :)), matmul(springs%k(1:2 * n, 1:2 * n, i), re(1:2 * n, :)))
    end do
  end function spring_modes

  !> A readable name of mode j from its coefficients.
  function mode_name(fl, j) result(name)
    type(floating_t), intent(in) :: fl
    integer, intent(in) :: j
    character(len=:), allocatable :: name
    real(dp) :: c(3)
    c = abs(fl%coef(:, j)) / maxval(abs(fl%coef(:, j)))
    name = ''
    if (c(1) > 1.0e-8_dp) name = name // '+translation x'
    if (c(2) > 1.0e-8_dp) name = name // '+translation y'
    if (c(3) > 1.0e-8_dp) name = name // '+rotation'
    name = name(2:)
  end function mode_name

  !> The rigid motion R c, c (k) a combination of the modes of one body:
  !> u(x) = (a_x - omega (y - y0), a_y + omega (x - x0)).  kind = 'rotation'
  !> with point the centre about which it turns, or kind = 'translation' with
  !> point its unit direction (when |omega| size <= 1e-8 |a|: no turning).
  !>   fl    (in)  the modes
  !>   c     (in)  (k) amplitudes; only the modes of one body nonzero
  !>   kind  (out) 'rotation' or 'translation'
  !>   point (out) (2) the centre, or the direction
  subroutine describe_motion(fl, c, kind, point)
    type(floating_t), intent(in) :: fl
    real(dp), intent(in) :: c(:)
    character(len=:), allocatable, intent(out) :: kind
    real(dp), intent(out) :: point(2)
    real(dp) :: a(3), omega, xc(2), length
    integer :: j
    a = 0.0_dp
    xc = 0.0_dp
    length = 1.0_dp
    do j = 1, fl%k
      if (c(j) == 0.0_dp) cycle
      a = a + c(j) * fl%coef(:, j) / fl%norm(j)    ! mode j = r3 coef_j / norm_j
      xc = fl%centre(:, j)
      length = fl%length(j)
    end do
    omega = a(3) / length                          ! r3's rotation is scaled by 1 / size
    if (abs(a(3)) > 1.0e-8_dp * max(norm2(a(1:2)), tiny(1.0_dp))) then
      kind = 'rotation'
      point = [xc(1) - a(2) / omega, xc(2) + a(1) / omega]   ! where u(x) = 0
    else
      kind = 'translation'
      point = a(1:2) / norm2(a(1:2))
    end if
  end subroutine describe_motion

  !> The rigid motion R c in words: 'rotation about (x, y)' or 'translation
  !> along (dx, dy)' (coordinates below 1e-9 of the body's size written as 0).
  function motion_name(fl, c) result(name)
    type(floating_t), intent(in) :: fl
    real(dp), intent(in) :: c(:)
    character(len=:), allocatable :: name
    character(len=:), allocatable :: kind
    real(dp) :: point(2), length
    character(len=32) :: bx, by
    call describe_motion(fl, c, kind, point)
    length = fl%length(maxloc(abs(c), dim=1))
    if (kind == 'translation') length = 1.0_dp
    where (abs(point) <= 1.0e-9_dp * length) point = 0.0_dp
    write(bx, '(es11.4)') point(1)
    write(by, '(es11.4)') point(2)
    if (kind == 'rotation') then
      name = 'rotation about (' // trim(adjustl(bx)) // ', ' // trim(adjustl(by)) // ')'
    else
      name = 'translation along (' // trim(adjustl(bx)) // ', ' // trim(adjustl(by)) // ')'
    end if
  end function motion_name

  !> u <- u - D (D'D)^-1 D'u, D = R c (ndof, m): u loses its components along
  !> the rigid motions D (made orthogonal to each of them).
  !>   fl (in)    the modes
  !>   c  (in)    (k, m) combinations of the modes
  !>   u  (inout) (ndof) displacement
  subroutine remove_motions(fl, c, u)
    type(floating_t), intent(in) :: fl
    real(dp), intent(in) :: c(:,:)
    real(dp), intent(inout) :: u(:)
    real(dp), allocatable :: d(:,:), g(:,:), y(:,:)
    integer, allocatable :: ipiv(:)
    real(dp), allocatable :: work(:)
    real(dp) :: wq(1)
    integer :: m, info
    m = size(c, 2)
    if (m == 0) return
    d = matmul(fl%r, c)
    g = matmul(transpose(d), d)                    ! D'D (m, m), symmetric positive definite
    y = reshape(matmul(transpose(d), u), [m, 1])   ! D'u
    allocate(ipiv(m))
    call dsysv('U', m, 1, g, m, ipiv, y, m, wq, -1, info)
    allocate(work(max(1, int(wq(1)))))
    call dsysv('U', m, 1, g, m, ipiv, y, m, work, size(work), info)
    if (info == 0) u = u - matmul(d, y(:, 1))
  end subroutine remove_motions

end module rigid_modes
