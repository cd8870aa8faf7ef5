!> run_plots: the pictures of a run (OUTPUT plot=png; doc/outputs.md,
!> "Pictures"): STEM_pressure.png, the contact pressure (and with friction
!> the shear) along the slave boundary of each pair, read from the contact
!> table just written, and with steps=all STEM_steps.png (steps_plot's
!> script), the forces and rigid motions against the load factor or the
!> column OUTPUT x= names, read from STEM_steps.csv.  Axis labels give the
!> units of the deck's plane and round-off is drawn flat (plot_text).
!>
!> gnuplot draws them.  It is started without a shell, with an argument
!> vector and a time limit (process_runner), on a script written here into
!> the run's private folder; it writes the picture there, and the bytes are
!> then copied to a temporary of the output folder, committed with the run's
!> other files.  A deck is untrusted and gnuplot runs commands (`system`,
!> `!`): every string of the script that comes from outside (the TITLE, the
!> column names, the paths) is a single-quoted gnuplot string, in which
!> nothing is substituted (no backquotes, no macros) and a quote is doubled,
!> with control characters removed so that no string ends a line.
!>
!> A picture is a convenience: gnuplot missing, failing or slow gives a
!> warning (code `plot`) and the run goes on with its other files.
!>
!> Programming interface
!>   draw_plots(run, contact_path, steps_path, tmp, names)
!>       draw the pictures from the tables at contact_path and steps_path ('' when
!>       not written); each PNG is appended to tmp as a temporary of the output
!>       folder and its name to names
module run_plots
  use, intrinsic :: iso_c_binding, only: c_int, c_double, c_null_char
  use kinds, only: dp, i8
  use strings, only: int_to_str, real_to_str, printable, exact_to_str
  use errors, only: error_t
  use system_binding, only: c2d_run_program, c_unlink, c2d_run_exited, c2d_run_signaled, &
                            c2d_run_timeout
  use safe_files, only: find_program, read_file, private_folder, file_kind, c2d_regular, temporary_t, create_temporary, &
                        close_temporary, discard_temporaries, grow_temporaries
  use run_state, only: run_t
  use run_log, only: add_warning
  use plot_text, only: gnuplot_string, terminal_lines, title_text, csv_field, pressure_unit, is_flat, flat_range
  use steps_plot, only: steps_script
  implicit none
  private
  public :: draw_plots

  real(dp), parameter :: gnuplot_timeout = 60.0_dp   !< seconds gnuplot may take for one picture

