!> steps_plot: the script of STEM_steps.png (OUTPUT steps=all plot=png;
!> doc/outputs.md, "Pictures"), the history of a load path read from
!> STEM_steps.csv: against the abscissa the deck chooses (OUTPUT x=COLUMN,
!> default the default ramp's load factor), a panel of contact forces (each
!> pair's resultant on its slave body, each RIGID's contact force), a panel
!> of supports (the reactions of the FIX boundaries and the SPRINGs' forces,
!> when at most most_supports boundaries of each), a panel of the RIGIDs'
!> motions (ux, uy; rz on the right axis).  Every label says its unit in the
!> deck's plane, and round-off is drawn flat (plot_text's rule).
!>
!> Why it exists: the history's columns are the scene's (named by
!> step_table), the round-off rule needs the values, and an unknown x=
!> must stop the run before it solves: one module knows the three.
!>
!> Programming interface
!>   check_plot_column(prob, diag)      OUTPUT x=: an input error (at the OUTPUT line) when
!>                                      the steps table has no such column; the columns listed
!>   steps_script(run, table, png, script)
!>                                      the gnuplot script drawing png from the table ('' when
!>                                      there is nothing to draw)
module steps_plot
  use kinds, only: dp, i8
  use strings, only: int_to_str, exact_to_str, starts_with, ends_with
  use errors, only: diag_t, add_error
  use problem, only: problem_t
  use step_table, only: step_header
  use safe_files, only: read_file
  use run_state, only: run_t
  use plot_text, only: gnuplot_string, terminal_lines, title_text, csv_field, force_unit, &
                       column_label, is_flat, flat_range
  implicit none
  private
  public :: check_plot_column, steps_script

  integer, parameter :: most_supports = 4     !< more FIX (or SPRING) boundaries than this: not drawn

  !> One curve of the picture and its values over the steps.
  type :: series_t
    integer :: column = 0                     !< 1-based column of the table
    integer :: panel = 0                      !< 1 contact forces, 2 supports, 3 rigid motions
    integer :: axis = 1                       !< 1 left axis, 2 right axis (rotations)
    real(dp) :: vmin = huge(1.0_dp), vmax = -huge(1.0_dp), total = 0.0_dp
    integer :: count = 0                      !< rows read
  end type series_t

