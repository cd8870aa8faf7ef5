!> case_selection: --cases FILE.csv, the case a run solves (--case N, else
!> SLURM_ARRAY_TASK_ID, else every case in turn), and the check that every
!> -D and case-table name is a PARAMETER of the deck.
!>
!> Why it exists: the choice of a case rewrites the run's overrides and
!> output folder before the deck is read; it sits beside command_line and
!> deck_cases, out of the program's story.  Who may use it: the program and
!> problem_setup.  Bad input ends the run (exit 2, FILE:LINE messages).
!>
!> Programming interface
!>   select_case(run)       the case's PARAMETERs join the overrides, its outputs go to DIR/case_N;
!>                          with no case chosen, every case is run in turn and the program exits
!>   check_overrides(run)   every override names a PARAMETER of the deck read (errors to run%diag)
module case_selection
  use strings, only: int_to_str
  use errors, only: diag_t, add_error, has_errors
  use exits, only: stop_input_errors, exit_program
  use run_state, only: run_t
  use deck_reader, only: read_deck
  use deck_expressions, only: parameter_set_t, find_parameter
  use deck_cases, only: case_table_t, read_case_table, case_parameters, run_every_case
  use command_line, only: case_index
  implicit none
  private
  public :: select_case, check_overrides

contains


  !> --cases FILE.csv: the case of --case N, else of SLURM_ARRAY_TASK_ID, else
  !> every case in turn (this program again per case; exit with the worst status).
  !> The chosen row's values join the overrides; the outputs go to DIR/case_N.
  subroutine select_case(run)
    type(run_t), intent(inout) :: run
    type(case_table_t) :: table
    character(len=32) :: task
    integer :: length, status, k
    call read_case_table(run%cases_path, table, run%diag)
    call stop_input_errors(run%diag)
    if (run%case_number == 0) then
      call get_environment_variable('SLURM_ARRAY_TASK_ID', task, length, status)
      if (status == 0 .and. length > 0) run%case_number = case_index(trim(task), 'SLURM_ARRAY_TASK_ID')
    end if
    if (run%case_number == 0) then
      call check_header(run, table)
      call run_every_case(table%ncase, run%quiet, status)
      call exit_program(status)
    end if
    if (run%case_number > table%ncase) then
      call add_error(run%diag, run%cases_path, table%header_line, 'case ' // int_to_str(run%case_number) // ' out of range ' // &
                     '(the table has ' // int_to_str(table%ncase) // ' cases; expected 1 to ' // &
                     int_to_str(table%ncase) // ')')
      call stop_input_errors(run%diag)
    end if
    do k = 1, table%ncol
      if (find_parameter(run%overrides, trim(table%name(k))) > 0) call add_error(run%diag, run%cases_path, table%header_line, &
        'parameter "' // trim(table%name(k)) // '" both in the case table and in -D (expected one of them)')
    end do
    call stop_input_errors(run%diag)
    call case_parameters(table, run%case_number, run%overrides)
    run%outdir = run%outdir // '/case_' // int_to_str(run%case_number)
  end subroutine select_case

  !> Before every case runs: the table's names must be PARAMETERs of the deck
  !> (checked here once when the deck reads without errors; else each case
  !> reports the deck's errors).
  subroutine check_header(run, table)
    type(run_t), intent(inout) :: run
    type(case_table_t), intent(in) :: table
    type(diag_t) :: probe_diag
    type(parameter_set_t) :: probe
    probe = run%overrides
    call case_parameters(table, 1, probe)
    call read_deck(run%deck_path, run%deck, probe_diag, probe)
    if (has_errors(probe_diag)) return
    run%overrides = probe
    call check_overrides(run)
    call stop_input_errors(run%diag)
  end subroutine check_header

  !> Every -D and case-table name must be a PARAMETER of the deck.
  subroutine check_overrides(run)
    type(run_t), intent(inout) :: run
    integer :: k
    character(len=:), allocatable :: known
    known = ''
    do k = 1, run%deck%params%n
      known = known // merge(', ', '  ', k > 1) // trim(run%deck%params%name(k))
    end do
    known = adjustl(known)
    if (run%deck%params%n == 0) known = 'none declared'
    do k = 1, run%overrides%n
      if (find_parameter(run%deck%params, trim(run%overrides%name(k))) > 0) cycle
      if (run%overrides%origin(k) == '-D') then
        call add_error(run%diag, '-D ' // trim(run%overrides%name(k)), 0, 'the deck ' // run%deck%file // &
                       ' declares no PARAMETER of this name (expected one of: ' // trim(known) // ')')
      else
        call add_error(run%diag, run%cases_path, 1, 'unknown parameter "' // trim(run%overrides%name(k)) // &
                       '" in the header: the deck ' // run%deck%file // ' declares no PARAMETER of this name ' // &
                       '(expected one of: ' // trim(known) // ')')
      end if
    end do
  end subroutine check_overrides

end module case_selection