contains

  !> Draw the run's pictures and add them to its temporaries.
  !>   run          (inout) the deck's title and output names; warnings on failure
  !>   contact_path (in)    the contact table written ('' when none: no pressure picture)
  !>   steps_path   (in)    STEM_steps.csv written ('' when none: no steps picture)
  !>   tmp          (inout) the run's temporaries; each picture's appended
  !>   names        (inout) the file names of the pictures added
  subroutine draw_plots(run, contact_path, steps_path, tmp, names)
    type(run_t), intent(inout) :: run
    character(len=*), intent(in) :: contact_path, steps_path
    type(temporary_t), allocatable, intent(inout) :: tmp(:)
    character(len=:), allocatable, intent(inout) :: names
    character(len=:), allocatable :: folder, gnuplot, stem, script
    type(error_t), allocatable :: err
    logical :: found

    stem = run%prob%deck%output%vtk(1:len(run%prob%deck%output%vtk) - 4)
    if (len(contact_path) == 0 .and. len(steps_path) == 0) return
    call find_program('gnuplot', gnuplot, found)
    if (.not. found) then
      call add_warning(run%log, 'plot', 'gnuplot not found on PATH (install the Debian package gnuplot-nox): ' // &
                       'no picture drawn, the other outputs are written')
      return
    end if
    call private_folder(folder, err)
    if (allocated(err)) then
      call add_warning(run%log, 'plot', 'cannot make a private folder for gnuplot: no picture drawn')
      return
    end if
    if (len(contact_path) > 0) then
      call pressure_script(run, contact_path, folder // '/' // stem // '_pressure.png', script)
      if (len(script) > 0) &
        call draw(run, gnuplot, script, folder, stem // '_pressure', tmp, names)
    end if
    if (len(steps_path) > 0) then
      call steps_script(run, steps_path, folder // '/' // stem // '_steps.png', script)
      if (len(script) > 0) call draw(run, gnuplot, script, folder, stem // '_steps', tmp, names)
    end if
  end subroutine draw_plots

  !> Run gnuplot on script (written to folder/base.gp), which draws
  !> folder/base.png; copy the picture to a temporary for the output
  !> base.png.  Any failure: a warning, nothing added.
  subroutine draw(run, gnuplot, script, folder, base, tmp, names)
    type(run_t), intent(inout) :: run
    character(len=*), intent(in) :: gnuplot, script, folder, base
    type(temporary_t), allocatable, intent(inout) :: tmp(:)
    character(len=:), allocatable, intent(inout) :: names
    character(len=:), allocatable :: gp, log, png, argv, bytes, why
    type(temporary_t) :: t(1)
    type(error_t), allocatable :: err
    integer(c_int) :: how, status
    integer :: u, ios, st, kind

    gp = folder // '/' // base // '.gp'
    log = folder // '/' // base // '.log'
    png = folder // '/' // base // '.png'
    if (c_unlink(log // c_null_char) /= 0) continue     ! the runner makes the log: it must not exist
    if (c_unlink(png // c_null_char) /= 0) continue     ! a picture there afterwards is gnuplot's
    open(newunit=u, file=gp, status='replace', action='write', form='formatted', iostat=ios)
    if (ios == 0) write(u, '(a)', iostat=ios) script
    if (ios == 0) close(u, iostat=ios)
    if (ios /= 0) then
      call add_warning(run%log, 'plot', 'cannot write the gnuplot script ' // gp // ': no ' // base // '.png')
      return
    end if
    argv = gnuplot // c_null_char // gp // c_null_char
    if (c2d_run_program(argv, 2_c_int, log // c_null_char, real(gnuplot_timeout, c_double), how, status) /= 0) continue
    why = ''
    select case (how)
    case (c2d_run_timeout)
      why = 'gnuplot did not finish within ' // real_to_str(gnuplot_timeout) // ' s'
    case (c2d_run_signaled)
      why = 'gnuplot was killed by signal ' // int_to_str(int(status))
    case (c2d_run_exited)
      if (status /= 0) why = 'gnuplot failed with exit status ' // int_to_str(int(status)) // first_line(log)
    case default
      why = 'cannot run ' // gnuplot // ' (error ' // int_to_str(int(status)) // ')'
    end select
    if (len(why) == 0) then
      kind = file_kind(png)
      call read_file(png, bytes, st)
      if (kind /= c2d_regular) st = 4
      if (st /= 0) then
        why = 'gnuplot wrote no picture' // first_line(log)
      else if (len(bytes) < 8) then
        why = 'gnuplot wrote an empty picture' // first_line(log)
      end if
    end if
    if (len(why) > 0) then
      call add_warning(run%log, 'plot', why // ': no ' // base // '.png (the other outputs are written)')
      return
    end if
    ios = 0
    call create_temporary(run%opts%outdir, base // '.png', t(1), err)
    if (.not. allocated(err)) then
      open(newunit=u, file=t(1)%io_path, access='stream', form='unformatted', status='replace', action='write', &
           iostat=ios)
      if (ios == 0) write(u, iostat=ios) bytes
      if (ios == 0) close(u, iostat=ios)
    end if
    if (allocated(err) .or. ios /= 0) then
      call add_warning(run%log, 'plot', run%opts%outdir // ': cannot write ' // base // '.png')
      call close_temporary(t(1))
      call discard_temporaries(t)
      return
    end if
    call grow_temporaries(tmp, 1)
    tmp(size(tmp)) = t(1)
    if (len(names) > 0) names = names // ', '
    names = names // base // '.png'
  end subroutine draw

  !> The script of STEM_pressure.png: a panel per pair, the pressure against
  !> the arc length s along the slave boundary (and with friction the shear
  !> on a second axis), over the zone in contact and a margin either side.
  !> The pressure axis starts at 0; the shear's holds 0, and a shear that is
  !> round-off against the pair's largest pressure or shear is drawn flat
  !> (plot_text's rule).
  !>   run    (in)  the scene (pairs, PLANE, TITLE)
  !>   table  (in)  the contact table's path, written
  !>   png    (in)  the picture's path
  !>   script (out) '' when the table cannot be read
  subroutine pressure_script(run, table, png, script)
    type(run_t), intent(in) :: run
    character(len=*), intent(in) :: table, png
    character(len=:), allocatable, intent(out) :: script
    character(len=:), allocatable :: buf, header, line, shear, unit
    real(dp), allocatable :: s_all(:, :), s_zone(:, :), p_max(:), t_range(:, :), t_sum(:)
    integer, allocatable :: rows(:)
    real(dp) :: s, a, b, margin, pressure, t, scale
    integer :: npair, st, k, status
    integer(i8) :: p, q
    logical :: friction
    character(len=*), parameter :: nl = achar(10)

    script = ''
    npair = run%prob%cs%npair
    if (npair <= 0) return
    call read_file(table, buf, st)
    if (st /= 0) return
    ! s_all: the pair's s range; s_zone: that of its rows in contact (error_numerical);
    ! p_max, t_range, t_sum: its largest pressure, its shear's range and sum
    allocate(s_all(2, npair), s_zone(2, npair), t_range(2, npair), p_max(npair), t_sum(npair), rows(npair))
    s_all(1, :) = huge(1.0_dp)
    s_all(2, :) = -huge(1.0_dp)
    s_zone = s_all
    t_range = s_all
    p_max = 0.0_dp
    t_sum = 0.0_dp
    rows = 0
    header = ''
    friction = .false.
    p = 1
    do while (p <= len(buf, kind=i8))
      q = index(buf(p:), nl, kind=i8)
      if (q == 0) q = len(buf, kind=i8) - p + 2
      line = buf(p:p + q - 2)
      p = p + q
      if (len(header) == 0) then
        header = line
        friction = index(header, ',shear,') > 0
        cycle
      end if
      call read_row(line, friction, k, s, status, pressure, t)
      if (k < 1 .or. k > npair) cycle
      s_all(:, k) = [min(s_all(1, k), s), max(s_all(2, k), s)]
      if (status == 1) s_zone(:, k) = [min(s_zone(1, k), s), max(s_zone(2, k), s)]
      p_max(k) = max(p_max(k), abs(pressure))
      t_range(:, k) = [min(t_range(1, k), t), max(t_range(2, k), t)]
      t_sum(k) = t_sum(k) + t
      rows(k) = rows(k) + 1
    end do

    unit = pressure_unit(run%prob%deck)
    script = terminal_lines(900, 90 + 300 * npair, png) // &
             'set datafile separator '','' ' // nl // &
             'set grid' // nl // &
             'set key top right' // nl // &
             'set multiplot layout ' // int_to_str(npair) // ',1 title ' // &
             gnuplot_string(title_text(run, 'contact pressure along the slave boundary')) // nl // &
             'set xlabel ''s, arc length along the slave boundary (length)''' // nl // &
             'set ylabel ' // gnuplot_string('contact pressure (' // unit // ')') // nl // &
             'set yrange [0:*]' // nl
    if (friction) script = script // 'set ytics nomirror' // nl // 'set y2tics' // nl // &
                           'set y2label ' // gnuplot_string('shear (' // unit // ')') // nl
    do k = 1, npair
      if (s_all(1, k) > s_all(2, k)) cycle              ! no row: the table is not the one expected
      if (s_zone(1, k) <= s_zone(2, k)) then
        a = s_zone(1, k)
        b = s_zone(2, k)
        margin = 0.5_dp * (b - a)
        if (margin <= 0.0_dp) margin = 0.05_dp * (s_all(2, k) - s_all(1, k))
        a = max(s_all(1, k), a - margin)
        b = min(s_all(2, k), b + margin)
      else
        a = s_all(1, k)
        b = s_all(2, k)
      end if
      if (b <= a) b = a + 1.0_dp
      if (s_zone(1, k) > s_zone(2, k)) then
        script = script // 'set title ''pair ' // int_to_str(k) // ' (no node in contact)''' // nl
      else
        script = script // 'set title ''pair ' // int_to_str(k) // '''' // nl
      end if
      script = script // 'set xrange [' // exact_to_str(a) // ':' // exact_to_str(b) // ']' // nl
      ! the shear's axis holds 0 too; a round-off shear is drawn flat, at its mean
      shear = '$9'
      if (friction) then
        scale = max(p_max(k), abs(t_range(1, k)), abs(t_range(2, k)))
        if (is_flat(t_range(1, k), t_range(2, k), scale)) then
          shear = '(' // exact_to_str(t_sum(k) / rows(k)) // ')'
          script = script // 'set y2range ' // flat_range(t_sum(k) / rows(k), t_sum(k) / rows(k), scale) // nl
        else
          script = script // 'set y2range [*<0:0<*]' // nl
        end if
      end if
      script = script // &
               'plot ' // gnuplot_string(table) // ' skip 1 using 2:($1 == ' // int_to_str(k) // ' ? $7 : NaN) ' // &
               'with linespoints lw 2 pt 7 ps 0.6 title ''pressure'''
      if (friction) script = script // ', '''' skip 1 using 2:($1 == ' // int_to_str(k) // ' ? ' // shear // ' : NaN) ' // &
                             'axes x1y2 with linespoints lw 2 pt 5 ps 0.5 title ''shear'''
      script = script // nl
    end do
    script = script // 'unset multiplot' // nl // 'set output' // nl
  end subroutine pressure_script

  !> The pair, the arc length s, the status, the pressure and (with
  !> friction) the shear of a contact table row (columns 1, 2, 8, 7, 9);
  !> k = 0 when the row does not read.
  subroutine read_row(line, friction, k, s, status, pressure, shear)
    character(len=*), intent(in) :: line
    logical, intent(in) :: friction
    integer, intent(out) :: k, status
    real(dp), intent(out) :: s, pressure, shear
    character(len=:), allocatable :: field
    integer :: ios
    k = 0
    s = 0.0_dp
    status = -1
    pressure = 0.0_dp
    shear = 0.0_dp
    field = csv_field(line, 1)
    read(field, *, iostat=ios) k
    field = csv_field(line, 2)
    if (ios == 0) read(field, *, iostat=ios) s
    field = csv_field(line, 8)
    if (ios == 0) read(field, *, iostat=ios) status
    field = csv_field(line, 7)
    if (ios == 0) read(field, *, iostat=ios) pressure
    field = csv_field(line, 9)
    if (ios == 0 .and. friction) read(field, *, iostat=ios) shear
    if (ios /= 0) k = 0
  end subroutine read_row


  !> ': ' and the first line of gnuplot's log (printable), '' when empty.
  function first_line(log) result(text)
    character(len=*), intent(in) :: log
    character(len=:), allocatable :: text
    character(len=:), allocatable :: buf
    integer :: st, q
    text = ''
    call read_file(log, buf, st)
    if (st /= 0) return
    buf = adjustl(buf)
    q = index(buf, achar(10))
    if (q == 1) return
    if (q > 0) buf = buf(1:q - 1)
    if (len_trim(buf) == 0) return
    text = ': ' // trim(printable(buf(1:min(len(buf), 200))))
  end function first_line

end module run_plots
