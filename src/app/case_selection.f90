!> case_selection: --cases FILE.csv, the case a run solves (--case N, else
!> SLURM_ARRAY_TASK_ID, else every case in turn), and the check that every
!> -D and case-table name is a PARAMETER of the deck.
!>
!> Why it exists: the choice of a case rewrites the run's overrides and
!> output folder before the deck is read; it sits beside command_line and
!> deck_cases (the table's parser, which runs nothing), out of the program's
!> story.  Who may use it: the program and problem_setup.  Bad input ends the
!> run (exit 2, FILE:LINE messages).
!>
!> A run of all the cases starts this program again once per case, one after
!> the other, with the same arguments and `--case N` (fork/exec, no shell; its
!> output is this run's): each case is exactly the run `--case N` alone.  A
!> case whose DIR/case_N holds a complete summary (sweep_table's
!> case_complete, the test scripts/sweep makes) is not run again, so a sweep
!> cut short resumes where it stopped.  Then DIR/cases.csv is written, a row
!> per case (sweep_table); --collect writes it alone, from what has run.
!>
!> Programming interface
!>   select_case(run)       the case's PARAMETERs join the overrides, its outputs go to DIR/case_N;
!>                          with no case chosen, every case is run in turn (--collect: none), the
!>                          table DIR/cases.csv written, and the program exits
!>   check_overrides(run)   every override names a PARAMETER of the deck read (errors to run%diag)
module case_selection
  use strings, only: int_to_str
  use errors, only: diag_t, add_error, has_errors
  use exits, only: stop_input_errors, exit_program
  use run_state, only: run_t
  use deck_reader, only: read_deck
  use deck_expressions, only: parameter_set_t, find_parameter
  use deck_cases, only: case_table_t, read_case_table, case_parameters
  use command_line, only: case_index
  use safe_files, only: real_path, make_folders
  use sweep_table, only: case_complete, case_statuses, write_sweep_table, not_run
  use errors, only: error_t
  use system_binding, only: c2d_run_program, c2d_run_exited, c2d_run_signaled
  use, intrinsic :: iso_c_binding, only: c_int, c_double, c_null_char
  use, intrinsic :: iso_fortran_env, only: output_unit, error_unit
  implicit none
  private
  public :: select_case, check_overrides

contains


  !> --cases FILE.csv: the case of --case N, else of SLURM_ARRAY_TASK_ID, else
  !> every case in turn (this program again per case; exit with the worst status)
  !> and the sweep table; with --collect the table alone.
  !> The chosen row's values join the overrides; the outputs go to DIR/case_N.
  !>   run (inout) the command line's options; the deck is read here only to check the table
  subroutine select_case(run)
    type(run_t), intent(inout) :: run
    type(case_table_t) :: table
    character(len=32) :: task
    integer :: length, status, k
    integer, allocatable :: case_status(:)
    character(len=:), allocatable :: summary
    call read_case_table(run%opts%cases_path, table, run%diag)
    call stop_input_errors(run%diag)
    do k = 1, table%ncol                        ! before any case runs: a bad table writes nothing
      if (find_parameter(run%opts%overrides, trim(table%name(k))) > 0) call add_error(run%diag, run%opts%cases_path, &
        table%header_line, &
        'parameter "' // trim(table%name(k)) // '" both in the case table and in -D (expected one of them)')
    end do
    call stop_input_errors(run%diag)
    if (run%opts%case_number == 0 .and. .not. run%opts%collect) then
      call get_environment_variable('SLURM_ARRAY_TASK_ID', task, length, status)
      if (status == 0 .and. length > 0) run%opts%case_number = case_index(trim(task), 'SLURM_ARRAY_TASK_ID')
    end if
    if (run%opts%case_number == 0) then
      call check_header(run, table)
      summary = ''                              ! unknown when the deck does not read: no case is complete
      if (allocated(run%prob%deck%output%summary)) summary = run%prob%deck%output%summary
      if (run%opts%collect) then
        call case_statuses(run%opts%outdir, table%ncase, summary, case_status)
      else
        call run_every_case(table%ncase, run%log%quiet, run%opts%outdir, summary, case_status)
      end if
      call write_table(run, table, summary, case_status, status)
      call exit_program(status)
    end if
    if (run%opts%case_number > table%ncase) then
      call add_error(run%diag, run%opts%cases_path, table%header_line, 'case ' // int_to_str(run%opts%case_number) // &
        ' out of range ' // &
                     '(the table has ' // int_to_str(table%ncase) // ' cases; expected 1 to ' // &
                     int_to_str(table%ncase) // ')')
      call stop_input_errors(run%diag)
    end if
    call case_parameters(table, run%opts%case_number, run%opts%overrides)
    run%opts%outdir = run%opts%outdir // '/case_' // int_to_str(run%opts%case_number)
  end subroutine select_case

  !> Before every case runs: the table's names must be PARAMETERs of the deck
  !> (checked here once when the deck reads without errors; else each case
  !> reports the deck's errors).
  subroutine check_header(run, table)
    type(run_t), intent(inout) :: run
    type(case_table_t), intent(in) :: table
    type(diag_t) :: probe_diag
    type(parameter_set_t) :: probe
    probe = run%opts%overrides
    call case_parameters(table, 1, probe)
    call read_deck(run%opts%deck_path, run%prob%deck, probe_diag, probe)
    if (has_errors(probe_diag)) return
    run%opts%overrides = probe
    call check_overrides(run)
    call stop_input_errors(run%diag)
  end subroutine check_header

  !> Run this program once per case, in turn, with its own arguments and
  !> `--case N`; each case's output goes where this run's goes.  A complete
  !> case (its summary in place) is not run again: its status is 0.
  !>   ncase   (in)  number of cases
  !>   quiet   (in)  no `case N of M` lines
  !>   outdir  (in)  DIR, the cases' DIR/case_N
  !>   summary (in)  the summary's file name ('' when unknown)
  !>   status  (out) (ncase) each case's exit status (a case killed by a
  !>                 signal or that could not start counts as 1)
  subroutine run_every_case(ncase, quiet, outdir, summary, status)
    integer, intent(in) :: ncase
    logical, intent(in) :: quiet
    character(len=*), intent(in) :: outdir, summary
    integer, allocatable, intent(out) :: status(:)
    character(len=:), allocatable :: self, packed, arg
    integer :: n, j, length, nargs, case_status, nrun
    integer(c_int) :: how, st
    logical :: ok

    allocate(status(ncase), source=0)
    nrun = 0
    call real_path('/proc/self/exe', self, ok)
    if (.not. ok) then
      call get_command_argument(0, length=length)
      allocate(character(len=length) :: self)
      call get_command_argument(0, self)
    end if
    do n = 1, ncase
      if (case_complete(outdir // '/case_' // int_to_str(n), summary)) then
        if (.not. quiet) write(output_unit, '(a)') 'case     ' // int_to_str(n) // ' of ' // int_to_str(ncase) // &
          ': complete in ' // outdir // '/case_' // int_to_str(n) // ', not run again'
        cycle
      end if
      nrun = nrun + 1
      packed = self // c_null_char
      nargs = 1
      do j = 1, command_argument_count()
        call get_command_argument(j, length=length)
        if (allocated(arg)) deallocate(arg)
        allocate(character(len=length) :: arg)
        call get_command_argument(j, arg)
        packed = packed // arg // c_null_char
        nargs = nargs + 1
      end do
      packed = packed // '--case' // c_null_char // int_to_str(n) // c_null_char
      nargs = nargs + 2
      if (.not. quiet) then
        write(output_unit, '(a)') 'case     ' // int_to_str(n) // ' of ' // int_to_str(ncase)
        flush(output_unit)
      end if
      if (c2d_run_program(packed, int(nargs, c_int), c_null_char, huge(1.0_c_double), how, st) /= 0) continue
      if (how == c2d_run_exited) then
        case_status = int(st)
      else
        case_status = 1
        if (how == c2d_run_signaled) then
          write(error_unit, '(a)') 'contact2d: error: case ' // int_to_str(n) // ' was killed by signal ' // &
                                   int_to_str(int(st))
        else
          write(error_unit, '(a)') 'contact2d: error: case ' // int_to_str(n) // ' could not start (error ' // &
                                   int_to_str(int(st)) // ')'
        end if
      end if
      status(n) = case_status
    end do
    if (.not. quiet) then
      write(output_unit, '(a)') 'cases    ' // int_to_str(nrun) // ' run, ' // int_to_str(ncase - nrun) // &
        ' complete before, exit status ' // int_to_str(maxval([0, status])) // ' (the worst of the cases)'
    end if
  end subroutine run_every_case

  !> DIR/cases.csv from the cases' statuses and summaries, and the run's
  !> exit status: the worst of the cases' (a case not run counts as 1); 2
  !> when the table cannot be written (nothing written, an error on stderr).
  !>   run     (in)  the options: DIR, quiet
  !>   table   (in)  the case table
  !>   summary (in)  the summary's file name
  !>   status  (in)  (ncase) each case's exit status or not_run
  !>   worst   (out) the exit status of this run
  subroutine write_table(run, table, summary, status, worst)
    type(run_t), intent(in) :: run
    type(case_table_t), intent(in) :: table
    character(len=*), intent(in) :: summary
    integer, intent(in) :: status(:)
    integer, intent(out) :: worst
    type(error_t), allocatable :: err
    character(len=:), allocatable :: failed
    integer :: solved, n
    worst = maxval([0, merge(1, status, status == not_run)])
    call make_folders(run%opts%outdir, err)
    if (.not. allocated(err)) call write_sweep_table(run%opts%outdir, table, summary, status, solved, err)
    if (allocated(err)) then
      write(error_unit, '(a)') 'contact2d: error: ' // run%opts%outdir // ': cannot write cases.csv ' // &
                               '(a writable folder expected)'
      worst = 2
      return
    end if
    if (run%log%quiet) return
    failed = ''
    do n = 1, table%ncase
      if (status(n) /= 0) failed = failed // ' ' // int_to_str(n)
    end do
    if (len(failed) > 0) failed = '; not solved: cases' // failed
    write(output_unit, '(a)') 'table    ' // run%opts%outdir // '/cases.csv: ' // int_to_str(solved) // ' of ' // &
                              int_to_str(table%ncase) // ' cases solved' // failed
  end subroutine write_table

  !> Every -D and case-table name must be a PARAMETER of the deck.
  subroutine check_overrides(run)
    type(run_t), intent(inout) :: run
    integer :: k
    character(len=:), allocatable :: known
    known = ''
    do k = 1, run%prob%deck%params%n
      known = known // merge(', ', '  ', k > 1) // trim(run%prob%deck%params%name(k))
    end do
    known = adjustl(known)
    if (run%prob%deck%params%n == 0) known = 'none declared'
    do k = 1, run%opts%overrides%n
      if (find_parameter(run%prob%deck%params, trim(run%opts%overrides%name(k))) > 0) cycle
      if (run%opts%overrides%origin(k) == '-D') then
        call add_error(run%diag, '-D ' // trim(run%opts%overrides%name(k)), 0, 'the deck ' // run%prob%deck%file // &
                       ' declares no PARAMETER of this name (expected one of: ' // trim(known) // ')')
      else
        call add_error(run%diag, run%opts%cases_path, 1, 'unknown parameter "' // trim(run%opts%overrides%name(k)) // &
                       '" in the header: the deck ' // run%prob%deck%file // ' declares no PARAMETER of this name ' // &
                       '(expected one of: ' // trim(known) // ')')
      end if
    end do
  end subroutine check_overrides

end module case_selection
