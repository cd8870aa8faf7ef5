!> deck_expressions: the evaluator against values computed by hand (precedence,
!> associativity, functions), every error class, and format_number's round trip
!> (the shortest decimal that reads back to the same double) on 1e5 random doubles
!> over 600 decades and on the edge values.
program test_deck_expressions
  use kinds, only: dp, i8
  use deck_expressions, only: parameter_set_t, add_parameter, evaluate, substitute
  use strings, only: format_number
  use testing, only: check, check_close, finish_tests, urand, tol_round
  implicit none
  type(parameter_set_t) :: set
  integer :: i, nbad, nlong, ios
  integer(i8) :: state
  real(dp) :: x, y, edge(9)
  character(len=:), allocatable :: s, message

  call add_parameter(set, 'a', 2.0_dp, 'default')
  call add_parameter(set, 'L_1', 0.5_dp, 'default')
  call value_is('1+2*3', 7.0_dp)
  call value_is('(1+2)*3', 9.0_dp)
  call value_is('2^3^2', 512.0_dp)                       ! right-associative
  call value_is('2**3**2', 512.0_dp)
  call value_is('-a^2', -4.0_dp)                         ! ^ above unary minus
  call value_is('2^-1', 0.5_dp)
  call value_is('8/4/2', 1.0_dp)                         ! / left-associative
  call value_is('10-4-3', 3.0_dp)
  call value_is('- -a', 2.0_dp)
  call value_is('2.0d5 + 1.5E-3 + .5 + 5.', 200005.5015_dp)
  call value_is(' a * L_1 ', 1.0_dp)
  call value_is('sqrt(a)^2', 2.0_dp)
  call value_is('exp(log(3))', 3.0_dp)
  call value_is('sin(pi/6) + cos(0) + tan(pi/4) + abs(-a)', 4.5_dp)
  call value_is('min(3, a, 7) + max(-1, -5, L_1, 0)', 2.5_dp)
  call value_is('PI', 3.14159265358979323846_dp)

  call error_is('b + 1', 'undeclared parameter "b"')
  call error_is('1 +', 'ends too early')
  call error_is('(1 + 2', 'missing ")"')
  call error_is('1 2', 'syntax error')
  call error_is('a/(a-2)', 'division by zero')
  call error_is('0^-1', 'division by zero')
  call error_is('log(0)', 'log of a non-positive number')
  call error_is('sqrt(-a)', 'sqrt of a negative number')
  call error_is('(-8)^(1/3)', 'negative base to a non-integer power')
  call error_is('exp(710)', 'not finite')
  call error_is('1e200*1e200', 'not finite')
  call error_is('1e300/1e-300', 'not finite')
  call error_is('10^400', 'not finite')
  call error_is('cosh(1)', 'unknown function "cosh"')
  call error_is('min(1)', 'min with one argument')
  call error_is('sin(1, 2)', 'expected one argument')
  call error_is('sqrt', 'without arguments')
  call error_is('', 'empty expression')
  call error_is('1e999', 'bad number')

  call substitute('MESH rect nx=${2*a} x1=${L_1} ! ${a}', set, s, message)
  call check(.not. allocated(message) .and. s == 'MESH rect nx=4 x1=0.5 ! 2', 'substitute: every ${...} replaced')
  call substitute('TITLE ${a', set, s, message)
  call check(allocated(message), 'substitute: an unclosed ${ is an error')

  ! format_number: reads back exactly, at most 17 significant digits
  edge = [0.1_dp, 1.0_dp / 3.0_dp, huge(1.0_dp), tiny(1.0_dp), -5.0e-324_dp, 1.0e15_dp, 1.0e-5_dp, 123456789012345.0_dp, &
          -0.0_dp]
  nbad = 0
  nlong = 0
  state = 12345_i8
  do i = 1, size(edge) + 100000
    if (i <= size(edge)) then
      x = edge(i)
    else
      x = (urand(state) - 0.5_dp) * 10.0_dp**(int(600 * urand(state)) - 300)
    end if
    s = format_number(x)
    read(s, *, iostat=ios) y
    if (ios /= 0 .or. y /= x) nbad = nbad + 1
    if (len(s) > 24) nlong = nlong + 1
  end do
  call check(nbad == 0, 'format_number reads back to the same double (1e5 random values and the edges)')
  call check(nlong == 0, 'format_number: at most 24 characters')
  call check(format_number(0.1_dp * 3) == '0.30000000000000004', 'format_number(0.1*3) = 0.30000000000000004')
  call check(format_number(0.25_dp) == '0.25' .and. format_number(200000.0_dp) == '200000' .and. &
             format_number(1.0e-7_dp) == '1e-7' .and. format_number(-2.5e20_dp) == '-2.5e20', &
             'format_number: 0.25, 200000, 1e-7, -2.5e20 as written')
  ! the main program's variables are saved, never freed at its end: freed
  ! here, as LeakSanitizer (make MODE=sanitize) counts them lost
  deallocate(s)
  if (allocated(message)) deallocate(message)
  call finish_tests()

contains

  subroutine value_is(text, want)
    character(len=*), intent(in) :: text
    real(dp), intent(in) :: want
    real(dp) :: got
    character(len=:), allocatable :: message
    call evaluate(text, set, got, message)
    call check(.not. allocated(message), 'evaluate "' // text // '": no error')
    if (.not. allocated(message)) call check_close(got, want, tol_round(4), 'evaluate "' // text // '"')
  end subroutine value_is

  subroutine error_is(text, want)
    character(len=*), intent(in) :: text, want
    real(dp) :: got
    character(len=:), allocatable :: message
    call evaluate(text, set, got, message)
    if (.not. allocated(message)) message = '(no error)'
    call check(index(message, want) > 0, 'evaluate "' // text // '": error "' // want // '"')
  end subroutine error_is

end program test_deck_expressions
