!> stress_equilibration: an equilibrated stress reconstruction of one body
!> and the guaranteed bound of its energy-norm error it gives (Prager and
!> Synge, Quart. Appl. Math. 5, 1947; the patch construction of Braess and
!> Schoeberl, Math. Comp. 77, 2008, and Ern and Vohralik, SIAM J. Numer.
!> Anal. 53, 2015; weak symmetry as in Bertrand, Moldenhauer and Starke,
!> 2019, and Riedlbeck, Di Pietro, Ern et al., 2017).
!>
!> The body is held by its supports and loaded by the line forces g of its
!> loaded edges (the contact tractions: module energy_bound), no volume
!> force.  u_h is its Galerkin solution for these data.  A stress T in
!> H(div), row by row, with
!>     div T = 0 (plane),   div T_z = 0 and hoop s_tt = div T_r / 2 pi (axisymmetric),
!>     T n = g on the loaded edges, 0 on the other free edges,
!> T = w sigma_r, w the thickness (plane) or 2 pi r (axisymmetric), gives
!>     ||u - u_h||_E <= eta_sym + C_K eta_skew,
!>     eta_sym^2  = int (sym sigma_r - sigma_h) : D^-1 (sym sigma_r - sigma_h) w dA,
!>     eta_skew^2 = (2 / kappa) int s^2 w dA,  s = (sigma_r,xy - sigma_r,yx) / 2,
!> kappa the least eigenvalue of D in the orthonormal strain basis (eps : D
!> eps >= kappa |eps|^2) and C_K the Korn constant ||rot v|| <= C_K ||eps(v)||
!> of the displacements the supports allow (doc/theory.md, "Error estimate").
!>
!> T = sum_a T^a over the corner nodes a, T^a supported on the elements
!> around a (its patch), each element split into triangles (a quadrangle
!> along its diagonal 1-3), T^a row-wise Raviart-Thomas RT_m (m the
!> element order) on each triangle, the minimizer of
!>     || sym(T^a / w) - psi_a sigma_h ||^2_{D^-1} + gamma ||skew(T^a / w)||^2
!> under the constraints
!>     div T^a_i = w (sigma_h grad psi_a)_i projected on P_m (rows with a divergence constraint),
!>     T^a n = psi_a g on the loaded edges, 0 on the patch's boundary and free edges, free on
!>     the edges held in that row's component,
!>     T^a = 0 on the axis (axisymmetric: w = 0 there, the energy of T / w stays finite),
!> psi_a the corner hat function of the elements (P1 or Q1): a small dense
!> saddle-point system (LAPACK dsysv), its unknowns the RT_m coefficients in
!> monomials, the normal continuity imposed by edge moments.  The constant
!> moment of each source is the program's own quadrature of the nodal
!> force, so the patch problems are compatible exactly (Galerkin
!> orthogonality: sum over the patch of the sources = the force of the
!> hat = int psi_a g).
!>
!> Why it exists, as one file: the patch problem (its unknowns, its
!> constraints, its source) is one construction; its parts have no use apart.
!> The Raviart-Thomas basis is raviart_thomas's, the contact data energy_bound's.
!>
!> Programming interface
!>   type(edge_traction_t)     the loaded edges of a body and their line forces
!>   equilibrate_body(bd, u, fixed, loads, eta_sym2, eta_skew2, energy2, info)
!>                             eta_sym^2, eta_skew^2 and ||u_h||_E^2 of the body; info 0 done,
!>                             1 a body this does not cover, 2 a patch problem failed
module stress_equilibration
  use kinds, only: dp
  use body, only: body_t, node_elements, body_pressure_modes
  use elements, only: shape_at, stiffness_rule, corner_count, max_nen
  use error_estimate, only: point_stress, compliance
  use axisymmetric_elements, only: radial_weight
  use lapack_interfaces, only: dsysv
  use raviart_thomas, only: rt_basis, monomials, triangle_rule, gauss_points
  implicit none
  private
  public :: edge_traction_t, equilibrate_body

  !> The loaded edges of a body: line force g (force per unit length of the
  !> section's boundary, w sigma n: full circle in axisymmetry), x, y,
  !> linear (two nodes) or quadratic (three) along each edge.
  type :: edge_traction_t
    integer, allocatable :: node(:,:)      !< (3, nseg) end nodes a, b and the middle node (0: none)
    real(dp), allocatable :: g(:,:,:)      !< (2, 3, nseg) g at a, b and the middle, x, y
  end type edge_traction_t

  !> One triangle of a patch.
  type :: sub_t
    integer :: v(3) = 0                    !< its corner nodes (counter-clockwise)
    integer :: parent = 0                  !< its element
    integer :: first = 0                   !< its first unknown - 1
    real(dp) :: x(2, 3) = 0, xc(2) = 0, h = 0, area = 0
    logical :: axis = .false.              !< an edge on the axis (axisymmetric)
  end type sub_t

  !> The patch problems' dense arrays, kept from one patch to the next (a
  !> fresh allocation per patch costs more than the solve: page faults).
  type :: patch_work_t
    real(dp), allocatable :: kkt(:,:)      !< the saddle-point matrix [A B'; B -eps I]
    real(dp), allocatable :: bmat(:,:)     !< the constraints' rows B
    real(dp), allocatable :: work(:)       !< dsysv's work
  end type patch_work_t

  !> penalty on the skew part in the patch problems, relative to eta_skew^2
  real(dp), parameter :: skew_weight = 1.0_dp
  real(dp), parameter :: pi = 3.14159265358979323846_dp

contains

  !> The error bound's parts of one body (module header).
  !>   bd    (in)  the body (plane or axisymmetric; triangles P1, P2 with straight edges, Q1)
  !>   u     (in)  (2, nnode) its displacement, x, y
  !>   fixed (in)  (2, nnode) the components its supports hold
  !>   loads (in)  its loaded edges
  !>   eta_sym2, eta_skew2 (out) eta_sym^2 and eta_skew^2 (module header)
  !>   energy2 (out) ||u_h||_E^2
  !>   info  (out) 0 done; 1 not covered (8- or 9-node elements, curved P2 edges, B-bar,
  !>               a support on a single node); 2 a patch problem was singular
  subroutine equilibrate_body(bd, u, fixed, loads, eta_sym2, eta_skew2, energy2, info)
    type(body_t), intent(in) :: bd
    real(dp), intent(in) :: u(:,:)
    logical, intent(in) :: fixed(:,:)
    type(edge_traction_t), intent(in) :: loads
    real(dp), intent(out) :: eta_sym2, eta_skew2, energy2
    integer, intent(out) :: info
    integer, allocatable :: eptr(:), elist(:), sub_first(:), lptr(:), llist(:)
    real(dp), allocatable :: coef(:,:)
    type(sub_t), allocatable :: subs(:)
    type(patch_work_t) :: ws
    real(dp) :: ci(4, 4), kappa
    integer :: e, a, m, nrt, nsub, nc
    eta_sym2 = 0
    eta_skew2 = 0
    energy2 = 0
    info = 1
    nc = merge(4, 3, bd%axisymmetric)
    if (any(bd%mesh%nen == 8 .or. bd%mesh%nen == 9)) return
    if (any([(body_pressure_modes(bd, bd%mesh%nen(e)) > 0, e = 1, bd%mesh%nelem)])) return
    do e = 1, bd%mesh%nelem
      if (bd%mesh%nen(e) == 6) then
        if (.not. straight(bd%mesh%x(:, bd%mesh%conn(1:6, e)))) return
      end if
    end do
    m = merge(2, 1, any(bd%mesh%nen == 6 .or. bd%mesh%nen == 4))
    nrt = (m + 1) * (m + 3)
    call make_subs(bd, subs, sub_first, nsub)
    call node_elements(bd%mesh, eptr, elist)
    call load_lists(bd%mesh%nnode, loads, lptr, llist)
    ci(1:nc, 1:nc) = compliance(bd, nc)
    kappa = least_stiffness(bd, nc)
    if (.not. kappa > 0.0_dp) return
    allocate(coef(2 * nrt, nsub), source=0.0_dp)
    info = 0
    do a = 1, bd%mesh%nnode
      if (.not. is_corner(bd, eptr, elist, a)) cycle
      call patch_problem(bd, u, fixed, loads, lptr, llist, eptr, elist, subs, sub_first, a, m, ci, &
                         skew_weight * 2 / kappa, coef, ws, info)
      if (info /= 0) return
    end do
    call bound_parts(bd, u, subs, m, ci, coef, eta_sym2, eta_skew2, energy2)
    eta_skew2 = eta_skew2 * 2 / kappa
  end subroutine equilibrate_body

  !> The triangles of the body's elements: a triangle is its own, a
  !> quadrangle 1-2-3-4 gives 1-2-3 and 1-3-4.
  subroutine make_subs(bd, subs, sub_first, nsub)
    type(body_t), intent(in) :: bd
    type(sub_t), allocatable, intent(out) :: subs(:)
    integer, allocatable, intent(out) :: sub_first(:)
    integer, intent(out) :: nsub
    integer :: e, k, s, nk
    integer, parameter :: split(3, 2) = reshape([1, 2, 3, 1, 3, 4], [3, 2])
    allocate(sub_first(bd%mesh%nelem + 1))
    nsub = 0
    do e = 1, bd%mesh%nelem
      sub_first(e) = nsub
      nsub = nsub + merge(2, 1, corner_count(bd%mesh%nen(e)) == 4)
    end do
    sub_first(bd%mesh%nelem + 1) = nsub
    allocate(subs(nsub))
    do e = 1, bd%mesh%nelem
      nk = sub_first(e + 1) - sub_first(e)
      do k = 1, nk
        s = sub_first(e) + k
        subs(s)%v = bd%mesh%conn(split(:, k), e)
        if (nk == 1) subs(s)%v = bd%mesh%conn(1:3, e)
        subs(s)%parent = e
        subs(s)%x = bd%mesh%x(:, subs(s)%v)
        subs(s)%xc = sum(subs(s)%x, 2) / 3
        subs(s)%h = max(norm2(subs(s)%x(:, 2) - subs(s)%x(:, 1)), norm2(subs(s)%x(:, 3) - subs(s)%x(:, 2)), &
                        norm2(subs(s)%x(:, 1) - subs(s)%x(:, 3)))
        subs(s)%area = 0.5_dp * ((subs(s)%x(1, 2) - subs(s)%x(1, 1)) * (subs(s)%x(2, 3) - subs(s)%x(2, 1)) - &
                                 (subs(s)%x(2, 2) - subs(s)%x(2, 1)) * (subs(s)%x(1, 3) - subs(s)%x(1, 1)))
      end do
    end do
  end subroutine make_subs

  !> The patch problem of corner node a (module header); its solution added
  !> to coef.  info = 1 when a row is closed (no held edge) while a's
  !> component is held (a support on a single node), 2 when singular.
  subroutine patch_problem(bd, u, fixed, loads, lptr, llist, eptr, elist, subs, sub_first, a, m, ci, gam, coef, ws, info)
    type(body_t), intent(in) :: bd
    real(dp), intent(in) :: u(:,:), ci(4, 4), gam
    logical, intent(in) :: fixed(:,:)
    type(edge_traction_t), intent(in) :: loads
    integer, intent(in) :: lptr(:), llist(:), eptr(:), elist(:), sub_first(:), a, m
    type(sub_t), intent(in) :: subs(:)
    real(dp), intent(inout) :: coef(:,:)
    type(patch_work_t), intent(inout) :: ws
    integer, intent(inout) :: info
    type(sub_t), allocatable :: ps(:)
    real(dp), allocatable :: rhs(:), g(:), sol(:,:), stiff(:,:), acc1(:,:)
    integer, allocatable :: ipiv(:)
    logical :: open_row(2)
    integer :: np, k, ie, e, nrt, n, nc, mc, nmono, i, j, le, k2, p, q, r, kk, lwork, naxis, ld
    real(dp) :: xq(2, 64), wq(64), xiq(2, 64), sigq(4, 64), wgt(64), xe(2, max_nen), ue(2, max_nen), sig(4), dv, &
                nsh(max_nen), w, &
                psi, gpsi(2), phi(2, 24), divphi(24), emat(4, 48), smat(48), t(4), mono(15), d(2), eps, scale, ce(4, 48), &
                bdiv(24, 15), dmom(2, 15)
    integer :: nq, nen, ii, jj
    nrt = (m + 1) * (m + 3)
    nmono = (m + 1) * (m + 2) / 2
    nc = merge(4, 3, bd%axisymmetric)
    np = 0
    do ie = eptr(a), eptr(a + 1) - 1
      np = np + sub_first(elist(ie) + 1) - sub_first(elist(ie))
    end do
    allocate(ps(np))
    k = 0
    do ie = eptr(a), eptr(a + 1) - 1
      e = elist(ie)
      do j = sub_first(e) + 1, sub_first(e + 1)
        k = k + 1
        ps(k) = subs(j)
        ps(k)%first = (k - 1) * 2 * nrt
        ps(k)%axis = bd%axisymmetric .and. count(abs(ps(k)%x(1, :)) <= 1.0e-9_dp * ps(k)%h) >= 2
      end do
    end do
    n = 2 * nrt * np
    naxis = count(ps%axis)
    mc = np * (6 * (m + 1) + 2 * nmono) + naxis * 2 * (2 * m + 3)
    if (.not. allocated(ws%kkt)) allocate(ws%kkt(0, 0), ws%bmat(0, 0))
    if (size(ws%kkt, 1) < n + mc) then
      deallocate(ws%kkt, ws%bmat)
      if (allocated(ws%work)) deallocate(ws%work)
      allocate(ws%kkt(2 * (n + mc), 2 * (n + mc)), ws%bmat(2 * (n + mc), 2 * (n + mc)), ws%work(64 * 2 * (n + mc)))
    end if
    ld = size(ws%kkt, 1)
    associate (amat => ws%kkt, bmat => ws%bmat)
    amat(1:n, 1:n) = 0
    allocate(rhs(n), source=0.0_dp)
    allocate(acc1(2, np), source=0.0_dp)
    ! the energy's quadratic form, and each triangle's accurate source moments
    do k = 1, np
      call triangle_stresses(bd, u, ps(k), m, nq, xq, wq, xiq, sigq, wgt)
      e = ps(k)%parent
      do q = 1, nq
        sig(1:nc) = sigq(1:nc, q)
        call hat(bd, e, a, xiq(:, q), psi, gpsi)
        w = wgt(q)
        call rt_basis(m, ps(k)%xc, ps(k)%h, xq(:, q), phi, divphi)
        call stress_map(bd%axisymmetric, nrt, w, phi, divphi, emat, smat)
        t(1:nc) = psi * sig(1:nc)
        ! the hoop stress of T^a is div T^a_r / 2 pi, and div(psi T_r) = psi div T_r
        ! + grad psi . T_r: its target takes the second term, which the patches' sum cancels
        if (bd%axisymmetric) t(4) = t(4) + w / (2 * pi) * dot_product(gpsi, sig([1, 3]))
        associate (o => ps(k)%first, l => 2 * nrt)
          ce(1:nc, 1:l) = matmul(ci(1:nc, 1:nc), emat(1:nc, 1:l))
          do jj = 1, l
            do ii = 1, l
              amat(o + ii, o + jj) = amat(o + ii, o + jj) + wq(q) * w * &
                (dot_product(emat(1:nc, ii), ce(1:nc, jj)) + gam * smat(ii) * smat(jj))
            end do
          end do
          rhs(o + 1:o + l) = rhs(o + 1:o + l) + wq(q) * w * matmul(transpose(emat(1:nc, 1:l)), matmul(ci(1:nc, 1:nc), t(1:nc)))
        end associate
        acc1(:, k) = acc1(:, k) + wq(q) * w * row_force(sig, gpsi)
      end do
    end do
    ! the program's own nodal force of the hat, element by element (stiffness rule)
    allocate(stiff(2, np), source=0.0_dp)
    do k = 1, np
      if (k > 1) then
        if (ps(k)%parent == ps(k - 1)%parent) cycle
      end if
      e = ps(k)%parent
      nen = bd%mesh%nen(e)
      xe(:, 1:nen) = bd%mesh%x(:, bd%mesh%conn(1:nen, e))
      ue(:, 1:nen) = u(:, bd%mesh%conn(1:nen, e))
      block
        real(dp) :: sxi(2, 9), sw(9)
        integer :: sq, nsq
        call stiffness_rule(nen, nsq, sxi, sw)
        do sq = 1, nsq
          call point_stress(bd, e, xe(:, 1:nen), ue(:, 1:nen), sxi(:, sq), sig(1:nc), dv, nsh(1:nen), 0.0_dp)
          call hat(bd, e, a, sxi(:, sq), psi, gpsi)
          stiff(:, k) = stiff(:, k) + sw(sq) * dv * row_force(sig, gpsi)
        end do
      end block
    end do
    ! constraints
    bmat(1:mc, 1:n) = 0
    allocate(g(mc), source=0.0_dp)
    r = 0
    open_row = .false.
    do k = 1, np
      do le = 1, 3
        p = ps(k)%v(le)
        q = ps(k)%v(mod(le, 3) + 1)
        k2 = 0
        do kk = 1, np
          if (kk /= k .and. any(ps(kk)%v == p) .and. any(ps(kk)%v == q)) k2 = kk
        end do
        if (k2 > 0 .and. k2 < k) cycle                   ! that edge's constraints are made
        if (k2 > 0) then                                 ! inside the patch: the outward fluxes add up to 0
          do i = 1, 2
            do j = 0, m
              r = r + 1
              call flux_row(ps(k), le, m, i, j, bmat(r, 1:n), 1.0_dp)
              call flux_row(ps(k2), edge_of(ps(k2), p, q), m, i, j, bmat(r, 1:n), 1.0_dp)
            end do
          end do
        else if (edge_subs(eptr, elist, sub_first, subs, p, q) == 2) then   ! the patch's boundary: 0
          do i = 1, 2
            do j = 0, m
              r = r + 1
              call flux_row(ps(k), le, m, i, j, bmat(r, 1:n), 1.0_dp)
            end do
          end do
        else if (ps(k)%axis .and. abs(bd%mesh%x(1, p)) <= 1.0e-9_dp * ps(k)%h .and. &
                 abs(bd%mesh%x(1, q)) <= 1.0e-9_dp * ps(k)%h) then        ! the axis: T = 0
          do i = 1, 2
            do j = 0, m
              r = r + 1
              call flux_row(ps(k), le, m, i, j, bmat(r, 1:n), 1.0_dp)
            end do
            do j = 0, m + 1
              r = r + 1
              call tangent_row(ps(k), le, m, i, real(j, dp) / (m + 1), bmat(r, 1:n))
            end do
          end do
        else                                             ! the body's boundary: held, loaded or free
          do i = 1, 2
            if (edge_held(bd, fixed, ps(k), p, q, i)) then
              open_row(i) = .true.
              cycle
            end if
            do j = 0, m
              r = r + 1
              call flux_row(ps(k), le, m, i, j, bmat(r, 1:n), 1.0_dp)
              g(r) = load_moment(loads, lptr, llist, bd%mesh%x, p, q, a, i, j, m)
            end do
          end do
        end if
      end do
    end do
    ! divergence: plane both rows, axisymmetric the z row (the r row's is the hoop stress)
    do i = merge(2, 1, bd%axisymmetric), 2
      if (.not. open_row(i) .and. fixed(i, a)) then   ! a support on a single node: no finite energy
        info = 1
        return
      end if
    end do
    do k = 1, np
      call triangle_stresses(bd, u, ps(k), m, nq, xq, wq, xiq, sigq, wgt)
      e = ps(k)%parent
      bdiv = 0
      dmom = 0
      do q = 1, nq
        call rt_basis(m, ps(k)%xc, ps(k)%h, xq(:, q), phi, divphi)
        call monomials(m, ps(k)%xc, ps(k)%h, xq(:, q), mono)
        call hat(bd, e, a, xiq(:, q), psi, gpsi)
        d = wgt(q) * row_force(sigq(:, q), gpsi)
        do j = 1, nmono
          bdiv(1:nrt, j) = bdiv(1:nrt, j) + wq(q) * divphi(1:nrt) * mono(j)
          dmom(:, j) = dmom(:, j) + wq(q) * d * mono(j)
        end do
      end do
      ! the constant moment: the program's force of the hat on the element,
      ! shared between its triangles by area, so that the patch's sources
      ! add up to int psi_a g exactly (compatibility)
      kk = first_of(ps, k)
      dmom(:, 1) = dmom(:, 1) + (stiff(:, kk) - parent_sum(ps, acc1, k)) * ps(k)%area / parent_area(ps, e)
      do i = merge(2, 1, bd%axisymmetric), 2
        do j = 1, nmono
          if (j == 1 .and. k == 1 .and. .not. open_row(i)) cycle   ! implied by the others (compatibility)
          if (j == nmono .and. ps(k)%axis) cycle                   ! outside div of the fields that vanish on the axis
          r = r + 1
          associate (o => ps(k)%first + (i - 1) * nrt)
            bmat(r, o + 1:o + nrt) = bdiv(1:nrt, j)
          end associate
          g(r) = dmom(i, j)
        end do
      end do
    end do
    mc = r
    ! rows scaled to unit length; the multipliers' block -eps I keeps the
    ! system regular where constraints repeat one another (consistently)
    do r = 1, mc
      scale = norm2(bmat(r, 1:n))
      if (scale > 0.0_dp) then
        bmat(r, 1:n) = bmat(r, 1:n) / scale
        g(r) = g(r) / scale
      end if
    end do
    eps = 1.0e-13_dp * maxval([(abs(amat(j, j)), j = 1, n)])
    amat(n + 1:n + mc, 1:n) = bmat(1:mc, 1:n)           ! the lower triangle is all dsysv reads
    amat(n + 1:n + mc, n + 1:n + mc) = 0
    do j = n + 1, n + mc
      amat(j, j) = -eps
    end do
    allocate(sol(n + mc, 1), ipiv(n + mc))
    sol(1:n, 1) = rhs
    sol(n + 1:, 1) = g(1:mc)
    lwork = size(ws%work)
    call dsysv('L', n + mc, 1, amat, ld, ipiv, sol, n + mc, ws%work, lwork, info)
    if (info /= 0) then
      info = 2
      return
    end if
    ! the constraints hold to round-off, or the patch failed
    if (mc > 0 .and. maxval(abs(matmul(bmat(1:mc, 1:n), sol(1:n, 1)) - g(1:mc))) > &
        1.0e-7_dp * max(maxval(abs(g(1:mc))), tiny(1.0_dp))) then
      info = 2
      return
    end if
    do k = 1, np
      j = sub_first(ps(k)%parent) + count([(ps(kk)%parent == ps(k)%parent, kk = 1, k)])
      coef(:, j) = coef(:, j) + sol(ps(k)%first + 1:ps(k)%first + 2 * nrt, 1)
    end do
    end associate
  end subroutine patch_problem

  !> The collapsed Gauss points xq, wq of triangle sb (triangle_rule, n =
  !> m + 3) and at each the reference point xiq of its element, sigma_h
  !> (sigq, the law's components) and w.
  subroutine triangle_stresses(bd, u, sb, m, nq, xq, wq, xiq, sigq, wgt)
    type(body_t), intent(in) :: bd
    real(dp), intent(in) :: u(:,:)
    type(sub_t), intent(in) :: sb
    integer, intent(in) :: m
    integer, intent(out) :: nq
    real(dp), intent(out) :: xq(:,:), wq(:), xiq(:,:), sigq(:,:), wgt(:)
    real(dp) :: xe(2, max_nen), ue(2, max_nen), dv, nsh(max_nen)
    integer :: q, e, nen, nc
    nc = merge(4, 3, bd%axisymmetric)
    call triangle_rule(sb%x, m + 3, nq, xq, wq)
    e = sb%parent
    nen = bd%mesh%nen(e)
    xe(:, 1:nen) = bd%mesh%x(:, bd%mesh%conn(1:nen, e))
    ue(:, 1:nen) = u(:, bd%mesh%conn(1:nen, e))
    do q = 1, nq
      xiq(:, q) = parent_point(nen, xe, xq(:, q))
      call point_stress(bd, e, xe(:, 1:nen), ue(:, 1:nen), xiq(:, q), sigq(1:nc, q), dv, nsh(1:nen), 0.0_dp)
      wgt(q) = weight_at(bd, xq(:, q))
    end do
  end subroutine triangle_stresses

  !> The first triangle in the patch of triangle k's element.
  pure integer function first_of(ps, k) result(kk)
    type(sub_t), intent(in) :: ps(:)
    integer, intent(in) :: k
    kk = k
    do while (kk > 1)
      if (ps(kk - 1)%parent /= ps(k)%parent) exit
      kk = kk - 1
    end do
  end function first_of

  !> The sum of acc(:, k) over the triangles of triangle k's element.
  pure function parent_sum(ps, acc, k) result(s)
    type(sub_t), intent(in) :: ps(:)
    real(dp), intent(in) :: acc(:,:)
    integer, intent(in) :: k
    real(dp) :: s(2)
    integer :: kk
    s = 0
    do kk = 1, size(ps)
      if (ps(kk)%parent == ps(k)%parent) s = s + acc(:, kk)
    end do
  end function parent_sum

  !> The area of element e's triangles in the patch.
  pure real(dp) function parent_area(ps, e) result(s)
    type(sub_t), intent(in) :: ps(:)
    integer, intent(in) :: e
    integer :: k
    s = 0
    do k = 1, size(ps)
      if (ps(k)%parent == e) s = s + ps(k)%area
    end do
  end function parent_area

  !> eta_sym^2, the skew part's int s^2 w dA, and ||u_h||_E^2 of the
  !> reconstruction coef (module header).
  subroutine bound_parts(bd, u, subs, m, ci, coef, sym2, skew2, energy2)
    type(body_t), intent(in) :: bd
    real(dp), intent(in) :: u(:,:), ci(4, 4), coef(:,:)
    type(sub_t), intent(in) :: subs(:)
    integer, intent(in) :: m
    real(dp), intent(out) :: sym2, skew2, energy2
    real(dp) :: xq(2, 64), wq(64), xiq(2, 64), sigq(4, 64), wgt(64), sig(4), w, &
                phi(2, 24), divphi(24), emat(4, 48), smat(48), sr(4), s
    integer :: k, q, nq, nc, nrt
    nc = merge(4, 3, bd%axisymmetric)
    nrt = (m + 1) * (m + 3)
    sym2 = 0
    skew2 = 0
    energy2 = 0
    do k = 1, size(subs)
      call triangle_stresses(bd, u, subs(k), m, nq, xq, wq, xiq, sigq, wgt)
      do q = 1, nq
        sig(1:nc) = sigq(1:nc, q)
        w = wgt(q)
        call rt_basis(m, subs(k)%xc, subs(k)%h, xq(:, q), phi, divphi)
        call stress_map(bd%axisymmetric, nrt, w, phi, divphi, emat, smat)
        sr(1:nc) = matmul(emat(1:nc, 1:2 * nrt), coef(:, k)) - sig(1:nc)
        s = dot_product(smat(1:2 * nrt), coef(:, k))
        sym2 = sym2 + wq(q) * w * dot_product(sr(1:nc), matmul(ci(1:nc, 1:nc), sr(1:nc)))
        skew2 = skew2 + wq(q) * w * s**2
        energy2 = energy2 + wq(q) * w * dot_product(sig(1:nc), matmul(ci(1:nc, 1:nc), sig(1:nc)))
      end do
    end do
  end subroutine bound_parts

  !> The stress of T = w sigma at a point, in the law's components, and its
  !> skew part s, as linear maps of the triangle's coefficients (row x:
  !> 1..nrt, row y: nrt+1..2 nrt): sigma = emat c, s = smat' c.
  pure subroutine stress_map(axisymmetric, nrt, w, phi, divphi, emat, smat)
    logical, intent(in) :: axisymmetric
    integer, intent(in) :: nrt
    real(dp), intent(in) :: w, phi(:,:), divphi(:)
    real(dp), intent(out) :: emat(:,:), smat(:)
    emat = 0
    emat(1, 1:nrt) = phi(1, 1:nrt) / w                        ! s_xx = T_xx / w
    emat(2, nrt + 1:2 * nrt) = phi(2, 1:nrt) / w              ! s_yy = T_yy / w
    emat(3, 1:nrt) = phi(2, 1:nrt) / (2 * w)                  ! s_xy = (T_xy + T_yx) / 2 w
    emat(3, nrt + 1:2 * nrt) = phi(1, 1:nrt) / (2 * w)
    if (axisymmetric) emat(4, 1:nrt) = divphi(1:nrt) / (2 * pi)   ! s_tt = div T_r / 2 pi
    smat(1:nrt) = phi(2, 1:nrt) / (2 * w)                     ! s = (T_xy - T_yx) / 2 w
    smat(nrt + 1:2 * nrt) = -phi(1, 1:nrt) / (2 * w)
  end subroutine stress_map

  !> (sigma grad psi) row by row: the force density of the hat psi.
  pure function row_force(sig, gpsi) result(f)
    real(dp), intent(in) :: sig(:), gpsi(2)
    real(dp) :: f(2)
    f(1) = sig(1) * gpsi(1) + sig(3) * gpsi(2)
    f(2) = sig(3) * gpsi(1) + sig(2) * gpsi(2)
  end function row_force

  !> Add c times the row of int_e (T_i . n) s^j ds, n the triangle's
  !> outward normal on its edge le (from v(le) to the next), s in 0..1 from
  !> the edge's node of lower number (both triangles of an edge agree).
  pure subroutine flux_row(sb, le, m, i, j, row, c)
    type(sub_t), intent(in) :: sb
    integer, intent(in) :: le, m, i, j
    real(dp), intent(inout) :: row(:)
    real(dp), intent(in) :: c
    real(dp) :: gx(8), gw(8), x0(2), x1(2), tv(2), nv(2), len, phi(2, 24), divphi(24), x(2)
    integer :: q, nrt, o
    nrt = (m + 1) * (m + 3)
    call edge_ends(sb, le, x0, x1)
    tv = sb%x(:, mod(le, 3) + 1) - sb%x(:, le)
    len = norm2(tv)
    nv = [tv(2), -tv(1)] / len
    call gauss_points(m + 3, gx, gw)
    o = sb%first + (i - 1) * nrt
    do q = 1, m + 3
      x = x0 + gx(q) * (x1 - x0)
      call rt_basis(m, sb%xc, sb%h, x, phi, divphi)
      row(o + 1:o + nrt) = row(o + 1:o + nrt) + c * gw(q) * len * gx(q)**j * matmul(nv, phi(:, 1:nrt))
    end do
  end subroutine flux_row

  !> The row of T_i . t at the point s (0..1) of edge le.
  pure subroutine tangent_row(sb, le, m, i, s, row)
    type(sub_t), intent(in) :: sb
    integer, intent(in) :: le, m, i
    real(dp), intent(in) :: s
    real(dp), intent(inout) :: row(:)
    real(dp) :: x0(2), x1(2), tv(2), phi(2, 24), divphi(24)
    integer :: nrt, o
    nrt = (m + 1) * (m + 3)
    call edge_ends(sb, le, x0, x1)
    tv = (x1 - x0) / norm2(x1 - x0)
    call rt_basis(m, sb%xc, sb%h, x0 + s * (x1 - x0), phi, divphi)
    o = sb%first + (i - 1) * nrt
    row(o + 1:o + nrt) = matmul(tv, phi(:, 1:nrt))
  end subroutine tangent_row

  !> The ends of edge le of a triangle, the node of lower number first.
  pure subroutine edge_ends(sb, le, x0, x1)
    type(sub_t), intent(in) :: sb
    integer, intent(in) :: le
    real(dp), intent(out) :: x0(2), x1(2)
    integer :: l2
    l2 = mod(le, 3) + 1
    if (sb%v(le) < sb%v(l2)) then
      x0 = sb%x(:, le)
      x1 = sb%x(:, l2)
    else
      x0 = sb%x(:, l2)
      x1 = sb%x(:, le)
    end if
  end subroutine edge_ends

  !> The local edge of a triangle from node p to node q (either way).
  pure integer function edge_of(sb, p, q) result(le)
    type(sub_t), intent(in) :: sb
    integer, intent(in) :: p, q
    integer :: l
    le = 0
    do l = 1, 3
      if ((sb%v(l) == p .and. sb%v(mod(l, 3) + 1) == q) .or. (sb%v(l) == q .and. sb%v(mod(l, 3) + 1) == p)) le = l
    end do
  end function edge_of

  !> How many triangles of the body have the edge p-q.
  integer function edge_subs(eptr, elist, sub_first, subs, p, q) result(c)
    integer, intent(in) :: eptr(:), elist(:), sub_first(:), p, q
    type(sub_t), intent(in) :: subs(:)
    integer :: ie, s
    c = 0
    do ie = eptr(p), eptr(p + 1) - 1
      do s = sub_first(elist(ie)) + 1, sub_first(elist(ie) + 1)
        if (any(subs(s)%v == p) .and. any(subs(s)%v == q)) c = c + 1
      end do
    end do
  end function edge_subs

  !> The boundary edge p-q of triangle sb is held in component i: its
  !> nodes (and the middle node of a 6-node element's edge) all are.
  logical function edge_held(bd, fixed, sb, p, q, i) result(held)
    type(body_t), intent(in) :: bd
    logical, intent(in) :: fixed(:,:)
    type(sub_t), intent(in) :: sb
    integer, intent(in) :: p, q, i
    integer :: l, e
    held = fixed(i, p) .and. fixed(i, q)
    e = sb%parent
    if (.not. held .or. bd%mesh%nen(e) /= 6) return
    do l = 1, 3                      ! the middle node 3 + l lies between corners l and l + 1
      if (any(bd%mesh%conn(l, e) == [p, q]) .and. any(bd%mesh%conn(mod(l, 3) + 1, e) == [p, q])) &
        held = fixed(i, bd%mesh%conn(3 + l, e))
    end do
  end function edge_held

  !> int_e psi_a g_i s^j ds over the edge p-q (s from its node of lower
  !> number), g the sum of the loaded edges lying on it.
  real(dp) function load_moment(loads, lptr, llist, x, p, q, a, i, j, m) result(f)
    type(edge_traction_t), intent(in) :: loads
    integer, intent(in) :: lptr(:), llist(:), p, q, a, i, j, m
    real(dp), intent(in) :: x(:,:)
    real(dp) :: gx(8), gw(8), x0(2), x1(2), xs(2), len, tau, gv, psi, l3(3)
    integer :: k, l, n0, n1, sg
    f = 0
    n0 = min(p, q)
    n1 = max(p, q)
    x0 = x(:, n0)
    x1 = x(:, n1)
    len = norm2(x1 - x0)
    call gauss_points(m + 4, gx, gw)
    do l = lptr(p), lptr(p + 1) - 1
      sg = llist(l)
      if (.not. any(loads%node(1:2, sg) == q)) cycle
      do k = 1, m + 4
        xs = x0 + gx(k) * (x1 - x0)
        psi = 0
        if (a == n0) psi = 1 - gx(k)
        if (a == n1) psi = gx(k)
        tau = dot_product(xs - x(:, loads%node(1, sg)), x(:, loads%node(2, sg)) - x(:, loads%node(1, sg))) / len**2
        if (loads%node(3, sg) > 0) then      ! quadratic: Lagrange at 0, 1, 1/2
          l3 = [(1 - tau) * (1 - 2 * tau), tau * (2 * tau - 1), 4 * tau * (1 - tau)]
          gv = dot_product(l3, loads%g(i, :, sg))
        else
          gv = (1 - tau) * loads%g(i, 1, sg) + tau * loads%g(i, 2, sg)
        end if
        f = f + gw(k) * len * psi * gv * gx(k)**j
      end do
    end do
  end function load_moment

  !> The loaded edges at each node (CSR).
  subroutine load_lists(nnode, loads, ptr, list)
    integer, intent(in) :: nnode
    type(edge_traction_t), intent(in) :: loads
    integer, allocatable, intent(out) :: ptr(:), list(:)
    integer :: s, k, nseg
    integer, allocatable :: next(:)
    nseg = 0
    if (allocated(loads%node)) nseg = size(loads%node, 2)
    allocate(ptr(nnode + 1), source=0)
    do s = 1, nseg
      do k = 1, 2
        ptr(loads%node(k, s) + 1) = ptr(loads%node(k, s) + 1) + 1
      end do
    end do
    ptr(1) = 1
    do k = 1, nnode
      ptr(k + 1) = ptr(k + 1) + ptr(k)
    end do
    allocate(list(ptr(nnode + 1) - 1), next(nnode))
    next = ptr(1:nnode)
    do s = 1, nseg
      do k = 1, 2
        list(next(loads%node(k, s))) = s
        next(loads%node(k, s)) = next(loads%node(k, s)) + 1
      end do
    end do
  end subroutine load_lists

  !> The hat of corner node a on element e at the reference point xi: its
  !> value and gradient (the P1 or Q1 shape function of the corners).
  pure subroutine hat(bd, e, a, xi, psi, gpsi)
    type(body_t), intent(in) :: bd
    integer, intent(in) :: e, a
    real(dp), intent(in) :: xi(2)
    real(dp), intent(out) :: psi, gpsi(2)
    real(dp) :: n(4), dndx(2, 4), detj
    integer :: nc, l
    nc = corner_count(bd%mesh%nen(e))
    call shape_at(nc, bd%mesh%x(:, bd%mesh%conn(1:nc, e)), xi, n(1:nc), dndx(:, 1:nc), detj)
    psi = 0
    gpsi = 0
    do l = 1, nc
      if (bd%mesh%conn(l, e) == a) then
        psi = n(l)
        gpsi = dndx(:, l)
      end if
    end do
  end subroutine hat

  !> The reference point of the element's point x: affine for a triangle,
  !> Newton's method on the bilinear map of a quadrangle.
  pure function parent_point(nen, xe, x) result(xi)
    integer, intent(in) :: nen
    real(dp), intent(in) :: xe(:,:), x(2)
    real(dp) :: xi(2), n(4), dndx(2, 4), detj, r(2), jinv(2, 2)
    real(dp), parameter :: s(4) = [-1, 1, 1, -1], t(4) = [-1, -1, 1, 1]
    integer :: it
    if (corner_count(nen) == 3) then
      call shape_at(3, xe(:, 1:3), [0.0_dp, 0.0_dp], n(1:3), dndx(:, 1:3), detj)
      xi = [dot_product(dndx(:, 2), x - xe(:, 1)), dot_product(dndx(:, 3), x - xe(:, 1))]
      return
    end if
    xi = 0
    do it = 1, 20
      call shape_at(4, xe(:, 1:4), xi, n, dndx, detj)
      r = x - matmul(xe(:, 1:4), n)
      jinv(1, :) = matmul(dndx, s)             ! d xi / dx: the map reproduces xi itself
      jinv(2, :) = matmul(dndx, t)
      xi = xi + matmul(jinv, r)
      if (norm2(r) <= 1.0e-14_dp * norm2(xe(:, 3) - xe(:, 1))) exit
    end do
  end function parent_point

  !> w at x: the thickness, or 2 pi r.
  pure real(dp) function weight_at(bd, x) result(w)
    type(body_t), intent(in) :: bd
    real(dp), intent(in) :: x(2)
    if (bd%axisymmetric) then
      w = radial_weight(x(1))
    else
      w = bd%thick
    end if
  end function weight_at

  !> A corner node of some element around a.
  logical function is_corner(bd, eptr, elist, a) result(yes)
    type(body_t), intent(in) :: bd
    integer, intent(in) :: eptr(:), elist(:), a
    integer :: ie, e
    yes = .false.
    do ie = eptr(a), eptr(a + 1) - 1
      e = elist(ie)
      if (any(bd%mesh%conn(1:corner_count(bd%mesh%nen(e)), e) == a)) yes = .true.
    end do
  end function is_corner

  !> The 6-node triangle's middle nodes lie at their edges' middles.
  pure logical function straight(xe) result(yes)
    real(dp), intent(in) :: xe(2, 6)
    integer :: l
    real(dp) :: h
    h = maxval(abs(xe(:, 1:3) - spread(sum(xe(:, 1:3), 2) / 3, 2, 3)))
    yes = .true.
    do l = 1, 3
      if (norm2(xe(:, 3 + l) - (xe(:, l) + xe(:, mod(l, 3) + 1)) / 2) > 1.0e-8_dp * h) yes = .false.
    end do
  end function straight

  !> kappa: the least eigenvalue of D in the orthonormal strain basis (the
  !> shear's engineering strain times 1 / sqrt 2): 1 / the largest of
  !> T^-1 D^-1 T^-1, by the power method (D^-1 from error_estimate's
  !> compliance; a 3 x 3 or 4 x 4 SPD matrix, whose largest eigenvalue the
  !> iteration reaches from any start with a component along it).
  real(dp) function least_stiffness(bd, nc) result(kappa)
    type(body_t), intent(in) :: bd
    integer, intent(in) :: nc
    real(dp) :: c(4, 4), v(4), tt(4), lambda
    integer :: i, j, it
    tt = [1.0_dp, 1.0_dp, sqrt(2.0_dp), 1.0_dp]
    c = 0
    c(1:nc, 1:nc) = compliance(bd, nc)
    do j = 1, nc
      do i = 1, nc
        c(i, j) = c(i, j) / (tt(i) * tt(j))
      end do
    end do
    v = [1.0_dp, 0.7_dp, 1.3_dp, 0.9_dp]
    v(nc + 1:) = 0
    lambda = 0
    do it = 1, 500
      v = matmul(c, v)
      lambda = norm2(v)
      if (.not. lambda > 0.0_dp) exit
      v = v / lambda
    end do
    kappa = 0
    if (lambda > 0.0_dp) kappa = 1 / lambda
  end function least_stiffness

end module stress_equilibration
