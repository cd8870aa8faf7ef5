!> friction_newton: one load step of frictional 2D contact (Coulomb or
!> Tresca) by the primal-dual active set method, a semismooth Newton method
!> on the complementarity functions of the step.
!>
!> The problem and its symbols are friction_lcp's: G, [qn; qt], trow, cmu,
!> bound, lam = [lambda; tau], and the scaled problem Gs = D G D, qs = D q,
!> s = D^-1 lam, v = qs + Gs s, bs_k = bound_k / d_{n+k} + mus_k s_{trow(k)}
!> with mus_k = cmu_k d_{trow(k)} / d_{n+k}.  The conditions of the step are
!> the zeros of (c = 1 on the scaled problem, whose diagonal is 1)
!>     s_i - max(0, s_i - c v_i)                       normal rows
!>     s_j - clamp(s_j - c v_j, -bs_k, bs_k)           tangential rows, j = n + k
!> (s_j - c v_j = tau + c ds in scaled units), and their generalized Newton
!> step is fixed by a partition of the rows (Hueber, Stadler & Wohlmuth,
!> SIAM J. Sci. Comput. 30 (2008) 572-596, in 2D):
!>     A      normal rows in contact (s_i - c v_i > 0):       v_i = 0
!>     I      the other normal rows:                           s_i = 0
!>     St     sticking tangential rows:                        v_j = 0
!>     Sl     slipping rows, with a sign sg_k:                 s_j = sg_k bs_k
!> (a tangential row whose bound vanishes, Coulomb's open node, is in Sl
!> with tau = 0).  The step solves these m = n + nt linear equations:
!> s_I = 0 and s_Sl = sg (bound/d + mus s_trow) are substituted, which
!> leaves the rows A u St of Gs on the unknowns s_A, s_St, a dense
!> non-symmetric system (the slip columns add mus Gs(:, j) sg to the
!> columns of their normal rows) solved by LU (dgesv), O(|A u St|^3) per
!> step.  The next partition is read off the new (s, v): A from s_i - c v_i,
!> the bound b from the predicted normal force max(0, s_i - c v_i); a
!> sticking row whose force exceeds b slips with the sign of its force, a
!> slipping row whose slip turns against its force (sg v_j > 0, ds = -v_j)
!> sticks.  This is the tangential rule above in the limit c -> 0: with
!> c = 1 a slipping row whose slip came out against its force went straight
!> to the opposite slip, and on a plate sheared with mu = 1 (bench/friction.sh)
!> sixty rows flipped sign at every step, a cycle of two partitions.  The
!> start takes the rows at their bound (|s_j| >= b (1 - 1e-9), b > 0) as
!> slipping, the others as sticking: from the previous step's solution, the
!> partition of that solution (a step of its own when its slipping rows were
!> taken at their bound to round-off only: 3 or 4 steps in place of 1 on
!> random Coulomb problems).  The iteration stops when the partition repeats and
!> the residual of friction_lcp is below tol.  Starting from the caller's lam
!> (the previous load step's solution) it needs 4 to 14 steps on that plate
!> where PGS needs hundreds of sweeps or stalls.
!>
!> Convergence is local for Coulomb friction (and not proved for large mu):
!> the method stops with info 2 after maxit steps (a cycle of partitions,
!> or no convergence) and info 3 when the system of a partition is
!> singular; the caller (friction_auto) then falls back on Lemke's method.
!>
!> Programming interface
!>   solve_friction_newton(g, prob, opts, lam, rep)
!>     g, prob as friction_lcp's solve_friction_lcp (check_friction_problem
!>     first: info -1, -2 with its message); opts%tol on
!>     friction_lcp's residual, opts%maxit the step limit (0: 50); lam in:
!>     the starting point, out: the solution or the last iterate; rep: info
!>     0 solved, 2 step limit, 3 singular partition or out of memory, < 0
!>     g, prob or lam invalid,
!>     iterations = Newton steps, residual and complementarity of lam.
!> No routine prints anything.
module friction_newton
  use kinds, only: dp
  use lapack_interfaces, only: dgesv
  use strings, only: int_to_str, real_to_str
  use lcp_scaling, only: lcp_options_t, lcp_report_t, scaling_vector, lcp_gaps, report_out_of_memory, set_report, info_no_memory
  use friction_lcp, only: friction_problem_t, measure_friction, check_friction_problem
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  implicit none
  private
  public :: solve_friction_newton

  integer, parameter :: default_steps = 50     ! step limit when opts%maxit = 0
  !> At the start a row within this relative distance of its bound is taken
  !> as slipping: from the previous step's solution its force is at its bound
  !> only to round-off.
  real(dp), parameter :: start_tol = 1.0e-9_dp
  integer, parameter :: row_inactive = 0, row_active = 1       ! normal rows: I, A
  integer, parameter :: row_stick = 2, row_slip = 3            ! tangential rows: St, Sl

