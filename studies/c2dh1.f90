!> c2dh1: broken H1 and energy-norm error of contact2d runs against a fine
!> reference (P1 triangle meshes; the same measure as `c2derr.py h1`, which
!> also takes Q1 cells, about a hundred times faster).
!>
!>   c2dh1 [-m E,nu ...] [--plane strain|stress] [--window x0,x1,y0,y1]
!>         REF.vtk RUN.vtk [RUN.vtk ...]
!>
!> For each run, with e = u_ref - u_h on every body B (CELL_DATA `body`):
!>   |e|_{1,h}^2 = sum_B int_B |grad e|^2,
!>   ||e||_E^2   = sum_B int_B sigma(e) : eps(e)
!>               = sum_B int_B lam (div e)^2 + 2 mu (e_xx^2 + e_yy^2) + mu g_xy^2,
!> integrated over the reference triangles.  grad u_ref and grad u_h are
!> constant on each piece T_ref & T_h, so the integral is exact: a reference
!> triangle inside one run triangle (nested meshes) takes one evaluation; a
!> cut one is clipped against every run triangle it meets (Sutherland-Hodgman
!> on the barycentric half-planes) and integrated piece by piece.  A part of a
!> reference triangle outside the run's body (a curved boundary meshed by
!> chords) takes the gradient of the nearest run triangle.  Run triangles are
!> found through a multi-level bucket grid (level L: buckets of side s0/2^L,
!> each triangle on the level just coarser than itself).
!>
!> Options
!>   -m E,nu        Young's modulus and Poisson ratio, one option per body in
!>                  body order; the last one serves the remaining bodies
!>                  (default 1,0: the energy norm is then the H1 seminorm)
!>   --plane P      stress: plane-stress lambda = 2 lam mu / (lam + 2 mu);
!>                  anything else: plane strain (the default)
!>   --window B     x0,x1,y0,y1: only the reference triangles whose centroid
!>                  lies in the box
!>
!> Output, one CSV line per run:
!>   run,h1,h1_rel,energy,energy_rel,nested,h1_body1,h1_body2,...
!> h1_rel and energy_rel are relative to the reference's own seminorm and
!> energy norm over the same region; nested is the share of reference
!> triangles lying inside one run triangle.  Exit status 0, or 2 on bad input
!> with `c2dh1: message` on stderr.
!>
!> The VTK reader takes the legacy ASCII files contact2d writes: POINTS, CELLS
!> (triangles only), CELL_TYPES, POINT_DATA VECTORS displacement, CELL_DATA
!> SCALARS body; every other SCALARS or VECTORS array is skipped.  Numbers are
!> read with the syntax of C strtod and correctly rounded: m 10^k with the
!> integer m < 2^53 and |k| <= 22 (the 10-digit numbers of contact2d) in one
!> floating-point operation, any other one through a Fortran internal read.
!>
!> There is no limit on the number of bodies, -m options or run files.
!>
!> Build:  gfortran -std=f2008 -O2 -J MODDIR -o c2dh1 c2dh1.f90
!> (studies/run-all adds the warning flags; MODDIR receives the two .mod files)
!>
!> Programming interface (this file only)
!>   module c2dh1_vtk      vtk_t, read_vtk, scan_number, stop_bad_input
!>   module c2dh1_overlap  run_body_t, lame_t, build_run_body, triangle_gradient,
!>                         locate_triangle, outside_distance, integrate_cut_triangle,
!>                         accumulate_error, energy_density, lame_constants
!>   program c2dh1         the command line, the loop over runs and bodies, the CSV

!> c2dh1_vtk: legacy ASCII VTK files of contact2d, strtod-compatible number
!> scanning, and the exit path for bad input.
module c2dh1_vtk
  use, intrinsic :: iso_c_binding, only: c_int
  use, intrinsic :: iso_fortran_env, only: dp => real64, il => int64, error_unit, output_unit
  use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_positive_inf, ieee_negative_inf, ieee_quiet_nan
  implicit none
  private
  public :: dp, il, vtk_t, read_vtk, scan_number, stop_bad_input

  !> One legacy VTK file of contact2d.
  type :: vtk_t
    integer :: npt = 0                   !< number of points
    integer :: ncell = 0                 !< number of cells (all triangles)
    real(dp), allocatable :: x(:, :)     !< (2, npt) coordinates
    real(dp), allocatable :: u(:, :)     !< (2, >= npt) displacement
    integer, allocatable :: tri(:, :)    !< (3, ncell) vertices, 1-based
    integer, allocatable :: body(:)      !< (>= ncell) 1-based body of each cell
  end type vtk_t

  !> 10^k, k = 0 ... 22: the powers of ten that are exact in real64.
  real(dp), parameter :: power_of_ten(0:22) = [1.0e0_dp, 1.0e1_dp, 1.0e2_dp, 1.0e3_dp, 1.0e4_dp, &
    1.0e5_dp, 1.0e6_dp, 1.0e7_dp, 1.0e8_dp, 1.0e9_dp, 1.0e10_dp, 1.0e11_dp, 1.0e12_dp, 1.0e13_dp, &
    1.0e14_dp, 1.0e15_dp, 1.0e16_dp, 1.0e17_dp, 1.0e18_dp, 1.0e19_dp, 1.0e20_dp, 1.0e21_dp, 1.0e22_dp]

  interface
    subroutine c_exit(status) bind(c, name="exit")
      import :: c_int
      integer(c_int), value :: status
    end subroutine c_exit
  end interface

