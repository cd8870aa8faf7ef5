!> post_processing: what the files report, computed from the displacement and
!> the contact multipliers: stresses, energy and the reaction of each FIX
!> (R = K u - f_ext - f_contact on its fixed dofs) and of each SPRING
!> (-K_s u over its springs), the contact resultant of
!> each pair, each RIGID's motion and the force on it, the contact measures
!> (pressures p = mu / int(phi_i), status, counts, complementarity) and the
!> nodal contact fields of the VTK file; last, the check that every number
!> about to be written is finite.
!>
!> Why it exists: these are the run's results, not its method; the run asks
!> for them of its final state and of each recorded load step alike, each
!> piece on the results it is given (the run's own, or a step's).  A result
!> that overflows returns an error (nothing is written).
!>
!> Programming interface
!>   name_results(prob, res)            the summary's names of the FIXes, SPRINGs and RIGIDs, once
!>   take_solution(prob, sol, res)      a step's solution into results: multipliers, gaps, slips,
!>                                      states, free motions, method and fallbacks
!>   contact_measures(prob, w, sol, res)  pressures, status, counts, complementarity (W of the rows)
!>   state_results(prob, fext, res, err)  contact resultants, stresses, energy, reactions, the
!>                                      RIGIDs, the nodal contact fields, zones; all checked finite
!>   engineering_results(prob, res)     each pair's zones, peak and centre of pressure (contact_zones),
!>                                      each FIX boundary's mean displacement
!>   fix_boundaries(prob, labels, of_fix)   the distinct BODY:BOUNDARY of the FIXes, each FIX's among them
module post_processing
  use kinds, only: dp
  use strings, only: int_to_str
  use errors, only: error_t, set_error
  use problem, only: problem_t
  use step_solution, only: step_solution_t
  use results_writer, only: results_t
  use body, only: element_response, to_global_axes, spring_reactions
  use finite_strain_assembly, only: finite_strain_fields, internal_force_vector
  use contact_set, only: row_of_node, state_row_of_node, node_rows, node_traction
  use contact_condensation, only: contact_forces
  use contact_zones, only: pair_zones
  use mesh, only: find_name, boundary_nodes
  use text_scan, only: string_t
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  implicit none
  private
  public :: name_results, take_solution, contact_measures, state_results, engineering_results, fix_boundaries

