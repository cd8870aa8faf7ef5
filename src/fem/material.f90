!> material: the plane elasticity tensor A of the paper (a general symmetric,
!> elliptic tensor), in engineering (Voigt) notation sigma = D eps with
!> eps = (exx, eyy, gxy), and the out-of-plane stress of plane strain.
!>
!> Isotropic and orthotropic laws.  The orthotropic law is given in material
!> axes (1, 2, 3) rotated by `angle` (degrees, counter-clockwise from x) in the
!> plane.  Plane stress: sigma_zz = 0.  Plane strain: eps_zz = 0, so
!> sigma_zz = c1 sigma_11 + c2 sigma_22 (material axes), c = -S_3k / S_33.
!>
!> Programming interface
!>   type(elasticity_t)               D(3,3) and what stress recovery needs
!>   make_isotropic(E, nu, plane_stress, mat)
!>   make_orthotropic(E1, E2, E3, nu12, nu13, nu23, G12, angle_deg, plane_stress, mat)
!>   out_of_plane_stress(mat, sigma)  sigma_zz for an in-plane stress (sxx, syy, sxy)
!>   von_mises(mat, sigma [, adt])    equivalent stress, sigma_zz included
!>   von_mises_4(sigma4)              equivalent stress of (sxx, syy, sxy, szz), the four
!>                                    components of an axisymmetric stress (szz the hoop)
!>   tensor_condition(mat)            ||D||_F ||D^-1||_F (large: nearly incompressible)
!>   locking_nu                       0.45, the nu above which fully integrated linear
!>                                    elements lock (the scene's B-bar, the locking warning)
!>
!> Axisymmetric law (PLANE axisymmetric): the material axis 3 is the hoop
!> direction, and sigma = D4 eps with eps = (err, ezz, grz, ett), D4 the
!> inverse of the 3D compliance of (11, 22, 12, 33) turned by `angle` in the
!> r-z plane; the thermal strain is alpha dT (1, 1, 0, 1).
!>
!> Thermal strain: alpha dT (1, 1, 1) in 3D.  Plane stress: eps0 = alpha dT
!> (1, 1, 0).  Plane strain (eps_zz = 0): the in-plane part becomes
!> alpha dT (1 - S_13/S_33, 1 - S_23/S_33) in material axes ((1 + nu) for an
!> isotropic law) and sigma_zz gains -alpha dT / S_33.
module material
  use kinds, only: dp
  use lapack_interfaces, only: dpotrf, dpotri
  implicit none
  private
  public :: elasticity_t, make_isotropic, make_orthotropic, out_of_plane_stress, von_mises, von_mises_4, tensor_condition
  public :: locking_nu

  !> nu above which linear elements lock: lambda / mu = 2 nu / (1 - 2 nu) = 9
  !> at 0.45, where P1's error from the volumetric constraint becomes of the
  !> order of its discretization error (doc/theory.md, the monitors' table).
  !> Above it the scene gives the bodies the B-bar strain (body) and the run
  !> warns of the elements that B-bar does not cure (model_checks).
  real(dp), parameter :: locking_nu = 0.45_dp

  type :: elasticity_t
    real(dp) :: d(3, 3) = 0.0_dp     !< sigma = D eps, global axes, Voigt (xx, yy, xy) with gamma_xy
    logical :: plane_stress = .false.
    real(dp) :: czz(2) = 0.0_dp      !< plane strain: sigma_zz = czz(1) s11 + czz(2) s22 (material axes)
    real(dp) :: angle = 0.0_dp       !< material axis 1, radians from x
    real(dp) :: emax = 0.0_dp        !< largest Young's modulus, a stiffness scale
    real(dp) :: eth(3) = 0.0_dp      !< in-plane thermal strain per unit alpha dT, global Voigt
    real(dp) :: szz_th = 0.0_dp      !< plane strain: sigma_zz gains szz_th alpha dT
    real(dp) :: d4(4, 4) = 0.0_dp    !< axisymmetric: sigma = D4 eps, (rr, zz, rz, tt) with gamma_rz
  end type elasticity_t

contains

  !> Isotropic law; requires E > 0, -1 < nu < 0.5 (checked by the deck reader).
  subroutine make_isotropic(e, nu, plane_stress, mat)
    real(dp), intent(in) :: e, nu
    logical, intent(in) :: plane_stress
    type(elasticity_t), intent(out) :: mat
    call make_orthotropic(e, e, e, nu, nu, nu, e / (2.0_dp * (1.0_dp + nu)), 0.0_dp, plane_stress, mat)
  end subroutine make_isotropic

  !> Orthotropic law from engineering constants in material axes.
  !>   e1, e2, e3   (in) Young's moduli, > 0
  !>   nu12, nu13, nu23 (in) Poisson ratios (nu_ij = -eps_j / eps_i under sigma_i)
  !>   g12          (in) in-plane shear modulus, > 0
  !>   angle_deg    (in) rotation of axis 1 from x, degrees
  !>   plane_stress (in) .true. plane stress, .false. plane strain
  !>   mat          (out) the law in global axes
  subroutine make_orthotropic(e1, e2, e3, nu12, nu13, nu23, g12, angle_deg, plane_stress, mat)
    real(dp), intent(in) :: e1, e2, e3, nu12, nu13, nu23, g12, angle_deg
    logical, intent(in) :: plane_stress
    type(elasticity_t), intent(out) :: mat
    real(dp) :: s(3, 3), sr(2, 2), dm(3, 3), t(3, 3), det, c, sn, emax, r1, r2, r3
    real(dp), parameter :: pi = acos(-1.0_dp)

    ! 3D normal compliance in material axes, times emax: s = emax S is of
    ! order one whatever the moduli' scale (S itself, of order 1/E, and its
    ! products would underflow for E near the top of the range, its inverse
    ! then overflow); D = emax s^-1
    emax = max(e1, e2, e3)
    r1 = emax / e1
    r2 = emax / e2
    r3 = emax / e3
    s = reshape([r1, -nu12 * r1, -nu13 * r1, &
                 -nu12 * r1, r2, -nu23 * r2, &
                 -nu13 * r1, -nu23 * r2, r3], [3, 3])
    if (plane_stress) then
      sr = s(1:2, 1:2)
      mat%czz = 0.0_dp
    else
      ! eps_zz = 0: S'_ij = S_ij - S_i3 S_3j / S_33
      sr(1, 1) = s(1, 1) - s(1, 3) * s(3, 1) / s(3, 3)
      sr(1, 2) = s(1, 2) - s(1, 3) * s(3, 2) / s(3, 3)
      sr(2, 1) = sr(1, 2)
      sr(2, 2) = s(2, 2) - s(2, 3) * s(3, 2) / s(3, 3)
      mat%czz = [-s(3, 1) / s(3, 3), -s(3, 2) / s(3, 3)]
    end if
    det = sr(1, 1) * sr(2, 2) - sr(1, 2) * sr(2, 1)
    dm = 0.0_dp
    dm(1, 1) = emax * (sr(2, 2) / det)
    dm(2, 2) = emax * (sr(1, 1) / det)
    dm(1, 2) = emax * (-sr(1, 2) / det)
    dm(2, 1) = dm(1, 2)
    dm(3, 3) = g12
    ! D = T' D' T with eps' = T eps (engineering shear)
    mat%angle = angle_deg * pi / 180.0_dp
    c = cos(mat%angle)
    sn = sin(mat%angle)
    t = reshape([c**2, sn**2, -2.0_dp * c * sn, &
                 sn**2, c**2, 2.0_dp * c * sn, &
                 c * sn, -c * sn, c**2 - sn**2], [3, 3])
    mat%d = matmul(transpose(t), matmul(dm, t))
    mat%d = 0.5_dp * (mat%d + transpose(mat%d))
    mat%plane_stress = plane_stress
    mat%emax = emax
    ! thermal strain per unit alpha dT, material axes -> global (tensor rotation)
    block
      real(dp) :: a1, a2
      if (plane_stress) then
        a1 = 1.0_dp; a2 = 1.0_dp
        mat%szz_th = 0.0_dp
      else
        a1 = 1.0_dp - s(1, 3) / s(3, 3)
        a2 = 1.0_dp - s(2, 3) / s(3, 3)
        mat%szz_th = -emax / s(3, 3)
      end if
      mat%eth = [a1 * c**2 + a2 * sn**2, a1 * sn**2 + a2 * c**2, 2.0_dp * (a1 - a2) * c * sn]
    end block
    call axisymmetric_tensor(s, emax, g12, t, mat%d4)
  end subroutine make_orthotropic

  !> The axisymmetric tensor D4 (rr, zz, rz, tt): the inverse of the scaled
  !> 3D normal compliance s = emax S (material axes 1, 2, 3 = hoop) by LAPACK
  !> (dpotrf, dpotri: s is symmetric positive definite for a law the deck
  !> reader accepted), the shear G12 beside it, turned to r, z by t (the
  !> in-plane rotation of eps; the hoop strain is unchanged by it).
  subroutine axisymmetric_tensor(s, emax, g12, t, d4)
    real(dp), intent(in) :: s(3, 3), emax, g12, t(3, 3)
    real(dp), intent(out) :: d4(4, 4)
    real(dp) :: sinv(3, 3), dm(4, 4), t4(4, 4)
    integer :: info, i, j
    integer, parameter :: slot(3) = [1, 2, 4]        ! 11, 22, 33 -> rows of (rr, zz, rz, tt)
    sinv = s
    call dpotrf('U', 3, sinv, 3, info)
    if (info == 0) call dpotri('U', 3, sinv, 3, info)
    d4 = 0.0_dp
    if (info /= 0) return                            ! not an admissible 3D law: no axisymmetric tensor
    dm = 0.0_dp
    do j = 1, 3
      do i = 1, j
        dm(slot(i), slot(j)) = emax * sinv(i, j)
        dm(slot(j), slot(i)) = emax * sinv(i, j)
      end do
    end do
    dm(3, 3) = g12
    t4 = 0.0_dp
    t4(1:3, 1:3) = t
    t4(4, 4) = 1.0_dp
    d4 = matmul(transpose(t4), matmul(dm, t4))        ! D4 = T4' D4' T4
    d4 = 0.5_dp * (d4 + transpose(d4))
  end subroutine axisymmetric_tensor

  !> sigma_zz of plane strain for the in-plane stress sig = (sxx, syy, sxy).
  pure real(dp) function out_of_plane_stress(mat, sig, adt) result(szz)
    type(elasticity_t), intent(in) :: mat
    real(dp), intent(in) :: sig(3)
    real(dp), intent(in), optional :: adt       !< alpha dT of a thermal strain
    real(dp) :: c, sn, s11, s22
    if (mat%plane_stress) then
      szz = 0.0_dp
      return
    end if
    c = cos(mat%angle)
    sn = sin(mat%angle)
    s11 = c**2 * sig(1) + sn**2 * sig(2) + 2.0_dp * c * sn * sig(3)   ! a.sigma.a, a = (c, s)
    s22 = sn**2 * sig(1) + c**2 * sig(2) - 2.0_dp * c * sn * sig(3)   ! b.sigma.b, b = (-s, c)
    szz = mat%czz(1) * s11 + mat%czz(2) * s22
    if (present(adt)) szz = szz + mat%szz_th * adt
  end function out_of_plane_stress

  !> von Mises equivalent stress of (sxx, syy, sxy) with sigma_zz of the law.
  pure real(dp) function von_mises(mat, sig, adt) result(vm)
    type(elasticity_t), intent(in) :: mat
    real(dp), intent(in) :: sig(3)
    real(dp), intent(in), optional :: adt
    real(dp) :: szz
    szz = out_of_plane_stress(mat, sig, adt)
    vm = von_mises_4([sig, szz])
  end function von_mises

  !> von Mises equivalent stress of the four components (sxx, syy, sxy, szz)
  !> (axisymmetric: (srr, szz, srz, stt)).
  pure real(dp) function von_mises_4(sig4) result(vm)
    real(dp), intent(in) :: sig4(4)
    real(dp) :: t(4), big
    ! the squares of t = sigma / max|sigma|: no overflow for stresses near huge
    big = maxval(abs(sig4))
    if (big == 0.0_dp) then
      vm = 0.0_dp
      return
    end if
    t = sig4 / big
    vm = big * sqrt(max(0.0_dp, t(1)**2 + t(2)**2 + t(4)**2 - t(1) * t(2) - t(2) * t(4) &
                                - t(4) * t(1) + 3.0_dp * t(3)**2))
  end function von_mises_4

  !> Condition number of D in the Frobenius norm, ||D||_F ||D^-1||_F (within a
  !> factor 3 of the 2-norm's).  For an isotropic law in plane strain it is
  !> about 2 lambda / mu = 4 nu / (1 - 2 nu): it grows without bound as nu
  !> tends to 0.5, and K inherits it; near 1 / u (u the unit roundoff) K is
  !> singular to working precision whatever the FIX statements.
  pure real(dp) function tensor_condition(mat) result(kappa)
    type(elasticity_t), intent(in) :: mat
    real(dp) :: cof(3, 3), det
    associate (d => mat%d)
      cof(1, 1) = d(2, 2) * d(3, 3) - d(2, 3) * d(3, 2)
      cof(1, 2) = d(2, 3) * d(3, 1) - d(2, 1) * d(3, 3)
      cof(1, 3) = d(2, 1) * d(3, 2) - d(2, 2) * d(3, 1)
      cof(2, 1) = d(1, 3) * d(3, 2) - d(1, 2) * d(3, 3)
      cof(2, 2) = d(1, 1) * d(3, 3) - d(1, 3) * d(3, 1)
      cof(2, 3) = d(1, 2) * d(3, 1) - d(1, 1) * d(3, 2)
      cof(3, 1) = d(1, 2) * d(2, 3) - d(1, 3) * d(2, 2)
      cof(3, 2) = d(1, 3) * d(2, 1) - d(1, 1) * d(2, 3)
      cof(3, 3) = d(1, 1) * d(2, 2) - d(1, 2) * d(2, 1)
      det = d(1, 1) * cof(1, 1) + d(1, 2) * cof(1, 2) + d(1, 3) * cof(1, 3)   ! D^-1 = cof' / det
      if (abs(det) <= tiny(1.0_dp)) then
        kappa = huge(1.0_dp)
      else
        kappa = norm2(d) * norm2(cof) / abs(det)
      end if
    end associate
  end function tensor_condition

end module material
