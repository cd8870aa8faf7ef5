!> run_state: what one run of contact2d knows, in one derived type passed
!> explicitly from step to step of the program.
!>
!> Why it exists: the program reads like the method (read the deck, build
!> the scene, assemble, factorize, condense, solve the LCP, recover, write),
!> one call per step.  The steps hand each other the scene, the factor, the
!> condensed problem and the results; holding them in one `run_t` keeps
!> every step's signature short and every piece of state visible in one
!> place, with no module variables.  Who may use it: the program and its
!> step modules (problem_setup, linear_system, contact_solve, contact_step,
!> finite_sliding, held_by_contact, post_processing, run_outputs, step_table,
!> run_report, case_selection); no library module below them knows it.
!>
!> Programming interface
!>   type(run_t)               the run: options, deck, scene, factor, condensed problem, results
!>   ph_mesh .. ph_total       the timing phases (index into results_t%time)
module run_state
  use kinds, only: dp, i8
  use errors, only: diag_t
  use deck_reader, only: deck_t
  use deck_types, only: mesh_spec_t
  use deck_expressions, only: parameter_set_t
  use scene, only: scene_t
  use contact_set, only: contact_set_t
  use sparse_matrix, only: csc_t
  use sparse_cholesky, only: factor_t
  use contact_condensation, only: condensed_t
  use rigid_modes, only: floating_t
  use mode_support, only: mode_split_t
  use rigid_support, only: rigid_split_t
  use results_writer, only: results_t
  use safe_files, only: temporary_t
  use gmsh_runner, only: gmsh_options_t
  implicit none
  private
  public :: run_t, adapt_state_t
  public :: ph_mesh, ph_assemble, ph_factor, ph_condense, ph_lcp, ph_recover, ph_estimate, ph_output, ph_total

  integer, parameter :: ph_mesh = 1, ph_assemble = 2, ph_factor = 3, ph_condense = 4, ph_lcp = 5, &
                        ph_recover = 6, ph_estimate = 7, ph_output = 8, ph_total = 9

  !> ADAPT's loop (adaptivity), carried from one mesh's solve to the next.
  type :: adapt_state_t
    integer :: step = 0                            !< meshes solved so far
    real(dp) :: cpu0 = 0                           !< CPU seconds (gmsh's included) when this mesh's step began
    real(dp), allocatable :: time0(:)              !< (nphase) res%cpu when this mesh's step began
    real(dp) :: energy_prev = -1, dofs_prev = -1   !< the previous mesh's energy estimate and dofs (< 0: none)
    real(dp) :: pressure_prev = -1                 !< and its estimate of the ADAPT quantity (< 0: none)
    logical :: capped = .false.                    !< this mesh was made coarser than asked, to keep within max_dofs
    type(mesh_spec_t), allocatable :: geo(:)       !< (nbody) each body's mesh as the deck gives it: what gmsh re-meshes
  end type adapt_state_t

  type :: run_t
    ! --- the command line (command_line, case_selection) -----------------
    character(len=:), allocatable :: deck_path     !< the deck as typed
    character(len=:), allocatable :: outdir        !< the output folder (-o; DIR/case_N with --cases)
    logical :: check_only = .false.                !< --check: validate, solve nothing, write nothing
    logical :: quiet = .false.                     !< -q: no run log
    type(gmsh_options_t) :: gmsh                   !< --trust-geo, --gmsh-timeout
    type(parameter_set_t) :: overrides             !< -D name=value and the --cases row
    character(len=:), allocatable :: cases_path    !< --cases FILE.csv ('' when none)
    integer :: case_number = 0                     !< --case N (0: none given)
    integer :: jobs = 0                            !< -j N: threads of the run (0: the environment's)
    character(len=:), allocatable :: thread_note   !< what a memory limit changed in the thread count ('' none)
    type(diag_t) :: diag                           !< the input errors collected so far

    ! --- deck, scene, contact set, rigid modes (problem_setup) -----------
    type(deck_t) :: deck
    type(scene_t) :: sc
    type(contact_set_t) :: cs
    type(floating_t) :: fl                         !< the bodies' free rigid modes (held only by contact)
    type(mode_split_t) :: split                    !< those modes that contact holds, and those it does not
    type(rigid_split_t) :: rsplit                  !< the RIGIDs' free directions: floating modes loaded by FORCE
    integer, allocatable :: eq(:)                  !< (ndof) free equation of each dof, 0 when fixed
    integer :: nfree = 0                           !< free equations

    ! --- the linear system (linear_system) --------------------------------
    type(csc_t) :: k                               !< K_ff until it is factorized
    real(dp), allocatable :: rhs(:,:)              !< (nfree, 1) f_f - K_fd ubar, until u0 is solved
    integer, allocatable :: last(:)                !< the contact equations, ordered last
    integer, allocatable :: group(:)               !< (nfree) the mesh node of each equation (METIS's graph)
    character(len=5) :: ordering = 'auto'          !< 'metis' or 'amd' (SOLVER ordering=, auto resolved)
    integer :: overflow_body = 0                   !< a body whose K_fd ubar_d leaves double precision (0: none)
    type(factor_t) :: factor                       !< K_ff = L L' (contact dofs last)
    logical :: with_contact = .false.              !< contact rows, free modes or free RIGID directions
    real(dp), allocatable :: u0(:)                 !< (ndof) K^-1 f without contact forces (ubar on fixed dofs)
    real(dp), allocatable :: y(:)                  !< (nfree) forward half of u0's solve, L^-1 P f
    real(dp), allocatable :: w(:,:)                !< (nrow + ntan, nrow + ntan) W = C K^-1 C'
    real(dp), allocatable :: q(:)                  !< (nrow + ntan) q = g - C u0
    type(condensed_t) :: cd                        !< X_b = L_b^-1 C_b' or L_b per block of L_cc
    real(dp), allocatable :: cu0(:,:)              !< (nrow + ntan, ramps) C u0 of each ramp's loads (friction)
    real(dp), allocatable :: fc(:)                 !< (ndof) the contact forces -C' z

    ! --- the contact solution and results (contact_solve, post_processing) -
    type(results_t) :: res
    real(dp), allocatable :: rigid_alpha(:)        !< (rsplit%k) the RIGIDs' free motion, from the contact problem

    ! --- OUTPUT steps=all (contact_solve, run_outputs) --------------------
    type(temporary_t), allocatable :: step_tmp(:,:) !< (2, steps) the temporaries of each step's .vtu and contact table
    real(dp), allocatable :: step_table(:,:)       !< (ncol, steps) the rows of NAME_steps.csv
    integer :: step_iterations = 0                 !< LCP iterations of the step being recorded
    character(len=:), allocatable :: step_note     !< 'load step k of n: ' in messages while steps are solved

    ! --- ADAPT (adaptivity) ----------------------------------------------
    type(adapt_state_t) :: adapt

    ! --- the clock (run_report) ------------------------------------------
    integer(i8) :: t_start = 0, t_phase = 0        !< the run's start, the last lap
    real(dp) :: c_phase = 0                        !< the process's CPU seconds at the last lap
    integer(i8) :: t_asm0 = 0, t_asm1 = 0          !< the assembly of K's values, beside the ordering
    character(len=:), allocatable :: wrote(:)      !< the run log's `wrote` lines (run_outputs)
  end type run_t

end module run_state
