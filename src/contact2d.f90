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
  use diagnostics, only: diag_t, add_error, stop_input_errors, fail_numerical, exit_program, error_t, int_to_str
  use deck_reader, only: deck_t, read_deck
  use scene, only: scene_t, build_scene, load_factor
  use mesh, only: node_in_file
  use body, only: number_equations, build_pattern, assemble_stiffness, element_response, internal_forces
  use sparse_matrix, only: csc_t
  use sparse_cholesky, only: factor_t, analyze_pattern, factorize_values, solve, solve_forward, factor_nnz, factor_memory, &
                             factor_ordering
  use contact_set, only: contact_set_t, pair_spec_t, build_contact_set, row_of_node, node_rows, node_traction, has_friction
  use contact_condensation, only: contact_equations, condense, contact_forces, recover, constraint_values, &
                                  condensed_t, condensed_report, condensed_blocks
  use lcp_solvers, only: lcp_options_t, lcp_report_t
  use friction_lcp, only: solve_friction_lcp, friction_state
  use contact_lcp, only: contact_solution_t, solve_contact
  use rigid_modes, only: floating_t, find_floating_modes, mode_name, motion_name, describe_motion, remove_motions
  use mode_support, only: mode_split_t, split_free_modes
  use results_writer, only: results_t, write_vtk, write_contact_csv, write_summary, phase_names, nphase, peak_memory
  use safe_files, only: make_folders, temporary_t, create_temporary, close_temporary, commit_temporaries, &
                        discard_temporaries
  use gmsh_runner, only: gmsh_options_t
  use, intrinsic :: iso_fortran_env, only: output_unit, error_unit
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use omp_lib, only: omp_get_thread_num, omp_get_num_threads
  use cholmod_binding, only: c2d_malloc_trim, c2d_blas_park
  use threads, only: start_threads, run_threads
  implicit none

  character(len=*), parameter :: version = '1.0.0'
  integer, parameter :: ph_mesh = 1, ph_assemble = 2, ph_factor = 3, ph_condense = 4, ph_lcp = 5, &
                        ph_recover = 6, ph_output = 7, ph_total = 8
  ! ordering=auto: AMD up to this many free dofs, METIS nested dissection
  ! above (the crossover of bench/ordering.sh, doc/performance.md)
  integer, parameter :: amd_max_free = 500000

  character(len=:), allocatable :: deck_path, outdir
  character(len=5) :: ordering              !< 'metis' or 'amd' (SOLVER ordering=, auto resolved)
  logical :: check_only, quiet
  type(gmsh_options_t) :: gmsh              !< --trust-geo, --gmsh-timeout
  type(diag_t) :: diag
  type(deck_t) :: deck
  type(scene_t) :: sc
  type(contact_set_t) :: cs
  type(csc_t) :: k
  type(factor_t) :: factor
  type(results_t) :: res
  type(error_t), allocatable :: err, err_order
  type(floating_t) :: fl
  type(mode_split_t) :: split            ! the free modes that contact holds, and those it does not
  integer, allocatable :: eq(:), last(:), group(:)
  logical, allocatable :: held(:)
  integer :: nfree, i, nlabel
  integer :: jobs                         !< -j N: threads of the run (0: OpenMP's default)
  integer(i8) :: t_start, t_phase, t_solve, t_now, t_rate, t_asm0, t_asm1
  real(dp), allocatable :: rhs(:,:), x(:,:), u0(:), w(:,:), q(:), fint(:), fc(:)
  real(dp), allocatable :: y(:)           ! forward half of u0's solve
  type(condensed_t) :: cd                 ! X_b = L_b^-1 C_b' or L_b per block of L_cc (condense)
  logical :: with_contact
  real(dp), allocatable :: cu0(:,:)      ! (nrow + ntan, ramps) C u0 of each ramp's loads (friction)

  call parse_command_line(deck_path, outdir, check_only, quiet, gmsh, jobs)
  call start_threads(jobs)                ! threads, BLAS threads, malloc arenas: src/threads.f90
  call system_clock(t_start)
  t_phase = t_start

  ! --- deck and scene ---------------------------------------------------
  call read_deck(deck_path, deck, diag)
  call stop_input_errors(diag)
  if (.not. check_only) call make_folder(outdir, diag)
  call stop_input_errors(diag)
  call build_scene(deck, gmsh, sc, diag)
  call stop_input_errors(diag)
  call build_contact_set(sc%bodies, sc%specs, cs, err)
  if (allocated(err)) call contact_error(err)
  do i = 1, cs%npair
    if (cs%pair(i)%nrow == 0) write(error_unit, '(a)') 'contact2d: warning: ' // deck%file // ':' // &
      int_to_str(deck%contacts(i)%line) // ': no part of the master boundary faces the slave boundary: ' // &
      'this pair can never touch (check the boundary names and the slave/master choice)'
  end do
  ! free rigid modes (bodies held only by contact): pin k dofs to factorize K^#
  call find_floating_modes(sc%bodies, sc%fixed, fl)
  call check_floating_bodies()
  call check_friction_support()
  call split_free_modes(cs, sc%bodies, fl, sc%fext, split)
  held = sc%fixed
  if (fl%k > 0) held(fl%pin) = .true.
  call number_equations(held, eq, nfree)
  res%effects = sc%effects
  res%nfree = nfree
  call report_scene()
  if (check_only) then
    call say('check: the deck and its meshes are valid; nothing solved, nothing written')
    call exit_program(0)
  end if
  call check_unheld_loads()
  call lap(ph_mesh)

  ! --- assembly and factorization (contact dofs last) ----------------------
  ! The ordering (AMD or METIS) reads only the pattern: it runs on one core
  ! while the values are assembled on the other, then the numeric factorization.
  if (nfree == 0) call fail_numerical('every dof is fixed: there is nothing to solve')
  call build_pattern(sc%bodies, eq, nfree, k)
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
  call c2d_malloc_trim()     ! what the orderings freed, before the factors take their memory
  call factorize_values(factor, k, err)
  if (allocated(err)) call fail_numerical(err%message // equation_location(err%message))
  res%factor_nnz = factor_nnz(factor)
  res%ordering = factor_ordering(factor)
  res%factor_cut = factor%ncut
  res%factor_memory = real(factor_memory(factor), dp)
  deallocate(k%colptr, k%rowind, k%val)      ! K lives on in its factor only
  call lap(ph_factor)

  ! --- u0 = K^-1 f: with contact, its forward half y = L^-1 P f only ---------
  ! (condense takes u0 on the contact dofs from y, and the recovery ends the
  ! solve: one forward and one backward substitution in all, time_solve)
  allocate(u0(sc%ndof))
  u0 = sc%ubar
  with_contact = cs%nrow > 0 .or. fl%k > 0
  call system_clock(t_solve)
  if (with_contact) then
    allocate(y(nfree))
    call solve_forward(factor, rhs(:, 1), y)
  else
    allocate(x(nfree, 1))
    call solve(factor, rhs, x)
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
      call solve_contact_problem()
    end if
    call contact_measures()
    call lap(ph_lcp)
    deallocate(w, q)                       ! before the recovery: a lower peak
    allocate(res%u(sc%ndof))
    call system_clock(t_solve)
    if (cs%ntan > 0) then
      call recover(eq, factor, y, cd, u0, [res%mu, res%tau], res%u)
      call contact_forces(cs, [res%mu, res%tau], fc)
    else
      call recover(eq, factor, y, cd, u0, res%mu, res%u)
      call contact_forces(cs, res%mu, fc)
    end if
    call system_clock(t_now, t_rate)
    res%time_solve = res%time_solve + real(t_now - t_solve, dp) / real(t_rate, dp)
    if (fl%k > 0) res%u = res%u + matmul(fl%r, res%alpha)    ! + R alpha: the free rigid modes
    call remove_motions(fl, split%unheld, res%u)              ! no component along the unheld ones
  else
    res%u = u0
  end if
  if (.not. all(ieee_is_finite(res%u))) call fail_numerical('the displacement is not finite (overflow in the solve)')
  call lap(ph_recover)
  call c2d_blas_park()            ! no BLAS after this: the stresses and the files get both cores

  ! --- stresses, reactions, energy -----------------------------------------
  allocate(res%stress(3, sc%nelem), res%vm(sc%nelem), fint(sc%ndof))
  if (deck%output%fields(4) .or. deck%output%fields(5)) then
    call element_response(sc%bodies, res%u, fint, res%stress, res%vm)
  else
    call element_response(sc%bodies, res%u, fint)        ! no stress field asked for: none computed
  end if
  res%energy = 0.5_dp * dot_product(res%u, fint)
  allocate(res%reaction(2, size(sc%fixes)), source=0.0_dp)
  nlabel = 1
  do i = 1, size(sc%fixes)
    nlabel = max(nlabel, len(sc%fixes(i)%label))
  end do
  allocate(character(len=nlabel) :: res%fix_label(size(sc%fixes)))
  do i = 1, size(sc%fixes)
    res%fix_label(i) = sc%fixes(i)%label
  end do
  do i = 1, sc%ndof
    if (sc%fix_owner(i) > 0) then
      ! R = K u - f_ext - f_contact on a fixed dof
      res%reaction(2 - mod(i, 2), sc%fix_owner(i)) = res%reaction(2 - mod(i, 2), sc%fix_owner(i)) &
        + fint(i) - sc%fext(i) - fc(i)
    end if
  end do
  call nodal_contact_fields()
  call check_finite_results()
  call lap(ph_output)             ! stresses, reactions and energy are post-processing

  ! --- outputs ------------------------------------------------------------
  call write_outputs()
  call lap(ph_output)
  call report_run()
  call exit_program(0)

contains

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
      call analyze_pattern(factor, k%n, k%colptr, k%rowind, err_order, last=last, group=group, method=trim(ordering), &
                           cut=deck%solver%cut == 'auto')
    else
      call analyze_pattern(factor, k%n, k%colptr, k%rowind, err_order, group=group, method=trim(ordering), &
                           cut=deck%solver%cut == 'auto')
    end if
  end subroutine order_pattern

  !> The values of K and the right-hand side, timed (time_assemble_values).
  subroutine assemble_values()
    call system_clock(t_asm0)
    call assemble_stiffness(sc%bodies, eq, sc%ubar, k, rhs(:, 1))
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
    ! lcp=auto from the measured crossovers (doc/performance.md): the three
    ! solvers tie up to about 100 constraints, where Lemke's exact pivoting is
    ! kept; above, the primal-dual active set method needs 7-12 Newton steps
    ! on contact Delassus matrices (50x faster than Lemke, 6x than PGS at 5000)
    if (method == 'auto') then
      if (cs%nrow <= 100) then
        method = 'lemke'
      else
        method = 'pdas'
      end if
    end if
    ! H = B R (how the free modes open the gaps), e = R' f (their load), the
    ! combinations that the rows hold: mode_support (split)
    call solve_contact(w, q, split%h, split%e, split%held, method, opts, sol)
    res%lcp_method = method
    res%lcp_iterations = sol%rep%iterations
    res%lcp_residual = sol%rep%residual
    if (sol%rep%info /= 0) then
      if (allocated(sol%rep%message)) then
        call fail_numerical('contact problem not solved: ' // sol%rep%message)
      else
        call fail_numerical('contact problem not solved by ' // method // ' (info ' // int_to_str(sol%rep%info) // ')')
      end if
    end if
    if (.not. all(ieee_is_finite(sol%mu))) call fail_numerical('the contact multipliers are not finite')
    call move_alloc(sol%mu, res%mu)
    call move_alloc(sol%alpha, res%alpha)
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
  end subroutine contact_measures

  !> C u0_g for each ramp g of the load history (one solve per ramp, none when
  !> the deck has one ramp: then C u0 is the load path times the factor).
  subroutine friction_load_paths()
    integer :: g, j
    real(dp), allocatable :: rhsg(:,:), xg(:,:), ug(:), fk(:)
    allocate(cu0(cs%nrow + cs%ntan, size(sc%ramp, 2)))
    if (size(sc%ramp, 2) == 1) then
      call constraint_values(cs, u0, cu0(:, 1))
      return
    end if
    allocate(rhsg(nfree, 1), xg(nfree, 1), ug(sc%ndof), fk(sc%ndof))
    do g = 1, size(sc%ramp, 2)
      call internal_forces(sc%bodies, sc%ugroup(:, g), fk)        ! K ubar_g: its free rows are K_fd ubar_g
      do j = 1, sc%ndof
        if (eq(j) > 0) rhsg(eq(j), 1) = sc%fgroup(j, g) - fk(j)
      end do
      call solve(factor, rhsg, xg)
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
    real(dp), allocatable :: z(:), cu(:), qn(:), qt(:), sprev(:)
    integer :: n, nt, kstep, g, r
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
    allocate(z(n + nt), cu(n + nt), qn(n), qt(nt), sprev(nt), res%fstate(nt))
    z = 0.0_dp
    sprev = 0.0_dp
    res%lcp_iterations = 0
    do kstep = 1, sc%steps
      cu = 0.0_dp
      do g = 1, size(sc%ramp, 2)
        cu = cu + load_factor(sc%ramp(:, g), kstep) * cu0(:, g)
      end do
      qn = cs%g - cu(1:n)                          ! gaps without contact forces
      qt = sprev - cu(n + 1:)                      ! minus the slip of the step without contact forces
      call solve_friction_lcp(w, qn, qt, cs%tan_row, cs%tan_mu, cs%tan_bound, method, opts, z, rep)
      res%lcp_iterations = res%lcp_iterations + rep%iterations
      if (rep%info /= 0) call fail_numerical('friction, load step ' // int_to_str(kstep) // ' of ' // &
        int_to_str(sc%steps) // ': contact problem not solved: ' // rep%message)
      if (.not. all(ieee_is_finite(z))) call fail_numerical('friction, load step ' // int_to_str(kstep) // &
        ': the contact multipliers are not finite')
      sprev = cu(n + 1:) - matmul(w(n + 1:, :), z)  ! T u_k = T u0_k - T K^-1 C' z
      call friction_state(w, qn, qt, cs%tan_row, cs%tan_mu, cs%tan_bound, z, res%fstate)
      write(line, '(a,i0,a,i0,a,i0,a,i0,a,i0,a,es9.2)') 'step     ', kstep, '/', sc%steps, ': ' // method // ' ', &
        rep%iterations, ' iterations, ', count(z(1:n) > 0.0_dp), ' active, ', count(res%fstate == 2), &
        ' slipping, residual ', rep%residual
      call say(trim(line))
    end do
    res%lcp_method = method
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
    type(temporary_t) :: tmp(3)
    logical :: ok
    call create_temporary(outdir, deck%output%vtk, tmp(1), ok)
    if (ok .and. cs%npair > 0) call create_temporary(outdir, deck%output%contact, tmp(2), ok)
    if (ok) call create_temporary(outdir, deck%output%summary, tmp(3), ok)
    if (ok) call write_vtk(tmp(1)%io_path, deck%title, sc%bodies, res, deck%output%fields, ok)
    if (ok .and. cs%npair > 0) call write_contact_csv(tmp(2)%io_path, cs, res, ok)
    if (ok) then
      call lap(ph_output)
      res%memory_peak = peak_memory()
      call write_summary(tmp(3)%io_path, res, ok)
    end if
    do i = 1, 3
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
    character(len=:), allocatable :: how
    character(len=160) :: line
    call say('contact2d ' // version // ': ' // deck%file)
    if (len(deck%title) > 0) call say('title    ' // deck%title)
    call say('effects  ' // sc%effects)
    if (deck%plane_stress) then
      call say('model    plane stress, P1/Q1 elasticity, small deformation')
    else
      call say('model    plane strain, P1/Q1 elasticity, small deformation')
    end if
    do b = 1, size(sc%bodies)
      ! the body name is as long as the deck made it: not part of the buffer
      write(line, '(i0,a,i0,a,i0,a)') sc%bodies(b)%mesh%nnode, ' nodes, ', sc%bodies(b)%mesh%nelem, &
        ' elements (', count(sc%bodies(b)%mesh%nen == 4), ' quadrilaterals)'
      call say('body     ' // sc%bodies(b)%name // ': ' // trim(line))
    end do
    do ip = 1, cs%npair
      write(line, '(a,i0,a,i0,a,i0,a,i0,a)') 'contact  pair ', ip, ': ', size(cs%pair(ip)%snode), &
        ' slave nodes, ', size(cs%pair(ip)%mnode), ' master nodes, ', cs%pair(ip)%nrow, ' constrained (mortar, '
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
        else
          line = 'contact  pair ' // int_to_str(ip) // ': the master faces no slave segment (no contact possible)'
        end if
        call say(trim(line))
      end associate
    end do
    if (sc%steps > 1 .and. cs%ntan > 0) then
      call say('steps    ' // int_to_str(sc%steps) // ' load steps (friction: the answer depends on the load path)')
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
  end subroutine report_scene

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
      call fail_numerical('no equilibrium: body "' // sc%bodies(split%unheld_body(j))%name // '" is loaded along ' // &
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
    if (factor%ncut > 0) then
      write(line, '(a,i0,a,i0,a)') 'factor   ', factor%ncut, trim(merge(' part cut ', ' parts cut', factor%ncut == 1)) &
        // ' at the top separator (', factor%separator, &
        ' dofs): the halves factorized side by side, the separator' // &
        trim(merge(' and the contact dofs', '                     ', factor%nlast > 0)) // ' as a dense block'
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
        ' s, in factor) and the assembly of K (', res%time_assemble_values, ' s) ran side by side on two threads'
      call say('overlap  the ' // res%ordering // trim(line))
    end if
    if (cs%npair > 0) then
      call say('wrote    ' // outdir // '/' // deck%output%vtk // ', ' // deck%output%contact // ', ' // deck%output%summary)
    else
      call say('wrote    ' // outdir // '/' // deck%output%vtk // ', ' // deck%output%summary)
    end if
  end subroutine report_run

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

  !> Friction needs every body held by FIX in its rigid modes: the friction
  !> LCP has no equality constraints for the free modes (exit 2 at the CONTACT
  !> line of the first friction pair).
  subroutine check_friction_support()
    integer :: ip
    if (cs%ntan == 0 .or. fl%k == 0) return
    do ip = 1, cs%npair
      if (has_friction(cs%pair(ip)%spec)) then
        call add_error(diag, deck%file, deck%contacts(ip)%line, 'friction with a body held only by contact (body ' // &
          sc%bodies(fl%mode_body(1))%name // ': ' // mode_name(fl, 1) // ' not held by FIX) is not supported ' // &
          '(expected FIX on every body that a friction pair touches, or a frictionless pair)')
        call stop_input_errors(diag)
      end if
    end do
  end subroutine check_friction_support

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

  !> ': body NAME node N at (x, y), component u_x' for a message naming a free
  !> equation ('at equation K'); '' when it names none.
  function equation_location(message) result(where)
    character(len=*), intent(in) :: message
    character(len=:), allocatable :: where
    integer :: p, ios, eqn, d, b, node
    character(len=64) :: buf
    where = ''
    p = index(message, 'at equation ')
    if (p == 0) return
    read(message(p + 12:), *, iostat=ios) eqn
    if (ios /= 0) return
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
    call make_folders(path, ok)
    if (.not. ok) call add_error(d, path, 0, 'cannot create the output folder (a writable path expected)')
  end subroutine make_folder

  subroutine parse_command_line(deck_path, outdir, check_only, quiet, gmsh, jobs)
    character(len=:), allocatable, intent(out) :: deck_path, outdir
    logical, intent(out) :: check_only, quiet
    type(gmsh_options_t), intent(out) :: gmsh
    integer, intent(out) :: jobs            !< -j N; 0 when not given
    integer :: n, j, length, ios
    character(len=:), allocatable :: arg
    check_only = .false.
    quiet = .false.
    jobs = 0
    outdir = '.'
    deck_path = ''
    n = command_argument_count()
    j = 0
    do while (j < n)
      j = j + 1
      call get_command_argument(j, length=length)
      allocate(character(len=length) :: arg)
      call get_command_argument(j, arg)
      select case (arg)
      case ('-h', '--help')
        call print_help()
        call exit_program(0)
      case ('--version')
        write(output_unit, '(a)') 'contact2d ' // version
        call exit_program(0)
      case ('--check')
        check_only = .true.
      case ('-q')
        quiet = .true.
      case ('--trust-geo')
        gmsh%trust_geo = .true.
      case ('--gmsh-timeout')
        call option_value(j, n, arg, 'option --gmsh-timeout needs a number of seconds (--gmsh-timeout SECONDS)')
        ios = 1
        if (verify(arg, '0123456789.eE+') == 0 .and. len(arg) > 0) read(arg, *, iostat=ios) gmsh%timeout
        if (ios /= 0 .or. .not. (gmsh%timeout > 0.0_dp .and. gmsh%timeout <= 1.0e6_dp)) &
          call usage_error('bad value "' // arg // '" for --gmsh-timeout (seconds, a number > 0 and <= 1e6, ' // &
                           'expected)')
      case ('-j')
        call option_value(j, n, arg, 'option -j needs a number of threads (-j N)')
        ios = 1
        if (verify(arg, '0123456789') == 0 .and. len(arg) > 0 .and. len(arg) <= 4) read(arg, *, iostat=ios) jobs
        if (ios /= 0 .or. jobs < 1) call usage_error('bad value "' // arg // '" for -j (a number of threads, ' // &
                                                     '1 to 9999, expected)')
      case ('-o')
        if (j == n) call usage_error('option -o needs a folder (-o DIR)')
        j = j + 1
        call get_command_argument(j, length=length)
        deallocate(outdir)
        allocate(character(len=length) :: outdir)
        call get_command_argument(j, outdir)
        if (length == 0) call usage_error('option -o needs a folder (-o DIR)')
      case default
        if (len(arg) > 0) then
          if (arg(1:1) == '-') call usage_error('unknown option "' // arg // '" (expected -o DIR, -j N, --check, -q, ' // &
                                                '--trust-geo, --gmsh-timeout SECONDS, --version, -h)')
        end if
        if (len(deck_path) > 0) call usage_error('more than one deck given ("' // deck_path // '" and "' // arg // &
                                                  '"; one DECK expected)')
        deck_path = arg
      end select
      deallocate(arg)
    end do
    if (len(deck_path) == 0) call usage_error('no deck given (usage: contact2d [options] DECK)')
  end subroutine parse_command_line

  !> The value of the option at argument j of n: j moves to the next
  !> argument, arg becomes it; missing is the error when there is none.
  subroutine option_value(j, n, arg, missing)
    integer, intent(inout) :: j
    integer, intent(in) :: n
    character(len=:), allocatable, intent(inout) :: arg
    character(len=*), intent(in) :: missing
    integer :: length
    if (j == n) call usage_error(missing)
    j = j + 1
    call get_command_argument(j, length=length)
    deallocate(arg)
    allocate(character(len=length) :: arg)
    call get_command_argument(j, arg)
  end subroutine option_value

  subroutine usage_error(text)
    character(len=*), intent(in) :: text
    write(error_unit, '(a)') 'contact2d: error: ' // text
    call exit_program(2)
  end subroutine usage_error

  subroutine print_help()
    write(output_unit, '(a)') &
      'usage: contact2d [options] DECK', &
      '', &
      'Unilateral (Signorini) contact between elastic bodies in 2D by the mortar', &
      'finite element method (P1/Q1 plane elasticity, frictionless contact,', &
      'condensed LCP solved by Lemke, projected Gauss-Seidel or a primal-dual', &
      'active set (semismooth Newton) method).', &
      '', &
      'options:', &
      '  -o DIR       write all outputs into DIR (created if missing; default .)', &
      '  -j N         run on N threads (OpenMP and OpenBLAS; default: OMP_NUM_THREADS,', &
      '               else one per core)', &
      '  --check      read and validate the deck and meshes, print the scene, solve nothing', &
      '  -q           quiet: only errors on stderr (the summary file is still written)', &
      '  --trust-geo  let gmsh run a .geo as it is: no screen, no sandbox (it may then run', &
      '               commands and write files); without it, a .geo that runs commands, writes', &
      '               files or reads outside the deck''s folder is refused (exit 2)', &
      '  --gmsh-timeout SECONDS', &
      '               time limit of gmsh on each .geo (default 600); gmsh is then stopped', &
      '  --version    print the version', &
      '  -h, --help   this help', &
      '', &
      'deck statements (keywords and keys case-insensitive; ! and # start comments):', &
      '  TITLE text', &
      '  PLANE strain | PLANE stress thickness=T', &
      '  BODY name ... END', &
      '    MESH rect x0= y0= x1= y1= nx= ny= [elem=tri3|quad4] [diag=right|left|alt]', &
      '    MESH gmsh file=F.msh              (MSH 2.2 or 4.1 ASCII; physical groups name boundaries)', &
      '    MESH gmsh file=F.geo [name=value ...]   (meshed by gmsh -2 -setnumber name value)', &
      '    MATERIAL isotropic E= nu=', &
      '    MATERIAL orthotropic E1= E2= nu12= G12= [angle=0] [E3= nu13= nu23=]', &
      '    DENSITY rho=', &
      '    FIX boundary [ux=] [uy=] [ramp=k0:k1]', &
      '    TRACTION boundary tx= ty= [ramp=k0:k1]', &
      '    PRESSURE boundary p= [ramp=k0:k1]', &
      '    BODYFORCE fx= fy= [ramp=k0:k1]', &
      '    THERMAL alpha= dT= [region=NAME]  (uniform temperature change; per physical surface)', &
      '    OFFSET dx= dy=                    (rigid shift of the body''s geometry)', &
      '  GRAVITY gx= gy= [ramp=k0:k1]', &
      '  CONTACT slave=body:boundary master=body:boundary [gap=geometry|zero] [mu=C | tresca=S]', &
      '                                    (frictionless unless mu= (Coulomb) or tresca= (slip bound))', &
      '  SOLVER lcp=auto|lemke|pgs|pdas [tol=1e-10] [maxit=N] [omega=1.0]   (pdas: frictionless only)', &
      '         [ordering=auto|metis|amd]  (fill-reducing ordering; auto: AMD up to 5e5 free dofs, METIS above)', &
      '         [condense=auto|solve|inverse]  (W per body: triangular solves or the block''s inverse)', &
      '         [cut=auto|off]  (auto: a body of more than 2e5 dofs and twice the others cut in two halves)', &
      '  STEPS n                           (load steps; ramp=k0:k1: load 0 at step k0 rising to 1 at k1)', &
      '  OUTPUT [vtk=FILE] [contact=FILE.csv] [summary=FILE] [fields=displacement,contact_pressure,gap,stress,von_mises]', &
      '', &
      'exit status: 0 solved, 1 solver failure (diagnostic on stderr), 2 bad input.', &
      'See doc/deck.md for every statement, default and output.'
  end subroutine print_help

end program contact2d