contains

  !> One load step by the primal-dual active set method (module header).
  !>   g     (in)    (n+nt, n+nt) G, symmetric PSD, finite
  !>   prob  (in)    the step's problem, valid
  !>   opts  (in)    tol (> 0), maxit (>= 0; 0: 50 steps)
  !>   lam   (inout) (n+nt) starting point (negative lambda taken as 0);
  !>                 the solution when rep%info = 0, else the last iterate
  !>   rep   (out)   info 0 solved, 2 step limit, 3 singular or out of memory,
  !>                 -1 / -2 g or prob invalid (check_friction_problem), -4
  !>                 lam of the wrong size;
  !>                 iterations (steps), residual, complementarity, message
  subroutine solve_friction_newton(g, prob, opts, lam, rep)
    real(dp), intent(in) :: g(:, :)
    type(friction_problem_t), intent(in) :: prob
    type(lcp_options_t), intent(in) :: opts
    real(dp), intent(inout) :: lam(:)
    type(lcp_report_t), intent(out) :: rep
    real(dp), allocatable :: d(:), gs(:, :), qs(:), s(:), v(:), bs0(:), mus(:), a(:, :), r(:)
    integer, allocatable :: kind(:), next(:), sg(:), nsg(:), unk(:), col(:), ipiv(:)
    integer :: n, nt, m, i, j, k, step, maxit, nu, st, info
    logical :: same

    call check_friction_problem(g, prob, rep)
    if (rep%info < 0) return
    if (size(lam) /= prob%n + prob%nt) then
      call set_report(rep, -4, 'friction Newton: lam has ' // int_to_str(size(lam)) // ' entries (expected n + nt = ' // &
        int_to_str(prob%n + prob%nt) // ')')
      return
    end if
    n = prob%n
    nt = prob%nt
    m = n + nt
    maxit = opts%maxit
    if (maxit == 0) maxit = default_steps
    allocate(d(m), gs(m, m), qs(m), s(m), v(m), bs0(nt), mus(nt), kind(m), next(m), sg(nt), nsg(nt), &
             col(m), stat=st)
    if (st /= 0) then
      call report_out_of_memory(rep, 'scaling the friction LCP (' // int_to_str(m) // ' rows)', &
                                8.0_dp * real(m, dp) * real(m + 12, dp))
      return
    end if
    call scaling_vector(g, d)                          ! d_i = 1/sqrt(G_ii), as friction_lcp
    do j = 1, m
      gs(:, j) = d * g(:, j) * d(j)                    ! Gs = D G D
    end do
    qs(1:n) = d(1:n) * prob%qn
    qs(n + 1:) = d(n + 1:) * prob%qt
    do k = 1, nt
      bs0(k) = prob%bound(k) / d(n + k)
      mus(k) = prob%cmu(k) * d(prob%trow(k)) / d(n + k)
    end do
    do i = 1, m                                        ! s = D^-1 lam, lambda >= 0
      s(i) = 0.0_dp
      if (ieee_is_finite(lam(i))) s(i) = lam(i) / d(i)
      if (i <= n) s(i) = max(0.0_dp, s(i))
    end do
    call lcp_gaps(gs, qs, s, v)
    call partition(s, v, .true., kind, sg)

    rep%info = 2
    do step = 1, maxit
      rep%iterations = step
      ! the unknowns: the rows of A and St, in order
      nu = 0
      col = 0
      do i = 1, m
        if (kind(i) == row_active .or. kind(i) == row_stick) then
          nu = nu + 1
          col(i) = nu
        end if
      end do
      if (allocated(unk)) deallocate(unk)
      allocate(unk(nu))
      do i = 1, m
        if (col(i) > 0) unk(col(i)) = i
      end do
      ! Gs(A u St, A u St) with the slip columns folded into their normal rows'
      if (allocated(a)) deallocate(a)
      allocate(a(nu, nu), r(nu), ipiv(nu), stat=st)
      if (st /= 0) then
        call report_out_of_memory(rep, 'the Newton step of the friction LCP (' // int_to_str(nu) // ' unknowns)', &
                                  8.0_dp * real(nu, dp) * real(nu, dp))
        exit
      end if
      do j = 1, nu
        a(:, j) = gs(unk, unk(j))
      end do
      r = -qs(unk)
      do k = 1, nt
        j = n + k
        if (kind(j) /= row_slip) cycle
        r = r - gs(unk, j) * real(sg(k), dp) * bs0(k)                 ! s_j = sg (bs0 + mus s_i)
        i = prob%trow(k)
        if (col(i) > 0) a(:, col(i)) = a(:, col(i)) + gs(unk, j) * real(sg(k), dp) * mus(k)
      end do
      if (nu > 0) then
        call dgesv(nu, 1, a, nu, ipiv, r, nu, info)
        if (info /= 0) then
          call set_report(rep, 3, 'friction Newton: the system of step ' // int_to_str(step) // ' is singular ' // &
            '(linearly dependent contact rows)')
          exit
        end if
      end if
      deallocate(ipiv)
      ! the new iterate
      do i = 1, m
        if (col(i) > 0) then
          s(i) = r(col(i))
        else if (i <= n) then
          s(i) = 0.0_dp
        end if
      end do
      deallocate(r)
      do k = 1, nt
        j = n + k
        if (kind(j) == row_slip) s(j) = real(sg(k), dp) * max(0.0_dp, bs0(k) + mus(k) * s(prob%trow(k)))
      end do
      call lcp_gaps(gs, qs, s, v)
      next = kind
      nsg = sg
      call partition(s, v, .false., next, nsg)
      same = all(next == kind) .and. all(nsg == sg .or. next(n + 1:) /= row_slip)
      kind = next
      sg = nsg
      if (same) then
        lam = d * s
        call measure_friction(g, prob, lam, rep)
        if (rep%residual <= opts%tol) then
          rep%info = 0
          exit
        end if
      end if
    end do
    lam = d * s
    call measure_friction(g, prob, lam, rep)
    select case (rep%info)
    case (0)
      rep%message = 'friction Newton: solved in ' // int_to_str(rep%iterations) // ' steps, residual ' // &
        real_to_str(rep%residual)
    case (2)
      rep%stopped = 'step limit'
      rep%message = 'friction Newton: no convergence in ' // int_to_str(maxit) // ' steps (residual ' // &
        real_to_str(rep%residual) // '; the method converges only near a solution with Coulomb friction, ' // &
        'which does not show that there is none)'
    case default
      if (rep%info /= info_no_memory) rep%stopped = 'singular'
    end select

  contains

    !> The partition of the rows at (s, v) (module header), the tangential
    !> rows from their class before (kind, sg on entry; first: .true. for the
    !> starting point, where they have none).
    subroutine partition(s, v, first, kind, sg)
      real(dp), intent(in) :: s(:), v(:)
      logical, intent(in) :: first
      integer, intent(inout) :: kind(:), sg(:)
      real(dp) :: b
      integer :: i, k, j
      do i = 1, n
        kind(i) = merge(row_active, row_inactive, s(i) - v(i) > 0.0_dp)
      end do
      do k = 1, nt
        j = n + k
        i = prob%trow(k)
        b = bs0(k)
        if (kind(i) == row_active) b = b + mus(k) * max(0.0_dp, s(i) - v(i))
        if (b <= 0.0_dp) then
          kind(j) = row_slip                           ! no bound: tau = 0
          sg(k) = 1
        else if (.not. first .and. kind(j) == row_slip) then
          ! a slipping row sticks when its slip turns against its force
          ! (ds = -v_j, sg ds < 0), and never flips sign in one step
          if (real(sg(k), dp) * v(j) > 0.0_dp) kind(j) = row_stick
        else if (abs(s(j)) >= b * (1.0_dp - merge(start_tol, 0.0_dp, first)) .and. &
                 (.not. first .or. s(j) /= 0.0_dp)) then
          kind(j) = row_slip                           ! a sticking row beyond its bound slips
          sg(k) = int(sign(1.0_dp, s(j)))
        else
          kind(j) = row_stick
          sg(k) = 0
        end if
      end do
    end subroutine partition

  end subroutine solve_friction_newton

end module friction_newton
