!> contact2d: unilateral (Signorini) contact between elastic bodies in 2D by
!> the mortar finite element method (Ben Belgacem, Hild, Laborde).
!>
!> The run reads like the algorithm:
!>   read the deck -> build the scene (meshes, laws, loads, contact pairs)
!>   -> assemble K_ff, f_f -> factorize (contact dofs last) -> u0 = K^-1 f
!>   -> condense the contact problem onto the slave nodes: W, q
!>   -> solve LCP(W, q) (Lemke or projected Gauss-Seidel) -> recover u
!>   -> stresses, reactions, energy -> VTK, contact table, summary.
program contact2d
  use kinds, only: dp, i8
  use diagnostics, only: diag_t, add_error, has_errors, stop_input_errors, fail_numerical, exit_program, error_t, &
                         int_to_str, real_to_str
  use deck_reader, only: deck_t, read_deck, path_too_long
  use deck_expressions, only: parameter_set_t, find_parameter, format_number
  use deck_cases, only: case_table_t, read_case_table, case_parameters, run_every_case
  use scene, only: scene_t, build_scene, group_factor, step_loads, group_name
  use mesh, only: node_in_file, is_quadratic
  use material, only: tensor_condition
  use body, only: number_equations, build_pattern, assemble_stiffness, element_response, internal_forces, &
                  to_global_axes
  use sparse_matrix, only: csc_t
  use sparse_cholesky, only: factor_t, analyze_pattern, factorize_values, solve, solve_forward, factor_nnz, factor_memory, &
                             factor_ordering
  use contact_set, only: contact_set_t, pair_spec_t, build_contact_set, row_of_node, node_rows, node_traction, has_friction
  use contact_condensation, only: contact_equations, condense, contact_forces, recover, constraint_values, &
                                  condensed_t, condensed_report, condensed_blocks
  use lcp_solvers, only: lcp_options_t, lcp_report_t
  use friction_lcp, only: solve_friction_lcp, friction_state
  use friction_modes, only: solve_friction_floating, no_equilibrium
  use contact_lcp, only: contact_solution_t, solve_contact
  use rigid_modes, only: floating_t, find_floating_modes, mode_name, motion_name, describe_motion, remove_motions
  use mode_support, only: mode_split_t, split_free_modes
  use rigid_support, only: rigid_split_t, split_rigid_modes, rigid_direction, pulled_rigid
  use results_writer, only: results_t, write_vtk, write_contact_csv, write_summary, write_pvd, write_step_table, &
                            phase_names, nphase, peak_memory
  use safe_files, only: make_folders, temporary_t, create_temporary, close_temporary, commit_temporaries, &
                        discard_temporaries
  use gmsh_runner, only: gmsh_options_t
  use local_axes, only: rotate_constraint_rows
  use, intrinsic :: iso_fortran_env, only: output_unit, error_unit
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use omp_lib, only: omp_get_thread_num, omp_get_num_threads
  use threads, only: start_threads, run_threads
  use command_line, only: version, parse_command_line, case_index, usage_error
  implicit none

  integer, parameter :: ph_mesh = 1, ph_assemble = 2, ph_factor = 3, ph_condense = 4, ph_lcp = 5, &
                        ph_recover = 6, ph_output = 7, ph_total = 8
  ! ordering=auto: AMD up to this many free dofs, METIS nested dissection
  ! above (the crossover of bench/ordering.sh, doc/performance.md)
  integer, parameter :: amd_max_free = 500000

  character(len=:), allocatable :: deck_path, outdir
  character(len=5) :: ordering              !< 'metis' or 'amd' (SOLVER ordering=, auto resolved)
  logical :: check_only, quiet
  type(gmsh_options_t) :: gmsh              !< --trust-geo, --gmsh-timeout
  type(parameter_set_t) :: overrides        !< -D name=value and the --cases row
  character(len=:), allocatable :: cases_path   !< --cases FILE.csv ('' when none)
  integer :: case_number                    !< --case N (0: none given)
  type(diag_t) :: diag
  type(deck_t) :: deck
  type(scene_t) :: sc
  type(contact_set_t) :: cs
  type(csc_t) :: k
  type(factor_t) :: factor
  type(results_t) :: res
  type(error_t), allocatable :: err, err_order
  integer :: overflow_body = 0              !< a body whose K_fd ubar_d leaves double precision (0: none)
  type(floating_t) :: fl
  type(mode_split_t) :: split            ! the free modes that contact holds, and those it does not
  type(rigid_split_t) :: rsplit          ! the RIGIDs' free directions: floating modes loaded by FORCE
  real(dp), allocatable :: rigid_alpha(:) ! (rsplit%k) their motion, from the contact problem
  integer, allocatable :: eq(:), last(:), group(:)
  logical, allocatable :: held(:)
  integer :: nfree, i, nlabel
  integer :: jobs                         !< -j N: threads of the run (0: OpenMP's default)
  character(len=:), allocatable :: thread_note   !< what a memory limit changed in the thread count ('' none)
  integer(i8) :: t_start, t_phase, t_solve, t_now, t_rate, t_asm0, t_asm1
  real(dp), allocatable :: rhs(:,:), x(:,:), u0(:), w(:,:), q(:), fint(:), fc(:)
  real(dp), allocatable :: y(:)           ! forward half of u0's solve
  type(condensed_t) :: cd                 ! X_b = L_b^-1 C_b' or L_b per block of L_cc (condense)
  logical :: with_contact
  real(dp), allocatable :: cu0(:,:)      ! (nrow + ntan, ramps) C u0 of each ramp's loads (friction)
  ! OUTPUT steps=all: a VTK file per step and a row per step of NAME_steps.csv
  type(temporary_t), allocatable :: step_tmp(:)   ! (steps) the per-step VTK files' temporaries
  real(dp), allocatable :: step_table(:,:)        ! (ncol, steps) the rows of NAME_steps.csv
  integer :: step_iterations = 0                  ! LCP iterations of the step being recorded
  character(len=:), allocatable :: step_note      ! 'load step k of n: ' in messages while steps are solved

  call parse_command_line(deck_path, outdir, check_only, quiet, gmsh, overrides, cases_path, case_number, jobs)
  call start_threads(jobs, thread_note, err)   ! threads, BLAS threads, malloc arenas: src/threads.f90
  if (allocated(err)) call fail_numerical(err%message)
  if (len(cases_path) > 0) call select_case()
  call system_clock(t_start)
  t_phase = t_start

  ! --- deck and scene ---------------------------------------------------
  call read_deck(deck_path, deck, diag, overrides)
  call check_overrides()
  call stop_input_errors(diag)
  if (.not. check_only) call make_folder(outdir, diag)
  call stop_input_errors(diag)
  call build_scene(deck, gmsh, sc, diag, err)
  call stop_input_errors(diag)
  if (allocated(err)) call fail_numerical(err%message)
  call build_contact_set(sc%bodies, sc%specs, cs, err)
  if (allocated(err)) call contact_error(err)
  call rotate_constraint_rows(cs, sc%bodies)     ! nodes in local axes (FIX un=/ut=)
  do i = 1, cs%npair
    if (cs%pair(i)%nrow == 0) write(error_unit, '(a)') 'contact2d: warning: ' // deck%file // ':' // &
      int_to_str(deck%contacts(i)%line) // ': no part of the master boundary faces the slave boundary: ' // &
      'this pair can never touch (check the boundary names and the slave/master choice)'
  end do
  ! free rigid modes (bodies held only by contact): pin k dofs to factorize K^#
  call find_floating_modes(sc%bodies, sc%fixed, fl)
  call check_floating_bodies()
  call split_free_modes(cs, sc%bodies, fl, sc%fext, split)
  call split_rigid_modes(cs, sc%rigids, sc%fixed, sc%fext, rsplit)
  call check_floating_friction_solver()
  held = sc%fixed
  if (fl%k > 0) held(fl%pin) = .true.
  held(rsplit%dof) = .true.                 ! a RIGID has no stiffness: its free dofs are modes, not equations
  call number_equations(held, eq, nfree)
  res%effects = sc%effects
  res%axisymmetric = deck%axisymmetric
  res%nfree = nfree
  call report_scene()
  if (check_only) then
    call say('check: the deck and its meshes are valid; nothing solved, nothing written')
    call exit_program(0)
  end if
  call check_unheld_loads()
  call check_unheld_rigid_loads()
  call lap(ph_mesh)

  ! --- assembly and factorization (contact dofs last) ----------------------
  ! The ordering (AMD or METIS) reads only the pattern: it runs on one core
  ! while the values are assembled on the other, then the numeric factorization.
  if (nfree == 0) call fail_numerical('every dof is fixed: there is nothing to solve')
  call build_pattern(sc%bodies, eq, nfree, k, err)
  if (allocated(err)) call fail_numerical(err%message)
  allocate(rhs(nfree, 1))
  rhs = 0.0_dp
  do i = 1, sc%ndof
    if (eq(i) > 0) rhs(eq(i), 1) = sc%fext(i)
  end do
  call contact_equations(cs, eq, last)
  call node_groups(eq, nfree, group)
  ordering = deck%solver%ordering
  if (ordering == 'auto') ordering = merge('amd  ', 'metis', nfree <= amd_max_free)
  call lap(ph_assemble)
  ! The ordering starts on the main thread (AMD, METIS and CHOLMOD allocate:
  ! the main malloc arena); a scene of several bodies orders them side by
  ! side on a nested team (sparse_cholesky's parts).  The assembly, which
  ! allocates nothing per element (elements' fixed-size work arrays), runs
  ! beside it.
  !$omp parallel
  if (omp_get_thread_num() == 0) call order_pattern()
  if (omp_get_thread_num() == 1 .or. omp_get_num_threads() == 1) call assemble_values()
  !$omp end parallel
  call split_overlap()
  if (allocated(err_order)) call fail_numerical(err_order%message)
  if (overflow_body > 0) call fail_numerical('body "' // sc%bodies(overflow_body)%name // '": its prescribed ' // &
    'displacements times its stiffness leave the range of double precision (expected moduli and prescribed ' // &
    'values whose product stays below about 1e308)')
  call factorize_values(factor, k, err)
  if (allocated(err)) call fail_numerical(factor_failure(err))
  res%factor_nnz = factor_nnz(factor)
  res%ordering = factor_ordering(factor)
  res%factor_memory = real(factor_memory(factor), dp)
  deallocate(k%colptr, k%rowind, k%val)      ! K lives on in its factor only
  call lap(ph_factor)

  ! --- u0 = K^-1 f: with contact, its forward half y = L^-1 P f only ---------
  ! (condense takes u0 on the contact dofs from y, and the recovery ends the
  ! solve: one forward and one backward substitution in all, time_solve)
  allocate(u0(sc%ndof))
  u0 = sc%ubar
  with_contact = cs%nrow > 0 .or. fl%k > 0 .or. rsplit%k > 0
  call system_clock(t_solve)
  if (with_contact) then
    allocate(y(nfree))
    call solve_forward(factor, rhs(:, 1), y, err)
    if (allocated(err)) call fail_numerical(err%message)
  else
    allocate(x(nfree, 1))
    call solve(factor, rhs, x, err)
    if (allocated(err)) call fail_numerical(err%message)
    do i = 1, sc%ndof
      if (eq(i) > 0) u0(i) = x(eq(i), 1)
    end do
  end if
  call system_clock(t_now, t_rate)
  res%time_solve = real(t_now - t_solve, dp) / real(t_rate, dp)
  deallocate(rhs)
  if (allocated(x)) deallocate(x)

  allocate(fc(sc%ndof))
  fc = 0.0_dp
  res%lcp_method = 'none'
  if (with_contact) then
    ! the forward solve counts as condensation when there is contact, as
    ! recovery otherwise: a scene without contact spends nothing on it
    call condense(cs, eq, factor, y, u0, w, q, cd, err, deck%solver%condense)
    if (allocated(err)) call fail_numerical(err%message)
    res%condense_block = condensed_blocks(cd)
    if (cs%ntan > 0) then
      call friction_load_paths()
      call lap(ph_condense)
      call solve_friction_steps()
    else
      call lap(ph_condense)
      if (deck%output%steps_all) call solve_earlier_steps()
      call solve_contact_problem()
      step_iterations = res%lcp_iterations
      if (deck%output%steps_all) then
        call contact_measures()
        call say_step(sc%steps, res%lcp_method, step_iterations, res%active_nodes)
        deallocate(res%pressure, res%status)         ! measured again below, as without steps
      end if
    end if
    call contact_measures()
    call lap(ph_lcp)
    deallocate(w, q)                       ! before the recovery: a lower peak
    allocate(res%u(sc%ndof))
    call system_clock(t_solve)
    if (cs%ntan > 0) then
      call recover(eq, factor, y, cd, u0, [res%mu, res%tau], res%u, err)
      call contact_forces(cs, [res%mu, res%tau], fc)
    else
      call recover(eq, factor, y, cd, u0, res%mu, res%u, err)
      call contact_forces(cs, res%mu, fc)
    end if
    if (allocated(err)) call fail_numerical(err%message)
    call system_clock(t_now, t_rate)
    res%time_solve = res%time_solve + real(t_now - t_solve, dp) / real(t_rate, dp)
    if (fl%k > 0) res%u = res%u + matmul(fl%r, res%alpha)    ! + R alpha: the free rigid modes
    call remove_motions(fl, split%unheld, res%u)              ! no component along the unheld ones
    if (allocated(rigid_alpha)) res%u(rsplit%dof) = rigid_alpha   ! the RIGIDs' free motion
  else
    if (deck%output%steps_all) call solve_earlier_steps()
    res%u = u0
  end if
  if (.not. all(ieee_is_finite(res%u))) call fail_numerical('the displacement is not finite (overflow in the solve)')
  call lap(ph_recover)

  ! --- stresses, reactions, energy -----------------------------------------
  if (with_contact) then
    if (cs%ntan > 0) then
      call pair_resultants([res%mu, res%tau])
    else
      call pair_resultants(res%mu)
    end if
  else
    call pair_resultants([real(dp) ::])
  end if
  call post_process(sc%fext)
  call rigid_results()
  call nodal_contact_fields()
  call check_finite_results()
  if (deck%output%steps_all) call add_step_row(sc%steps)
  call lap(ph_output)             ! stresses, reactions and energy are post-processing

  ! --- outputs ------------------------------------------------------------
  call write_outputs()
  call lap(ph_output)
  call report_run()
  call exit_program(0)

contains

  !> Stresses (when the VTK file asks for them), energy and the reaction of
  !> each FIX, R = K u - f_ext - f_contact on its fixed dofs, from res%u and
  !> the contact forces fc; then res%u in x, y components (nodes in local
  !> axes: the reaction of a fixed dof along n or t is that force along n or
  !> t, summed in x, y into its FIX's reaction).
  !>   fext (in) (ndof) the external forces of the step (solver basis)
  subroutine post_process(fext)
    real(dp), intent(in) :: fext(:)
    integer :: j, b, a
    real(dp), allocatable :: axis(:,:)
    if (allocated(fint)) deallocate(fint)
    if (allocated(res%stress)) deallocate(res%stress, res%vm)
    if (allocated(res%reaction)) deallocate(res%reaction)
    if (allocated(res%fix_label)) deallocate(res%fix_label)
    allocate(res%stress(merge(4, 3, deck%axisymmetric), sc%nelem), res%vm(sc%nelem), fint(sc%ndof))
    if (deck%output%fields(4) .or. deck%output%fields(5)) then
      call element_response(sc%bodies, res%u, fint, res%stress, res%vm)
    else
      call element_response(sc%bodies, res%u, fint)        ! no stress field asked for: none computed
    end if
    res%energy = 0.5_dp * dot_product(res%u, fint)
    allocate(res%reaction(2, size(sc%fixes)), source=0.0_dp)
    nlabel = 1
    do j = 1, size(sc%fixes)
      nlabel = max(nlabel, len(sc%fixes(j)%label))
    end do
    allocate(character(len=nlabel) :: res%fix_label(size(sc%fixes)))
    do j = 1, size(sc%fixes)
      res%fix_label(j) = sc%fixes(j)%label
    end do
    ! the direction of each dof: e_x, e_y, or n, t at a node in local axes
    allocate(axis(2, sc%ndof), source=0.0_dp)
    axis(1, 1::2) = 1.0_dp
    axis(2, 2::2) = 1.0_dp
    do b = 1, size(sc%bodies)
      if (.not. allocated(sc%bodies(b)%axes)) cycle
      do a = 1, sc%bodies(b)%mesh%nnode
        if (all(sc%bodies(b)%axes(:, a) == 0.0_dp)) cycle
        j = sc%bodies(b)%dof0 + 2 * a - 1
        axis(:, j) = sc%bodies(b)%axes(:, a)
        axis(:, j + 1) = [-sc%bodies(b)%axes(2, a), sc%bodies(b)%axes(1, a)]
      end do
    end do
    do j = 1, sc%ndof
      if (sc%fix_owner(j) > 0) then
        ! R = K u - f_ext - f_contact on a fixed dof, along its direction
        res%reaction(:, sc%fix_owner(j)) = res%reaction(:, sc%fix_owner(j)) + (fint(j) - fext(j) - fc(j)) * axis(:, j)
      end if
    end do
    call to_global_axes(sc%bodies, res%u)
  end subroutine post_process

  !> res%contact_force: per pair, the resultant of the contact forces on its
  !> slave body, the sum over the slave dofs of -C' z restricted to the
  !> pair's rows (-sum_i mu_i n_i - tau_i t_i, the slave's outward normal n);
  !> and fc = -C' z, all pairs, on every dof.
  !>   z (in) (nrow) normal multipliers, or (nrow + ntan) with the tangential ones
  subroutine pair_resultants(z)
    real(dp), intent(in) :: z(:)
    real(dp), allocatable :: zp(:)
    integer :: ip, r, d0, nn
    if (.not. allocated(fc)) allocate(fc(sc%ndof))
    fc = 0.0_dp
    if (allocated(res%contact_force)) deallocate(res%contact_force)
    allocate(res%contact_force(2, cs%npair), source=0.0_dp)
    if (size(z) == 0) return
    allocate(zp(size(z)))
    do ip = 1, cs%npair
      zp = 0.0_dp
      do r = 1, cs%nrow
        if (cs%row_pair(r) == ip) zp(r) = z(r)
      end do
      do r = 1, size(z) - cs%nrow
        if (cs%row_pair(cs%tan_row(r)) == ip) zp(cs%nrow + r) = z(cs%nrow + r)
      end do
      call contact_forces(cs, zp, fc)
      call to_global_axes(sc%bodies, fc)
      d0 = sc%bodies(cs%pair(ip)%spec%slave_body)%dof0
      nn = sc%bodies(cs%pair(ip)%spec%slave_body)%mesh%nnode
      res%contact_force(1, ip) = sum(fc(d0 + 1:d0 + 2 * nn:2))
      res%contact_force(2, ip) = sum(fc(d0 + 2:d0 + 2 * nn:2))
    end do
    call contact_forces(cs, z, fc)
  end subroutine pair_resultants

  !> OUTPUT steps=all without friction: steps 1 .. n-1, each an independent
  !> solve at its load factors with the factorization and W of the final
  !> step (only the right-hand side changes): u0_k = K^-1 f_k, q_k = g - B u0_k,
  !> LCP(W, q_k), u_k = K^-1 (f_k - B' mu_k).  Each step's VTK file and table
  !> row are written; res is then as before (the final step is solved next).
  subroutine solve_earlier_steps()
    type(results_t) :: saved
    type(mode_split_t) :: split_n
    real(dp), allocatable :: fk(:), ubk(:), u0k(:), cq(:), q_n(:)
    integer :: kstep
    saved = res
    split_n = split
    if (allocated(q)) q_n = q
    allocate(fk(sc%ndof), ubk(sc%ndof), u0k(sc%ndof), cq(cs%nrow + cs%ntan))
    do kstep = 1, sc%steps - 1
      res = saved
      step_note = 'load step ' // int_to_str(kstep) // ' of ' // int_to_str(sc%steps) // ': '
      call step_loads(sc, kstep, fk, ubk)
      call solve_loads(fk, ubk, [real(dp) ::], u0k)
      if (with_contact) then
        call constraint_values(cs, u0k, cq)
        q = cs%g - cq(1:cs%nrow)                   ! gaps without contact forces
        if (fl%k > 0) then
          call split_free_modes(cs, sc%bodies, fl, fk, split)
          call check_unheld_loads()
        end if
        if (rsplit%k > 0) then
          call split_rigid_modes(cs, sc%rigids, sc%fixed, fk, rsplit)
          call check_unheld_rigid_loads()
        end if
        call solve_contact_problem()
        call contact_measures()
        step_iterations = res%lcp_iterations
        call record_step(kstep, fk, ubk, res%mu)
        call say_step(kstep, res%lcp_method, step_iterations, res%active_nodes)
      else
        step_iterations = 0
        call record_step(kstep, fk, ubk, [real(dp) ::])
      end if
    end do
    res = saved
    split = split_n
    if (rsplit%k > 0) call split_rigid_modes(cs, sc%rigids, sc%fixed, sc%fext, rsplit)
    if (allocated(q_n)) q = q_n
    step_note = 'load step ' // int_to_str(sc%steps) // ' of ' // int_to_str(sc%steps) // ': '
    call step_loads(sc, sc%steps, fk, ubk)         ! the bodies' thermal strains of the final step
  end subroutine solve_earlier_steps

  !> The run log's line of a step solved on its own (OUTPUT steps=all).
  subroutine say_step(kstep, method, iterations, active)
    integer, intent(in) :: kstep, iterations, active
    character(len=*), intent(in) :: method
    character(len=160) :: line
    write(line, '(a,i0,a,i0,a,i0,a,i0,a)') 'step     ', kstep, '/', sc%steps, ': ' // method // ' ', iterations, &
      ' iterations, ', active, ' active'
    call say(trim(line))
  end subroutine say_step

  !> u = K^-1 (f - K_fd ubar - C' z) on the free dofs, ubar on the fixed ones
  !> (one solve with the factorization).
  !>   fk, ubk (in) (ndof) loads and prescribed values;  z (in) multipliers (may be empty)
  !>   u (out) (ndof)
  subroutine solve_loads(fk, ubk, z, u)
    real(dp), intent(in) :: fk(:), ubk(:), z(:)
    real(dp), intent(out) :: u(:)
    real(dp), allocatable :: kub(:), fz(:), b(:,:), xb(:,:)
    integer :: j
    allocate(kub(sc%ndof), fz(sc%ndof), b(nfree, 1), xb(nfree, 1))
    call internal_forces(sc%bodies, ubk, kub)      ! its free rows are K_fd ubar
    fz = 0.0_dp
    if (size(z) > 0) call contact_forces(cs, z, fz)
    do j = 1, sc%ndof
      if (eq(j) > 0) b(eq(j), 1) = fk(j) - kub(j) + fz(j)
    end do
    call solve(factor, b, xb, err)
    if (allocated(err)) call fail_numerical(err%message)
    u = ubk
    do j = 1, sc%ndof
      if (eq(j) > 0) u(j) = xb(eq(j), 1)
    end do
  end subroutine solve_loads

  !> One step's displacement from its multipliers z (res%mu, res%gap, ...
  !> set), its post-processing, VTK file and table row.
  subroutine record_step(kstep, fk, ubk, z)
    integer, intent(in) :: kstep
    real(dp), intent(in) :: fk(:), ubk(:), z(:)
    logical :: ok
    if (allocated(res%u)) deallocate(res%u)
    allocate(res%u(sc%ndof))
    call solve_loads(fk, ubk, z, res%u)
    if (fl%k > 0) res%u = res%u + matmul(fl%r, res%alpha)
    call remove_motions(fl, split%unheld, res%u)
    if (allocated(rigid_alpha)) res%u(rsplit%dof) = rigid_alpha
    if (.not. all(ieee_is_finite(res%u))) call fail_numerical('load step ' // int_to_str(kstep) // &
      ': the displacement is not finite (overflow in the solve)')
    call pair_resultants(z)
    call post_process(fk)
    if (allocated(res%node_pressure)) deallocate(res%node_pressure, res%node_gap)
    if (allocated(res%node_shear)) deallocate(res%node_shear)
    call nodal_contact_fields()
    call check_finite_results()
    call add_step_row(kstep)
    call create_step_file(kstep, ok)
    if (ok) call write_vtk(step_tmp(kstep)%io_path, deck%title, sc%bodies, res, deck%output%fields, ok)
    call close_temporary(step_tmp(kstep))
    if (.not. ok) call output_failure()
  end subroutine record_step

  !> The temporary of step k's VTK file (STEM_000k.vtk).
  subroutine create_step_file(kstep, ok)
    integer, intent(in) :: kstep
    logical, intent(out) :: ok
    if (.not. allocated(step_tmp)) allocate(step_tmp(sc%steps))
    call create_temporary(outdir, step_file(kstep), step_tmp(kstep), ok)
  end subroutine create_step_file

  !> STEM_000k.vtk, STEM the vtk= name without .vtk.
  function step_file(kstep) result(name)
    integer, intent(in) :: kstep
    character(len=:), allocatable :: name
    character(len=16) :: buf
    write(buf, '(i4.4)') kstep
    name = output_stem() // '_' // trim(buf) // '.vtk'
  end function step_file

  function output_stem() result(stem)
    character(len=:), allocatable :: stem
    stem = deck%output%vtk(1:len(deck%output%vtk) - 4)
  end function output_stem

  !> Row k of NAME_steps.csv from res: step, the load factor of each load
  !> path, the reactions of every FIX, the contact resultant of every pair,
  !> active nodes, LCP iterations.
  subroutine add_step_row(kstep)
    integer, intent(in) :: kstep
    integer :: ng, nc, g, c
    ng = size(sc%ramp, 2)
    nc = 1 + ng + 2 * size(sc%fixes) + 2 * cs%npair + 6 * size(sc%rigids) + 2
    call rigid_results()
    if (.not. allocated(step_table)) allocate(step_table(nc, sc%steps), source=0.0_dp)
    step_table(1, kstep) = kstep
    do g = 1, ng
      step_table(1 + g, kstep) = group_factor(sc, g, kstep)
    end do
    c = 1 + ng
    step_table(c + 1:c + 2 * size(sc%fixes), kstep) = reshape(res%reaction, [2 * size(sc%fixes)])
    c = c + 2 * size(sc%fixes)
    step_table(c + 1:c + 2 * cs%npair, kstep) = reshape(res%contact_force, [2 * cs%npair])
    c = c + 2 * cs%npair
    step_table(c + 1:c + 6 * size(sc%rigids), kstep) = reshape(res%rigid, [6 * size(sc%rigids)])
    step_table(nc - 1, kstep) = res%active_nodes
    step_table(nc, kstep) = step_iterations
  end subroutine add_step_row

  !> The header line of NAME_steps.csv.
  function step_header() result(h)
    character(len=:), allocatable :: h
    integer :: g, j
    h = 'step'
    do g = 1, size(sc%ramp, 2)
      h = h // ',factor_' // group_name(sc, g)
    end do
    do j = 1, size(sc%fixes)
      h = h // ',' // sc%fixes(j)%label // '_Fx,' // sc%fixes(j)%label // '_Fy'
    end do
    do j = 1, cs%npair
      h = h // ',contact_' // int_to_str(j) // '_Fx,contact_' // int_to_str(j) // '_Fy'
    end do
    do j = 1, size(sc%rigids)
      h = h // ',' // sc%rigids(j)%name // '_ux,' // sc%rigids(j)%name // '_uy,' // sc%rigids(j)%name // '_rz,' // &
        sc%rigids(j)%name // '_fx,' // sc%rigids(j)%name // '_fy,' // sc%rigids(j)%name // '_m'
    end do
    h = h // ',active_nodes,lcp_iterations'
  end function step_header

  subroutine output_failure()
    if (allocated(step_tmp)) call discard_temporaries(step_tmp)
    write(error_unit, '(a)') 'contact2d: error: ' // outdir // ': cannot write the output files (a writable folder expected)'
    call exit_program(2)
  end subroutine output_failure

  !> Seconds since the last lap go to phase ph; the total is kept up to date.
  subroutine lap(ph)
    integer, intent(in) :: ph
    integer(i8) :: now, rate
    call system_clock(now, rate)
    res%time(ph) = res%time(ph) + real(now - t_phase, dp) / real(rate, dp)
    res%time(ph_total) = real(now - t_start, dp) / real(rate, dp)
    t_phase = now
  end subroutine lap

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
  subroutine order_pattern()
    if (size(last) > 0) then
      call analyze_pattern(factor, k%n, k%colptr, k%rowind, err_order, last=last, group=group, method=trim(ordering))
    else
      call analyze_pattern(factor, k%n, k%colptr, k%rowind, err_order, group=group, method=trim(ordering))
    end if
  end subroutine order_pattern

  !> The values of K and the right-hand side, timed (time_assemble_values).
  subroutine assemble_values()
    call system_clock(t_asm0)
    call assemble_stiffness(sc%bodies, eq, sc%ubar, k, rhs(:, 1), overflow_body)
    call system_clock(t_asm1)
  end subroutine assemble_values

  !> The ordering and the assembly of the values ran side by side: the
  !> ordering is charged to factor, the part of the assembly it did not hide
  !> to assemble, so that the phases still add up to the total.
  subroutine split_overlap()
    integer(i8) :: now, rate
    real(dp) :: wall
    call system_clock(now, rate)
    wall = real(now - t_phase, dp) / real(rate, dp)
    res%time_assemble_values = real(t_asm1 - t_asm0, dp) / real(rate, dp)
    res%time_ordering = min(wall, factor%time_analyze)
    res%time(ph_factor) = res%time(ph_factor) + res%time_ordering
    res%time(ph_assemble) = res%time(ph_assemble) + (wall - res%time_ordering)
    res%time(ph_total) = real(now - t_start, dp) / real(rate, dp)
    t_phase = now
  end subroutine split_overlap

  subroutine say(text)
    character(len=*), intent(in) :: text
    if (.not. quiet) write(output_unit, '(a)') text
  end subroutine say

  !> A contact-set error belongs to its CONTACT statement.
  subroutine contact_error(e)
    type(error_t), intent(in) :: e
    integer :: ip, colon
    ip = 0
    colon = index(e%message, ':')
    if (e%message(1:min(8, len(e%message))) == 'CONTACT ' .and. colon > 9) read(e%message(9:colon - 1), *) ip
    if (e%status == 2 .and. ip >= 1 .and. ip <= size(deck%contacts)) then
      call add_error(diag, deck%file, deck%contacts(ip)%line, e%message(colon + 2:))
      call stop_input_errors(diag)
    end if
    call fail_numerical(e%message)
  end subroutine contact_error

  !> The condensed contact problem by the chosen method (with the free rigid
  !> modes as equality constraints); mu, gaps, pressures, status.
  subroutine solve_contact_problem()
    type(lcp_options_t) :: opts
    type(contact_solution_t) :: sol
    character(len=:), allocatable :: method
    integer :: j

    opts%tol = deck%solver%tol
    opts%maxit = deck%solver%maxit
    opts%omega = deck%solver%omega
    method = deck%solver%lcp
    ! lcp=auto from the measured crossovers (doc/performance.md, "The three LCP
    ! solvers"): up to about 100 constraints the three tie and Lemke's exact
    ! pivoting is kept; above, the primal-dual active set method needs a few
    ! Newton steps where the others need many pivots or sweeps
    if (method == 'auto') then
      if (cs%nrow <= 100) then
        method = 'lemke'
      else
        method = 'pdas'
      end if
    end if
    ! H = B R (how the free modes open the gaps), e = R' f (their load), the
    ! combinations that the rows hold: mode_support (split)
    if (rsplit%k > 0) then
      ! the RIGIDs' free directions join the bodies' free modes (rigid_support)
      call solve_contact(w, q, reshape([split%h, rsplit%h(1:cs%nrow, :)], [cs%nrow, fl%k + rsplit%k]), &
                         [split%e, rsplit%e], &
                         block_diagonal(split%held, rsplit%held), method, opts, sol)
    else
      call solve_contact(w, q, split%h, split%e, split%held, method, opts, sol)
    end if
    res%lcp_method = method
    res%lcp_iterations = sol%rep%iterations
    res%lcp_residual = sol%rep%residual
    if (sol%rep%info /= 0) then
      if (sol%rep%info == 1 .and. rsplit%k > 0) call diagnose_pulled_rigid()
      if (allocated(sol%rep%message)) then
        if (index(sol%rep%message, 'out of memory') == 1) call fail_numerical(sol%rep%message)
        call fail_numerical(step_prefix() // 'contact problem not solved: ' // sol%rep%message)
      else
        call fail_numerical(step_prefix() // 'contact problem not solved by ' // method // ' (info ' // &
                            int_to_str(sol%rep%info) // ')')
      end if
    end if
    if (.not. all(ieee_is_finite(sol%mu))) call fail_numerical('the contact multipliers are not finite')
    call move_alloc(sol%mu, res%mu)
    rigid_alpha = sol%alpha(fl%k + 1:)
    res%alpha = sol%alpha(1:fl%k)
    allocate(character(len=256) :: res%unheld_mode(size(split%unheld, 2)))
    do j = 1, size(split%unheld, 2)
      call say('note     body ' // sc%bodies(split%unheld_body(j))%name // ': rigid mode (' // &
        motion_name(fl, split%unheld(:, j)) // ') held by neither FIX nor contact and unloaded: its amplitude ' // &
        'is set to 0 (the displacement has no component along it; the pressures do not depend on it)')
      res%unheld_mode(j) = unheld_summary(j)
    end do

    call move_alloc(sol%gap, res%gap)
  end subroutine solve_contact_problem

  !> Pressures, status, node counts and complementarity of the solved
  !> contact problem (res%mu, res%gap set).
  subroutine contact_measures()
    integer :: r, ip, node, rows(3), nr
    real(dp) :: dmax, pmax, gmax
    allocate(res%pressure(cs%nrow), res%status(cs%nrow))
    res%contact_nodes = cs%nrow
    if (cs%nrow == 0) return
    dmax = 0.0_dp
    do r = 1, cs%nrow
      dmax = max(dmax, w(r, r))
    end do
    res%redundant = count([(w(r, r) <= 1.0e-14_dp * dmax, r = 1, cs%nrow)])
    pmax = 0.0_dp
    do r = 1, cs%nrow
      ip = cs%row_pair(r)
      node = cs%row_node(r)
      res%pressure(r) = res%mu(r) / cs%weight(r)      ! p = mu / int(phi_i)
      pmax = max(pmax, abs(res%pressure(r)))
    end do
    do r = 1, cs%nrow
      res%status(r) = merge(1, 0, res%mu(r) > 1.0e-12_dp * maxval(abs(res%mu)) .and. res%mu(r) > 0.0_dp)
    end do
    ! counts of slave nodes (a one-segment zone has two nodes on one row)
    res%contact_nodes = 0
    res%active_nodes = 0
    do ip = 1, cs%npair
      do node = 1, size(cs%pair(ip)%snode)
        call node_rows(cs, ip, node, rows, nr)
        if (nr == 0) cycle
        res%contact_nodes = res%contact_nodes + 1
        if (any(res%status(rows(1:nr)) == 1)) res%active_nodes = res%active_nodes + 1
      end do
    end do
    ! length scale: the initial gaps, or the gaps the loads open without contact forces (q)
    gmax = max(maxval(abs(cs%g)), maxval(abs(q(1:cs%nrow))))
    if (pmax > 0.0_dp .and. gmax > 0.0_dp) then
      res%complementarity = maxval(abs(res%pressure * res%gap)) / (pmax * gmax)
    else
      res%complementarity = 0.0_dp
    end if
    res%min_gap = min(0.0_dp, minval(res%gap))
    res%min_pressure = minval(res%pressure)
    do ip = 1, cs%npair                 ! quadratic: a closed row whose master value is extended
      do r = 1, 2
        if (.not. cs%pair(ip)%extended(r)) cycle
        node = merge(cs%pair(ip)%mortar%first, cs%pair(ip)%mortar%last, r == 1)
        nr = row_of_node(cs, ip, node)
        if (nr == 0) cycle
        if (res%status(nr) == 1) write(error_unit, '(a)') 'contact2d: warning: ' // deck%file // ':' // &
          int_to_str(deck%contacts(ip)%line) // ': the contact reaches the slave node ' // int_to_str(node) // &
          ' where the master ends inside a quadratic slave element: its row uses the master''s end value ' // &
          '(refine the slave there or swap slave and master)'
      end do
    end do
  end subroutine contact_measures

  !> C u0_g for each ramp g of the load history (one solve per ramp, none when
  !> the deck has one ramp: then C u0 is the load path times the factor).
  subroutine friction_load_paths()
    integer :: g, j
    real(dp), allocatable :: rhsg(:,:), xg(:,:), ug(:), fk(:)
    allocate(cu0(cs%nrow + cs%ntan, size(sc%ramp, 2)))
    if (size(sc%ramp, 2) == 1 .and. group_factor(sc, 1, sc%steps) == 1.0_dp) then
      call constraint_values(cs, u0, cu0(:, 1))
      return
    end if
    allocate(rhsg(nfree, 1), xg(nfree, 1), ug(sc%ndof), fk(sc%ndof))
    do g = 1, size(sc%ramp, 2)
      call internal_forces(sc%bodies, sc%ugroup(:, g), fk)        ! K ubar_g: its free rows are K_fd ubar_g
      do j = 1, sc%ndof
        if (eq(j) > 0) rhsg(eq(j), 1) = sc%fgroup(j, g) - fk(j)
      end do
      call solve(factor, rhsg, xg, err)
      if (allocated(err)) call fail_numerical(err%message)
      ug = sc%ugroup(:, g)
      do j = 1, sc%ndof
        if (eq(j) > 0) ug(j) = xg(eq(j), 1)
      end do
      call constraint_values(cs, ug, cu0(:, g))
    end do
  end subroutine friction_load_paths

  !> Frictional contact in load steps: at step k the loads are the ramps'
  !> factors times their loads, the slip of the step is measured from the
  !> tangential displacement T u of step k-1, and the condensed friction LCP
  !> (normal and tangential multipliers, friction_lcp) is solved, warm-started
  !> from step k-1.
  subroutine solve_friction_steps()
    type(lcp_options_t) :: opts
    type(lcp_report_t) :: rep
    character(len=:), allocatable :: method
    real(dp), allocatable :: z(:), cu(:), qn(:), qt(:), sprev(:), fk(:), ubk(:)
    real(dp), allocatable :: hh(:,:), eg(:,:), eh(:), alpha(:), unbalanced(:)
    character(len=:), allocatable :: cause
    integer :: n, nt, kstep, g, r, iterations
    logical :: floating
    type(results_t) :: saved
    character(len=200) :: line

    n = cs%nrow
    nt = cs%ntan
    opts%tol = deck%solver%tol
    opts%maxit = deck%solver%maxit
    opts%omega = deck%solver%omega
    method = deck%solver%lcp
    ! lcp=auto: Lemke on the friction LCP (n + 3 nt unknowns) while its dense
    ! tableau is small, the block Gauss-Seidel above
    if (method == 'auto') method = merge('lemke', 'pgs  ', n + 3 * nt <= 400)
    method = trim(method)
    ! bodies held only by contact: the amplitudes of the held combinations of
    ! their modes are unknowns of the friction LCP (friction_modes), against
    ! H = C R V and the load e = V'R'f of each ramp
    allocate(res%alpha(fl%k), source=0.0_dp)
    floating = size(split%held, 2) + size(rsplit%held, 2) > 0
    if (floating) then
      method = 'lemke'
      call say('friction ' // int_to_str(size(split%held, 2) + size(rsplit%held, 2)) // ' rigid-mode amplitudes ' // &
        'of the bodies and RIGIDs held only by contact are unknowns of each step''s friction LCP, solved by ' // &
        'Lemke (' // int_to_str(n + 3 * nt + 2 * (size(split%held, 2) + size(rsplit%held, 2))) // ' unknowns)')
      ! the bodies' held modes, then the RIGIDs' held free directions (their FORCE per ramp)
      hh = reshape([matmul(split%h, split%held), matmul(rsplit%h, rsplit%held)], &
                   [n + nt, size(split%held, 2) + size(rsplit%held, 2)])
      eg = reshape([transpose(matmul(transpose(split%held), matmul(transpose(fl%r), sc%fgroup))), &
                    transpose(matmul(transpose(rsplit%held), sc%fgroup(rsplit%dof, :)))], &
                   [size(sc%ramp, 2), size(hh, 2)])
      eg = transpose(eg)
      allocate(eh(size(hh, 2)), alpha(size(hh, 2)))
    end if
    allocate(z(n + nt), cu(n + nt), qn(n), qt(nt), sprev(nt), res%fstate(nt))
    if (deck%output%steps_all) then
      saved = res
      allocate(fk(sc%ndof), ubk(sc%ndof))
    end if
    z = 0.0_dp
    sprev = 0.0_dp
    iterations = 0
    do kstep = 1, sc%steps
      cu = 0.0_dp
      do g = 1, size(sc%ramp, 2)
        cu = cu + group_factor(sc, g, kstep) * cu0(:, g)
      end do
      qn = cs%g - cu(1:n)                          ! gaps without contact forces
      qt = sprev - cu(n + 1:)                      ! minus the slip of the step without contact forces
      if (floating) then
        eh = 0.0_dp
        do g = 1, size(sc%ramp, 2)
          eh = eh + group_factor(sc, g, kstep) * eg(:, g)
        end do
        call solve_friction_floating(w, qn, qt, cs%tan_row, cs%tan_mu, cs%tan_bound, hh, eh, opts, z, alpha, rep, &
                                     unbalanced, cause)
        if (rep%info == no_equilibrium) call fail_numerical('friction, load step ' // int_to_str(kstep) // ' of ' // &
          int_to_str(sc%steps) // ': ' // floating_no_equilibrium(unbalanced, cause))
        if (rep%info /= 0 .and. index(rep%message, 'out of memory') /= 1) call fail_numerical('friction, load step ' &
          // int_to_str(kstep) // ' of ' // int_to_str(sc%steps) // ': no equilibrium found for the bodies held ' // &
          'only by contact (' // floating_names() // '): ' // rep%message)
        cu = cu + matmul(hh, alpha)                ! C u0 + C R alpha: the step's rigid motion
        qn = cs%g - cu(1:n)
        qt = qt - matmul(hh(n + 1:, :), alpha)
        res%alpha = matmul(split%held, alpha(1:size(split%held, 2)))
        rigid_alpha = matmul(rsplit%held, alpha(size(split%held, 2) + 1:))
      else
        call solve_friction_lcp(w, qn, qt, cs%tan_row, cs%tan_mu, cs%tan_bound, method, opts, z, rep)
      end if
      iterations = iterations + rep%iterations
      if (rep%info /= 0 .and. index(rep%message, 'out of memory') == 1) call fail_numerical(rep%message)
      if (rep%info /= 0) call fail_numerical('friction, load step ' // int_to_str(kstep) // ' of ' // &
        int_to_str(sc%steps) // ': contact problem not solved: ' // rep%message)
      if (.not. all(ieee_is_finite(z))) call fail_numerical('friction, load step ' // int_to_str(kstep) // &
        ': the contact multipliers are not finite')
      sprev = cu(n + 1:) - matmul(w(n + 1:, :), z)  ! T u_k = T u0_k - T K^-1 C' z
      call friction_state(w, qn, qt, cs%tan_row, cs%tan_mu, cs%tan_bound, z, res%fstate, err)
      if (allocated(err)) call fail_numerical(err%message)
      write(line, '(a,i0,a,i0,a,i0,a,i0,a,i0,a,es9.2)') 'step     ', kstep, '/', sc%steps, ': ' // method // ' ', &
        rep%iterations, ' iterations, ', count(z(1:n) > 0.0_dp), ' active, ', count(res%fstate == 2), &
        ' slipping, residual ', rep%residual
      call say(trim(line))
      step_iterations = rep%iterations
      if (deck%output%steps_all .and. kstep < sc%steps) then
        ! this step's displacement, fields and row (the final step is the run's own)
        res%mu = z(1:n)
        res%tau = z(n + 1:)
        res%gap = qn + matmul(w(1:n, :), z)
        call contact_measures()
        call step_loads(sc, kstep, fk, ubk)
        call record_step(kstep, fk, ubk, z)
        call step_loads(sc, sc%steps, fk, ubk)
        call move_alloc(res%fstate, saved%fstate)
        call move_alloc(res%alpha, saved%alpha)
        res = saved
        call move_alloc(saved%fstate, res%fstate)
        call move_alloc(saved%alpha, res%alpha)
      end if
    end do
    res%lcp_method = method
    res%lcp_iterations = iterations
    res%lcp_residual = rep%residual
    res%steps = sc%steps
    res%mu = z(1:n)
    res%tau = z(n + 1:)
    res%gap = qn + matmul(w(1:n, :), z)
    res%slip = sprev
    allocate(res%shear(nt), res%tan_of_row(n))
    res%tan_of_row = 0
    do r = 1, nt
      res%tan_of_row(cs%tan_row(r)) = r
      res%shear(r) = -res%tau(r) / cs%weight(cs%tan_row(r))    ! the force on the slave is -tau t
    end do
    res%stick_nodes = count(res%fstate == 1)
    res%slip_nodes = count(res%fstate == 2)
  end subroutine solve_friction_steps

  !> contact_pressure, gap (and shear) on the nodes, for the VTK file: what
  !> the contact table reports (node_traction).
  subroutine nodal_contact_fields()
    integer :: r, ip, node, gnode, rows(3), nr
    real(dp), allocatable :: tforce(:)
    allocate(res%node_pressure(sc%ndof / 2), res%node_gap(sc%ndof / 2))
    res%node_pressure = 0.0_dp
    res%node_gap = 0.0_dp
    if (allocated(res%tau)) then
      allocate(res%node_shear(sc%ndof / 2), source=0.0_dp)
      allocate(tforce(cs%nrow), source=0.0_dp)
      tforce(cs%tan_row) = -res%tau                   ! the force on the slave is -tau t
    end if
    do ip = 1, cs%npair
      do node = 1, size(cs%pair(ip)%snode)
        r = row_of_node(cs, ip, node)
        if (r == 0) cycle
        gnode = sc%bodies(cs%pair(ip)%spec%slave_body)%dof0 / 2 + cs%pair(ip)%snode(node)
        res%node_pressure(gnode) = node_traction(cs, ip, node, res%mu)
        call node_rows(cs, ip, node, rows, nr)
        res%node_gap(gnode) = minval(res%gap(rows(1:nr)))
        if (allocated(tforce)) res%node_shear(gnode) = node_traction(cs, ip, node, tforce)
      end do
    end do
  end subroutine nodal_contact_fields

  !> Write every output to a temporary of its own, then commit them all.
  subroutine write_outputs()
    type(temporary_t), allocatable :: tmp(:)
    logical :: ok
    character(len=:), allocatable :: names(:)
    integer :: kstep, nl
    ! the run's three files, then with steps=all the .pvd, the step table and
    ! the per-step VTK files (all but the last one written as they were solved)
    allocate(tmp(3))
    call create_temporary(outdir, deck%output%vtk, tmp(1), ok)
    if (ok .and. cs%npair > 0) call create_temporary(outdir, deck%output%contact, tmp(2), ok)
    if (ok) call create_temporary(outdir, deck%output%summary, tmp(3), ok)
    if (ok) call write_vtk(tmp(1)%io_path, deck%title, sc%bodies, res, deck%output%fields, ok)
    if (ok .and. cs%npair > 0) call write_contact_csv(tmp(2)%io_path, cs, res, ok)
    if (ok .and. deck%output%steps_all) then
      call create_step_file(sc%steps, ok)
      if (ok) call write_vtk(step_tmp(sc%steps)%io_path, deck%title, sc%bodies, res, deck%output%fields, ok)
      nl = len(step_file(sc%steps))
      allocate(character(len=nl) :: names(sc%steps))
      do kstep = 1, sc%steps
        names(kstep) = step_file(kstep)
      end do
      tmp = [tmp, temporary_t(), temporary_t(), step_tmp]
      if (ok) call create_temporary(outdir, output_stem() // '.pvd', tmp(4), ok)
      if (ok) call write_pvd(tmp(4)%io_path, names, ok)
      if (ok) call create_temporary(outdir, output_stem() // '_steps.csv', tmp(5), ok)
      if (ok) call write_step_table(tmp(5)%io_path, step_header(), step_table, ok)
    end if
    if (ok) then
      call lap(ph_output)
      res%memory_peak = peak_memory()
      call write_summary(tmp(3)%io_path, res, ok)
    end if
    do i = 1, size(tmp)
      call close_temporary(tmp(i))
    end do
    if (ok) call commit_temporaries(outdir, tmp, ok)
    if (.not. ok) then
      call discard_temporaries(tmp)
      write(error_unit, '(a)') 'contact2d: error: ' // outdir // ': cannot write the output files (a writable folder expected)'
      call exit_program(2)
    end if
  end subroutine write_outputs

  subroutine report_scene()
    integer :: b, ip
    character(len=:), allocatable :: how, family
    character(len=160) :: line
    call say('contact2d ' // version // ': ' // deck%file)
    if (len(deck%title) > 0) call say('title    ' // deck%title)
    call report_parameters()
    call say('effects  ' // sc%effects)
    family = 'P1/Q1'                                 ! the element families of the bodies
    if (any([(is_quadratic(sc%bodies(b)%mesh), b = 1, size(sc%bodies))])) family = 'quadratic (P2/Q8/Q9)'
    if (any([(is_quadratic(sc%bodies(b)%mesh), b = 1, size(sc%bodies))]) .and. &
        .not. all([(is_quadratic(sc%bodies(b)%mesh), b = 1, size(sc%bodies))])) family = 'P1/Q1 and quadratic'
    if (deck%axisymmetric) then
      call say('model    axisymmetric (x = r, y = z), ' // family // ' elasticity, small deformation; ' // &
               'loads per unit area and volume, u_r = 0 on the axis; every force is for the full circle (2 pi r)')
    else if (deck%plane_stress) then
      call say('model    plane stress, ' // family // ' elasticity, small deformation')
    else
      call say('model    plane strain, ' // family // ' elasticity, small deformation')
    end if
    do b = 1, size(sc%bodies)
      ! the body name is as long as the deck made it: not part of the buffer
      write(line, '(i0,a,i0,a,i0,a)') sc%bodies(b)%mesh%nnode, ' nodes, ', sc%bodies(b)%mesh%nelem, &
        ' elements (', count(sc%bodies(b)%mesh%nen == 4 .or. sc%bodies(b)%mesh%nen >= 8), ' quadrilaterals)'
      call say('body     ' // sc%bodies(b)%name // ': ' // trim(line))
    end do
    call report_rigids()
    do ip = 1, cs%npair
      write(line, '(a,i0,a,i0,a,i0,a,i0,a)') 'contact  pair ', ip, ': ', size(cs%pair(ip)%snode), &
        ' slave nodes, ', size(cs%pair(ip)%mnode), ' master nodes, ', cs%pair(ip)%nrow, ' constrained (mortar, '
      if (cs%pair(ip)%spec%rigid > 0) write(line, '(a,i0,a,i0,a,i0,a)') 'contact  pair ', ip, ': ', &
        size(cs%pair(ip)%snode), ' slave nodes against RIGID ' // sc%rigids(cs%pair(ip)%spec%rigid)%name // &
        ' (its exact shape), ', cs%pair(ip)%nrow, ' constrained (mortar, '
      call say(trim(line) // ' ' // friction_law(deck%contacts(ip)%friction, cs%pair(ip)%spec) // ')')
      associate(pr => cs%pair(ip), mo => cs%pair(ip)%mortar)
        if (mo%first > 0) then
          write(line, '(a,es11.4,a,es11.4)') 'contact  pair ' // int_to_str(ip) // ': initial gap from ', &
            minval(mo%gap0(mo%first:mo%last)), ' to ', maxval(mo%gap0(mo%first:mo%last))
          if (pr%closed .and. mo%first == 1 .and. mo%last == size(pr%snode)) then
            line = trim(line) // ', a closed curve covered all round (no zone ends)'
          else if (any(pr%fold)) then
            line = trim(line) // ', a zone end inside a slave segment (the master''s end)'
          end if
          if (pr%spec%interference) line = trim(line) // ', interference=allow'
          if (pr%quadratic) then
            ! the quadratic operator's choices (doc/theory.md, "Quadratic traces")
            call say(trim(line))
            write(line, '(a,i0,a,i0,a)') 'contact  pair ' // int_to_str(ip) // ': quadratic mortar, slave degree ', &
              pr%degree(1), ', master degree ', pr%degree(2), ': non-penetration at every trace node'
            if (any(pr%extended)) then
              call say(trim(line))
              line = 'contact  pair ' // int_to_str(ip) // ': the master ends inside a zone-end slave element: ' // &
                     'its end value extended over the rest'
            end if
          end if
          if (has_friction(pr%spec)) then
            ! the assumption the frictional rows rest on (doc/theory.md, "Friction on curved surfaces")
            call say(trim(line))
            write(line, '(a,f5.3,a)') 'contact  pair ' // int_to_str(ip) // ': rows along the common normal ' // &
              'w n_slave - (1 - w) n_master, w = ', pr%slave_weight, ' (from the two sides'' curvatures)'
          end if
        else
          line = 'contact  pair ' // int_to_str(ip) // ': the master faces no slave segment (no contact possible)'
        end if
        call say(trim(line))
      end associate
    end do
    if (sc%steps > 1 .and. cs%ntan > 0) then
      call say('steps    ' // int_to_str(sc%steps) // ' load steps (friction: the answer depends on the load path)')
    else if (sc%steps > 1 .and. deck%output%steps_all) then
      call say('steps    ' // int_to_str(sc%steps) // ' load steps, each solved at its load factors (without ' // &
               'friction the steps are independent; one factorization for all)')
    else if (sc%steps > 1) then
      call say('steps    ' // int_to_str(sc%steps) // ' load steps declared; without friction the answer does not ' // &
               'depend on the load path: the final step alone is solved')
    end if
    do ip = 1, fl%k
      if (any(split%unheld_body == fl%mode_body(ip))) then
        call say('rigid    body ' // sc%bodies(fl%mode_body(ip))%name // ': ' // mode_name(fl, ip) // ' not held by FIX')
      else
        call say('rigid    body ' // sc%bodies(fl%mode_body(ip))%name // ': ' // mode_name(fl, ip) // &
                 ' not held by FIX: held by contact (equilibrium as an equality constraint)')
      end if
    end do
    do ip = 1, size(split%unheld, 2)
      b = split%unheld_body(ip)
      how = '(the contact normals do not resist it)'
      if (split%tau(b) > 1.0e-10_dp) how = '(the contact normals do not resist it beyond the contact polygon''s median ' // &
        'turning angle, ' // trim(adjustl(real_short(split%tau(b)))) // ' rad)'
      call say('rigid    body ' // sc%bodies(b)%name // ': ' // motion_name(fl, split%unheld(:, ip)) // &
        ' held by neither FIX nor contact ' // how // '; ' // int_to_str(count(fl%mode_body == b) - &
        count(split%unheld_body == b)) // ' other combination(s) held by contact')
    end do
    write(line, '(a,i0,a,i0,a,i0,a)') 'sizes    ', sc%ndof, ' dofs, ', nfree, ' free, ', cs%nrow, ' contact constraints'
    call say(trim(line))
    if (len(thread_note) > 0) call say('threads  ' // thread_note)
  end subroutine report_scene

  !> The run log's lines of each RIGID: its shape, reference point, which
  !> directions are prescribed and which are free (loaded or not, held by
  !> contact or not).
  subroutine report_rigids()
    integer :: r, j, k
    character(len=200) :: line
    character(len=2), parameter :: dname(3) = ['ux', 'uy', 'rz']
    character(len=:), allocatable :: how
    do r = 1, size(sc%rigids)
      associate (sh => sc%rigids(r))
        select case (deck%rigids(r)%shape)
        case ('circle')
          write(line, '(a,g0.6,a,g0.6,a,g0.6,a)') 'circle of radius ', sh%radius, ' centred at (', sh%centre(1), ', ', &
            sh%centre(2), ')'
          if (sh%outside) then
            line = trim(line) // ', solid outside (a hole)'
          else
            line = trim(line) // ', solid inside'
          end if
        case default
          write(line, '(a,i0,a)') deck%rigids(r)%shape // ' of ', size(sh%pt, 2), ' points'
        end select
        write(line(len_trim(line) + 1:), '(a,g0.6,a,g0.6,a)') ', reference point (', sh%ref(1), ', ', sh%ref(2), ')'
        call say('rigid    ' // sh%name // ': ' // trim(line))
        how = ''
        do j = 1, 3
          if (sc%fixed(sh%dof0 + j)) then
            how = how // ', ' // dname(j) // ' prescribed'
          else
            how = how // ', ' // dname(j) // ' free'
            do k = 1, rsplit%k
              if (rsplit%dof(k) == sh%dof0 + j .and. sc%fext(sh%dof0 + j) /= 0.0_dp) how = how // ' (FORCE)'
            end do
          end if
        end do
        if (size(deck%rigids(r)%fixes) + size(deck%rigids(r)%forces) == 0) then
          call say('rigid    ' // sh%name // ': held fixed (no FIX, no FORCE)')
        else if (all(sc%fixed(sh%dof0 + 1:sh%dof0 + 3))) then
          call say('rigid    ' // sh%name // ': ' // how(3:))
        else
          call say('rigid    ' // sh%name // ': ' // how(3:) // ' (a free direction is held by contact alone: ' // &
                   'its equilibrium is an equality of the contact problem)')
        end if
      end associate
    end do
    do j = 1, size(rsplit%unheld, 2)
      if (rsplit%loaded(j)) cycle
      call say('note     RIGID ' // sc%rigids(rsplit%unheld_owner(j))%name // ': free direction (' // &
        rigid_direction(rsplit, rsplit%unheld(:, j)) // ') held by neither FIX nor contact and unloaded: its ' // &
        'motion is set to 0 (the contact normals do not resist it)')
    end do
  end subroutine report_rigids

  !> x in es10.3
  function real_short(x) result(s)
    real(dp), intent(in) :: x
    character(len=10) :: s
    write(s, '(es10.3)') x
  end function real_short

  !> 'BODY KIND X Y' of unheld combination j for the summary: KIND rotation
  !> (X Y its centre) or translation (X Y its unit direction).
  function unheld_summary(j) result(t)
    integer, intent(in) :: j
    character(len=:), allocatable :: t, kind
    real(dp) :: point(2)
    character(len=32) :: bx, by
    call describe_motion(fl, split%unheld(:, j), kind, point)
    write(bx, '(es24.16e3)') point(1)
    write(by, '(es24.16e3)') point(2)
    t = sc%bodies(split%unheld_body(j))%name // ' ' // kind // ' ' // trim(adjustl(bx)) // ' ' // trim(adjustl(by))
  end function unheld_summary

  !> A rigid motion that neither FIX nor contact holds must carry no load:
  !> else no static equilibrium exists (exit 1, naming the body and motion).
  subroutine check_unheld_loads()
    integer :: j
    character(len=16) :: buf
    do j = 1, size(split%unheld, 2)
      if (.not. split%loaded(j)) cycle
      write(buf, '(es10.3)') split%load(j)
      call fail_numerical(step_prefix() // 'no equilibrium: body "' // sc%bodies(split%unheld_body(j))%name // &
        '" is loaded along ' // &
        'a rigid mode (' // motion_name(fl, split%unheld(:, j)) // ') that neither FIX nor contact holds ' // &
        '(frictionless contact holds only normal to the contact surface; load along it ' // trim(adjustl(buf)) // &
        ' of the loads'' scale)')
    end do
  end subroutine check_unheld_loads

  !> x with one decimal (f10.1)
  function real_fixed(x) result(s)
    real(dp), intent(in) :: x
    character(len=10) :: s
    write(s, '(f10.1)') x
  end function real_fixed

  subroutine report_run()
    character(len=200) :: line
    character(len=:), allocatable :: how
    integer :: p
    if (cs%nrow > 0) then
      write(line, '(a,i0,a,i0,a,es10.3,a,es10.3)') 'lcp      ' // res%lcp_method // ': ', res%lcp_iterations, &
        ' iterations, ', res%active_nodes, ' active nodes, residual ', res%lcp_residual, &
        ', complementarity ', res%complementarity
      if (res%lcp_method == 'lemke' .and. res%lcp_iterations > 0) then
        ! Lemke's cost per pivot: O(n^2) on its dense tableau (performance.md)
        write(line(len_trim(line) + 1:), '(a,es9.3,a)') ', ', &
          res%time(ph_lcp) / res%lcp_iterations, ' s per pivot'
      end if
      call say(trim(line))
      write(line, '(a,es12.4,a,es12.4)') 'contact  min gap ', res%min_gap, ', min pressure ', res%min_pressure
      call say(trim(line))
    end if
    do p = 1, size(sc%rigids)
      write(line, '(a,3es12.4,a,3es12.4)') ': motion (ux, uy, rz) =', res%rigid(1:3, p), &
        ', contact force on it (fx, fy, m) =', res%rigid(4:6, p)
      call say('rigid    ' // sc%rigids(p)%name // trim(line))
    end do
    write(line, '(a,es16.8,a,i0)') 'energy   ', res%energy, ',  nnz(L) ', res%factor_nnz
    call say(trim(line) // ' (' // res%ordering // '),  peak memory ' // &
             trim(adjustl(real_fixed(res%memory_peak / 1048576.0_dp))) // ' MB')
    if (factor%nparts > 1) then
      write(line, '(a,i0,a)') 'factor   ', factor%nparts, ' parts (blocks of K that no entry couples: the bodies)'
      if (factor%side_by_side > 1) then
        write(line, '(a,i0,a)') trim(line) // ' ordered and factorized side by side on ', &
          factor%side_by_side, ' threads'
      else
        line = trim(line) // ' ordered and factorized one after the other'
      end if
      call say(trim(line))
    end if
    if (allocated(cd%block)) then
      how = condensed_report(cd)
      if (len(how) > 0) call say('condense W from L_cc by body: ' // how)
    end if
    call say('phase        seconds')
    do p = 1, nphase
      write(line, '(a,f12.4)') phase_names(p), res%time(p)
      call say(trim(line))
    end do
    if (run_threads() > 1) then
      write(line, '(a,f8.3,a,f8.3,a)') ' ordering (', res%time_ordering, &
        ' s, in factor) and the assembly of K (', res%time_assemble_values, ' s) ran side by side'
      call say('overlap  the ' // res%ordering // trim(line))
    end if
    if (cs%npair > 0) then
      call say('wrote    ' // outdir // '/' // deck%output%vtk // ', ' // deck%output%contact // ', ' // deck%output%summary)
    else
      call say('wrote    ' // outdir // '/' // deck%output%vtk // ', ' // deck%output%summary)
    end if
    if (deck%output%steps_all) call say('wrote    ' // step_file(1) // ' .. ' // step_file(sc%steps) // ', ' // &
                                        output_stem() // '.pvd, ' // output_stem() // '_steps.csv')
  end subroutine report_run

  !> 'load step k of n: ' while the steps of OUTPUT steps=all are solved, else ''.
  function step_prefix() result(t)
    character(len=:), allocatable :: t
    t = ''
    if (allocated(step_note)) t = step_note
  end function step_prefix

  !> Each RIGID's motion (u_x, u_y, theta of its reference point, res%u) and
  !> the contact force on it (fc = -C' z on its dofs: force x, y, moment about
  !> the reference point), for the summary, the step table and the log.
  subroutine rigid_results()
    integer :: r, nl
    if (allocated(res%rigid)) deallocate(res%rigid, res%rigid_name)
    nl = 1
    do r = 1, size(sc%rigids)
      nl = max(nl, len(sc%rigids(r)%name))
    end do
    allocate(character(len=nl) :: res%rigid_name(size(sc%rigids)))
    allocate(res%rigid(6, size(sc%rigids)), source=0.0_dp)
    do r = 1, size(sc%rigids)
      res%rigid_name(r) = sc%rigids(r)%name
      res%rigid(1:3, r) = res%u(sc%rigids(r)%dof0 + 1:sc%rigids(r)%dof0 + 3)
      if (allocated(fc)) res%rigid(4:6, r) = fc(sc%rigids(r)%dof0 + 1:sc%rigids(r)%dof0 + 3)
    end do
  end subroutine rigid_results

  !> [a 0; 0 b]: the held combinations of the bodies' modes and of the RIGIDs'
  !> free directions, side by side.
  function block_diagonal(a, b) result(c)
    real(dp), intent(in) :: a(:,:), b(:,:)
    real(dp), allocatable :: c(:,:)
    allocate(c(size(a, 1) + size(b, 1), size(a, 2) + size(b, 2)), source=0.0_dp)
    c(1:size(a, 1), 1:size(a, 2)) = a
    c(size(a, 1) + 1:, size(a, 2) + 1:) = b
  end function block_diagonal

  !> A RIGID's free direction that contact does not hold must carry no load
  !> (exit 1 naming the obstacle and the direction); an unloaded one keeps 0.
  subroutine check_unheld_rigid_loads()
    integer :: j
    do j = 1, size(rsplit%unheld, 2)
      if (.not. rsplit%loaded(j)) cycle
      call fail_numerical(step_prefix() // 'no equilibrium: RIGID "' // sc%rigids(rsplit%unheld_owner(j))%name // &
        '" is loaded along a direction (' // rigid_direction(rsplit, rsplit%unheld(:, j)) // ') that neither its ' // &
        'FIX nor its contacts hold (frictionless contact pushes only normal to the contact surface; expected FIX ' // &
        'on that direction, or a load the contact normals can balance)')
    end do
  end subroutine check_unheld_rigid_loads

  !> The contact problem has no solution because some load pulls a body off its
  !> contacts: when it is a RIGID's FORCE, say which RIGID and which way.
  subroutine diagnose_pulled_rigid()
    integer :: owner
    real(dp) :: resid(3)
    character(len=80) :: buf
    call pulled_rigid(rsplit, owner, resid)
    if (owner == 0) return
    write(buf, '(a,es10.3,a,es10.3,a,es10.3,a)') '(', resid(1), ', ', resid(2), ', ', resid(3), ')'
    call fail_numerical(step_prefix() // 'no equilibrium: the FORCE on RIGID "' // sc%rigids(owner)%name // &
      '" pulls it away from its contacts: contact can only push, and the part (fx, fy, m) = ' // trim(buf) // &
      ' of its load cannot be balanced by any contact pressure (expected a FORCE that presses the obstacle ' // &
      'on the slave boundary)')
  end subroutine diagnose_pulled_rigid


  !> How a pair's tangential behaviour is described in the log.
  function friction_law(kind, spec) result(t)
    character(len=*), intent(in) :: kind
    type(pair_spec_t), intent(in) :: spec
    character(len=:), allocatable :: t
    character(len=32) :: v
    select case (kind)
    case ('coulomb')
      write(v, '(g0.6)') spec%mu
      t = 'Coulomb friction mu = ' // trim(v)
      if (spec%mu == 0.0_dp) t = t // ': frictionless'
    case ('tresca')
      write(v, '(g0.6)') spec%tresca
      t = 'Tresca friction, slip bound ' // trim(v)
      if (spec%tresca == 0.0_dp) t = t // ': frictionless'
    case default
      t = 'frictionless'
    end select
  end function friction_law

  !> A body held only by contact in a scene with friction: the friction LCP
  !> with its mode amplitudes is solved by Lemke (friction_modes); lcp=pgs
  !> is refused at the SOLVER line (exit 2).
  subroutine check_floating_friction_solver()
    if (cs%ntan == 0 .or. deck%solver%lcp /= 'pgs') return
    if (size(split%held, 2) == 0 .and. size(rsplit%held, 2) > 0) then
      call add_error(diag, deck%file, deck%solver%line, 'lcp=pgs with friction on a RIGID under FORCE is not ' // &
        'supported (expected lcp=lemke or lcp=auto, which solve it by Lemke''s method)')
      call stop_input_errors(diag)
    end if
    if (size(split%held, 2) == 0) return
    call add_error(diag, deck%file, deck%solver%line, 'lcp=pgs with friction on a body held only by contact (body "' // &
      sc%bodies(fl%mode_body(1))%name // '": ' // mode_name(fl, 1) // ' not held by FIX) is not supported ' // &
      '(expected lcp=lemke or lcp=auto, which solve it by Lemke''s method)')
    call stop_input_errors(diag)
  end subroutine check_floating_friction_solver

  !> The diagnosis of a frictional step without equilibrium from the unbalanced
  !> load along the held combinations (the bodies' modes, then the RIGIDs'
  !> free directions): the body or the RIGID that carries most of it.
  function floating_no_equilibrium(unbalanced, cause) result(t)
    real(dp), intent(in) :: unbalanced(:)
    character(len=*), intent(in) :: cause
    character(len=:), allocatable :: t
    real(dp), allocatable :: cr(:)
    integer :: kb, r
    kb = size(split%held, 2)
    if (kb > 0) then
      if (maxval(abs(unbalanced(1:kb))) >= maxval(abs(unbalanced(kb + 1:)), mask=.true.) .or. &
          size(unbalanced) == kb) then
        t = friction_no_equilibrium(matmul(split%held, unbalanced(1:kb)), cause)
        return
      end if
    end if
    cr = matmul(rsplit%held, unbalanced(kb + 1:))
    r = rsplit%owner(maxloc(abs(cr), dim=1))
    cr = merge(cr, 0.0_dp, rsplit%owner == r)
    if (cause == 'friction') then
      t = 'no equilibrium: the FORCE on RIGID "' // sc%rigids(r)%name // '" exceeds what friction can hold: it ' // &
        'would move by ' // rigid_direction(rsplit, cr) // ' (the contact forces within the friction cone ' // &
        'cannot balance its load)'
    else
      t = 'no equilibrium: the FORCE on RIGID "' // sc%rigids(r)%name // '" pulls it away from its contacts: it ' // &
        'would move by ' // rigid_direction(rsplit, cr) // ' (no contact force balances its load, whatever ' // &
        'the friction)'
    end if
  end function floating_no_equilibrium

  !> The names of the bodies with free rigid modes, quoted, comma-separated.
  function floating_names() result(t)
    character(len=:), allocatable :: t
    integer :: b
    t = ''
    do b = 1, size(sc%bodies)
      if (.not. any(fl%mode_body == b)) cycle
      if (len(t) > 0) t = t // ', '
      t = t // '"' // sc%bodies(b)%name // '"'
    end do
  end function floating_names

  !> The diagnosis of a step without static equilibrium: the body and the
  !> motion the unbalanced load c (k, along the modes) drives.
  !>   c     (in) (k) e - H'z at the closest balance, in the modes' amplitudes
  !>   cause (in) 'friction' (the cone is too small) or 'contact'
  function friction_no_equilibrium(c, cause) result(t)
    real(dp), intent(in) :: c(:)
    character(len=*), intent(in) :: cause
    character(len=:), allocatable :: t
    real(dp), allocatable :: cb(:)
    integer :: b
    b = fl%mode_body(maxloc(abs(c), dim=1))
    cb = merge(c, 0.0_dp, fl%mode_body == b)          ! the motion of that body alone
    if (cause == 'friction') then
      t = 'no equilibrium: the loads on body "' // sc%bodies(b)%name // '" exceed what friction can hold: ' // &
        'it would move by ' // motion_name(fl, cb) // ' (the contact forces within the friction cone ' // &
        'cannot balance the loads)'
    else
      t = 'no equilibrium: the loads pull body "' // sc%bodies(b)%name // '" away from its contacts: ' // &
        'it would move by ' // motion_name(fl, cb) // ' (no contact force balances the loads, ' // &
        'whatever the friction)'
    end if
  end function friction_no_equilibrium

  !> Every number about to be written must be finite: loads near the top of
  !> the accepted range can overflow in the post-processing (energy, stresses)
  !> even when the displacement did not.  Numerical failure, exit 1, nothing
  !> written.
  subroutine check_finite_results()
    logical :: ok
    ok = ieee_is_finite(res%energy) .and. all(ieee_is_finite(res%reaction)) .and. &
         ieee_is_finite(res%complementarity)
    if (deck%output%fields(4) .or. deck%output%fields(5)) &
      ok = ok .and. all(ieee_is_finite(res%stress)) .and. all(ieee_is_finite(res%vm))
    if (allocated(res%gap)) ok = ok .and. all(ieee_is_finite(res%gap)) .and. all(ieee_is_finite(res%pressure))
    if (.not. ok) call fail_numerical('the results overflow (stresses, reactions, energy or contact quantities ' // &
      'are not finite): the loads or prescribed values are out of the range of double precision arithmetic')
  end subroutine check_finite_results

  !> A body whose FIX leaves a rigid mode free must be held by a CONTACT.
  subroutine check_floating_bodies()
    integer :: j, ip, b
    logical :: in_contact
    do j = 1, fl%k
      b = fl%mode_body(j)
      in_contact = .false.
      do ip = 1, size(sc%specs)
        if (sc%specs(ip)%slave_body == b .or. sc%specs(ip)%master_body == b) in_contact = .true.
      end do
      if (.not. in_contact) call add_error(diag, deck%file, deck%bodies(b)%line, 'body "' // sc%bodies(b)%name // &
        '": its FIX statements leave a rigid-body mode free (' // mode_name(fl, j) // ') and no CONTACT holds ' // &
        'the body (a FIX that blocks it, or a CONTACT, expected)')
    end do
    call stop_input_errors(diag)
  end subroutine check_floating_bodies

  !> The factorization's message, with the dof it names located in the mesh.
  !> A singular K from a body whose law is nearly incompressible (nu close to
  !> 0.5 in plane strain) is said so instead: the dependent column is then
  !> round-off, not a rigid-body mode.
  function factor_failure(e) result(text)
    type(error_t), intent(in) :: e
    character(len=:), allocatable :: text
    integer :: b
    text = e%message // equation_location(e%equation)
    if (index(e%message, 'stiffness matrix is singular') /= 1) return
    do b = 1, size(sc%bodies)
      ! beyond 1e12, K keeps fewer than 4 digits of u = 1.1e-16
      if (tensor_condition(sc%bodies(b)%law) > 1.0e12_dp) then
        text = 'stiffness matrix is singular to working precision: body "' // sc%bodies(b)%name // &
          '" is nearly incompressible (its elasticity tensor has condition number ' // &
          real_to_str(tensor_condition(sc%bodies(b)%law)) // ', nu too close to 0.5; expected a Poisson ratio ' // &
          'that leaves 1 - 2 nu well above the round-off, such as nu <= 0.4999)'
        return
      end if
    end do
  end function factor_failure

  !> '; that is body NAME, node N at (x, y), component u_x' for free
  !> equation eqn (an error's equation field); '' for 0 (none).
  function equation_location(eqn) result(where)
    integer, intent(in) :: eqn
    character(len=:), allocatable :: where
    integer :: d, b, node
    character(len=64) :: buf
    where = ''
    if (eqn <= 0) return
    do d = 1, size(eq)
      if (eq(d) /= eqn) cycle
      do b = size(sc%bodies), 1, -1
        if (d > sc%bodies(b)%dof0) exit
      end do
      node = (d - sc%bodies(b)%dof0 + 1) / 2
      write(buf, '(a,es11.4,a,es11.4,a)') ' at (', sc%bodies(b)%mesh%x(1, node), ',', sc%bodies(b)%mesh%x(2, node), ')'
      where = '; that is body "' // sc%bodies(b)%name // '", node ' // int_to_str(node_in_file(sc%bodies(b)%mesh, node)) // &
              trim(buf) // &
              ', component ' // merge('u_x', 'u_y', mod(d - sc%bodies(b)%dof0, 2) == 1)
      return
    end do
  end function equation_location

  !> Create the output folder (and its parents) when missing: mkdir(2), no
  !> shell, so any name a user can type works.
  subroutine make_folder(path, d)
    character(len=*), intent(in) :: path
    type(diag_t), intent(inout) :: d
    logical :: ok
    if (len(path_too_long(path, 0)) > 0) then
      call add_error(d, path(1:min(len(path), 40)) // '...', 0, 'cannot create the output folder: ' // path_too_long(path, 0))
      return
    end if
    call make_folders(path, ok)
    if (.not. ok) call add_error(d, path, 0, 'cannot create the output folder (a writable path expected)')
  end subroutine make_folder

  !> --cases FILE.csv: the case of --case N, else of SLURM_ARRAY_TASK_ID, else
  !> every case in turn (this program again per case; exit with the worst status).
  !> The chosen row's values join the overrides; the outputs go to DIR/case_N.
  subroutine select_case()
    type(case_table_t) :: table
    character(len=32) :: task
    integer :: length, status, k
    call read_case_table(cases_path, table, diag)
    call stop_input_errors(diag)
    if (case_number == 0) then
      call get_environment_variable('SLURM_ARRAY_TASK_ID', task, length, status)
      if (status == 0 .and. length > 0) case_number = case_index(trim(task), 'SLURM_ARRAY_TASK_ID')
    end if
    if (case_number == 0) then
      call check_header(table)
      call run_every_case(table%ncase, quiet, status)
      call exit_program(status)
    end if
    if (case_number > table%ncase) then
      call add_error(diag, cases_path, table%header_line, 'case ' // int_to_str(case_number) // ' out of range ' // &
                     '(the table has ' // int_to_str(table%ncase) // ' cases; expected 1 to ' // &
                     int_to_str(table%ncase) // ')')
      call stop_input_errors(diag)
    end if
    do k = 1, table%ncol
      if (find_parameter(overrides, trim(table%name(k))) > 0) call add_error(diag, cases_path, table%header_line, &
        'parameter "' // trim(table%name(k)) // '" both in the case table and in -D (expected one of them)')
    end do
    call stop_input_errors(diag)
    call case_parameters(table, case_number, overrides)
    outdir = outdir // '/case_' // int_to_str(case_number)
  end subroutine select_case

  !> Before every case runs: the table's names must be PARAMETERs of the deck
  !> (checked here once when the deck reads without errors; else each case
  !> reports the deck's errors).
  subroutine check_header(table)
    type(case_table_t), intent(in) :: table
    type(diag_t) :: probe_diag
    type(parameter_set_t) :: probe
    probe = overrides
    call case_parameters(table, 1, probe)
    call read_deck(deck_path, deck, probe_diag, probe)
    if (has_errors(probe_diag)) return
    overrides = probe
    call check_overrides()
    call stop_input_errors(diag)
  end subroutine check_header

  !> Every -D and case-table name must be a PARAMETER of the deck.
  subroutine check_overrides()
    integer :: k
    character(len=:), allocatable :: known
    known = ''
    do k = 1, deck%params%n
      known = known // merge(', ', '  ', k > 1) // trim(deck%params%name(k))
    end do
    known = adjustl(known)
    if (deck%params%n == 0) known = 'none declared'
    do k = 1, overrides%n
      if (find_parameter(deck%params, trim(overrides%name(k))) > 0) cycle
      if (overrides%origin(k) == '-D') then
        call add_error(diag, '-D ' // trim(overrides%name(k)), 0, 'the deck ' // deck%file // &
                       ' declares no PARAMETER of this name (expected one of: ' // trim(known) // ')')
      else
        call add_error(diag, cases_path, 1, 'unknown parameter "' // trim(overrides%name(k)) // &
                       '" in the header: the deck ' // deck%file // ' declares no PARAMETER of this name ' // &
                       '(expected one of: ' // trim(known) // ')')
      end if
    end do
  end subroutine check_overrides

  !> The run log's `param    name = value (origin)` lines; the summary's
  !> `parameter NAME VALUE` lines.
  subroutine report_parameters()
    integer :: k, width
    character(len=:), allocatable :: value
    width = 1
    do k = 1, deck%params%n
      width = max(width, len_trim(deck%params%name(k)) + 1 + len(format_number(deck%params%value(k))))
    end do
    allocate(character(len=width) :: res%parameter(deck%params%n))
    do k = 1, deck%params%n
      value = format_number(deck%params%value(k))
      res%parameter(k) = trim(deck%params%name(k)) // ' ' // value
      call say('param    ' // trim(deck%params%name(k)) // ' = ' // value // ' (' // trim(deck%params%origin(k)) // ')')
    end do
  end subroutine report_parameters

end program contact2d