contains

  !> The names of the summary's rows, which the load steps do not change:
  !> each FIX's BODY:BOUNDARY (its reaction), each SPRING's BODY:NAME, each
  !> RIGID's name.
  !>   res (inout) fix_label, spring_label, rigid_name on exit
  subroutine name_results(prob, res)
    type(problem_t), intent(in) :: prob
    type(results_t), intent(inout) :: res
    integer :: j, b, n
    allocate(res%fix_label(size(prob%sc%fixes)), res%rigid_name(size(prob%sc%rigids)))
    do j = 1, size(prob%sc%fixes)
      res%fix_label(j)%s = prob%sc%fixes(j)%label
    end do
    allocate(res%spring_label(sum([(size(prob%deck%bodies(b)%springs), b = 1, size(prob%deck%bodies))])))
    n = 0
    do b = 1, size(prob%deck%bodies)
      do j = 1, size(prob%deck%bodies(b)%springs)
        n = n + 1
        res%spring_label(n)%s = prob%deck%bodies(b)%name // ':' // prob%deck%bodies(b)%springs(j)%boundary
      end do
    end do
    do j = 1, size(prob%sc%rigids)
      res%rigid_name(j)%s = prob%sc%rigids(j)%name
    end do
  end subroutine name_results

  !> A solved step's answer into results: the multipliers, gaps, free
  !> motions and unheld modes, with friction the tangential multipliers,
  !> slips and states (and friction_results), the method's figures and the
  !> fallbacks (`lcp_fallback STEP FROM TO`).
  !>   sol (in)    the step's solution (unallocated multipliers: no contact)
  !>   res (inout) the results it fills
  subroutine take_solution(prob, sol, res)
    type(problem_t), intent(in) :: prob
    type(step_solution_t), intent(in) :: sol
    type(results_t), intent(inout) :: res
    integer :: k
    if (allocated(sol%mu)) res%mu = sol%mu
    if (allocated(sol%gap)) res%gap = sol%gap
    if (allocated(sol%alpha)) res%alpha = sol%alpha
    if (allocated(sol%unheld_mode)) res%unheld_mode = sol%unheld_mode
    if (allocated(sol%method)) res%lcp_method = sol%method
    if (allocated(sol%newton)) res%newton = sol%newton
    res%lcp_iterations = sol%iterations
    res%lcp_residual = sol%residual
    res%certificate = [sol%cert%complementarity, sol%cert%cone, sol%cert%equilibrium]
    if (allocated(sol%fallback)) then
      allocate(res%lcp_fallback(size(sol%fallback)))
      do k = 1, size(sol%fallback)
        res%lcp_fallback(k)%s = int_to_str(sol%fallback(k)%step) // ' ' // sol%fallback(k)%from // ' ' // sol%fallback(k)%to
      end do
    end if
    if (.not. allocated(sol%tau)) return
    res%tau = sol%tau
    res%slip = sol%slip
    res%fstate = sol%fstate
    res%lcp_iterations = sol%total_iterations          ! with friction: every step's, the history's cost
    call friction_results(prob, res)
  end subroutine take_solution

  !> A step's friction results from its tangential multipliers and states:
  !> the shear traction and tangential row of each row, the stick and slip counts.
  !>   res (inout) tau, fstate on entry; shear, tan_of_row, stick_nodes, slip_nodes on exit
  subroutine friction_results(prob, res)
    type(problem_t), intent(in) :: prob
    type(results_t), intent(inout) :: res
    real(dp), allocatable :: tforce(:)
    integer :: r, k
    allocate(res%shear(prob%cs%ntan), res%tan_of_row(prob%cs%nrow))
    res%tan_of_row = 0
    allocate(tforce(prob%cs%nrow), source=0.0_dp)
    tforce(prob%cs%tan_row) = -res%tau                    ! the force on the slave is -tau t
    do r = 1, prob%cs%ntan
      k = prob%cs%tan_row(r)
      res%tan_of_row(k) = r
      if (prob%cs%weight(k) > 0.0_dp) then
        res%shear(r) = tforce(k) / prob%cs%weight(k)
      else                    ! a hat without weight (a quadratic trace's node on the axis): with its neighbour's
        res%shear(r) = node_traction(prob%cs, prob%cs%row_pair(k), prob%cs%row_node(k), tforce)
      end if
    end do
    res%stick_nodes = count(res%fstate == 1)
    res%slip_nodes = count(res%fstate == 2)
  end subroutine friction_results

  !> The results of a state from its displacement and multipliers: the
  !> contact resultants, stresses, energy, reactions, the RIGIDs, the nodal
  !> contact fields and the zones, all checked finite.
  !>   fext (in)    (ndof) the state's external forces (solver basis)
  !>   res  (inout) u (solver basis), the thermal strains adt and the
  !>                multipliers (mu, tau: unallocated without contact), contact
  !>                measures on entry; the results on exit, u in x, y components
  !>   err  (out)   a result is not finite (the loads overflow)
  subroutine state_results(prob, fext, res, err)
    type(problem_t), intent(in) :: prob
    real(dp), intent(in) :: fext(:)
    type(results_t), intent(inout) :: res
    type(error_t), allocatable, intent(out) :: err
    real(dp), allocatable :: fc(:)
    if (.not. allocated(res%mu)) then
      call pair_resultants(prob, [real(dp) ::], res, fc)
    else if (allocated(res%tau)) then
      call pair_resultants(prob, [res%mu, res%tau], res, fc)
    else
      call pair_resultants(prob, res%mu, res, fc)
    end if
    call post_process(prob, fext, fc, res)
    call rigid_results(prob, fc, res)
    call nodal_contact_fields(prob, res)
    call engineering_results(prob, res)
    call check_finite_results(prob, res, err)
  end subroutine state_results

  !> res%contact_force: per pair, the resultant of the contact forces on its
  !> slave body, the sum over the slave dofs of -C' z restricted to the
  !> pair's rows (-sum_i mu_i n_i - tau_i t_i, the slave's outward normal n);
  !> and fc = -C' z, all pairs, on every dof.
  !>   z  (in)  (nrow) normal multipliers, or (nrow + ntan) with the tangential ones
  !>   fc (out) (ndof) -C' z, solver basis
  subroutine pair_resultants(prob, z, res, fc)
    type(problem_t), intent(in) :: prob
    real(dp), intent(in) :: z(:)
    type(results_t), intent(inout) :: res
    real(dp), allocatable, intent(out) :: fc(:)
    real(dp), allocatable :: zp(:)
    integer :: ip, r, d0, nn
    allocate(fc(prob%sc%ndof), source=0.0_dp)
    if (allocated(res%contact_force)) deallocate(res%contact_force)
    allocate(res%contact_force(2, prob%cs%npair), source=0.0_dp)
    if (size(z) == 0) return
    allocate(zp(size(z)))
    do ip = 1, prob%cs%npair
      zp = 0.0_dp
      do r = 1, prob%cs%nrow
        if (prob%cs%row_pair(r) == ip) zp(r) = z(r)
      end do
      do r = 1, size(z) - prob%cs%nrow
        if (prob%cs%row_pair(prob%cs%tan_row(r)) == ip) zp(prob%cs%nrow + r) = z(prob%cs%nrow + r)
      end do
      call contact_forces(prob%cs, zp, fc)
      call to_global_axes(prob%sc%bodies, fc)
      d0 = prob%sc%bodies(prob%cs%pair(ip)%spec%slave_body)%dof0
      nn = prob%sc%bodies(prob%cs%pair(ip)%spec%slave_body)%mesh%nnode
      res%contact_force(1, ip) = sum(fc(d0 + 1:d0 + 2 * nn:2))
      res%contact_force(2, ip) = sum(fc(d0 + 2:d0 + 2 * nn:2))
    end do
    call contact_forces(prob%cs, z, fc)
  end subroutine pair_resultants

  !> Stresses (when the VTK file asks for them), energy and the reaction of
  !> each FIX, R = K u - f_ext - f_contact on its fixed dofs, from res%u and
  !> the contact forces fc; then res%u in x, y components (nodes in local
  !> axes: the reaction of a fixed dof along n or t is that force along n or
  !> t, summed in x, y into its FIX's reaction).
  !>   fext (in) (ndof) the external forces of the step (solver basis)
  !>   fc   (in) (ndof) the contact forces -C' z (solver basis)
  subroutine post_process(prob, fext, fc, res)
    type(problem_t), intent(in) :: prob
    real(dp), intent(in) :: fext(:), fc(:)
    type(results_t), intent(inout) :: res
    integer :: j, b, a, n, ns
    real(dp), allocatable :: axis(:,:), fint(:)
    if (allocated(res%stress)) deallocate(res%stress, res%vm)
    if (allocated(res%reaction)) deallocate(res%reaction)
    allocate(res%stress(merge(4, 3, prob%deck%axisymmetric), prob%sc%nelem), res%vm(prob%sc%nelem), fint(prob%sc%ndof))
    if (prob%deck%output%fields(4) .or. prob%deck%output%fields(5) .or. any(prob%sc%bodies%finite)) then
      call element_response(prob%sc%bodies, res%u, fint, res%stress, res%vm, res%adt)
    else
      call element_response(prob%sc%bodies, res%u, fint)        ! no stress field asked for: none computed
    end if
    res%energy = 0.5_dp * dot_product(res%u, fint)
    if (any(prob%sc%bodies%finite)) call finite_strain_results(prob, res, fint)
    allocate(res%reaction(2, size(prob%sc%fixes)), source=0.0_dp)
    ! the direction of each dof: e_x, e_y, or n, t at a node in local axes
    allocate(axis(2, prob%sc%ndof), source=0.0_dp)
    axis(1, 1::2) = 1.0_dp
    axis(2, 2::2) = 1.0_dp
    do b = 1, size(prob%sc%bodies)
      if (.not. allocated(prob%sc%bodies(b)%axes)) cycle
      do a = 1, prob%sc%bodies(b)%mesh%nnode
        if (all(prob%sc%bodies(b)%axes(:, a) == 0.0_dp)) cycle
        j = prob%sc%bodies(b)%dof0 + 2 * a - 1
        axis(:, j) = prob%sc%bodies(b)%axes(:, a)
        axis(:, j + 1) = [-prob%sc%bodies(b)%axes(2, a), prob%sc%bodies(b)%axes(1, a)]
      end do
    end do
    do j = 1, prob%sc%ndof
      if (prob%sc%fix_owner(j) > 0) then
        ! R = K u - f_ext - f_contact on a fixed dof, along its direction
        associate (r => res%reaction(:, prob%sc%fix_owner(j)))
          r = r + (fint(j) - fext(j) - fc(j)) * axis(:, j)
        end associate
      end if
    end do
    ! each SPRING's force on its body, -K_s u (u still in the solver basis)
    if (allocated(res%spring_force)) deallocate(res%spring_force)
    allocate(res%spring_force(2, sum([(size(prob%deck%bodies(b)%springs), b = 1, size(prob%deck%bodies))])), source=0.0_dp)
    n = 0
    do b = 1, size(prob%sc%bodies)
      ns = size(prob%deck%bodies(b)%springs)
      if (ns > 0) call spring_reactions(prob%sc%bodies(b), res%u, res%spring_force(:, n + 1:n + ns))
      n = n + ns
    end do
    call to_global_axes(prob%sc%bodies, res%u)
  end subroutine post_process

  !> A scene with hyperelastic bodies: their internal forces f_int(u) in
  !> fint (the reactions' f_int - f_ext - f_c), the stored energy (the
  !> linear bodies' u'K u / 2 plus the hyperelastic ones' int W dV0), J and
  !> the largest stretch of every element (1 in the linear bodies), and the
  !> hyperelastic elements' Cauchy stress in place of the linear one.
  !>   fint (inout) (ndof) the linear K u of every body on entry
  subroutine finite_strain_results(prob, res, fint)
    type(problem_t), intent(in) :: prob
    type(results_t), intent(inout) :: res
    real(dp), intent(inout) :: fint(:)
    real(dp) :: we
    integer :: b, d0, nd, bad(2)
    res%energy = 0.0_dp
    do b = 1, size(prob%sc%bodies)
      if (prob%sc%bodies(b)%finite) cycle
      d0 = prob%sc%bodies(b)%dof0
      nd = 2 * prob%sc%bodies(b)%mesh%nnode
      res%energy = res%energy + 0.5_dp * dot_product(res%u(d0 + 1:d0 + nd), fint(d0 + 1:d0 + nd))
    end do
    if (allocated(res%jacobian)) deallocate(res%jacobian, res%stretch)
    allocate(res%jacobian(prob%sc%nelem), res%stretch(prob%sc%nelem), source=1.0_dp)
    call finite_strain_fields(prob%sc%bodies, res%u, we, res%jacobian, res%stretch, res%stress, res%vm)
    res%energy = res%energy + we
    call internal_force_vector(prob%sc%bodies, res%u, fint, bad)
  end subroutine finite_strain_results

  !> Each RIGID's motion (u_x, u_y, theta of its reference point, res%u) and
  !> the contact force on it (fc = -C' z on its dofs: force x, y, moment about
  !> the reference point), for the summary, the step table and the log.
  subroutine rigid_results(prob, fc, res)
    type(problem_t), intent(in) :: prob
    real(dp), intent(in) :: fc(:)
    type(results_t), intent(inout) :: res
    integer :: r
    if (allocated(res%rigid)) deallocate(res%rigid)
    allocate(res%rigid(6, size(prob%sc%rigids)), source=0.0_dp)
    do r = 1, size(prob%sc%rigids)
      res%rigid(1:3, r) = res%u(prob%sc%rigids(r)%dof0 + 1:prob%sc%rigids(r)%dof0 + 3)
      res%rigid(4:6, r) = fc(prob%sc%rigids(r)%dof0 + 1:prob%sc%rigids(r)%dof0 + 3)
    end do
  end subroutine rigid_results

  !> Pressures, status, node counts and complementarity of a solved
  !> contact problem (res%mu, res%gap set).
  !>   w   (in) (nrow + ntan, nrow + ntan) W of the step's rows (its diagonal:
  !>            the redundant rows)
  !>   sol (in) the step's solution: q, its gaps without contact forces (the
  !>            length scale of the complementarity, with the initial gaps)
  subroutine contact_measures(prob, w, sol, res)
    type(problem_t), intent(in) :: prob
    real(dp), intent(in) :: w(:,:)
    type(step_solution_t), intent(in) :: sol
    type(results_t), intent(inout) :: res
    integer :: r, ip, node, rows(3), nr
    real(dp) :: dmax, pmax, gmax
    if (allocated(res%pressure)) deallocate(res%pressure, res%status)
    allocate(res%pressure(prob%cs%nrow), res%status(prob%cs%nrow))
    res%contact_nodes = prob%cs%nrow
    if (prob%cs%nrow == 0) return
    dmax = 0.0_dp
    do r = 1, prob%cs%nrow
      dmax = max(dmax, w(r, r))
    end do
    res%redundant = count([(w(r, r) <= 1.0e-14_dp * dmax, r = 1, prob%cs%nrow)])
    pmax = 0.0_dp
    do r = 1, prob%cs%nrow
      ip = prob%cs%row_pair(r)
      node = prob%cs%row_node(r)
      if (prob%cs%weight(r) > 0.0_dp) then
        res%pressure(r) = res%mu(r) / prob%cs%weight(r)    ! p = mu / int(phi_i)
      else                                                ! a hat without weight (a quadratic trace's
        res%pressure(r) = node_traction(prob%cs, ip, node, res%mu)   ! node on the axis): with its neighbour's
      end if
      pmax = max(pmax, abs(res%pressure(r)))
    end do
    do r = 1, prob%cs%nrow
      res%status(r) = merge(1, 0, res%mu(r) > 1.0e-12_dp * maxval(abs(res%mu)) .and. res%mu(r) > 0.0_dp)
    end do
    ! counts of slave nodes (a one-segment zone has two nodes on one row)
    res%contact_nodes = 0
    res%active_nodes = 0
    do ip = 1, prob%cs%npair
      do node = 1, size(prob%cs%pair(ip)%snode)
        call node_rows(prob%cs, ip, node, rows, nr)
        if (nr == 0) cycle
        res%contact_nodes = res%contact_nodes + 1
        if (any(res%status(rows(1:nr)) == 1)) res%active_nodes = res%active_nodes + 1
      end do
    end do
    ! length scale: the initial gaps, or the gaps the loads open without contact forces (q)
    gmax = max(maxval(abs(prob%cs%g)), maxval(abs(sol%q(1:prob%cs%nrow))))
    if (pmax > 0.0_dp .and. gmax > 0.0_dp) then
      res%complementarity = maxval(abs(res%pressure * res%gap)) / (pmax * gmax)
    else
      res%complementarity = 0.0_dp
    end if
    res%min_gap = min(0.0_dp, minval(res%gap))
    res%min_pressure = minval(res%pressure)
  end subroutine contact_measures

  !> contact_pressure, gap (and with friction shear, friction state and
  !> slip) on the nodes, for the VTK files: what the contact table reports
  !> (node_traction; the state and slip of the node's row's tangential row).
  subroutine nodal_contact_fields(prob, res)
    type(problem_t), intent(in) :: prob
    type(results_t), intent(inout) :: res
    integer :: r, ip, node, gnode, rows(3), nr, t
    real(dp), allocatable :: tforce(:)
    if (allocated(res%node_pressure)) deallocate(res%node_pressure, res%node_gap)
    allocate(res%node_pressure(prob%sc%ndof / 2), res%node_gap(prob%sc%ndof / 2))
    res%node_pressure = 0.0_dp
    res%node_gap = 0.0_dp
    if (allocated(res%tau)) then
      allocate(res%node_shear(prob%sc%ndof / 2), source=0.0_dp)
      allocate(res%node_fstate(prob%sc%ndof / 2), source=0)
      allocate(res%node_slip(prob%sc%ndof / 2), source=0.0_dp)
      allocate(tforce(prob%cs%nrow), source=0.0_dp)
      tforce(prob%cs%tan_row) = -res%tau                   ! the force on the slave is -tau t
    end if
    do ip = 1, prob%cs%npair
      do node = 1, size(prob%cs%pair(ip)%snode)
        r = row_of_node(prob%cs, ip, node)
        if (r == 0) cycle
        gnode = prob%sc%bodies(prob%cs%pair(ip)%spec%slave_body)%dof0 / 2 + prob%cs%pair(ip)%snode(node)
        res%node_pressure(gnode) = node_traction(prob%cs, ip, node, res%mu)
        call node_rows(prob%cs, ip, node, rows, nr)
        res%node_gap(gnode) = minval(res%gap(rows(1:nr)))
        if (allocated(tforce)) then
          res%node_shear(gnode) = node_traction(prob%cs, ip, node, tforce)
          t = res%tan_of_row(state_row_of_node(prob%cs, ip, node))   ! an axis node's state is its neighbour's
          if (t > 0) then
            res%node_fstate(gnode) = res%fstate(t)
            res%node_slip(gnode) = res%slip(t)
          end if
        end if
      end do
    end do
  end subroutine nodal_contact_fields

  !> What an engineer reads first: each pair's contact zone (its ends, length,
  !> count), peak pressure and centre of pressure, and with friction its stick
  !> zone (contact_zones, doc/outputs.md); each FIX boundary's displacement,
  !> the mean of u over its nodes.
  !>   res (inout) u (x, y components), mu, status (tau, fstate) on entry;
  !>               zones, fix_boundary, boundary_u on exit
  subroutine engineering_results(prob, res)
    type(problem_t), intent(in) :: prob
    type(results_t), intent(inout) :: res
    integer :: ip, j, b, ib, k
    integer, allocatable :: of_fix(:), nodes(:)
    real(dp), allocatable :: none(:)
    integer, allocatable :: no_state(:)
    if (allocated(res%zones)) deallocate(res%zones)
    allocate(res%zones(prob%cs%npair), none(0), no_state(0))
    do ip = 1, prob%cs%npair
      if (.not. (allocated(res%mu) .and. allocated(res%status))) cycle
      if (allocated(res%tau) .and. allocated(res%fstate)) then
        call pair_zones(prob%cs, ip, res%mu, res%status, res%tau, res%fstate, res%zones(ip))
      else
        call pair_zones(prob%cs, ip, res%mu, res%status, none, no_state, res%zones(ip))
      end if
    end do
    call fix_boundaries(prob, res%fix_boundary, of_fix)
    if (allocated(res%boundary_u)) deallocate(res%boundary_u)
    allocate(res%boundary_u(2, size(res%fix_boundary)), source=0.0_dp)
    do k = 1, size(res%fix_boundary)
      j = findloc(of_fix, k, dim=1)                 ! the first FIX on it: its body and boundary name
      b = prob%sc%fixes(j)%body
      ib = find_name(prob%sc%bodies(b)%mesh%bnd, res%fix_boundary(k)%s(len(prob%sc%bodies(b)%name) + 2:))
      if (ib == 0) cycle
      call boundary_nodes(prob%sc%bodies(b)%mesh%bnd(ib), nodes)
      if (size(nodes) == 0) cycle
      res%boundary_u(1, k) = sum(res%u(prob%sc%bodies(b)%dof0 + 2 * nodes - 1)) / size(nodes)
      res%boundary_u(2, k) = sum(res%u(prob%sc%bodies(b)%dof0 + 2 * nodes)) / size(nodes)
    end do
  end subroutine engineering_results

  !> The distinct boundaries the FIX statements hold, BODY:BOUNDARY in the
  !> order of their first FIX: two FIX statements on one boundary (ux in one
  !> load path, uy in another) are one boundary, its reaction their sum.
  !>   labels (out) (nfb) the distinct labels
  !>   of_fix (out) (nfix) each FIX's index in labels
  subroutine fix_boundaries(prob, labels, of_fix)
    type(problem_t), intent(in) :: prob
    type(string_t), allocatable, intent(out) :: labels(:)
    integer, allocatable, intent(out) :: of_fix(:)
    type(string_t), allocatable :: seen(:)
    integer :: j, k, n
    allocate(of_fix(size(prob%sc%fixes)), seen(size(prob%sc%fixes)))
    n = 0
    do j = 1, size(prob%sc%fixes)
      of_fix(j) = 0
      do k = 1, n
        if (seen(k)%s == prob%sc%fixes(j)%label) then
          of_fix(j) = k
          exit
        end if
      end do
      if (of_fix(j) > 0) cycle
      n = n + 1
      seen(n)%s = prob%sc%fixes(j)%label
      of_fix(j) = n
    end do
    allocate(labels(n))
    do k = 1, n
      call move_alloc(seen(k)%s, labels(k)%s)
    end do
  end subroutine fix_boundaries

  !> Every number about to be written must be finite: loads near the top of
  !> the accepted range can overflow in the post-processing (energy, stresses)
  !> even when the displacement did not: a numerical failure, nothing written.
  subroutine check_finite_results(prob, res, err)
    type(problem_t), intent(in) :: prob
    type(results_t), intent(in) :: res
    type(error_t), allocatable, intent(out) :: err
    logical :: ok
    ok = ieee_is_finite(res%energy) .and. all(ieee_is_finite(res%reaction)) .and. all(ieee_is_finite(res%spring_force)) .and. &
         ieee_is_finite(res%complementarity)
    if (prob%deck%output%fields(4) .or. prob%deck%output%fields(5)) &
      ok = ok .and. all(ieee_is_finite(res%stress)) .and. all(ieee_is_finite(res%vm))
    if (allocated(res%gap)) ok = ok .and. all(ieee_is_finite(res%gap)) .and. all(ieee_is_finite(res%pressure))
    if (.not. ok) call set_error(err, 'the results overflow (stresses, reactions, energy or contact quantities ' // &
      'are not finite): the loads or prescribed values are out of the range of double precision arithmetic')
  end subroutine check_finite_results

end module post_processing
