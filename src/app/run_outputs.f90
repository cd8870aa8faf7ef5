!> run_outputs: the files of a run (DECK.md, "Outputs"): the output folder,
!> the VTK file, the contact table and the summary, and with OUTPUT
!> steps=all per step an XML VTK file (.vtu) and a contact table, the
!> ParaView collection (.pvd) and the step table.  Every file is written to
!> a temporary of its own and all are committed together once every one is
!> written (safe_files), so a failed run leaves no half-written file.
!>
!> Why it exists: the naming of the files, their temporaries and the step
!> table are bookkeeping the method does not need to show.  Who may use it:
!> the program and its application modules.  A folder that takes no file
!> ends the run (exit 2), as the program would.
!>
!> Programming interface
!>   make_folder(path, diag)     create the output folder and its parents (an input error when it cannot)
!>   write_step(out, outdir, prob, k, res, iterations)   step k's table row, .vtu and contact
!>                               table from its results (OUTPUT steps=all)
!>   write_outputs(run)          every file of the run, committed together (with OUTPUT plot=png the
!>                               pictures run_plots draws); run%out%wrote for the log; then the meshes
!>                               gmsh made go to the mesh cache
module run_outputs
  use kinds, only: dp
  use strings, only: int_to_str
  use text_scan, only: ends_with_ci
  use errors, only: diag_t, add_error, error_t
  use exits, only: exit_program
  use run_state, only: run_t, outputs_t
  use run_log, only: lap, ph_output
  use problem, only: problem_t
  use deck_reader, only: path_too_long
  use step_table, only: step_columns, zone_sets, widen_rows
  use results_writer, only: results_t, write_contact_csv, write_summary, write_pvd, write_step_table, peak_memory
  use vtk_files, only: write_vtk, write_vtu
  use safe_files, only: make_folders, temporary_t, create_temporary, grow_temporaries, close_temporary, &
                        commit_temporaries, discard_temporaries
  use, intrinsic :: iso_fortran_env, only: error_unit
  use run_phase, only: enter_phase
  use run_estimate, only: predict_cost
  use mesh_cache, only: keep_mesh
  use run_plots, only: draw_plots
  implicit none
  private
  public :: make_folder, write_step, write_outputs

