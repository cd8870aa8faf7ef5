!> Unit tests of deck_syntax's key table: read_keys on one statement against a
!> row of keys, each message compared with the wording DECK.md and
!> tests/bad/*.expect give for it (the contract), each bound tested on both
!> sides (a strict bound refuses the bound itself, an inclusive one takes it).
program test_deck_syntax
  use kinds, only: dp
  use deck_syntax, only: state_t, stmt_t, key_t, key_values_t, string_t, read_keys, store_echo, split_words, &
                         join_equals, classify_words, real_key, integer_key, choice_key, ramp_key, curve_key, &
                         name_key, text_key
  use testing, only: check, check_close, finish_tests
  implicit none

  call test_number_ranges()
  call test_integers_and_choices()
  call test_required_and_unknown()
  call test_load_path()
  call finish_tests()

contains

  !> Read `line` against keys; return the state (its messages) and the values.
  subroutine read_line(line, keys, s, v)
    character(len=*), intent(in) :: line
    type(key_t), intent(in) :: keys(:)
    type(state_t), intent(out) :: s
    type(key_values_t), intent(out) :: v
    type(stmt_t) :: st
    type(string_t), allocatable :: tok(:)
    integer :: ntok

    allocate(s%errs(16), s%echo(4))
    call store_echo(s, line)
    call split_words(line, tok, ntok)
    call join_equals(tok, ntok)
    call classify_words(tok, ntok, st)
    st%line = 1
    st%keyword = tok(1)%s
    st%what = tok(1)%s
    st%usage = tok(1)%s // ' USAGE'
    st%words = 0
    st%keys = keys
    call read_keys(s, st, v)
  end subroutine read_line

  !> The single message of s is text (and there is exactly one).
  subroutine check_message(s, text, name)
    type(state_t), intent(in) :: s
    character(len=*), intent(in) :: text, name
    call check(s%nerr == 1, name // ': one message')
    if (s%nerr >= 1) call check(s%errs(1)%text == text, name // ': "' // s%errs(1)%text // '"')
  end subroutine check_message

  !> Read `line` against keys: it is refused with the single message text.
  subroutine check_refused(line, keys, text, name)
    character(len=*), intent(in) :: line, text, name
    type(key_t), intent(in) :: keys(:)
    type(state_t) :: s
    type(key_values_t) :: v
    call read_line(line, keys, s, v)
    call check_message(s, text, name)
  end subroutine check_refused

  subroutine test_number_ranges()
    type(state_t) :: s
    type(key_values_t) :: v
    type(key_t), allocatable :: keys(:)

    keys = [real_key('E', gt=0.0_dp), real_key('nu', gt=-1.0_dp, lt=0.5_dp), &
            real_key('mu', ge=0.0_dp, le=1000.0_dp), real_key('tresca', ge=0.0_dp, note=', a shear stress')]
    call read_line('MATERIAL E=2e5 nu=-0.99 mu=1000 tresca=0', keys, s, v)
    call check(s%nerr == 0, 'numbers inside their ranges, inclusive bounds taken')
    call check(all(v%ok), 'numbers inside their ranges: ok')
    call check_close(v%x(1), 2.0e5_dp, 0.0_dp, 'E=2e5 converted')
    call check_close(v%x(3), 1000.0_dp, 0.0_dp, 'mu=1000 converted')
    call read_line('MATERIAL E=0', keys, s, v)
    call check_message(s, 'bad value E=0 (expected E > 0)', 'strict lower bound')
    call check(.not. v%ok(1), 'E=0 not ok')
    call check_refused('MATERIAL nu=0.5', keys, 'bad value nu=0.5 (expected -1 < nu < 0.5)', 'strict upper bound')
    call check_refused('MATERIAL nu=-1', keys, 'bad value nu=-1 (expected -1 < nu < 0.5)', 'strict lower bound of two')
    call check_refused('MATERIAL mu=1000.5', keys, &
                       'bad value mu=1000.5 (expected 0 <= mu <= 1000)', 'inclusive upper bound')
    call check_refused('MATERIAL tresca=-2', keys, &
                       'bad value tresca=-2 (expected tresca >= 0, a shear stress)', 'note after the range')
    call check_refused('MATERIAL E=1e400', keys, &
                       'bad number "1e400" for "E" (expected a finite number)', 'not a finite number')
  end subroutine test_number_ranges

  subroutine test_integers_and_choices()
    type(state_t) :: s
    type(key_values_t) :: v
    type(key_t), allocatable :: keys(:)

    keys = [integer_key('nx'), integer_key('maxit', at_least=0), choice_key('lcp', 'auto|lemke|pgs|pdas'), &
            name_key('region', 'region'), text_key('fields', 'LIST')]
    call read_line('SOLVER nx=3 maxit=0 lcp=PDAS region=a_b.1 fields=x,y', keys, s, v)
    call check(s%nerr == 0, 'integers, choice, name and text accepted')
    call check(v%k(1) == 3 .and. v%k(2) == 0, 'integers converted')
    call check(v%text(3)%s == 'pdas', 'choice in its canonical spelling')
    call check(v%text(5)%s == 'x,y', 'text as written')
    call check_refused('SOLVER nx=0', keys, 'bad value nx=0 (expected a positive integer)', 'positive integer')
    call check_refused('SOLVER maxit=1.5', keys, 'bad value maxit=1.5 (expected an integer >= 0)', 'integer at least 0')
    call check_refused('SOLVER lcp=newton', keys, 'bad value lcp=newton (expected lcp=auto|lemke|pgs|pdas)', 'choice')
    call check_refused('SOLVER region=a/b', keys, &
                       'bad region name "a/b" (expected letters, digits, _ . - only)', 'name')
  end subroutine test_integers_and_choices

  subroutine test_required_and_unknown()
    type(state_t) :: s
    type(key_values_t) :: v
    type(key_t), allocatable :: keys(:)

    keys = [real_key('rho', required=.true., gt=0.0_dp), real_key('x')]
    call check_refused('DENSITY x=1', keys, 'missing key "rho" for DENSITY (expected DENSITY USAGE)', 'required key')
    call check_refused('DENSITY rho=1 y=2', keys, 'unknown key "y" for DENSITY (expected rho, x)', 'unknown key')
    call check_refused('DENSITY rho=1 RHO=2', keys, &
                       'duplicate key "rho" (expected each key at most once)', 'repeated key, any case')
    call read_line('DENSITY rho=', keys, s, v)
    call check(s%nerr == 1, 'empty value: one message')
    call check(s%errs(1)%text == 'missing value for "rho" (expected rho=number)', 'empty value')
    call check_refused('DENSITY rho=1 word', keys, &
                       'unexpected word "word" (expected DENSITY USAGE)', 'a word where none is taken')
  end subroutine test_required_and_unknown

  subroutine test_load_path()
    type(state_t) :: s
    type(key_values_t) :: v
    type(key_t), allocatable :: keys(:)

    keys = [real_key('fx'), ramp_key(), curve_key()]
    call read_line('BODYFORCE fx=1 ramp=2:5', keys, s, v)
    call check(s%nerr == 0 .and. all(v%ramp == [2, 5]), 'ramp=2:5 read')
    call check(v%curve == '', 'no curve: empty name')
    call read_line('BODYFORCE fx=1 curve=up', keys, s, v)
    call check(s%nerr == 0 .and. v%curve == 'up' .and. all(v%ramp == 0), 'curve=up read, no ramp')
    call check_refused('BODYFORCE ramp=5:2', keys, &
                       'bad ramp "5:2" (expected ramp=k0:k1 with k0 < k1: the load rises from step k0 to ' // &
                       'step k1)', 'ramp k0 >= k1')
    call check_refused('BODYFORCE ramp=0:1 curve=up', keys, &
                       'ramp= and curve= together (expected one load path per statement: ramp=k0:k1 or ' // &
                       'curve=NAME)', 'ramp and curve')
  end subroutine test_load_path

end program test_deck_syntax
