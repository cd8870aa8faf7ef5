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
!> step_forces), fix_dofs (the FIX statements' dofs, and the nodes' local axes
!> of FIX un=/ut=, to which the groups' forces are turned here),
!> deck_boundaries (the boundary a statement names, its edges' outward
!> normals), body_loads (TRACTION, PRESSURE, BODYFORCE, GRAVITY, THERMAL on a
!> body) and point_supports (FORCE and SPRING on a body).
!>
!> PLANE axisymmetric: the bodies' kernels on the full circle (body), every
!> node at r >= 0 (check_radius), u_r = 0 on the axis (apply_axis), a
!> RIGID's u_x and theta held (apply_rigid_motions).
!>
!> Thermal strains.  A body's alpha dT of step k is its THERMAL statements'
!> value at load factor 1 times the factor of their group at k
!> (step_thermal_strains); a state's stresses take them as an argument
!> (body: element_response; error_estimate).  The scene never changes once
!> built: body_t%adt keeps the value at load factor 1 (allocated: the body
!> has THERMAL), from which the groups' nodal forces were made.
!>
!> Programming interface
!>   type(scene_t)                       bodies, dof data, loads, pair specs, effects;
!>        extends load_groups_t (steps, ramp, fgroup, ugroup: load_groups' procedures take it)
!>   build_scene(deck, gmsh, sc, diag, err)  gmsh: how .geo files are meshed (trust,
!>        time limit); errors go to diag with deck lines
!>   step_forces(sc, t, fext, ubar)       the external forces and prescribed values of step t
!>   step_thermal_strains(sc, t, adt)     alpha dT of every element at step t, (nelem) in
!>        output order (body b's element e at elem0 + e), 0 in bodies without THERMAL
module scene
  use kinds, only: dp
  use strings, only: int_to_str, real_to_str, format_number
  use errors, only: diag_t, add_error, has_errors, error_t
  use deck_reader, only: deck_t, body_deck_t, material_t, LOAD_TRACTION, LOAD_PRESSURE, LOAD_POINT, rigid_deck_t
  use mesh, only: mesh_t, finalize_mesh, order_for_locality, node_in_file, &
                  locality_min_nodes
  use mesh_rect, only: make_rect_mesh
  use gmsh_reader, only: read_gmsh_file
  use gmsh_runner, only: gmsh_options_t, mesh_geo_file
  use mesh_cache, only: mesh_entry_t, geo_key, find_cached_mesh
  use geo_screen, only: screen_geo
  use safe_files, only: private_folder, real_path
  use material, only: make_isotropic, make_orthotropic, locking_nu
  use hyperelastic, only: make_hyperelastic, initial_moduli
  use body, only: body_t, to_local_axes
  use contact_set, only: pair_spec_t
  use load_groups, only: load_groups_t, collect_groups, ramp_group, group_factors
  use deck_boundaries, only: boundary_index, need_edges
  use fix_dofs, only: apply_fixes
  use point_supports, only: apply_point_forces, apply_springs
  use body_loads, only: apply_edge_loads, apply_body_loads, apply_thermal
  use rigid_obstacle, only: rigid_shape_t, shape_line, shape_circle, shape_polyline
  implicit none
  private
  public :: scene_t, fix_ref_t, build_scene, step_forces, step_thermal_strains

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
                                                     !< (adt1 not allocated: the body has no THERMAL)
    type(mesh_entry_t), allocatable :: new_meshes(:) !< the .geo meshes gmsh made, for the mesh cache
                                                     !< once the run has succeeded (mesh_cache)
    integer :: reused_meshes = 0              !< .geo meshes read from the mesh cache
  end type scene_t

contains

  !> Build the scene of a deck read without errors.  The statements are
  !> resolved body by body in deck order, so that the input errors come in
  !> the order of the deck's lines.
  !>   deck    (in)  the deck
  !>   gmsh    (in)  how .geo files are meshed: trusted or screened, time limit
  !>   sc      (out) the scene (incomplete when diag has errors)
  !>   diag    (inout) input errors, FILE:LINE of the deck or the mesh file
  !>   err     (out) allocated when the memory ran out (error_numerical)
  subroutine build_scene(deck, gmsh, sc, diag, err)
    type(deck_t), intent(in) :: deck
    type(gmsh_options_t), intent(in) :: gmsh
    type(scene_t), intent(out) :: sc
    type(diag_t), intent(inout) :: diag
    type(error_t), allocatable, intent(out) :: err
    integer :: b, ifix, ndof, k

    call make_bodies(deck, gmsh, sc%bodies, sc%new_meshes, sc%reused_meshes, diag, err)
    if (allocated(err) .or. has_errors(diag)) return
    call order_meshes_for_locality(deck, sc%bodies)
    call number_body_dofs(sc%bodies, ndof, sc%nnode, sc%nelem)
    call make_rigids(deck, ndof, sc%rigids)
    sc%ndof = ndof
    allocate(sc%fixed(ndof), sc%ubar(ndof), sc%fix_owner(ndof), sc%fext(ndof))
    sc%fixed = .false.; sc%ubar = 0.0_dp; sc%fix_owner = 0; sc%fext = 0.0_dp
    call collect_groups(deck, ndof, sc%load_groups_t)
    allocate(sc%thermal(size(sc%bodies)))
    call list_fixes(deck, sc%fixes)

    ifix = 0
    do b = 1, size(sc%bodies)
      associate(bdeck => deck%bodies(b), bd => sc%bodies(b))
        call apply_fixes(deck, bdeck, [(ramp_group(sc, bdeck%fixes(k)%ramp, bdeck%fixes(k)%curve), &
                                        k = 1, size(bdeck%fixes))], ifix, bd, sc%fixed, sc%ugroup, sc%fix_owner, diag)
        if (deck%axisymmetric) call apply_axis(deck, bdeck, ifix, bd, sc%fixed, sc%ugroup, sc%fix_owner, diag)
        ifix = ifix + size(bdeck%fixes)
        call apply_edge_loads(deck, bdeck, bd, sc%load_groups_t, diag)
        call apply_body_loads(deck, bdeck, bd, sc%load_groups_t)
        call apply_point_forces(deck, bdeck, bd, sc%load_groups_t, diag)
        call apply_springs(deck, bdeck, bd, diag)
        if (size(bdeck%thermals) > 0) &
          call apply_thermal(deck, bdeck, bd, sc%load_groups_t, sc%thermal(b)%adt1, sc%thermal(b)%group, diag)
      end associate
    end do
    call apply_rigid_motions(deck, sc%rigids, sc%load_groups_t, sc%fixed)
    call forces_to_local_axes(sc%bodies, sc%fgroup)
    call step_forces(sc, real(sc%steps, dp), sc%fext, sc%ubar)
    call make_pair_specs(deck, sc%bodies, sc%rigids, sc%specs, diag)
    sc%effects = scene_effects(deck, sc)
  end subroutine build_scene

  !> The external forces and prescribed values of step k: fext = sum_g f_g(k)
  !> fgroup_g, ubar likewise (eq. (1)'s data at the step's load factors).
  !>   sc    (in)  the scene
  !>   t     (in)  the step, 1..steps (a point between two when a step is split)
  !>   fext  (out) (ndof) external nodal forces of step t
  !>   ubar  (out) (ndof) prescribed values of step t
  subroutine step_forces(sc, t, fext, ubar)
    type(scene_t), intent(in) :: sc
    real(dp), intent(in) :: t
    real(dp), intent(out) :: fext(:), ubar(:)
    real(dp) :: f(size(sc%ramp, 2))
    f = group_factors(sc, t)
    fext = matmul(sc%fgroup, f)
    ubar = matmul(sc%ugroup, f)
  end subroutine step_forces

  !> The thermal strains of step k: alpha dT of each element, its THERMAL's
  !> value at load factor 1 times its group's factor at k.  What the stresses
  !> of step k subtract from the strain (sigma = D (eps - alpha dT eth)); the
  !> nodal forces of the strains are in fgroup already (step_forces).
  !>   sc  (in)  the scene
  !>   k   (in)  the step, 1..steps
  !>   adt (out) (sc%nelem) alpha dT of body b's element e at bodies(b)%elem0 + e
  !>             (the output order of the stresses); 0 in a body without THERMAL
  subroutine step_thermal_strains(sc, t, adt)
    type(scene_t), intent(in) :: sc
    real(dp), intent(in) :: t
    real(dp), intent(out) :: adt(:)
    real(dp) :: f(size(sc%ramp, 2))
    integer :: b
    f = group_factors(sc, t)
    adt = 0.0_dp
    do b = 1, size(sc%bodies)
      if (.not. allocated(sc%thermal(b)%adt1)) cycle
      associate(e0 => sc%bodies(b)%elem0, ne => sc%bodies(b)%mesh%nelem)
        adt(e0 + 1:e0 + ne) = sc%thermal(b)%adt1 * f(sc%thermal(b)%group)
      end associate
    end do
  end subroutine step_thermal_strains

  !> The bodies of the deck, each around its mesh (make_mesh, make_body).
  !> They are read one after the other: gfortran 12 keeps the length of a
  !> deferred-length character function result (int_to_str, the reader's
  !> names and messages) in a static variable of the caller, so two threads
  !> reading meshes garble each other's strings (doc/robustness.md).
  !>   deck          (in)    the deck
  !>   gmsh          (in)    how .geo files are meshed (make_mesh)
  !>   bodies        (out)   (nbody) the bodies, meshes finalized (incomplete when diag has errors)
  !>   new_meshes    (out)   the .geo meshes gmsh made, for the mesh cache
  !>   reused_meshes (inout) counts the .geo meshes read from the mesh cache
  !>   diag          (inout) errors at the deck's MESH lines or in the mesh files
  !>   err           (out)   allocated when the memory ran out
  subroutine make_bodies(deck, gmsh, bodies, new_meshes, reused_meshes, diag, err)
    type(deck_t), intent(in) :: deck
    type(gmsh_options_t), intent(in) :: gmsh
    type(body_t), allocatable, intent(out) :: bodies(:)
    type(mesh_entry_t), allocatable, intent(out) :: new_meshes(:)
    integer, intent(inout) :: reused_meshes
    type(diag_t), intent(inout) :: diag
    type(error_t), allocatable, intent(out) :: err
    integer :: b
    allocate(bodies(size(deck%bodies)), new_meshes(0))
    do b = 1, size(bodies)
      call make_mesh(deck, b, gmsh, bodies(b)%mesh, new_meshes, reused_meshes, diag, err)
      if (allocated(err)) return
      call make_body(deck, b, bodies(b), diag)
    end do
  end subroutine make_bodies

  !> A large mesh file's numbering is its generator's: renumbered for
  !> locality (mesh: order_for_locality) above locality_min_nodes nodes.
  !> The generated rectangles are numbered row by row already.
  !>   deck   (in)    the deck (each body's MESH kind)
  !>   bodies (inout) the bodies, meshes finalized
  subroutine order_meshes_for_locality(deck, bodies)
    type(deck_t), intent(in) :: deck
    type(body_t), intent(inout) :: bodies(:)
    integer :: b
    do b = 1, size(bodies)
      if (deck%bodies(b)%mesh%kind /= 'rect' .and. bodies(b)%mesh%nnode > locality_min_nodes) &
        call order_for_locality(bodies(b)%mesh)
    end do
  end subroutine order_meshes_for_locality

  !> The bodies' dof and element offsets, in body order: body b's node a,
  !> component c is dof dof0 + 2 (a - 1) + c; its element e is elem0 + e.
  !>   bodies (inout) dof0 and elem0 set
  !>   ndof   (out)   the bodies' dofs, 2 x all nodes
  !>   nnode, nelem (out) totals over the bodies
  subroutine number_body_dofs(bodies, ndof, nnode, nelem)
    type(body_t), intent(inout) :: bodies(:)
    integer, intent(out) :: ndof, nnode, nelem
    integer :: b
    ndof = 0; nnode = 0; nelem = 0
    do b = 1, size(bodies)
      bodies(b)%dof0 = ndof
      bodies(b)%elem0 = nelem
      ndof = ndof + 2 * bodies(b)%mesh%nnode
      nnode = nnode + bodies(b)%mesh%nnode
      nelem = nelem + bodies(b)%mesh%nelem
    end do
  end subroutine number_body_dofs

  !> The RIGID obstacles: their shapes (make_rigid_shape) and three dofs each
  !> (u_x, u_y, theta of the reference point) after the bodies'.
  !>   deck   (in)    the deck
  !>   ndof   (inout) the dofs numbered so far; on exit with the RIGIDs'
  !>   rigids (out)   (nrigid) the shapes, dof0 set
  subroutine make_rigids(deck, ndof, rigids)
    type(deck_t), intent(in) :: deck
    integer, intent(inout) :: ndof
    type(rigid_shape_t), allocatable, intent(out) :: rigids(:)
    integer :: r
    allocate(rigids(size(deck%rigids)))
    do r = 1, size(deck%rigids)
      call make_rigid_shape(deck%rigids(r), rigids(r))
      rigids(r)%dof0 = ndof
      ndof = ndof + 3
    end do
  end subroutine make_rigids

  !> Every FIX statement of the bodies, in deck order, for its reaction line.
  !>   deck  (in)  the deck
  !>   fixes (out) body and label BODY:BOUNDARY of each
  subroutine list_fixes(deck, fixes)
    type(deck_t), intent(in) :: deck
    type(fix_ref_t), allocatable, intent(out) :: fixes(:)
    integer :: b, k, n
    allocate(fixes(sum([(size(deck%bodies(b)%fixes), b = 1, size(deck%bodies))])))
    n = 0
    do b = 1, size(deck%bodies)
      do k = 1, size(deck%bodies(b)%fixes)
        n = n + 1
        fixes(n)%body = b
        fixes(n)%label = deck%bodies(b)%name // ':' // deck%bodies(b)%fixes(k)%boundary
      end do
    end do
  end subroutine list_fixes

  !> The nodes in local axes (FIX un=/ut=) take their forces in those axes:
  !> every load group's forces turned (body: to_local_axes).
  !>   bodies (in)    the bodies, their axes
  !>   fgroup (inout) (ndof, ngroup) the groups' forces, x, y on entry
  subroutine forces_to_local_axes(bodies, fgroup)
    type(body_t), intent(in) :: bodies(:)
    real(dp), intent(inout) :: fgroup(:,:)
    integer :: b, g
    if (.not. any([(allocated(bodies(b)%axes), b = 1, size(bodies))])) return
    do g = 1, size(fgroup, 2)
      call to_local_axes(bodies, fgroup(:, g))
    end do
  end subroutine forces_to_local_axes

  !> The CONTACT pairs: slave and master boundaries found in their bodies
  !> (deck_boundaries), or the RIGID master's exact shape.
  !>   deck   (in)    the deck
  !>   bodies (in)    the bodies, meshes finalized
  !>   rigids (in)    the RIGID shapes (make_rigids)
  !>   specs  (out)   (npair) the pairs
  !>   diag   (inout) unknown boundaries, a boundary in contact with itself
  subroutine make_pair_specs(deck, bodies, rigids, specs, diag)
    type(deck_t), intent(in) :: deck
    type(body_t), intent(in) :: bodies(:)
    type(rigid_shape_t), intent(in) :: rigids(:)
    type(pair_spec_t), allocatable, intent(out) :: specs(:)
    type(diag_t), intent(inout) :: diag
    integer :: ip
    allocate(specs(size(deck%contacts)))
    do ip = 1, size(deck%contacts)
      associate(c => deck%contacts(ip), sp => specs(ip))
        sp%slave_body = c%slave_body
        sp%master_body = c%master_body
        sp%gap_zero = c%gap_zero
        sp%interference = c%interference
        sp%finite = c%finite
        if (c%friction == 'coulomb') sp%mu = c%mu
        if (c%friction == 'tresca') sp%tresca = c%tresca
        sp%slave_bnd = boundary_index(deck, c%line, bodies(c%slave_body), c%slave_boundary, 'CONTACT slave', &
                                      need_edges, diag)
        if (c%master_rigid > 0) then                   ! against a RIGID: its exact shape, no master mesh
          sp%rigid = c%master_rigid
          sp%shape = rigids(c%master_rigid)
          cycle
        end if
        sp%master_bnd = boundary_index(deck, c%line, bodies(c%master_body), c%master_boundary, 'CONTACT master', &
                                       need_edges, diag)
        if (c%slave_body == c%master_body .and. c%slave_boundary == c%master_boundary) then
          call add_error(diag, deck%file, c%line, 'slave and master are the same boundary (two different boundaries expected)')
        end if
      end associate
    end do
  end subroutine make_pair_specs

  !> The effects the scene simulates, for the run log and the summary: each
  !> named when the deck asks for it (scene_t%effects).  Read on a scene
  !> built without errors.
  !>   deck (in) the deck;  sc (in) its scene, built
  function scene_effects(deck, sc) result(effects)
    type(deck_t), intent(in) :: deck
    type(scene_t), intent(in) :: sc
    character(len=:), allocatable :: effects
    integer :: b, ip
    logical :: axis, traction, pressure, force
    axis = .false.; traction = .false.; pressure = .false.; force = .false.
    do b = 1, size(deck%bodies)
      associate(loads => deck%bodies(b)%loads, m => sc%bodies(b)%mesh)
        ! u_r = 0 held at the nodes on the axis (apply_axis)
        if (deck%axisymmetric) axis = axis .or. any(m%x(1, 1:m%nnode) == 0.0_dp)
        traction = traction .or. any(loads%kind == LOAD_TRACTION)
        pressure = pressure .or. any(loads%kind == LOAD_PRESSURE)
        force = force .or. any(loads%kind == LOAD_POINT)
      end associate
    end do
    effects = 'elasticity'
    if (deck%axisymmetric) effects = 'axisymmetric elasticity'
    if (axis) effects = effects // ' axis_condition'
    if (any(sc%fixed .and. sc%ubar /= 0.0_dp)) effects = effects // ' prescribed_displacement'
    if (traction) effects = effects // ' traction'
    if (pressure) effects = effects // ' pressure'
    if (any(deck%bodies(:)%has_bodyforce)) effects = effects // ' body_force'
    if (deck%has_gravity .and. any(deck%bodies(:)%has_density)) effects = effects // ' gravity'
    if (force) effects = effects // ' point_force'
    if (any([(sc%bodies(b)%springs%n > 0, b = 1, size(sc%bodies))])) effects = effects // ' spring'
    if (any([(size(deck%bodies(b)%thermals) > 0, b = 1, size(deck%bodies))])) effects = effects // ' thermal'
    if (any(deck%bodies(:)%has_offset)) effects = effects // ' offset'
    if (any(sc%bodies(:)%finite)) effects = effects // ' finite_strain'
    if (size(sc%specs) > 0) effects = effects // ' contact'
    if (size(sc%rigids) > 0) effects = effects // ' rigid_obstacle'
    if (any([(size(deck%rigids(ip)%forces) > 0, ip = 1, size(deck%rigids))])) effects = effects // ' rigid_force'
    if (any([(deck%contacts(ip)%friction /= 'none', ip = 1, size(deck%contacts))])) effects = effects // ' friction'
  end function scene_effects

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
  !> load group); no FIX and no FORCE: all three held at 0.  In PLANE
  !> axisymmetric u_x and theta are held at 0 (a solid of revolution moves
  !> along its axis only; deck_checks refuses a FIX or FORCE across it).
  !>   deck   (in)    the deck's RIGID blocks
  !>   rigids (in)    their shapes, dof0 (make_rigids)
  !>   lg     (inout) the load groups: ugroup and fgroup get the values and forces
  !>   fixed  (inout) (ndof) the Dirichlet dofs
  subroutine apply_rigid_motions(deck, rigids, lg, fixed)
    type(deck_t), intent(in) :: deck
    type(rigid_shape_t), intent(in) :: rigids(:)
    class(load_groups_t), intent(inout) :: lg
    logical, intent(inout) :: fixed(:)
    integer :: r, j, d, i, g
    do r = 1, size(deck%rigids)
      associate (rd => deck%rigids(r))
        d = rigids(r)%dof0
        if (size(rd%fixes) == 0 .and. size(rd%forces) == 0) fixed(d + 1:d + 3) = .true.
        if (deck%axisymmetric) fixed([d + 1, d + 3]) = .true.
        do i = 1, size(rd%fixes)
          g = ramp_group(lg, rd%fixes(i)%ramp, rd%fixes(i)%curve)
          do j = 1, 3
            if (.not. rd%fixes(i)%has(j)) cycle
            fixed(d + j) = .true.
            lg%ugroup(d + j, g) = lg%ugroup(d + j, g) + rd%fixes(i)%value(j)
          end do
        end do
        do i = 1, size(rd%forces)
          g = ramp_group(lg, rd%forces(i)%ramp, rd%forces(i)%curve)
          do j = 1, 3
            if (rd%forces(i)%has(j)) lg%fgroup(d + j, g) = lg%fgroup(d + j, g) + rd%forces(i)%value(j)
          end do
        end do
      end associate
    end do
  end subroutine apply_rigid_motions

  !> The mesh of body ib: its MESH rect generated, its .msh file read, or its
  !> .geo file meshed by gmsh into the run's private folder, after the screen
  !> of what the .geo may do (unless trusted), and read.  A .geo mesh of the
  !> same key in the mesh cache (gmsh%cache, mesh_cache) is read from there
  !> instead; one gmsh made joins new_meshes.
  !>   deck          (in)    the deck;  ib (in) the body
  !>   gmsh          (in)    how .geo files are meshed: trusted or screened, time limit, cache
  !>   mesh          (out)   the mesh, finalized (incomplete when diag has new errors)
  !>   new_meshes    (inout) the .geo meshes gmsh made: this one's key and file added
  !>   reused_meshes (inout) counts the .geo meshes read from the mesh cache
  !>   diag          (inout) errors at the deck's MESH line or in the mesh file
  !>   err           (out)   allocated when the memory ran out
  subroutine make_mesh(deck, ib, gmsh, mesh, new_meshes, reused_meshes, diag, err)
    type(deck_t), intent(in) :: deck
    integer, intent(in) :: ib
    type(gmsh_options_t), intent(in) :: gmsh
    type(mesh_t), intent(out) :: mesh
    type(mesh_entry_t), allocatable, intent(inout) :: new_meshes(:)
    integer, intent(inout) :: reused_meshes
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
          reused_meshes = reused_meshes + 1
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
          if (len(key) > 0) call add_entry(new_meshes, key, path)
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
        else if (mt%kind == 'neo_hookean' .or. mt%kind == 'mooney_rivlin') then
          call make_hyperelastic_body(deck, mt, bd)
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
    if (.not. bd%finite) bd%bbar = .not. deck%plane_stress .and. deck%bodies(ib)%material%kind == 'isotropic' &
                                   .and. deck%bodies(ib)%material%nu > locking_nu
    if (bd%axisymmetric .and. bd%mesh%nnode > 0) call check_radius(deck, deck%bodies(ib), bd, diag)
  end subroutine make_body

  !> A hyperelastic body: its law, and beside it the law's small-strain limit
  !> (E, nu of the reference state) as bd%law, the initial tangent (the
  !> first factorization, the condensation and the rigid modes use it).
  subroutine make_hyperelastic_body(deck, mt, bd)
    type(deck_t), intent(in) :: deck
    type(material_t), intent(in) :: mt
    type(body_t), intent(inout) :: bd
    real(dp) :: e, nu
    bd%finite = .true.
    call make_hyperelastic(mt%c10, mt%c01, mt%bulk, bd%rubber)
    call initial_moduli(bd%rubber, e, nu)
    call make_isotropic(e, nu, deck%plane_stress, bd%law)
    bd%bbar = nu > locking_nu             ! F-bar on its Q1 and quadratic elements (finite_strain_assembly)
  end subroutine make_hyperelastic_body

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
  !> bd, a Dirichlet dof owned by no FIX (it has no reaction line).  A node
  !> that a FIX un=/ut= put in local axes is held along the axis of its two
  !> that is r; a FIX that gives such a node u_r /= 0, or local axes along
  !> neither r nor z, is an error at the PLANE line.
  !>   deck      (in)    the deck (its file and PLANE line, for the messages)
  !>   bdeck     (in)    the body's statements (its FIX lines)
  !>   ifix0     (in)    the FIX statements of the bodies before this one: FIX k is ifix0 + k
  !>   bd        (in)    the body, its FIX statements applied (apply_fixes)
  !>   fixed     (inout) (ndof) the Dirichlet dofs: the nodes on the axis held in r
  !>   ugroup    (in)    (ndof, ngroup) the prescribed values of each load group
  !>   fix_owner (in)    (ndof) the FIX of each fixed dof
  !>   diag      (inout) the errors
  subroutine apply_axis(deck, bdeck, ifix0, bd, fixed, ugroup, fix_owner, diag)
    type(deck_t), intent(in) :: deck
    type(body_deck_t), intent(in) :: bdeck
    integer, intent(in) :: ifix0
    type(body_t), intent(in) :: bd
    logical, intent(inout) :: fixed(:)
    real(dp), intent(in) :: ugroup(:,:)
    integer, intent(in) :: fix_owner(:)
    type(diag_t), intent(inout) :: diag
    real(dp), parameter :: same = 1.0e-9_dp
    integer :: a, slot, dof, k
    real(dp) :: p(2)
    do a = 1, bd%mesh%nnode
      if (bd%mesh%x(1, a) /= 0.0_dp) cycle
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
      if (fixed(dof)) then
        if (any(ugroup(dof, :) /= 0.0_dp)) then
          k = fix_owner(dof) - ifix0                                  ! the FIX in the body's list
          call add_error(diag, deck%file, bdeck%fixes(k)%line, 'FIX ' // bdeck%fixes(k)%boundary // &
            ' gives node ' // int_to_str(node_in_file(bd%mesh, a)) // ' of body "' // bd%name // &
            '", on the axis, a radial displacement (u_r = 0 on the axis of PLANE axisymmetric, line ' // &
            int_to_str(deck%plane_line) // ', expected)')
          return
        end if
      else
        fixed(dof) = .true.
      end if
    end do
  end subroutine apply_axis

  !> Append a mesh cache entry.  Element by element: an array constructor
  !> of a type with allocatable components leaks its temporaries under
  !> gfortran 12 (the sanitizer's leak check on a two-.geo run).
  subroutine add_entry(list, key, path)
    type(mesh_entry_t), allocatable, intent(inout) :: list(:)
    character(len=*), intent(in) :: key, path
    type(mesh_entry_t), allocatable :: longer(:)
    integer :: i
    allocate(longer(size(list) + 1))
    do i = 1, size(list)
      call move_alloc(list(i)%key, longer(i)%key)
      call move_alloc(list(i)%msh_path, longer(i)%msh_path)
    end do
    longer(size(longer))%key = key
    longer(size(longer))%msh_path = path
    call move_alloc(longer, list)
  end subroutine add_entry

end module scene