contains

  !> Create the output folder (and its parents) when missing: mkdir(2), no
  !> shell, so any name a user can type works.
  subroutine make_folder(path, d)
    character(len=*), intent(in) :: path
    type(diag_t), intent(inout) :: d
    type(error_t), allocatable :: err
    if (len(path_too_long(path, 0)) > 0) then
      call add_error(d, path(1:min(len(path), 40)) // '...', 0, 'cannot create the output folder: ' // path_too_long(path, 0))
      return
    end if
    call make_folders(path, err)
    if (allocated(err)) call add_error(d, path, 0, 'cannot create the output folder (a writable path expected)')
  end subroutine make_folder

  !> Step k's row of NAME_steps.csv, its VTK file STEM_000k.vtu and its
  !> contact table CSTEM_000k.csv (temporaries, committed with the run's
  !> other files by write_outputs).
  !>   out        (inout) step_table's row k, step_tmp(:, k) on exit
  !>   outdir     (in)    the output folder
  !>   prob       (in)    the problem, its rows those of the step
  !>   kstep      (in)    the step, 1 .. steps - 1
  !>   res        (in)    the step's results
  !>   iterations (in)    its LCP iterations
  subroutine write_step(out, outdir, prob, kstep, res, iterations)
    type(outputs_t), intent(inout) :: out
    character(len=*), intent(in) :: outdir
    type(problem_t), intent(in) :: prob
    integer, intent(in) :: kstep, iterations
    type(results_t), intent(in) :: res
    type(error_t), allocatable :: err
    call add_step_row(out, prob, kstep, res, iterations)
    call write_step_files(out, outdir, prob, kstep, res, err)
    if (allocated(err)) call output_failure(out, outdir)
  end subroutine write_step

  !> Write every output to a temporary of its own, then commit them all; the
  !> run log's `wrote` lines are kept in run%out%wrote.  A folder that takes no
  !> file ends the run (exit 2, nothing written).
  !>   run (inout) the results on entry; step_table's last row, res%memory_peak, wrote on exit
  subroutine write_outputs(run)
    type(run_t), intent(inout) :: run
    type(temporary_t), allocatable :: tmp(:)
    type(error_t), allocatable :: err
    character(len=:), allocatable :: names(:)
    real(dp), allocatable :: times(:)
    integer :: kstep, nl, i, j, k
    character(len=:), allocatable :: line1, line2, line3, header, plots, contact_path, steps_path
    real(dp), allocatable :: row(:)
    logical, allocatable :: whole(:)
    call enter_phase('writing the outputs')
    ! the run's three files, then with steps=all the .pvd, the step table and
    ! the per-step files (all but the last step's written as they were solved)
    if (run%prob%deck%output%steps_all) call add_step_row(run%out, run%prob, run%prob%sc%steps, run%res, run%sol%iterations)
    allocate(tmp(3))
    ! each call below runs only while no error has come (err is the first)
    call create_temporary(run%opts%outdir, run%prob%deck%output%vtk, tmp(1), err)
    if (.not. allocated(err) .and. run%prob%cs%npair > 0) &
      call create_temporary(run%opts%outdir, run%prob%deck%output%contact, tmp(2), err)
    if (.not. allocated(err)) call create_temporary(run%opts%outdir, run%prob%deck%output%summary, tmp(3), err)
    if (.not. allocated(err)) &
      call write_vtk(tmp(1)%io_path, run%prob%deck%title, run%prob%sc%bodies, run%res, run%prob%deck%output%fields, err)
    if (.not. allocated(err) .and. run%prob%cs%npair > 0) call write_contact_csv(tmp(2)%io_path, run%prob%cs, run%res, err)
    if (.not. allocated(err) .and. run%prob%deck%output%steps_all) then
      call write_step_files(run%out, run%opts%outdir, run%prob, run%prob%sc%steps, run%res, err)
      nl = len(step_file(run%prob, run%prob%sc%steps))
      allocate(character(len=nl) :: names(run%prob%sc%steps))
      allocate(times(run%prob%sc%steps))
      do kstep = 1, run%prob%sc%steps
        names(kstep) = step_file(run%prob, kstep)
        times(kstep) = real(kstep, dp) / real(run%prob%sc%steps, dp)    ! the default ramp 0:STEPS
      end do
      ! then the .pvd, the step table and every step's files (not by an array
      ! constructor: grow_temporaries says why)
      call grow_temporaries(tmp, 2 + size(run%out%step_tmp))
      k = 5
      do j = 1, size(run%out%step_tmp, 2)
        do i = 1, size(run%out%step_tmp, 1)
          k = k + 1
          tmp(k) = run%out%step_tmp(i, j)
        end do
      end do
      if (.not. allocated(err)) call create_temporary(run%opts%outdir, output_stem(run%prob) // '.pvd', tmp(4), err)
      if (.not. allocated(err)) call write_pvd(tmp(4)%io_path, names, times, err)
      if (.not. allocated(err)) call create_temporary(run%opts%outdir, output_stem(run%prob) // '_steps.csv', tmp(5), err)
      if (.not. allocated(err)) then
        call step_columns(run%prob, run%prob%sc%steps, run%res, run%sol%iterations, run%out%zone_sets, header, row, &
                          whole)
        call write_step_table(tmp(5)%io_path, header, run%out%step_table, whole, err)
      end if
    end if
    ! the pictures, from the tables just written (their temporaries)
    plots = ''
    if (.not. allocated(err) .and. run%prob%deck%output%plot) then
      contact_path = ''
      if (run%prob%cs%npair > 0) contact_path = tmp(2)%path
      steps_path = ''
      if (run%prob%deck%output%steps_all) steps_path = tmp(5)%path
      call draw_plots(run, contact_path, steps_path, tmp, plots)
    end if
    if (.not. allocated(err)) then
      call lap(run%log, ph_output)
      run%res%memory_peak = peak_memory()
      call predict_this_cost(run)             ! every phase timed but the summary's own writing
      run%res%time = run%log%time
      run%res%cpu = run%log%cpu
      if (allocated(run%log%warning)) run%res%warning = run%log%warning
      if (allocated(run%res%pair_label)) deallocate(run%res%pair_label)
      allocate(run%res%pair_label(size(run%prob%deck%contacts)))     ! CONTACT name=, the summary's PAIR
      do i = 1, size(run%prob%deck%contacts)
        run%res%pair_label(i)%s = ''
        if (allocated(run%prob%deck%contacts(i)%name)) run%res%pair_label(i)%s = run%prob%deck%contacts(i)%name
      end do
      call write_summary(tmp(3)%io_path, run%res, err)
    end if
    do i = 1, size(tmp)
      call close_temporary(tmp(i))
    end do
    if (.not. allocated(err)) call commit_temporaries(run%opts%outdir, tmp, err)
    ! the message names the output folder, whichever file failed
    if (allocated(err)) then
      call discard_temporaries(tmp)
      write(error_unit, '(a)') 'contact2d: error: ' // run%opts%outdir // ': cannot write the output files ' // &
        '(a writable folder expected)'
      call exit_program(2)
    end if
    call keep_new_meshes(run)
    if (run%prob%cs%npair > 0) then
      line1 = 'wrote    ' // run%opts%outdir // '/' // run%prob%deck%output%vtk // ', ' // run%prob%deck%output%contact // ', ' // &
              run%prob%deck%output%summary
    else
      line1 = 'wrote    ' // run%opts%outdir // '/' // run%prob%deck%output%vtk // ', ' // run%prob%deck%output%summary
    end if
    line2 = ''
    if (run%prob%deck%output%steps_all) then
      line2 = 'wrote    ' // step_file(run%prob, 1) // ' .. ' // step_file(run%prob, run%prob%sc%steps) // ', ' // &
              output_stem(run%prob) // '.pvd, ' // output_stem(run%prob) // '_steps.csv'
      if (run%prob%cs%npair > 0) line2 = line2 // ', ' // step_contact_file(run%prob, 1) // ' .. ' // &
                                    step_contact_file(run%prob, run%prob%sc%steps)
    end if
    line3 = ''
    if (len(plots) > 0) line3 = 'wrote    ' // run%opts%outdir // '/' // plots
    nl = max(len(line1), len(line2), len(line3))
    if (len(line2) > 0 .and. len(line3) > 0) then
      run%out%wrote = [character(len=nl) :: line1, line2, line3]
    else if (len(line2) > 0) then
      run%out%wrote = [character(len=nl) :: line1, line2]
    else if (len(line3) > 0) then
      run%out%wrote = [character(len=nl) :: line1, line3]
    else
      run%out%wrote = [line1]
    end if
  end subroutine write_outputs

  !> The meshes gmsh made for this run go to the mesh cache (mesh_cache), now
  !> that the run has succeeded: a failed run leaves nothing in its folder.
  !> One that cannot be kept costs the next run a run of gmsh, nothing else.
  subroutine keep_new_meshes(run)
    type(run_t), intent(in) :: run
    type(error_t), allocatable :: err
    integer :: i
    if (.not. allocated(run%opts%gmsh%cache) .or. .not. allocated(run%prob%sc%new_meshes)) return
    do i = 1, size(run%prob%sc%new_meshes)
      call keep_mesh(run%opts%gmsh%cache, run%prob%sc%new_meshes(i)%key, run%prob%sc%new_meshes(i)%msh_path, err)
    end do
  end subroutine keep_new_meshes

  !> The CPU time and dofs of a run with half this one's energy error
  !> (estimate cost_to_halve): from this mesh's phases (ADAPT's earlier
  !> meshes left out) and its indicators.
  subroutine predict_this_cost(run)
    type(run_t), intent(inout) :: run
    real(dp) :: spent(ph_output)
    spent = run%log%cpu(1:ph_output)
    if (allocated(run%adapt%time0)) spent = spent - run%adapt%time0(1:ph_output)   ! this mesh's step alone
    call predict_cost(run%prob, run%res, spent, run%adapt%energy_prev, run%adapt%dofs_prev)
  end subroutine predict_this_cost

  !> Step k's .vtu and contact table, each to a temporary of its own
  !> (out%step_tmp(:, k)), from the step's results.
  !>   err (out) allocated when a file could not be made or written
  subroutine write_step_files(out, outdir, prob, kstep, res, err)
    type(outputs_t), intent(inout) :: out
    character(len=*), intent(in) :: outdir
    type(problem_t), intent(in) :: prob
    integer, intent(in) :: kstep
    type(results_t), intent(in) :: res
    type(error_t), allocatable, intent(out) :: err
    if (.not. allocated(out%step_tmp)) allocate(out%step_tmp(2, prob%sc%steps))
    call create_temporary(outdir, step_file(prob, kstep), out%step_tmp(1, kstep), err)
    if (.not. allocated(err)) call write_vtu(out%step_tmp(1, kstep)%io_path, prob%sc%bodies, res, prob%deck%output%fields, err)
    call close_temporary(out%step_tmp(1, kstep))
    if (allocated(err) .or. prob%cs%npair == 0) return
    call create_temporary(outdir, step_contact_file(prob, kstep), out%step_tmp(2, kstep), err)
    if (.not. allocated(err)) call write_contact_csv(out%step_tmp(2, kstep)%io_path, prob%cs, res, err)
    call close_temporary(out%step_tmp(2, kstep))
  end subroutine write_step_files

  !> STEM_000k.vtu, STEM the vtk= name without .vtk.
  function step_file(prob, kstep) result(name)
    type(problem_t), intent(in) :: prob
    integer, intent(in) :: kstep
    character(len=:), allocatable :: name
    name = output_stem(prob) // '_' // step_number(kstep) // '.vtu'
  end function step_file

  !> Step k's contact table: the contact= name with _000k before its .csv
  !> (NAME_contact_000k.csv by default), or after it when it has none.
  function step_contact_file(prob, kstep) result(name)
    type(problem_t), intent(in) :: prob
    integer, intent(in) :: kstep
    character(len=:), allocatable :: name
    integer :: n
    associate (contact => prob%deck%output%contact)
      n = len(contact)
      if (ends_with_ci(contact, '.csv') .and. n > 4) then
        name = contact(1:n - 4) // '_' // step_number(kstep) // contact(n - 3:)
      else
        name = contact // '_' // step_number(kstep) // '.csv'
      end if
    end associate
  end function step_contact_file

  !> k with at least four digits: 0001, ..., 9999, 10000.
  function step_number(kstep) result(s)
    integer, intent(in) :: kstep
    character(len=:), allocatable :: s
    character(len=16) :: buf
    write(buf, '(i4.4)') kstep
    s = trim(buf)
  end function step_number

  function output_stem(prob) result(stem)
    type(problem_t), intent(in) :: prob
    character(len=:), allocatable :: stem
    stem = prob%deck%output%vtk(1:len(prob%deck%output%vtk) - 4)
  end function output_stem

  !> Row k of NAME_steps.csv from the step's results res (step_columns: the
  !> load factors, the reactions and mean displacement of every FIX boundary,
  !> each pair's resultant, zones, peak and centre of pressure, the RIGIDs,
  !> active nodes, LCP iterations).
  subroutine add_step_row(out, prob, kstep, res, iterations)
    type(outputs_t), intent(inout) :: out
    type(problem_t), intent(in) :: prob
    integer, intent(in) :: kstep, iterations
    type(results_t), intent(in) :: res
    character(len=:), allocatable :: header, old
    real(dp), allocatable :: row(:), was(:)
    logical, allocatable :: whole(:)
    integer, allocatable :: sets(:,:)
    if (allocated(out%zone_sets)) sets = out%zone_sets
    call zone_sets(res, out%zone_sets)
    call step_columns(prob, kstep, res, iterations, out%zone_sets, header, row, whole)
    if (.not. allocated(out%step_table)) then
      allocate(out%step_table(size(row), prob%sc%steps), source=0.0_dp)
    else if (size(out%step_table, 1) /= size(row)) then
      ! a pair has more zones than at the steps before: their rows get its new columns
      call step_columns(prob, kstep, res, iterations, sets, old, was, whole)
      call widen_rows(old, header, out%step_table)
    end if
    out%step_table(:, kstep) = row
  end subroutine add_step_row

  !> A step's file could not be written: the step files made so far are
  !> discarded, and the run ends (exit 2) naming the output folder.
  subroutine output_failure(out, outdir)
    type(outputs_t), intent(inout) :: out
    character(len=*), intent(in) :: outdir
    integer :: k
    if (allocated(out%step_tmp)) then
      do k = 1, size(out%step_tmp, 2)
        call discard_temporaries(out%step_tmp(:, k))
      end do
    end if
    write(error_unit, '(a)') 'contact2d: error: ' // outdir // ': cannot write the output files (a writable folder expected)'
    call exit_program(2)
  end subroutine output_failure

end module run_outputs
