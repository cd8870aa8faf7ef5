!> linear_system: the run's linear algebra with K_ff: its pattern, values and
!> right-hand side, the fill-reducing ordering, the factorization, u0 = K^-1 f
!> and the condensation onto the contact rows, the solves of a load step or
!> of a ramp, and the recovery of u from the contact multipliers.
!>
!> Why it exists: the program says "assemble, factorize, condense, recover"
!> in one call each; the overlap of the ordering with the assembly (an
!> OpenMP region of two threads), the timing of the solves and the location
!> of a singular equation in the mesh stay here, out of the method's story.
!> Who may use it: the program and its step modules (run_state's list).  A
!> failure ends the run (exit 1 with the diagnosis), as the program would.
!>
!> Programming interface
!>   assemble_system(run)      K_ff, f_f - K_fd ubar, and the ordering of K's pattern beside it
!>   factorize_system(run)     K_ff = L L'
!>   condense_system(run)      u0 (or its forward half), W, q (contact_condensation), C u0 per ramp
!>   recover_system(run)       u from the multipliers and the rigid motions
!>   solve_loads(run, f, ubar, z, u)   u = K^-1 (f - K_fd ubar - C' z), one load step
module linear_system
  use kinds, only: dp, i8
  use strings, only: int_to_str, real_to_str
  use errors, only: error_t
  use exits, only: fail_numerical
  use run_state, only: run_t, ph_assemble, ph_factor, ph_condense, ph_recover
  use run_report, only: lap, split_overlap
  use load_groups, only: group_factor
  use mesh, only: node_in_file
  use material, only: tensor_condition
  use body, only: build_pattern, assemble_stiffness, internal_forces
  use sparse_cholesky, only: analyze_pattern, factorize_values, solve, solve_forward, factor_nnz, factor_memory, &
                             factor_ordering
  use contact_condensation, only: contact_equations, condense, contact_forces, recover, constraint_values, &
                                  condensed_blocks
  use rigid_modes, only: remove_motions
  use omp_lib, only: omp_get_thread_num, omp_get_num_threads
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use run_phase, only: enter_phase
  implicit none
  private
  public :: assemble_system, factorize_system, condense_system, recover_system, solve_loads

  ! ordering=auto: AMD up to this many free dofs, METIS nested dissection
  ! above (the crossover of bench/ordering.sh, doc/performance.md)
  integer, parameter :: amd_max_free = 500000

contains

  !> K_ff and its right-hand side f_f - K_fd ubar, and the fill-reducing
  !> ordering of K's pattern (contact dofs last).  The ordering reads only the
  !> pattern: it runs on one thread while the values are assembled on
  !> another (AMD, METIS and CHOLMOD allocate: the main malloc arena; the
  !> assembly allocates nothing per element).  A scene of several bodies
  !> orders them side by side on a nested team (sparse_cholesky's parts).
  !>   run (inout) scene, eq, nfree on entry; k, rhs, last, group, the factor's analysis on exit
  subroutine assemble_system(run)
    type(run_t), intent(inout) :: run
    type(error_t), allocatable :: err, err_order
    integer :: i
    call enter_phase('assembling K')
    if (run%nfree == 0) call fail_numerical('every dof is fixed: there is nothing to solve')
    call build_pattern(run%sc%bodies, run%eq, run%nfree, run%k, err)
    if (allocated(err)) call fail_numerical(err%message)
    allocate(run%rhs(run%nfree, 1))
    run%rhs = 0.0_dp
    do i = 1, run%sc%ndof
      if (run%eq(i) > 0) run%rhs(run%eq(i), 1) = run%sc%fext(i)
    end do
    call contact_equations(run%cs, run%eq, run%last)
    call node_groups(run%eq, run%nfree, run%group)
    run%ordering = run%deck%solver%ordering
    if (run%ordering == 'auto') run%ordering = merge('amd  ', 'metis', run%nfree <= amd_max_free)
    call lap(run, ph_assemble)
    !$omp parallel
    if (omp_get_thread_num() == 0) call order_pattern(run, err_order)
    if (omp_get_thread_num() == 1 .or. omp_get_num_threads() == 1) call assemble_values(run)
    !$omp end parallel
    call split_overlap(run)
    if (allocated(err_order)) call fail_numerical(err_order%message)
    if (run%overflow_body > 0) call fail_numerical('body "' // run%sc%bodies(run%overflow_body)%name // &
      '": its prescribed displacements times its stiffness leave the range of double precision (expected ' // &
      'moduli and prescribed values whose product stays below about 1e308)')
  end subroutine assemble_system

  !> K_ff = L L' (numeric factorization on the analysis of assemble_system);
  !> K itself is freed, it lives on in its factor only.  A singular K ends
  !> the run with the dof it names located in the mesh.
  !>   run (inout) k on entry; factor and its figures in res on exit
  subroutine factorize_system(run)
    type(run_t), intent(inout) :: run
    type(error_t), allocatable :: err
    call enter_phase('factorizing K')
    call factorize_values(run%factor, run%k, err)
    if (allocated(err)) call fail_numerical(factor_failure(run, err))
    run%res%factor_nnz = factor_nnz(run%factor)
    run%res%ordering = factor_ordering(run%factor)
    run%res%factor_memory = real(factor_memory(run%factor), dp)
    deallocate(run%k%colptr, run%k%rowind, run%k%val)
    call lap(run, ph_factor)
  end subroutine factorize_system

  !> u0 = K^-1 f and, with contact, the condensed problem W = C K^-1 C',
  !> q = g - C u0 (contact_condensation) and with friction C u0 of each ramp.
  !> With contact only the forward half y = L^-1 P f of u0's solve is done
  !> here: condense takes u0 on the contact dofs from y, and the recovery
  !> ends the solve (one forward and one backward substitution in all,
  !> time_solve).  The forward solve counts as condensation when there is
  !> contact, as recovery otherwise: a scene without contact spends nothing
  !> on it.
  !>   run (inout) factor, rhs on entry; u0, y, w, q, cd, cu0, fc on exit (rhs freed)
  subroutine condense_system(run)
    type(run_t), intent(inout) :: run
    type(error_t), allocatable :: err
    real(dp), allocatable :: x(:,:)
    integer(i8) :: t_solve, t_now, t_rate
    integer :: i
    call enter_phase('condensing the contact problem')
    allocate(run%u0(run%sc%ndof))
    run%u0 = run%sc%ubar
    run%with_contact = run%cs%nrow > 0 .or. run%fl%k > 0 .or. run%rsplit%k > 0
    call system_clock(t_solve)
    if (run%with_contact) then
      allocate(run%y(run%nfree))
      call solve_forward(run%factor, run%rhs(:, 1), run%y, err)
      if (allocated(err)) call fail_numerical(err%message)
    else
      allocate(x(run%nfree, 1))
      call solve(run%factor, run%rhs, x, err)
      if (allocated(err)) call fail_numerical(err%message)
      do i = 1, run%sc%ndof
        if (run%eq(i) > 0) run%u0(i) = x(run%eq(i), 1)
      end do
    end if
    call system_clock(t_now, t_rate)
    run%res%time_solve = real(t_now - t_solve, dp) / real(t_rate, dp)
    deallocate(run%rhs)
    allocate(run%fc(run%sc%ndof))
    run%fc = 0.0_dp
    run%res%lcp_method = 'none'
    if (.not. run%with_contact) return
    call condense(run%cs, run%eq, run%factor, run%y, run%u0, run%w, run%q, run%cd, err, run%deck%solver%condense)
    if (allocated(err)) call fail_numerical(err%message)
    run%res%condense_block = condensed_blocks(run%cd)
    if (run%cs%ntan > 0) call friction_load_paths(run)
    call lap(run, ph_condense)
  end subroutine condense_system

  !> u = K^-1 (f - C' z) from the multipliers (the backward half of the
  !> solve with y), plus the free rigid modes' motion R alpha and the
  !> RIGIDs' free motion; no component along the modes nothing holds.  W and
  !> q are freed first: a lower peak.  Without contact u = u0.
  !>   run (inout) the multipliers in res on entry; res%u and fc on exit
  subroutine recover_system(run)
    type(run_t), intent(inout) :: run
    type(error_t), allocatable :: err
    integer(i8) :: t_solve, t_now, t_rate
    call enter_phase('recovering the displacements')
    if (run%with_contact) then
      deallocate(run%w, run%q)
      allocate(run%res%u(run%sc%ndof))
      call system_clock(t_solve)
      if (run%cs%ntan > 0) then
        call recover(run%eq, run%factor, run%y, run%cd, run%u0, [run%res%mu, run%res%tau], run%res%u, err)
        call contact_forces(run%cs, [run%res%mu, run%res%tau], run%fc)
      else
        call recover(run%eq, run%factor, run%y, run%cd, run%u0, run%res%mu, run%res%u, err)
        call contact_forces(run%cs, run%res%mu, run%fc)
      end if
      if (allocated(err)) call fail_numerical(err%message)
      call system_clock(t_now, t_rate)
      run%res%time_solve = run%res%time_solve + real(t_now - t_solve, dp) / real(t_rate, dp)
      if (run%fl%k > 0) run%res%u = run%res%u + matmul(run%fl%r, run%res%alpha)   ! + R alpha: the free rigid modes
      call remove_motions(run%fl, run%split%unheld, run%res%u)                   ! none along the unheld ones
      if (allocated(run%rigid_alpha)) run%res%u(run%rsplit%dof) = run%rigid_alpha  ! the RIGIDs' free motion
    else
      run%res%u = run%u0
    end if
    if (.not. all(ieee_is_finite(run%res%u))) call fail_numerical('the displacement is not finite (overflow in the solve)')
    call lap(run, ph_recover)
  end subroutine recover_system

  !> u = K^-1 (f - K_fd ubar - C' z) on the free dofs, ubar on the fixed ones
  !> (one solve with the factorization).
  !>   fk, ubk (in) (ndof) loads and prescribed values;  z (in) multipliers (may be empty)
  !>   u (out) (ndof)
  subroutine solve_loads(run, fk, ubk, z, u)
    type(run_t), intent(inout) :: run
    real(dp), intent(in) :: fk(:), ubk(:), z(:)
    real(dp), intent(out) :: u(:)
    real(dp), allocatable :: kub(:), fz(:), b(:,:), xb(:,:)
    type(error_t), allocatable :: err
    integer :: j
    allocate(kub(run%sc%ndof), fz(run%sc%ndof), b(run%nfree, 1), xb(run%nfree, 1))
    call internal_forces(run%sc%bodies, ubk, kub)      ! its free rows are K_fd ubar
    fz = 0.0_dp
    if (size(z) > 0) call contact_forces(run%cs, z, fz)
    do j = 1, run%sc%ndof
      if (run%eq(j) > 0) b(run%eq(j), 1) = fk(j) - kub(j) + fz(j)
    end do
    call solve(run%factor, b, xb, err)
    if (allocated(err)) call fail_numerical(err%message)
    u = ubk
    do j = 1, run%sc%ndof
      if (run%eq(j) > 0) u(j) = xb(run%eq(j), 1)
    end do
  end subroutine solve_loads

  !> C u0_g for each ramp g of the load history (one solve per ramp, none when
  !> the deck has one ramp: then C u0 is the load path times the factor).
  subroutine friction_load_paths(run)
    type(run_t), intent(inout) :: run
    integer :: g, j
    real(dp), allocatable :: rhsg(:,:), xg(:,:), ug(:), fk(:)
    type(error_t), allocatable :: err
    allocate(run%cu0(run%cs%nrow + run%cs%ntan, size(run%sc%ramp, 2)))
    if (size(run%sc%ramp, 2) == 1 .and. group_factor(run%sc, 1, run%sc%steps) == 1.0_dp) then
      call constraint_values(run%cs, run%u0, run%cu0(:, 1))
      return
    end if
    allocate(rhsg(run%nfree, 1), xg(run%nfree, 1), ug(run%sc%ndof), fk(run%sc%ndof))
    do g = 1, size(run%sc%ramp, 2)
      call internal_forces(run%sc%bodies, run%sc%ugroup(:, g), fk)        ! K ubar_g: its free rows are K_fd ubar_g
      do j = 1, run%sc%ndof
        if (run%eq(j) > 0) rhsg(run%eq(j), 1) = run%sc%fgroup(j, g) - fk(j)
      end do
      call solve(run%factor, rhsg, xg, err)
      if (allocated(err)) call fail_numerical(err%message)
      ug = run%sc%ugroup(:, g)
      do j = 1, run%sc%ndof
        if (run%eq(j) > 0) ug(j) = xg(run%eq(j), 1)
      end do
      call constraint_values(run%cs, ug, run%cu0(:, g))
    end do
  end subroutine friction_load_paths

  !> The mesh node of each free equation, numbered 1, 2, ... in order of
  !> first appearance: METIS orders the graph of the nodes.
  subroutine node_groups(eq, nfree, group)
    integer, intent(in) :: eq(:), nfree
    integer, allocatable, intent(out) :: group(:)
    integer :: d, ng, last_node
    allocate(group(nfree))
    ng = 0
    last_node = 0
    do d = 1, size(eq)                      ! dofs 2a-1, 2a of node a are adjacent
      if (eq(d) == 0) cycle
      if ((d + 1) / 2 /= last_node) then
        ng = ng + 1
        last_node = (d + 1) / 2
      end if
      group(eq(d)) = ng
    end do
  end subroutine node_groups

  !> The fill-reducing ordering and symbolic analysis of K's pattern (the
  !> contact dofs last).
  subroutine order_pattern(run, err_order)
    type(run_t), intent(inout) :: run
    type(error_t), allocatable, intent(out) :: err_order
    if (size(run%last) > 0) then
      call analyze_pattern(run%factor, run%k%n, run%k%colptr, run%k%rowind, err_order, &
                          last=run%last, group=run%group, method=trim(run%ordering))
    else
      call analyze_pattern(run%factor, run%k%n, run%k%colptr, run%k%rowind, err_order, &
                          group=run%group, method=trim(run%ordering))
    end if
  end subroutine order_pattern

  !> The values of K and the right-hand side, timed (time_assemble_values).
  subroutine assemble_values(run)
    type(run_t), intent(inout) :: run
    call system_clock(run%t_asm0)
    call assemble_stiffness(run%sc%bodies, run%eq, run%sc%ubar, run%k, run%rhs(:, 1), run%overflow_body)
    call system_clock(run%t_asm1)
  end subroutine assemble_values

  !> The factorization's message, with the dof it names located in the mesh.
  !> A singular K from a body whose law is nearly incompressible (nu close to
  !> 0.5 in plane strain) is said so instead: the dependent column is then
  !> round-off, not a rigid-body mode.
  function factor_failure(run, e) result(text)
    type(run_t), intent(in) :: run
    type(error_t), intent(in) :: e
    character(len=:), allocatable :: text
    integer :: b
    text = e%message // equation_location(run, e%equation)
    if (.not. e%singular) return
    do b = 1, size(run%sc%bodies)
      ! beyond 1e12, K keeps fewer than 4 digits of u = 1.1e-16
      if (tensor_condition(run%sc%bodies(b)%law) > 1.0e12_dp) then
        text = 'stiffness matrix is singular to working precision: body "' // run%sc%bodies(b)%name // &
          '" is nearly incompressible (its elasticity tensor has condition number ' // &
          real_to_str(tensor_condition(run%sc%bodies(b)%law)) // ', nu too close to 0.5; expected a Poisson ratio ' // &
          'that leaves 1 - 2 nu well above the round-off, such as nu <= 0.4999)'
        return
      end if
    end do
  end function factor_failure

  !> '; that is body NAME, node N at (x, y), component u_x' for free
  !> equation eqn (an error's equation field); '' for 0 (none).
  function equation_location(run, eqn) result(where)
    type(run_t), intent(in) :: run
    integer, intent(in) :: eqn
    character(len=:), allocatable :: where
    integer :: d, b, node
    character(len=64) :: buf
    where = ''
    if (eqn <= 0) return
    do d = 1, size(run%eq)
      if (run%eq(d) /= eqn) cycle
      do b = size(run%sc%bodies), 1, -1
        if (d > run%sc%bodies(b)%dof0) exit
      end do
      node = (d - run%sc%bodies(b)%dof0 + 1) / 2
      write(buf, '(a,es11.4,a,es11.4,a)') ' at (', run%sc%bodies(b)%mesh%x(1, node), ',', run%sc%bodies(b)%mesh%x(2, node), ')'
      where = '; that is body "' // run%sc%bodies(b)%name // '", node ' // &
        int_to_str(node_in_file(run%sc%bodies(b)%mesh, node)) // &
              trim(buf) // &
              ', component ' // merge('u_x', 'u_y', mod(d - run%sc%bodies(b)%dof0, 2) == 1)
      return
    end do
  end function equation_location

end module linear_system
