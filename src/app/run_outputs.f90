!> run_outputs: the files of a run (DECK.md, "Outputs"): the output folder,
!> the VTK file, the contact table and the summary, and with OUTPUT
!> steps=all a VTK file per step, the ParaView collection and the step
!> table.  Every file is written to a temporary of its own and all are
!> committed together once every one is written (safe_files), so a failed
!> run leaves no half-written file.
!>
!> Why it exists: the naming of the files, their temporaries and the step
!> table are bookkeeping the method does not need to show.  Who may use it:
!> the program and its step modules (run_state's list).  A folder that takes
!> no file ends the run (exit 2), as the program would.
!>
!> Programming interface
!>   make_folder(path, diag)     create the output folder and its parents (an input error when it cannot)
!>   write_step(run, k, res)     step k's table row and VTK file from its results (OUTPUT steps=all)
!>   write_outputs(run)          every file of the run, committed together; run%wrote for the log;
!>                               then the meshes gmsh made go to the mesh cache
module run_outputs
  use kinds, only: dp
  use strings, only: int_to_str
  use errors, only: diag_t, add_error, error_t
  use exits, only: exit_program
  use run_state, only: run_t, ph_output
  use run_report, only: lap
  use deck_reader, only: path_too_long
  use post_processing, only: rigid_results, engineering_results
  use step_table, only: step_columns
  use results_writer, only: results_t, write_vtk, write_contact_csv, write_summary, write_pvd, write_step_table, peak_memory
  use safe_files, only: make_folders, temporary_t, create_temporary, close_temporary, commit_temporaries, &
                        discard_temporaries
  use, intrinsic :: iso_fortran_env, only: error_unit
  use run_phase, only: enter_phase
  use mesh_cache, only: keep_mesh
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

  !> Step k's row of NAME_steps.csv and its VTK file STEM_000k.vtk (a
  !> temporary, committed with the run's other files by write_outputs).
  !>   run   (inout) step_table's row k, step_tmp(k) on exit
  !>   kstep (in)    the step, 1 .. steps - 1
  !>   res   (inout) the step's results (res%rigid set here)
  subroutine write_step(run, kstep, res)
    type(run_t), intent(inout) :: run
    integer, intent(in) :: kstep
    type(results_t), intent(inout) :: res
    type(error_t), allocatable :: err
    call add_step_row(run, kstep, res)
    call create_step_file(run, kstep, err)
    if (.not. allocated(err)) call write_vtk(run%step_tmp(kstep)%io_path, run%deck%title, run%sc%bodies, res, &
                                             run%deck%output%fields, err)
    call close_temporary(run%step_tmp(kstep))
    if (allocated(err)) call output_failure(run)
  end subroutine write_step

  !> Write every output to a temporary of its own, then commit them all; the
  !> run log's `wrote` lines are kept in run%wrote.  A folder that takes no
  !> file ends the run (exit 2, nothing written).
  !>   run (inout) the results on entry; step_table's last row, res%memory_peak, wrote on exit
  subroutine write_outputs(run)
    type(run_t), intent(inout) :: run
    type(temporary_t), allocatable :: tmp(:)
    type(error_t), allocatable :: err
    character(len=:), allocatable :: names(:)
    integer :: kstep, nl, i
    character(len=:), allocatable :: line1, line2, header
    real(dp), allocatable :: row(:)
    logical, allocatable :: whole(:)
    call enter_phase('writing the outputs')
    ! the run's three files, then with steps=all the .pvd, the step table and
    ! the per-step VTK files (all but the last one written as they were solved)
    if (run%deck%output%steps_all) call add_step_row(run, run%sc%steps, run%res)
    allocate(tmp(3))
    ! each call below runs only while no error has come (err is the first)
    call create_temporary(run%outdir, run%deck%output%vtk, tmp(1), err)
    if (.not. allocated(err) .and. run%cs%npair > 0) &
      call create_temporary(run%outdir, run%deck%output%contact, tmp(2), err)
    if (.not. allocated(err)) call create_temporary(run%outdir, run%deck%output%summary, tmp(3), err)
    if (.not. allocated(err)) &
      call write_vtk(tmp(1)%io_path, run%deck%title, run%sc%bodies, run%res, run%deck%output%fields, err)
    if (.not. allocated(err) .and. run%cs%npair > 0) call write_contact_csv(tmp(2)%io_path, run%cs, run%res, err)
    if (.not. allocated(err) .and. run%deck%output%steps_all) then
      call create_step_file(run, run%sc%steps, err)
      if (.not. allocated(err)) call write_vtk(run%step_tmp(run%sc%steps)%io_path, run%deck%title, run%sc%bodies, &
                                               run%res, run%deck%output%fields, err)
      nl = len(step_file(run, run%sc%steps))
      allocate(character(len=nl) :: names(run%sc%steps))
      do kstep = 1, run%sc%steps
        names(kstep) = step_file(run, kstep)
      end do
      tmp = [tmp, temporary_t(), temporary_t(), run%step_tmp]
      if (.not. allocated(err)) call create_temporary(run%outdir, output_stem(run) // '.pvd', tmp(4), err)
      if (.not. allocated(err)) call write_pvd(tmp(4)%io_path, names, err)
      if (.not. allocated(err)) call create_temporary(run%outdir, output_stem(run) // '_steps.csv', tmp(5), err)
      if (.not. allocated(err)) then
        call step_columns(run, run%sc%steps, run%res, header, row, whole)
        call write_step_table(tmp(5)%io_path, header, run%step_table, whole, err)
      end if
    end if
    if (.not. allocated(err)) then
      call lap(run, ph_output)
      run%res%memory_peak = peak_memory()
      call write_summary(tmp(3)%io_path, run%res, err)
    end if
    do i = 1, size(tmp)
      call close_temporary(tmp(i))
    end do
    if (.not. allocated(err)) call commit_temporaries(run%outdir, tmp, err)
    ! the message names the output folder, whichever file failed
    if (allocated(err)) then
      call discard_temporaries(tmp)
      write(error_unit, '(a)') 'contact2d: error: ' // run%outdir // ': cannot write the output files ' // &
        '(a writable folder expected)'
      call exit_program(2)
    end if
    call keep_new_meshes(run)
    if (run%cs%npair > 0) then
      line1 = 'wrote    ' // run%outdir // '/' // run%deck%output%vtk // ', ' // run%deck%output%contact // ', ' // &
              run%deck%output%summary
    else
      line1 = 'wrote    ' // run%outdir // '/' // run%deck%output%vtk // ', ' // run%deck%output%summary
    end if
    if (run%deck%output%steps_all) then
      line2 = 'wrote    ' // step_file(run, 1) // ' .. ' // step_file(run, run%sc%steps) // ', ' // &
              output_stem(run) // '.pvd, ' // output_stem(run) // '_steps.csv'
      run%wrote = [character(len=max(len(line1), len(line2))) :: line1, line2]
    else
      run%wrote = [line1]
    end if
  end subroutine write_outputs

  !> The meshes gmsh made for this run go to the mesh cache (mesh_cache), now
  !> that the run has succeeded: a failed run leaves nothing in its folder.
  !> One that cannot be kept costs the next run a run of gmsh, nothing else.
  subroutine keep_new_meshes(run)
    type(run_t), intent(in) :: run
    type(error_t), allocatable :: err
    integer :: i
    if (.not. allocated(run%gmsh%cache) .or. .not. allocated(run%sc%new_meshes)) return
    do i = 1, size(run%sc%new_meshes)
      call keep_mesh(run%gmsh%cache, run%sc%new_meshes(i)%key, run%sc%new_meshes(i)%msh_path, err)
    end do
  end subroutine keep_new_meshes

  !> The temporary of step k's VTK file (STEM_000k.vtk).
  subroutine create_step_file(run, kstep, err)
    type(run_t), intent(inout) :: run
    integer, intent(in) :: kstep
    type(error_t), allocatable, intent(out) :: err
    if (.not. allocated(run%step_tmp)) allocate(run%step_tmp(run%sc%steps))
    call create_temporary(run%outdir, step_file(run, kstep), run%step_tmp(kstep), err)
  end subroutine create_step_file

  !> STEM_000k.vtk, STEM the vtk= name without .vtk.
  function step_file(run, kstep) result(name)
    type(run_t), intent(in) :: run
    integer, intent(in) :: kstep
    character(len=:), allocatable :: name
    character(len=16) :: buf
    write(buf, '(i4.4)') kstep
    name = output_stem(run) // '_' // trim(buf) // '.vtk'
  end function step_file

  function output_stem(run) result(stem)
    type(run_t), intent(in) :: run
    character(len=:), allocatable :: stem
    stem = run%deck%output%vtk(1:len(run%deck%output%vtk) - 4)
  end function output_stem

  !> Row k of NAME_steps.csv from the step's results res (step_columns: the
  !> load factors, the reactions and mean displacement of every FIX boundary,
  !> each pair's resultant, zones, peak and centre of pressure, the RIGIDs,
  !> active nodes, LCP iterations).
  subroutine add_step_row(run, kstep, res)
    type(run_t), intent(inout) :: run
    integer, intent(in) :: kstep
    type(results_t), intent(inout) :: res
    character(len=:), allocatable :: header
    real(dp), allocatable :: row(:)
    logical, allocatable :: whole(:)
    call rigid_results(run, res)
    call engineering_results(run, res)
    call step_columns(run, kstep, res, header, row, whole)
    if (.not. allocated(run%step_table)) allocate(run%step_table(size(row), run%sc%steps), source=0.0_dp)
    run%step_table(:, kstep) = row
  end subroutine add_step_row

  subroutine output_failure(run)
    type(run_t), intent(inout) :: run
    if (allocated(run%step_tmp)) call discard_temporaries(run%step_tmp)
    write(error_unit, '(a)') 'contact2d: error: ' // run%outdir // ': cannot write the output files (a writable folder expected)'
    call exit_program(2)
  end subroutine output_failure

end module run_outputs
