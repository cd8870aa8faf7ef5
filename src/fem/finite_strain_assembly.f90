!> finite_strain_assembly: the residual and the tangent of a scene
!> whose bodies are some hyperelastic (body%finite: module
!> finite_strain_elements) and some linear (their K u and K, as module body),
!> on K's pattern of build_pattern and with its Dirichlet elimination
!> (doc/theory.md, "Finite strain: hyperelastic bodies").  The tangent is
!> the consistent one, but that with theta the F-bar elements' initial-stress
!> terms take the pressure of their dilatation state (newton_step).
!>
!> At a displacement u (ndof, solver basis) and a correction dubar of the
!> prescribed values (the fixed dofs' target minus their current value), the
!> Newton system of one iterate is
!>     K_ff du_f = f_f - f_int,f(u) - K_fd dubar_d,
!> whose matrix and right-hand side assemble_tangent adds; f_int (all dofs)
!> comes from internal_force_vector (the reactions are its fixed rows).  A
!> node in local axes (FIX un=/ut=) has its element rows turned as module
!> body's: ue = Q u to the kernels, Q' fe and Q' K Q back.
!>
!> An element with J <= 0 at a point stops the assembly: bad = (body, element)
!> and the outputs are incomplete; the caller cuts the load step.  With
!> definite, each hyperelastic element's tangent is cut to its positive part
!> (its negative eigenvalues set to zero): the matrix of a descent direction
!> where the consistent tangent is not positive definite (newton_step).
!>
!> Programming interface
!>   assemble_tangent(bodies, u, eq, dubar, k, rhs, bad [, definite, theta])
!>        k += K_ff(u), rhs -= f_int,f(u) + K_fd dubar_d
!>   internal_force_vector(bodies, u, fint, bad)             fint = f_int(u) (ndof)
!>   element_dilatations(bodies, u, du, j0, dj0, bad)        F-bar's J0 and dJ0/du du per element
!>   finite_strain_fields(bodies, u, energy, jac, stretch, stress, vm)
!>        the hyperelastic bodies' energy, J, largest stretch and Cauchy stress per element
module finite_strain_assembly
  use kinds, only: dp
  use elements, only: element_stiffness, max_nen
  use axisymmetric_elements, only: axi_element_stiffness
  use body, only: body_t, element_dofs, element_coordinates, rotate_element_matrix, rotate_element_vector, &
                  scatter_element, scatter_springs, add_spring_forces, body_pressure_modes
  use finite_strain_elements, only: finite_strain_response, finite_strain_energy, finite_strain_state, &
                                    finite_strain_dilatation
  use material, only: von_mises_4
  use sparse_matrix, only: csc_t
  use lapack_interfaces, only: dsyev
  implicit none
  private
  public :: assemble_tangent, internal_force_vector, finite_strain_fields, element_dilatations

contains

  !> ve = element e's values of v (solver basis) in x, y components (a node in
  !> local axes turned back, as module body's kernels take them).
  subroutine element_values(bd, e, v, ve)
    type(body_t), intent(in) :: bd
    integer, intent(in) :: e
    real(dp), intent(in) :: v(:)
    real(dp), intent(out) :: ve(:)
    integer :: dofs(2 * max_nen), m
    m = 2 * bd%mesh%nen(e)
    call element_dofs(bd, e, dofs)
    ve(1:m) = v(dofs(1:m))
    if (allocated(bd%axes)) call rotate_element_vector(bd, e, ve, .true.)
  end subroutine element_values

  !> Element e of body bd at u: fe (solver basis) and, when present, ke.
  !>   info (out) 0; > 0 when J <= 0 at a point of the element
  subroutine element_response_at(bd, e, u, fe, ke, info, theta)
    type(body_t), intent(in) :: bd
    integer, intent(in) :: e
    real(dp), intent(in) :: u(:)
    real(dp), intent(out) :: fe(:)
    real(dp), intent(inout), optional :: ke(:,:)
    integer, intent(out) :: info
    real(dp), intent(in), optional :: theta
    real(dp) :: xe(2, max_nen), ue(2 * max_nen), kl(2 * max_nen, 2 * max_nen)
    integer :: nen, m
    nen = bd%mesh%nen(e)
    m = 2 * nen
    call element_coordinates(bd%mesh, e, xe)
    call element_values(bd, e, u, ue)
    info = 0
    if (bd%finite) then
      ! F-bar where the linear kernels take B-bar's mean dilatation (Q1 of a
      ! nearly incompressible body); the quadratic elements go without it
      if (present(ke)) then
        call finite_strain_response(nen, xe(:, 1:nen), ue(1:m), bd%rubber, bd%axisymmetric, bd%thick, fe(1:m), kl, &
                                    info, fbar=with_fbar(bd, nen), theta=theta)
      else                                   ! the forces alone (the line search's residuals): no tangent
        call finite_strain_response(nen, xe(:, 1:nen), ue(1:m), bd%rubber, bd%axisymmetric, bd%thick, fe(1:m), &
                                    info=info, fbar=with_fbar(bd, nen))
      end if
      if (info /= 0) return
    else
      if (bd%axisymmetric) then
        call axi_element_stiffness(nen, xe(:, 1:nen), bd%law%d4, kl, body_pressure_modes(bd, nen))
      else
        call element_stiffness(nen, xe(:, 1:nen), bd%law%d, bd%thick, kl, body_pressure_modes(bd, nen))
      end if
      fe(1:m) = matmul(kl(1:m, 1:m), ue(1:m))
    end if
    if (allocated(bd%axes)) call rotate_element_vector(bd, e, fe, .false.)   ! Q' fe
    if (.not. present(ke)) return
    if (allocated(bd%axes)) call rotate_element_matrix(bd, e, kl)             ! Q' K Q
    ke(1:m, 1:m) = kl(1:m, 1:m)
  end subroutine element_response_at

  !> k += K_ff(u), rhs -= f_int,f(u) + K_fd dubar_d over every element and spring.
  !>   bodies (in)    the bodies, dof0 set
  !>   u      (in)    (ndof) displacement, solver basis
  !>   eq     (in)    (ndof) free equation numbers
  !>   dubar  (in)    (ndof) on the fixed dofs: the correction of their prescribed values
  !>   k      (inout) values accumulated on build_pattern's pattern
  !>   rhs    (inout) (nfree) holds f_f on entry
  !>   bad    (out)   (2) 0, 0; (body, element) of an element with J <= 0 (k, rhs incomplete),
  !>                  (body, 0) when a term K_fd dubar_d would overflow
  !>   definite (in, optional) .true.: the hyperelastic elements' tangents cut to
  !>                  their positive parts (module header)
  !>   theta  (in, optional) (nelem, global numbering) the F-bar elements'
  !>                  dilatation states, the pressure of their tangents (newton_step)
  subroutine assemble_tangent(bodies, u, eq, dubar, k, rhs, bad, definite, theta)
    type(body_t), intent(in) :: bodies(:)
    real(dp), intent(in) :: u(:), dubar(:)
    integer, intent(in) :: eq(:)
    type(csc_t), intent(inout) :: k
    real(dp), intent(inout) :: rhs(:)
    integer, intent(out) :: bad(2)
    logical, intent(in), optional :: definite
    real(dp), intent(in), optional :: theta(:)
    real(dp) :: fe(2 * max_nen), ke(2 * max_nen, 2 * max_nen), fs(size(u))
    integer :: dofs(2 * max_nen), b, e, m, a, info
    logical :: ok
    bad = 0
    do b = 1, size(bodies)
      do e = 1, bodies(b)%mesh%nelem
        m = 2 * bodies(b)%mesh%nen(e)
        if (present(theta)) then
          call element_response_at(bodies(b), e, u, fe, ke, info, theta(bodies(b)%elem0 + e))
        else
          call element_response_at(bodies(b), e, u, fe, ke, info)
        end if
        if (info /= 0) then
          bad = [b, e]
          return
        end if
        if (present(definite)) then
          if (definite .and. bodies(b)%finite) call definite_part(ke(1:m, 1:m))
        end if
        call element_dofs(bodies(b), e, dofs)
        do a = 1, m                                        ! rhs_f -= f_int,f
          if (eq(dofs(a)) > 0) rhs(eq(dofs(a))) = rhs(eq(dofs(a))) - fe(a)
        end do
        call scatter_element(m, dofs, ke, eq, dubar, k, rhs, ok)
        if (.not. ok .and. bad(1) == 0) bad = [b, 0]
      end do
      if (bodies(b)%springs%n > 0) then                    ! springs: linear, K_s u and K_s
        fs = 0.0_dp
        call add_spring_forces(bodies(b), u, fs)
        do a = 1, size(u)
          if (eq(a) > 0) rhs(eq(a)) = rhs(eq(a)) - fs(a)
        end do
        call scatter_springs(bodies(b), eq, dubar, k, rhs, ok)
        if (.not. ok .and. bad(1) == 0) bad = [b, 0]
      end if
    end do
  end subroutine assemble_tangent

  !> ke's positive semi-definite part: its negative eigenvalues set to zero
  !> (the iterate's descent matrix where the consistent tangent is not
  !> definite: assemble_tangent's definite).
  subroutine definite_part(ke)
    real(dp), intent(inout) :: ke(:,:)
    real(dp) :: v(size(ke, 1), size(ke, 1)), lam(size(ke, 1)), work(34 * size(ke, 1))
    integer :: info, n
    n = size(ke, 1)
    v = ke
    call dsyev('V', 'U', n, v, n, lam, work, size(work), info)
    if (info /= 0 .or. lam(1) >= 0.0_dp) return
    ke = matmul(v * spread(max(lam, 0.0_dp), 1, n), transpose(v))
  end subroutine definite_part

  !> Whether bd's elements of nen nodes take F-bar: a nearly incompressible
  !> body (bd%bbar, initial nu > 0.45), on Q1 and on the quadratic elements
  !> (P2, Q8, Q9: the mean dilatation as P2/P0, Q2/P0; doc/theory.md says
  !> what it gains); a 3-node triangle has one point, where F-bar is nothing.
  pure logical function with_fbar(bd, nen)
    type(body_t), intent(in) :: bd
    integer, intent(in) :: nen
    with_fbar = bd%bbar .and. nen >= 4
  end function with_fbar

  !> Per element (bodies(b)%elem0 + e) of a hyperelastic body with F-bar:
  !> its mean dilatation J0 at u and dJ0/du du; the others' 1 and 0.
  !>   bad (out) (2) 0, 0; (body, element) of an element with J <= 0
  subroutine element_dilatations(bodies, u, du, j0, dj0, bad)
    type(body_t), intent(in) :: bodies(:)
    real(dp), intent(in) :: u(:), du(:)
    real(dp), intent(out) :: j0(:), dj0(:)
    integer, intent(out) :: bad(2)
    real(dp) :: xe(2, max_nen), ue(2 * max_nen), due(2 * max_nen)
    integer :: b, e, m, nen, info, ge
    j0 = 1.0_dp
    dj0 = 0.0_dp
    bad = 0
    do b = 1, size(bodies)
      if (.not. bodies(b)%finite) cycle
      do e = 1, bodies(b)%mesh%nelem
        nen = bodies(b)%mesh%nen(e)
        if (.not. with_fbar(bodies(b), nen)) cycle
        m = 2 * nen
        ge = bodies(b)%elem0 + e
        call element_coordinates(bodies(b)%mesh, e, xe)
        call element_values(bodies(b), e, u, ue)
        call element_values(bodies(b), e, du, due)
        call finite_strain_dilatation(nen, xe(:, 1:nen), ue(1:m), due(1:m), bodies(b)%axisymmetric, j0(ge), dj0(ge), &
                                      info)
        if (info /= 0) then
          bad = [b, e]
          return
        end if
      end do
    end do
  end subroutine element_dilatations

  !> fint = f_int(u) on every dof (the fixed rows: the reactions), solver basis.
  !>   bad (out) (2) 0, 0; (body, element) of an element with J <= 0 (fint incomplete)
  subroutine internal_force_vector(bodies, u, fint, bad)
    type(body_t), intent(in) :: bodies(:)
    real(dp), intent(in) :: u(:)
    real(dp), intent(out) :: fint(:)
    integer, intent(out) :: bad(2)
    real(dp) :: fe(2 * max_nen)
    integer :: dofs(2 * max_nen), b, e, m, info
    fint = 0.0_dp
    bad = 0
    do b = 1, size(bodies)
      do e = 1, bodies(b)%mesh%nelem
        m = 2 * bodies(b)%mesh%nen(e)
        call element_response_at(bodies(b), e, u, fe, info=info)
        if (info /= 0) then
          bad = [b, e]
          return
        end if
        call element_dofs(bodies(b), e, dofs)
        fint(dofs(1:m)) = fint(dofs(1:m)) + fe(1:m)
      end do
      call add_spring_forces(bodies(b), u, fint)
    end do
  end subroutine internal_force_vector

  !> The hyperelastic bodies' results at u (solver basis): their stored
  !> energy int W dV0, and per element (global numbering, bodies(b)%elem0 + e)
  !> J and the largest principal stretch at the element's centre, and there
  !> the Cauchy stress (xx, yy, xy, or rr, zz, rz, tt in axisymmetric
  !> analysis) and its von Mises value when stress is present.  Elements of
  !> linear bodies keep what the caller put there (jac, stretch: 1).
  !>   energy (out) the hyperelastic bodies' energy (the linear ones' is the caller's)
  !>   jac, stretch (inout) (nelem)
  !>   stress (inout, optional) (3 or 4, nelem);  vm (inout, optional) (nelem)
  subroutine finite_strain_fields(bodies, u, energy, jac, stretch, stress, vm)
    type(body_t), intent(in) :: bodies(:)
    real(dp), intent(in) :: u(:)
    real(dp), intent(out) :: energy
    real(dp), intent(inout) :: jac(:), stretch(:)
    real(dp), intent(inout), optional :: stress(:,:), vm(:)
    real(dp) :: xe(2, max_nen), ue(2 * max_nen), sig4(4), we
    integer :: b, e, nen, ge, info
    energy = 0.0_dp
    do b = 1, size(bodies)
      if (.not. bodies(b)%finite) cycle
      associate (bd => bodies(b))
        do e = 1, bd%mesh%nelem
          nen = bd%mesh%nen(e)
          ge = bd%elem0 + e
          call element_coordinates(bd%mesh, e, xe)
          call element_values(bd, e, u, ue)
          call finite_strain_energy(nen, xe(:, 1:nen), ue(1:2 * nen), bd%rubber, bd%axisymmetric, bd%thick, we, &
                                    info, fbar=with_fbar(bd, nen))
          energy = energy + we
          call finite_strain_state(nen, xe(:, 1:nen), ue(1:2 * nen), bd%rubber, bd%axisymmetric, sig4, jac(ge), &
                                   stretch(ge), info)
          if (present(stress)) then
            stress(:, ge) = sig4(1:size(stress, 1))
            vm(ge) = von_mises_4(sig4)
          end if
        end do
      end associate
    end do
  end subroutine finite_strain_fields

end module finite_strain_assembly
