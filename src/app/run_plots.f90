!> run_plots: the pictures of a run (OUTPUT plot=png; doc/outputs.md,
!> "Pictures"): STEM_pressure.png, the contact pressure (and with friction
!> the shear) along the slave boundary of each pair, read from the contact
!> table just written, and with steps=all STEM_steps.png, each pair's contact
!> resultant (and the support reactions) against the load factor, read from
!> STEM_steps.csv.
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
  implicit none
  private
  public :: draw_plots

  real(dp), parameter :: gnuplot_timeout = 60.0_dp   !< seconds gnuplot may take for one picture
  integer, parameter :: most_reactions = 4           !< more FIX boundaries than this: no reaction panel

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
  !>   script (out) '' when the table cannot be read
  subroutine pressure_script(run, table, png, script)
    type(run_t), intent(in) :: run
    character(len=*), intent(in) :: table, png
    character(len=:), allocatable, intent(out) :: script
    character(len=:), allocatable :: buf, header, line
    real(dp), allocatable :: s_all(:, :), s_zone(:, :)
    real(dp) :: s, a, b, margin
    integer :: npair, st, k, status
    integer(i8) :: p, q
    logical :: friction
    character(len=*), parameter :: nl = achar(10)

    script = ''
    npair = run%prob%cs%npair
    if (npair <= 0) return
    call read_file(table, buf, st)
    if (st /= 0) return
    ! s_all: the pair's s range; s_zone: that of its rows in contact (error_numerical)
    allocate(s_all(2, npair), s_zone(2, npair))
    s_all(1, :) = huge(1.0_dp)
    s_all(2, :) = -huge(1.0_dp)
    s_zone = s_all
    header = ''
    p = 1
    do while (p <= len(buf, kind=i8))
      q = index(buf(p:), nl, kind=i8)
      if (q == 0) q = len(buf, kind=i8) - p + 2
      line = buf(p:p + q - 2)
      p = p + q
      if (len(header) == 0) then
        header = line
        cycle
      end if
      call read_row(line, k, s, status)
      if (k < 1 .or. k > npair) cycle
      s_all(:, k) = [min(s_all(1, k), s), max(s_all(2, k), s)]
      if (status == 1) s_zone(:, k) = [min(s_zone(1, k), s), max(s_zone(2, k), s)]
    end do
    friction = index(header, ',shear,') > 0

    script = terminal_lines(900, 90 + 300 * npair, png) // &
             'set datafile separator '','' ' // nl // &
             'set grid' // nl // &
             'set key top right' // nl // &
             'set multiplot layout ' // int_to_str(npair) // ',1 title ' // &
             gnuplot_string(title_text(run, 'contact pressure along the slave boundary')) // nl // &
             'set xlabel ''s, arc length along the slave boundary''' // nl // &
             'set ylabel ''contact pressure (force per unit length)''' // nl // &
             'set yrange [0:*]' // nl
    ! the shear's axis holds 0 too: a uniform shear is not drawn as round-off
    if (friction) script = script // 'set ytics nomirror' // nl // 'set y2tics' // nl // 'set y2range [*<0:0<*]' // nl // &
                           'set y2label ''shear (force per unit length)''' // nl
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
      script = script // 'set xrange [' // exact_to_str(a) // ':' // exact_to_str(b) // ']' // nl // &
               'plot ' // gnuplot_string(table) // ' skip 1 using 2:($1 == ' // int_to_str(k) // ' ? $7 : NaN) ' // &
               'with linespoints lw 2 pt 7 ps 0.6 title ''pressure'''
      if (friction) script = script // ', '''' skip 1 using 2:($1 == ' // int_to_str(k) // ' ? $9 : NaN) ' // &
                             'axes x1y2 with linespoints lw 2 pt 5 ps 0.5 title ''shear'''
      script = script // nl
    end do
    script = script // 'unset multiplot' // nl // 'set output' // nl
  end subroutine pressure_script

  !> The script of STEM_steps.png: each pair's contact resultant (fx, fy)
  !> against the load factor of the default ramp (the table's second column),
  !> and in a second panel the reactions when at most most_reactions
  !> boundaries are held.
  !>   script (out) '' when the table cannot be read or has nothing to draw
  subroutine steps_script(run, table, png, script)
    type(run_t), intent(in) :: run
    character(len=*), intent(in) :: table, png
    character(len=:), allocatable, intent(out) :: script
    character(len=:), allocatable :: buf, header, name, forces, reactions
    integer :: st, c, p, q, nforce, nreaction
    character(len=*), parameter :: nl = achar(10)

    script = ''
    call read_file(table, buf, st)
    if (st /= 0) return
    q = index(buf, nl)
    if (q == 0) return
    header = buf(1:q - 1)
    ! the header's columns, in order: step, factor_..., ...
    forces = ''
    reactions = ''
    nforce = 0
    nreaction = 0
    c = 0
    p = 1
    do while (p <= len(header))
      q = index(header(p:), ',')
      if (q == 0) q = len(header) - p + 2
      name = header(p:p + q - 2)
      p = p + q
      c = c + 1
      if (starts_with(name, 'contact_force_') .and. (ends_with(name, '_fx') .or. ends_with(name, '_fy'))) then
        nforce = nforce + 1
        forces = forces // plot_item(table, c, name, nforce == 1)
      else if (starts_with(name, 'reaction_') .and. (ends_with(name, '_fx') .or. ends_with(name, '_fy'))) then
        nreaction = nreaction + 1
        reactions = reactions // plot_item(table, c, name, nreaction == 1)
      end if
    end do
    if (c < 2 .or. .not. starts_with(header_column(header, 2), 'factor_')) return
    if (nreaction > 2 * most_reactions) nreaction = 0
    if (nforce == 0 .and. nreaction == 0) return

    script = terminal_lines(900, merge(760, 440, nforce > 0 .and. nreaction > 0), png) // &
             'set datafile separator '','' ' // nl // &
             'set grid' // nl // &
             'set key outside right' // nl // &
             'set multiplot layout ' // merge('2', '1', nforce > 0 .and. nreaction > 0) // ',1 title ' // &
             gnuplot_string(title_text(run, 'forces against the load factor')) // nl // &
             'set xlabel ' // gnuplot_string('load factor (' // header_column(header, 2) // ')') // nl
    if (nforce > 0) script = script // 'set title ''contact resultant on the slave body of each pair''' // nl // &
                             'set ylabel ''force''' // nl // 'plot ' // forces // nl
    if (nreaction > 0) script = script // 'set title ''support reactions''' // nl // &
                                'set ylabel ''force''' // nl // 'plot ' // reactions // nl
    script = script // 'unset multiplot' // nl // 'set output' // nl
  end subroutine steps_script

  !> One curve of a plot command: column c of the table against column 2.
  function plot_item(table, c, name, first) result(item)
    character(len=*), intent(in) :: table, name
    integer, intent(in) :: c
    logical, intent(in) :: first
    character(len=:), allocatable :: item
    item = ''
    if (.not. first) item = ', '
    item = item // gnuplot_string(table) // ' skip 1 using 2:' // int_to_str(c) // ' with linespoints lw 2 pt 7 ps 0.6 ' // &
           merge('dt 2', 'dt 1', ends_with(name, '_fx')) // ' title ' // gnuplot_string(name)
  end function plot_item

  !> The terminal: pngcairo when this gnuplot has it (smoother lines), else png.
  function terminal_lines(width, height, png) result(text)
    integer, intent(in) :: width, height
    character(len=*), intent(in) :: png
    character(len=:), allocatable :: text
    character(len=*), parameter :: nl = achar(10)
    text = 'if (strstrt(GPVAL_TERMINALS, ''pngcairo'') > 0) {' // nl // &
           '  set terminal pngcairo size ' // int_to_str(width) // ',' // int_to_str(height) // &
           ' noenhanced font ''sans,10''' // nl // &
           '} else {' // nl // &
           '  set terminal png size ' // int_to_str(width) // ',' // int_to_str(height) // ' noenhanced' // nl // &
           '}' // nl // &
           'set output ' // gnuplot_string(png) // nl
  end function terminal_lines

  !> The deck's TITLE, then what the picture shows.
  function title_text(run, what) result(text)
    type(run_t), intent(in) :: run
    character(len=*), intent(in) :: what
    character(len=:), allocatable :: text
    text = what
    if (allocated(run%prob%deck%title)) then
      if (len_trim(run%prob%deck%title) > 0) text = trim(run%prob%deck%title) // ': ' // what
    end if
  end function title_text

  !> s as a gnuplot single-quoted string: nothing inside is substituted (no
  !> backquote command, no macro), a quote is written twice, and control
  !> characters (a line's end would end the command) are dropped.
  pure function gnuplot_string(s) result(q)
    character(len=*), intent(in) :: s
    character(len=:), allocatable :: q
    integer :: i, c
    q = ''''
    do i = 1, len(s)
      c = iachar(s(i:i))
      if (c < 32 .or. c == 127) cycle
      if (s(i:i) == '''') then
        q = q // ''''''
      else
        q = q // s(i:i)
      end if
    end do
    q = q // ''''
  end function gnuplot_string

  !> The pair, the arc length s and the status of a contact table row
  !> (columns 1, 2 and 8); k = 0 when the row does not read.
  subroutine read_row(line, k, s, status)
    character(len=*), intent(in) :: line
    integer, intent(out) :: k, status
    real(dp), intent(out) :: s
    character(len=:), allocatable :: field
    integer :: ios
    k = 0
    s = 0.0_dp
    status = -1
    field = header_column(line, 1)
    read(field, *, iostat=ios) k
    field = header_column(line, 2)
    if (ios == 0) read(field, *, iostat=ios) s
    field = header_column(line, 8)
    if (ios == 0) read(field, *, iostat=ios) status
    if (ios /= 0) k = 0
  end subroutine read_row

  !> The n-th comma-separated field of line ('' when it has fewer).
  function header_column(line, n) result(field)
    character(len=*), intent(in) :: line
    integer, intent(in) :: n
    character(len=:), allocatable :: field
    integer :: p, q, c
    field = ''
    p = 1
    do c = 1, n
      if (p > len(line) + 1) return
      q = index(line(p:), ',')
      if (q == 0) q = len(line) - p + 2
      if (c == n) field = line(p:p + q - 2)
      p = p + q
    end do
  end function header_column


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

  pure logical function starts_with(s, prefix)
    character(len=*), intent(in) :: s, prefix
    starts_with = len(s) >= len(prefix)
    if (starts_with) starts_with = s(1:len(prefix)) == prefix
  end function starts_with

  pure logical function ends_with(s, suffix)
    character(len=*), intent(in) :: s, suffix
    ends_with = len(s) >= len(suffix)
    if (ends_with) ends_with = s(len(s) - len(suffix) + 1:) == suffix
  end function ends_with

end module run_plots