contains

  !> Print `c2dh1: message arg` on stderr and exit with status 2.
  !>   message (in) what is wrong, ending with a blank when arg follows
  !>   arg     (in) the offending argument or file ('' for none)
  subroutine stop_bad_input(message, arg)
    character(len=*), intent(in) :: message, arg
    flush(output_unit)
    write(error_unit, '(a)') 'c2dh1: ' // message // arg
    flush(error_unit)
    call c_exit(2_c_int)
  end subroutine stop_bad_input

  !> The characters C isspace takes in the C locale: blank, \t, \n, \v, \f, \r.
  pure logical function is_space(c)
    character, intent(in) :: c
    is_space = c == ' ' .or. (iachar(c) >= 9 .and. iachar(c) <= 13)
  end function is_space

  !> The characters 0 ... 9.
  !> A signed decimal exponent starting at buf(j0) (after its 'e' or 'p'):
  !> its value in expo (digits beyond a magnitude of 100000 ignored) and the
  !> position after its last digit in next; expo = 0 and next = 0 when no
  !> digit follows the optional sign.
  pure subroutine read_exponent(buf, n, j0, expo, next)
    character(len=*), intent(in) :: buf
    integer(il), intent(in) :: n, j0
    integer(il), intent(out) :: expo, next
    integer(il) :: j
    logical :: negative
    expo = 0
    next = 0
    j = j0
    negative = buf(j:j) == '-'
    if (negative .or. buf(j:j) == '+') j = j + 1
    if (j > n) return
    if (.not. is_digit(buf(j:j))) return
    do
      if (j > n) exit
      if (.not. is_digit(buf(j:j))) exit
      if (expo < 100000) expo = 10 * expo + (iachar(buf(j:j)) - 48)
      j = j + 1
    end do
    if (negative) expo = -expo
    next = j
  end subroutine read_exponent

  pure logical function is_digit(c)
    character, intent(in) :: c
    is_digit = c >= '0' .and. c <= '9'
  end function is_digit

  !> c in lower case (ASCII letters only).
  pure character function lower(c)
    character, intent(in) :: c
    lower = c
    if (c >= 'A' .and. c <= 'Z') lower = achar(iachar(c) + 32)
  end function lower

  !> The whole file as one string.
  !>   path (in)  file name
  !>   buf  (out) its bytes, up to the first NUL byte if any
  !> Exits with status 2 when the file cannot be opened or read.
  subroutine read_whole_file(path, buf)
    character(len=*), intent(in) :: path
    character(len=:), allocatable, intent(out) :: buf
    integer :: unit, ios
    integer(il) :: n, k

    if (len(path) == 0) call stop_bad_input('cannot open ', path)
    open(newunit=unit, file=path, access='stream', form='unformatted', action='read', status='old', iostat=ios)
    if (ios /= 0) call stop_bad_input('cannot open ', path)
    inquire(unit=unit, size=n)
    if (n < 0) call stop_bad_input('cannot read ', path)
    allocate(character(len=n) :: buf)
    if (n > 0) then
      read(unit, iostat=ios) buf
      if (ios /= 0) call stop_bad_input('cannot read ', path)
    end if
    close(unit)
    k = index(buf, achar(0), kind=il)
    if (k > 0) buf = buf(1:k - 1)
  end subroutine read_whole_file

  !> The next blank-delimited word of buf at or after pos.
  !>   buf    (in)    the text
  !>   pos    (inout) on entry where to start; on exit just after the word
  !>   ws, we (out)   the word is buf(ws:we)
  !>   found  (out)   .false. when only white space is left (pos, ws, we then unchanged)
  subroutine next_word(buf, pos, ws, we, found)
    character(len=*), intent(in) :: buf
    integer(il), intent(inout) :: pos
    integer(il), intent(inout) :: ws, we
    logical, intent(out) :: found
    integer(il) :: n, i

    n = len(buf, kind=il)
    i = pos
    do
      if (i > n) exit
      if (.not. is_space(buf(i:i))) exit
      i = i + 1
    end do
    found = i <= n
    if (.not. found) return
    ws = i
    do
      if (i > n) exit
      if (is_space(buf(i:i))) exit
      i = i + 1
    end do
    we = i - 1
    pos = i
  end subroutine next_word

  !> Move pos to the next newline (or past the end).
  subroutine skip_line(buf, pos)
    character(len=*), intent(in) :: buf
    integer(il), intent(inout) :: pos
    integer(il) :: n

    n = len(buf, kind=il)
    do
      if (pos > n) exit
      if (buf(pos:pos) == achar(10)) exit
      pos = pos + 1
    end do
  end subroutine skip_line

  !> Scan one number at or after buf(pos:) with the syntax of C strtod: white
  !> space, an optional sign, then a decimal ([digits][.digits] with at least
  !> one digit, then [eE][+-]digits when digits follow), a hexadecimal (0x...,
  !> [pP][+-]digits), INF, INFINITY, NAN or NAN(chars), letters in any case.
  !>   buf   (in)    the text
  !>   pos   (inout) on entry where to start; on exit just after the number
  !>                 (unchanged when there is none)
  !>   value (out)   the number, correctly rounded for decimals (see the file header)
  !>   ok    (out)   .false. when no number starts there
  subroutine scan_number(buf, pos, value, ok)
    character(len=*), intent(in) :: buf
    integer(il), intent(inout) :: pos
    real(dp), intent(out) :: value
    logical, intent(out) :: ok
    integer(il), parameter :: max_exact = 9007199254740992_il   ! 2^53
    integer(il) :: n, i, j, start, m, dexp, expo, e10
    integer :: nsig, ndig, d, ios
    logical :: negative, truncated
    character :: c

    n = len(buf, kind=il)
    value = 0.0_dp
    ok = .false.
    i = pos
    do
      if (i > n) return
      if (.not. is_space(buf(i:i))) exit
      i = i + 1
    end do
    start = i
    negative = buf(i:i) == '-'
    if (negative .or. buf(i:i) == '+') i = i + 1
    if (i > n) return
    c = buf(i:i)

    if (c == '0' .and. i < n) then                    ! hexadecimal, else the decimal "0"
      if (lower(buf(i + 1:i + 1)) == 'x') then
        call scan_hexadecimal(buf, i + 2, j, value, ok)
        if (ok) then
          if (negative) value = -value
          pos = j
          return
        end if
      end if
    end if

    if (is_digit(c) .or. c == '.') then               ! decimal: m 10^dexp, m of <= 18 digits
      m = 0
      nsig = 0
      ndig = 0
      dexp = 0
      truncated = .false.
      do
        if (i > n) exit
        c = buf(i:i)
        if (.not. is_digit(c)) exit
        d = iachar(c) - 48
        ndig = ndig + 1
        if (nsig < 18) then
          if (m > 0 .or. d > 0) then
            m = 10 * m + d
            nsig = nsig + 1
          end if
        else
          dexp = dexp + 1
          if (d > 0) truncated = .true.
        end if
        i = i + 1
      end do
      if (i <= n) then
        if (buf(i:i) == '.') then
          i = i + 1
          do
            if (i > n) exit
            c = buf(i:i)
            if (.not. is_digit(c)) exit
            d = iachar(c) - 48
            ndig = ndig + 1
            if (nsig < 18) then
              if (m > 0 .or. d > 0) then
                m = 10 * m + d
                nsig = nsig + 1
              end if
              dexp = dexp - 1
            else if (d > 0) then
              truncated = .true.
            end if
            i = i + 1
          end do
        end if
      end if
      if (ndig == 0) return                            ! a lone "."
      expo = 0
      if (i < n) then                                  ! exponent, only when a digit follows
        if (lower(buf(i:i)) == 'e') then
          call read_exponent(buf, n, i + 1, expo, j)
          if (j > 0) i = j
        end if
      end if
      e10 = dexp + expo
      if (m == 0 .and. .not. truncated) then
        value = 0.0_dp
      else if (.not. truncated .and. m <= max_exact .and. abs(e10) <= 22) then
        if (e10 >= 0) then                             ! one rounding: exact m and 10^|e10|
          value = real(m, dp) * power_of_ten(e10)
        else
          value = real(m, dp) / power_of_ten(-e10)
        end if
      else
        read(buf(start:i - 1), *, iostat=ios) value
        if (ios /= 0) return
        negative = .false.
      end if
      if (negative) value = -value
      ok = .true.
      pos = i
      return
    end if

    if (i + 2 <= n) then                               ! INF, INFINITY, NAN, NAN(chars)
      if (lower(buf(i:i)) == 'i' .and. lower(buf(i + 1:i + 1)) == 'n' .and. lower(buf(i + 2:i + 2)) == 'f') then
        i = i + 3
        if (i + 4 <= n) then
          if (lower(buf(i:i)) == 'i' .and. lower(buf(i + 1:i + 1)) == 'n' .and. lower(buf(i + 2:i + 2)) == 'i' &
              .and. lower(buf(i + 3:i + 3)) == 't' .and. lower(buf(i + 4:i + 4)) == 'y') i = i + 5
        end if
        if (negative) then
          value = ieee_value(value, ieee_negative_inf)
        else
          value = ieee_value(value, ieee_positive_inf)
        end if
        ok = .true.
        pos = i
      else if (lower(buf(i:i)) == 'n' .and. lower(buf(i + 1:i + 1)) == 'a' .and. lower(buf(i + 2:i + 2)) == 'n') then
        i = i + 3
        if (i <= n) then
          if (buf(i:i) == '(') then
            j = i + 1
            do
              if (j > n) exit
              c = lower(buf(j:j))
              if (.not. (is_digit(c) .or. (c >= 'a' .and. c <= 'z') .or. c == '_')) exit
              j = j + 1
            end do
            if (j <= n) then
              if (buf(j:j) == ')') i = j + 1
            end if
          end if
        end if
        value = ieee_value(value, ieee_quiet_nan)
        ok = .true.
        pos = i
      end if
    end if
  end subroutine scan_number

  !> The hexadecimal digits of a C hexadecimal floating constant, after "0x".
  !>   buf   (in)  the text
  !>   first (in)  the character after "0x"
  !>   last  (out) just after the number
  !>   value (out) |number|; exact up to 15 significant hexadecimal digits
  !>   ok    (out) .false. when no hexadecimal digit follows
  subroutine scan_hexadecimal(buf, first, last, value, ok)
    character(len=*), intent(in) :: buf
    integer(il), intent(in) :: first
    integer(il), intent(out) :: last
    real(dp), intent(out) :: value
    logical, intent(out) :: ok
    integer(il) :: n, i, j, m, bexp, pexp
    integer :: ndig, nsig, d
    logical :: after_point

    n = len(buf, kind=il)
    i = first
    m = 0
    bexp = 0
    ndig = 0
    nsig = 0
    after_point = .false.
    do
      if (i > n) exit
      d = index('0123456789abcdef', lower(buf(i:i))) - 1
      if (d < 0) then
        if (buf(i:i) /= '.' .or. after_point) exit
        after_point = .true.
        i = i + 1
        cycle
      end if
      ndig = ndig + 1
      if (nsig < 15) then
        if (m > 0 .or. d > 0) then
          m = 16 * m + d
          nsig = nsig + 1
        end if
        if (after_point) bexp = bexp - 4
      else if (.not. after_point) then
        bexp = bexp + 4
      end if
      i = i + 1
    end do
    ok = ndig > 0
    value = 0.0_dp
    last = i
    if (.not. ok) return
    pexp = 0
    if (i < n) then
      if (lower(buf(i:i)) == 'p') then
        call read_exponent(buf, n, i + 1, pexp, j)
        if (j > 0) last = j
      end if
    end if
    if (m == 0) return
    bexp = bexp + pexp
    if (bexp > 1100) then
      value = ieee_value(value, ieee_positive_inf)
    else if (bexp >= -1200) then
      value = scale(real(m, dp), int(bexp))
    end if
  end subroutine scan_hexadecimal

  !> The next number of a file; exits with status 2 when there is none.
  subroutine next_number(buf, pos, path, value)
    character(len=*), intent(in) :: buf, path
    integer(il), intent(inout) :: pos
    real(dp), intent(out) :: value
    logical :: ok

    call scan_number(buf, pos, value, ok)
    if (.not. ok) call stop_bad_input('bad number in ', path)
  end subroutine next_number

  !> The next number of a file as a count (truncated toward zero, >= 0).
  subroutine next_count(buf, pos, path, count)
    character(len=*), intent(in) :: buf, path
    integer(il), intent(inout) :: pos
    integer(il), intent(out) :: count
    real(dp) :: v

    call next_number(buf, pos, path, v)
    if (.not. (v >= 0.0_dp .and. v < 4.0e18_dp)) call stop_bad_input('bad count in ', path)
    count = int(v, il)
  end subroutine next_count

  !> Read a legacy ASCII VTK file of contact2d.
  !>   path (in)  file name
  !>   m    (out) points, displacement, triangles and their bodies
  !> Exits with status 2 on a file that cannot be read, a bad number, a cell
  !> that is not a triangle, a missing section or inconsistent counts.
  subroutine read_vtk(path, m)
    character(len=*), intent(in) :: path
    type(vtk_t), intent(out) :: m
    character(len=:), allocatable :: buf
    character(len=:), allocatable :: name
    integer(il) :: p, q, ws, we, count, ncomp, i, k, npt, ncell
    integer :: section                   ! 1 point data, 2 cell data
    logical :: found, vec
    real(dp) :: v, skip

    call read_whole_file(path, buf)
    section = 0
    count = 0
    ws = 1
    we = 0
    p = 1
    call skip_line(buf, p)               ! # vtk DataFile Version
    if (p <= len(buf, kind=il)) p = p + 1
    call skip_line(buf, p)               ! title
    do
      call next_word(buf, p, ws, we, found)
      if (.not. found) exit
      select case (buf(ws:we))
      case ('POINTS')
        call next_count(buf, p, path, npt)
        if (npt > huge(m%npt)) call stop_bad_input('bad count in ', path)
        call next_word(buf, p, ws, we, found)          ! data type
        m%npt = int(npt)
        if (allocated(m%x)) deallocate(m%x)
        allocate(m%x(2, m%npt))
        do i = 1, npt
          call next_number(buf, p, path, m%x(1, i))
          call next_number(buf, p, path, m%x(2, i))
          call next_number(buf, p, path, skip)
        end do
      case ('CELLS')
        call next_count(buf, p, path, ncell)
        if (ncell > huge(m%ncell)) call stop_bad_input('bad count in ', path)
        call next_number(buf, p, path, skip)
        m%ncell = int(ncell)
        if (allocated(m%tri)) deallocate(m%tri)
        allocate(m%tri(3, m%ncell))
        do i = 1, ncell
          call next_number(buf, p, path, v)
          if (aint(v) /= 3.0_dp) call stop_bad_input('only triangles are supported (use c2derr.py h1 for quads): ', path)
          do k = 1, 3
            call next_number(buf, p, path, v)
            if (v >= 0.0_dp .and. v < 2147483647.0_dp) then
              m%tri(k, i) = int(v) + 1
            else
              m%tri(k, i) = 0
            end if
          end do
        end do
      case ('CELL_TYPES')
        call next_count(buf, p, path, count)
        do i = 1, count
          call next_number(buf, p, path, v)
          if (aint(v) /= 5.0_dp) call stop_bad_input('only triangles are supported: ', path)
        end do
      case ('POINT_DATA', 'CELL_DATA')
        section = merge(1, 2, buf(ws:ws) == 'P')
        call next_count(buf, p, path, count)
      case ('SCALARS', 'VECTORS')
        vec = buf(ws:ws) == 'V'
        ncomp = merge(3, 1, vec)
        name = ''
        call next_word(buf, p, ws, we, found)
        if (found) name = buf(ws:we)
        call next_word(buf, p, ws, we, found)          ! data type
        q = p                                          ! optional component count, same line
        do
          if (q > len(buf, kind=il)) exit
          if (buf(q:q) /= ' ' .and. buf(q:q) /= achar(9)) exit
          q = q + 1
        end do
        if (.not. vec .and. q <= len(buf, kind=il)) then
          if (is_digit(buf(q:q))) then
            call next_number(buf, p, path, v)
            ncomp = int(max(-1.0e9_dp, min(1.0e9_dp, v)), il)
          end if
        end if
        q = p
        call next_word(buf, q, ws, we, found)
        if (found) then
          if (buf(ws:we) == 'LOOKUP_TABLE') then
            p = q
            call next_word(buf, p, ws, we, found)      ! table name
          end if
        end if
        if (section == 1 .and. name == 'displacement') then
          if (count > huge(1)) call stop_bad_input('bad count in ', path)
          if (allocated(m%u)) deallocate(m%u)
          allocate(m%u(2, count))
          do i = 1, count
            call next_number(buf, p, path, m%u(1, i))
            call next_number(buf, p, path, m%u(2, i))
            do k = 3, ncomp
              call next_number(buf, p, path, skip)
            end do
          end do
        else if (section == 2 .and. name == 'body') then
          if (count > huge(1)) call stop_bad_input('bad count in ', path)
          if (allocated(m%body)) deallocate(m%body)
          allocate(m%body(count))
          do i = 1, count
            call next_number(buf, p, path, v)
            if (abs(v) < 2147483647.0_dp) then
              m%body(i) = int(v)
            else
              m%body(i) = 0
            end if
          end do
        else
          do i = 1, count * ncomp
            call next_number(buf, p, path, skip)
          end do
        end if
      end select
    end do
    if (.not. (allocated(m%x) .and. allocated(m%tri) .and. allocated(m%u) .and. allocated(m%body))) &
      call stop_bad_input('missing POINTS, CELLS, displacement or body in ', path)
    if (size(m%u, 2) < m%npt .or. size(m%body) < m%ncell) &
      call stop_bad_input('fewer displacement or body values than points or cells in ', path)
    if (m%ncell > 0) then
      if (minval(m%tri) < 1 .or. maxval(m%tri) > m%npt) call stop_bad_input('bad cell vertex in ', path)
    end if
  end subroutine read_vtk

