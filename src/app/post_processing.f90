!> post_processing: what the files report, computed from the displacement and
!> the contact multipliers: stresses, energy and the reaction of each FIX
!> (R = K u - f_ext - f_contact on its fixed dofs) and of each SPRING
!> (-K_s u over its springs), the contact resultant of
!> each pair, each RIGID's motion and the force on it, the contact measures
!> (pressures p = mu / int(phi_i), status, counts, complementarity) and the
!> nodal contact fields of the VTK file; last, the check that every number
!> about to be written is finite.
!>
!> Why it exists: these are the run's results, not its method; the program
!> asks for them in one call (compute_results), a load step of OUTPUT
!> steps=all piece by piece, each piece on the results it is given (res:
!> the run's own, or a step's).  Who may use it: the program and its step
!> modules (run_state's list).  A result that overflows ends the run (exit 1,
!> nothing written), as the program would.
!>
!> Programming interface
!>   name_results(run)            the summary's names of the FIXes and RIGIDs, once
!>   compute_results(run)         everything below for the run's final state
!>   pair_resultants(run, z, res) fc = -C' z and the resultant on each pair's slave body
!>   post_process(run, fext, res) stresses, energy, reactions; u in x, y components
!>   rigid_results(run, res)      each RIGID's motion and the contact force on it
!>   contact_measures(run, res)   pressures, status, counts, complementarity (mu, gap set)
!>   nodal_contact_fields(run, res)  contact pressure, gap, shear on the nodes (VTK)
!>   engineering_results(run, res)   each pair's zones, peak and centre of pressure (contact_zones),
!>                                   each FIX boundary's mean displacement
!>   fix_boundaries(run, labels, of_fix)   the distinct BODY:BOUNDARY of the FIXes, each FIX's among them
!>   check_finite_results(run, res)  exit 1 when a result to be written is not finite
module post_processing
  use kinds, only: dp
  use exits, only: fail_numerical
  use run_state, only: run_t
  use results_writer, only: results_t
  use run_report, only: add_warning
  use body, only: element_response, to_global_axes, spring_reactions
  use contact_set, only: row_of_node, state_row_of_node, node_rows, node_traction
  use contact_condensation, only: contact_forces
  use contact_zones, only: pair_zones
  use mesh, only: find_name, boundary_nodes
  use text_scan, only: string_t
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use run_phase, only: enter_phase
  implicit none
  private
  public :: name_results, compute_results, pair_resultants, post_process, rigid_results, contact_measures, nodal_contact_fields
  public :: check_finite_results, engineering_results, fix_boundaries

