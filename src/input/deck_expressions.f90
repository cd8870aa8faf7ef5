!> deck_expressions: deck parameters, ${...} substitution and the small
!> arithmetic evaluator behind them (doc/deck.md, "Parameters").
!>
!> A deck declares parameters with `PARAMETER name=value ...`; a later line
!> may hold `${expression}` anywhere, replaced by the expression's value before
!> the line is split into a statement.  Expressions:
!>   numbers in Fortran or C notation (2, 2.5, .5, 2e5, 2.0d5, -1.5E-3),
!>   declared parameters, pi, + - * / ^ (also **; right-associative, above
!>   unary minus: -2^2 = -4), parentheses, sqrt exp log sin cos tan abs, and
!>   min max with two or more arguments separated by commas.
!> Every result must be finite: division by zero, log or sqrt outside their
!> domain, overflow, a negative base to a non-integer power are errors, each
!> returned as a message `what is wrong (what was expected)` for the caller's
!> FILE:LINE.  Values are printed back in the shortest decimal form that reads
!> back to the same double (strings' format_number), so a substituted line means
!> exactly the value computed.
!>
!> Programming interface
!>   type(parameter_set_t)   named values, each with its origin ('default', '-D', 'case N')
!>   add_parameter(set, name, value, origin)     append (caller checks the name is new)
!>   find_parameter(set, name)                   index, 0 when absent
!>   evaluate(text, set, x, message)             the value of an expression; message
!>                                               allocated on error
!>   substitute(text, set, out, message)         every ${...} of text replaced
!>   is_parameter_name(name)                     [A-Za-z_][A-Za-z0-9_]*, not reserved
module deck_expressions
  use kinds, only: dp
  use text_scan, only: parse_real, is_digit, is_letter, lower
  use strings, only: format_number
  implicit none
  private
  public :: parameter_set_t, add_parameter, find_parameter, evaluate, substitute
  public :: is_parameter_name

  integer, parameter :: name_len = 64          !< longest parameter name

  !> Declared parameters in declaration order (also a list of overrides).
  type :: parameter_set_t
    integer :: n = 0
    character(len=name_len), allocatable :: name(:)   !< (capacity) names, case as written
    real(dp), allocatable :: value(:)                 !< (capacity) values
    character(len=16), allocatable :: origin(:)       !< (capacity) 'default', '-D', 'case N'
    integer, allocatable :: line(:)                   !< (capacity) deck line of the declaration
  end type parameter_set_t

  character(len=*), parameter :: function_list = 'sqrt, exp, log, sin, cos, tan, abs, min, max'
  real(dp), parameter :: pi = 3.14159265358979323846264338327950288_dp
  real(dp), parameter :: log_huge = 709.0_dp   !< exp(x) and products stay below huge above this

  !> Parser state: the expression and the position of the next character.
  type :: cursor_t
    character(len=:), allocatable :: text
    integer :: pos = 1
  end type cursor_t

contains

  ! ================================================================ parameter sets

  !> Append name = value (origin) to set.
  subroutine add_parameter(set, name, value, origin, line)
    type(parameter_set_t), intent(inout) :: set
    character(len=*), intent(in) :: name, origin
    real(dp), intent(in) :: value
    integer, intent(in), optional :: line
    type(parameter_set_t) :: grown
    integer :: cap
    if (.not. allocated(set%name)) allocate(set%name(8), set%value(8), set%origin(8), set%line(8))
    if (set%n == size(set%name)) then
      cap = 2 * size(set%name)
      allocate(grown%name(cap), grown%value(cap), grown%origin(cap), grown%line(cap))
      grown%name(1:set%n) = set%name(1:set%n)
      grown%value(1:set%n) = set%value(1:set%n)
      grown%origin(1:set%n) = set%origin(1:set%n)
      grown%line(1:set%n) = set%line(1:set%n)
      call move_alloc(grown%name, set%name)
      call move_alloc(grown%value, set%value)
      call move_alloc(grown%origin, set%origin)
      call move_alloc(grown%line, set%line)
    end if
    set%n = set%n + 1
    set%name(set%n) = name
    set%value(set%n) = value
    set%origin(set%n) = origin
    set%line(set%n) = 0
    if (present(line)) set%line(set%n) = line
  end subroutine add_parameter

  !> Index of name in set (case-sensitive), 0 when absent.
  pure integer function find_parameter(set, name) result(k)
    type(parameter_set_t), intent(in) :: set
    character(len=*), intent(in) :: name
    do k = 1, set%n
      if (len(name) <= name_len) then
        if (set%name(k) == name .and. len_trim(set%name(k)) == len(name)) return
      end if
    end do
    k = 0
  end function find_parameter

  !> A parameter name: an identifier of at most 64 characters that is neither
  !> pi nor a function name.
  pure logical function is_parameter_name(name)
    character(len=*), intent(in) :: name
    integer :: i
    is_parameter_name = len(name) > 0 .and. len(name) <= name_len
    if (.not. is_parameter_name) return
    is_parameter_name = is_letter(name(1:1)) .or. name(1:1) == '_'
    do i = 2, len(name)
      if (.not. (is_letter(name(i:i)) .or. is_digit(name(i:i)) .or. name(i:i) == '_')) is_parameter_name = .false.
    end do
    if (is_parameter_name) is_parameter_name = .not. is_reserved(name)
  end function is_parameter_name

  pure logical function is_reserved(name)
    character(len=*), intent(in) :: name
    select case (lower(name))
    case ('pi', 'sqrt', 'exp', 'log', 'sin', 'cos', 'tan', 'abs', 'min', 'max')
      is_reserved = .true.
    case default
      is_reserved = .false.
    end select
  end function is_reserved

  ! ================================================================ substitution

  !> Replace every ${expression} of text by its value (format_number).
  !>   text    (in)  one deck line (comments already removed)
  !>   set     (in)  the parameters declared so far
  !>   out     (out) the line with each ${...} replaced
  !>   message (out) allocated on the first error: what is wrong (what was expected)
  subroutine substitute(text, set, out, message)
    character(len=*), intent(in) :: text
    type(parameter_set_t), intent(in) :: set
    character(len=:), allocatable, intent(out) :: out
    character(len=:), allocatable, intent(out) :: message
    integer :: i, open_at, close_at
    real(dp) :: x

    out = ''
    i = 1
    do
      open_at = index(text(i:), '${')
      if (open_at == 0) exit
      open_at = i + open_at - 1
      close_at = index(text(open_at + 2:), '}')
      if (close_at == 0) then
        message = 'unclosed "${" (expected ${name} or ${expression})'
        return
      end if
      close_at = open_at + 1 + close_at
      call evaluate(text(open_at + 2:close_at - 1), set, x, message)
      if (allocated(message)) return
      out = out // text(i:open_at - 1) // format_number(x)
      i = close_at + 1
    end do
    out = out // text(i:)
  end subroutine substitute

  ! ================================================================ evaluation

  !> The value of an arithmetic expression.
  !>   text    (in)  the expression
  !>   set     (in)  the parameters it may name
  !>   x       (out) its value (finite) when message is not allocated
  !>   message (out) allocated on error: what is wrong (what was expected)
  subroutine evaluate(text, set, x, message)
    character(len=*), intent(in) :: text
    type(parameter_set_t), intent(in) :: set
    real(dp), intent(out) :: x
    character(len=:), allocatable, intent(out) :: message
    type(cursor_t) :: c

    x = 0
    c%text = text
    c%pos = 1
    if (len_trim(text) == 0) then
      message = 'empty expression (expected a number, a parameter or an expression)'
      return
    end if
    call parse_sum(c, set, x, message)
    if (allocated(message)) return
    call skip_blanks(c)
    if (c%pos <= len(c%text)) then
      message = 'syntax error in expression "' // clip(text) // '" at "' // clip(c%text(c%pos:)) // &
                '" (expected an operator + - * / ^ or the end)'
      x = 0
    end if
  end subroutine evaluate

  !> sum := product { (+|-) product }
  recursive subroutine parse_sum(c, set, x, message)
    type(cursor_t), intent(inout) :: c
    type(parameter_set_t), intent(in) :: set
    real(dp), intent(out) :: x
    character(len=:), allocatable, intent(inout) :: message
    call parse_terms(c, set, '+-', x, message)
  end subroutine parse_sum

  !> The terms of a sum (ops '+-', each a product) or of a product (ops '*/',
  !> each a unary), combined left to right: operand { op operand }.
  recursive subroutine parse_terms(c, set, ops, x, message)
    type(cursor_t), intent(inout) :: c
    type(parameter_set_t), intent(in) :: set
    character(len=2), intent(in) :: ops
    real(dp), intent(out) :: x
    character(len=:), allocatable, intent(inout) :: message
    real(dp) :: y
    character :: op
    call parse_operand(x)
    do while (.not. allocated(message))
      if (.not. next_operator(c, ops, op)) exit
      call parse_operand(y)
      if (allocated(message)) exit
      call combine(op, y, c, x, message)
    end do
  contains
    recursive subroutine parse_operand(z)
      real(dp), intent(out) :: z
      if (ops == '+-') then
        call parse_terms(c, set, '*/', z, message)
      else
        call parse_unary(c, set, z, message)
      end if
    end subroutine parse_operand
  end subroutine parse_terms

  !> x = x op y for op one of + - * /, finite or an error (x then unchanged).
  subroutine combine(op, y, c, x, message)
    character, intent(in) :: op
    real(dp), intent(in) :: y
    type(cursor_t), intent(in) :: c
    real(dp), intent(inout) :: x
    character(len=:), allocatable, intent(inout) :: message
    real(dp) :: z
    select case (op)
    case ('+', '-')
      z = merge(-y, y, op == '-')
      if (abs(x) > 0.5_dp * huge(x) .and. abs(z) > 0.5_dp * huge(x)) then
        if (sign(1.0_dp, x) == sign(1.0_dp, z)) then
          message = overflow(c)
          return
        end if
      end if
      x = x + z
    case ('/')
      if (y == 0.0_dp) then
        message = 'division by zero in "' // clip(c%text) // '" (expected a non-zero divisor)'
        return
      end if
      if (x /= 0.0_dp) then                  ! (.and. does not cut short: log(0) traps)
        if (log(abs(x)) - log(abs(y)) > log_huge) then
          message = overflow(c)
          return
        end if
      end if
      x = x / y
    case default
      if (x /= 0.0_dp .and. y /= 0.0_dp) then
        if (log(abs(x)) + log(abs(y)) > log_huge) then
          message = overflow(c)
          return
        end if
      end if
      x = x * y
    end select
  end subroutine combine

  !> The next character, when it is one of ops (not the '*' of the power
  !> operator '**'), taken as op; .false. (nothing taken) otherwise.
  logical function next_operator(c, ops, op)
    type(cursor_t), intent(inout) :: c
    character(len=*), intent(in) :: ops
    character, intent(out) :: op
    call skip_blanks(c)
    next_operator = .false.
    op = ' '
    if (c%pos > len(c%text)) return
    op = c%text(c%pos:c%pos)
    if (index(ops, op) == 0) return
    if (op == '*' .and. c%pos < len(c%text)) then
      if (c%text(c%pos + 1:c%pos + 1) == '*') return
    end if
    c%pos = c%pos + 1
    next_operator = .true.
  end function next_operator


  !> unary := (+|-) unary | power
  recursive subroutine parse_unary(c, set, x, message)
    type(cursor_t), intent(inout) :: c
    type(parameter_set_t), intent(in) :: set
    real(dp), intent(out) :: x
    character(len=:), allocatable, intent(inout) :: message
    logical :: negative
    x = 0
    call skip_blanks(c)
    if (c%pos <= len(c%text)) then
      if (c%text(c%pos:c%pos) == '-' .or. c%text(c%pos:c%pos) == '+') then
        negative = c%text(c%pos:c%pos) == '-'
        c%pos = c%pos + 1
        call parse_unary(c, set, x, message)
        if (negative) x = -x
        return
      end if
    end if
    call parse_power(c, set, x, message)
  end subroutine parse_unary

  !> power := primary [ (^|**) unary ]   (right-associative: 2^3^2 = 2^9)
  recursive subroutine parse_power(c, set, x, message)
    type(cursor_t), intent(inout) :: c
    type(parameter_set_t), intent(in) :: set
    real(dp), intent(out) :: x
    character(len=:), allocatable, intent(inout) :: message
    real(dp) :: y
    call parse_primary(c, set, x, message)
    if (allocated(message)) return
    call skip_blanks(c)
    if (c%pos > len(c%text)) return
    if (c%text(c%pos:c%pos) == '^') then
      c%pos = c%pos + 1
    else if (c%pos < len(c%text) .and. c%text(c%pos:min(c%pos + 1, len(c%text))) == '**') then
      c%pos = c%pos + 2
    else
      return
    end if
    call parse_unary(c, set, y, message)
    if (allocated(message)) return
    call power(x, y, c, message)
  end subroutine parse_power

  !> x = x^y, finite or an error.
  subroutine power(x, y, c, message)
    real(dp), intent(inout) :: x
    real(dp), intent(in) :: y
    type(cursor_t), intent(in) :: c
    character(len=:), allocatable, intent(inout) :: message
    if (x == 0.0_dp) then
      if (y < 0.0_dp) then
        message = 'division by zero in "' // clip(c%text) // '" (0 to a negative power; expected a non-zero base)'
      else if (y == 0.0_dp) then
        x = 1.0_dp
      end if
      return
    end if
    if (x < 0.0_dp .and. y /= aint(y)) then
      message = 'negative base to a non-integer power in "' // clip(c%text) // &
                '" (expected a base >= 0 or an integer exponent)'
      return
    end if
    if (y * log(abs(x)) > log_huge) then
      message = overflow(c)
      return
    end if
    if (y == aint(y) .and. abs(y) < 1.0e9_dp) then
      x = x**nint(y)
    else
      x = x**y
    end if
  end subroutine power

  !> primary := number | pi | name | function ( sum {, sum} ) | ( sum )
  recursive subroutine parse_primary(c, set, x, message)
    type(cursor_t), intent(inout) :: c
    type(parameter_set_t), intent(in) :: set
    real(dp), intent(out) :: x
    character(len=:), allocatable, intent(inout) :: message
    integer :: start, k
    character(len=:), allocatable :: word
    logical :: ok

    x = 0
    call skip_blanks(c)
    if (c%pos > len(c%text)) then
      message = 'expression "' // clip(c%text) // '" ends too early (expected a number, a parameter or "(")'
      return
    end if
    start = c%pos
    if (c%text(start:start) == '(') then
      c%pos = c%pos + 1
      call parse_sum(c, set, x, message)
      if (allocated(message)) return
      call expect_char(c, ')', message)
      return
    end if
    if (is_digit(c%text(start:start)) .or. c%text(start:start) == '.') then
      c%pos = number_end(c%text, start)
      call parse_real(c%text(start:c%pos - 1), x, ok)
      if (.not. ok) message = 'bad number "' // clip(c%text(start:c%pos - 1)) // '" in "' // clip(c%text) // &
                              '" (expected a number such as 2, 2.5, 2e5 or 2.0d5, |x| < 1e308)'
      return
    end if
    if (is_letter(c%text(start:start)) .or. c%text(start:start) == '_') then
      do while (c%pos <= len(c%text))
        if (.not. (is_letter(c%text(c%pos:c%pos)) .or. is_digit(c%text(c%pos:c%pos)) .or. &
                   c%text(c%pos:c%pos) == '_')) exit
        c%pos = c%pos + 1
      end do
      word = c%text(start:c%pos - 1)
      call skip_blanks(c)
      if (c%pos <= len(c%text)) then
        if (c%text(c%pos:c%pos) == '(') then
          call parse_call(c, set, word, x, message)
          return
        end if
      end if
      if (lower(word) == 'pi') then
        x = pi
        return
      end if
      k = find_parameter(set, word)
      if (k == 0) then
        if (is_reserved(word)) then
          message = 'function ' // word // ' without arguments in "' // clip(c%text) // '" (expected ' // &
                    word // '(...))'
        else
          message = 'undeclared parameter "' // clip(word) // '" (expected a name declared by PARAMETER on an ' // &
                    'earlier line' // known_names(set) // ')'
        end if
        return
      end if
      x = set%value(k)
      return
    end if
    message = 'syntax error in expression "' // clip(c%text) // '" at "' // clip(c%text(start:)) // &
              '" (expected a number, a parameter, a function or "(")'
  end subroutine parse_primary

  !> name ( sum {, sum} ): one of the functions, its domain checked.
  recursive subroutine parse_call(c, set, name, x, message)
    type(cursor_t), intent(inout) :: c
    type(parameter_set_t), intent(in) :: set
    character(len=*), intent(in) :: name
    real(dp), intent(out) :: x
    character(len=:), allocatable, intent(inout) :: message
    real(dp) :: args(64)
    integer :: nargs
    character(len=:), allocatable :: fn

    x = 0
    fn = lower(name)
    if (.not. is_reserved(fn) .or. fn == 'pi') then
      message = 'unknown function "' // clip(name) // '" (expected one of ' // function_list // ')'
      return
    end if
    c%pos = c%pos + 1                                ! the '('
    nargs = 0
    do
      if (nargs == size(args)) then
        message = 'more than 64 arguments to ' // fn // ' (expected fewer)'
        return
      end if
      nargs = nargs + 1
      call parse_sum(c, set, args(nargs), message)
      if (allocated(message)) return
      call skip_blanks(c)
      if (c%pos > len(c%text)) exit
      if (c%text(c%pos:c%pos) /= ',') exit
      c%pos = c%pos + 1
    end do
    call expect_char(c, ')', message)
    if (allocated(message)) return
    if (fn == 'min' .or. fn == 'max') then
      if (nargs < 2) then
        message = fn // ' with one argument in "' // clip(c%text) // '" (expected two or more, separated by commas)'
      else if (fn == 'min') then
        x = minval(args(1:nargs))
      else
        x = maxval(args(1:nargs))
      end if
      return
    end if
    if (nargs /= 1) then
      message = fn // ' with ' // trim(int_text(nargs)) // ' arguments in "' // clip(c%text) // &
                '" (expected one argument)'
      return
    end if
    x = args(1)
    select case (fn)
    case ('sqrt')
      if (x < 0.0_dp) then
        message = 'sqrt of a negative number in "' // clip(c%text) // '" (expected an argument >= 0)'
        return
      end if
      x = sqrt(x)
    case ('exp')
      if (x > log_huge) then
        message = overflow(c)
        return
      end if
      x = exp(x)
    case ('log')
      if (x <= 0.0_dp) then
        message = 'log of a non-positive number in "' // clip(c%text) // '" (expected an argument > 0)'
        return
      end if
      x = log(x)
    case ('sin')
      x = sin(x)
    case ('cos')
      x = cos(x)
    case ('tan')
      x = tan(x)
    case ('abs')
      x = abs(x)
    end select
  end subroutine parse_call

  subroutine expect_char(c, ch, message)
    type(cursor_t), intent(inout) :: c
    character, intent(in) :: ch
    character(len=:), allocatable, intent(inout) :: message
    call skip_blanks(c)
    if (c%pos <= len(c%text)) then
      if (c%text(c%pos:c%pos) == ch) then
        c%pos = c%pos + 1
        return
      end if
      message = 'syntax error in expression "' // clip(c%text) // '" at "' // clip(c%text(c%pos:)) // &
                '" (expected "' // ch // '")'
    else
      message = 'syntax error in expression "' // clip(c%text) // '": missing "' // ch // '" (expected "' // ch // &
                '" before the end)'
    end if
  end subroutine expect_char

  function overflow(c) result(message)
    type(cursor_t), intent(in) :: c
    character(len=:), allocatable :: message
    message = 'the value of "' // clip(c%text) // '" is not finite (overflow; expected |value| < 1e308)'
  end function overflow

  subroutine skip_blanks(c)
    type(cursor_t), intent(inout) :: c
    do while (c%pos <= len(c%text))
      if (c%text(c%pos:c%pos) /= ' ' .and. c%text(c%pos:c%pos) /= achar(9)) exit
      c%pos = c%pos + 1
    end do
  end subroutine skip_blanks

  !> One past the end of the number that starts at text(start:): digits [. digits]
  !> [ (e|E|d|D) [sign] digits ]; the exponent only when digits follow it.
  pure integer function number_end(text, start) result(i)
    character(len=*), intent(in) :: text
    integer, intent(in) :: start
    integer :: j
    i = start
    do while (i <= len(text))
      if (.not. is_digit(text(i:i))) exit
      i = i + 1
    end do
    if (i <= len(text)) then
      if (text(i:i) == '.') then
        i = i + 1
        do while (i <= len(text))
          if (.not. is_digit(text(i:i))) exit
          i = i + 1
        end do
      end if
    end if
    if (i > len(text)) return
    if (index('eEdD', text(i:i)) == 0) return
    j = i + 1
    if (j <= len(text)) then
      if (text(j:j) == '+' .or. text(j:j) == '-') j = j + 1
    end if
    if (j > len(text)) return
    if (.not. is_digit(text(j:j))) return
    i = j
    do while (i <= len(text))
      if (.not. is_digit(text(i:i))) exit
      i = i + 1
    end do
  end function number_end

  !> ', one of a, b, c' for a message ('' when no parameter is declared).
  function known_names(set) result(t)
    type(parameter_set_t), intent(in) :: set
    character(len=:), allocatable :: t
    integer :: k
    t = ''
    if (set%n == 0) then
      t = '; none declared'
      return
    end if
    do k = 1, min(set%n, 8)
      if (k > 1) t = t // ', '
      t = t // trim(set%name(k))
    end do
    if (set%n > 8) t = t // ', ...'
    t = '; declared: ' // t
  end function known_names



  !> User text for a message: trimmed, control and non-ASCII bytes as '?', cut after 40.
  pure function clip(s) result(t)
    character(len=*), intent(in) :: s
    character(len=:), allocatable :: t
    integer :: i
    t = trim(adjustl(s))
    if (len(t) > 40) t = t(1:40) // '...'
    do i = 1, len(t)
      if (iachar(t(i:i)) < 32 .or. iachar(t(i:i)) > 126) t(i:i) = '?'
    end do
  end function clip

  pure function int_text(k) result(t)
    integer, intent(in) :: k
    character(len=12) :: t
    write(t, '(i0)') k
  end function int_text

end module deck_expressions
