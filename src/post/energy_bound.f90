!> energy_bound: the guaranteed upper bound of the relative energy-norm
!> error (summary `estimate energy_bound`), by the equilibrated stress
!> reconstruction of module stress_equilibration, body by body.
!>
!> The problem it bounds.  Each body is held by its supports and loaded on
!> its contact boundaries by the line force g that the discrete contact
!> forces f_c = -C' z (normal and, with friction, tangential) stand for:
!> along each pair's slave and master traces, g in the traces' own space
!> (linear or quadratic between the nodes) with
!>     int g N_j ds = f_c,j   for every node j of the trace
!> (a mass-matrix solve along the trace).  For these data u_h is exactly the
!> Galerkin solution (K u_h = f_c on the free dofs), so for the solution
!> u_g of the bodies under the traction g (Prager-Synge, module
!> stress_equilibration)
!>     ||u_g - u_h||_E^2 <= sum_b (eta_sym,b + C_K eta_skew,b)^2 = eta^2,
!> and, Galerkin orthogonality giving ||u_g||_E^2 = ||u_h||_E^2 + ||u_g - u_h||_E^2,
!>     estimate_energy_bound = eta / sqrt(||u_h||_E^2 + eta^2) >= ||u_g - u_h||_E / ||u_g||_E.
!> C_K = 1 (doc/theory.md, "Error estimate": when that Korn constant holds).
!> It is the bound of the error of u_h for the contact tractions the run
!> found, not of the contact problem's own solution: the traction's own
!> error is what estimate pressure reports.
!>
!> Computed only where the construction holds: no other load on the bodies
!> (their free dofs carry the contact forces alone), no thermal strain, no
!> springs, no supports in local axes, no 8- or 9-node elements, no curved
!> 6-node elements, no B-bar; otherwise res%estimate_energy_bound = -1 and
!> the summary has no such line.
!>
!> Programming interface
!>   bound_energy_error(prob, res)   res%estimate_energy_bound of the final state (u in x, y)
module energy_bound
  use kinds, only: dp
  use problem, only: problem_t
  use results_writer, only: results_t
  use body, only: internal_forces, to_global_axes
  use contact_condensation, only: contact_forces
  use stress_equilibration, only: edge_traction_t, equilibrate_body
  use lapack_interfaces, only: dgesv
  implicit none
  private
  public :: bound_energy_error

  !> The Korn constant the bound is stated with (module header).
  real(dp), parameter :: korn = 1.0_dp

