!> linear_system: the operations on K_ff, each written once: its pattern,
!> values and right-hand side, the fill-reducing ordering, the
!> factorization, u0 = K^-1 f and the condensation onto the contact rows,
!> the solves of a load step or of a ramp, and the recovery of u from the
!> contact multipliers and the free motions.
!>
!> Why it exists: the solve layer says "assemble, factorize, condense,
!> recover" in one call each; the overlap of the ordering with the assembly
!> (an OpenMP region of two threads), the timing of the solves and the
!> location of a singular equation in the mesh stay here, out of the method's
!> story.  Nothing here stops the run: every failure returns an error_t.
!>
!> Programming interface
!>   type(system_t)            K_ff until factorized, the factor, u0, W, q, the condensed blocks
!>   assemble_system(prob, sys, log, err)    K_ff, f_f - K_fd ubar, the ordering beside them
!>   factorize_system(prob, sys, log, err)   K_ff = L L'
!>   condense_system(prob, sys, log, err)    u0 (or its forward half), W, q, C u0 per ramp
!>   condense_rows(prob, sys, err)           W and q again on the current rows (sliding=finite)
!>   solve_loads(prob, sys, f, ubar, z, u, err)   u = K^-1 (f - K_fd ubar - C' z), one load step
!>   add_free_motions(prob, sol, u)          u += R alpha, none along the unheld modes, the RIGIDs' motion
!>   recover_solution(prob, sys, sol, u, err)  the final step's u from its multipliers and free motions
!>   step_displacement(prob, sys, f, ubar, sol, u, err)  an earlier step's u, likewise
module linear_system
  use kinds, only: dp, i8
  use strings, only: int_to_str, real_to_str
  use errors, only: error_t, set_error
  use run_log, only: log_t, lap, lap_shared, clock_seconds, ph_assemble, ph_factor, ph_condense, ph_recover
  use run_phase, only: enter_phase
  use problem, only: problem_t
  use step_solution, only: step_solution_t, multipliers
  use load_groups, only: group_factor
  use mesh, only: node_in_file
  use material, only: tensor_condition
  use body, only: build_pattern, assemble_stiffness, internal_forces
  use sparse_matrix, only: csc_t
  use sparse_cholesky, only: factor_t, analyze_pattern, factorize_values, solve, solve_forward
  use contact_condensation, only: condensed_t, contact_equations, condense, contact_forces, recover, &
                                  constraint_values, condensed_blocks
  use rigid_modes, only: remove_motions
  use omp_lib, only: omp_get_thread_num, omp_get_num_threads
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  implicit none
  private
  public :: system_t, assemble_system, factorize_system, condense_system, condense_rows, solve_loads
  public :: add_free_motions, recover_solution, step_displacement

  ! ordering=auto: AMD up to this many free dofs, METIS nested dissection
  ! above (the crossover of bench/ordering.sh, doc/performance.md)
  integer, parameter :: amd_max_free = 500000

  type :: system_t
    type(csc_t) :: k                               !< K_ff until it is factorized
    real(dp), allocatable :: rhs(:,:)              !< (nfree, 1) f_f - K_fd ubar, until u0 is solved
    integer, allocatable :: last(:)                !< the contact equations, ordered last
    integer, allocatable :: group(:)               !< (nfree) the mesh node of each equation (METIS's graph)
    character(len=5) :: ordering = 'auto'          !< 'metis' or 'amd' (SOLVER ordering=, auto resolved)
    type(factor_t) :: factor                       !< K_ff = L L' (contact dofs last)
    logical :: with_contact = .false.              !< contact rows, free modes or free RIGID directions
    real(dp), allocatable :: u0(:)                 !< (ndof) K^-1 f without contact forces (ubar on fixed dofs)
    real(dp), allocatable :: y(:)                  !< (nfree) forward half of u0's solve, L^-1 P f
    real(dp), allocatable :: w(:,:)                !< (nrow + ntan, nrow + ntan) W = C K^-1 C' of the current rows
    real(dp), allocatable :: q(:)                  !< (nrow + ntan) q = g - C u0 of the current rows
    type(condensed_t) :: cd                        !< X_b = L_b^-1 C_b' or L_b per block of L_cc
    integer, allocatable :: blocks(:,:)            !< (3, blocks) the first condensation's blocks (summary condense_block)
    real(dp), allocatable :: cu0(:,:)              !< (nrow + ntan, ramps) C u0 of each ramp's loads (friction)
    real(dp) :: time_solve = 0                     !< seconds of the one solve u0 = K^-1 f (inside a phase)
    real(dp) :: time_ordering = 0                  !< seconds of the ordering and analysis (inside factor)
    real(dp) :: time_assemble_values = 0           !< seconds of the assembly of K's values, beside the ordering
  end type system_t

contains

  !> K_ff and its right-hand side f_f - K_fd ubar, and the fill-reducing
  !> ordering of K's pattern (contact dofs last).  The ordering reads only the
  !> pattern: it runs on one thread while the values are assembled on
  !> another (AMD, METIS and CHOLMOD allocate: the main malloc arena; the
  !> assembly allocates nothing per element).  A scene of several bodies
  !> orders them side by side on a nested team (sparse_cholesky's parts).
  !>   prob (in)    scene, eq, nfree, cs, the deck's SOLVER ordering=
  !>   sys  (out)   k, rhs, last, group, the factor's analysis
  !>   log  (inout) the clock: assemble and factor (the ordering's share)
  !>   err  (out)   every dof fixed, a pattern or ordering failure, an overflow
  subroutine assemble_system(prob, sys, log, err)
    type(problem_t), intent(in) :: prob
    type(system_t), intent(out) :: sys
    type(log_t), intent(inout) :: log
    type(error_t), allocatable, intent(out) :: err
    type(error_t), allocatable :: err_order
    integer(i8) :: t_asm0, t_asm1, rate
    integer :: i, overflow_body
    call enter_phase('assembling K')
    if (prob%nfree == 0) then
      call set_error(err, 'every dof is fixed: there is nothing to solve')
      return
    end if
    call build_pattern(prob%sc%bodies, prob%eq, prob%nfree, sys%k, err)
    if (allocated(err)) return
    allocate(sys%rhs(prob%nfree, 1))
    sys%rhs = 0.0_dp
    do i = 1, prob%sc%ndof
      if (prob%eq(i) > 0) sys%rhs(prob%eq(i), 1) = prob%sc%fext(i)
    end do
    call contact_equations(prob%cs, prob%eq, sys%last)
    call node_groups(prob%eq, prob%nfree, sys%group)
    sys%ordering = prob%deck%solver%ordering
    if (sys%ordering == 'auto') sys%ordering = merge('amd  ', 'metis', prob%nfree <= amd_max_free)
    call lap(log, ph_assemble)
    overflow_body = 0
    !$omp parallel
    if (omp_get_thread_num() == 0) call order_pattern(sys, err_order)
    if (omp_get_thread_num() == 1 .or. omp_get_num_threads() == 1) then
      call system_clock(t_asm0)
      call assemble_stiffness(prob%sc%bodies, prob%eq, prob%sc%ubar, sys%k, sys%rhs(:, 1), overflow_body)
      call system_clock(t_asm1)
    end if
    !$omp end parallel
    call system_clock(count_rate=rate)
    sys%time_assemble_values = real(t_asm1 - t_asm0, dp) / real(rate, dp)
    call charge_overlap(sys, log)
    if (allocated(err_order)) then
      call move_alloc(err_order, err)
      return
    end if
    if (overflow_body > 0) call set_error(err, 'body "' // prob%sc%bodies(overflow_body)%name // &
      '": its prescribed displacements times its stiffness leave the range of double precision (expected ' // &
      'moduli and prescribed values whose product stays below about 1e308)')
  end subroutine assemble_system

  !> The ordering and the assembly of the values ran side by side: the
  !> ordering is charged to factor, the part of the assembly it did not hide
  !> to assemble, so that the phases still add up to the total.
  subroutine charge_overlap(sys, log)
    type(system_t), intent(inout) :: sys
    type(log_t), intent(inout) :: log
    real(dp) :: wall
    wall = clock_seconds(log)
    sys%time_ordering = min(wall, sys%factor%time_analyze)
    if (wall > 0.0_dp) then
      call lap_shared(log, [ph_factor, ph_assemble], [sys%time_ordering, wall - sys%time_ordering] / wall)
    else
      call lap(log, ph_factor)
    end if
  end subroutine charge_overlap

  !> K_ff = L L' (numeric factorization on the analysis of assemble_system);
  !> K itself is freed, it lives on in its factor only.  A singular K
  !> returns the dof it names located in the mesh.
  !>   sys (inout) k on entry; factor on exit
  subroutine factorize_system(prob, sys, log, err)
    type(problem_t), intent(in) :: prob
    type(system_t), intent(inout) :: sys
    type(log_t), intent(inout) :: log
    type(error_t), allocatable, intent(out) :: err
    call enter_phase('factorizing K')
    call factorize_values(sys%factor, sys%k, err)
    if (allocated(err)) then
      err%message = factor_failure(prob, err)
      return
    end if
    deallocate(sys%k%colptr, sys%k%rowind, sys%k%val)
    call lap(log, ph_factor)
  end subroutine factorize_system

  !> u0 = K^-1 f and, with contact, the condensed problem W = C K^-1 C',
  !> q = g - C u0 (contact_condensation) and with friction C u0 of each ramp.
  !> With contact only the forward half y = L^-1 P f of u0's solve is done
  !> here: condense takes u0 on the contact dofs from y, and the recovery
  !> ends the solve (one forward and one backward substitution in all,
  !> time_solve).  The forward solve counts as condensation when there is
  !> contact, as recovery otherwise: a scene without contact spends nothing
  !> on it.
  !>   sys (inout) factor, rhs on entry; u0, y, w, q, cd, cu0 on exit (rhs freed)
  subroutine condense_system(prob, sys, log, err)
    type(problem_t), intent(in) :: prob
    type(system_t), intent(inout) :: sys
    type(log_t), intent(inout) :: log
    type(error_t), allocatable, intent(out) :: err
    real(dp), allocatable :: x(:,:)
    integer(i8) :: t_solve, t_now, t_rate
    integer :: i
    call enter_phase('condensing the contact problem')
    allocate(sys%u0(prob%sc%ndof))
    sys%u0 = prob%sc%ubar
    sys%with_contact = prob%cs%nrow > 0 .or. prob%fl%k > 0 .or. prob%rsplit%k > 0
    call system_clock(t_solve)
    if (sys%with_contact) then
      allocate(sys%y(prob%nfree))
      call solve_forward(sys%factor, sys%rhs(:, 1), sys%y, err)
      if (allocated(err)) return
    else
      allocate(x(prob%nfree, 1))
      call solve(sys%factor, sys%rhs, x, err)
      if (allocated(err)) return
      do i = 1, prob%sc%ndof
        if (prob%eq(i) > 0) sys%u0(i) = x(prob%eq(i), 1)
      end do
    end if
    call system_clock(t_now, t_rate)
    sys%time_solve = real(t_now - t_solve, dp) / real(t_rate, dp)
    deallocate(sys%rhs)
    if (.not. sys%with_contact) return
    call condense_rows(prob, sys, err)
    if (allocated(err)) return
    sys%blocks = condensed_blocks(sys%cd)
    if (prob%cs%ntan > 0) call friction_load_paths(prob, sys, err)
    if (allocated(err)) return
    call lap(log, ph_condense)
  end subroutine condense_system

  !> W = C K^-1 C' and q = g - C u0 on the current rows, on the factor
  !> already had (the contact dofs of a finite pair never change:
  !> contact_set marks every node of its boundaries).
  !>   sys (inout) factor, y, u0 on entry; w, q, cd on exit
  subroutine condense_rows(prob, sys, err)
    type(problem_t), intent(in) :: prob
    type(system_t), intent(inout) :: sys
    type(error_t), allocatable, intent(out) :: err
    call condense(prob%cs, prob%eq, sys%factor, sys%y, sys%u0, sys%w, sys%q, sys%cd, err, prob%deck%solver%condense)
  end subroutine condense_rows

  !> u = K^-1 (f - K_fd ubar - C' z) on the free dofs, ubar on the fixed ones
  !> (one solve with the factorization).
  !>   fk, ubk (in) (ndof) loads and prescribed values;  z (in) multipliers (may be empty)
  !>   u (out) (ndof)
  subroutine solve_loads(prob, sys, fk, ubk, z, u, err)
    type(problem_t), intent(in) :: prob
    type(system_t), intent(in) :: sys
    real(dp), intent(in) :: fk(:), ubk(:), z(:)
    real(dp), intent(out) :: u(:)
    type(error_t), allocatable, intent(out) :: err
    real(dp), allocatable :: kub(:), fz(:), b(:,:), xb(:,:)
    integer :: j
    allocate(kub(prob%sc%ndof), fz(prob%sc%ndof), b(prob%nfree, 1), xb(prob%nfree, 1))
    call internal_forces(prob%sc%bodies, ubk, kub)      ! its free rows are K_fd ubar
    fz = 0.0_dp
    if (size(z) > 0) call contact_forces(prob%cs, z, fz)
    do j = 1, prob%sc%ndof
      if (prob%eq(j) > 0) b(prob%eq(j), 1) = fk(j) - kub(j) + fz(j)
    end do
    u = ubk
    call solve(sys%factor, b, xb, err)
    if (allocated(err)) return
    do j = 1, prob%sc%ndof
      if (prob%eq(j) > 0) u(j) = xb(prob%eq(j), 1)
    end do
  end subroutine solve_loads

  !> The free motions of a solved step added to a displacement: R alpha of
  !> the bodies' free modes, no component along the modes the step did not
  !> hold, the RIGIDs' free motion on their dofs.
  !>   sol (in)    the step's alpha, split and rigid_alpha
  !>   u   (inout) (ndof) K^-1 (f - C'z) on entry; u on exit
  subroutine add_free_motions(prob, sol, u)
    type(problem_t), intent(in) :: prob
    type(step_solution_t), intent(in) :: sol
    real(dp), intent(inout) :: u(:)
    if (prob%fl%k > 0) u = u + matmul(prob%fl%r, sol%alpha)          ! + R alpha: the free rigid modes
    call remove_motions(prob%fl, sol%split%unheld, u)                  ! none along the unheld ones
    if (allocated(sol%rigid_alpha)) u(prob%rsplit%dof) = sol%rigid_alpha  ! the RIGIDs' free motion
  end subroutine add_free_motions

  !> u of the final step, u = K^-1 (f - C' z) by the backward half of u0's
  !> solve (y, the condensed blocks), plus the free motions.  W and q are
  !> freed first: a lower peak.  Without contact u = u0.
  !>   sol (in)  the final step's multipliers and free motions
  !>   u   (out) (ndof)
  subroutine recover_solution(prob, sys, sol, log, u, err)
    type(problem_t), intent(in) :: prob
    type(system_t), intent(inout) :: sys
    type(step_solution_t), intent(in) :: sol
    type(log_t), intent(inout) :: log
    real(dp), allocatable, intent(out) :: u(:)
    type(error_t), allocatable, intent(out) :: err
    integer(i8) :: t_solve, t_now, t_rate
    call enter_phase('recovering the displacements')
    if (allocated(sol%u)) then                        ! the solve gave it whole (finite strain)
      u = sol%u
      if (allocated(sys%w)) deallocate(sys%w)
      if (allocated(sys%q)) deallocate(sys%q)
    else if (sys%with_contact) then
      deallocate(sys%w, sys%q)
      allocate(u(prob%sc%ndof))
      call system_clock(t_solve)
      call recover(prob%eq, sys%factor, sys%y, sys%cd, sys%u0, multipliers(sol), u, err)
      if (allocated(err)) return
      call system_clock(t_now, t_rate)
      sys%time_solve = sys%time_solve + real(t_now - t_solve, dp) / real(t_rate, dp)
      call add_free_motions(prob, sol, u)
    else
      u = sys%u0
    end if
    if (.not. all(ieee_is_finite(u))) then
      call set_error(err, 'the displacement is not finite (overflow in the solve)')
      return
    end if
    call lap(log, ph_recover)
  end subroutine recover_solution

  !> u of a load step other than the final one: one solve with its loads
  !> and multipliers, plus its free motions.
  !>   fk, ubk (in) (ndof) the step's loads and prescribed values
  !>   sol     (in) the step's multipliers and free motions
  !>   u       (out) (ndof)
  subroutine step_displacement(prob, sys, fk, ubk, sol, u, err)
    type(problem_t), intent(in) :: prob
    type(system_t), intent(in) :: sys
    real(dp), intent(in) :: fk(:), ubk(:)
    type(step_solution_t), intent(in) :: sol
    real(dp), allocatable, intent(out) :: u(:)
    type(error_t), allocatable, intent(out) :: err
    if (allocated(sol%u)) then                        ! the solve gave it whole (finite strain)
      u = sol%u
      return
    end if
    allocate(u(prob%sc%ndof))
    if (allocated(sol%mu)) then
      call solve_loads(prob, sys, fk, ubk, multipliers(sol), u, err)
    else
      call solve_loads(prob, sys, fk, ubk, [real(dp) ::], u, err)
    end if
    if (allocated(err)) return
    if (allocated(sol%mu)) call add_free_motions(prob, sol, u)
    if (.not. all(ieee_is_finite(u))) call set_error(err, 'the displacement is not finite (overflow in the solve)')
  end subroutine step_displacement

  !> C u0_g for each ramp g of the load history (one solve per ramp, none when
  !> the deck has one ramp: then C u0 is the load path times the factor).
  subroutine friction_load_paths(prob, sys, err)
    type(problem_t), intent(in) :: prob
    type(system_t), intent(inout) :: sys
    type(error_t), allocatable, intent(out) :: err
    integer :: g, j
    real(dp), allocatable :: rhsg(:,:), xg(:,:), ug(:), fk(:)
    allocate(sys%cu0(prob%cs%nrow + prob%cs%ntan, size(prob%sc%ramp, 2)))
    if (size(prob%sc%ramp, 2) == 1 .and. group_factor(prob%sc, 1, real(prob%sc%steps, dp)) == 1.0_dp) then
      call constraint_values(prob%cs, sys%u0, sys%cu0(:, 1))
      return
    end if
    allocate(rhsg(prob%nfree, 1), xg(prob%nfree, 1), ug(prob%sc%ndof), fk(prob%sc%ndof))
    do g = 1, size(prob%sc%ramp, 2)
      call internal_forces(prob%sc%bodies, prob%sc%ugroup(:, g), fk)        ! K ubar_g: its free rows are K_fd ubar_g
      do j = 1, prob%sc%ndof
        if (prob%eq(j) > 0) rhsg(prob%eq(j), 1) = prob%sc%fgroup(j, g) - fk(j)
      end do
      call solve(sys%factor, rhsg, xg, err)
      if (allocated(err)) return
      ug = prob%sc%ugroup(:, g)
      do j = 1, prob%sc%ndof
        if (prob%eq(j) > 0) ug(j) = xg(prob%eq(j), 1)
      end do
      call constraint_values(prob%cs, ug, sys%cu0(:, g))
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
  subroutine order_pattern(sys, err_order)
    type(system_t), intent(inout) :: sys
    type(error_t), allocatable, intent(out) :: err_order
    if (size(sys%last) > 0) then
      call analyze_pattern(sys%factor, sys%k%n, sys%k%colptr, sys%k%rowind, err_order, &
                          last=sys%last, group=sys%group, method=trim(sys%ordering))
    else
      call analyze_pattern(sys%factor, sys%k%n, sys%k%colptr, sys%k%rowind, err_order, &
                          group=sys%group, method=trim(sys%ordering))
    end if
  end subroutine order_pattern

  !> The factorization's message, with the dof it names located in the mesh.
  !> A singular K from a body whose law is nearly incompressible (nu close to
  !> 0.5 in plane strain) is said so instead: the dependent column is then
  !> round-off, not a rigid-body mode.
  function factor_failure(prob, e) result(text)
    type(problem_t), intent(in) :: prob
    type(error_t), intent(in) :: e
    character(len=:), allocatable :: text
    integer :: b
    text = e%message // equation_location(prob, e%equation)
    if (.not. e%singular) return
    do b = 1, size(prob%sc%bodies)
      ! beyond 1e12, K keeps fewer than 4 digits of u = 1.1e-16
      if (tensor_condition(prob%sc%bodies(b)%law) > 1.0e12_dp) then
        text = 'stiffness matrix is singular to working precision: body "' // prob%sc%bodies(b)%name // &
          '" is nearly incompressible (its elasticity tensor has condition number ' // &
          real_to_str(tensor_condition(prob%sc%bodies(b)%law)) // ', nu too close to 0.5; expected a Poisson ratio ' // &
          'that leaves 1 - 2 nu well above the round-off, such as nu <= 0.4999)'
        return
      end if
    end do
  end function factor_failure

  !> '; that is body NAME, node N at (x, y), component u_x' for free
  !> equation eqn (an error's equation field); '' for 0 (none).
  function equation_location(prob, eqn) result(where)
    type(problem_t), intent(in) :: prob
    integer, intent(in) :: eqn
    character(len=:), allocatable :: where
    integer :: d, b, node
    character(len=64) :: buf
    where = ''
    if (eqn <= 0) return
    do d = 1, size(prob%eq)
      if (prob%eq(d) /= eqn) cycle
      do b = size(prob%sc%bodies), 1, -1
        if (d > prob%sc%bodies(b)%dof0) exit
      end do
      node = (d - prob%sc%bodies(b)%dof0 + 1) / 2
      write(buf, '(a,es11.4,a,es11.4,a)') ' at (', prob%sc%bodies(b)%mesh%x(1, node), ',', &
        prob%sc%bodies(b)%mesh%x(2, node), ')'
      where = '; that is body "' // prob%sc%bodies(b)%name // '", node ' // &
        int_to_str(node_in_file(prob%sc%bodies(b)%mesh, node)) // trim(buf) // &
        ', component ' // merge('u_x', 'u_y', mod(d - prob%sc%bodies(b)%dof0, 2) == 1)
      return
    end do
  end function equation_location

end module linear_system
