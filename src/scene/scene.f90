!> scene: from the deck to the physics.  The one module that knows both
!> deck_t and the bodies: it makes each body's mesh (MESH rect, a .msh file or a
!> .geo file meshed by gmsh), its elasticity tensor, its Dirichlet data (FIX),
!> its loads (TRACTION, PRESSURE, BODYFORCE, GRAVITY, THERMAL, FORCE), its
!> springs (SPRING) and resolves the CONTACT pairs.  Every name that needs a mesh to check (boundaries) is checked
!> here or in its parts, and reported at the deck line of the statement that
!> uses it.
!>
!> The scene declares its effects: only what the deck asks for is simulated,
!> and scene%effects lists it for the run log and the summary.
!>
!> Its parts, modules of their own: load_groups (the load history: one group
!> per distinct ramp k0:k1 or CURVE, with its loads and prescribed values;
!> scene_t extends load_groups_t, and fext, ubar are the last step's,
!> step_loads), fix_dofs (the FIX statements' dofs, and the nodes' local axes
!> of FIX un=/ut=, to which the groups' forces are turned here) and
!> deck_boundaries (the boundary a statement names), point_supports (FORCE
!> and SPRING on a body).
!>
!> PLANE axisymmetric: the bodies' kernels on the full circle (body), every
!> node at r >= 0 (check_radius), u_r = 0 on the axis (apply_axis).
!>
!> Programming interface
!>   type(scene_t)                       bodies, dof data, loads, pair specs, effects;
!>        extends load_groups_t (steps, ramp, fgroup, ugroup: load_groups' procedures take it)
!>   step_loads(sc, k, fext, ubar)        the loads of step k (and the bodies' thermal strains)
!>   build_scene(deck, gmsh, sc, diag, err)  gmsh: how .geo files are meshed (trust,
!>        time limit); errors go to diag with deck lines
module scene
  use kinds, only: dp
  use strings, only: int_to_str, real_to_str
  use errors, only: diag_t, add_error, has_errors, error_t
  use deck_reader, only: deck_t, body_deck_t, LOAD_TRACTION, LOAD_PRESSURE, LOAD_POINT, rigid_deck_t
  use mesh, only: mesh_t, is_quadratic, finalize_mesh, find_name, order_for_locality, name_list, node_in_file, &
                  locality_min_nodes
  use mesh_rect, only: make_rect_mesh
  use gmsh_reader, only: read_gmsh_file
  use gmsh_runner, only: gmsh_options_t, mesh_geo_file
  use mesh_cache, only: mesh_entry_t, geo_key, find_cached_mesh
  use geo_screen, only: screen_geo
  use safe_files, only: private_folder, real_path
  use material, only: make_isotropic, make_orthotropic, locking_nu
  use elements, only: element_body_load, edge_load, edge_load_quadratic, max_nen
  use axisymmetric_elements, only: axi_element_body_load, axi_edge_load, axi_edge_load_quadratic
  use body, only: body_t, node_elements, edge_outward_normal, element_dofs, thermal_loads, to_local_axes
  use contact_set, only: pair_spec_t
  use load_groups, only: load_groups_t, collect_groups, ramp_group, group_factors
  use deck_boundaries, only: boundary_index
  use fix_dofs, only: apply_fixes
  use point_supports, only: apply_point_forces, apply_springs
  use rigid_obstacle, only: rigid_shape_t, shape_line, shape_circle, shape_polyline
  implicit none
  private
  public :: scene_t, fix_ref_t, build_scene, step_loads

  !> A FIX statement, for its reaction line in the summary.
  type :: fix_ref_t
    integer :: body = 0
    character(len=:), allocatable :: label   !< BODY:BOUNDARY
  end type fix_ref_t

  !> The thermal strain of a body along its load path: at step k, adt of
  !> each element is the factor of its group times adt1.
  type :: thermal_path_t
    real(dp), allocatable :: adt1(:)          !< (nelem) alpha dT at load factor 1
    integer, allocatable :: group(:)          !< (nelem) load group of each element's THERMAL
  end type thermal_path_t

  type, extends(load_groups_t) :: scene_t
    type(body_t), allocatable :: bodies(:)
    integer :: ndof = 0                       !< 2 x all nodes
    integer :: nnode = 0, nelem = 0           !< totals over bodies
    logical, allocatable :: fixed(:)          !< (ndof) Dirichlet dofs
    real(dp), allocatable :: ubar(:)          !< (ndof) prescribed values
    integer, allocatable :: fix_owner(:)      !< (ndof) FIX that owns a fixed dof (first one)
    type(fix_ref_t), allocatable :: fixes(:)  !< all FIX statements, deck order
    real(dp), allocatable :: fext(:)          !< (ndof) external nodal forces
    type(pair_spec_t), allocatable :: specs(:)  !< CONTACT pairs
    type(rigid_shape_t), allocatable :: rigids(:)  !< (nrigid) RIGID obstacles; dofs after the bodies'
    character(len=:), allocatable :: effects  !< space-separated effects simulated
    type(thermal_path_t), allocatable :: thermal(:)  !< (nbody) alpha dT at factor 1 and its group
    type(mesh_entry_t), allocatable :: new_meshes(:) !< the .geo meshes gmsh made, for the mesh cache
                                                     !< once the run has succeeded (mesh_cache)
    integer :: reused_meshes = 0              !< .geo meshes read from the mesh cache
  end type scene_t

contains

  !> Build the scene of a deck read without errors.
  !>   deck    (in)  the deck
  !>   gmsh    (in)  how .geo files are meshed: trusted or screened, time limit
  !>   sc      (out) the scene (incomplete when diag has errors)
  !>   diag    (inout) input errors, FILE:LINE of the deck or the mesh file
  !>   err     (out) allocated when the memory ran out (status 1)
  subroutine build_scene(deck, gmsh, sc, diag, err)
    type(deck_t), intent(in) :: deck
    type(gmsh_options_t), intent(in) :: gmsh
    type(scene_t), intent(out) :: sc
    type(diag_t), intent(inout) :: diag
    type(error_t), allocatable, intent(out) :: err
    integer :: b, nb, nfix, ifix, ndof, ip, naxis, k
    logical :: has_traction, has_pressure, has_bforce, has_gravity, has_dirichlet, has_thermal, has_offset, has_axis
    logical :: has_force

    ! The bodies are read one after the other: gfortran 12 keeps the length of
    ! a deferred-length character function result (int_to_str, the reader's
    ! names and messages) in a static variable of the caller, so two threads
    ! reading meshes garble each other's strings (doc/robustness.md)
    nb = size(deck%bodies)
    allocate(sc%bodies(nb), sc%new_meshes(0))
    do b = 1, nb
      call make_mesh(deck, b, gmsh, sc, sc%bodies(b)%mesh, diag, err)
      if (allocated(err)) return
      call make_body(deck, b, sc%bodies(b), diag)
    end do
    if (has_errors(diag)) return
    ! a large mesh file's numbering is its generator's: renumber for locality
    ! (the generated rectangles are numbered row by row already)
    do b = 1, nb
      if (deck%bodies(b)%mesh%kind /= 'rect' .and. sc%bodies(b)%mesh%nnode > locality_min_nodes) &
        call order_for_locality(sc%bodies(b)%mesh)
    end do

    ! dof and element offsets
    ndof = 0
    do b = 1, nb
      sc%bodies(b)%dof0 = ndof
      sc%bodies(b)%elem0 = sc%nelem
      ndof = ndof + 2 * sc%bodies(b)%mesh%nnode
      sc%nnode = sc%nnode + sc%bodies(b)%mesh%nnode
      sc%nelem = sc%nelem + sc%bodies(b)%mesh%nelem
    end do
    ! a RIGID: three dofs (u_x, u_y, theta of its reference point) after the bodies'
    allocate(sc%rigids(size(deck%rigids)))
    do b = 1, size(deck%rigids)
      ! rigid_obstacle's projection of the exact gap carries no radial weight,
      ! and of the three motions only the axial one is axisymmetric
      if (deck%axisymmetric) &
        call add_error(diag, deck%file, deck%rigids(b)%line, 'RIGID obstacles are not available in PLANE ' // &
                       'axisymmetric (line ' // int_to_str(deck%plane_line) // ') (a meshed body as the master expected)')
      call make_rigid_shape(deck%rigids(b), sc%rigids(b))
      sc%rigids(b)%dof0 = ndof
      ndof = ndof + 3
    end do
    sc%ndof = ndof
    allocate(sc%fixed(ndof), sc%ubar(ndof), sc%fix_owner(ndof), sc%fext(ndof))
    sc%fixed = .false.; sc%ubar = 0.0_dp; sc%fix_owner = 0; sc%fext = 0.0_dp
    call collect_groups(deck, ndof, sc%load_groups_t)
    allocate(sc%thermal(nb))

    nfix = 0
    do b = 1, nb
      nfix = nfix + size(deck%bodies(b)%fixes)
    end do
    allocate(sc%fixes(nfix))
    ifix = 0
    has_dirichlet = .false.
    has_traction = .false.; has_pressure = .false.; has_bforce = .false.; has_gravity = .false.
    has_thermal = .false.
    has_axis = .false.
    has_force = .false.
    do b = 1, nb
      associate(fixes => deck%bodies(b)%fixes)
        do k = 1, size(fixes)
          sc%fixes(ifix + k)%body = b
          sc%fixes(ifix + k)%label = deck%bodies(b)%name // ':' // fixes(k)%boundary
        end do
        call apply_fixes(deck, deck%bodies(b), [(ramp_group(sc, fixes(k)%ramp, fixes(k)%curve), k = 1, size(fixes))], &
                         ifix, sc%bodies(b), sc%fixed, sc%ugroup, sc%fix_owner, diag)
        ifix = ifix + size(fixes)
      end associate
      if (deck%axisymmetric) then
        call apply_axis(deck, sc, b, naxis, diag)
        has_axis = has_axis .or. naxis > 0
      end if
      call apply_loads(deck, deck%bodies(b), sc, b, diag, has_traction, has_pressure, has_bforce, has_gravity)
      call apply_point_forces(deck, deck%bodies(b), sc%bodies(b), sc%load_groups_t, diag, has_force)
      call apply_springs(deck, deck%bodies(b), sc%bodies(b), diag)
      if (size(deck%bodies(b)%thermals) > 0) then
        call apply_thermal(deck, deck%bodies(b), sc, b, diag)
        has_thermal = .true.
      end if
    end do
    has_offset = any(deck%bodies(:)%has_offset)
    call apply_rigid_motions(deck, sc)
    ! the nodes in local axes (FIX un=/ut=) take their forces in those axes
    if (any([(allocated(sc%bodies(b)%axes), b = 1, nb)])) then
      do ip = 1, size(sc%ramp, 2)
        call to_local_axes(sc%bodies, sc%fgroup(:, ip))
      end do
    end if
    call step_loads(sc, sc%steps, sc%fext, sc%ubar)
    has_dirichlet = any(sc%fixed .and. sc%ubar /= 0.0_dp)

    ! contact pairs
    allocate(sc%specs(size(deck%contacts)))
    do ip = 1, size(deck%contacts)
      associate(c => deck%contacts(ip))
        sc%specs(ip)%slave_body = c%slave_body
        sc%specs(ip)%master_body = c%master_body
        sc%specs(ip)%gap_zero = c%gap_zero
        sc%specs(ip)%interference = c%interference
        sc%specs(ip)%finite = c%finite
        if (c%friction == 'coulomb') sc%specs(ip)%mu = c%mu
        if (c%friction == 'tresca') sc%specs(ip)%tresca = c%tresca
        sc%specs(ip)%slave_bnd = boundary_index(deck, c%line, sc%bodies(c%slave_body), c%slave_boundary, 'CONTACT slave', &
                                                .true., diag)
        if (c%master_rigid > 0) then                   ! against a RIGID: its exact shape, no master mesh
          sc%specs(ip)%rigid = c%master_rigid
          sc%specs(ip)%shape = sc%rigids(c%master_rigid)
          if (is_quadratic(sc%bodies(c%slave_body)%mesh)) call add_error(diag, deck%file, c%line, 'contact on ' // &
            'quadratic elements is not available yet (P1/Q1 boundaries expected)')
          cycle
        end if
        sc%specs(ip)%master_bnd = boundary_index(deck, c%line, sc%bodies(c%master_body), c%master_boundary, &
                                                 'CONTACT master', .true., diag)
        if (c%slave_body == c%master_body .and. c%slave_boundary == c%master_boundary) then
          call add_error(diag, deck%file, c%line, 'slave and master are the same boundary (two different boundaries expected)')
        end if
      end associate
    end do

    sc%effects = 'elasticity'
    if (deck%axisymmetric) sc%effects = 'axisymmetric elasticity'
    if (has_axis) sc%effects = sc%effects // ' axis_condition'
    if (has_dirichlet) sc%effects = sc%effects // ' prescribed_displacement'
    if (has_traction) sc%effects = sc%effects // ' traction'
    if (has_pressure) sc%effects = sc%effects // ' pressure'
    if (has_bforce) sc%effects = sc%effects // ' body_force'
    if (has_gravity) sc%effects = sc%effects // ' gravity'
    if (has_force) sc%effects = sc%effects // ' point_force'
    if (any([(sc%bodies(b)%springs%n > 0, b = 1, nb)])) sc%effects = sc%effects // ' spring'
    if (has_thermal) sc%effects = sc%effects // ' thermal'
    if (has_offset) sc%effects = sc%effects // ' offset'
    if (size(sc%specs) > 0) sc%effects = sc%effects // ' contact'
    if (size(sc%rigids) > 0) sc%effects = sc%effects // ' rigid_obstacle'
    if (any([(size(deck%rigids(ip)%forces) > 0, ip = 1, size(deck%rigids))])) sc%effects = sc%effects // ' rigid_force'
    if (any([(deck%contacts(ip)%friction /= 'none', ip = 1, size(deck%contacts))])) &
      sc%effects = sc%effects // ' friction'
  end subroutine build_scene

  !> The loads of step k: fext = sum_g f_g(k) fgroup_g, ubar likewise, and the
  !> bodies' thermal strains alpha dT scaled by their groups' factors.
  !>   sc    (inout) the scene (its bodies' adt are set for step k)
  !>   k     (in)    the step, 1..steps
  !>   fext  (out)   (ndof) external nodal forces of step k
  !>   ubar  (out)   (ndof) prescribed values of step k
  subroutine step_loads(sc, k, fext, ubar)
    type(scene_t), intent(inout) :: sc
    integer, intent(in) :: k
    real(dp), intent(out) :: fext(:), ubar(:)
    real(dp) :: f(size(sc%ramp, 2))
    integer :: b
    f = group_factors(sc, k)
    fext = matmul(sc%fgroup, f)
    ubar = matmul(sc%ugroup, f)
    do b = 1, size(sc%bodies)
      if (allocated(sc%thermal(b)%adt1)) sc%bodies(b)%adt = sc%thermal(b)%adt1 * f(sc%thermal(b)%group)
    end do
  end subroutine step_loads

  !> The shape of a RIGID block: kind, points or circle, reference point
  !> (default: the circle's centre, the first point), size.
  subroutine make_rigid_shape(rd, sh)
    type(rigid_deck_t), intent(in) :: rd
    type(rigid_shape_t), intent(out) :: sh
    sh%name = rd%name
    select case (rd%shape)
    case ('circle')
      sh%kind = shape_circle
      sh%centre = rd%centre
      sh%radius = rd%radius
      sh%outside = rd%outside
      sh%ref = rd%centre
      sh%length = rd%radius
      allocate(sh%pt(2, 0))
    case default
      sh%kind = merge(shape_line, shape_polyline, rd%shape == 'line')
      sh%pt = rd%points
      sh%ref = rd%points(:, 1)
      sh%length = max(maxval(rd%points(1, :)) - minval(rd%points(1, :)), &
                      maxval(rd%points(2, :)) - minval(rd%points(2, :)))
    end select
    if (rd%has_ref) sh%ref = rd%ref
  end subroutine make_rigid_shape

  !> The dofs of each RIGID: the directions FIX names are prescribed (their
  !> values in the FIX's load group), the others free and loaded by FORCE (its
  !> load group); no FIX and no FORCE: all three held at 0.
  subroutine apply_rigid_motions(deck, sc)
    type(deck_t), intent(in) :: deck
    type(scene_t), intent(inout) :: sc
    integer :: r, j, d, i, g
    do r = 1, size(deck%rigids)
      associate (rd => deck%rigids(r))
        d = sc%rigids(r)%dof0
        if (size(rd%fixes) == 0 .and. size(rd%forces) == 0) sc%fixed(d + 1:d + 3) = .true.
        do i = 1, size(rd%fixes)
          g = ramp_group(sc, rd%fixes(i)%ramp, rd%fixes(i)%curve)
          do j = 1, 3
            if (.not. rd%fixes(i)%has(j)) cycle
            sc%fixed(d + j) = .true.
            sc%ugroup(d + j, g) = sc%ugroup(d + j, g) + rd%fixes(i)%value(j)
          end do
        end do
        do i = 1, size(rd%forces)
          g = ramp_group(sc, rd%forces(i)%ramp, rd%forces(i)%curve)
          do j = 1, 3
            if (rd%forces(i)%has(j)) sc%fgroup(d + j, g) = sc%fgroup(d + j, g) + rd%forces(i)%value(j)
          end do
        end do
      end associate
    end do
  end subroutine apply_rigid_motions

  !> The mesh of body ib: its MESH rect generated, its .msh file read, or its
  !> .geo file meshed by gmsh into the run's private folder, after the screen
  !> of what the .geo may do (unless trusted), and read.  A .geo mesh of the
  !> same key in the mesh cache (gmsh%cache, mesh_cache) is read from there
  !> instead; one gmsh made joins sc%new_meshes.
  !>   deck (in)    the deck;  ib (in) the body
  !>   gmsh (in)    how .geo files are meshed: trusted or screened, time limit, cache
  !>   sc   (inout) new_meshes, reused_meshes
  !>   mesh (out)   the mesh, finalized (incomplete when diag has new errors)
  !>   diag (inout) errors at the deck's MESH line or in the mesh file
  !>   err  (out)   allocated when the memory ran out
  subroutine make_mesh(deck, ib, gmsh, sc, mesh, diag, err)
    type(deck_t), intent(in) :: deck
    integer, intent(in) :: ib
    type(gmsh_options_t), intent(in) :: gmsh
    type(scene_t), intent(inout) :: sc
    type(mesh_t), intent(out) :: mesh
    type(diag_t), intent(inout) :: diag
    type(error_t), allocatable, intent(out) :: err
    character(len=:), allocatable :: path, work, deck_folder, log, key
    type(error_t), allocatable :: step_err
    logical :: found
    integer :: n0
    n0 = diag%count
    associate(ms => deck%bodies(ib)%mesh)
      if (ms%kind == 'rect') then
        call make_rect_mesh(ms%x0, ms%y0, ms%x1, ms%y1, ms%nx, ms%ny, ms%elem, ms%diag, mesh, err)
        if (allocated(err)) return
        call finalize_mesh(mesh, deck%file, diag)
        return
      end if
      path = ms%path                           ! the file read: the .msh, or what gmsh made of the .geo
      if (ms%is_geo) then
        call real_path(deck%dir, deck_folder, found)
        if (.not. found) deck_folder = deck%dir
        if (.not. gmsh%trust_geo) call screen_geo(ms%path, deck_folder, diag)
        if (diag%count > n0) return
        key = ''
        found = .false.
        if (allocated(gmsh%cache)) then
          if (len(gmsh%cache) > 0) call geo_key(ms%path, ms%order, ms%set_names, ms%set_values, key)
          if (len(key) > 0) call find_cached_mesh(gmsh%cache, key, path, found)
        end if
        if (found) then
          sc%reused_meshes = sc%reused_meshes + 1
        else
          call private_folder(work, step_err)
          if (allocated(step_err)) then
            call add_error(diag, deck%file, ms%line, 'cannot make a private folder for gmsh''s files in $TMPDIR ' // &
                           '(or /tmp) (a writable folder expected)')
            return
          end if
          path = work // '/body' // int_to_str(ib) // '.msh'
          log = work // '/body' // int_to_str(ib) // '.log'
          call mesh_geo_file(ms%path, ms%order, ms%set_names, ms%set_values, gmsh, deck_folder, path, log, step_err)
          if (allocated(step_err)) then
            call add_error(diag, deck%file, ms%line, 'gmsh could not mesh "' // ms%file // '": ' // step_err%message)
            return
          end if
          if (len(key) > 0) sc%new_meshes = [sc%new_meshes, mesh_entry_t(key, path)]
        end if
      end if
      call read_gmsh_file(path, mesh, diag, err)
      if (allocated(err)) return
      if (diag%count == n0) call finalize_mesh(mesh, ms%path, diag)
    end associate
  end subroutine make_mesh

  !> Body ib around its mesh: its name, OFFSET, elasticity tensor, thickness
  !> and, axisymmetric, the check that no node is left of the axis.
  !>   bd (inout) the body, its mesh made (make_mesh)
  subroutine make_body(deck, ib, bd, diag)
    type(deck_t), intent(in) :: deck
    integer, intent(in) :: ib
    type(body_t), intent(inout) :: bd
    type(diag_t), intent(inout) :: diag
    bd%name = deck%bodies(ib)%name
    associate(bdeck => deck%bodies(ib))
      ! OFFSET: a rigid shift of the geometry, before any contact geometry is made
      if (bdeck%has_offset .and. bd%mesh%nnode > 0) then
        bd%mesh%x(1, :) = bd%mesh%x(1, :) + bdeck%dx
        bd%mesh%x(2, :) = bd%mesh%x(2, :) + bdeck%dy
      end if
      associate(mt => bdeck%material)
        if (mt%kind == 'orthotropic') then
          call make_orthotropic(mt%e1, mt%e2, mt%e3, mt%nu12, mt%nu13, mt%nu23, mt%g12, mt%angle, deck%plane_stress, &
                                bd%law)
        else
          call make_isotropic(mt%e, mt%nu, deck%plane_stress, bd%law)
        end if
      end associate
    end associate
    bd%thick = 1.0_dp
    if (deck%plane_stress) bd%thick = deck%thickness
    bd%axisymmetric = deck%axisymmetric
    ! nearly incompressible: the B-bar strain where the elements would lock
    ! (body, doc/theory.md "Nearly incompressible materials"); in plane
    ! stress the through-thickness strain takes up the change of volume
    bd%bbar = .not. deck%plane_stress .and. deck%bodies(ib)%material%kind == 'isotropic' .and. &
              deck%bodies(ib)%material%nu > locking_nu
    if (bd%axisymmetric .and. bd%mesh%nnode > 0) call check_radius(deck, deck%bodies(ib), bd, diag)
  end subroutine make_body

  !> PLANE axisymmetric: every node at r = x >= 0.  A node within 1e-10 of
  !> the body's size from the axis is put on it (r = 0 exactly: it gets
  !> u_r = 0, apply_axis); one further left is an error at the MESH line (at
  !> the OFFSET line when an OFFSET moved the body).
  subroutine check_radius(deck, bdeck, bd, diag)
    type(deck_t), intent(in) :: deck
    type(body_deck_t), intent(in) :: bdeck
    type(body_t), intent(inout) :: bd
    type(diag_t), intent(inout) :: diag
    real(dp) :: tol
    integer :: a
    associate(x => bd%mesh%x)
      tol = 1.0e-10_dp * max(maxval(abs(x(1, :))), maxval(x(2, :)) - minval(x(2, :)))
      where (abs(x(1, :)) <= tol) x(1, :) = 0.0_dp
      a = minloc(x(1, :), dim=1)
      if (x(1, a) < 0.0_dp) call add_error(diag, deck%file, merge(bdeck%offset_line, bdeck%mesh%line, bdeck%has_offset), &
        'body "' // bd%name // '" has node ' // int_to_str(node_in_file(bd%mesh, a)) // ' at x = ' // &
        real_to_str(x(1, a)) // ', left of the axis of PLANE axisymmetric (line ' // int_to_str(deck%plane_line) // &
        ') (every node at x = r >= 0 expected)')
    end associate
  end subroutine check_radius

  !> PLANE axisymmetric: u_r = 0 at every node on the axis (r = 0) of body
  !> b, a Dirichlet dof owned by no FIX (it has no reaction line).  A node
  !> that a FIX un=/ut= put in local axes is held along the axis of its two
  !> that is r; a FIX that gives such a node u_r /= 0, or local axes along
  !> neither r nor z, is an error at the PLANE line.
  subroutine apply_axis(deck, sc, b, naxis, diag)
    type(deck_t), intent(in) :: deck
    type(scene_t), intent(inout) :: sc
    integer, intent(in) :: b
    integer, intent(out) :: naxis
    type(diag_t), intent(inout) :: diag
    real(dp), parameter :: same = 1.0e-9_dp
    integer :: a, slot, dof, j, k
    real(dp) :: p(2)
    naxis = 0
    associate(bd => sc%bodies(b))
      do a = 1, bd%mesh%nnode
        if (bd%mesh%x(1, a) /= 0.0_dp) cycle
        naxis = naxis + 1
        slot = 1
        if (allocated(bd%axes)) then
          if (any(bd%axes(:, a) /= 0.0_dp)) then
            p = [bd%axes(1, a), -bd%axes(2, a)]             ! e_r in the node's axes (n, t)
            slot = 0
            if (abs(abs(p(1)) - 1.0_dp) <= same) slot = 1
            if (abs(abs(p(2)) - 1.0_dp) <= same) slot = 2
          end if
        end if
        if (slot == 0) then
          call add_error(diag, deck%file, deck%plane_line, 'node ' // int_to_str(node_in_file(bd%mesh, a)) // &
            ' of body "' // bd%name // '" is on the axis and a FIX un=/ut= put it in local axes along neither ' // &
            'r nor z (u_r = 0 on the axis: local axes along r and z there expected)')
          return
        end if
        dof = bd%dof0 + 2 * (a - 1) + slot
        if (sc%fixed(dof)) then
          if (any(sc%ugroup(dof, :) /= 0.0_dp)) then
            k = sc%fix_owner(dof) - sum([(size(deck%bodies(j)%fixes), j = 1, b - 1)])   ! the FIX in body b's list
            call add_error(diag, deck%file, deck%bodies(b)%fixes(k)%line, 'FIX ' // deck%bodies(b)%fixes(k)%boundary // &
              ' gives node ' // int_to_str(node_in_file(bd%mesh, a)) // ' of body "' // bd%name // &
              '", on the axis, a radial displacement (u_r = 0 on the axis of PLANE axisymmetric, line ' // &
              int_to_str(deck%plane_line) // ', expected)')
            return
          end if
        else
          sc%fixed(dof) = .true.
        end if
      end do
    end associate
  end subroutine apply_axis

  !> alpha dT per element from the THERMAL statements of a body: the one
  !> without region= sets every element, those with region= set their region's
  !> elements (a region statement overrides the whole-body one there).  Each
  !> statement follows its curve= (else the ramp 0:STEPS): its elements' nodal
  !> forces go to that load group, and sc%thermal(b) keeps alpha dT and the
  !> group per element for the steps' stresses.
  subroutine apply_thermal(deck, bdeck, sc, b, diag)
    type(deck_t), intent(in) :: deck
    type(body_deck_t), intent(in) :: bdeck
    type(scene_t), intent(inout) :: sc
    integer, intent(in) :: b
    type(diag_t), intent(inout) :: diag
    integer :: k, ir, g
    associate(bd => sc%bodies(b), tp => sc%thermal(b))
    allocate(bd%adt(bd%mesh%nelem), source=0.0_dp)
    allocate(tp%group(bd%mesh%nelem), source=1)
    do k = 1, size(bdeck%thermals)
      if (len(bdeck%thermals(k)%region) == 0) then
        bd%adt = bdeck%thermals(k)%alpha * bdeck%thermals(k)%dt
        tp%group = ramp_group(sc, [0, deck%steps], bdeck%thermals(k)%curve)
      end if
    end do
    do k = 1, size(bdeck%thermals)
      associate(th => bdeck%thermals(k))
        if (len(th%region) == 0) cycle
        ir = find_name(bd%mesh%reg, th%region)
        if (ir == 0) then
          call add_error(diag, deck%file, th%line, 'THERMAL: unknown region "' // th%region // '" in body "' // &
                         bd%name // '" (expected one of: ' // &
                         name_list(bd%mesh%reg, 'none: the mesh names no physical surface') // ')')
          cycle
        end if
        bd%adt(bd%mesh%reg(ir)%elems) = th%alpha * th%dt
        tp%group(bd%mesh%reg(ir)%elems) = ramp_group(sc, [0, deck%steps], th%curve)
      end associate
    end do
    if (has_errors(diag)) return
    ! the nodal forces of each group's elements (adt masked to them) go to its column
    tp%adt1 = bd%adt
    do g = 1, size(sc%ramp, 2)
      if (.not. any(tp%group == g)) cycle
      bd%adt = merge(tp%adt1, 0.0_dp, tp%group == g)
      call thermal_loads(bd, sc%fgroup(:, g))
    end do
    bd%adt = tp%adt1
    end associate
  end subroutine apply_thermal

  !> External nodal forces of body b: TRACTION, PRESSURE, BODYFORCE, GRAVITY
  !> (FORCE: point_supports).
  subroutine apply_loads(deck, bdeck, sc, b, diag, has_traction, has_pressure, has_bforce, has_gravity)
    type(deck_t), intent(in) :: deck
    type(body_deck_t), intent(in) :: bdeck
    type(scene_t), intent(inout) :: sc
    integer, intent(in) :: b
    type(diag_t), intent(inout) :: diag
    logical, intent(inout) :: has_traction, has_pressure, has_bforce, has_gravity
    integer :: k, ib, s, na, nb, nm, owner, e, nen
    integer :: dofs(2 * max_nen)
    integer, allocatable :: eptr(:), elist(:)
    real(dp) :: t(2), nrm(2), fe(2 * max_nen), chord(2), pr
    logical :: have_topology

    have_topology = .false.
    associate(bd => sc%bodies(b), m => sc%bodies(b)%mesh)
      do k = 1, size(bdeck%loads)
        associate(ld => bdeck%loads(k))
          if (ld%kind == LOAD_POINT) cycle                 ! FORCE: point_supports
          ib = boundary_index(deck, ld%line, bd, ld%boundary, merge('TRACTION', 'PRESSURE', ld%kind == LOAD_TRACTION), &
                              .true., diag)
          if (ib == 0) cycle
          if ((ld%kind == LOAD_PRESSURE .or. ld%local) .and. .not. have_topology) then
            call node_elements(m, eptr, elist)
            have_topology = .true.
          end if
          do s = 1, m%bnd(ib)%nseg
            na = m%bnd(ib)%seg(1, s)
            nb = m%bnd(ib)%seg(2, s)
            pr = 0.0_dp
            if (ld%kind == LOAD_TRACTION .and. .not. ld%local) then
              t = [ld%tx, ld%ty]
            else
              call edge_outward_normal(m, eptr, elist, na, nb, nrm, owner)
              if (owner <= 0) then
                call add_error(diag, deck%file, ld%line, merge('PRESSURE', 'TRACTION', ld%kind == LOAD_PRESSURE) // &
                  ' on "' // ld%boundary // &
                  '": an edge is not on the outer boundary of body "' // bd%name // '" (boundary edges expected)')
                exit
              end if
              if (ld%kind == LOAD_TRACTION) then    ! tn n + tt t, t = (-n_y, n_x)
                t = ld%tx * nrm + ld%ty * [-nrm(2), nrm(1)]
              else
                t = -ld%p * nrm                   ! positive pressure pushes into the body
                if (allocated(m%bnd(ib)%mid)) then
                  ! a curved edge: the pressure follows the edge's normal, outward on the
                  ! right of na -> nb when the chord's right normal points outward
                  chord = m%x(:, nb) - m%x(:, na)
                  pr = -ld%p * sign(1.0_dp, dot_product(nrm, [chord(2), -chord(1)]))
                  t = 0.0_dp
                end if
              end if
            end if
            if (allocated(m%bnd(ib)%mid) .and. bd%axisymmetric) then
              nm = m%bnd(ib)%mid(s)
              call axi_edge_load_quadratic(reshape([m%x(:, na), m%x(:, nb), m%x(:, nm)], [2, 3]), t, pr, fe(1:6))
            else if (allocated(m%bnd(ib)%mid)) then       ! 3-node edge, 3-point Gauss
              nm = m%bnd(ib)%mid(s)
              call edge_load_quadratic(reshape([m%x(:, na), m%x(:, nb), m%x(:, nm)], [2, 3]), t, pr, bd%thick, fe(1:6))
            else if (bd%axisymmetric) then                ! per unit area, on the circle 2 pi r
              call axi_edge_load(m%x(:, na), m%x(:, nb), t, fe(1:4))
            else
              call edge_load(m%x(:, na), m%x(:, nb), t, bd%thick, fe(1:4))
            end if
            associate(f => sc%fgroup(:, ramp_group(sc, ld%ramp, ld%curve)))
              f(bd%dof0 + 2 * (na - 1) + [1, 2]) = f(bd%dof0 + 2 * (na - 1) + [1, 2]) + fe(1:2)
              f(bd%dof0 + 2 * (nb - 1) + [1, 2]) = f(bd%dof0 + 2 * (nb - 1) + [1, 2]) + fe(3:4)
              if (allocated(m%bnd(ib)%mid)) &
                f(bd%dof0 + 2 * (nm - 1) + [1, 2]) = f(bd%dof0 + 2 * (nm - 1) + [1, 2]) + fe(5:6)
            end associate
          end do
          if (ld%kind == LOAD_TRACTION) has_traction = .true.
          if (ld%kind == LOAD_PRESSURE) has_pressure = .true.
        end associate
      end do

      ! body force and gravity: one element loop when they share a ramp
      if (bdeck%has_bodyforce) has_bforce = .true.
      if (deck%has_gravity .and. bdeck%has_density) has_gravity = .true.
      if (bdeck%has_bodyforce .and. deck%has_gravity .and. bdeck%has_density .and. &
          all(bdeck%bodyforce_ramp == deck%gravity_ramp) .and. bdeck%bodyforce_curve == deck%gravity_curve) then
        call add_body_load([bdeck%fx, bdeck%fy] + bdeck%rho * [deck%gx, deck%gy], deck%gravity_ramp, deck%gravity_curve)
      else
        if (bdeck%has_bodyforce) call add_body_load([bdeck%fx, bdeck%fy], bdeck%bodyforce_ramp, bdeck%bodyforce_curve)
        if (deck%has_gravity .and. bdeck%has_density) call add_body_load(bdeck%rho * [deck%gx, deck%gy], &
                                                                         deck%gravity_ramp, deck%gravity_curve)
      end if
    end associate
  contains
    !> Nodal forces of the body force density bf (per unit volume), ramp r or curve c.
    subroutine add_body_load(bf, r, c)
      real(dp), intent(in) :: bf(2)
      integer, intent(in) :: r(2), c
      integer :: g
      g = ramp_group(sc, r, c)
      associate(bd => sc%bodies(b), m => sc%bodies(b)%mesh)
        do e = 1, m%nelem
          nen = m%nen(e)
          if (bd%axisymmetric) then
            call axi_element_body_load(nen, m%x(:, m%conn(1:nen, e)), bf, fe(1:2 * nen))
          else
            call element_body_load(nen, m%x(:, m%conn(1:nen, e)), bf, bd%thick, fe(1:2 * nen))
          end if
          call element_dofs(bd, e, dofs)
          sc%fgroup(dofs(1:2 * nen), g) = sc%fgroup(dofs(1:2 * nen), g) + fe(1:2 * nen)
        end do
      end associate
    end subroutine add_body_load
  end subroutine apply_loads

end module scene
