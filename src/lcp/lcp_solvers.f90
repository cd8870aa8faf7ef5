!> lcp_solvers: the linear complementarity problem of frictionless contact.
!>
!> LCP(W, q): find z in R^n with
!>     z >= 0,   w = q + W z >= 0,   z'w = 0,
!> where W (n x n) is the Delassus matrix B K^-1 B' of the condensed mortar
!> contact problem (symmetric positive semi-definite, entries are compliances)
!> and q = g - B K^-1 f the gap of the unconstrained solution.  z is the vector
!> of nodal contact forces mu, w the final normal gaps.  For symmetric W this is
!> the KKT system of the convex QP  min 1/2 z'Wz + q'z  subject to z >= 0.
!>
!> The solvers work on the symmetrically scaled problem and report
!> scale-free measures (lcp_scaling); Lemke's method is in lcp_lemke, projected
!> Gauss-Seidel in lcp_pgs, the primal-dual active set method in lcp_newton.
!>
!> Why it exists: this module is the one door to the frictionless solvers
!> and their shared types, so a caller says `use lcp_solvers` whatever the
!> method; it holds no code of its own.  Each method is in a file of its own
!> because each is a job of its own (the tableau and its pivoting, the
!> sweeps and their monitor, the scaling and measures they share).
!>
!> Programming interface
!>   type(lcp_options_t)  tol (1e-10, on the scaled residual), maxit (0: default,
!>                        Lemke 10 n + 100 pivots, PGS min(1e5, max(1e4, 1e10/n^2))
!>                        sweeps), omega (1, PGS relaxation, 0 < omega < 2)
!>   type(lcp_report_t)   info, iterations, residual, complementarity, message
!>       info  0 solved; 1 no solution (Lemke ray termination, or a zero row of W
!>             with a negative q_i); 2 iteration limit; 3 PGS divergence or
!>             stagnation; 4 Lemke terminated but the residual exceeds tol (loss
!>             of accuracy); -k argument k invalid
!>   solve_lcp_lemke(W, q, z, opts, rep)   z intent(out)
!>   solve_lcp_pgs(W, q, z, opts, rep)     z intent(inout): initial guess, clipped to >= 0
!>   pgs_problem_t, run_pgs, pgs_set_row, pgs_limits, pgs_outcome
!>                                         the PGS driver (lcp_pgs) that the friction
!>                                         sweeps of friction_lcp share
!>   lcp_natural_residual(W, q, z)         the scaled natural residual (lcp_scaling)
!>   scale_lcp(W, q, d, Ws, qs)            the symmetric diagonal scaling
!>   scaling_vector(W, d)                  its d alone
!>   solve_lcp_lemke_scaled(M, q, d, z, opts, rep)
!>                                         Lemke on D M D, D q with a scaling d
!>                                         given by the caller and no row removed:
!>                                         for LCPs with zero diagonal entries or a
!>                                         non-symmetric M (frictional contact)
!> W need not be symmetric for Lemke and PGS to run (both use W's columns), but
!> the convergence of PGS and the meaning of ray termination assume W PSD.
!> No routine prints anything; every outcome is in the report.
module lcp_solvers
  use lcp_scaling, only: lcp_options_t, lcp_report_t, lcp_natural_residual, scale_lcp, scaling_vector, measure_solution, &
                         set_report, out_of_memory, max_diagonal, negative_diagonal, info_no_memory
  use lcp_lemke, only: solve_lcp_lemke, solve_lcp_lemke_scaled
  use lcp_pgs, only: solve_lcp_pgs, pgs_outcome, pgs_problem_t, run_pgs, pgs_set_row, pgs_limits
  implicit none
  private
  public :: lcp_options_t, lcp_report_t
  public :: solve_lcp_lemke, solve_lcp_pgs, lcp_natural_residual, scale_lcp, scaling_vector, measure_solution
  public :: solve_lcp_lemke_scaled, pgs_outcome, set_report, out_of_memory
  public :: pgs_problem_t, run_pgs, pgs_set_row, pgs_limits
  public :: max_diagonal, negative_diagonal, info_no_memory
end module lcp_solvers