contains

  !> res%estimate_energy_bound (module header), -1 where not computed.
  !>   res (inout) u (x, y), mu, tau, adt on entry; estimate_energy_bound on exit
  !>   why (out)   '' when computed, else why not (for the run log)
  subroutine bound_energy_error(prob, res, why)
    type(problem_t), intent(in) :: prob
    type(results_t), intent(inout) :: res
    character(len=:), allocatable, intent(out) :: why
    type(edge_traction_t), allocatable :: loads(:)
    real(dp), allocatable :: fc(:), fint(:), u(:,:)
    logical, allocatable :: fixed(:,:)
    real(dp) :: sym2, skew2, e2, eta2, energy2, scale
    integer :: b, nn, d0, info
    res%estimate_energy_bound = -1
    why = 'a support in local axes, a spring or a thermal strain'
    do b = 1, size(prob%sc%bodies)
      associate (bd => prob%sc%bodies(b))
        if (allocated(bd%axes) .or. bd%springs%n > 0) return
        if (any(res%adt(bd%elem0 + 1:bd%elem0 + bd%mesh%nelem) /= 0.0_dp)) return
      end associate
    end do
    call trace_loads(prob, res, loads, fc)
    ! no load but the contact forces: K u_h = f_c on every free dof
    allocate(fint(prob%sc%ndof))
    call internal_forces(prob%sc%bodies, res%u, fint)
    scale = maxval(abs(fint))
    why = 'no internal force'
    if (.not. scale > 0.0_dp) return
    why = 'a load other than the contact forces (body, edge or point load)'
    if (any(.not. prob%sc%fixed .and. abs(fint - fc(1:prob%sc%ndof)) > 1.0e-7_dp * scale)) return
    eta2 = 0
    energy2 = 0
    do b = 1, size(prob%sc%bodies)
      associate (bd => prob%sc%bodies(b))
        nn = bd%mesh%nnode
        d0 = bd%dof0
        u = reshape(res%u(d0 + 1:d0 + 2 * nn), [2, nn])
        fixed = reshape(prob%sc%fixed(d0 + 1:d0 + 2 * nn), [2, nn])
        call equilibrate_body(bd, u, fixed, loads(b), sym2, skew2, e2, info)
        why = 'body ' // trim(bd%name) // ': its elements or supports are not covered (8- or 9-node, ' // &
              'curved, B-bar, a support on one node)'
        if (info == 2) why = 'body ' // trim(bd%name) // ': a patch problem could not be solved'
        if (info /= 0) return
        eta2 = eta2 + (sqrt(sym2) + korn * sqrt(skew2))**2
        energy2 = energy2 + e2
      end associate
    end do
    why = ''
    if (energy2 + eta2 > 0.0_dp) then
      res%estimate_energy_bound = sqrt(eta2 / (energy2 + eta2))
    else
      res%estimate_energy_bound = 0
    end if
  end subroutine bound_energy_error

  !> Each body's loaded edges: the line force g of each pair's contact
  !> forces along its slave and master traces (module header); fc (ndof+)
  !> all pairs' contact forces in x, y.
  subroutine trace_loads(prob, res, loads, fc)
    type(problem_t), intent(in) :: prob
    type(results_t), intent(in) :: res
    type(edge_traction_t), allocatable, intent(out) :: loads(:)
    real(dp), allocatable, intent(out) :: fc(:)
    real(dp), allocatable :: z(:), zp(:), fp(:)
    integer :: ip, r, nz
    allocate(loads(size(prob%sc%bodies)))
    nz = 0
    if (allocated(res%mu)) then
      z = res%mu
      if (allocated(res%tau)) z = [res%mu, res%tau]
      nz = size(z)
    end if
    allocate(fc(prob%sc%ndof), source=0.0_dp)
    if (nz == 0) return
    allocate(fp(prob%sc%ndof), zp(nz))
    call contact_forces(prob%cs, z, fc)
    call to_global_axes(prob%sc%bodies, fc)
    do ip = 1, prob%cs%npair
      zp = 0
      do r = 1, prob%cs%nrow
        if (prob%cs%row_pair(r) == ip) zp(r) = z(r)
      end do
      do r = 1, nz - prob%cs%nrow
        if (prob%cs%row_pair(prob%cs%tan_row(r)) == ip) zp(prob%cs%nrow + r) = z(prob%cs%nrow + r)
      end do
      fp = 0
      call contact_forces(prob%cs, zp, fp)
      call to_global_axes(prob%sc%bodies, fp)
      associate (pr => prob%cs%pair(ip))
        call add_trace(prob, pr%spec%slave_body, pr%snode, pr%degree(1), fp, loads(pr%spec%slave_body))
        if (pr%spec%master_body > 0) &
          call add_trace(prob, pr%spec%master_body, pr%mnode, pr%degree(2), fp, loads(pr%spec%master_body))
      end associate
    end do
  end subroutine trace_loads

  !> The line force g along one trace (nodes chain, linear or quadratic)
  !> of body b from the nodal forces f (x, y, solver dofs): M g = f on the
  !> trace's nodes, M its mass matrix; its segments appended to load.
  subroutine add_trace(prob, b, chain, degree, f, load)
    type(problem_t), intent(in) :: prob
    integer, intent(in) :: b, chain(:), degree
    real(dp), intent(in) :: f(:)
    type(edge_traction_t), intent(inout) :: load
    integer, allocatable :: loc(:), node(:), ipiv(:), seg(:,:), newnode(:,:)
    real(dp), allocatable :: mass(:,:), g(:,:), newg(:,:,:)
    real(dp) :: len, me(3, 3)
    integer :: k, n, ns, s, i, j, info, step, nold
    associate (bd => prob%sc%bodies(b))
      if (size(chain) < 2) return
      allocate(loc(bd%mesh%nnode), source=0)
      allocate(node(size(chain)))
      n = 0
      do k = 1, size(chain)
        if (loc(chain(k)) == 0) then
          n = n + 1
          loc(chain(k)) = n
          node(n) = chain(k)
        end if
      end do
      step = merge(2, 1, degree == 2)
      ns = (size(chain) - 1) / step
      allocate(seg(3, ns), source=0)
      do s = 1, ns
        k = 1 + (s - 1) * step
        seg(1:2, s) = [chain(k), chain(k + step)]
        if (step == 2) seg(3, s) = chain(k + 1)
      end do
      allocate(mass(n, n), g(n, 2), source=0.0_dp)
      do s = 1, ns
        len = norm2(bd%mesh%x(:, seg(2, s)) - bd%mesh%x(:, seg(1, s)))
        if (step == 2) then        ! ends, then the middle
          me = len / 30 * reshape([4, -1, 2, -1, 4, 2, 2, 2, 16], [3, 3])
        else
          me(1:2, 1:2) = len / 6 * reshape([2, 1, 1, 2], [2, 2])
        end if
        do j = 1, step + 1
          do i = 1, step + 1
            mass(loc(seg(i, s)), loc(seg(j, s))) = mass(loc(seg(i, s)), loc(seg(j, s))) + me(i, j)
          end do
        end do
      end do
      do k = 1, n
        g(k, :) = f(bd%dof0 + 2 * node(k) - 1:bd%dof0 + 2 * node(k))
      end do
      allocate(ipiv(n))
      call dgesv(n, 2, mass, n, ipiv, g, n, info)
      if (info /= 0) return
      nold = 0
      if (allocated(load%node)) nold = size(load%node, 2)
      allocate(newnode(3, nold + ns), source=0)
      allocate(newg(2, 3, nold + ns), source=0.0_dp)
      if (nold > 0) then
        newnode(:, 1:nold) = load%node
        newg(:, :, 1:nold) = load%g
      end if
      do s = 1, ns
        newnode(:, nold + s) = seg(:, s)
        do i = 1, step + 1
          newg(:, i, nold + s) = g(loc(seg(i, s)), :)
        end do
      end do
      call move_alloc(newnode, load%node)
      call move_alloc(newg, load%g)
    end associate
  end subroutine add_trace

end module energy_bound
