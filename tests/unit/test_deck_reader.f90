!> Unit tests of deck_reader.
!>
!> - tests/unit/data/deck_full.deck (every statement and key) and deck_odd.deck (odd
!>   case, tabs, comments, CRLF, byte-order mark, C/Fortran numbers): every parsed value
!>   against the value written in the deck, and the documented defaults.
!> - tests/bad/deck_*.deck: each yields an error whose first message line, with the
!>   folder 'tests/bad/' removed, equals the line in the matching .expect file (what
!>   `contact2d deck_x.deck` prints inside tests/bad).
!> - numbers and integers accepted and refused, written into temporary decks.
!> - CURVE and curve=: points as written, names resolved on every statement that
!>   takes one, curve_factor before, between and after the points; FIX un=/ut= and
!>   TRACTION tn=/tt= flagged local; OUTPUT steps=all.
!> - FORCE and SPRING in a BODY: values as written, the point force kept with
!>   the loads (load_point), the spring's form from its keys; the errors of
!>   their keys; a body held by a SPRING alone passes the whole-deck check.
!> - STEPS, ramp= and CONTACT friction (mu=, tresca=): values as written, every ramp
!>   resolved to [k0, k1] (default [0, STEPS]), the end-of-deck checks.
!> - robustness: missing file, empty file, a 1 MB line, binary bytes, the error cap,
!>   and randomly damaged copies of deck_full.deck (no crash, bounded messages).
!> Run from the repository root.
program test_deck_reader
  use kinds, only: dp
  use errors, only: diag_t
  use deck_reader, only: deck_t, read_deck, load_traction, load_pressure, load_point, curve_factor
  use testing, only: check, check_close, finish_tests, unit_roundoff
  implicit none

  call test_full_deck()
  call test_odd_deck()
  call test_bad_decks()
  call test_numbers()
  call test_integers()
  call test_steps_and_ramps()
  call test_curves()
  call test_friction()
  call test_supports()
  call test_robustness()
  call finish_tests()

