!> deck_body_statements: the statements of a BODY ... END block, one handler
!> each (the rows are in deck_statements' table, with their keys, types and
!> ranges; read_keys has checked and converted those before a handler runs).
!>
!>   BODY name                      opens the block (deck%bodies grows by one)
!>   MESH rect ... | MESH gmsh ...  one row per form; the form-less row reports a missing or unknown kind
!>   MATERIAL isotropic | orthotropic, DENSITY, FIX, TRACTION, PRESSURE,
!>   BODYFORCE, THERMAL, OFFSET,
!>   FORCE (a point force), SPRING  see deck_reader's header for their keys
!>   GRAVITY                        a top-level statement, read as BODYFORCE is
!>
!> Programming interface (statement handlers, deck_syntax's statement_handler)
!>   do_body, do_mesh, do_mesh_rect, do_mesh_gmsh, do_material (its three rows), do_density,
!>   do_fix, do_load (TRACTION, PRESSURE, FORCE in a BODY), do_thermal, do_vector (BODYFORCE, OFFSET,
!>   GRAVITY), do_spring
!>   plane_compliance_ok, strain_compliance_ok   orthotropic compliance positive definite
module deck_body_statements
  use kinds, only: dp
  use strings, only: int_to_str, format_number
  use safe_files, only: file_kind, kind_name, c2d_regular, c2d_missing, c2d_unreadable
  use deck_types, only: deck_t, body_deck_t, fix_t, load_t, material_t, thermal_t, load_traction, load_pressure, &
                        load_point, spring_deck_t
  use deck_syntax, only: state_t, stmt_t, key_values_t, report, read_keys, check_extra_words, check_no_pairs, &
                         check_name, form_word, cut, quoted, shown
  use text_scan, only: parse_real, lower, is_identifier, is_printable, ends_with_ci
  use, intrinsic :: iso_fortran_env, only: int64
  implicit none
  private
  public :: do_body, do_mesh, do_mesh_rect, do_mesh_gmsh, do_material, do_density, do_fix, do_load
  public :: do_thermal, do_vector, do_spring, plane_compliance_ok, strain_compliance_ok

contains

  !> BODY name
  subroutine do_body(s, deck, st)
    type(state_t), intent(inout) :: s
    type(deck_t), intent(inout) :: deck
    type(stmt_t), intent(in) :: st
    type(body_deck_t) :: body
    integer :: b
    logical :: ok

    body%line = st%line
    body%name = ''
    allocate(body%fixes(0), body%loads(0), body%thermals(0), body%springs(0))
    if (st%nword == 0) then
      call report(s, st%line, 'missing body name (expected ' // st%usage // ')')
    else
      body%name = st%word(1)%s
      call check_name(s, st, body%name, 'body', ok)
      if (ok) then
        do b = 1, s%nbody
          if (deck%bodies(b)%name == body%name) then
            call report(s, st%line, 'duplicate BODY name ' // quoted(body%name) // ' (first at line ' // &
                        int_to_str(deck%bodies(b)%line) // '; expected a new name)')
            exit
          end if
        end do
      end if
      call check_extra_words(s, st, 1, st%usage)
    end if
    call check_no_pairs(s, st)
    deck%bodies = [deck%bodies, body]
    s%nbody = s%nbody + 1
    s%cur = s%nbody
    s%end_hinted = .false.
    s%block_name = body%name
    s%block_line = body%line
  end subroutine do_body

  !> MESH without a known kind: the form-less row of MESH.
  subroutine do_mesh(s, deck, st)
    type(state_t), intent(inout) :: s
    type(deck_t), intent(inout) :: deck
    type(stmt_t), intent(in) :: st
    deck%bodies(s%cur)%mesh%line = st%line
    if (len(form_word(s, st, 'mesh')) > 0) call report(s, st%line, 'unknown mesh kind ' // quoted(st%word(1)%s) // &
                                                       ' (expected rect or gmsh)')
  end subroutine do_mesh

  !> MESH rect [x0=] [y0=] [x1=] [y1=] nx= ny= [elem=] [diag=]
  subroutine do_mesh_rect(s, deck, st)
    type(state_t), intent(inout) :: s
    type(deck_t), intent(inout) :: deck
    type(stmt_t), intent(in) :: st
    type(key_values_t) :: v
    logical :: known(4)

    associate (m => deck%bodies(s%cur)%mesh)
      m%line = st%line
      m%kind = 'rect'
      call read_keys(s, st, v)
      if (v%ok(1)) m%x0 = v%x(1)
      if (v%ok(2)) m%y0 = v%x(2)
      if (v%ok(3)) m%x1 = v%x(3)
      if (v%ok(4)) m%y1 = v%x(4)
      known = v%ok(1:4) .or. .not. v%seen(1:4)            ! valid or the default
      if (known(1) .and. known(3) .and. .not. m%x1 > m%x0) &
        call report(s, st%line, 'bad rectangle x0=' // shown(v%text(1), '0') // ' x1=' // shown(v%text(3), '1') // &
                    ' (expected x1 > x0)')
      if (known(2) .and. known(4) .and. .not. m%y1 > m%y0) &
        call report(s, st%line, 'bad rectangle y0=' // shown(v%text(2), '0') // ' y1=' // shown(v%text(4), '1') // &
                    ' (expected y1 > y0)')
      if (v%ok(5)) m%nx = v%k(5)
      if (v%ok(6)) m%ny = v%k(6)
      if (m%nx > 0 .and. m%ny > 0) then
        if (int(m%nx, int64) * int(m%ny, int64) > 100000000_int64) &
          call report(s, st%line, 'rect mesh too large (expected nx*ny <= 100000000)')
      end if
      m%elem = 'tri3'
      m%diag = 'right'
      if (allocated(v%text(7)%s)) m%elem = merge_text(v%ok(7), v%text(7)%s)
      if (allocated(v%text(8)%s)) then
        m%diag = merge_text(v%ok(8), v%text(8)%s)
        if (m%elem(1:1) == 'q') call report(s, st%line, 'diag= applies only to elem=tri3 or tri6 (got elem=' // &
                                            m%elem // ')')
      end if
    end associate
  end subroutine do_mesh_rect

  !> A choice's value when valid, '' when not.
  pure function merge_text(ok, text) result(t)
    logical, intent(in) :: ok
    character(len=*), intent(in) :: text
    character(len=:), allocatable :: t
    t = ''
    if (ok) t = text
  end function merge_text

  !> MESH gmsh file=NAME.msh | file=NAME.geo [name=number ...]
  !> Its keys are the file and the .geo file's own variables: read here, not from the row.
  subroutine do_mesh_gmsh(s, deck, st)
    type(state_t), intent(inout) :: s
    type(deck_t), intent(inout) :: deck
    type(stmt_t), intent(in) :: st
    integer :: i, j, nset, ifile, kind
    logical :: ok, is_msh, seen_order
    real(dp) :: x

    associate (m => deck%bodies(s%cur)%mesh, dir => deck%dir, usage => st%usage)
    m%line = st%line
    m%kind = 'gmsh'
    m%elem = ''
    m%diag = ''
    seen_order = .false.
    call check_extra_words(s, st, 1, usage)
    ifile = 0
    do i = 1, st%npair
      if (lower(st%key(i)%s) /= 'file') cycle
      if (ifile > 0) then
        call report(s, st%line, 'duplicate key "file" (expected each key at most once)')
      else
        ifile = i
      end if
    end do
    if (ifile == 0) then
      call report(s, st%line, 'missing key "file" for MESH gmsh (expected ' // usage // ')')
      return
    end if
    m%file = st%value(ifile)%s
    if (len(m%file) == 0) then
      call report(s, st%line, 'missing value for "file" (expected file=NAME.msh or file=NAME.geo)')
      return
    end if
    is_msh = ends_with_ci(m%file, '.msh')
    m%is_geo = ends_with_ci(m%file, '.geo')
    if (.not. (is_msh .or. m%is_geo) .or. len(m%file) < 5 .or. .not. is_printable(m%file)) then
      call report(s, st%line, 'bad mesh file name ' // quoted(m%file) // ' (expected a name ending in .msh or .geo)')
      return
    end if
    if (m%file(1:1) == '/' .or. dir == '.') then
      m%path = m%file
    else if (dir == '/') then
      m%path = '/' // m%file
    else
      m%path = dir // '/' // m%file
    end if
    kind = file_kind(m%path)
    if (kind == c2d_missing) then
      call report(s, st%line, 'cannot find mesh file ' // quoted(m%file) // ' (looked for ' // cut(m%path) // ')')
    else if (kind /= c2d_regular .and. kind /= c2d_unreadable) then
      call report(s, st%line, 'mesh file ' // quoted(m%file) // ' is ' // kind_name(kind) // &
                  ', not a regular file: refused (a .msh or .geo file expected)')
    end if

    nset = 0
    allocate(m%set_names(st%npair), m%set_values(st%npair))
    do i = 1, st%npair
      if (i == ifile .or. lower(st%key(i)%s) == 'file') cycle
      if (len(st%key(i)%s) == 0) then
        call report(s, st%line, 'missing key before ' // quoted('=' // st%value(i)%s) // ' (expected key=value)')
        cycle
      end if
      if (is_msh) then
        call report(s, st%line, 'unknown key ' // quoted(st%key(i)%s) // ' for MESH gmsh with a .msh file ' // &
                    '(expected file= only; name=number pairs are for .geo files)')
        cycle
      end if
      if (lower(st%key(i)%s) == 'order') then        ! gmsh -order 1 or 2, not a .geo variable
        if (seen_order) then
          call report(s, st%line, 'duplicate key "order" (expected each key at most once)')
        else if (st%value(i)%s == '1' .or. st%value(i)%s == '2') then
          m%order = merge(2, 1, st%value(i)%s == '2')
        else
          call report(s, st%line, 'bad value order=' // cut(st%value(i)%s) // ' (expected order=1|2)')
        end if
        seen_order = .true.
        cycle
      end if
      if (.not. is_identifier(st%key(i)%s)) then
        call report(s, st%line, 'bad parameter name ' // quoted(st%key(i)%s) // ' for MESH gmsh (expected a ' // &
                    '.geo variable: a letter or _, then letters, digits or _, at most 64 characters)')
        cycle
      end if
      do j = 1, nset
        if (trim(m%set_names(j)) == st%key(i)%s) exit
      end do
      if (j <= nset) then
        call report(s, st%line, 'duplicate key ' // quoted(st%key(i)%s) // ' (expected each key at most once)')
        cycle
      end if
      if (len(st%value(i)%s) == 0) then
        call report(s, st%line, 'missing value for ' // quoted(st%key(i)%s) // ' (expected ' // st%key(i)%s // &
                    '=number)')
        cycle
      end if
      call parse_real(st%value(i)%s, x, ok)
      if (.not. ok) then
        call report(s, st%line, 'bad number ' // quoted(st%value(i)%s) // ' for ' // quoted(st%key(i)%s) // &
                    ' (expected a finite number)')
        cycle
      end if
      nset = nset + 1
      m%set_names(nset) = st%key(i)%s
      m%set_values(nset) = x
    end do
    m%set_names = m%set_names(1:nset)
    m%set_values = m%set_values(1:nset)
    end associate
  end subroutine do_mesh_gmsh

  !> MATERIAL isotropic E= nu= | MATERIAL orthotropic E1= E2= nu12= G12= [angle=]
  !> [E3=] [nu13=] [nu23=] | MATERIAL neo_hookean mu= K= | MATERIAL mooney_rivlin
  !> c10= c01= K=; on the form-less row, a missing or unknown kind.
  subroutine do_material(s, deck, st)
    type(state_t), intent(inout) :: s
    type(deck_t), intent(inout) :: deck
    type(stmt_t), intent(in) :: st
    type(key_values_t) :: v
    type(material_t) :: mat
    integer :: nerr0

    deck%bodies(s%cur)%material%line = st%line
    deck%bodies(s%cur)%material%kind = ''
    nerr0 = s%nerr
    if (st%what == 'MATERIAL') then
      if (len(form_word(s, st, 'material')) > 0) call report(s, st%line, 'unknown material kind ' // &
        quoted(st%word(1)%s) // &
        ' (expected isotropic, orthotropic, neo_hookean or mooney_rivlin)')
      return
    end if
    call read_keys(s, st, v)
    mat%line = st%line
    select case (st%what)
    case ('MATERIAL isotropic')
      mat%kind = 'isotropic'
      mat%e = v%x(1)
      mat%nu = v%x(2)
    case ('MATERIAL neo_hookean')                      ! W = mu/2 (J^-2/3 I1 - 3) + ...: c10 = mu/2
      mat%kind = 'neo_hookean'
      mat%c10 = 0.5_dp * v%x(1)
      mat%bulk = v%x(2)
    case ('MATERIAL mooney_rivlin')
      mat%kind = 'mooney_rivlin'
      mat%c10 = v%x(1)
      mat%c01 = v%x(2)
      mat%bulk = v%x(3)
      ! the initial shear modulus mu = 2 (c10 + c01) must be positive, and so
      ! must c10 + c01 J^-2/3 (I2 / I1) for W to stay convex in shear at large
      ! stretches: both hold with c10 >= 0 and c10 + c01 > 0
      if (all(v%ok(1:2))) then
        if (.not. (mat%c10 >= 0.0_dp .and. mat%c10 + mat%c01 > 0.0_dp)) call report(s, st%line, &
          'bad moduli c10=' // trim(format_number(mat%c10)) // ' c01=' // trim(format_number(mat%c01)) // &
          ' (expected c10 >= 0 and c10 + c01 > 0: the shear modulus 2 (c10 + c01) positive)')
      end if
    case default
      mat%kind = 'orthotropic'
      mat%e1 = v%x(1)
      mat%e2 = v%x(2)
      mat%nu12 = v%x(3)
      mat%g12 = v%x(4)
      mat%angle = v%x(5)
      mat%e3 = merge(v%x(6), mat%e2, v%ok(6))          ! E3 = E2, nu13 = nu23 = nu12 by default
      mat%nu13 = merge(v%x(7), mat%nu12, v%ok(7))
      mat%nu23 = merge(v%x(8), mat%nu12, v%ok(8))
      if (all(v%ok(1:3))) then
        if (.not. plane_compliance_ok(mat)) call report(s, st%line, 'orthotropic in-plane compliance not ' // &
                                                        'positive definite (expected nu12^2 < E1/E2)')
      end if
    end select
    if (s%nerr == nerr0) deck%bodies(s%cur)%material = mat
  end subroutine do_material

  !> 1 - nu12^2 E2/E1 > 0, computed without overflow.
  pure logical function plane_compliance_ok(m) result(ok)
    type(material_t), intent(in) :: m
    ok = 1.0_dp - ratio_term(2, [m%nu12], m%e2, m%e1) > 0
  end function plane_compliance_ok

  !> det of the normal 3x3 compliance (times E1 E2 E3 / E1 ...) > 0 in the form
  !> 1 - nu12^2 E2/E1 - nu23^2 E3/E2 - nu13^2 E3/E1 - 2 nu12 nu23 nu13 E3/E1 > 0.
  pure logical function strain_compliance_ok(m) result(ok)
    type(material_t), intent(in) :: m
    real(dp) :: det
    det = 1.0_dp - ratio_term(2, [m%nu12], m%e2, m%e1) - ratio_term(2, [m%nu23], m%e3, m%e2) &
          - ratio_term(2, [m%nu13], m%e3, m%e1) - 2.0_dp * ratio_term(1, [m%nu12, m%nu23, m%nu13], m%e3, m%e1)
    ok = det > 0
  end function strain_compliance_ok

  !> prod(nu)^power * num/den with num, den > 0, through logarithms and clamped at
  !> 1e250 in magnitude, so that no input overflows.
  pure real(dp) function ratio_term(power, nu, num, den) result(t)
    integer, intent(in) :: power
    real(dp), intent(in) :: nu(:), num, den
    real(dp) :: lg, sgn
    integer :: i
    t = 0
    if (any(nu == 0) .or. .not. (num > 0 .and. den > 0)) return
    lg = log(num) - log(den)
    sgn = 1
    do i = 1, size(nu)
      lg = lg + power * log(abs(nu(i)))
      if (nu(i) < 0) sgn = -sgn
    end do
    if (power == 2) sgn = 1
    t = sgn * exp(min(lg, 575.0_dp))
  end function ratio_term

  !> DENSITY rho=
  subroutine do_density(s, deck, st)
    type(state_t), intent(inout) :: s
    type(deck_t), intent(inout) :: deck
    type(stmt_t), intent(in) :: st
    type(key_values_t) :: v

    associate (body => deck%bodies(s%cur))
      body%density_line = st%line
      call read_keys(s, st, v)
      if (v%ok(1)) body%rho = v%x(1)
      body%has_density = v%ok(1)
    end associate
  end subroutine do_density

  !> The boundary a FIX, TRACTION, PRESSURE, SPRING (or the point a FORCE)
  !> names (its first word); '' when bad.
  !>   what (in, optional) what the name is, for messages (default 'boundary')
  subroutine read_boundary(s, st, boundary, what)
    type(state_t), intent(inout) :: s
    type(stmt_t), intent(in) :: st
    character(len=:), allocatable, intent(out) :: boundary
    character(len=*), intent(in), optional :: what
    character(len=:), allocatable :: named
    logical :: ok
    boundary = ''
    named = 'boundary'
    if (present(what)) named = what
    if (st%nword == 0) then
      call report(s, st%line, 'missing ' // named // ' name (expected ' // st%usage // ')')
    else
      call check_name(s, st, st%word(1)%s, named, ok)
      if (ok) boundary = st%word(1)%s
    end if
  end subroutine read_boundary

  !> A pair of components in x, y (keys 1, 2 of the row) or in the boundary's
  !> axes n, t (keys 5, 6), not both.
  !>   local (out) the n, t pair was given;  a, b (inout) its values (unchanged when absent or bad)
  subroutine read_component_pair(s, st, v, local, a, b)
    type(state_t), intent(inout) :: s
    type(stmt_t), intent(in) :: st
    type(key_values_t), intent(in) :: v
    logical, intent(out) :: local
    real(dp), intent(inout) :: a, b
    character(len=:), allocatable :: x, y, n, t
    integer :: i, j

    x = trim(st%keys(1)%name)
    y = trim(st%keys(2)%name)
    n = trim(st%keys(5)%name)
    t = trim(st%keys(6)%name)
    local = .false.
    if ((v%seen(1) .or. v%seen(2)) .and. (v%seen(5) .or. v%seen(6))) then
      call report(s, st%line, x // '=/' // y // '= and ' // n // '=/' // t // '= together (expected x, y ' // &
                  'components ' // x // ', ' // y // ' or boundary components ' // n // ', ' // t // &
                  ', not both: two statements for the two)')
      return
    end if
    local = v%seen(5) .or. v%seen(6)
    i = merge(5, 1, local)
    j = merge(6, 2, local)
    if (v%ok(i)) a = v%x(i)
    if (v%ok(j)) b = v%x(j)
  end subroutine read_component_pair

  !> FIX boundary [ux=] [uy=] | [un=] [ut=] [ramp=|curve=]
  subroutine do_fix(s, deck, st)
    type(state_t), intent(inout) :: s
    type(deck_t), intent(inout) :: deck
    type(stmt_t), intent(in) :: st
    type(fix_t), allocatable :: grown(:)
    type(fix_t) :: fix
    type(key_values_t) :: v

    associate (body => deck%bodies(s%cur))
      fix%line = st%line
      call read_boundary(s, st, fix%boundary)
      call read_keys(s, st, v)
      call read_component_pair(s, st, v, fix%local, fix%ux, fix%uy)
      fix%ramp = v%ramp
      fix%curve_name = v%curve
      fix%has_ux = v%seen(merge(5, 1, fix%local))      ! ux, uy hold un, ut
      fix%has_uy = v%seen(merge(6, 2, fix%local))
      if (.not. (fix%has_ux .or. fix%has_uy)) then     ! FIX boundary [ramp=]: clamp both
        fix%has_ux = .true.
        fix%has_uy = .true.
      end if
      ! capacity doubles: 1e5 FIX statements cost 1e5 copies in all, not 5e9
      if (body%nfix == size(body%fixes)) then
        allocate(grown(max(8, 2 * size(body%fixes))))
        grown(1:body%nfix) = body%fixes(1:body%nfix)
        call move_alloc(grown, body%fixes)
      end if
      body%nfix = body%nfix + 1
      body%fixes(body%nfix) = fix
    end associate
  end subroutine do_fix

  !> TRACTION boundary tx= ty= | tn= tt= [ramp=|curve=], PRESSURE boundary p=
  !> [ramp=|curve=], or FORCE point [fx=] [fy=] [ramp=|curve=] in a BODY: a
  !> force on the node(s) of a point set, kept with the body's loads
  !> (load_point); whether the name is a point set is known with the mesh
  !> (scene).
  subroutine do_load(s, deck, st)
    type(state_t), intent(inout) :: s
    type(deck_t), intent(inout) :: deck
    type(stmt_t), intent(in) :: st
    type(load_t) :: load
    type(key_values_t) :: v
    integer :: nerr0

    nerr0 = s%nerr
    load%line = st%line
    if (st%what == 'FORCE') then
      call read_boundary(s, st, load%boundary, 'point')
    else
      call read_boundary(s, st, load%boundary)
    end if
    call read_keys(s, st, v)
    select case (st%what)
    case ('TRACTION')
      load%kind = load_traction
      if (.not. any(v%seen([1, 2, 5, 6]))) call report(s, st%line, 'missing tx= and ty= (expected ' // st%usage // ')')
      call read_component_pair(s, st, v, load%local, load%tx, load%ty)
    case ('FORCE')
      load%kind = load_point
      if (.not. (v%seen(1) .or. v%seen(2))) call report(s, st%line, 'FORCE without a component (expected ' // &
                                                        st%usage // ')')
      if (v%ok(1)) load%tx = v%x(1)
      if (v%ok(2)) load%ty = v%x(2)
    case default
      load%kind = load_pressure
      load%p = v%x(1)
    end select
    load%ramp = v%ramp
    load%curve_name = v%curve
    if (s%nerr == nerr0) call append_load(deck%bodies(s%cur), load)
  end subroutine do_load

  !> SPRING boundary kn= [kt=] | SPRING point [kx=] [ky=]: the keys say which
  !> (kn, kt: a foundation on a boundary's edges; kx, ky: a spring at the
  !> node(s) of a point set), not both.
  subroutine do_spring(s, deck, st)
    type(state_t), intent(inout) :: s
    type(deck_t), intent(inout) :: deck
    type(stmt_t), intent(in) :: st
    type(spring_deck_t) :: spring
    type(key_values_t) :: v

    spring%line = st%line
    call read_boundary(s, st, spring%boundary)
    call read_keys(s, st, v)
    spring%point = v%seen(3) .or. v%seen(4)
    if ((v%seen(1) .or. v%seen(2)) .and. spring%point) then
      call report(s, st%line, 'kn=/kt= and kx=/ky= together (expected kn= [kt=] for a foundation on a boundary, ' // &
                  'or kx= ky= for a spring at a point, not both)')
    else if (.not. (spring%point .or. v%seen(1))) then
      call report(s, st%line, 'missing kn= (expected ' // st%usage // ')')
    end if
    if (v%ok(1)) spring%kn = v%x(1)
    if (v%ok(2)) spring%kt = v%x(2)
    if (v%ok(3)) spring%kx = v%x(3)
    if (v%ok(4)) spring%ky = v%x(4)
    ! kept when bad too: the body has a SPRING, and the whole-deck checks
    ! (a body held by nothing) should not say otherwise; a deck with errors
    ! is never solved
    deck%bodies(s%cur)%springs = [deck%bodies(s%cur)%springs, spring]
  end subroutine do_spring

  !> Append a load to the body's list; the capacity doubles, as for FIX.
  subroutine append_load(body, load)
    type(body_deck_t), intent(inout) :: body
    type(load_t), intent(in) :: load
    type(load_t), allocatable :: grown(:)
    if (body%nload == size(body%loads)) then
      allocate(grown(max(8, 2 * size(body%loads))))
      grown(1:body%nload) = body%loads(1:body%nload)
      call move_alloc(grown, body%loads)
    end if
    body%nload = body%nload + 1
    body%loads(body%nload) = load
  end subroutine append_load


  !> THERMAL alpha= dT= [region=NAME]
  subroutine do_thermal(s, deck, st)
    type(state_t), intent(inout) :: s
    type(deck_t), intent(inout) :: deck
    type(stmt_t), intent(in) :: st
    type(thermal_t) :: th
    type(key_values_t) :: v
    integer :: k

    associate (body => deck%bodies(s%cur))
      call read_keys(s, st, v)
      th%curve_name = v%curve
      th%alpha = v%x(1)
      th%dt = v%x(2)
      th%region = ''
      if (v%ok(3)) th%region = v%text(3)%s
      if (.not. (v%ok(1) .and. v%ok(2) .and. (v%ok(3) .or. .not. allocated(v%text(3)%s)))) return
      do k = 1, size(body%thermals)
        if (body%thermals(k)%region == th%region) then
          if (len(th%region) == 0) then
            call report(s, st%line, 'second THERMAL for the whole of BODY ' // quoted(body%name) // ' (first at line ' // &
                        int_to_str(body%thermals(k)%line) // '; expected one, or one per region=)')
          else
            call report(s, st%line, 'second THERMAL for region ' // quoted(th%region) // ' (first at line ' // &
                        int_to_str(body%thermals(k)%line) // '; expected one per region)')
          end if
          return
        end if
      end do
      th%line = st%line
      body%thermals = [body%thermals, th]
    end associate
  end subroutine do_thermal

  !> The statements of a vector: BODYFORCE fx= fy= [ramp=|curve=], OFFSET dx= dy=
  !> (a rigid shift of the body's mesh before anything else), and GRAVITY gx= gy=
  !> [ramp=|curve=] (at the top level: the deck's body force per unit mass).
  subroutine do_vector(s, deck, st)
    type(state_t), intent(inout) :: s
    type(deck_t), intent(inout) :: deck
    type(stmt_t), intent(in) :: st
    integer :: ramp(2)
    character(len=:), allocatable :: curve

    select case (st%what)
    case ('GRAVITY')
      deck%gravity_line = st%line
      call read_vector_statement(s, st, deck%gx, deck%gy, deck%has_gravity, deck%gravity_ramp, deck%gravity_curve_name)
    case ('BODYFORCE')
      associate (body => deck%bodies(s%cur))
        body%bodyforce_line = st%line
        call read_vector_statement(s, st, body%fx, body%fy, body%has_bodyforce, body%bodyforce_ramp, &
                                   body%bodyforce_curve_name)
      end associate
    case default
      associate (body => deck%bodies(s%cur))
        body%offset_line = st%line
        call read_vector_statement(s, st, body%dx, body%dy, body%has_offset, ramp, curve)
      end associate
    end select
  end subroutine do_vector

  !> A statement of a vector (GRAVITY, BODYFORCE, OFFSET): no words, its two
  !> components first in its row (at least one given), then ramp= and curve=
  !> when it takes a load path.
  !>   a, b        (inout) the components as given (unchanged when absent)
  !>   given       (out)   at least one component given, and every one given a number
  !>   ramp, curve_name (out) the load path (ramp_unset and '' when none)
  subroutine read_vector_statement(s, st, a, b, given, ramp, curve_name)
    type(state_t), intent(inout) :: s
    type(stmt_t), intent(in) :: st
    real(dp), intent(inout) :: a, b
    logical, intent(out) :: given
    integer, intent(out) :: ramp(2)
    character(len=:), allocatable, intent(out) :: curve_name
    type(key_values_t) :: v

    call read_keys(s, st, v)
    if (.not. (v%seen(1) .or. v%seen(2))) call report(s, st%line, 'missing ' // trim(st%keys(1)%name) // '= and ' // &
                                                      trim(st%keys(2)%name) // '= (expected ' // st%usage // ')')
    if (v%ok(1)) a = v%x(1)
    if (v%ok(2)) b = v%x(2)
    ramp = v%ramp
    curve_name = v%curve
    given = (v%ok(1) .or. .not. v%seen(1)) .and. (v%ok(2) .or. .not. v%seen(2)) .and. (v%seen(1) .or. v%seen(2))
  end subroutine read_vector_statement

end module deck_body_statements