end module c2dh1_vtk


!> c2dh1_overlap: the run triangles of one body with their bucket grid, point
!> location, clipping, and the error integrands.
module c2dh1_overlap
  use c2dh1_vtk, only: dp, il, vtk_t
  implicit none
  private
  public :: run_body_t, lame_t, build_run_body, triangle_gradient, locate_triangle, outside_distance
  public :: integrate_cut_triangle, accumulate_error, energy_density, lame_constants

  integer, parameter :: max_level = 24   !< finest bucket level

  !> One run triangle.
  type :: run_triangle_t
    real(dp) :: x0 = 0.0_dp, y0 = 0.0_dp                          !< first vertex
    real(dp) :: d11 = 0.0_dp, d12 = 0.0_dp, d21 = 0.0_dp, d22 = 0.0_dp  !< inverse Jacobian: (xi, eta) = D (x - x0)
    real(dp) :: g(4) = 0.0_dp                                      !< grad u_h: dux/dx, dux/dy, duy/dx, duy/dy
  end type run_triangle_t

  !> One level of the bucket grid, compressed rows; bucket (i, j), 0-based, is i nby + j.
  type :: grid_level_t
    real(dp) :: inv = 0.0_dp                 !< buckets per unit length
    integer(il) :: nbx = 0, nby = 0          !< buckets along x and y
    integer(il), allocatable :: start(:)     !< (0:nbx nby) first entry of each bucket in item
    integer, allocatable :: item(:)          !< (0:start(nbx nby) - 1) triangle indices (1-based)
  end type grid_level_t

  !> The triangles of one body of a run.
  type :: run_body_t
    integer :: n = 0                                 !< number of triangles
    type(run_triangle_t), allocatable :: t(:)        !< (n) the triangles
    real(dp) :: xmin = 0.0_dp, ymin = 0.0_dp         !< lower left corner of the grid
    integer :: nlev = 0                              !< levels 0 ... nlev - 1 are used
    type(grid_level_t) :: lev(0:max_level)           !< the bucket grid
    integer :: last = 1                              !< the triangle found last (search hint)
    integer(il), allocatable :: mark(:)              !< (n) scratch of integrate_cut_triangle
    integer(il) :: stamp = 0                         !< current mark value
  end type run_body_t

  !> Lame constants.
  type :: lame_t
    real(dp) :: lam = 0.0_dp, mu = 0.0_dp
  end type lame_t