contains

  !> Every statement and key of deck_full.deck.
  subroutine test_full_deck()
    type(deck_t) :: d
    type(diag_t) :: g
    real(dp), parameter :: r = 4 * unit_roundoff   ! read correctly rounded (eps/2), a few roundings more if computed
    integer :: i

    call read_deck('tests/unit/data/deck_full.deck', d, g)
    call check(g%count == 0, 'full: no errors')
    if (g%count > 0) print '(a)', g%items(1)%text
    call check(d%file == 'tests/unit/data/deck_full.deck', 'full: file')
    call check(d%dir == 'tests/unit/data', 'full: dir')
    call check(d%name == 'deck_full', 'full: name')
    call check(d%title == 'Full deck = every statement, KEEP Case', 'full: title keeps case, = and stops at !')
    call check(d%plane_stress, 'full: plane stress')
    call check_close(d%thickness, 2.5_dp, r, 'full: thickness')
    call check(d%has_gravity .and. d%gravity_line == 5, 'full: gravity given, line 5')
    call check_close(d%gx, 1.5_dp, r, 'full: gx')
    call check_close(d%gy, -9810.0_dp, r, 'full: gy')
    call check(size(d%bodies) == 3, 'full: three bodies')
    if (size(d%bodies) /= 3) return

    associate (b => d%bodies(1))
      call check(b%name == 'base' .and. b%line == 7, 'full: body 1 name, line')
      call check(b%mesh%kind == 'rect' .and. b%mesh%line == 8, 'full: body 1 MESH rect, line')
      call check_close(b%mesh%x0, -1.0_dp, r, 'full: x0')
      call check_close(b%mesh%y0, -0.5_dp, r, 'full: y0')
      call check_close(b%mesh%x1, 3.0_dp, r, 'full: x1')
      call check(b%mesh%y1 == 0, 'full: y1')
      call check(b%mesh%nx == 16 .and. b%mesh%ny == 3, 'full: nx, ny')
      call check(b%mesh%elem == 'tri3' .and. b%mesh%diag == 'left', 'full: elem, diag')
      call check(b%mesh%file == '' .and. size(b%mesh%set_names) == 0, 'full: rect has no file, no set')
      call check(b%material%kind == 'isotropic' .and. b%material%line == 9, 'full: body 1 isotropic')
      call check_close(b%material%e, 210000.0_dp, r, 'full: E')
      call check_close(b%material%nu, 0.29_dp, r, 'full: nu')
      call check(b%has_density .and. b%density_line == 10, 'full: density')
      call check_close(b%rho, 7.85e-9_dp, r, 'full: rho')
      call check(size(b%fixes) == 3, 'full: three FIX')
      if (size(b%fixes) == 3) then
        call check(b%fixes(1)%boundary == 'bottom' .and. b%fixes(1)%has_ux .and. b%fixes(1)%has_uy .and. &
                   b%fixes(1)%ux == 0 .and. b%fixes(1)%uy == 0 .and. b%fixes(1)%line == 11, &
                   'full: FIX bottom clamps both')
        call check(b%fixes(2)%boundary == 'left' .and. b%fixes(2)%has_ux .and. .not. b%fixes(2)%has_uy .and. &
                   b%fixes(2)%ux == 0, 'full: FIX left ux=0')
        call check(b%fixes(3)%has_ux .and. b%fixes(3)%has_uy, 'full: FIX right ux= uy=')
        call check_close(b%fixes(3)%ux, 0.001_dp, r, 'full: FIX right ux')
        call check_close(b%fixes(3)%uy, -0.002_dp, r, 'full: FIX right uy')
      end if
      call check(size(b%loads) == 0, 'full: body 1 no loads')
      call check(b%has_bodyforce .and. b%bodyforce_line == 14, 'full: bodyforce')
      call check_close(b%fx, 0.25_dp, r, 'full: fx')
      call check_close(b%fy, -1.0_dp, r, 'full: fy')
    end associate

    associate (b => d%bodies(2))
      call check(b%name == 'punch', 'full: body 2 name')
      call check(b%mesh%kind == 'gmsh' .and. .not. b%mesh%is_geo, 'full: body 2 MESH gmsh .msh')
      call check(b%mesh%file == '../../bad/deck_ok_square.msh', 'full: msh file as written')
      call check(b%mesh%path == 'tests/unit/data/../../bad/deck_ok_square.msh', 'full: msh path resolved')
      call check(size(b%mesh%set_names) == 0 .and. size(b%mesh%set_values) == 0, 'full: msh no set')
      call check(b%material%kind == 'orthotropic', 'full: orthotropic')
      call check_close(b%material%e1, 140000.0_dp, r, 'full: E1')
      call check_close(b%material%e2, 10000.0_dp, r, 'full: E2')
      call check_close(b%material%nu12, 0.3_dp, r, 'full: nu12')
      call check_close(b%material%g12, 5000.0_dp, r, 'full: G12')
      call check_close(b%material%angle, 45.0_dp, r, 'full: angle')
      call check_close(b%material%e3, 9000.0_dp, r, 'full: E3')
      call check_close(b%material%nu13, 0.28_dp, r, 'full: nu13')
      call check_close(b%material%nu23, 0.4_dp, r, 'full: nu23')
      call check(size(b%fixes) == 0 .and. .not. b%has_density .and. .not. b%has_bodyforce, 'full: body 2 bare')
      call check(size(b%loads) == 2, 'full: two loads')
      if (size(b%loads) == 2) then
        call check(b%loads(1)%kind == load_traction .and. b%loads(1)%boundary == 'top' .and. &
                   b%loads(1)%line == 20, 'full: TRACTION top')
        call check_close(b%loads(1)%tx, 1.5_dp, r, 'full: tx')
        call check_close(b%loads(1)%ty, -20.0_dp, r, 'full: ty')
        call check(b%loads(2)%kind == load_pressure .and. b%loads(2)%boundary == 'left', 'full: PRESSURE left')
        call check_close(b%loads(2)%p, 3.25_dp, r, 'full: p')
      end if
    end associate

    associate (b => d%bodies(3))
      call check(b%name == 'cap' .and. b%mesh%is_geo, 'full: body 3 .geo')
      call check(b%mesh%path == 'tests/unit/data/deck_square.geo', 'full: geo path resolved')
      call check(size(b%mesh%set_names) == 2, 'full: two .geo parameters')
      if (size(b%mesh%set_names) == 2) then
        call check(b%mesh%set_names(1) == 'L' .and. b%mesh%set_names(2) == 'hc', 'full: .geo names keep case')
        call check_close(b%mesh%set_values(1), 2.0_dp, r, 'full: L')
        call check_close(b%mesh%set_values(2), 0.125_dp, r, 'full: hc')
      end if
      call check(size(b%fixes) == 1, 'full: body 3 one FIX')
      if (size(b%fixes) == 1) call check(.not. b%fixes(1)%has_ux .and. b%fixes(1)%has_uy, 'full: FIX top uy only')
    end associate

    call check(size(d%contacts) == 3, 'full: three contacts')
    if (size(d%contacts) == 3) then
      call check(d%contacts(1)%slave_body == 2 .and. d%contacts(1)%master_body == 1 .and. &
                 d%contacts(1)%slave_boundary == 'bottom' .and. d%contacts(1)%master_boundary == 'top' .and. &
                 d%contacts(1)%gap_zero .and. d%contacts(1)%line == 30, 'full: contact 1')
      call check(d%contacts(2)%slave_body == 3 .and. d%contacts(2)%master_body == 2 .and. &
                 .not. d%contacts(2)%gap_zero, 'full: contact 2 gap=geometry')
      call check(d%contacts(3)%slave_body == 1 .and. d%contacts(3)%master_body == 3 .and. &
                 d%contacts(3)%slave_boundary == 'right' .and. .not. d%contacts(3)%gap_zero, &
                 'full: contact 3 default gap')
    end if
    call check(d%solver%lcp == 'pgs' .and. d%solver%maxit == 5000 .and. d%solver%line == 33, 'full: solver')
    call check_close(d%solver%tol, 1.0e-12_dp, r, 'full: tol')
    call check_close(d%solver%omega, 1.2_dp, r, 'full: omega')
    call check(d%steps == 1 .and. d%steps_line == 0, 'full: default one load step')
    call check(all(d%gravity_ramp == [0, 1]), 'full: gravity ramp resolved to [0, 1]')
    call check(all([(all(d%bodies(1)%fixes(i)%ramp == [0, 1]), i = 1, size(d%bodies(1)%fixes))]) .and. &
               all([(all(d%bodies(2)%loads(i)%ramp == [0, 1]), i = 1, size(d%bodies(2)%loads))]), &
               'full: FIX and load ramps resolved to [0, 1]')
    call check(all([(all(d%bodies(i)%bodyforce_ramp == [0, 1]), i = 1, 3)]), 'full: bodyforce ramps [0, 1]')
    call check(all([(d%contacts(i)%friction == 'none' .and. d%contacts(i)%mu == 0 .and. &
                     d%contacts(i)%tresca == 0, i = 1, size(d%contacts))]), 'full: contacts frictionless')
    call check(d%output%vtk == 'full_result.vtk', 'full: vtk prefix gets .vtk')
    call check(d%output%contact == 'pairs.csv' .and. d%output%summary == 'full.sum', 'full: contact, summary')
  end subroutine test_full_deck

  !> deck_odd.deck: case, tabs, comments, CRLF, BOM, blanks around '=', numbers; defaults.
  subroutine test_odd_deck()
    type(deck_t) :: d
    type(diag_t) :: g
    real(dp), parameter :: r = 4 * unit_roundoff   ! read correctly rounded (eps/2), a few roundings more if computed

    call read_deck('tests/unit/data/deck_odd.deck', d, g)
    call check(g%count == 0, 'odd: no errors')
    if (g%count > 0) print '(a)', g%items(1)%text
    call check(d%title == 'Odd Deck', 'odd: title (tab as blank, # comment)')
    call check(.not. d%plane_stress, 'odd: plane strain')
    call check(d%thickness == 1, 'odd: default thickness 1')
    call check(.not. d%has_gravity, 'odd: no gravity')
    call check(size(d%bodies) == 2, 'odd: two bodies')
    if (size(d%bodies) /= 2) return
    associate (b => d%bodies(1))
      call check(b%name == 'Left_Block.1' .and. b%line == 7, 'odd: name keeps case')
      call check(b%mesh%kind == 'rect' .and. b%mesh%elem == 'quad4', 'odd: RECT, ELEM=Quad4')
      call check(b%mesh%x0 == 0 .and. b%mesh%y0 == 0, 'odd: default x0, y0')
      call check_close(b%mesh%x1, 2.0_dp, r, 'odd: X1=2.0D0')
      call check_close(b%mesh%y1, 5.0_dp, r, 'odd: y1=5.')
      call check(b%mesh%nx == 4 .and. b%mesh%ny == 2, 'odd: NX=4, ny = 2')
      call check_close(b%material%e, 2.0e5_dp, r, 'odd: e = 2.0d5')
      call check_close(b%material%nu, 0.3_dp, r, 'odd: NU=.3')
      call check(size(b%fixes) == 2, 'odd: two FIX')
      if (size(b%fixes) == 2) then
        call check(b%fixes(1)%has_ux .and. .not. b%fixes(1)%has_uy, 'odd: UX only')
        call check_close(b%fixes(1)%ux, -1.5e-3_dp, r, 'odd: UX=-1.5E-3')
        call check(b%fixes(2)%has_uy .and. b%fixes(2)%uy == 0 .and. b%fixes(2)%line == 11, 'odd: uY=+0')
      end if
    end associate
    associate (b => d%bodies(2))
      call check(b%name == 'right-block', 'odd: body 2 name')
      call check(b%mesh%elem == 'tri3' .and. b%mesh%diag == 'alt', 'odd: default tri3, diag=ALT')
      call check(b%mesh%y0 == 0 .and. b%mesh%y1 == 1, 'odd: default y0, y1')
      call check(b%material%kind == 'orthotropic' .and. b%material%angle == 0, 'odd: default angle 0')
      call check_close(b%material%g12, 2.0e4_dp, r, 'odd: g12=2.0e+04')
      call check_close(b%material%e3, 5.0e4_dp, r, 'odd: default E3 = E2')
      call check_close(b%material%nu13, 0.25_dp, r, 'odd: default nu13 = nu12')
      call check_close(b%material%nu23, 0.25_dp, r, 'odd: default nu23 = nu12')
      call check(size(b%loads) == 1, 'odd: one load')
      if (size(b%loads) == 1) then
        call check(b%loads(1)%kind == load_traction .and. b%loads(1)%ty == 0, 'odd: traction, default ty 0')
        call check_close(b%loads(1)%tx, -5.0_dp, r, 'odd: TX =-.5e1')
      end if
    end associate
    call check(size(d%contacts) == 1, 'odd: one contact')
    if (size(d%contacts) == 1) then
      call check(d%contacts(1)%slave_body == 2 .and. d%contacts(1)%master_body == 1 .and. &
                 d%contacts(1)%master_boundary == 'right' .and. d%contacts(1)%line == 18, 'odd: contact, last line')
    end if
    call check(d%solver%lcp == 'auto' .and. d%solver%maxit == 0 .and. d%solver%line == 0, 'odd: solver defaults')
    call check_close(d%solver%tol, 1.0e-10_dp, r, 'odd: default tol')
    call check(d%solver%omega == 1, 'odd: default omega')
    call check(d%output%vtk == 'deck_odd.vtk' .and. d%output%contact == 'deck_odd_contact.csv' .and. &
               d%output%summary == 'deck_odd.summary', 'odd: default output names')
  end subroutine test_odd_deck

  !> Each bad deck: at least one error; first message line as in its .expect file.
  subroutine test_bad_decks()
    character(len=*), parameter :: names(91) = [character(len=32) :: &
      'deck_bad_name', 'deck_bad_number', 'deck_binary', 'deck_blank_equals_missing', 'deck_body_in_body', &
      'deck_body_no_name', 'deck_boundary_case', 'deck_contact_alone', 'deck_contact_duplicate', &
      'deck_contact_same_boundary', 'deck_contact_syntax', 'deck_contact_unknown_body', 'deck_density_alone', &
      'deck_density_negative', 'deck_diag', 'deck_diag_quad4', 'deck_duplicate_body', 'deck_duplicate_key', &
      'deck_elem', 'deck_empty', 'deck_end_alone', 'deck_fix_bad_value', 'deck_gmsh_extension', &
      'deck_gmsh_geo_value', 'deck_gmsh_missing_file', 'deck_gmsh_msh_extra', 'deck_gmsh_no_file', &
      'deck_gravity_in_body', 'deck_hex', 'deck_material_kind_missing', 'deck_mesh_alone', 'deck_mesh_kind', &
      'deck_missing_end', 'deck_missing_value', 'deck_nan', 'deck_negative_modulus', 'deck_no_material', &
      'deck_no_mesh', 'deck_nu_range', 'deck_nx_not_integer', 'deck_ny_zero', 'deck_ortho_g12', &
      'deck_ortho_missing', 'deck_ortho_plane', 'deck_ortho_strain', 'deck_output_empty', 'deck_output_same', &
      'deck_output_slash', 'deck_outside_body', 'deck_overflow', 'deck_plane_kind', 'deck_plane_strain_thickness', &
      'deck_plane_thickness', 'deck_pressure_missing', 'deck_rect_boundary', 'deck_rect_extent', &
      'deck_rect_missing_nx', 'deck_rigid_body', 'deck_rigid_group', 'deck_second_material', 'deck_second_mesh', &
      'deck_second_solver', 'deck_solver_lcp', 'deck_solver_maxit', 'deck_solver_omega', 'deck_solver_tol', &
      'deck_traction_missing', 'deck_trailing_garbage', 'deck_unknown_gap', 'deck_unknown_key', &
      'deck_unknown_keyword', 'deck_steps_value', 'deck_steps_missing', 'deck_second_steps', 'deck_ramp_syntax', &
      'deck_ramp_order', 'deck_ramp_steps', 'deck_ramp_no_steps', 'deck_friction_both', 'deck_friction_mu_range', &
      'deck_friction_tresca_negative', 'deck_curve_unknown', 'deck_curve_order', &
      'deck_curve_point', 'deck_curve_ramp', 'deck_curve_empty', 'deck_curve_duplicate', 'deck_output_steps', &
      'deck_output_steps_clash', 'deck_traction_mixed', 'deck_fix_axes_mixed']
    type(deck_t) :: d
    type(diag_t) :: g
    character(len=:), allocatable :: expected, got
    integer :: i

    do i = 1, size(names)
      g = diag_t()
      call read_deck('tests/bad/' // trim(names(i)) // '.deck', d, g)
      call read_first_line('tests/bad/' // trim(names(i)) // '.expect', expected)
      if (g%count == 0) then
        call check(.false., 'bad: ' // trim(names(i)) // ' yields an error')
        cycle
      end if
      got = replace_all(first_line(g%items(1)%text), 'tests/bad/', '')
      call check(got == expected .and. len(got) == len(expected), 'bad: ' // trim(names(i)) // ' first message')
      if (got /= expected) print '(a)', '  got:      ' // got // new_line('a') // '  expected: ' // expected
      call check(g%count <= 2, 'bad: ' // trim(names(i)) // ' no cascade')
    end do
  end subroutine test_bad_decks

  !> Numbers accepted and refused, as GRAVITY gx= in a small valid deck.
  subroutine test_numbers()
    character(len=*), parameter :: good(17) = [character(len=40) :: '200000', '2e5', '2.0d5', '2.0D5', &
      '-1.5E-3', '.5', '5.', '+.5e-3', '1.e3', '-0', '9.9e307', '0.000e999', '007', '-2.5E+02', '1E-400', &
      '00000000000000000000000000000001e307', '1.25d-1']
    real(dp), parameter :: good_value(17) = [200000.0_dp, 2.0e5_dp, 2.0e5_dp, 2.0e5_dp, -1.5e-3_dp, 0.5_dp, &
      5.0_dp, 5.0e-4_dp, 1000.0_dp, 0.0_dp, 9.9e307_dp, 0.0_dp, 7.0_dp, -250.0_dp, 0.0_dp, 1.0e307_dp, 0.125_dp]
    character(len=*), parameter :: bad(24) = [character(len=40) :: '1e308', '1.8e308', '-1e400', 'e5', '.', '+', &
      '-', '1e', '1e+', '1q5', '1,5', '0x1A', 'NaN', 'nan', 'Inf', '-infinity', '1_dp', '2.0.1', '1e5.0', '--1', &
      '1d', '.e5', '1e99999999999999', '5/2']
    type(deck_t) :: d
    type(diag_t) :: g
    integer :: i

    do i = 1, size(good)
      call read_text_deck(small_deck('GRAVITY gx=' // trim(good(i))), d, g)
      call check(g%count == 0, 'number accepted: ' // trim(good(i)))
      if (good_value(i) == 0) then
        call check(abs(d%gx) < 1.0e-300_dp, 'number value: ' // trim(good(i)))
      else
        call check_close(d%gx, good_value(i), 4 * unit_roundoff, 'number value: ' // trim(good(i)))
      end if
    end do
    do i = 1, size(bad)
      call read_text_deck(small_deck('GRAVITY gx=' // trim(bad(i))), d, g)
      call check(g%count == 1, 'number refused: ' // trim(bad(i)))
      if (g%count >= 1) call check(index(g%items(1)%text, 'bad number') > 0 .and. &
                                   index(g%items(1)%text, '"gx"') > 0, 'number message: ' // trim(bad(i)))
    end do
  end subroutine test_numbers

  !> nx= accepts positive integers only; the size limit.
  subroutine test_integers()
    character(len=*), parameter :: good(3) = [character(len=12) :: '4', '+4', '0004']
    character(len=*), parameter :: bad(7) = [character(len=12) :: '2.5', '4.0', '1e1', '0', '-3', '9999999999', 'four']
    type(deck_t) :: d
    type(diag_t) :: g
    integer :: i

    do i = 1, size(good)
      call read_text_deck(small_deck('', 'nx=' // trim(good(i)) // ' ny=1'), d, g)
      call check(g%count == 0, 'integer accepted: ' // trim(good(i)))
      if (size(d%bodies) == 1) call check(d%bodies(1)%mesh%nx == 4, 'integer value: ' // trim(good(i)))
    end do
    do i = 1, size(bad)
      call read_text_deck(small_deck('', 'nx=' // trim(bad(i)) // ' ny=1'), d, g)
      call check(g%count == 1, 'integer refused: ' // trim(bad(i)))
      if (g%count >= 1) call check(index(g%items(1)%text, 'bad value nx=') > 0, 'integer message: ' // trim(bad(i)))
    end do
    call read_text_deck(small_deck('', 'nx=100000 ny=100000'), d, g)
    call check(g%count == 1, 'rect mesh size limit')
  end subroutine test_integers

  !> STEPS n and ramp=k0:k1 on FIX, TRACTION, PRESSURE, BODYFORCE, GRAVITY: explicit
  !> values, defaults resolved to [0, STEPS] (STEPS may follow the ramps), errors.
  subroutine test_steps_and_ramps()
    character(len=*), parameter :: nl = achar(10)
    character(len=*), parameter :: head = 'BODY b' // nl // ' MESH rect nx=2 ny=2' // nl // &
                                          ' MATERIAL isotropic E=1 nu=0' // nl
    character(len=*), parameter :: bad_ramp(8) = [character(len=12) :: '0-5', '5', ':5', '0:', 'a:b', '-1:5', &
                                                  '0:2.5', '0:5:7']
    type(deck_t) :: d
    type(diag_t) :: g
    integer :: i

    ! no STEPS, no ramp: one step, every ramp [0, 1], absent statements included
    call read_text_deck(small_deck(''), d, g)
    call check(g%count == 0 .and. d%steps == 1 .and. d%steps_line == 0, 'steps: default 1')
    call check(all(d%bodies(1)%fixes(1)%ramp == [0, 1]), 'ramp: FIX default [0, 1]')
    call check(all(d%bodies(1)%bodyforce_ramp == [0, 1]) .and. all(d%gravity_ramp == [0, 1]), &
               'ramp: absent BODYFORCE and GRAVITY [0, 1]')

    ! the Cattaneo-Mindlin loading: press, then shear, on the same boundary
    call read_text_deck(head // ' FIX bottom' // nl // ' FIX top uy=-0.002 ramp=0:5' // nl // &
                        ' FIX top ux=0.001 RAMP = 5:20' // nl // ' FIX left ramp=3:4' // nl // &
                        ' TRACTION right ty=-1' // nl // ' PRESSURE right p=2 ramp=2:3' // nl // &
                        ' BODYFORCE fy=-1 ramp=1:20' // nl // 'END' // nl // &
                        'BODY c' // nl // ' MESH rect y0=1 y1=2 nx=2 ny=2' // nl // ' MATERIAL isotropic E=1 nu=0' // nl // &
                        ' FIX top' // nl // ' BODYFORCE fx=1' // nl // 'END' // nl // &
                        'GRAVITY gy=-9.81 ramp=0:7' // nl // 'STEPS 20 ! after the ramps' // nl, d, g)
    call check(g%count == 0, 'ramp: deck with ramps reads')
    if (g%count > 0) print '(a)', g%items(1)%text
    call check(d%steps == 20 .and. d%steps_line == 19, 'steps: STEPS 20 and its line')
    if (size(d%bodies) == 2 .and. g%count == 0) then
      associate (b => d%bodies(1))
        call check(size(b%fixes) == 4, 'ramp: four FIX, two on the same boundary')
        call check(all(b%fixes(1)%ramp == [0, 20]), 'ramp: FIX without ramp= gets [0, STEPS]')
        call check(all(b%fixes(2)%ramp == [0, 5]) .and. b%fixes(2)%has_uy .and. .not. b%fixes(2)%has_ux, &
                   'ramp: FIX top uy ramp=0:5')
        call check(all(b%fixes(3)%ramp == [5, 20]) .and. b%fixes(3)%has_ux .and. .not. b%fixes(3)%has_uy, &
                   'ramp: FIX top ux RAMP = 5:20')
        call check(b%fixes(2)%boundary == 'top' .and. b%fixes(3)%boundary == 'top', 'ramp: both on top')
        call check(all(b%fixes(4)%ramp == [3, 4]) .and. b%fixes(4)%has_ux .and. b%fixes(4)%has_uy .and. &
                   b%fixes(4)%ux == 0 .and. b%fixes(4)%uy == 0, 'ramp: FIX with ramp= only still clamps both')
        call check(size(b%loads) == 2, 'ramp: two loads')
        if (size(b%loads) == 2) then
          call check(all(b%loads(1)%ramp == [0, 20]), 'ramp: TRACTION default [0, STEPS]')
          call check(all(b%loads(2)%ramp == [2, 3]) .and. b%loads(2)%p == 2, 'ramp: PRESSURE ramp=2:3')
        end if
        call check(b%has_bodyforce .and. all(b%bodyforce_ramp == [1, 20]), 'ramp: BODYFORCE ramp=1:20')
      end associate
      call check(all(d%bodies(2)%bodyforce_ramp == [0, 20]) .and. d%bodies(2)%has_bodyforce, &
                 'ramp: BODYFORCE default [0, STEPS]')
      call check(all(d%bodies(2)%fixes(1)%ramp == [0, 20]), 'ramp: second body FIX default')
      call check(d%has_gravity .and. all(d%gravity_ramp == [0, 7]), 'ramp: GRAVITY ramp=0:7')
    end if
    call read_text_deck(small_deck('STEPS 6'), d, g)
    call check(g%count == 0 .and. all(d%gravity_ramp == [0, 6]) .and. all(d%bodies(1)%fixes(1)%ramp == [0, 6]) &
               .and. all(d%bodies(1)%bodyforce_ramp == [0, 6]), 'ramp: defaults follow STEPS 6')
    call read_text_deck(small_deck('STEPS 100000' // nl // 'GRAVITY gy=1 ramp=99999:100000'), d, g)
    call check(g%count == 0 .and. d%steps == 100000 .and. all(d%gravity_ramp == [99999, 100000]), &
               'steps: largest STEPS and ramp')
    call read_text_deck(small_deck('GRAVITY gy=1 ramp=0:1'), d, g)
    call check(g%count == 0 .and. all(d%gravity_ramp == [0, 1]), 'ramp: ramp=0:1 without STEPS')

    ! errors
    call expect_error(small_deck('STEPS 100001'), 6, 'bad number of load steps "100001" (expected STEPS n ' // &
                      'with an integer 1 <= n <= 100000)', 'steps: 100001 refused')
    call expect_error(small_deck('STEPS 2.0'), 6, 'bad number of load steps "2.0"', 'steps: 2.0 refused')
    call expect_error(small_deck('STEPS -3'), 6, 'bad number of load steps "-3"', 'steps: -3 refused')
    call expect_error(small_deck('STEPS 4 5'), 6, 'unexpected word "5" (expected STEPS n', 'steps: extra word')
    call expect_error(small_deck('STEPS n=4'), 6, 'unexpected "n=4" (expected STEPS n', 'steps: key=value')
    call expect_error(head // ' STEPS 4' // nl // ' FIX left' // nl // 'END' // nl, 4, &
                      'statement STEPS inside BODY "b"', 'steps: inside BODY')
    do i = 1, size(bad_ramp)
      call expect_error(small_deck('GRAVITY gy=1 ramp=' // trim(bad_ramp(i)) // nl // 'STEPS 10'), 6, &
                        'bad ramp "' // trim(bad_ramp(i)) // '" (expected ramp=k0:k1 with integers 0 <= k0 < k1 ' // &
                        '<= STEPS n)', 'ramp: ' // trim(bad_ramp(i)) // ' refused')
    end do
    call expect_error(small_deck('GRAVITY gy=1 ramp=' // nl // 'STEPS 10'), 6, &
                      'missing value for "ramp" (expected ramp=k0:k1)', 'ramp: empty value')
    call expect_error(small_deck('GRAVITY gy=1 ramp=4:2' // nl // 'STEPS 10'), 6, &
                      'bad ramp "4:2" (expected ramp=k0:k1 with k0 < k1', 'ramp: k0 > k1 refused')
    call expect_error(small_deck('STEPS 3' // nl // 'GRAVITY gy=1 ramp=2:4'), 7, &
                      'ramp=2:4 ends after the last load step (expected k1 <= 3, the STEPS value at line 6)', &
                      'ramp: k1 > STEPS refused')
    call expect_error(head // ' FIX left ux=0 ramp=0:2' // nl // 'END' // nl, 4, &
                      'ramp=0:2 ends after the last load step (expected k1 <= 1, as STEPS defaults to 1 when absent)', &
                      'ramp: k1 > 1 without STEPS refused')
    call expect_error(small_deck('STEPS 0' // nl // 'GRAVITY gy=1 ramp=0:4'), 6, 'bad number of load steps "0"', &
                      'ramp: no second message after a bad STEPS')
    call expect_error(small_deck('STEPS 10' // nl // 'STEPS 10'), 7, 'second STEPS (first at line 6; ' // &
                      'expected at most one)', 'steps: second STEPS')
    call expect_error(small_deck('GRAVITY ramp=0:1'), 6, 'missing gx= and gy=', 'ramp: not a value of GRAVITY')
  end subroutine test_steps_and_ramps

  !> CURVE, curve= on every statement that takes it, local axes, OUTPUT steps=.
  subroutine test_curves()
    character(len=*), parameter :: nl = achar(10)
    type(deck_t) :: d
    type(diag_t) :: g
    real(dp), parameter :: r = 4 * unit_roundoff   ! read correctly rounded (eps/2), a few roundings more if computed

    call read_text_deck('STEPS 4' // nl // 'BODY b' // nl // ' MESH rect nx=2 ny=2' // nl // &
                        ' MATERIAL isotropic E=1 nu=0' // nl // ' DENSITY rho=1' // nl // &
                        ' FIX bottom un=0 curve=lu' // nl // ' FIX left ux=0.5 ramp=1:2' // nl // &
                        ' TRACTION top tn=-1 tt=2 curve=up' // nl // ' PRESSURE right p=2 curve=lu' // nl // &
                        ' BODYFORCE fy=-1 curve=up' // nl // ' THERMAL alpha=1 dT=2 curve=lu' // nl // 'END' // nl // &
                        'GRAVITY gy=-1 curve=lu' // nl // 'CURVE lu 0:0 2:1 4:0.5' // nl // 'CURVE up 1.5:2' // nl // &
                        'OUTPUT steps=ALL' // nl, d, g)
    call check(g%count == 0, 'curve: deck with curves reads')
    if (g%count > 0) print '(a)', g%items(1)%text
    if (g%count > 0 .or. size(d%curves) /= 2) return
    call check(d%curves(1)%name == 'lu' .and. size(d%curves(1)%t) == 3 .and. d%curves(1)%line == 14, &
               'curve: CURVE lu, three points, its line')
    call check(all(d%curves(1)%t == [0.0_dp, 2.0_dp, 4.0_dp]) .and. all(d%curves(1)%v == [0.0_dp, 1.0_dp, 0.5_dp]), &
               'curve: points as written')
    associate (b => d%bodies(1))
      call check(b%fixes(1)%curve == 1 .and. b%fixes(1)%local .and. b%fixes(1)%has_ux .and. &
                 .not. b%fixes(1)%has_uy, 'curve: FIX un=0 curve=lu: local, normal only, curve 1')
      call check(b%fixes(2)%curve == 0 .and. all(b%fixes(2)%ramp == [1, 2]) .and. .not. b%fixes(2)%local, &
                 'curve: FIX with ramp= keeps its ramp')
      call check(b%loads(1)%curve == 2 .and. b%loads(1)%local .and. b%loads(1)%tx == -1 .and. b%loads(1)%ty == 2, &
                 'curve: TRACTION tn tt curve=up')
      call check(b%loads(2)%curve == 1, 'curve: PRESSURE curve=lu')
      call check(b%bodyforce_curve == 2 .and. b%thermals(1)%curve == 1, 'curve: BODYFORCE and THERMAL curve=')
    end associate
    call check(d%gravity_curve == 1 .and. d%output%steps_all, 'curve: GRAVITY curve=, OUTPUT steps=all')
    call check_close(curve_factor(d%curves(1), -1.0_dp), 0.0_dp, r, 'curve_factor: before the first point', 1.0_dp)
    call check_close(curve_factor(d%curves(1), 1.0_dp), 0.5_dp, r, 'curve_factor: loading')
    call check_close(curve_factor(d%curves(1), 3.0_dp), 0.75_dp, r, 'curve_factor: unloading')
    call check_close(curve_factor(d%curves(1), 4.0_dp), 0.5_dp, r, 'curve_factor: at the last point')
    call check_close(curve_factor(d%curves(1), 9.0_dp), 0.5_dp, r, 'curve_factor: after the last point')
    call check_close(curve_factor(d%curves(2), 0.0_dp), 2.0_dp, r, 'curve_factor: one point: constant')
    ! OUTPUT x=: kept as written (a column name, checked once the scene is built), only with steps=all plot=png
    call read_text_deck(small_deck('OUTPUT steps=all plot=png x=reaction_b:left_fy'), d, g)
    call check(g%count == 0 .and. allocated(d%output%x), 'output x=: read with steps=all plot=png')
    if (allocated(d%output%x)) call check(d%output%x == 'reaction_b:left_fy', 'output x=: the column as written')
    call read_text_deck(small_deck('OUTPUT steps=all plot=png'), d, g)
    call check(g%count == 0 .and. .not. allocated(d%output%x), 'output x=: none by default (the load factor)')
    call expect_error(small_deck('OUTPUT plot=png x=step'), 6, 'x=step chooses the abscissa of the steps plot', &
                      'output x=: refused without steps=all')
    call expect_error(small_deck('OUTPUT steps=all x=step'), 6, 'x=step chooses the abscissa of the steps plot', &
                      'output x=: refused without plot=png')
    call expect_error(small_deck('OUTPUT steps=all plot=png y=step'), 6, 'unknown key "y" for OUTPUT (expected vtk, ' // &
                      'contact, summary, fields, steps, plot, x)', 'output: the unknown-key message lists x')
  end subroutine test_curves

  !> CONTACT mu= and tresca=: values, the default frictionless contact, errors, and
  !> lcp=pdas refused with friction.
  subroutine test_friction()
    character(len=*), parameter :: nl = achar(10)
    character(len=*), parameter :: two = 'BODY lower' // nl // ' MESH rect nx=2 ny=2' // nl // &
      ' MATERIAL isotropic E=1 nu=0' // nl // ' FIX bottom' // nl // 'END' // nl // 'BODY upper' // nl // &
      ' MESH rect y0=1 y1=2 nx=2 ny=2' // nl // ' MATERIAL isotropic E=1 nu=0' // nl // ' FIX top' // nl // &
      'END' // nl                          ! 10 lines
    character(len=*), parameter :: pair = 'CONTACT slave=lower:top master=upper:bottom'
    type(deck_t) :: d
    type(diag_t) :: g
    real(dp), parameter :: r = 4 * unit_roundoff   ! read correctly rounded (eps/2), a few roundings more if computed

    call read_text_deck(two // pair // nl // 'CONTACT slave=lower:bottom master=upper:top gap=zero MU=0.3' // nl // &
                        'CONTACT slave=upper:left master=lower:left tresca = 2.5e1' // nl // &
                        'CONTACT slave=upper:right master=lower:right mu=0' // nl // &
                        'CONTACT slave=lower:left master=upper:right tresca=0' // nl // &
                        'CONTACT slave=lower:right master=upper:left mu=1e3' // nl // 'STEPS 8' // nl, d, g)
    call check(g%count == 0, 'friction: deck reads')
    if (g%count > 0) print '(a)', g%items(1)%text
    call check(size(d%contacts) == 6, 'friction: six contacts')
    if (size(d%contacts) /= 6) return
    call check(d%contacts(1)%friction == 'none' .and. d%contacts(1)%mu == 0 .and. d%contacts(1)%tresca == 0, &
               'friction: default none')
    call check(d%contacts(2)%friction == 'coulomb' .and. d%contacts(2)%gap_zero .and. d%contacts(2)%tresca == 0, &
               'friction: MU= is Coulomb')
    call check_close(d%contacts(2)%mu, 0.3_dp, r, 'friction: mu value')
    call check(d%contacts(3)%friction == 'tresca' .and. d%contacts(3)%mu == 0, 'friction: tresca =')
    call check_close(d%contacts(3)%tresca, 25.0_dp, r, 'friction: tresca value')
    call check(d%contacts(4)%friction == 'coulomb' .and. d%contacts(4)%mu == 0, 'friction: mu=0 kept as Coulomb')
    call check(d%contacts(5)%friction == 'tresca' .and. d%contacts(5)%tresca == 0, 'friction: tresca=0 kept')
    call check_close(d%contacts(6)%mu, 1000.0_dp, r, 'friction: mu=1e3 accepted')
    call check(d%steps == 8, 'friction: STEPS 8')

    call read_text_deck(two // pair // ' mu=0' // nl // 'SOLVER lcp=pdas' // nl, d, g)
    call check(g%count == 0, 'friction: mu=0 (frictionless) with lcp=pdas accepted')
    call check(.not. allocated(d%solver%cut), 'solver: no cut unless the deck gives one (the run then says it is ignored)')
    call read_text_deck(two // pair // nl // 'SOLVER CUT=Off' // nl, d, g)
    call check(g%count == 0 .and. d%solver%cut == 'off', 'solver: cut=off read (key and value in any case)')
    call read_text_deck(two // pair // nl // 'SOLVER lcp=pdas' // nl // 'STEPS 5' // nl, d, g)
    call check(g%count == 0, 'friction: STEPS without friction with lcp=pdas accepted')
    call read_text_deck(two // pair // ' mu=0.2' // nl // 'SOLVER lcp=pdas' // nl, d, g)
    call check(g%count == 0 .and. d%solver%lcp == 'pdas', 'friction: lcp=pdas accepted with Coulomb friction')
    call read_text_deck(two // 'SOLVER lcp=PDAS' // nl // pair // ' tresca=1' // nl, d, g)
    call check(g%count == 0 .and. d%solver%lcp == 'pdas', 'friction: lcp=pdas accepted with Tresca friction')
    call expect_error(two // pair // ' tresca=1 mu=0.1' // nl, 11, 'mu= and tresca= together (expected one ' // &
                      'friction law per CONTACT)', 'friction: both laws refused')
    call expect_error(two // pair // ' mu=1000.5' // nl, 11, 'bad value mu=1000.5 (expected 0 <= mu <= 1000)', &
                      'friction: mu > 1000 refused')
    call expect_error(two // pair // ' mu=-1e-9' // nl, 11, 'bad value mu=-1e-9 (expected 0 <= mu <= 1000)', &
                      'friction: negative mu refused')
    call expect_error(two // pair // ' mu=nan' // nl, 11, 'bad number "nan" for "mu" (expected a finite number)', &
                      'friction: mu=nan refused')
    call expect_error(two // pair // ' tresca=-2' // nl, 11, 'bad value tresca=-2 (expected tresca >= 0, a shear ' // &
                      'stress)', 'friction: negative tresca refused')
    call expect_error(two // pair // ' tresca=1e999' // nl, 11, 'bad number "1e999" for "tresca"', &
                      'friction: tresca=1e999 refused')
    call expect_error(two // pair // ' friction=0.3' // nl, 11, 'unknown key "friction" for CONTACT (expected ' // &
                      'slave, master, gap, mu, tresca, interference, sliding, name)', 'friction: unknown key lists mu, tresca')
  end subroutine test_friction

  !> FORCE point ... and SPRING ... in a BODY block.
  subroutine test_supports()
    character(len=*), parameter :: nl = achar(10)
    character(len=*), parameter :: head = 'BODY b' // nl // ' MESH rect nx=2 ny=2' // nl // &
                                          ' MATERIAL isotropic E=1 nu=0' // nl
    type(deck_t) :: d
    type(diag_t) :: g

    ! (rect bodies name no point sets: the reader checks the name, the scene its kind)

    call read_text_deck(head // ' SPRING bottom kn=3 kt=0.5' // nl // ' SPRING left kx=2' // nl // &
                        ' FORCE top fy=-7 ramp=1:2' // nl // 'END' // nl // 'STEPS 2' // nl, d, g)
    call check(g%count == 0, 'supports: deck read without error (held by its SPRING alone)')
    if (g%count /= 0) return
    associate (b => d%bodies(1))
      call check(size(b%springs) == 2, 'supports: two SPRING statements')
      call check(.not. b%springs(1)%point .and. b%springs(1)%kn == 3.0_dp .and. b%springs(1)%kt == 0.5_dp .and. &
                 b%springs(1)%boundary == 'bottom' .and. b%springs(1)%line == 4, 'supports: foundation kn, kt, name, line')
      call check(b%springs(2)%point .and. b%springs(2)%kx == 2.0_dp .and. b%springs(2)%ky == 0.0_dp .and. &
                 b%springs(2)%boundary == 'left', 'supports: point spring kx, ky = 0 by default')
      call check(size(b%loads) == 1, 'supports: FORCE kept with the loads')
      call check(b%loads(1)%kind == load_point .and. b%loads(1)%tx == 0.0_dp .and. b%loads(1)%ty == -7.0_dp .and. &
                 b%loads(1)%boundary == 'top' .and. all(b%loads(1)%ramp == [1, 2]), 'supports: FORCE fx, fy, point, ramp')
    end associate
    call expect_error(head // ' SPRING bottom kt=1' // nl // 'END' // nl, 4, 'missing kn= (expected SPRING', &
                      'supports: kt= without kn=')
    call expect_error(head // ' SPRING bottom kn=1 ky=2' // nl // 'END' // nl, 4, 'kn=/kt= and kx=/ky= together', &
                      'supports: kn= with ky=')
    call expect_error(head // ' SPRING bottom kn=-1' // nl // 'END' // nl, 4, 'bad value kn=-1 (expected kn >= 0', &
                      'supports: negative kn')
    call expect_error(head // ' SPRING left kx=1 ky=-2' // nl // 'END' // nl, 4, 'bad value ky=-2 (expected ky >= 0', &
                      'supports: negative ky')
    call expect_error(head // ' FIX bottom' // nl // ' FORCE top ramp=0:1' // nl // 'END' // nl, 5, &
                      'FORCE without a component', 'supports: FORCE without fx, fy')
    call expect_error(head // ' FIX bottom' // nl // ' FORCE fx=1' // nl // 'END' // nl, 5, 'missing point name', &
                      'supports: FORCE without a point')
    call expect_error(head // ' FIX bottom' // nl // ' FORCE top fy=1 m=1' // nl // 'END' // nl, 5, 'unknown key "m"', &
                      'supports: FORCE on a body takes no moment')
  end subroutine test_supports

  !> Read text as a deck: exactly one error, at `line`, whose text after 'FILE:LINE: '
  !> starts with `start`.
  subroutine expect_error(text, line, start, name)
    character(len=*), intent(in) :: text, start, name
    integer, intent(in) :: line
    type(deck_t) :: d
    type(diag_t) :: g
    character(len=:), allocatable :: msg, tag
    integer :: k

    call read_text_deck(text, d, g)
    if (g%count /= 1) then
      call check(.false., name // ' (' // itoa(g%count) // ' errors, 1 expected)')
      if (g%count > 1) print '(a)', '  ' // first_line(g%items(1)%text) // new_line('a') // '  ' // &
                                    first_line(g%items(2)%text)
      return
    end if
    msg = first_line(g%items(1)%text)
    tag = '.deck:' // itoa(line) // ': '
    k = index(msg, tag)
    if (k > 0) msg = msg(k + len(tag):)
    call check(k > 0 .and. index(msg, start) == 1, name)
    if (.not. (k > 0 .and. index(msg, start) == 1)) print '(a)', '  got: ' // first_line(g%items(1)%text)
  end subroutine expect_error

  !> Missing and empty files, a 1 MB line, binary bytes, the error cap, damaged decks.
  subroutine test_robustness()
    type(deck_t) :: d
    type(diag_t) :: g
    character(len=:), allocatable :: text, full
    character(len=:), allocatable :: big
    integer :: i, k, n, pos, worst, nbad
    real :: u(3)

    g = diag_t()
    call read_deck('tests/unit/data/no_such_deck.deck', d, g)
    call check(g%count == 1, 'missing file: one error')
    if (g%count == 1) call check(index(g%items(1)%text, 'no_such_deck.deck: cannot open') > 0, &
                                 'missing file: file-level message')
    call check(allocated(d%bodies) .and. allocated(d%contacts) .and. d%output%vtk == 'no_such_deck.vtk', &
               'missing file: deck components allocated, defaults set')

    call read_text_deck('', d, g)
    call check(g%count == 1, 'empty file: one error')
    if (g%count == 1) call check(index(g%items(1)%text, 'deck has no BODY') > 0, 'empty file: no BODY')

    big = repeat('x', 1000000)
    call read_text_deck(small_deck('! ' // big), d, g)
    call check(g%count == 0, '1 MB comment line: no error')
    call read_text_deck(small_deck('FOO' // big), d, g)
    call check(g%count == 1, '1 MB unknown keyword: one error')
    if (g%count == 1) call check(len(g%items(1)%text) < 600, '1 MB line: message and echo cut short')
    call read_text_deck(small_deck('TITLE ' // big), d, g)
    call check(g%count == 0 .and. len(d%title) == len(big), '1 MB title kept')

    text = ''
    do i = 0, 255
      text = text // achar(i)
    end do
    call read_text_deck(repeat(text, 8), d, g)
    call check(g%count == 1, 'binary with NUL: one error')
    if (g%count >= 1) call check(index(g%items(1)%text, 'NUL byte') > 0, 'binary with NUL: message')
    call read_text_deck(repeat(text(2:), 40), d, g)
    call check(g%count >= 1 .and. g%count <= 101, 'binary without NUL: errors, capped')

    text = ''
    do i = 1, 300
      text = text // 'FOO' // new_line('a')
    end do
    call read_text_deck(text, d, g)
    call check(g%count == 101, 'error cap: 100 errors and a last word')
    if (g%count == 101) call check(index(g%items(101)%text, 'too many errors') > 0, 'error cap: message')

    ! damaged copies of deck_full.deck: no crash, bounded output
    call read_whole_file('tests/unit/data/deck_full.deck', full)
    call random_seed(size=n)
    call random_seed(put=[(1234 + 17 * i, i = 1, n)])
    worst = 0
    nbad = 0
    do i = 1, 300
      text = full
      do k = 1, 4
        call random_number(u)
        pos = 1 + int(u(1) * len(text))
        pos = min(pos, len(text))
        if (u(2) < 0.6) then                          ! replace a byte
          text(pos:pos) = achar(int(u(3) * 256))
        else if (u(2) < 0.8) then                     ! delete a span
          text = text(1:pos - 1) // text(min(len(text) + 1, pos + 1 + int(u(3) * 40)):)
        else if (u(2) < 0.9) then                     ! duplicate a span
          text = text(1:pos) // text(pos:min(len(text), pos + int(u(3) * 80))) // text(pos + 1:)
        else                                          ! truncate
          text = text(1:pos)
        end if
        if (len(text) == 0) text = 'x'
      end do
      call read_text_deck(text, d, g)
      worst = max(worst, g%count)
      if (g%count > 0) nbad = nbad + 1
    end do
    call check(worst <= 101, 'damaged decks: at most 101 messages')
    call check(nbad > 0, 'damaged decks: errors found')
  end subroutine test_robustness

  ! ---------------------------------------------------------------- helpers

  !> A small valid deck with one extra line and optional rect keys.
  function small_deck(extra, rect) result(text)
    character(len=*), intent(in) :: extra
    character(len=*), intent(in), optional :: rect
    character(len=:), allocatable :: text
    character(len=*), parameter :: nl = achar(10)
    character(len=:), allocatable :: mesh_keys
    mesh_keys = 'nx=2 ny=2'
    if (present(rect)) mesh_keys = rect
    text = 'BODY b' // nl // ' MESH rect ' // mesh_keys // nl // ' MATERIAL isotropic E=1 nu=0' // nl // &
           ' FIX left' // nl // 'END' // nl // extra // nl
  end function small_deck

  !> Write text to a temporary deck file, read it, delete the file.
  subroutine read_text_deck(text, d, g)
    character(len=*), intent(in) :: text
    type(deck_t), intent(out) :: d
    type(diag_t), intent(out) :: g
    character(len=:), allocatable :: path
    character(len=512) :: tmp
    integer :: u, stat
    real :: x

    call get_environment_variable('TMPDIR', tmp, status=stat)
    if (stat /= 0 .or. len_trim(tmp) == 0) tmp = '/tmp'
    call random_number(x)
    path = trim(tmp) // '/contact2d_test_deck_reader_' // itoa(int(x * 1.0e8)) // '.deck'
    open(newunit=u, file=path, access='stream', form='unformatted', status='replace', action='write')
    if (len(text) > 0) write(u) text
    close(u)
    call read_deck(path, d, g)
    open(newunit=u, file=path, status='old')
    close(u, status='delete')
  end subroutine read_text_deck

  subroutine read_whole_file(path, text)
    character(len=*), intent(in) :: path
    character(len=:), allocatable, intent(out) :: text
    integer :: u, n
    open(newunit=u, file=path, access='stream', form='unformatted', status='old', action='read')
    inquire(unit=u, size=n)
    allocate(character(len=n) :: text)
    read(u) text
    close(u)
  end subroutine read_whole_file

  subroutine read_first_line(path, line)
    character(len=*), intent(in) :: path
    character(len=:), allocatable, intent(out) :: line
    character(len=2000) :: buf
    integer :: u, ios
    line = '(cannot read ' // path // ')'
    open(newunit=u, file=path, status='old', action='read', iostat=ios)
    if (ios /= 0) return
    read(u, '(a)', iostat=ios) buf
    close(u)
    if (ios == 0) line = trim(buf)
  end subroutine read_first_line

  pure function first_line(s) result(t)
    character(len=*), intent(in) :: s
    character(len=:), allocatable :: t
    integer :: k
    k = index(s, new_line('a'))
    if (k == 0) then
      t = s
    else
      t = s(1:k - 1)
    end if
  end function first_line

  pure function replace_all(s, old, new) result(t)
    character(len=*), intent(in) :: s, old, new
    character(len=:), allocatable :: t
    integer :: i, k
    t = ''
    i = 1
    do
      k = index(s(i:), old)
      if (k == 0) exit
      t = t // s(i:i + k - 2) // new
      i = i + k - 1 + len(old)
    end do
    t = t // s(i:)
  end function replace_all

  pure function itoa(i) result(s)
    integer, intent(in) :: i
    character(len=:), allocatable :: s
    character(len=12) :: buf
    write(buf, '(i0)') i
    s = trim(buf)
  end function itoa

end program test_deck_reader
