!> lcp_scaling: what the LCP solvers share: their options and report, the
!> symmetric diagonal scaling of LCP(W, q), the checks of the arguments and
!> the split of the redundant rows, and the scale-free measures of a
!> candidate solution.
!>
!> Scaling.  W's entries may span many orders of magnitude, so every solver
!> works on the symmetrically scaled problem
!>     Ws = D W D,   qs = D q,   z = D zs,   ws = D w,   D = diag(1/sqrt(W_ii)),
!> which has a unit diagonal (and |Ws_ij| <= 1 when W is PSD).  A row whose
!> diagonal is zero (W_ii <= 1e-30 max_j W_jj) is a redundant constraint: for a
!> PSD W its whole row and column vanish, w_i = q_i whatever z, and z_i = 0 is
!> taken; it is scaled with d_i = 1/sqrt(max_j W_jj).  If such a row has
!> qs_i < -tol ||qs||_inf the LCP has no solution (info = 1).
!> Tolerances are relative to the scaled problem; the measures reported are
!>     residual         r = || min(zs, ws) ||_inf / ||qs||_inf  (1 in place of
!>                      ||qs|| when q = 0): scale-free, whatever the units of q
!>                      (the natural residual: r = 0 iff z solves the LCP),
!>     complementarity  max_i |zs_i ws_i| / (max_i |zs_i| max_i |qs_i|)
!>                      (zs_i ws_i = z_i w_i; 0 when z = 0; divided by
!>                      max_i |zs_i|**2 instead when q = 0).
!>
!> Why it exists: Lemke (lcp_lemke), PGS (lcp_pgs), PDAS (lcp_newton) and the
!> friction solvers scale, check and measure the same way; one copy here.
!> Who may use it: the LCP modules; others through lcp_solvers.
!>
!> Programming interface
!>   type(lcp_options_t), type(lcp_report_t)   see lcp_solvers
!>   type(scaled_lcp_t)             the scaled problem on the rows kept
!>   prepare_lcp(W, q, z, opts, check_omega, p, rep)   check, scale, drop the zero rows
!>   scale_lcp(W, q, d, Ws, qs)     the symmetric diagonal scaling
!>   scaling_vector(W, d)           its d alone
!>   lcp_gaps(W, q, z, gap)         the gaps w = q + W z (dgemv)
!>   measure_solution(W, q, d, z, rep)   residual and complementarity of z
!>   lcp_natural_residual(W, q, z)  the residual r above
!>   certifies_infeasible(M, q, y)  whether y (Lemke's ray) proves that LCP(M, q) has no feasible point
!>   max_diagonal(W), negative_diagonal(W), scale_of(qmax)
!>   check_lcp_sizes(W, q, nz, opts, rep), check_lcp_values(W, q, rep),
!>   check_lcp_options(opts, info, rep)   the argument checks
!>   residual_outcome(rep, tol, solved, stopped, cause)   info 0 or 4 and the message from the residual
!>   set_report(rep, info, message), out_of_memory(phase, bytes)
!>   report_out_of_memory(rep, phase, bytes)   info info_no_memory, `out of memory while PHASE (...)`
!>   info_no_memory                  the info of a solve that could not allocate what it needs (6)
module lcp_scaling
  use kinds, only: dp, i8
  use lapack_interfaces, only: dgemv
  use strings, only: int_to_str, real_to_str
  use errors, only: error_t, set_out_of_memory
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  implicit none
  private
  public :: lcp_options_t, lcp_report_t, scaled_lcp_t
  public :: info_no_memory

  !> rep%info of a solve that could not allocate what it needs (message:
  !> `out of memory while ...`); the methods' own outcomes are 0 to 5
  integer, parameter :: info_no_memory = 6
  public :: prepare_lcp, scale_lcp, scaling_vector, lcp_gaps, measure_solution, lcp_natural_residual
  public :: certifies_infeasible
  public :: max_diagonal, negative_diagonal, scale_of
  public :: set_report, out_of_memory, report_out_of_memory, check_lcp_sizes, check_lcp_values, check_lcp_options
  public :: residual_outcome

  !> Solver settings.
  type :: lcp_options_t
    real(dp) :: tol = 1.0e-10_dp   !< tolerance on the scaled natural residual, > 0
    integer :: maxit = 0           !< pivot / sweep limit, >= 0; 0 selects the default
    real(dp) :: omega = 1.0_dp     !< PGS relaxation, 0 < omega < 2
  end type lcp_options_t

  !> Outcome of a solve.
  type :: lcp_report_t
    integer :: info = 0                      !< 0 solved, > 0 failure, < 0 argument -info invalid
    integer :: iterations = 0                !< Lemke pivots or PGS sweeps
    real(dp) :: residual = 0.0_dp            !< scaled natural residual of the returned z
    real(dp) :: complementarity = 0.0_dp     !< scaled complementarity of the returned z
    character(len=:), allocatable :: message !< one-line summary or diagnostic
    character(len=16) :: stopped = ''        !< why an unsolved run stopped, for a log line: 'stagnated',
                                             !< 'diverged', 'sweep limit', 'ray', 'pivot limit', 'inaccurate'
  end type lcp_report_t

  !> The scaled problem restricted to the rows with a positive diagonal.
  type :: scaled_lcp_t
    integer :: n = 0                      !< size of the original problem
    integer :: m = 0                      !< number of rows kept
    real(dp), allocatable :: d(:)         !< (n) scaling D
    integer, allocatable :: rows(:)       !< (m) original indices of the rows kept
    real(dp), allocatable :: ws(:, :)     !< (m, m) (D W D)(rows, rows)
    real(dp), allocatable :: qs(:)        !< (m) (D q)(rows)
    real(dp) :: qscale = 1.0_dp           !< ||D q||_inf over all n rows (1 when q = 0)
  end type scaled_lcp_t

  real(dp), parameter :: diag_zero_ratio = 1.0e-30_dp      ! W_ii below this * max diag: zero row
  real(dp), parameter :: diag_negative_ratio = 1.0e-8_dp   ! W_ii below -this * max diag: not PSD
  ! Farkas' inequalities of a computed ray, relative to the sizes of their
  ! terms: the ray carries the round-off of Lemke's tableau, which near-ties
  ! of 3e-8 relative have shown to reach far beyond eps
  real(dp), parameter :: certificate_ratio = 1.0e-8_dp

contains

  !> Check the arguments, scale, and split off the zero rows.
  !>   W, q       (in)    the problem
  !>   z          (inout) the caller's z: unchanged but on rep%info = 1 or 3,
  !>                      when it is set to 0 and measured (residual,
  !>                      complementarity)
  !>   opts       (in)    options
  !>   check_omega(in)    .true. for PGS
  !>   p          (out)   the scaled problem on the rows kept (d set whenever the
  !>                      sizes are valid)
  !>   rep        (out)   info -1..-4 on an invalid argument (message set); 1 when
  !>                      a zero row has a clearly negative q_i; 3 when the scaled
  !>                      problem's arrays cannot be allocated; 0 otherwise
  subroutine prepare_lcp(W, q, z, opts, check_omega, p, rep)
    real(dp), intent(in) :: W(:, :)
    real(dp), intent(in) :: q(:)
    real(dp), intent(inout) :: z(:)
    type(lcp_options_t), intent(in) :: opts
    logical, intent(in) :: check_omega
    type(scaled_lcp_t), intent(out) :: p
    type(lcp_report_t), intent(inout) :: rep
    real(dp), allocatable :: qs_all(:)
    real(dp) :: dmax
    integer :: n, i, j, nbad, first_bad, st

    rep%info = 0
    n = size(q)
    call check_lcp_sizes(W, q, size(z), opts, rep)
    if (rep%info == 0 .and. check_omega) then
      if (.not. (opts%omega > 0.0_dp .and. opts%omega < 2.0_dp)) &
        call set_report(rep, -4, 'LCP: omega = ' // real_to_str(opts%omega) // ' (expected 0 < omega < 2)')
    end if
    if (rep%info == 0) call check_lcp_values(W, q, rep)
    if (rep%info /= 0) return
    dmax = max_diagonal(W)

    p%n = n
    allocate(p%d(n), qs_all(n))
    call scaling_vector(W, p%d)
    qs_all = p%d * q                                    ! qs = D q
    p%qscale = 1.0_dp
    if (n > 0) p%qscale = scale_of(maxval(abs(qs_all)))

    ! Zero rows: z_i = 0, feasible only when q_i is not clearly negative.
    p%m = 0
    nbad = 0
    first_bad = 0
    do i = 1, n
      if (is_zero_row(W(i, i), dmax)) then
        if (qs_all(i) < -opts%tol * p%qscale) then
          nbad = nbad + 1
          if (first_bad == 0) first_bad = i
        end if
      else
        p%m = p%m + 1
      end if
    end do
    if (nbad > 0) then
      call set_report(rep, 1, 'LCP: row/column ' // int_to_str(first_bad) // &
        ' of W is zero (redundant constraint) but q(' // int_to_str(first_bad) // ') = ' // &
        real_to_str(q(first_bad)) // ' < 0: the LCP has no solution (' // int_to_str(nbad) // &
        ' such row(s))')
      z = 0.0_dp
      call measure_solution(W, q, p%d, z, rep)
      return
    end if

    allocate(p%rows(p%m), p%ws(p%m, p%m), p%qs(p%m), stat=st)
    if (st /= 0) then
      call report_out_of_memory(rep, 'scaling the LCP (' // int_to_str(p%m) // ' rows)', &
                                8.0_dp * real(p%m, dp) * real(p%m, dp))
      z = 0.0_dp
      call measure_solution(W, q, p%d, z, rep)
      return
    end if
    p%m = 0
    do i = 1, n
      if (.not. is_zero_row(W(i, i), dmax)) then
        p%m = p%m + 1
        p%rows(p%m) = i
      end if
    end do
    do j = 1, p%m
      p%ws(:, j) = p%d(p%rows) * W(p%rows, p%rows(j)) * p%d(p%rows(j))   ! (D W D)(rows, rows)
    end do
    p%qs = qs_all(p%rows)
  end subroutine prepare_lcp

  !> The sizes and options of LCP(W, q), the first bad one reported.
  !>   W, q  (in)    the problem
  !>   nz    (in)    the size of the caller's z
  !>   opts  (in)    tol, maxit
  !>   rep   (inout) info -1 W not square, -2 q's size, -3 z's size, -4 tol or
  !>                 maxit, with the message; unchanged when all are valid
  subroutine check_lcp_sizes(W, q, nz, opts, rep)
    real(dp), intent(in) :: W(:, :)
    real(dp), intent(in) :: q(:)
    integer, intent(in) :: nz
    type(lcp_options_t), intent(in) :: opts
    type(lcp_report_t), intent(inout) :: rep
    integer :: n
    n = size(q)
    if (size(W, 1) /= size(W, 2)) then
      call set_report(rep, -1, 'LCP: W is not square (' // int_to_str(size(W, 1)) // ' x ' // &
        int_to_str(size(W, 2)) // ')')
    else if (size(W, 1) /= n) then
      call set_report(rep, -2, 'LCP: q has ' // int_to_str(n) // ' entries, W is ' // &
        int_to_str(size(W, 1)) // ' x ' // int_to_str(size(W, 1)))
    else if (nz /= n) then
      call set_report(rep, -3, 'LCP: z has ' // int_to_str(nz) // ' entries (expected ' // &
        int_to_str(n) // ')')
    else
      call check_lcp_options(opts, -4, rep)
    end if
  end subroutine check_lcp_sizes

  !> tol and maxit of the options.
  !>   opts  (in)    tol (finite, > 0), maxit (>= 0)
  !>   info  (in)    the info of an invalid option (-k, opts the k-th argument)
  !>   rep   (inout) info and the message when one is invalid; unchanged otherwise
  subroutine check_lcp_options(opts, info, rep)
    type(lcp_options_t), intent(in) :: opts
    integer, intent(in) :: info
    type(lcp_report_t), intent(inout) :: rep
    if (.not. (ieee_is_finite(opts%tol) .and. opts%tol > 0.0_dp)) then
      call set_report(rep, info, 'LCP: tol = ' // real_to_str(opts%tol) // ' (expected tol > 0)')
    else if (opts%maxit < 0) then
      call set_report(rep, info, 'LCP: maxit = ' // int_to_str(opts%maxit) // ' (expected >= 0)')
    end if
  end subroutine check_lcp_options

  !> The values of LCP(W, q): W and q finite, no diagonal entry of W negative
  !> beyond round-off (negative_diagonal).
  !>   W, q  (in)    the problem, sizes valid
  !>   rep   (inout) info -1 (W) or -2 (q) with the message; unchanged when valid
  subroutine check_lcp_values(W, q, rep)
    real(dp), intent(in) :: W(:, :)
    real(dp), intent(in) :: q(:)
    type(lcp_report_t), intent(inout) :: rep
    integer :: i
    if (.not. all(ieee_is_finite(W))) then
      call set_report(rep, -1, 'LCP: W has non-finite entries')
    else if (.not. all(ieee_is_finite(q))) then
      call set_report(rep, -2, 'LCP: q has non-finite entries')
    else
      i = negative_diagonal(W)
      if (i > 0) call set_report(rep, -1, 'LCP: W(' // int_to_str(i) // ',' // int_to_str(i) // ') = ' // &
        real_to_str(W(i, i)) // ' < 0 (W must be positive semi-definite)')
    end if
  end subroutine check_lcp_values

  !> The outcome of a solver that stopped on its own test (Lemke's last pivot,
  !> PDAS's settled active set): info 0 with the message `SOLVED, residual R`
  !> when the residual of the solution returned is within tol, else info 4
  !> with `STOPPED but the residual R exceeds tol T (CAUSE)`.
  !>   rep     (inout) residual set on entry; info, message on exit
  !>   tol     (in)    the residual target
  !>   solved  (in)    'Lemke: solved in 12 pivots'
  !>   stopped (in)    'Lemke: terminated after 12 pivots'
  !>   cause   (in)    what a residual above tol points to ('W ill-conditioned')
  subroutine residual_outcome(rep, tol, solved, stopped, cause)
    type(lcp_report_t), intent(inout) :: rep
    real(dp), intent(in) :: tol
    character(len=*), intent(in) :: solved, stopped, cause
    if (rep%residual <= tol) then
      rep%info = 0
      rep%message = solved // ', residual ' // real_to_str(rep%residual)
    else
      rep%info = 4
      rep%stopped = 'inaccurate'
      rep%message = stopped // ' but the residual ' // real_to_str(rep%residual) // ' exceeds tol ' // &
        real_to_str(tol) // ' (' // cause // ')'
    end if
  end subroutine residual_outcome

  !> Symmetric diagonal scaling Ws = D W D, qs = D q, D = diag(d) with
  !> d_i = 1/sqrt(W_ii); a row with W_ii <= 1e-30 max_j W_jj (a zero row of a PSD
  !> matrix) gets d_i = 1/sqrt(max_j W_jj) (1 when W has no positive diagonal).
  !>   W   (in)  (n, n)
  !>   q   (in)  (n)
  !>   d   (out) (n) the scaling, > 0
  !>   Ws  (out) (n, n) D W D (unit diagonal on the rows with a positive diagonal)
  !>   qs  (out) (n) D q
  subroutine scale_lcp(W, q, d, Ws, qs)
    real(dp), intent(in) :: W(:, :)
    real(dp), intent(in) :: q(:)
    real(dp), intent(out) :: d(:)
    real(dp), intent(out) :: Ws(:, :)
    real(dp), intent(out) :: qs(:)
    integer :: j

    call scaling_vector(W, d)
    do j = 1, size(q)
      Ws(:, j) = d * W(:, j) * d(j)                   ! (D W D)_ij = d_i W_ij d_j
    end do
    qs = d * q
  end subroutine scale_lcp

  !> d_i = 1/sqrt(W_ii), or 1/sqrt(max diag) on a zero row (see scale_lcp).
  pure subroutine scaling_vector(W, d)
    real(dp), intent(in) :: W(:, :)
    real(dp), intent(out) :: d(:)
    real(dp) :: dmax
    integer :: i

    dmax = max_diagonal(W)
    do i = 1, size(d)
      if (is_zero_row(W(i, i), dmax)) then
        if (dmax > 0.0_dp) then
          d(i) = 1.0_dp / sqrt(dmax)
        else
          d(i) = 1.0_dp
        end if
      else
        d(i) = 1.0_dp / sqrt(W(i, i))
      end if
    end do
  end subroutine scaling_vector

  !> Residual and complementarity of z on the scaled problem (module header).
  !>   W, q  (in)    the problem, (n, n) and (n)
  !>   d     (in)    (n) the scaling
  !>   z     (in)    (n) candidate
  !>   rep   (inout) residual and complementarity set
  subroutine measure_solution(W, q, d, z, rep)
    real(dp), intent(in) :: W(:, :)
    real(dp), intent(in) :: q(:)
    real(dp), intent(in) :: d(:)
    real(dp), intent(in) :: z(:)
    type(lcp_report_t), intent(inout) :: rep
    real(dp), allocatable :: gap(:), zs(:), ws(:)
    real(dp) :: prod, zmax, qmax
    integer :: n

    n = size(q)
    rep%residual = 0.0_dp
    rep%complementarity = 0.0_dp
    if (n == 0) return
    allocate(gap(n), zs(n), ws(n))
    call lcp_gaps(W, q, z, gap)                               ! w = q + W z
    zs = z / d                                                ! zs = D^-1 z
    ws = d * gap                                              ! ws = D w
    qmax = maxval(abs(d * q))
    rep%residual = maxval(abs(min(zs, ws))) / scale_of(qmax)
    prod = maxval(abs(zs * ws))
    zmax = maxval(abs(zs))
    if (prod > 0.0_dp) then
      if (qmax > 0.0_dp) then
        rep%complementarity = prod / (zmax * qmax)
      else
        rep%complementarity = prod / zmax**2
      end if
    end if
  end subroutine measure_solution

  !> The gaps w = q + W z of a candidate z (dgemv; nothing to do when n = 0).
  !>   W    (in)  (n, n)
  !>   q    (in)  (n)
  !>   z    (in)  (n)
  !>   gap  (out) (n) w = q + W z
  subroutine lcp_gaps(W, q, z, gap)
    real(dp), intent(in) :: W(:, :)
    real(dp), intent(in) :: q(:)
    real(dp), intent(in) :: z(:)
    real(dp), intent(out) :: gap(:)
    integer :: n
    n = size(q)
    gap = q
    if (n > 0) call dgemv('N', n, n, 1.0_dp, W, n, z, 1, 1.0_dp, gap, 1)
  end subroutine lcp_gaps

  !> Scaled natural residual r = ||min(zs, ws)||_inf / ||qs||_inf of a
  !> candidate z (zs = D^-1 z, ws = D (q + W z), qs = D q, D as in scale_lcp).
  !> r = 0 exactly when z solves LCP(W, q).
  !>   W  (in) (n, n)
  !>   q  (in) (n)
  !>   z  (in) (n) candidate, finite
  !>   r  (result) the residual; huge(1.0_dp) when the sizes do not match
  function lcp_natural_residual(W, q, z) result(r)
    real(dp), intent(in) :: W(:, :)
    real(dp), intent(in) :: q(:)
    real(dp), intent(in) :: z(:)
    real(dp) :: r
    type(lcp_report_t) :: rep
    real(dp), allocatable :: d(:)

    r = huge(1.0_dp)
    if (size(W, 1) /= size(q) .or. size(W, 2) /= size(q) .or. size(z) /= size(q)) return
    allocate(d(size(q)))
    call scaling_vector(W, d)
    call measure_solution(W, q, d, z, rep)
    r = rep%residual
  end function lcp_natural_residual

  !> Whether y proves that LCP(M, q) has no solution, not even a feasible
  !> point: y >= 0, y /= 0, M'y <= 0 and q'y < 0 (Farkas: a z >= 0 with
  !> q + M z >= 0 would give 0 <= y'(q + M z) = q'y + (M'y)'z < 0).  Lemke's
  !> ray (solve_lcp_lemke, solve_lcp_lemke_scaled: ray) is such a y when M
  !> is positive semi-definite; for another M, e.g. the copositive LCP of
  !> Coulomb friction, it may not be, and then it proves nothing.  The
  !> inequalities are tested against the round-off of their terms:
  !> (M'y)_j <= c (|M|'y)_j and q'y < -c |q|'y, c = certificate_ratio.
  !>   M  (in) (n, n)
  !>   q  (in) (n)
  !>   y  (in) (n) the candidate, finite
  !>   (result) .false. also when the sizes do not match
  logical function certifies_infeasible(M, q, y) result(ok)
    real(dp), intent(in) :: M(:, :)
    real(dp), intent(in) :: q(:)
    real(dp), intent(in) :: y(:)
    real(dp), allocatable :: my(:), size_my(:)
    integer :: n
    ok = .false.
    n = size(q)
    if (size(M, 1) /= n .or. size(M, 2) /= n .or. size(y) /= n .or. n == 0) return
    if (any(y < 0.0_dp) .or. .not. any(y > 0.0_dp)) return
    my = matmul(transpose(M), y)                      ! M'y
    size_my = matmul(transpose(abs(M)), y)            ! |M|'y
    ok = all(my <= certificate_ratio * size_my) .and. &
         dot_product(q, y) < -certificate_ratio * dot_product(abs(q), y)
  end function certifies_infeasible

  pure function max_diagonal(W) result(dmax)
    real(dp), intent(in) :: W(:, :)
    real(dp) :: dmax
    integer :: i
    dmax = 0.0_dp
    do i = 1, min(size(W, 1), size(W, 2))
      dmax = max(dmax, W(i, i))
    end do
  end function max_diagonal

  !> The first i with W(i,i) < 0 beyond round-off (|W(i,i)| > 1e-8 of the
  !> largest diagonal entry): W is then not positive semi-definite; 0 if none.
  pure integer function negative_diagonal(W) result(bad)
    real(dp), intent(in) :: W(:, :)
    real(dp) :: dmax
    integer :: i
    dmax = max_diagonal(W)
    bad = 0
    do i = 1, min(size(W, 1), size(W, 2))
      if (W(i, i) < 0.0_dp .and. abs(W(i, i)) > diag_negative_ratio * dmax) then
        bad = i
        return
      end if
    end do
  end function negative_diagonal

  pure logical function is_zero_row(wii, dmax)
    real(dp), intent(in) :: wii, dmax
    is_zero_row = wii <= diag_zero_ratio * dmax
  end function is_zero_row

  !> The scale of the scaled q: its largest entry, 1 when q = 0.
  pure real(dp) function scale_of(qmax) result(sc)
    real(dp), intent(in) :: qmax
    sc = qmax
    if (.not. (sc > 0.0_dp)) sc = 1.0_dp
  end function scale_of

  !> rep%info = info, rep%message = message.
  !> A solve that could not allocate what it needs: info info_no_memory (a
  !> caller tells it from a failure of the method without reading the text).
  !>   rep   (inout) the report
  !>   phase (in)    what the solver was doing
  !>   bytes (in)    what it needed, >= 0
  subroutine report_out_of_memory(rep, phase, bytes)
    type(lcp_report_t), intent(inout) :: rep
    character(len=*), intent(in) :: phase
    real(dp), intent(in) :: bytes
    call set_report(rep, info_no_memory, out_of_memory(phase, bytes))
  end subroutine report_out_of_memory

  subroutine set_report(rep, info, message)
    type(lcp_report_t), intent(inout) :: rep
    integer, intent(in) :: info
    character(len=*), intent(in) :: message
    rep%info = info
    rep%message = message
  end subroutine set_report

  !> `out of memory while PHASE (about N MB needed)`, the program's wording
  !> for an allocation that failed (errors: set_out_of_memory).
  function out_of_memory(phase, bytes) result(message)
    character(len=*), intent(in) :: phase
    real(dp), intent(in) :: bytes
    character(len=:), allocatable :: message
    type(error_t), allocatable :: err
    call set_out_of_memory(err, phase, int(min(bytes, 9.0e18_dp), i8))
    message = err%message
  end function out_of_memory

end module lcp_scaling