contains

  !> grad u of the P1 triangle (a, b, c) and its inverse Jacobian D.
  !>   m   (in)  the mesh with its displacement
  !>   v   (in)  (3) vertices a, b, c (1-based)
  !>   d   (out) (4) D = J^-1 row by row: (xi, eta) = D (x - x_a)
  !>   g   (out) (4) grad u = (du/dxi, du/deta) D: dux/dx, dux/dy, duy/dx, duy/dy
  !>   det (out) det J (twice the signed area)
  subroutine triangle_gradient(m, v, d, g, det)
    type(vtk_t), intent(in) :: m
    integer, intent(in) :: v(3)
    real(dp), intent(out) :: d(4), g(4), det
    real(dp) :: a11, a12, a21, a22, dux1, dux2, duy1, duy2

    a11 = m%x(1, v(2)) - m%x(1, v(1))
    a12 = m%x(1, v(3)) - m%x(1, v(1))
    a21 = m%x(2, v(2)) - m%x(2, v(1))
    a22 = m%x(2, v(3)) - m%x(2, v(1))
    det = a11 * a22 - a12 * a21
    dux1 = m%u(1, v(2)) - m%u(1, v(1))
    dux2 = m%u(1, v(3)) - m%u(1, v(1))
    duy1 = m%u(2, v(2)) - m%u(2, v(1))
    duy2 = m%u(2, v(3)) - m%u(2, v(1))
    d(1) = a22 / det
    d(2) = -a12 / det
    d(3) = -a21 / det
    d(4) = a11 / det
    g(1) = dux1 * d(1) + dux2 * d(3)
    g(2) = dux1 * d(2) + dux2 * d(4)
    g(3) = duy1 * d(1) + duy2 * d(3)
    g(4) = duy1 * d(2) + duy2 * d(4)
  end subroutine triangle_gradient

  !> The triangles of body b of a run and their bucket grid.  Level L has
  !> buckets of side s0/2^L (s0 a little more than the largest triangle's
  !> bounding-box side); a triangle goes to L = floor(log2(s0 / its side)),
  !> where it meets at most 2 x 2 buckets, L <= max_level, and L lowered
  !> while the level's dense grid would exceed 2^24 buckets.
  !>   m (in)  the run
  !>   b (in)  the body (CELL_DATA body value)
  !>   r (out) its triangles, r%n = 0 when the run has none in body b
  subroutine build_run_body(m, b, r)
    type(vtk_t), intent(in) :: m
    integer, intent(in) :: b
    type(run_body_t), intent(out) :: r
    real(dp), allocatable :: box(:, :)   ! (4, n) xmin, xmax, ymin, ymax
    integer, allocatable :: lev(:)       ! (n) level of each triangle
    integer(il), allocatable :: fill(:)
    real(dp) :: s0, xmax, ymax, d(4), size, p2
    integer :: c, k, n, lv, pass
    integer(il) :: nb, i, j, i0, i1, j0, j1, bk

    n = count(m%body(1:m%ncell) == b)
    r%n = n
    allocate(r%t(n), box(4, n), lev(n), r%mark(n))
    r%mark = 0
    r%xmin = huge(1.0_dp)
    r%ymin = huge(1.0_dp)
    xmax = -huge(1.0_dp)
    ymax = -huge(1.0_dp)
    s0 = 0.0_dp
    k = 0
    do c = 1, m%ncell
      if (m%body(c) /= b) cycle
      k = k + 1
      associate (v => m%tri(:, c))
        call triangle_gradient(m, v, d, r%t(k)%g, size)
        r%t(k)%x0 = m%x(1, v(1))
        r%t(k)%y0 = m%x(2, v(1))
        r%t(k)%d11 = d(1)
        r%t(k)%d12 = d(2)
        r%t(k)%d21 = d(3)
        r%t(k)%d22 = d(4)
        box(1, k) = min(m%x(1, v(1)), m%x(1, v(2)), m%x(1, v(3)))
        box(2, k) = max(m%x(1, v(1)), m%x(1, v(2)), m%x(1, v(3)))
        box(3, k) = min(m%x(2, v(1)), m%x(2, v(2)), m%x(2, v(3)))
        box(4, k) = max(m%x(2, v(1)), m%x(2, v(2)), m%x(2, v(3)))
      end associate
      r%xmin = min(r%xmin, box(1, k))
      xmax = max(xmax, box(2, k))
      r%ymin = min(r%ymin, box(3, k))
      ymax = max(ymax, box(4, k))
      s0 = max(s0, max(box(2, k) - box(1, k), box(4, k) - box(3, k)))
    end do
    if (n == 0) return
    s0 = s0 * 1.000001_dp
    r%nlev = 0
    do k = 1, n
      size = max(max(box(2, k) - box(1, k), box(4, k) - box(3, k)), 1.0e-300_dp)
      lv = exponent(s0 / size) - 1                     ! floor(log2(s0 / size))
      if (lv > max_level) lv = max_level
      do                                               ! keep a level's dense grid below 2^24 buckets
        if (lv <= 0) exit
        p2 = real(2**lv, dp)
        if (((xmax - r%xmin) * p2 / s0 + 2.0_dp) * ((ymax - r%ymin) * p2 / s0 + 2.0_dp) <= 16777216.0_dp) exit
        lv = lv - 1
      end do
      lev(k) = lv
      if (lv + 1 > r%nlev) r%nlev = lv + 1
    end do
    do lv = 0, r%nlev - 1
      associate (q => r%lev(lv))
        q%inv = real(2**lv, dp) / s0
        q%nbx = int((xmax - r%xmin) * q%inv, il) + 1
        q%nby = int((ymax - r%ymin) * q%inv, il) + 1
        nb = q%nbx * q%nby
        allocate(q%start(0:nb), fill(0:nb - 1))
        q%start = 0
        fill = 0
        do pass = 0, 1                                 ! count, then fill
          do k = 1, n
            if (lev(k) /= lv) cycle
            i0 = int((box(1, k) - r%xmin) * q%inv, il)
            i1 = int((box(2, k) - r%xmin) * q%inv, il)
            j0 = int((box(3, k) - r%ymin) * q%inv, il)
            j1 = int((box(4, k) - r%ymin) * q%inv, il)
            if (i1 >= q%nbx) i1 = q%nbx - 1
            if (j1 >= q%nby) j1 = q%nby - 1
            do i = i0, i1
              do j = j0, j1
                bk = i * q%nby + j
                if (pass == 1) then
                  q%item(q%start(bk) + fill(bk)) = k
                  fill(bk) = fill(bk) + 1
                else
                  q%start(bk + 1) = q%start(bk + 1) + 1
                end if
              end do
            end do
          end do
          if (pass == 0) then
            do i = 0, nb - 1
              q%start(i + 1) = q%start(i + 1) + q%start(i)
            end do
            allocate(q%item(0:max(q%start(nb), 1_il) - 1))
          end if
        end do
        deallocate(fill)
      end associate
    end do
  end subroutine build_run_body

  !> How far (x, y) lies outside triangle t in barycentric terms (<= 0 inside):
  !> -min(xi, eta, 1 - xi - eta).
  pure real(dp) function outside_distance(t, x, y)
    type(run_triangle_t), intent(in) :: t
    real(dp), intent(in) :: x, y
    real(dp) :: dx, dy, xi, eta

    dx = x - t%x0
    dy = y - t%y0
    xi = t%d11 * dx + t%d12 * dy
    eta = t%d21 * dx + t%d22 * dy
    outside_distance = -min(xi, min(eta, 1.0_dp - xi - eta))
  end function outside_distance

  !> The run triangle holding (x, y), or the nearest one: the search hint,
  !> then the bucket of (x, y) on every level; failing that, the triangle the
  !> least outside among those seen, the 3 x 3 buckets around on every level,
  !> or (when these are all empty) all triangles.
  !>   r    (inout) the body (r%n > 0); r%last becomes k when (x, y) is inside
  !>   x, y (in)    the point
  !>   k    (out)   the triangle, 1 ... r%n
  subroutine locate_triangle(r, x, y, k)
    type(run_body_t), intent(inout) :: r
    real(dp), intent(in) :: x, y
    integer, intent(out) :: k
    real(dp), parameter :: tol = 1.0e-8_dp
    real(dp) :: bestout, o
    integer :: lv, best
    integer(il) :: i, j, i0, j0, bk, kk

    if (outside_distance(r%t(r%last), x, y) <= tol) then
      k = r%last
      return
    end if
    best = 0
    bestout = huge(1.0_dp)
    do lv = 0, r%nlev - 1
      associate (q => r%lev(lv))
        i = floor((x - r%xmin) * q%inv, il)
        j = floor((y - r%ymin) * q%inv, il)
        if (i < 0 .or. j < 0 .or. i >= q%nbx .or. j >= q%nby) cycle
        bk = i * q%nby + j
        do kk = q%start(bk), q%start(bk + 1) - 1
          o = outside_distance(r%t(q%item(kk)), x, y)
          if (o <= tol) then
            k = q%item(kk)
            r%last = k
            return
          end if
          if (o < bestout) then
            bestout = o
            best = q%item(kk)
          end if
        end do
      end associate
    end do
    ! inside no triangle: the nearest among the 3 x 3 buckets around, or all
    do lv = 0, r%nlev - 1
      associate (q => r%lev(lv))
        i0 = floor((x - r%xmin) * q%inv, il)
        j0 = floor((y - r%ymin) * q%inv, il)
        do i = i0 - 1, i0 + 1
          do j = j0 - 1, j0 + 1
            if (i < 0 .or. j < 0 .or. i >= q%nbx .or. j >= q%nby) cycle
            bk = i * q%nby + j
            do kk = q%start(bk), q%start(bk + 1) - 1
              o = outside_distance(r%t(q%item(kk)), x, y)
              if (o < bestout) then
                bestout = o
                best = q%item(kk)
              end if
            end do
          end do
        end do
      end associate
    end do
    if (best == 0) then
      do kk = 1, r%n
        o = outside_distance(r%t(kk), x, y)
        if (o < bestout) then
          bestout = o
          best = int(kk)
        end if
      end do
    end if
    k = best
  end subroutine locate_triangle
  !> Area of triangle (px, py) clipped by the half-planes lambda_k >= 0 of t
  !> (Sutherland-Hodgman: one pass per barycentric coordinate xi, eta,
  !> 1 - xi - eta; the polygon keeps at most 3 + 3 vertices).
  !>   t      (in) the run triangle
  !>   px, py (in) (3) the vertices of the reference triangle
  pure real(dp) function clipped_area(t, px, py)
    type(run_triangle_t), intent(in) :: t
    real(dp), intent(in) :: px(3), py(3)
    real(dp) :: ax(9), ay(9), bx(9), by(9), lam(9), dx, dy, xi, eta, s, area
    integer :: n, m, i, j, k

    clipped_area = 0.0_dp
    n = 3
    ax(1:3) = px
    ay(1:3) = py
    do k = 1, 3
      do i = 1, n
        dx = ax(i) - t%x0
        dy = ay(i) - t%y0
        xi = t%d11 * dx + t%d12 * dy
        eta = t%d21 * dx + t%d22 * dy
        select case (k)
        case (1)
          lam(i) = xi
        case (2)
          lam(i) = eta
        case default
          lam(i) = 1.0_dp - xi - eta
        end select
      end do
      m = 0
      do i = 1, n
        j = mod(i, n) + 1
        if (lam(i) >= 0.0_dp) then
          m = m + 1
          bx(m) = ax(i)
          by(m) = ay(i)
        end if
        if ((lam(i) >= 0.0_dp) .neqv. (lam(j) >= 0.0_dp)) then
          s = lam(i) / (lam(i) - lam(j))
          m = m + 1
          bx(m) = ax(i) + s * (ax(j) - ax(i))
          by(m) = ay(i) + s * (ay(j) - ay(i))
        end if
      end do
      if (m < 3) return
      n = m
      ax(1:n) = bx(1:n)
      ay(1:n) = by(1:n)
    end do
    area = 0.0_dp
    do i = 1, n                                        ! shoelace formula
      j = mod(i, n) + 1
      area = area + (ax(i) * ay(j) - ax(j) * ay(i))
    end do
    clipped_area = abs(area) / 2.0_dp
  end function clipped_area

  !> W(d) = lam (tr d)^2 + 2 mu (d_xx^2 + d_yy^2) + mu (d_xy + d_yx)^2 = sigma(d) : eps(d),
  !> d = (dux/dx, dux/dy, duy/dx, duy/dy).
  pure real(dp) function energy_density(d, c)
    real(dp), intent(in) :: d(4)
    type(lame_t), intent(in) :: c
    real(dp) :: tr, gxy

    tr = d(1) + d(4)
    gxy = d(2) + d(3)
    energy_density = c%lam * tr * tr + 2.0_dp * c%mu * (d(1) * d(1) + d(4) * d(4)) + c%mu * gxy * gxy
  end function energy_density

  !> e1 += w |g - gh|^2 and en += w W(g - gh).
  !>   g, gh  (in)    (4) the two gradients
  !>   w      (in)    the area of the piece
  !>   c      (in)    the material
  !>   e1, en (inout) the sums
  pure subroutine accumulate_error(g, gh, w, c, e1, en)
    real(dp), intent(in) :: g(4), gh(4), w
    type(lame_t), intent(in) :: c
    real(dp), intent(inout) :: e1, en
    real(dp) :: d(4)

    d = g - gh
    e1 = e1 + w * (d(1) * d(1) + d(2) * d(2) + d(3) * d(3) + d(4) * d(4))
    en = en + w * energy_density(d, c)
  end subroutine accumulate_error

  !> A cut reference triangle: its pieces in the run triangles it meets.
  !> First the triangles holding its vertices and centroid; when they do not
  !> cover it, every triangle of the buckets its bounding box meets; what is
  !> still uncovered lies outside the run's body and takes the gradient of the
  !> triangle nearest to the centroid.
  !>   r      (inout) the run body (search hint and marks)
  !>   px, py (in)    (3) the vertices of the reference triangle
  !>   area   (in)    its area
  !>   cx, cy (in)    its centroid
  !>   g      (in)    (4) grad u_ref on it
  !>   c      (in)    the material
  !>   e1, en (inout) the sums of accumulate_error
  subroutine integrate_cut_triangle(r, px, py, area, cx, cy, g, c, e1, en)
    type(run_body_t), intent(inout) :: r
    real(dp), intent(in) :: px(3), py(3), area, cx, cy, g(4)
    type(lame_t), intent(in) :: c
    real(dp), intent(inout) :: e1, en
    integer :: first(4), i, k, lv
    integer(il) :: i0, i1, j0, j1, ii, jj, kk, bk
    real(dp) :: covered, a, xlo, xhi, ylo, yhi

    covered = 0.0_dp
    xlo = min(px(1), px(2), px(3))
    xhi = max(px(1), px(2), px(3))
    ylo = min(py(1), py(2), py(3))
    yhi = max(py(1), py(2), py(3))
    r%stamp = r%stamp + 1
    call locate_triangle(r, px(1), py(1), first(1))
    call locate_triangle(r, px(2), py(2), first(2))
    call locate_triangle(r, px(3), py(3), first(3))
    call locate_triangle(r, cx, cy, first(4))
    do i = 1, 4
      k = first(i)
      if (r%mark(k) == r%stamp) cycle
      r%mark(k) = r%stamp
      a = clipped_area(r%t(k), px, py)
      if (a > 0.0_dp) then
        call accumulate_error(g, r%t(k)%g, a, c, e1, en)
        covered = covered + a
      end if
    end do
    if (covered >= area * (1.0_dp - 1.0e-9_dp)) return
    do lv = 0, r%nlev - 1
      associate (q => r%lev(lv))
        i0 = max(floor((xlo - r%xmin) * q%inv, il), 0_il)
        i1 = min(floor((xhi - r%xmin) * q%inv, il), q%nbx - 1)
        j0 = max(floor((ylo - r%ymin) * q%inv, il), 0_il)
        j1 = min(floor((yhi - r%ymin) * q%inv, il), q%nby - 1)
        do ii = i0, i1
          do jj = j0, j1
            bk = ii * q%nby + jj
            do kk = q%start(bk), q%start(bk + 1) - 1
              k = q%item(kk)
              if (r%mark(k) == r%stamp) cycle
              r%mark(k) = r%stamp
              a = clipped_area(r%t(k), px, py)
              if (a > 0.0_dp) then
                call accumulate_error(g, r%t(k)%g, a, c, e1, en)
                covered = covered + a
              end if
            end do
          end do
        end do
      end associate
    end do
    if (covered < area * (1.0_dp - 1.0e-9_dp)) &       ! outside the run's body: nearest triangle
      call accumulate_error(g, r%t(first(4))%g, area - covered, c, e1, en)
  end subroutine integrate_cut_triangle

  !> Lame constants of (E, nu): mu = E / (2 (1 + nu)), lam = E nu / ((1 + nu) (1 - 2 nu)),
  !> in plane stress lam* = 2 lam mu / (lam + 2 mu).
  pure function lame_constants(e, nu, plane_stress) result(c)
    real(dp), intent(in) :: e, nu
    logical, intent(in) :: plane_stress
    type(lame_t) :: c

    c%mu = e / (2.0_dp * (1.0_dp + nu))
    c%lam = e * nu / ((1.0_dp + nu) * (1.0_dp - 2.0_dp * nu))
    if (plane_stress) c%lam = 2.0_dp * c%lam * c%mu / (c%lam + 2.0_dp * c%mu)
  end function lame_constants