contains

  !> The names of the summary's rows, which the load steps do not change:
  !> each FIX's BODY:BOUNDARY (its reaction), each SPRING's BODY:NAME, each
  !> RIGID's name.
  !>   run (inout) the scene on entry; res%fix_label, res%spring_label, res%rigid_name on exit
  subroutine name_results(run)
    type(run_t), intent(inout) :: run
    integer :: j, b, n
    allocate(run%res%fix_label(size(run%sc%fixes)), run%res%rigid_name(size(run%sc%rigids)))
    do j = 1, size(run%sc%fixes)
      run%res%fix_label(j)%s = run%sc%fixes(j)%label
    end do
    allocate(run%res%spring_label(sum([(size(run%deck%bodies(b)%springs), b = 1, size(run%deck%bodies))])))
    n = 0
    do b = 1, size(run%deck%bodies)
      do j = 1, size(run%deck%bodies(b)%springs)
        n = n + 1
        run%res%spring_label(n)%s = run%deck%bodies(b)%name // ':' // run%deck%bodies(b)%springs(j)%boundary
      end do
    end do
    do j = 1, size(run%sc%rigids)
      run%res%rigid_name(j)%s = run%sc%rigids(j)%name
    end do
  end subroutine name_results

  !> The results of the run's final state: the contact resultants (from mu,
  !> and tau with friction), stresses, energy, reactions, the RIGIDs, the
  !> nodal contact fields, all checked finite.
  !>   run (inout) res%u and the multipliers on entry; the results on exit
  subroutine compute_results(run)
    type(run_t), intent(inout) :: run
    call enter_phase('computing the results')
    if (run%with_contact) then
      if (run%cs%ntan > 0) then
        call pair_resultants(run, [run%res%mu, run%res%tau], run%res)
      else
        call pair_resultants(run, run%res%mu, run%res)
      end if
    else
      call pair_resultants(run, [real(dp) ::], run%res)
    end if
    call post_process(run, run%sc%fext, run%res)
    call rigid_results(run, run%res)
    call nodal_contact_fields(run, run%res)
    call engineering_results(run, run%res)
    call check_finite_results(run, run%res)
  end subroutine compute_results

  !> res%contact_force: per pair, the resultant of the contact forces on its
  !> slave body, the sum over the slave dofs of -C' z restricted to the
  !> pair's rows (-sum_i mu_i n_i - tau_i t_i, the slave's outward normal n);
  !> and fc = -C' z, all pairs, on every dof.
  !>   z (in) (nrow) normal multipliers, or (nrow + ntan) with the tangential ones
  subroutine pair_resultants(run, z, res)
    type(run_t), intent(inout) :: run
    real(dp), intent(in) :: z(:)
    type(results_t), intent(inout) :: res
    real(dp), allocatable :: zp(:)
    integer :: ip, r, d0, nn
    if (.not. allocated(run%fc)) allocate(run%fc(run%sc%ndof))
    run%fc = 0.0_dp
    if (allocated(res%contact_force)) deallocate(res%contact_force)
    allocate(res%contact_force(2, run%cs%npair), source=0.0_dp)
    if (size(z) == 0) return
    allocate(zp(size(z)))
    do ip = 1, run%cs%npair
      zp = 0.0_dp
      do r = 1, run%cs%nrow
        if (run%cs%row_pair(r) == ip) zp(r) = z(r)
      end do
      do r = 1, size(z) - run%cs%nrow
        if (run%cs%row_pair(run%cs%tan_row(r)) == ip) zp(run%cs%nrow + r) = z(run%cs%nrow + r)
      end do
      call contact_forces(run%cs, zp, run%fc)
      call to_global_axes(run%sc%bodies, run%fc)
      d0 = run%sc%bodies(run%cs%pair(ip)%spec%slave_body)%dof0
      nn = run%sc%bodies(run%cs%pair(ip)%spec%slave_body)%mesh%nnode
      res%contact_force(1, ip) = sum(run%fc(d0 + 1:d0 + 2 * nn:2))
      res%contact_force(2, ip) = sum(run%fc(d0 + 2:d0 + 2 * nn:2))
    end do
    call contact_forces(run%cs, z, run%fc)
  end subroutine pair_resultants

  !> Stresses (when the VTK file asks for them), energy and the reaction of
  !> each FIX, R = K u - f_ext - f_contact on its fixed dofs, from res%u and
  !> the contact forces fc; then res%u in x, y components (nodes in local
  !> axes: the reaction of a fixed dof along n or t is that force along n or
  !> t, summed in x, y into its FIX's reaction).
  !>   fext (in) (ndof) the external forces of the step (solver basis)
  subroutine post_process(run, fext, res)
    type(run_t), intent(in) :: run
    real(dp), intent(in) :: fext(:)
    type(results_t), intent(inout) :: res
    integer :: j, b, a, n, ns
    real(dp), allocatable :: axis(:,:), fint(:)
    if (allocated(res%stress)) deallocate(res%stress, res%vm)
    if (allocated(res%reaction)) deallocate(res%reaction)
    allocate(res%stress(merge(4, 3, run%deck%axisymmetric), run%sc%nelem), res%vm(run%sc%nelem), fint(run%sc%ndof))
    if (run%deck%output%fields(4) .or. run%deck%output%fields(5)) then
      call element_response(run%sc%bodies, res%u, fint, res%stress, res%vm)
    else
      call element_response(run%sc%bodies, res%u, fint)        ! no stress field asked for: none computed
    end if
    res%energy = 0.5_dp * dot_product(res%u, fint)
    allocate(res%reaction(2, size(run%sc%fixes)), source=0.0_dp)
    ! the direction of each dof: e_x, e_y, or n, t at a node in local axes
    allocate(axis(2, run%sc%ndof), source=0.0_dp)
    axis(1, 1::2) = 1.0_dp
    axis(2, 2::2) = 1.0_dp
    do b = 1, size(run%sc%bodies)
      if (.not. allocated(run%sc%bodies(b)%axes)) cycle
      do a = 1, run%sc%bodies(b)%mesh%nnode
        if (all(run%sc%bodies(b)%axes(:, a) == 0.0_dp)) cycle
        j = run%sc%bodies(b)%dof0 + 2 * a - 1
        axis(:, j) = run%sc%bodies(b)%axes(:, a)
        axis(:, j + 1) = [-run%sc%bodies(b)%axes(2, a), run%sc%bodies(b)%axes(1, a)]
      end do
    end do
    do j = 1, run%sc%ndof
      if (run%sc%fix_owner(j) > 0) then
        ! R = K u - f_ext - f_contact on a fixed dof, along its direction
        associate (r => res%reaction(:, run%sc%fix_owner(j)))
          r = r + (fint(j) - fext(j) - run%fc(j)) * axis(:, j)
        end associate
      end if
    end do
    ! each SPRING's force on its body, -K_s u (u still in the solver basis)
    if (allocated(res%spring_force)) deallocate(res%spring_force)
    allocate(res%spring_force(2, sum([(size(run%deck%bodies(b)%springs), b = 1, size(run%deck%bodies))])), source=0.0_dp)
    n = 0
    do b = 1, size(run%sc%bodies)
      ns = size(run%deck%bodies(b)%springs)
      if (ns > 0) call spring_reactions(run%sc%bodies(b), res%u, res%spring_force(:, n + 1:n + ns))
      n = n + ns
    end do
    call to_global_axes(run%sc%bodies, res%u)
  end subroutine post_process

  !> Each RIGID's motion (u_x, u_y, theta of its reference point, res%u) and
  !> the contact force on it (fc = -C' z on its dofs: force x, y, moment about
  !> the reference point), for the summary, the step table and the log.
  subroutine rigid_results(run, res)
    type(run_t), intent(in) :: run
    type(results_t), intent(inout) :: res
    integer :: r
    if (allocated(res%rigid)) deallocate(res%rigid)
    allocate(res%rigid(6, size(run%sc%rigids)), source=0.0_dp)
    do r = 1, size(run%sc%rigids)
      res%rigid(1:3, r) = res%u(run%sc%rigids(r)%dof0 + 1:run%sc%rigids(r)%dof0 + 3)
      if (allocated(run%fc)) res%rigid(4:6, r) = run%fc(run%sc%rigids(r)%dof0 + 1:run%sc%rigids(r)%dof0 + 3)
    end do
  end subroutine rigid_results

  !> Pressures, status, node counts and complementarity of the solved
  !> contact problem (res%mu, res%gap set).
  subroutine contact_measures(run, res)
    type(run_t), intent(in) :: run
    type(results_t), intent(inout) :: res
    integer :: r, ip, node, rows(3), nr
    real(dp) :: dmax, pmax, gmax
    allocate(res%pressure(run%cs%nrow), res%status(run%cs%nrow))
    res%contact_nodes = run%cs%nrow
    if (run%cs%nrow == 0) return
    dmax = 0.0_dp
    do r = 1, run%cs%nrow
      dmax = max(dmax, run%w(r, r))
    end do
    res%redundant = count([(run%w(r, r) <= 1.0e-14_dp * dmax, r = 1, run%cs%nrow)])
    pmax = 0.0_dp
    do r = 1, run%cs%nrow
      ip = run%cs%row_pair(r)
      node = run%cs%row_node(r)
      if (run%cs%weight(r) > 0.0_dp) then
        res%pressure(r) = res%mu(r) / run%cs%weight(r)    ! p = mu / int(phi_i)
      else                                                ! a hat without weight (a quadratic trace's
        res%pressure(r) = node_traction(run%cs, ip, node, res%mu)   ! node on the axis): with its neighbour's
      end if
      pmax = max(pmax, abs(res%pressure(r)))
    end do
    do r = 1, run%cs%nrow
      res%status(r) = merge(1, 0, res%mu(r) > 1.0e-12_dp * maxval(abs(res%mu)) .and. res%mu(r) > 0.0_dp)
    end do
    ! counts of slave nodes (a one-segment zone has two nodes on one row)
    res%contact_nodes = 0
    res%active_nodes = 0
    do ip = 1, run%cs%npair
      do node = 1, size(run%cs%pair(ip)%snode)
        call node_rows(run%cs, ip, node, rows, nr)
        if (nr == 0) cycle
        res%contact_nodes = res%contact_nodes + 1
        if (any(res%status(rows(1:nr)) == 1)) res%active_nodes = res%active_nodes + 1
      end do
    end do
    ! length scale: the initial gaps, or the gaps the loads open without contact forces (q)
    gmax = max(maxval(abs(run%cs%g)), maxval(abs(run%q(1:run%cs%nrow))))
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
  subroutine nodal_contact_fields(run, res)
    type(run_t), intent(in) :: run
    type(results_t), intent(inout) :: res
    integer :: r, ip, node, gnode, rows(3), nr, t
    real(dp), allocatable :: tforce(:)
    allocate(res%node_pressure(run%sc%ndof / 2), res%node_gap(run%sc%ndof / 2))
    res%node_pressure = 0.0_dp
    res%node_gap = 0.0_dp
    if (allocated(res%tau)) then
      allocate(res%node_shear(run%sc%ndof / 2), source=0.0_dp)
      allocate(res%node_fstate(run%sc%ndof / 2), source=0)
      allocate(res%node_slip(run%sc%ndof / 2), source=0.0_dp)
      allocate(tforce(run%cs%nrow), source=0.0_dp)
      tforce(run%cs%tan_row) = -res%tau                   ! the force on the slave is -tau t
    end if
    do ip = 1, run%cs%npair
      do node = 1, size(run%cs%pair(ip)%snode)
        r = row_of_node(run%cs, ip, node)
        if (r == 0) cycle
        gnode = run%sc%bodies(run%cs%pair(ip)%spec%slave_body)%dof0 / 2 + run%cs%pair(ip)%snode(node)
        res%node_pressure(gnode) = node_traction(run%cs, ip, node, res%mu)
        call node_rows(run%cs, ip, node, rows, nr)
        res%node_gap(gnode) = minval(res%gap(rows(1:nr)))
        if (allocated(tforce)) then
          res%node_shear(gnode) = node_traction(run%cs, ip, node, tforce)
          t = res%tan_of_row(state_row_of_node(run%cs, ip, node))   ! an axis node's state is its neighbour's
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
  subroutine engineering_results(run, res)
    type(run_t), intent(in) :: run
    type(results_t), intent(inout) :: res
    integer :: ip, j, b, ib, k
    integer, allocatable :: of_fix(:), nodes(:)
    real(dp), allocatable :: none(:)
    integer, allocatable :: no_state(:)
    if (allocated(res%zones)) deallocate(res%zones)
    allocate(res%zones(run%cs%npair), none(0), no_state(0))
    do ip = 1, run%cs%npair
      if (.not. (allocated(res%mu) .and. allocated(res%status))) cycle
      if (allocated(res%tau) .and. allocated(res%fstate)) then
        call pair_zones(run%cs, ip, res%mu, res%status, res%tau, res%fstate, res%zones(ip))
      else
        call pair_zones(run%cs, ip, res%mu, res%status, none, no_state, res%zones(ip))
      end if
    end do
    call fix_boundaries(run, res%fix_boundary, of_fix)
    if (allocated(res%boundary_u)) deallocate(res%boundary_u)
    allocate(res%boundary_u(2, size(res%fix_boundary)), source=0.0_dp)
    do k = 1, size(res%fix_boundary)
      j = findloc(of_fix, k, dim=1)                 ! the first FIX on it: its body and boundary name
      b = run%sc%fixes(j)%body
      ib = find_name(run%sc%bodies(b)%mesh%bnd, res%fix_boundary(k)%s(len(run%sc%bodies(b)%name) + 2:))
      if (ib == 0) cycle
      call boundary_nodes(run%sc%bodies(b)%mesh%bnd(ib), nodes)
      if (size(nodes) == 0) cycle
      res%boundary_u(1, k) = sum(res%u(run%sc%bodies(b)%dof0 + 2 * nodes - 1)) / size(nodes)
      res%boundary_u(2, k) = sum(res%u(run%sc%bodies(b)%dof0 + 2 * nodes)) / size(nodes)
    end do
  end subroutine engineering_results

  !> The distinct boundaries the FIX statements hold, BODY:BOUNDARY in the
  !> order of their first FIX: two FIX statements on one boundary (ux in one
  !> load path, uy in another) are one boundary, its reaction their sum.
  !>   labels (out) (nfb) the distinct labels
  !>   of_fix (out) (nfix) each FIX's index in labels
  subroutine fix_boundaries(run, labels, of_fix)
    type(run_t), intent(in) :: run
    type(string_t), allocatable, intent(out) :: labels(:)
    integer, allocatable, intent(out) :: of_fix(:)
    type(string_t), allocatable :: seen(:)
    integer :: j, k, n
    allocate(of_fix(size(run%sc%fixes)), seen(size(run%sc%fixes)))
    n = 0
    do j = 1, size(run%sc%fixes)
      of_fix(j) = 0
      do k = 1, n
        if (seen(k)%s == run%sc%fixes(j)%label) then
          of_fix(j) = k
          exit
        end if
      end do
      if (of_fix(j) > 0) cycle
      n = n + 1
      seen(n)%s = run%sc%fixes(j)%label
      of_fix(j) = n
    end do
    allocate(labels(n))
    do k = 1, n
      call move_alloc(seen(k)%s, labels(k)%s)
    end do
  end subroutine fix_boundaries

  !> Every number about to be written must be finite: loads near the top of
  !> the accepted range can overflow in the post-processing (energy, stresses)
  !> even when the displacement did not.  Numerical failure, exit 1, nothing
  !> written.
  subroutine check_finite_results(run, res)
    type(run_t), intent(in) :: run
    type(results_t), intent(inout) :: res
    logical :: ok
    ok = ieee_is_finite(res%energy) .and. all(ieee_is_finite(res%reaction)) .and. all(ieee_is_finite(res%spring_force)) .and. &
         ieee_is_finite(res%complementarity)
    if (run%deck%output%fields(4) .or. run%deck%output%fields(5)) &
      ok = ok .and. all(ieee_is_finite(res%stress)) .and. all(ieee_is_finite(res%vm))
    if (allocated(res%gap)) ok = ok .and. all(ieee_is_finite(res%gap)) .and. all(ieee_is_finite(res%pressure))
    if (.not. ok) call fail_numerical('the results overflow (stresses, reactions, energy or contact quantities ' // &
      'are not finite): the loads or prescribed values are out of the range of double precision arithmetic')
  end subroutine check_finite_results

end module post_processing
