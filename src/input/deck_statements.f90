!> deck_statements: the deck's grammar as a table, one row a statement (or
!> one form of it: MESH rect, MATERIAL isotropic), with its keys, their types
!> and ranges (deck_syntax's key_t), and the handlers of the top-level
!> statements.  The handlers of the BODY and RIGID blocks are in
!> deck_body_statements and deck_rigid_statements.
!>
!> A new statement is a row in define_statements and a handler; a new key is
!> an entry of its row (real_key('E', required=.true., gt=0.0_dp): read_keys
!> checks it and says what is wrong); a new block (RIGID ... END) is a row
!> that opens it and rows whose block it is.
!>
!> Programming interface
!>   define_statements(table)       the grammar
module deck_statements
  use kinds, only: dp
  use strings, only: int_to_str
  use deck_types, only: deck_t, contact_deck_t, curve_t
  use deck_expressions, only: add_parameter, find_parameter, evaluate, is_parameter_name
  use deck_syntax, only: state_t, stmt_t, statement_t, key_values_t, string_t, report, read_keys, add_row, &
                         real_key, integer_key, choice_key, ramp_key, curve_key, name_key, text_key, &
                         check_extra_words, check_no_pairs, check_name, form_word, find_key, join_list, cut, quoted, max_mu, &
                         max_steps
  use deck_body_statements, only: do_body, do_mesh, do_mesh_rect, do_mesh_gmsh, do_material, do_density, &
                                  do_fix, do_load, do_thermal, do_vector, do_spring
  use deck_rigid_statements, only: do_rigid, do_rigid_shape, do_rigid_ref, do_rigid_load
  use text_scan, only: parse_real, parse_integer, lower, is_name, is_identifier, ends_with_ci
  implicit none
  private
  public :: define_statements

contains

  !> The deck's grammar, one row a statement, in the order the unknown-keyword
  !> message lists them.  A statement with forms has a form-less row first
  !> (where it stands, how often; its handler reports a missing or unknown
  !> form), then one row per form.
  subroutine define_statements(table)
    type(statement_t), allocatable, intent(out) :: table(:)
    character(len=*), parameter :: ramp_curve = ' [ramp=k0:k1|curve=NAME]'
    character(len=*), parameter :: plane_usage = 'PLANE strain, PLANE stress [thickness=number] or PLANE axisymmetric'
    character(len=*), parameter :: rect_usage = 'MESH rect x0=number y0=number x1=number y1=number nx=integer ' // &
                                                'ny=integer [elem=tri3|quad4|tri6|quad8|quad9] [diag=right|left|alt]'
    character(len=*), parameter :: iso_usage = 'MATERIAL isotropic E=number nu=number'
    character(len=*), parameter :: ortho_usage = 'MATERIAL orthotropic E1=number E2=number nu12=number ' // &
                                                 'G12=number [angle=degrees] [E3=number] [nu13=number] [nu23=number]'
    character(len=*), parameter :: neo_usage = 'MATERIAL neo_hookean mu=number K=number'
    character(len=*), parameter :: mooney_usage = 'MATERIAL mooney_rivlin c10=number c01=number K=number'
    character(len=*), parameter :: contact_usage = 'CONTACT slave=body:boundary master=body:boundary ' // &
                                                   '[gap=geometry|zero] [mu=number|tresca=number] ' // &
                                                   '[interference=allow|reject] [sliding=small|finite] [name=NAME]'
    character(len=*), parameter :: solver_usage = 'SOLVER [lcp=auto|lemke|pgs|pdas] [tol=number] [maxit=integer] ' // &
                                                  '[omega=number] [ordering=auto|metis|amd] ' // &
                                                  '[condense=auto|solve|inverse] [cut=auto|off] [updates=integer] ' // &
                                                  '[newton_tol=number] [newton_maxit=integer] ' // &
                                                  '[newton_lcp=lemke|active_set]'
    character(len=*), parameter :: shape_usage = 'SHAPE line x0= y0= x1= y1= | SHAPE circle xc= yc= r= ' // &
                                                 '[solid=inside|outside] | SHAPE polyline points=x1:y1,x2:y2,...'
    real(dp), parameter :: zero = 0.0_dp

    allocate(table(0))
    call add_row(table, 'TITLE', '', do_title, once=.true.)
    call add_row(table, 'PLANE', '', do_plane, once=.true., usage=plane_usage)
    call add_row(table, 'PLANE', '', do_plane, form='strain', words=1, usage=plane_usage, &
                 keys=[text_key('thickness', 'number')])
    call add_row(table, 'PLANE', '', do_plane, form='stress', words=1, usage=plane_usage, &
                 keys=[real_key('thickness', gt=zero)])
    call add_row(table, 'PLANE', '', do_plane, form='axisymmetric', words=1, usage=plane_usage, &
                 keys=[text_key('thickness', 'number')])
    call add_row(table, 'BODY', '', do_body, opens='BODY', usage='BODY name')
    call add_row(table, 'MESH', 'BODY', do_mesh, once=.true., expected='one MESH per body', &
                 usage='MESH rect x0= y0= x1= y1= nx= ny= or MESH gmsh file=NAME.msh|NAME.geo')
    call add_row(table, 'MESH', 'BODY', do_mesh_rect, form='rect', words=1, usage=rect_usage, &
                 keys=[real_key('x0'), real_key('y0'), real_key('x1'), real_key('y1'), &
                       integer_key('nx', required=.true.), integer_key('ny', required=.true.), &
                       choice_key('elem', 'tri3|quad4|tri6|quad8|quad9'), choice_key('diag', 'right|left|alt')])
    call add_row(table, 'MESH', 'BODY', do_mesh_gmsh, form='gmsh', &
                 usage='MESH gmsh file=NAME.msh or file=NAME.geo [order=1|2] [name=number ...]')
    call add_row(table, 'MATERIAL', 'BODY', do_material, once=.true., expected='one MATERIAL per body', &
                 usage=iso_usage // ', MATERIAL orthotropic ..., MATERIAL neo_hookean ... or MATERIAL mooney_rivlin ...')
    call add_row(table, 'MATERIAL', 'BODY', do_material, form='isotropic', words=1, usage=iso_usage, &
                 keys=[real_key('E', required=.true., gt=zero), &
                       real_key('nu', required=.true., gt=-1.0_dp, lt=0.5_dp)])
    call add_row(table, 'MATERIAL', 'BODY', do_material, form='orthotropic', words=1, usage=ortho_usage, &
                 keys=[real_key('E1', required=.true., gt=zero), real_key('E2', required=.true., gt=zero), &
                       real_key('nu12', required=.true.), real_key('G12', required=.true., gt=zero), &
                       real_key('angle'), real_key('E3', gt=zero), real_key('nu13'), real_key('nu23')])
    call add_row(table, 'MATERIAL', 'BODY', do_material, form='neo_hookean', words=1, usage=neo_usage, &
                 keys=[real_key('mu', required=.true., gt=zero, note=', the shear modulus'), &
                       real_key('K', required=.true., gt=zero, note=', the bulk modulus')])
    call add_row(table, 'MATERIAL', 'BODY', do_material, form='mooney_rivlin', words=1, usage=mooney_usage, &
                 keys=[real_key('c10', required=.true.), real_key('c01', required=.true.), &
                       real_key('K', required=.true., gt=zero, note=', the bulk modulus')])
    call add_row(table, 'DENSITY', 'BODY', do_density, once=.true., words=0, usage='DENSITY rho=number', &
                 keys=[real_key('rho', required=.true., gt=zero)])
    call add_row(table, 'FIX', 'BODY', do_fix, words=1, &
                 usage='FIX boundary [ux=number] [uy=number] | [un=number] [ut=number]' // ramp_curve, &
                 keys=[real_key('ux'), real_key('uy'), ramp_key(), curve_key(), real_key('un'), real_key('ut')])
    call add_row(table, 'TRACTION', 'BODY', do_load, words=1, &
                 usage='TRACTION boundary tx=number ty=number | tn=number tt=number' // ramp_curve, &
                 keys=[real_key('tx'), real_key('ty'), ramp_key(), curve_key(), real_key('tn'), real_key('tt')])
    call add_row(table, 'PRESSURE', 'BODY', do_load, words=1, usage='PRESSURE boundary p=number' // ramp_curve, &
                 keys=[real_key('p', required=.true.), ramp_key(), curve_key()])
    call add_row(table, 'BODYFORCE', 'BODY', do_vector, once=.true., words=0, &
                 usage='BODYFORCE fx=number fy=number' // ramp_curve, &
                 keys=[real_key('fx'), real_key('fy'), ramp_key(), curve_key()])
    call add_row(table, 'THERMAL', 'BODY', do_thermal, words=0, &
                 usage='THERMAL alpha=number dT=number [region=NAME] [curve=NAME]', &
                 keys=[real_key('alpha', required=.true.), real_key('dT', required=.true.), &
                       name_key('region', 'region'), curve_key()])
    call add_row(table, 'OFFSET', 'BODY', do_vector, once=.true., words=0, usage='OFFSET dx=number dy=number', &
                 keys=[real_key('dx'), real_key('dy')])
    call add_row(table, 'FORCE', 'BODY', do_load, words=1, &
                 usage='FORCE point [fx=number] [fy=number]' // ramp_curve, &
                 keys=[real_key('fx'), real_key('fy'), ramp_key(), curve_key()])
    call add_row(table, 'SPRING', 'BODY', do_spring, words=1, &
                 usage='SPRING boundary kn=number [kt=number] | SPRING point [kx=number] [ky=number]', &
                 keys=[real_key('kn', ge=zero, note=', a stiffness'), real_key('kt', ge=zero, note=', a stiffness'), &
                       real_key('kx', ge=zero, note=', a stiffness'), real_key('ky', ge=zero, note=', a stiffness')])
    call add_row(table, 'END', '*')
    call add_row(table, 'GRAVITY', '', do_vector, once=.true., words=0, &
                 usage='GRAVITY gx=number gy=number' // ramp_curve, &
                 keys=[real_key('gx'), real_key('gy'), ramp_key(), curve_key()])
    call add_row(table, 'CONTACT', '', do_contact, words=0, usage=contact_usage, &
                 keys=[text_key('slave', 'body:boundary', required=.true.), &
                       text_key('master', 'body:boundary', required=.true.), choice_key('gap', 'geometry|zero'), &
                       real_key('mu', ge=zero, le=max_mu), real_key('tresca', ge=zero, note=', a shear stress'), &
                       choice_key('interference', 'allow|reject'), choice_key('sliding', 'small|finite'), &
                       text_key('name', 'NAME')])
    call add_row(table, 'SOLVER', '', do_solver, once=.true., words=0, usage=solver_usage, &
                 keys=[choice_key('lcp', 'auto|lemke|pgs|pdas'), real_key('tol', gt=zero), &
                       integer_key('maxit', at_least=0), real_key('omega', gt=zero, lt=2.0_dp), &
                       choice_key('ordering', 'auto|metis|amd'), choice_key('condense', 'auto|solve|inverse'), &
                       choice_key('cut', 'auto|off'), integer_key('updates', at_least=1), &
                       real_key('newton_tol', gt=zero, lt=1.0_dp, note=', a relative residual'), &
                       integer_key('newton_maxit', at_least=1), choice_key('newton_lcp', 'lemke|active_set')])
    call add_row(table, 'STEPS', '', do_steps, once=.true., usage='STEPS n with an integer 1 <= n <= 100000')
    call add_row(table, 'ESTIMATE', '', do_estimate, once=.true., usage='ESTIMATE [on|off|bound]')
    call add_row(table, 'ADAPT', '', do_adapt, once=.true., words=0, &
                 usage='ADAPT target=number [quantity=energy|pressure] [max_steps=N] [max_dofs=N]', &
                 keys=[real_key('target', required=.true., gt=zero, lt=1.0_dp, note=', a relative error'), &
                       choice_key('quantity', 'energy|pressure'), integer_key('max_steps'), &
                       integer_key('max_dofs', at_least=100)])
    call add_row(table, 'CURVE', '', do_curve, &
                 usage='CURVE name t0:v0 t1:v1 ... with step numbers t0 < t1 < ... and load factors v')
    call add_row(table, 'OUTPUT', '', do_output, once=.true., words=0, &
                 usage='OUTPUT [vtk=NAME] [contact=NAME] [summary=NAME] [fields=LIST] [steps=last|all] ' // &
                       '[plot=none|png] [x=COLUMN]', &
                 keys=[text_key('vtk', 'NAME'), text_key('contact', 'NAME'), text_key('summary', 'NAME'), &
                       text_key('fields', 'LIST'), text_key('steps', 'last|all'), choice_key('plot', 'none|png'), &
                       text_key('x', 'COLUMN')])
    call add_row(table, 'PARAMETER', '*', do_parameter)
    call add_row(table, 'RIGID', '', do_rigid, opens='RIGID', usage='RIGID name')
    call add_row(table, 'SHAPE', 'RIGID', do_rigid_shape, once=.true., expected='one SHAPE per RIGID', words=1, &
                 usage=shape_usage, &
                 keys=[real_key('x0'), real_key('y0'), real_key('x1'), real_key('y1'), real_key('xc'), &
                       real_key('yc'), real_key('r', gt=zero), choice_key('solid', 'inside|outside'), &
                       text_key('points', 'x1:y1,x2:y2,...')])
    call add_row(table, 'REF', 'RIGID', do_rigid_ref, once=.true., expected='one REF per RIGID', words=0, &
                 usage='REF x=number y=number', keys=[real_key('x', required=.true.), real_key('y', required=.true.)])
    call add_row(table, 'FIX', 'RIGID', do_rigid_load, words=0, &
                 usage='FIX [ux=number] [uy=number] [rz=radians]' // ramp_curve, &
                 keys=[real_key('ux'), real_key('uy'), real_key('rz'), ramp_key(), curve_key()])
    call add_row(table, 'FORCE', 'RIGID', do_rigid_load, words=0, &
                 usage='FORCE [fx=number] [fy=number] [m=number]' // ramp_curve, &
                 keys=[real_key('fx'), real_key('fy'), real_key('m'), ramp_key(), curve_key()])
  end subroutine define_statements

  ! ================================================================ top-level statements

  !> TITLE free text
  subroutine do_title(s, deck, st)
    type(state_t), intent(inout) :: s
    type(deck_t), intent(inout) :: deck
    type(stmt_t), intent(in) :: st
    integer :: i
    deck%title = st%rest
    do i = 1, len(deck%title)
      if (iachar(deck%title(i:i)) < 32 .or. iachar(deck%title(i:i)) == 127) deck%title(i:i) = '?'
    end do
  end subroutine do_title

  !> PLANE strain | PLANE stress [thickness=] | PLANE axisymmetric: the form-less
  !> row (a missing or unknown kind) and the three forms.
  subroutine do_plane(s, deck, st)
    type(state_t), intent(inout) :: s
    type(deck_t), intent(inout) :: deck
    type(stmt_t), intent(in) :: st
    type(key_values_t) :: v
    character(len=:), allocatable :: kind

    deck%plane_line = st%line
    kind = form_word(s, st, 'plane')
    if (len(kind) == 0) return
    if (kind /= 'strain' .and. kind /= 'stress' .and. kind /= 'axisymmetric') then
      call report(s, st%line, 'unknown plane kind ' // quoted(st%word(1)%s) // ' (expected ' // st%usage // ')')
      return
    end if
    call read_keys(s, st, v, 'PLANE ' // kind)
    select case (kind)
    case ('strain')
      deck%plane_stress = .false.
      if (v%seen(1)) call report(s, st%line, 'thickness= only with PLANE stress (PLANE strain is per unit thickness)')
    case ('axisymmetric')
      deck%axisymmetric = .true.
      if (v%seen(1)) call report(s, st%line, 'thickness= only with PLANE stress (PLANE axisymmetric is the ' // &
                                 'full solid of revolution)')
    case default
      deck%plane_stress = .true.
      if (v%ok(1)) deck%thickness = v%x(1)
    end select
  end subroutine do_plane

  !> CONTACT slave=body:boundary master=body:boundary [gap=geometry|zero] [mu=number | tresca=number]
  !>         [interference=allow|reject] [sliding=small|finite] [name=NAME]
  !>   s    (inout) the reader's state: errors, the pairs' body names
  !>   deck (inout) receives the pair
  !>   st   (in)    the statement
  subroutine do_contact(s, deck, st)
    type(state_t), intent(inout) :: s
    type(deck_t), intent(inout) :: deck
    type(stmt_t), intent(in) :: st
    type(key_values_t) :: v
    logical :: ok_s, ok_m, rigid_master
    type(contact_deck_t) :: c
    type(string_t), allocatable :: gs(:), gm(:)
    character(len=:), allocatable :: sbody, mbody
    integer :: nerr0, i

    nerr0 = s%nerr
    call read_keys(s, st, v)
    call split_side(s, st, v%text(1), 'slave', sbody, c%slave_boundary, ok_s)
    rigid_master = allocated(v%text(2)%s)             ! (Fortran does not cut .and. short)
    if (rigid_master) rigid_master = index(v%text(2)%s, ':') == 0 .and. is_name(v%text(2)%s)
    if (rigid_master) then
      mbody = v%text(2)%s                            ! master=RIGIDNAME: resolved after the deck
      c%master_boundary = ''
      ok_m = .false.
    else
      call split_side(s, st, v%text(2), 'master', mbody, c%master_boundary, ok_m)
    end if
    if (ok_s .and. ok_m) then
      if (sbody == mbody .and. c%slave_boundary == c%master_boundary) &
        call report(s, st%line, 'slave and master must be different boundaries (both are ' // &
                    cut(sbody // ':' // c%slave_boundary) // ')')
    end if
    c%gap_zero = v%ok(3) .and. v%text(3)%s == 'zero'
    ! an initial penetration deeper than a slave element is an input error unless allowed
    c%interference = v%ok(6) .and. v%text(6)%s == 'allow'
    ! small sliding (the default): pairing, gaps and normals of the initial configuration, a
    ! run that slides beyond it ending in exit 1 (contact_checks); finite sliding rebuilds them
    ! from the current configuration (contact_solve)
    c%finite = v%ok(7) .and. v%text(7)%s == 'finite'
    c%small_given = v%ok(7) .and. v%text(7)%s == 'small'
    ! gap=zero sets the gaps of the initial configuration; finite sliding measures them at every step
    if (c%finite .and. v%ok(3)) then
      if (v%text(3)%s == 'zero') call report(s, st%line, 'sliding=finite with gap=zero (expected gap=geometry: ' // &
        'finite sliding measures the gaps in the current configuration)')
    end if
    ! friction (beyond the paper): |tau| <= mu p (Coulomb) or |tau| <= tresca
    c%friction = 'none'
    if (v%seen(4) .and. v%seen(5)) &
      call report(s, st%line, 'mu= and tresca= together (expected one friction law per CONTACT)')
    if (v%ok(4)) then
      c%mu = v%x(4)
      c%friction = 'coulomb'
    end if
    if (v%ok(5)) then
      c%tresca = v%x(5)
      c%friction = 'tresca'
    end if
    call contact_name(s, deck, st, v, c)
    c%line = st%line
    if (s%nerr /= nerr0) then
      s%contact_bad = .true.
      return
    end if
    deck%contacts = [deck%contacts, c]
    if (s%ncontact + 1 > size(s%slave_name)) then
      allocate(gs(2 * size(s%slave_name)), gm(2 * size(s%slave_name)))
      do i = 1, s%ncontact
        call move_alloc(s%slave_name(i)%s, gs(i)%s)
        call move_alloc(s%master_name(i)%s, gm(i)%s)
      end do
      call move_alloc(gs, s%slave_name)
      call move_alloc(gm, s%master_name)
    end if
    s%ncontact = s%ncontact + 1
    s%slave_name(s%ncontact)%s = sbody
    s%master_name(s%ncontact)%s = mbody
  end subroutine do_contact

  !> name=NAME of a CONTACT: a word (a letter or _, then letters, digits, _)
  !> that no other CONTACT has, so that the summary's lines and the sweep's
  !> columns it labels (contact_force_NAME_fx) are one per pair and cannot be
  !> read as a pair's number.  Without it c%name is '' (the pair's number).
  !>   s    (inout) the reader's state: receives the errors
  !>   deck (in)    the CONTACTs read so far
  !>   st   (in)    the statement
  !>   v    (in)    its keys (name= the 8th)
  !>   c    (inout) the pair: c%name set
  subroutine contact_name(s, deck, st, v, c)
    type(state_t), intent(inout) :: s
    type(deck_t), intent(in) :: deck
    type(stmt_t), intent(in) :: st
    type(key_values_t), intent(in) :: v
    type(contact_deck_t), intent(inout) :: c
    integer :: j
    c%name = ''
    if (.not. allocated(v%text(8)%s)) return
    if (.not. is_identifier(v%text(8)%s)) then
      call report(s, st%line, 'bad contact name ' // quoted(v%text(8)%s) // ' (expected a word: a letter or _, ' // &
                  'then letters, digits, _; at most 64)')
      return
    end if
    do j = 1, size(deck%contacts)
      if (deck%contacts(j)%name == v%text(8)%s) then
        call report(s, st%line, 'contact name ' // quoted(v%text(8)%s) // ' already names the CONTACT of line ' // &
                    int_to_str(deck%contacts(j)%line) // ' (expected a name of its own per CONTACT)')
        return
      end if
    end do
    c%name = v%text(8)%s
  end subroutine contact_name

  !> Split 'body:boundary'; report a bad form.  ok false when absent or bad.
  subroutine split_side(s, st, val, name, body, boundary, ok)
    type(state_t), intent(inout) :: s
    type(stmt_t), intent(in) :: st
    type(string_t), intent(in) :: val
    character(len=*), intent(in) :: name
    character(len=:), allocatable, intent(out) :: body
    character(len=:), allocatable, intent(inout) :: boundary
    logical, intent(out) :: ok
    integer :: colon
    body = ''
    boundary = ''
    ok = .false.
    if (.not. allocated(val%s)) return
    colon = index(val%s, ':')
    if (colon > 1 .and. colon < len(val%s)) then
      body = val%s(1:colon - 1)
      boundary = val%s(colon + 1:)
      ok = is_name(body) .and. is_name(boundary)
    end if
    if (.not. ok) call report(s, st%line, 'bad value ' // name // '=' // cut(val%s) // ' (expected ' // name // &
                              '=body:boundary, names made of letters, digits, _ . -)')
  end subroutine split_side

  !> SOLVER [lcp=] [tol=] [maxit=] [omega=] [ordering=] [condense=] [cut=] [updates=]
  !> [newton_tol=] [newton_maxit=] [newton_lcp=]
  subroutine do_solver(s, deck, st)
    type(state_t), intent(inout) :: s
    type(deck_t), intent(inout) :: deck
    type(stmt_t), intent(in) :: st
    type(key_values_t) :: v

    deck%solver%line = st%line
    call read_keys(s, st, v)
    if (v%ok(1)) deck%solver%lcp = v%text(1)%s
    if (v%ok(5)) deck%solver%ordering = v%text(5)%s
    if (v%ok(6)) deck%solver%condense = v%text(6)%s
    if (v%ok(7)) deck%solver%cut = v%text(7)%s
    if (v%ok(2)) deck%solver%tol = v%x(2)
    if (v%ok(3)) deck%solver%maxit = v%k(3)
    if (v%ok(4)) deck%solver%omega = v%x(4)
    if (v%ok(8)) deck%solver%updates = v%k(8)
    if (v%ok(9)) deck%solver%newton_tol = v%x(9)
    if (v%ok(10)) deck%solver%newton_maxit = v%k(10)
    if (v%ok(11)) deck%solver%newton_lcp = v%text(11)%s
  end subroutine do_solver

  !> STEPS n: the number of load steps (the ramps run over steps 0..n)
  subroutine do_steps(s, deck, st)
    type(state_t), intent(inout) :: s
    type(deck_t), intent(inout) :: deck
    type(stmt_t), intent(in) :: st
    integer :: n, nerr0
    logical :: ok

    deck%steps_line = st%line
    nerr0 = s%nerr
    if (st%nword == 0) then
      if (st%npair == 0) call report(s, st%line, 'missing number of load steps (expected ' // st%usage // ')')
    else
      call parse_integer(st%word(1)%s, n, ok)
      if (ok) ok = n >= 1 .and. n <= max_steps
      if (ok) then
        deck%steps = n
      else
        call report(s, st%line, 'bad number of load steps ' // quoted(st%word(1)%s) // ' (expected ' // st%usage // ')')
      end if
      call check_extra_words(s, st, 1, st%usage)
    end if
    call check_no_pairs(s, st)
    s%steps_bad = s%nerr /= nerr0
  end subroutine do_steps

  !> ESTIMATE [on|off|bound]: the a posteriori error estimate of the run (on
  !> when the deck does not say); bound: on, and the guaranteed bound too.
  subroutine do_estimate(s, deck, st)
    type(state_t), intent(inout) :: s
    type(deck_t), intent(inout) :: deck
    type(stmt_t), intent(in) :: st
    deck%estimate_line = st%line
    if (st%nword >= 1) then
      select case (st%word(1)%s)
      case ('on')
        deck%estimate = .true.
      case ('off')
        deck%estimate = .false.
      case ('bound')
        deck%estimate = .true.
        deck%estimate_bound = .true.
      case default
        call report(s, st%line, 'bad value ' // quoted(st%word(1)%s) // ' (expected ' // st%usage // ')')
      end select
      call check_extra_words(s, st, 1, st%usage)
    end if
    call check_no_pairs(s, st)
  end subroutine do_estimate

  !> ADAPT target= [quantity=energy|pressure] [max_steps=] [max_dofs=]: the
  !> adaptive loop (its checks against the rest of the deck: deck_checks).
  subroutine do_adapt(s, deck, st)
    type(state_t), intent(inout) :: s
    type(deck_t), intent(inout) :: deck
    type(stmt_t), intent(in) :: st
    type(key_values_t) :: v
    deck%adapt%line = st%line
    call read_keys(s, st, v)
    deck%adapt%on = .true.
    deck%adapt%quantity = 'energy'
    if (v%ok(1)) deck%adapt%target = v%x(1)
    if (v%ok(2)) deck%adapt%quantity = v%text(2)%s
    if (v%ok(3)) deck%adapt%max_steps = v%k(3)
    if (v%ok(4)) deck%adapt%max_dofs = v%k(4)
  end subroutine do_adapt

  !> CURVE name t0:v0 t1:v1 ...: a piecewise-linear load factor against the
  !> step number, at least one point, t strictly increasing (numbers, not
  !> necessarily integers).
  subroutine do_curve(s, deck, st)
    type(state_t), intent(inout) :: s
    type(deck_t), intent(inout) :: deck
    type(stmt_t), intent(in) :: st
    type(curve_t) :: c
    integer :: k, colon, nerr0
    logical :: ok, ok1, ok2
    character(len=:), allocatable :: w

    nerr0 = s%nerr
    c%line = st%line
    call check_no_pairs(s, st)
    if (st%nword == 0) then
      call report(s, st%line, 'missing curve name (expected ' // st%usage // ')')
      return
    end if
    call check_name(s, st, st%word(1)%s, 'curve', ok)
    if (.not. ok) return
    c%name = st%word(1)%s
    do k = 1, size(deck%curves)
      if (deck%curves(k)%name == c%name .and. len(deck%curves(k)%name) == len(c%name)) then
        call report(s, st%line, 'second CURVE ' // quoted(c%name) // ' (first at line ' // &
                    int_to_str(deck%curves(k)%line) // '; expected unique curve names)')
        return
      end if
    end do
    if (st%nword == 1) then
      call report(s, st%line, 'curve ' // quoted(c%name) // ' has no points (expected ' // st%usage // ')')
      return
    end if
    allocate(c%t(st%nword - 1), c%v(st%nword - 1))
    do k = 2, st%nword
      w = st%word(k)%s
      colon = index(w, ':')
      ok1 = .false.
      ok2 = .false.
      if (colon > 1 .and. colon < len(w)) then
        call parse_real(w(1:colon - 1), c%t(k - 1), ok1)
        call parse_real(w(colon + 1:), c%v(k - 1), ok2)
      end if
      if (.not. (ok1 .and. ok2)) then
        call report(s, st%line, 'bad curve point ' // quoted(cut(w)) // ' (expected t:v, two numbers: the step ' // &
                    'and the load factor)')
        return
      end if
      if (k > 2) then
        if (.not. c%t(k - 1) > c%t(k - 2)) then
          call report(s, st%line, 'curve ' // quoted(c%name) // ': step ' // quoted(w(1:colon - 1)) // &
                      ' not after the previous point''s (expected increasing steps t0 < t1 < ...)')
          return
        end if
      end if
    end do
    if (s%nerr /= nerr0) return
    deck%curves = [deck%curves, c]
  end subroutine do_curve

  !> OUTPUT [vtk=] [contact=] [summary=] [fields=] [steps=] [plot=] [x=]
  !> (x=: a column of the steps table, known only once the scene is built:
  !> run_plots' check_plot_column checks the name)
  subroutine do_output(s, deck, st)
    type(state_t), intent(inout) :: s
    type(deck_t), intent(inout) :: deck
    type(stmt_t), intent(in) :: st
    character(len=16), parameter :: field_names(5) = [character(len=16) :: 'displacement', 'contact_pressure', &
                                                      'gap', 'stress', 'von_mises']
    type(key_values_t) :: v
    integer :: k, p, q, f
    character(len=:), allocatable :: item

    deck%output%line = st%line
    call read_keys(s, st, v)
    if (v%ok(6)) deck%output%plot = v%text(6)%s == 'png'
    if (allocated(v%text(5)%s)) then
      select case (lower(v%text(5)%s))
      case ('last')
        deck%output%steps_all = .false.
      case ('all')
        deck%output%steps_all = .true.
      case default
        call report(s, st%line, 'bad value ' // quoted(cut(v%text(5)%s)) // ' for steps= (expected steps=last or ' // &
                    'steps=all)')
      end select
    end if
    if (allocated(v%text(4)%s)) then
      ! fields=a,b,c (or all, or none): the arrays of the VTK file
      deck%output%fields = .false.
      p = 1
      do while (p <= len(v%text(4)%s) + 1)
        q = index(v%text(4)%s(p:), ',')
        if (q == 0) then
          q = len(v%text(4)%s) + 1
        else
          q = p + q - 1
        end if
        item = lower(v%text(4)%s(p:q - 1))
        f = find_key(item, field_names)
        if (item == 'all') then
          deck%output%fields = .true.
        else if (item == 'none') then
          continue
        else if (f == 0) then
          call report(s, st%line, 'unknown field ' // quoted(cut(item)) // ' in fields= (expected a comma-separated ' // &
                      'list of ' // join_list(field_names, ', ') // ', or all, or none)')
          exit
        else
          deck%output%fields(f) = .true.
        end if
        p = q + 1
      end do
    end if
    do k = 1, 3
      if (.not. allocated(v%text(k)%s)) cycle
      if (.not. is_name(v%text(k)%s) .or. v%text(k)%s == '.' .or. v%text(k)%s == '..') then
        call report(s, st%line, 'bad file name ' // trim(st%keys(k)%name) // '=' // cut(v%text(k)%s) // ' (expected a ' // &
                    'name in the output folder: letters, digits, _ . - only, no /)')
        cycle
      end if
      select case (k)
      case (1)
        deck%output%vtk = v%text(k)%s
        if (.not. ends_with_ci(v%text(k)%s, '.vtk')) deck%output%vtk = v%text(k)%s // '.vtk'
      case (2)
        deck%output%contact = v%text(k)%s
      case (3)
        deck%output%summary = v%text(k)%s
      end select
    end do
    if (allocated(v%text(7)%s)) then
      ! x= acts on the steps plot only, which needs the steps table
      if (.not. (deck%output%plot .and. deck%output%steps_all)) then
        call report(s, st%line, 'x=' // cut(v%text(7)%s) // ' chooses the abscissa of the steps plot, drawn with ' // &
                    'steps=all and plot=png (expected OUTPUT steps=all plot=png x=COLUMN)')
      else
        deck%output%x = v%text(7)%s
      end if
    end if
  end subroutine do_output

  !> PARAMETER name=value ...: each value an expression of the parameters
  !> declared before it; a -D or --cases value replaces it.
  subroutine do_parameter(s, deck, st)
    type(state_t), intent(inout) :: s
    type(deck_t), intent(inout) :: deck
    type(stmt_t), intent(in) :: st
    character(len=:), allocatable :: message
    real(dp) :: x
    integer :: i, k
    if (st%npair == 0) call report(s, st%line, 'PARAMETER declares nothing (expected PARAMETER name=value ...)')
    do i = 1, st%nword
      call report(s, st%line, 'word ' // quoted(st%word(i)%s) // ' in PARAMETER (expected name=value, ' // &
                  'without blanks inside the value, or ${...} around it)')
    end do
    do i = 1, st%npair
      associate (name => st%key(i)%s)
        if (.not. is_parameter_name(name)) then
          call report(s, st%line, 'bad parameter name ' // quoted(name) // ' (expected a letter or _ then ' // &
                      'letters, digits, _; at most 64; not pi or a function name)')
          cycle
        end if
        k = find_parameter(deck%params, name)
        if (k > 0) then
          call report(s, st%line, 'parameter ' // quoted(name) // ' declared twice (first at line ' // &
                      int_to_str(deck%params%line(k)) // '; expected each name once)')
          cycle
        end if
        call evaluate(st%value(i)%s, deck%params, x, message)
        if (allocated(message)) then
          call report(s, st%line, 'parameter ' // quoted(name) // ': ' // message)
          cycle
        end if
        k = find_parameter(s%overrides, name)
        if (k > 0) then
          call add_parameter(deck%params, name, s%overrides%value(k), s%overrides%origin(k), st%line)
        else
          call add_parameter(deck%params, name, x, 'default', st%line)
        end if
      end associate
    end do
  end subroutine do_parameter

end module deck_statements