end module c2dh1_overlap


!> The program: options, then for every run and every body of the reference
!> the error sums over the reference triangles, one CSV line per run.
program c2dh1
  use, intrinsic :: iso_fortran_env, only: output_unit
  use, intrinsic :: ieee_arithmetic, only: ieee_is_nan, ieee_is_finite
  use c2dh1_vtk, only: dp, il, vtk_t, read_vtk, scan_number, stop_bad_input
  use c2dh1_overlap, only: run_body_t, lame_t, build_run_body, triangle_gradient, locate_triangle, &
    outside_distance, integrate_cut_triangle, accumulate_error, energy_density, lame_constants
  implicit none

  !> A string of its own length.
  type :: text_t
    character(len=:), allocatable :: s
  end type text_t

  character(len=*), parameter :: usage = 'usage: c2dh1 [-m E,nu ...] [--plane strain|stress] ' // &
    '[--window x0,x1,y0,y1] REF.vtk RUN.vtk [...]'
  character(len=*), parameter :: real_format = '(es16.6e3)'   ! rewritten as C "%.6e" by real_text
  type(text_t), allocatable :: files(:), grown_files(:)
  real(dp), allocatable :: emod(:), nu(:), grown(:), e1(:), en(:), r1(:), rn(:)
  real(dp) :: win(4), pair(2), px(3), py(3), d(4), g(4), det, area, cx, cy, s1, sn, t1, tn
  integer :: nmat, nfile, nbody, a, b, c, k, q, nargs, imat
  integer(il) :: ntri, nexact
  logical :: stress, use_window, ok, exact
  character(len=:), allocatable :: arg, line
  type(vtk_t) :: ref, run
  type(run_body_t) :: rb
  type(lame_t) :: mat

  allocate(emod(0), nu(0), files(0))
  nmat = 0
  nfile = 0
  stress = .false.
  use_window = .false.
  win = 0.0_dp
  nargs = command_argument_count()
  a = 1
  do while (a <= nargs)
    call get_argument(a, arg)
    if (arg == '-m' .and. len(arg) == 2 .and. a < nargs) then
      a = a + 1
      call get_argument(a, arg)
      call scan_list(arg, pair, ok)
      if (.not. ok) call stop_bad_input('bad -m ', arg)
      allocate(grown(nmat + 1))
      grown(1:nmat) = emod
      grown(nmat + 1) = pair(1)
      call move_alloc(grown, emod)
      allocate(grown(nmat + 1))
      grown(1:nmat) = nu
      grown(nmat + 1) = pair(2)
      call move_alloc(grown, nu)
      nmat = nmat + 1
    else if (arg == '--plane' .and. len(arg) == 7 .and. a < nargs) then
      a = a + 1
      call get_argument(a, arg)
      stress = arg == 'stress' .and. len(arg) == 6
    else if (arg == '--window' .and. len(arg) == 8 .and. a < nargs) then
      a = a + 1
      call get_argument(a, arg)
      call scan_list(arg, win, ok)
      if (.not. ok) call stop_bad_input('bad --window ', arg)
      use_window = .true.
    else if (len(arg) >= 2 .and. arg(1:1) == '-') then
      call stop_bad_input('unknown option ', arg)
    else
      allocate(grown_files(nfile + 1))
      do k = 1, nfile
        call move_alloc(files(k)%s, grown_files(k)%s)
      end do
      grown_files(nfile + 1)%s = arg
      call move_alloc(grown_files, files)
      nfile = nfile + 1
    end if
    a = a + 1
  end do
  if (nfile < 2) call stop_bad_input(usage, '')
  if (nmat == 0) then
    emod = [1.0_dp]
    nu = [0.0_dp]
    nmat = 1
  end if

  ! Each run is read once; for each body its triangles get a bucket grid, and
  ! every reference triangle of that body is located in it: one evaluation
  ! when it lies in one run triangle, the clipped pieces otherwise.
  call read_vtk(files(1)%s, ref)
  nbody = 0
  if (ref%ncell > 0) nbody = max(0, maxval(ref%body(1:ref%ncell)))
  allocate(e1(nbody), en(nbody), r1(nbody), rn(nbody))
  do a = 2, nfile
    s1 = 0.0_dp
    sn = 0.0_dp
    t1 = 0.0_dp
    tn = 0.0_dp
    ntri = 0
    nexact = 0
    call read_vtk(files(a)%s, run)
    do b = 1, nbody
      imat = min(b, nmat)
      mat = lame_constants(emod(imat), nu(imat), stress)
      e1(b) = 0.0_dp
      en(b) = 0.0_dp
      r1(b) = 0.0_dp
      rn(b) = 0.0_dp
      call build_run_body(run, b, rb)
      if (rb%n == 0) call stop_bad_input('a body of the reference is missing in ', files(a)%s)
      do c = 1, ref%ncell
        if (ref%body(c) /= b) cycle
        associate (v => ref%tri(:, c))
          px = ref%x(1, v)
          py = ref%x(2, v)
          cx = (px(1) + px(2) + px(3)) / 3.0_dp
          cy = (py(1) + py(2) + py(3)) / 3.0_dp
          if (use_window) then
            if (.not. (cx >= win(1) .and. cx <= win(2) .and. cy >= win(3) .and. cy <= win(4))) cycle
          end if
          call triangle_gradient(ref, v, d, g, det)
        end associate
        area = abs(det) / 2.0_dp
        ntri = ntri + 1
        r1(b) = r1(b) + area * (g(1) * g(1) + g(2) * g(2) + g(3) * g(3) + g(4) * g(4))
        rn(b) = rn(b) + area * energy_density(g, mat)
        call locate_triangle(rb, cx, cy, k)
        ! vertices carry the VTK file's 10 significant digits
        exact = .true.
        do q = 1, 3
          exact = outside_distance(rb%t(k), px(q), py(q)) <= 1.0e-6_dp
          if (.not. exact) exit
        end do
        if (exact) then
          nexact = nexact + 1
          call accumulate_error(g, rb%t(k)%g, area, mat, e1(b), en(b))
        else
          call integrate_cut_triangle(rb, px, py, area, cx, cy, g, mat, e1(b), en(b))
        end if
      end do
      s1 = s1 + e1(b)
      sn = sn + en(b)
      t1 = t1 + r1(b)
      tn = tn + rn(b)
    end do
    line = files(a)%s // ',' // real_text(sqrt(s1)) // ',' // ratio_text(s1, t1) // ',' // real_text(sqrt(sn)) &
      // ',' // ratio_text(sn, tn) // ',' // share_text(nexact, ntri)
    do b = 1, nbody
      line = line // ',' // real_text(sqrt(e1(b)))
    end do
    write(output_unit, '(a)') line
    flush(output_unit)
  end do

