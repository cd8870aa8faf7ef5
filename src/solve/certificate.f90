!> certificate: the check of a solved load step against the conditions its
!> answer must satisfy, whatever method found it, each relative to a scale
!> of the problem itself (so that the deck's units do not change it):
!>   complementarity  the contact conditions: no penetration (gap_i >= 0 on
!>                    the scale of the gaps, max |q|), no tension (mu_i >= 0
!>                    on the scale of the forces, max |mu|), mu_i gap_i = 0 on
!>                    the product of the two; with friction also the natural
!>                    residual of the friction conditions (friction_lcp's,
!>                    scaled: stick rows do not slip, slipping rows are on
!>                    the cone and oppose their slip)
!>   cone             with friction, |tau_r| - (mu lambda_i + bound) on the
!>                    scale of the forces: every tangential force in its cone
!>   equilibrium      the free motions' equilibrium H'z = e along every
!>                    combination of the modes and RIGID directions that the
!>                    contacts hold, each relative to its load or to the
!>                    contact forces that balance each other along it
!>                    (a force, a moment: each on its own scale)
!> A step whose answer does not pass (certified) is a failed solve: the next
!> method is tried, then the step is split, then the run ends; never an
!> answer.  The figures go to the summary (`certificate complementarity REL
!> cone REL equilibrium REL`) and the step table.
!>
!> Why it exists: the methods report their own residuals in their own
!> scalings, and one of them may stop on a wrong answer (a degenerate
!> pivot, a compiler's rounding): one check of the answer itself, outside
!> every method, decides.
!>
!> Programming interface
!>   type(certificate_t)                     complementarity, cone, equilibrium (relative)
!>   certify_frictionless(w, q, h, e, held, mu, alpha, cert)   LCP(W, q) with free modes
!>   certify_friction(w, fp, z, h, e, alpha, cert)        the friction LCP (h, e: the held modes, may be empty)
!>   certified(cert)                         every figure within certificate_tol
!>   certificate_tol                         the largest figure accepted (1e-6)
module certificate
  use kinds, only: dp
  use friction_lcp, only: friction_problem_t, friction_residual
  implicit none
  private
  public :: certificate_t, certify_frictionless, certify_friction, certified, certificate_tol

  !> The largest relative figure of a certified answer.  The methods end at
  !> a scaled residual of SOLVER tol (1e-10 by default) and their exact
  !> finishes at round-off; the multipliers of the free modes at 1e3 tol.  A
  !> wrong answer (a pivot past the solution, a stalled iteration) is off by
  !> far more: 1e-6 tells the two apart with room on both sides.
  real(dp), parameter :: certificate_tol = 1.0e-6_dp

  type :: certificate_t
    real(dp) :: complementarity = 0               !< the contact conditions, relative
    real(dp) :: cone = 0                          !< the friction cone, relative (0 without friction)
    real(dp) :: equilibrium = 0                   !< the free motions' equilibrium, relative (0 without them)
  end type certificate_t

contains

  !> The certificate of an answer of LCP(W, q) with free modes: gap = q + W
  !> mu - H alpha >= 0, mu >= 0, mu'gap = 0, and H'mu = e along the held
  !> combinations.
  !>   w     (in)  (n, n) W
  !>   q     (in)  (n) the gaps without contact forces
  !>   h     (in)  (n, k) H: how each free mode or direction opens the gaps (k may be 0)
  !>   e     (in)  (k) their loads
  !>   held  (in)  (k, kh) the combinations the rows hold
  !>   mu    (in)  (n) the multipliers
  !>   alpha (in)  (k) the modes' amplitudes
  !>   cert  (out) the figures
  subroutine certify_frictionless(w, q, h, e, held, mu, alpha, cert)
    real(dp), intent(in) :: w(:,:), q(:), h(:,:), e(:), held(:,:), mu(:), alpha(:)
    type(certificate_t), intent(out) :: cert
    real(dp), allocatable :: gap(:), wmu(:), motion(:)
    wmu = matmul(w, mu)
    gap = q + wmu
    motion = [real(dp) ::]
    if (size(alpha) > 0) then
      motion = matmul(h, alpha)
      gap = gap - motion
    end if
    cert%complementarity = contact_conditions(gap, mu, [q, wmu, motion])
    if (size(held, 2) > 0) cert%equilibrium = mode_equilibrium(matmul(h, held), matmul(transpose(held), e), mu, &
                                                               force_scale(w, q))
  end subroutine certify_frictionless

  !> The certificate of an answer of the friction LCP z = [lambda; tau]: the
  !> normal rows as certify_frictionless, the friction conditions' natural
  !> residual, the cone, and the held modes' equilibrium H'z = e.
  !>   fp    (in) the step's friction problem, its gaps and slips with the
  !>              free motions (q - H alpha) included
  !>   z     (in) (n + nt) the multipliers
  !>   h, e  (in) (n + nt, k), (k): the held combinations and their loads (k may be 0)
  subroutine certify_friction(w, fp, z, h, e, cert)
    real(dp), intent(in) :: w(:,:), z(:), h(:,:), e(:)
    type(friction_problem_t), intent(in) :: fp
    type(certificate_t), intent(out) :: cert
    real(dp), allocatable :: gap(:), wz(:)
    real(dp) :: fscale, worst
    integer :: r, n
    n = fp%n
    wz = matmul(w(1:n, :), z)
    gap = fp%qn + wz
    cert%complementarity = max(contact_conditions(gap, z(1:n), [fp%qn, wz]), friction_residual(w, fp, z))
    fscale = max(maxval(abs(z), mask=.true.), maxval(fp%bound, mask=.true.), tiny(1.0_dp))
    worst = 0.0_dp
    do r = 1, fp%nt
      worst = max(worst, abs(z(n + r)) - (fp%cmu(r) * max(z(fp%trow(r)), 0.0_dp) + fp%bound(r)))
    end do
    cert%cone = worst / fscale
    cert%equilibrium = mode_equilibrium(h, e, z, force_scale(w(1:n, 1:n), fp%qn))
  end subroutine certify_friction

  !> .true. when every figure of cert is within certificate_tol.
  pure logical function certified(cert)
    type(certificate_t), intent(in) :: cert
    certified = cert%complementarity <= certificate_tol .and. cert%cone <= certificate_tol .and. &
                cert%equilibrium <= certificate_tol
  end function certified

  !> Penetration, tension and complementarity of the normal rows, the
  !> largest of the three, each on its scale: the gaps' (the largest of the
  !> gaps the loads open or close without contact forces, q, of how much the
  !> contact forces and the free motions move the rows, W mu and H alpha, and
  !> of the final gaps: a problem whose q is 0, a body pressed onto a flat
  !> by a force alone, still has the scale of its deformation), the forces'
  !> (max |mu|) and their product.
  !>   gap    (in) (n) the final gaps;  mu (in) (n) the multipliers
  !>   terms  (in) the parts of the gaps, q, W mu, H alpha (their sizes set the scale)
  pure real(dp) function contact_conditions(gap, mu, terms) result(c)
    real(dp), intent(in) :: gap(:), mu(:), terms(:)
    real(dp) :: gscale, mscale
    c = 0.0_dp
    if (size(mu) == 0) return
    gscale = max(maxval(abs(terms)), maxval(abs(gap)), tiny(1.0_dp))
    mscale = max(maxval(abs(mu)), tiny(1.0_dp))
    c = max(maxval(-gap) / gscale, maxval(-mu) / mscale, maxval(abs(mu * gap)) / (gscale * mscale), 0.0_dp)
  end function contact_conditions

  !> The largest relative residual of the equilibrium along the columns of
  !> h: |h_j'z - e_j| / max(|e_j|, sum_i |h_ij z_i|, f sum_i |h_ij|), the load
  !> along the combination, the contact forces that balance each other along
  !> it, or the problem's force scale f along it: a nil load held by forces
  !> at round-off (a body that floats off its contacts) is in equilibrium.
  !>   f (in) the force scale (force_scale)
  pure real(dp) function mode_equilibrium(h, e, z, f) result(c)
    real(dp), intent(in) :: h(:,:), e(:), z(:), f
    real(dp) :: scale
    integer :: j
    c = 0.0_dp
    do j = 1, size(e)
      scale = max(abs(e(j)), sum(abs(h(:, j) * z)), f * sum(abs(h(:, j))), tiny(1.0_dp))
      c = max(c, abs(dot_product(h(:, j), z) - e(j)) / scale)
    end do
  end function mode_equilibrium

  !> The problem's force scale: the largest force a row needs, alone on its
  !> own stiffness, to close or open its gap without contact forces,
  !> max_i |q_i| / W_ii over the rows a free dof moves (W_ii > 0).
  !>   w (in) (n, n) W;  q (in) (n) the gaps without contact forces
  pure real(dp) function force_scale(w, q) result(f)
    real(dp), intent(in) :: w(:,:), q(:)
    integer :: i
    f = 0.0_dp
    do i = 1, size(q)
      if (w(i, i) > 0.0_dp) f = max(f, abs(q(i)) / w(i, i))
    end do
  end function force_scale

end module certificate
