!> hyperelastic: the compressible Mooney-Rivlin law (neo-Hookean when c01 = 0)
!> of the rubber bodies, solved in finite strain (doc/theory.md, "Finite
!> strain"):
!>     W(F) = c10 (J^-2/3 I1 - 3) + c01 (J^-4/3 I2 - 3) + K/2 (J - 1)^2,
!> C = F' F, I1 = tr C, I2 = (I1^2 - tr C^2) / 2, I3 = det C = J^2, J = det F;
!> neo-Hookean: c10 = mu/2, c01 = 0.  The shear modulus of the reference
!> state is mu = 2 (c10 + c01), its bulk modulus K.
!>
!> The 2D kinematics enter only through F, a 3 x 3 matrix with F13 = F23 =
!> F31 = F32 = 0 (every routine here assumes it): F33 = 1 in plane strain, F33 = r / R = 1 + u_r / R (the hoop
!> stretch) in axisymmetry.  The stresses come from the invariants' derivatives
!> W_i = dW/dI_i (the law is linear in I1 and in I2 at fixed I3):
!>     S  = 2 (W1 I + W2 (I1 I - C) + W3 I3 C^-1)                (2nd Piola-Kirchhoff)
!>     CC = 4 dW/dC dC = 4 [W13 (I x A3 + A3 x I) + W23 (A2 x A3 + A3 x A2) + W33 A3 x A3
!>          + W2 (I x I - II) + W3 I3 (C^-1 x C^-1 - C^-1 o C^-1)]
!> with A2 = I1 I - C, A3 = I3 C^-1, II the symmetric identity and
!> (C^-1 o C^-1)_IJKL = (Cinv_IK Cinv_JL + Cinv_IL Cinv_JK) / 2.  The first
!> Piola-Kirchhoff stress P = F S and its tangent dP/dF, A_iJkL = delta_ik S_JL
!> + F_iI CC_IJKL F_kK, are what the total Lagrangian elements need.
!>
!> Reduced components.  Of F and P only five components are ever nonzero:
!> comp = (11, 12, 21, 22, 33); first_piola returns P and A in them (P5(5),
!> A5(5, 5)), the order of the elements' gradient operator.
!>
!> Programming interface
!>   type(hyperelastic_t)                  c10, c01, K of one body
!>   make_hyperelastic(c10, c01, bulk, law)
!>   initial_moduli(law, e, nu)            Young's modulus and Poisson's ratio of the
!>                                         reference state (the small-strain limit)
!>   strain_energy(law, f)                 W(F), F (3, 3); huge when J <= 0
!>   second_piola(law, f, s [, cc], info [, pvol])  S (3, 3) and CC (3, 3, 3, 3); info 1 when J <= 0;
!>                                         pvol: the pressure that stands for U'(J)
!>   first_piola(law, f, p5, a5, info [, pvol])  P and dP/dF in the five reduced components
!>   cauchy_stress(law, f, sig4, info)     sigma = P F' / J as (xx, yy, xy, zz)
!>   largest_stretch(f)                    the largest principal stretch sqrt(max eig C)
module hyperelastic
  use kinds, only: dp
  implicit none
  private
  public :: hyperelastic_t, make_hyperelastic, initial_moduli, strain_energy, second_piola, first_piola
  public :: cauchy_stress, largest_stretch, reduced_index

  type :: hyperelastic_t
    real(dp) :: c10 = 0.0_dp       !< first Mooney-Rivlin constant (mu/2 for neo-Hookean), >= 0
    real(dp) :: c01 = 0.0_dp       !< second constant (0 for neo-Hookean), c10 + c01 > 0
    real(dp) :: bulk = 0.0_dp      !< bulk modulus K > 0
  end type hyperelastic_t

  !> (row, column) of F and P of the five reduced components 11, 12, 21, 22, 33.
  integer, parameter :: reduced_index(2, 5) = reshape([1, 1, 1, 2, 2, 1, 2, 2, 3, 3], [2, 5])

  real(dp), parameter :: one_third = 1.0_dp / 3.0_dp

contains

  !> A law from its constants (checked by the deck reader: c10 >= 0,
  !> c10 + c01 > 0, bulk > 0).
  pure subroutine make_hyperelastic(c10, c01, bulk, law)
    real(dp), intent(in) :: c10, c01, bulk
    type(hyperelastic_t), intent(out) :: law
    law%c10 = c10
    law%c01 = c01
    law%bulk = bulk
  end subroutine make_hyperelastic

  !> The linear law W tends to at small strain: mu = 2 (c10 + c01), K, so
  !> E = 9 K mu / (3 K + mu), nu = (3 K - 2 mu) / (2 (3 K + mu)).
  pure subroutine initial_moduli(law, e, nu)
    type(hyperelastic_t), intent(in) :: law
    real(dp), intent(out) :: e, nu
    real(dp) :: mu
    mu = 2.0_dp * (law%c10 + law%c01)
    e = 9.0_dp * law%bulk * mu / (3.0_dp * law%bulk + mu)
    nu = (3.0_dp * law%bulk - 2.0_dp * mu) / (2.0_dp * (3.0_dp * law%bulk + mu))
  end subroutine initial_moduli

  !> W(F) per unit reference volume; huge(1.0_dp) when det F <= 0 (no
  !> admissible deformation turns matter inside out).
  pure real(dp) function strain_energy(law, f) result(w)
    type(hyperelastic_t), intent(in) :: law
    real(dp), intent(in) :: f(3, 3)
    real(dp) :: c(3, 3), i1, i2, jac
    jac = det3(f)
    if (.not. (jac > 0.0_dp)) then
      w = huge(1.0_dp)
      return
    end if
    c = matmul(transpose(f), f)
    i1 = c(1, 1) + c(2, 2) + c(3, 3)
    i2 = 0.5_dp * (i1**2 - sum(c * c))
    w = law%c10 * (jac**(-2.0_dp * one_third) * i1 - 3.0_dp) + law%c01 * (jac**(-4.0_dp * one_third) * i2 - 3.0_dp) &
        + 0.5_dp * law%bulk * (jac - 1.0_dp)**2
  end function strain_energy

  !> The second Piola-Kirchhoff stress S = 2 dW/dC and, optionally, the
  !> material tangent CC = 4 d2W/dC2 (module header).
  !>   law  (in)  the law
  !>   f    (in)  (3, 3) deformation gradient
  !>   s    (out) (3, 3) S, symmetric (0 when info /= 0)
  !>   cc   (out, optional) (3, 3, 3, 3) CC, with the minor and major symmetries
  !>   info (out) 0; 1 when det F <= 0 (nothing else computed)
  !>   pvol (in, optional) the pressure that stands for U'(J) = K (J - 1) in S
  !>        and CC (U'' = K is kept): the Newton tangent's pressure of a
  !>        dilatation state (newton_step); absent: U'(J)
  pure subroutine second_piola(law, f, s, cc, info, pvol)
    type(hyperelastic_t), intent(in) :: law
    real(dp), intent(in) :: f(3, 3)
    real(dp), intent(out) :: s(3, 3)
    real(dp), intent(out), optional :: cc(3, 3, 3, 3)
    integer, intent(out) :: info
    real(dp), intent(in), optional :: pvol
    real(dp) :: c(3, 3), cinv(3, 3), eye(3, 3), a2(3, 3), a3(3, 3)
    real(dp) :: i1, i2, i3, jac, w1, w2, w3, w13, w23, w33, ia, ib, ic, up
    integer :: i, j, k, l

    s = 0.0_dp
    jac = det3(f)
    if (.not. (jac > 0.0_dp)) then
      info = 1
      if (present(cc)) cc = 0.0_dp
      return
    end if
    info = 0
    c = matmul(transpose(f), f)
    i1 = c(1, 1) + c(2, 2) + c(3, 3)
    i2 = 0.5_dp * (i1**2 - sum(c * c))
    i3 = jac**2
    cinv = inverse3(c)
    eye = 0.0_dp
    do i = 1, 3
      eye(i, i) = 1.0_dp
    end do
    ! powers of I3 through J: I3^-1/3 = J^-2/3, ...
    ia = jac**(-2.0_dp * one_third)                  ! I3^-1/3
    ib = ia * ia                                     ! I3^-2/3
    ic = 1.0_dp / i3                                 ! I3^-1
    w1 = law%c10 * ia
    w2 = law%c01 * ib
    up = law%bulk * (jac - 1.0_dp)                   ! U'(J) of U = K/2 (J - 1)^2
    if (present(pvol)) up = pvol
    w3 = -one_third * law%c10 * i1 * ia * ic - 2.0_dp * one_third * law%c01 * i2 * ib * ic &
         + 0.5_dp * up / jac                          ! d/dI3 of U, dJ/dI3 = 1 / (2 J)
    a2 = i1 * eye - c
    a3 = i3 * cinv
    s = 2.0_dp * (w1 * eye + w2 * a2 + w3 * a3)     ! S = 2 sum_i W_i dI_i/dC
    if (.not. present(cc)) return
    w13 = -one_third * law%c10 * ia * ic
    w23 = -2.0_dp * one_third * law%c01 * ib * ic
    w33 = 4.0_dp / 9.0_dp * law%c10 * i1 * ia * ic**2 + 10.0_dp / 9.0_dp * law%c01 * i2 * ib * ic**2 &
          + 0.25_dp * (law%bulk * jac - up) / jac**3   ! (U'' J - U') / (4 J^3)
    do l = 1, 3
      do k = 1, 3
        do j = 1, 3
          do i = 1, 3
            cc(i, j, k, l) = 4.0_dp * ( &
              w13 * (eye(i, j) * a3(k, l) + a3(i, j) * eye(k, l)) &
              + w23 * (a2(i, j) * a3(k, l) + a3(i, j) * a2(k, l)) &
              + w33 * a3(i, j) * a3(k, l) &
              + w2 * (eye(i, j) * eye(k, l) - 0.5_dp * (eye(i, k) * eye(j, l) + eye(i, l) * eye(j, k))) &
              + w3 * i3 * (cinv(i, j) * cinv(k, l) - 0.5_dp * (cinv(i, k) * cinv(j, l) + cinv(i, l) * cinv(j, k))))
          end do
        end do
      end do
    end do
  end subroutine second_piola

  !> P = F S and the tangent A = dP/dF, A_iJkL = delta_ik S_JL + F_iI CC_IJKL F_kK,
  !> in the five reduced components (module header).
  !>   law  (in)  the law
  !>   f    (in)  (3, 3) deformation gradient, F13 = F23 = F31 = F32 = 0
  !>   p5   (out) (5) P11, P12, P21, P22, P33
  !>   a5   (out, optional) (5, 5) dP_m / dF_n (symmetric); absent: P alone
  !>   info (out) 0; 1 when det F <= 0 (p5, a5 zero)
  !>   pvol (in, optional) as second_piola's
  pure subroutine first_piola(law, f, p5, a5, info, pvol)
    type(hyperelastic_t), intent(in) :: law
    real(dp), intent(in) :: f(3, 3)
    real(dp), intent(out) :: p5(5)
    real(dp), intent(out), optional :: a5(5, 5)
    integer, intent(out) :: info
    real(dp), intent(in), optional :: pvol
    real(dp) :: s(3, 3), cc(3, 3, 3, 3), p(3, 3), t
    integer :: m, n, i, bj, k, bl, ii, kk
    if (present(a5)) then
      call second_piola(law, f, s, cc, info, pvol)
      a5 = 0.0_dp
    else
      call second_piola(law, f, s, info=info, pvol=pvol)
    end if
    p5 = 0.0_dp
    if (info /= 0) return
    p = matmul(f, s)
    do m = 1, 5
      p5(m) = p(reduced_index(1, m), reduced_index(2, m))
    end do
    if (.not. present(a5)) return
    do n = 1, 5
      k = reduced_index(1, n)
      bl = reduced_index(2, n)
      do m = 1, 5
        i = reduced_index(1, m)
        bj = reduced_index(2, m)
        t = 0.0_dp
        if (i == k) t = s(bj, bl)                                 ! geometric part
        do kk = 1, 3
          do ii = 1, 3
            t = t + f(i, ii) * cc(ii, bj, kk, bl) * f(k, kk)      ! material part
          end do
        end do
        a5(m, n) = t
      end do
    end do
  end subroutine first_piola

  !> Cauchy stress sigma = P F' / J = F S F' / J as (xx, yy, xy, zz) (in
  !> axisymmetry (rr, zz, rz, tt): the hoop last).
  !>   info (out) 0; 1 when det F <= 0 (sig4 zero)
  pure subroutine cauchy_stress(law, f, sig4, info)
    type(hyperelastic_t), intent(in) :: law
    real(dp), intent(in) :: f(3, 3)
    real(dp), intent(out) :: sig4(4)
    integer, intent(out) :: info
    real(dp) :: s(3, 3), sig(3, 3)
    call second_piola(law, f, s, info=info)
    sig4 = 0.0_dp
    if (info /= 0) return
    sig = matmul(f, matmul(s, transpose(f))) / det3(f)
    sig4 = [sig(1, 1), sig(2, 2), sig(1, 2), sig(3, 3)]
  end subroutine cauchy_stress

  !> The largest principal stretch sqrt(max eig C) of F (F13 = F23 = F31 =
  !> F32 = 0): the in-plane eigenvalues of C's 2 x 2 block and C33.
  pure real(dp) function largest_stretch(f) result(lam)
    real(dp), intent(in) :: f(3, 3)
    real(dp) :: c(2, 2), half_tr, rad
    c = matmul(transpose(f(1:2, 1:2)), f(1:2, 1:2))
    half_tr = 0.5_dp * (c(1, 1) + c(2, 2))
    rad = sqrt((0.5_dp * (c(1, 1) - c(2, 2)))**2 + c(1, 2)**2)
    lam = sqrt(max(half_tr + rad, f(3, 3)**2))
  end function largest_stretch

  !> det F of a block matrix F (F13 = F23 = F31 = F32 = 0, the only kind
  !> here): the in-plane determinant times F33.
  pure real(dp) function det3(a) result(d)
    real(dp), intent(in) :: a(3, 3)
    d = (a(1, 1) * a(2, 2) - a(1, 2) * a(2, 1)) * a(3, 3)
  end function det3

  !> The inverse of a block matrix (as det3's), det /= 0 assumed: the 2 x 2
  !> block's inverse beside 1 / a33.
  pure function inverse3(a) result(b)
    real(dp), intent(in) :: a(3, 3)
    real(dp) :: b(3, 3), d2
    d2 = a(1, 1) * a(2, 2) - a(1, 2) * a(2, 1)
    b = 0.0_dp
    b(1, 1) = a(2, 2) / d2
    b(2, 2) = a(1, 1) / d2
    b(1, 2) = -a(1, 2) / d2
    b(2, 1) = -a(2, 1) / d2
    b(3, 3) = 1.0_dp / a(3, 3)
  end function inverse3

end module hyperelastic