contains

  !> Command argument i, of its own length.
  subroutine get_argument(i, text)
    integer, intent(in) :: i
    character(len=:), allocatable, intent(out) :: text
    integer :: n

    call get_command_argument(i, length=n)
    allocate(character(len=n) :: text)
    if (n > 0) call get_command_argument(i, text)
  end subroutine get_argument

  !> size(v) comma-separated numbers at the start of text, as C sscanf "%lf,%lf,...":
  !> white space before a number is skipped, the commas follow the numbers
  !> directly, and whatever comes after the last number is ignored.
  !>   text (in)  the option value
  !>   v    (out) the numbers
  !>   ok   (out) .false. unless all size(v) were read
  subroutine scan_list(text, v, ok)
    character(len=*), intent(in) :: text
    real(dp), intent(out) :: v(:)
    logical, intent(out) :: ok
    integer(il) :: pos
    integer :: i

    v = 0.0_dp
    pos = 1
    do i = 1, size(v)
      if (i > 1) then
        ok = pos <= len(text, kind=il)
        if (ok) ok = text(pos:pos) == ','
        if (.not. ok) return
        pos = pos + 1
      end if
      call scan_number(text, pos, v(i), ok)
      if (.not. ok) return
    end do
  end subroutine scan_list

  !> x as C printf "%.6e": d.dddddde+XX, at least two exponent digits; nan, -nan, inf, -inf.
  function real_text(x) result(s)
    real(dp), intent(in) :: x
    character(len=:), allocatable :: s
    character(len=32) :: t, e
    integer :: ie, ex

    if (ieee_is_nan(x)) then
      s = 'nan'
      if (transfer(x, 0_il) < 0) s = '-nan'
    else if (.not. ieee_is_finite(x)) then
      s = 'inf'
      if (x < 0.0_dp) s = '-inf'
    else
      write(t, real_format) x
      t = adjustl(t)
      ie = index(t, 'E')
      read(t(ie + 1:), '(i5)') ex
      write(e, '(i0.2)') abs(ex)
      s = t(1:ie - 1) // 'e' // merge('-', '+', ex < 0) // trim(e)
    end if
  end function real_text

  !> sqrt(s / t) as real_text; t = 0 gives what C prints for sqrt(s / 0):
  !> -nan when s = 0 (x86 0/0), inf otherwise.
  function ratio_text(s, t) result(text)
    real(dp), intent(in) :: s, t
    character(len=:), allocatable :: text

    if (t /= 0.0_dp) then
      text = real_text(sqrt(s / t))
    else if (s == 0.0_dp) then
      text = '-nan'
    else
      text = 'inf'
    end if
  end function ratio_text

  !> nexact / ntri as C printf "%.4f" (0 when ntri = 0).
  function share_text(nexact, ntri) result(text)
    integer(il), intent(in) :: nexact, ntri
    character(len=:), allocatable :: text
    character(len=32) :: t
    real(dp) :: share

    share = 0.0_dp
    if (ntri > 0) share = real(nexact, dp) / real(ntri, dp)
    write(t, '(f32.4)') share
    text = trim(adjustl(t))
  end function share_text

end program c2dh1
