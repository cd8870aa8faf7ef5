!> plot_text: the pieces every gnuplot script of a run is made of (doc/outputs.md,
!> "Pictures"): the terminal, strings that gnuplot takes as text and never as
!> commands, the picture's title, the axis labels with the units of the
!> deck's plane, and the rule that keeps round-off from being drawn as a trend.
!>
!> Units follow the plane (doc/deck.md, "Units and the plane stress
!> thickness"): in plane strain every force is per unit thickness and the
!> contact pressure a force per unit length of the contact line (per unit
!> thickness); in plane stress both are for the whole thickness T; in
!> axisymmetric analysis forces are for the full circle (integrated over
!> 2 pi r) and the contact pressure is a force per unit area.
!>
!> Round-off: a series whose values vary over the steps by no more than
!> flat_tol times the scale of its axis (the largest |value| drawn on it, its
!> own included) is drawn flat, at its mean; an axis whose series are all flat
!> spans 0 and the values with a margin of a tenth of the scale (flat_range),
!> instead of gnuplot's autoscale blowing the 1e-12 wiggles up to the axis.
!>
!> Programming interface
!>   gnuplot_string(s)             s as a single-quoted gnuplot string (nothing substituted)
!>   terminal_lines(w, h, png)     the terminal and output lines of a w x h picture
!>   title_text(run, what)         the deck's TITLE, then what the picture shows
!>   csv_field(line, n)            the n-th comma-separated field of line
!>   force_unit(deck)              what a force is for in this plane ('per unit thickness' ...)
!>   pressure_unit(deck)           what a contact pressure is in this plane
!>   column_label(name, deck)      the axis label of a steps-table column, with its unit
!>   is_flat(vmin, vmax, scale)    the round-off rule (flat_tol)
!>   flat_range(vmin, vmax, scale) '[lo:hi]' of an axis whose series are all flat
module plot_text
  use kinds, only: dp
  use strings, only: int_to_str, format_number, exact_to_str, starts_with, ends_with
  use deck_types, only: deck_t
  use run_state, only: run_t
  implicit none
  private
  public :: gnuplot_string, terminal_lines, title_text, csv_field
  public :: force_unit, pressure_unit, column_label, is_flat, flat_range

  !> relative variation at or below which a series is round-off, not a
  !> trend: the steps' results agree to some 1e-13 of their scale when
  !> nothing changes (each step is its own solve); a real change of a
  !> plotted force is far above 1e-9 of the largest
  real(dp), parameter :: flat_tol = 1.0e-9_dp

contains

  !> s as a gnuplot single-quoted string: nothing inside is substituted (no
  !> backquote command, no macro), a quote is written twice, and control
  !> characters (a line's end would end the command) are dropped.
  !>   s (in) the text, from the deck or the file system
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

  !> The terminal: pngcairo when this gnuplot has it (smoother lines), else png.
  !>   width, height (in) the picture's size in pixels
  !>   png           (in) the picture's path
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
  !>   run  (in) the deck
  !>   what (in) what the picture shows
  function title_text(run, what) result(text)
    type(run_t), intent(in) :: run
    character(len=*), intent(in) :: what
    character(len=:), allocatable :: text
    text = what
    if (allocated(run%prob%deck%title)) then
      if (len_trim(run%prob%deck%title) > 0) text = trim(run%prob%deck%title) // ': ' // what
    end if
  end function title_text

  !> The n-th comma-separated field of line ('' when it has fewer).
  function csv_field(line, n) result(field)
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
  end function csv_field

  !> What a force of the outputs is for, in the deck's plane (module header):
  !> 'per unit thickness', 'for the thickness T', 'full circle'.
  !>   deck (in) its PLANE
  function force_unit(deck) result(text)
    type(deck_t), intent(in) :: deck
    character(len=:), allocatable :: text
    if (deck%axisymmetric) then
      text = 'full circle'
    else if (deck%plane_stress) then
      text = 'for the thickness ' // format_number(deck%thickness)
    else
      text = 'per unit thickness'
    end if
  end function force_unit

  !> What the contact pressure (and shear) of the outputs is, in the deck's
  !> plane (module header).
  !>   deck (in) its PLANE
  function pressure_unit(deck) result(text)
    type(deck_t), intent(in) :: deck
    character(len=:), allocatable :: text
    if (deck%axisymmetric) then
      text = 'force per unit area'
    else
      text = 'force per unit length of the contact line, ' // force_unit(deck)
    end if
  end function pressure_unit

  !> The axis label of a column of NAME_steps.csv: its name and, in
  !> brackets, what it holds in the deck's units (doc/outputs.md, "Step table").
  !>   name (in) the column's name
  !>   deck (in) its PLANE
  function column_label(name, deck) result(text)
    character(len=*), intent(in) :: name
    type(deck_t), intent(in) :: deck
    character(len=:), allocatable :: text
    character(len=:), allocatable :: unit
    logical :: force_part, motion_part

    force_part = ends_with(name, '_fx') .or. ends_with(name, '_fy')
    motion_part = ends_with(name, '_ux') .or. ends_with(name, '_uy')
    if (name == 'step') then
      unit = 'load step'
    else if (starts_with(name, 'factor_')) then
      unit = 'load factor'
    else if (force_part .and. (starts_with(name, 'reaction_') .or. starts_with(name, 'contact_force_') .or. &
                               starts_with(name, 'spring_') .or. starts_with(name, 'rigid_'))) then
      unit = 'force ' // force_unit(deck)
    else if (starts_with(name, 'rigid_') .and. ends_with(name, '_m')) then
      unit = 'moment, force times length ' // force_unit(deck)
    else if (starts_with(name, 'rigid_') .and. ends_with(name, '_rz')) then
      unit = 'rotation, radians'
    else if (motion_part) then
      unit = 'displacement, length'
    else if (starts_with(name, 'peak_pressure_') .and. ends_with(name, '_p')) then
      unit = 'contact pressure, ' // pressure_unit(deck)
    else if (ends_with(name, '_count') .or. name == 'active_nodes' .or. name == 'lcp_iterations') then
      unit = 'count'
    else if (starts_with(name, 'certificate_')) then
      unit = 'relative'
    else
      unit = 'length'                        ! zone ends and lengths, peak and centre positions
    end if
    text = name // ' (' // unit // ')'
  end function column_label

  !> The round-off rule (module header): values from vmin to vmax on an
  !> axis of the given scale (the largest |value| drawn on it) are flat.
  pure logical function is_flat(vmin, vmax, scale)
    real(dp), intent(in) :: vmin, vmax, scale
    is_flat = vmax - vmin <= flat_tol * scale
  end function is_flat

  !> '[lo:hi]' of an axis whose series are all flat: 0 and the values
  !> vmin..vmax, with a margin of a tenth of the scale (the axis of an
  !> all-zero series: [-1:1]).
  function flat_range(vmin, vmax, scale) result(text)
    real(dp), intent(in) :: vmin, vmax, scale
    character(len=:), allocatable :: text
    real(dp) :: lo, hi
    if (scale <= 0.0_dp) then
      lo = -1.0_dp
      hi = 1.0_dp
    else
      lo = min(0.0_dp, vmin) - 0.1_dp * scale
      hi = max(0.0_dp, vmax) + 0.1_dp * scale
    end if
    text = '[' // exact_to_str(lo) // ':' // exact_to_str(hi) // ']'
  end function flat_range

end module plot_text