contains

  !> OUTPUT x=COLUMN names a column of the steps table: else an input error
  !> at the OUTPUT line listing the columns.  The names are the scene's
  !> (step_table's step_header), known before anything is solved.
  !>   prob (in)    the problem, built
  !>   diag (inout) the error, added
  subroutine check_plot_column(prob, diag)
    type(problem_t), intent(in) :: prob
    type(diag_t), intent(inout) :: diag
    character(len=:), allocatable :: header
    if (.not. allocated(prob%deck%output%x)) return
    header = step_header(prob)
    if (column_index(header, prob%deck%output%x) > 0) return
    call add_error(diag, prob%deck%file, prob%deck%output%line, 'OUTPUT x=' // prob%deck%output%x // &
                   ': the steps table has no such column (expected one of ' // replace_commas(header) // ')')
  end subroutine check_plot_column

  !> The script of STEM_steps.png (module header).
  !>   run    (in)  the deck (x=, PLANE, TITLE)
  !>   table  (in)  the path of STEM_steps.csv, written
  !>   png    (in)  the picture's path
  !>   script (out) '' when the table cannot be read or has nothing to draw
  subroutine steps_script(run, table, png, script)
    type(run_t), intent(in) :: run
    character(len=*), intent(in) :: table, png
    character(len=:), allocatable, intent(out) :: script
    character(len=:), allocatable :: buf, header, name, xname
    type(series_t), allocatable :: ser(:)
    type(series_t) :: xs
    integer :: st, c, ncol, xcol, k, npanel, nreaction, nspring, panel
    logical :: drawn(3)
    character(len=*), parameter :: nl = achar(10)

    script = ''
    call read_file(table, buf, st)
    if (st /= 0) return
    k = index(buf, nl)
    if (k == 0) return
    header = buf(1:k - 1)
    ncol = count_fields(header)
    xcol = 2                                   ! the default ramp's load factor
    if (allocated(run%prob%deck%output%x)) xcol = column_index(header, run%prob%deck%output%x)
    if (xcol < 1 .or. ncol < 2) return
    xname = csv_field(header, xcol)
    ! the curves, panel by panel, the abscissa's own column left out
    allocate(ser(0))
    nreaction = 0
    nspring = 0
    do c = 1, ncol
      if (c == xcol) cycle
      name = csv_field(header, c)
      if (ends_with(name, '_fx') .or. ends_with(name, '_fy')) then
        if (starts_with(name, 'contact_force_') .or. starts_with(name, 'rigid_')) then
          ser = [ser, series_t(column=c, panel=1)]
        else if (starts_with(name, 'reaction_')) then
          ser = [ser, series_t(column=c, panel=2)]
          nreaction = nreaction + 1
        else if (starts_with(name, 'spring_')) then
          ser = [ser, series_t(column=c, panel=2)]
          nspring = nspring + 1
        end if
      else if (starts_with(name, 'rigid_') .and. (ends_with(name, '_ux') .or. ends_with(name, '_uy'))) then
        ser = [ser, series_t(column=c, panel=3)]
      else if (starts_with(name, 'rigid_') .and. ends_with(name, '_rz')) then
        ser = [ser, series_t(column=c, panel=3, axis=2)]
      end if
    end do
    ! too many boundaries for one panel to be read: that kind left out
    if (nreaction > 2 * most_supports) ser = pack(ser, .not. is_kind(ser, header, 'reaction_'))
    if (nspring > 2 * most_supports) ser = pack(ser, .not. is_kind(ser, header, 'spring_'))
    if (size(ser) == 0) return
    xs = series_t(column=xcol)
    call read_values(buf(k + 1:), ser, xs)
    if (xs%count == 0) return
    drawn = [(any(ser%panel == panel), panel = 1, 3)]
    npanel = count(drawn)

    script = terminal_lines(900, 80 + 340 * npanel, png) // &
             'set datafile separator '','' ' // nl // &
             'set grid' // nl // &
             'set key outside right' // nl // &
             'set multiplot layout ' // int_to_str(npanel) // ',1 title ' // &
             gnuplot_string(title_text(run, 'forces and motions against ' // xname)) // nl // &
             'set xlabel ' // gnuplot_string(column_label(xname, run%prob%deck)) // nl
    script = script // 'set xrange ' // axis_range([xs]) // nl
    do panel = 1, 3
      if (.not. drawn(panel)) cycle
      select case (panel)
      case (1)
        script = script // 'set title ''contact resultant on the slave body of each pair, contact force on each RIGID''' // &
                 nl // 'set ylabel ' // gnuplot_string('force (' // force_unit(run%prob%deck) // ')') // nl
      case (2)
        script = script // 'set title ''supports: reactions of the FIX boundaries, forces of the SPRINGs on the bodies''' // &
                 nl // 'set ylabel ' // gnuplot_string('force (' // force_unit(run%prob%deck) // ')') // nl
      case (3)
        script = script // 'set title ''RIGID motions of the reference point''' // nl // &
                 'set ylabel ''displacement (length)''' // nl
      end select
      script = script // 'set yrange ' // axis_range(pack(ser, ser%panel == panel .and. ser%axis == 1)) // nl
      if (any(ser%panel == panel .and. ser%axis == 2)) then
        script = script // 'set ytics nomirror' // nl // 'set y2tics' // nl // 'set y2label ''rotation (radians)''' // nl // &
                 'set y2range ' // axis_range(pack(ser, ser%panel == panel .and. ser%axis == 2)) // nl
      else
        script = script // 'set ytics mirror' // nl // 'unset y2tics' // nl // 'unset y2label' // nl
      end if
      script = script // 'plot '
      do c = 1, size(ser)
        if (ser(c)%panel /= panel) cycle
        if (.not. ends_with(script, 'plot ')) script = script // ', '
        script = script // plot_item(table, xcol, ser(c), ser, csv_field(header, ser(c)%column))
      end do
      script = script // nl
    end do
    script = script // 'unset multiplot' // nl // 'set output' // nl
  end subroutine steps_script

  !> One curve: column s%column against column xcol, at its mean when it
  !> is flat on its axis (the round-off rule).
  function plot_item(table, xcol, s, all, name) result(item)
    character(len=*), intent(in) :: table, name
    integer, intent(in) :: xcol
    type(series_t), intent(in) :: s, all(:)
    character(len=:), allocatable :: item
    real(dp) :: scale
    scale = axis_scale(pack(all, all%panel == s%panel .and. all%axis == s%axis))
    if (is_flat(s%vmin, s%vmax, scale)) then
      item = '(' // exact_to_str(s%total / s%count) // ')'
    else
      item = int_to_str(s%column)
    end if
    item = gnuplot_string(table) // ' skip 1 using ' // int_to_str(xcol) // ':' // item // &
           merge(' axes x1y2', '          ', s%axis == 2) // ' with linespoints lw 2 pt 7 ps 0.6 ' // &
           merge('dt 2', 'dt 1', ends_with(name, '_fx') .or. ends_with(name, '_ux')) // ' title ' // gnuplot_string(name)
  end function plot_item

  !> The scale of an axis: the largest |value| of its series.
  pure function axis_scale(ser) result(scale)
    type(series_t), intent(in) :: ser(:)
    real(dp) :: scale
    integer :: k
    scale = 0.0_dp
    do k = 1, size(ser)
      if (ser(k)%count > 0) scale = max(scale, abs(ser(k)%vmin), abs(ser(k)%vmax))
    end do
  end function axis_scale

  !> The range of an axis: '[*:*]' (gnuplot's autoscale) unless each of its
  !> series is flat on it, then plot_text's flat_range of their means.
  function axis_range(ser) result(text)
    type(series_t), intent(in) :: ser(:)
    character(len=:), allocatable :: text
    real(dp) :: scale, lo, hi, mean
    integer :: k
    scale = axis_scale(ser)
    lo = huge(1.0_dp)
    hi = -huge(1.0_dp)
    do k = 1, size(ser)
      if (ser(k)%count == 0) cycle
      if (.not. is_flat(ser(k)%vmin, ser(k)%vmax, scale)) then
        text = '[*:*]'
        return
      end if
      mean = ser(k)%total / ser(k)%count
      lo = min(lo, mean)
      hi = max(hi, mean)
    end do
    if (lo > hi) then
      lo = 0.0_dp
      hi = 0.0_dp
    end if
    text = flat_range(lo, hi, scale)
  end function axis_range

  !> The least, greatest and total value of each series' column and of the
  !> abscissa's, over the rows of the table (its header taken off).
  subroutine read_values(rows, ser, xs)
    character(len=*), intent(in) :: rows
    type(series_t), intent(inout) :: ser(:), xs
    integer, allocatable :: of_column(:)
    character(len=*), parameter :: nl = achar(10)
    integer(i8) :: p, q, e, f
    integer :: c, k, ios
    real(dp) :: v
    allocate(of_column(max(xs%column, maxval(ser%column))), source=0)
    do k = 1, size(ser)
      of_column(ser(k)%column) = k
    end do
    p = 1
    do while (p <= len(rows, kind=i8))
      q = index(rows(p:), nl, kind=i8)
      if (q == 0) q = len(rows, kind=i8) - p + 2
      e = p + q - 2                            ! the row is rows(p:e)
      c = 0
      f = p
      do while (f <= e + 1 .and. c < size(of_column))
        c = c + 1
        q = index(rows(f:e), ',', kind=i8)
        if (q == 0) q = e - f + 2
        if (of_column(c) > 0 .or. c == xs%column) then
          read(rows(f:f + q - 2), *, iostat=ios) v
          if (ios == 0) then
            if (c == xs%column) call take(xs, v)
            if (of_column(c) > 0) call take(ser(of_column(c)), v)
          end if
        end if
        f = f + q
      end do
      p = e + 2
    end do
  contains
    subroutine take(s, v)
      type(series_t), intent(inout) :: s
      real(dp), intent(in) :: v
      s%vmin = min(s%vmin, v)
      s%vmax = max(s%vmax, v)
      s%total = s%total + v
      s%count = s%count + 1
    end subroutine take
  end subroutine read_values

  !> Each series' column name starts with prefix.
  function is_kind(ser, header, prefix) result(yes)
    type(series_t), intent(in) :: ser(:)
    character(len=*), intent(in) :: header, prefix
    logical :: yes(size(ser))
    integer :: k
    do k = 1, size(ser)
      yes(k) = starts_with(csv_field(header, ser(k)%column), prefix)
    end do
  end function is_kind

  !> The 1-based column of header named name, 0 when none.
  function column_index(header, name) result(c)
    character(len=*), intent(in) :: header, name
    integer :: c, n
    n = count_fields(header)
    do c = 1, n
      if (csv_field(header, c) == name .and. len(csv_field(header, c)) == len(name)) return
    end do
    c = 0
  end function column_index

  !> The number of comma-separated fields of line.
  pure integer function count_fields(line)
    character(len=*), intent(in) :: line
    integer :: i
    count_fields = 1
    do i = 1, len(line)
      if (line(i:i) == ',') count_fields = count_fields + 1
    end do
  end function count_fields

  !> The header's names separated by ', '.
  pure function replace_commas(header) result(text)
    character(len=*), intent(in) :: header
    character(len=:), allocatable :: text
    integer :: i
    text = ''
    do i = 1, len(header)
      if (header(i:i) == ',') then
        text = text // ', '
      else
        text = text // header(i:i)
      end if
    end do
  end function replace_commas

end module steps_plot
