!> Unit tests of sparse_matrix and sparse_cholesky (CHOLMOD through the C shim).
!>
!> Matrices are built here: the 5-point Laplacian of an m-by-m grid of
!> interior nodes (Dirichlet nodes eliminated: SPD), the same graph with
!> Neumann rows (singular, constant null vector), and a P1 plane-strain
!> elasticity stiffness on a triangulated square (left edge fixed, or free).
!> References are independent of the code under test: residuals scaled in
!> the LAPACK manner, ||A x - b|| / (||A|| ||x|| + ||b||), the block of A^-1
!> obtained by solving with unit vectors, dense products from the triplets,
!> and the null vectors of the singular matrices.
program test_sparse_cholesky
  use kinds, only: dp, i8
  use errors, only: error_t, error_numerical
  use testing, only: check, check_close, check_small, finish_tests, tol_round
  use sparse_matrix, only: csc_t, csc_nnz, csc_symv, csc_from_triplets, csc_check
  use omp_lib, only: omp_get_max_threads, omp_set_num_threads
  use cholmod_binding, only: c2d_metis_per_thread, cholmod_ok, cholmod_not_posdef, cholmod_out_of_memory, &
                             cholmod_too_large, c2d_chol_no_handle, c2d_chol_no_factor, c2d_chol_not_super_ll, &
                             c2d_chol_block_moved, c2d_chol_bad_argument, c2d_order_metis, c2d_order_amd, &
                             c2d_name_ordering, c2d_name_status, c2d_solve_whole, c2d_solve_forward, c2d_solve_backward
  use sparse_cholesky_parts, only: status_name
  use sparse_cholesky, only: factor_t, factorize, solve, solve_vector, solve_block, trailing_factor_block, &
                             solve_forward, solve_backward, trailing_block_end, &
                             free_factor, factor_nnz, factor_flops, factor_memory, factor_ordering, &
                             analyze_pattern, factorize_values
  implicit none

  call test_triplets()
  call test_laplacian_solves()
  call test_trailing_block_laplacian()
  call test_trailing_block_all()
  call test_trailing_block_per_body()
  call test_parts()
  call test_metis_side_by_side()
  call test_metis_split()
  call test_elasticity()
  call test_singular()
  call test_bad_arguments()
  call test_fill_with_last()
  call test_node_groups()
  call test_singular_equation()
  call test_refactor_after_not_posdef()
  call test_status_names()
  call finish_tests()

contains

  ! ---------------------------------------------------------------- matrices

  !> 5-point Laplacian of an m-by-m grid, node (ix, iy) -> dof ix + m (iy-1).
  !> dirichlet: diagonal 4 (boundary neighbours eliminated, SPD); otherwise
  !> the diagonal is the node degree (pure Neumann, singular).
  subroutine grid_laplacian(m, dirichlet, A)
    integer, intent(in) :: m
    logical, intent(in) :: dirichlet
    type(csc_t), intent(out) :: A
    integer, allocatable :: ti(:), tj(:)
    real(dp), allocatable :: tv(:)
    integer :: ix, iy, k, nt, deg

    allocate(ti(3 * m * m), tj(3 * m * m), tv(3 * m * m))
    nt = 0
    do iy = 1, m
      do ix = 1, m
        k = ix + m * (iy - 1)
        deg = 0
        if (ix > 1) deg = deg + 1
        if (ix < m) deg = deg + 1
        if (iy > 1) deg = deg + 1
        if (iy < m) deg = deg + 1
        nt = nt + 1
        ti(nt) = k
        tj(nt) = k
        tv(nt) = merge(4.0_dp, real(deg, dp), dirichlet)
        if (ix < m) then                 ! east neighbour, given in the lower triangle
          nt = nt + 1
          ti(nt) = k + 1
          tj(nt) = k
          tv(nt) = -1.0_dp
        end if
        if (iy < m) then                 ! north neighbour, upper triangle
          nt = nt + 1
          ti(nt) = k
          tj(nt) = k + m
          tv(nt) = -1.0_dp
        end if
      end do
    end do
    call csc_from_triplets(m * m, ti(1:nt), tj(1:nt), tv(1:nt), A)
  end subroutine grid_laplacian

  !> P1 plane-strain elasticity (E = 1, nu = 0.3) on the unit square cut into
  !> nx-by-ny squares, each split into two triangles.  Node (ix, iy),
  !> ix = 0..nx, iy = 0..ny; dofs 2 node - 1 (x), 2 node (y).  fix_left
  !> removes the dofs of the nodes at x = 0; dof_of(2, nnode) gives the dof
  !> number of each nodal component (0 when removed).
  subroutine elasticity(nx, ny, fix_left, A, dof_of)
    integer, intent(in) :: nx, ny
    logical, intent(in) :: fix_left
    type(csc_t), intent(out) :: A
    integer, allocatable, intent(out) :: dof_of(:,:)
    real(dp), parameter :: young = 1.0_dp, nu = 0.3_dp
    integer, parameter :: node_of(6) = [1, 1, 2, 2, 3, 3], comp_of(6) = [1, 2, 1, 2, 1, 2]
    real(dp) :: d(3, 3), xy(2, 3), b(3, 6), ke(6, 6), area, lam, mu
    integer :: tri(3, 2), conn(3), ix, iy, e, a1, a2, c1, gi, gj, nt, ndof, node
    integer, allocatable :: ti(:), tj(:)
    real(dp), allocatable :: tv(:)

    lam = young * nu / ((1.0_dp + nu) * (1.0_dp - 2.0_dp * nu))
    mu = young / (2.0_dp * (1.0_dp + nu))
    d = 0.0_dp
    d(1, 1) = lam + 2.0_dp * mu
    d(2, 2) = lam + 2.0_dp * mu
    d(1, 2) = lam
    d(2, 1) = lam
    d(3, 3) = mu

    allocate(dof_of(2, (nx + 1) * (ny + 1)))
    ndof = 0
    do iy = 0, ny
      do ix = 0, nx
        node = 1 + ix + (nx + 1) * iy
        if (fix_left .and. ix == 0) then
          dof_of(:, node) = 0
        else
          dof_of(1, node) = ndof + 1
          dof_of(2, node) = ndof + 2
          ndof = ndof + 2
        end if
      end do
    end do

    allocate(ti(72 * nx * ny), tj(72 * nx * ny), tv(72 * nx * ny))
    nt = 0
    do iy = 0, ny - 1
      do ix = 0, nx - 1
        node = 1 + ix + (nx + 1) * iy
        tri(:, 1) = [node, node + 1, node + nx + 2]
        tri(:, 2) = [node, node + nx + 2, node + nx + 1]
        do e = 1, 2
          conn = tri(:, e)
          do a1 = 1, 3
            xy(1, a1) = real(mod(conn(a1) - 1, nx + 1), dp) / nx
            xy(2, a1) = real((conn(a1) - 1) / (nx + 1), dp) / ny
          end do
          area = 0.5_dp * ((xy(1, 2) - xy(1, 1)) * (xy(2, 3) - xy(2, 1)) - (xy(1, 3) - xy(1, 1)) * (xy(2, 2) - xy(2, 1)))
          b = 0.0_dp
          do a1 = 1, 3
            ! grad of the P1 shape function a1: (y_b - y_c, x_c - x_b) / (2 area)
            a2 = mod(a1, 3) + 1
            c1 = mod(a1 + 1, 3) + 1
            b(1, 2 * a1 - 1) = (xy(2, a2) - xy(2, c1)) / (2.0_dp * area)
            b(2, 2 * a1) = (xy(1, c1) - xy(1, a2)) / (2.0_dp * area)
            b(3, 2 * a1 - 1) = b(2, 2 * a1)
            b(3, 2 * a1) = b(1, 2 * a1 - 1)
          end do
          ke = area * matmul(transpose(b), matmul(d, b))     ! K_e = |T| B' D B
          do a1 = 1, 6
            gi = dof_of(comp_of(a1), conn(node_of(a1)))
            do a2 = 1, 6
              gj = dof_of(comp_of(a2), conn(node_of(a2)))
              if (gi == 0 .or. gj == 0 .or. gi > gj) cycle   ! upper triangle once
              nt = nt + 1
              ti(nt) = gi
              tj(nt) = gj
              tv(nt) = ke(a1, a2)
            end do
          end do
        end do
      end do
    end do
    call csc_from_triplets(ndof, ti(1:nt), tj(1:nt), tv(1:nt), A)
  end subroutine elasticity

  !> ||A||_inf (= ||A||_1) of the symmetric A: max_i sum_j |a_ij|.
  function norm_inf(A) result(s)
    type(csc_t), intent(in) :: A
    real(dp) :: s
    type(csc_t) :: absa
    real(dp), allocatable :: ones(:), rowsum(:)
    absa = A
    absa%val = abs(absa%val)
    allocate(ones(A%n), rowsum(A%n))
    ones = 1.0_dp
    call csc_symv(absa, ones, rowsum)
    s = maxval(rowsum)
  end function norm_inf

  !> The worst scaled residual of a 3-column block solve (b, ones and
  !> cos(w k), solved in one call).
  function block_residual(f, A, b, w) result(worst)
    type(factor_t), intent(in) :: f
    type(csc_t), intent(in) :: A
    real(dp), intent(in) :: b(:), w
    real(dp) :: worst
    real(dp), allocatable :: bb(:,:), xx(:,:)
    type(error_t), allocatable :: err
    integer :: j, k
    allocate(bb(A%n, 3), xx(A%n, 3))
    bb(:, 1) = b
    bb(:, 2) = 1.0_dp
    bb(:, 3) = [(cos(w * k), k = 1, A%n)]
    call solve(f, bb, xx, err)
    worst = 0.0_dp
    do j = 1, 3
      worst = max(worst, residual_ratio(A, xx(:, j), bb(:, j)))
    end do
  end function block_residual

  !> Scale-free residual ||A x - b||_inf / (||A||_inf ||x||_inf + ||b||_inf).
  function residual_ratio(A, x, b) result(r)
    type(csc_t), intent(in) :: A
    real(dp), intent(in) :: x(:), b(:)
    real(dp) :: r
    real(dp), allocatable :: ax(:)
    allocate(ax(A%n))
    call csc_symv(A, x, ax)
    r = maxval(abs(ax - b)) / (norm_inf(A) * maxval(abs(x)) + maxval(abs(b)))
  end function residual_ratio

  !> A right-hand side with O(1) entries of both signs.
  function smooth_rhs(n, shift) result(b)
    integer, intent(in) :: n, shift
    real(dp) :: b(n)
    integer :: i
    do i = 1, n
      b(i) = sin(0.37_dp * (i + shift)) + 0.5_dp * cos(0.011_dp * i * (shift + 1))
    end do
  end function smooth_rhs

  !> Inverse of S = Lcc Lcc' from the triangular factor: X = Lcc^-T Lcc^-1.
  function inverse_from_factor(lcc) result(x)
    real(dp), intent(in) :: lcc(:,:)
    real(dp) :: x(size(lcc, 1), size(lcc, 1))
    real(dp) :: y(size(lcc, 1), size(lcc, 1))
    integer :: m, i, j
    m = size(lcc, 1)
    ! Y = Lcc^-1 (forward substitution on the columns of I)
    y = 0.0_dp
    do j = 1, m
      y(j, j) = 1.0_dp
      do i = 1, m
        y(i, j) = (y(i, j) - dot_product(lcc(i, 1:i - 1), y(1:i - 1, j))) / lcc(i, i)
      end do
    end do
    ! X = Lcc^-T Y (back substitution)
    do j = 1, m
      do i = m, 1, -1
        x(i, j) = (y(i, j) - dot_product(lcc(i + 1:m, i), x(i + 1:m, j))) / lcc(i, i)
      end do
    end do
  end function inverse_from_factor

  !> Block (A^-1)(idx, idx) by solving A Z = E with the unit vectors e_idx.
  function inverse_block(f, n, idx) result(z)
    type(factor_t), intent(in) :: f
    integer, intent(in) :: n, idx(:)
    real(dp) :: z(size(idx), size(idx))
    real(dp), allocatable :: e(:,:), zz(:,:)
    type(error_t), allocatable :: err
    integer :: k
    allocate(e(n, size(idx)), zz(n, size(idx)))
    e = 0.0_dp
    do k = 1, size(idx)
      e(idx(k), k) = 1.0_dp
    end do
    call solve_block(f, e, zz, err)
    z = zz(idx, :)
  end function inverse_block

  !> .true. when text contains piece.
  logical function contains_text(text, piece)
    character(len=*), intent(in) :: text, piece
    contains_text = index(text, piece) > 0
  end function contains_text

  function itoa(i) result(s)
    integer, intent(in) :: i
    character(len=:), allocatable :: s
    character(len=16) :: buf
    write(buf, '(i0)') i
    s = trim(buf)
  end function itoa

  ! ------------------------------------------------------------------- tests

  !> csc_from_triplets and csc_symv against a dense matrix built from the
  !> same triplets (duplicates and both triangles).
  subroutine test_triplets()
    integer, parameter :: n = 7, nt = 20
    integer :: ti(nt), tj(nt), k, j, p
    real(dp) :: tv(nt), dense(n, n), x(n), y(n)
    type(csc_t) :: A
    type(error_t), allocatable :: err
    logical :: sorted, upper(n, n)

    do k = 1, nt
      ti(k) = 1 + mod(3 * k, n)
      tj(k) = 1 + mod(5 * k + k / 4, n)
      tv(k) = real(k, dp) - 7.5_dp
    end do
    ti(nt) = ti(1)                         ! an exact duplicate of triplet 1
    tj(nt) = tj(1)
    dense = 0.0_dp
    do k = 1, nt
      dense(ti(k), tj(k)) = dense(ti(k), tj(k)) + tv(k)
      if (ti(k) /= tj(k)) dense(tj(k), ti(k)) = dense(tj(k), ti(k)) + tv(k)
    end do
    call csc_from_triplets(n, ti, tj, tv, A)
    call csc_check(A, err)
    call check(.not. allocated(err), 'csc_from_triplets gives a valid upper CSC matrix')
    sorted = .true.
    do j = 1, n
      do p = A%colptr(j) + 1, A%colptr(j + 1) - 1
        if (A%rowind(p) <= A%rowind(p - 1)) sorted = .false.
      end do
    end do
    call check(sorted, 'csc_from_triplets: rows strictly ascending in each column')
    upper = .false.
    do k = 1, nt
      upper(min(ti(k), tj(k)), max(ti(k), tj(k))) = .true.
    end do
    call check(csc_nnz(A) == count(upper), 'csc_nnz = number of distinct upper positions of the triplets')
    do k = 1, n
      x(k) = 1.0_dp / k - 0.3_dp
    end do
    call csc_symv(A, x, y)
    call check_small(maxval(abs(y - matmul(dense, x))) / maxval(abs(matmul(abs(dense), abs(x)))), tol_round(4), &
                     'csc_symv equals the dense product of the triplets')
  end subroutine test_triplets

  !> Single and 7-column solves on the 60x60 Dirichlet Laplacian; `last` gives
  !> the same solution.
  subroutine test_laplacian_solves()
    integer, parameter :: m = 60, nrhs = 7
    type(csc_t) :: A
    type(factor_t) :: f, g
    type(error_t), allocatable :: err
    real(dp), allocatable :: b(:), x(:), bb(:,:), xx(:,:), xl(:)
    integer, allocatable :: last(:)
    real(dp) :: worst
    integer :: n, k

    call grid_laplacian(m, .true., A)
    n = A%n
    call factorize(f, A, err)
    call check(.not. allocated(err), 'factorize 60x60 Dirichlet Laplacian')
    if (allocated(err)) then
      print '(a)', '  ' // err%message
      return
    end if
    call check(factor_ordering(f) == 'metis', 'default ordering is metis')
    call check(factor_nnz(f) >= int(n, i8) .and. factor_nnz(f) <= int(n, i8) * (n + 1) / 2, &
               'n <= nnz(L) <= n(n+1)/2')
    call check(factor_flops(f) > 0.0_dp .and. factor_memory(f) > 0_i8, 'flop count and peak memory positive')
    call check(f%time_analyze >= 0.0_dp .and. f%time_factorize >= 0.0_dp, 'timings non-negative')

    allocate(b(n), x(n))
    b = smooth_rhs(n, 0)
    call solve(f, b, x, err)
    call check_small(residual_ratio(A, x, b), tol_round(16), 'single RHS: scaled residual < 16 eps')

    allocate(bb(n, nrhs), xx(n, nrhs))
    do k = 1, nrhs
      bb(:, k) = smooth_rhs(n, 13 * k)
    end do
    bb(:, 1) = b
    call solve(f, bb, xx, err)
    worst = 0.0_dp
    do k = 1, nrhs
      worst = max(worst, residual_ratio(A, xx(:, k), bb(:, k)))
    end do
    call check_small(worst, tol_round(16), '7-column block RHS: scaled residual < 16 eps for every column')
    call check_small(maxval(abs(xx(:, 1) - x)) / maxval(abs(x)), tol_round(32), &
                     'block solve column 1 equals the single solve')

    ! the top row of the grid ordered last, in reverse order
    allocate(last(m))
    last = [(n - k + 1, k = 1, m)]
    call factorize(g, A, err, last)
    call check(.not. allocated(err), 'factorize with the top row last')
    if (allocated(err)) then
      print '(a)', '  ' // err%message
      return
    end if
    call check(factor_ordering(g) == 'metis+last', 'ordering with last is metis+last')
    allocate(xl(n))
    call solve_vector(g, b, xl, err)
    call check_small(residual_ratio(A, xl, b), tol_round(16), 'last: scaled residual < 16 eps')
    ! two orderings solve to cond(A) eps apart (measured 11 eps)
    call check_small(maxval(abs(xl - x)) / maxval(abs(x)), tol_round(128), 'last: same solution as the default ordering')
    call free_factor(f)
    call free_factor(g)
  end subroutine test_laplacian_solves

  !> (L_cc L_cc')^-1 against the block of A^-1 from unit-vector solves, for a
  !> scattered, unsorted `last` on the 60x60 Laplacian.
  subroutine test_trailing_block_laplacian()
    integer, parameter :: m = 60, nlast = 40
    type(csc_t) :: A
    type(factor_t) :: f
    type(error_t), allocatable :: err
    real(dp), allocatable :: lcc(:,:)
    real(dp) :: z(nlast, nlast), zinv(nlast, nlast)
    integer :: last(nlast), k, n, i
    logical :: upper_zero

    call grid_laplacian(m, .true., A)
    n = A%n
    ! dofs spread over the grid (a diagonal line and a column), unsorted
    do k = 1, 20
      last(k) = 3 * k + m * (3 * k - 1)          ! (3k, 3k)
    end do
    do k = 1, 20
      last(20 + k) = 45 + m * (2 * k + 9)        ! (45, 2k+10)
    end do
    last(1:20) = last(20:1:-1)
    call factorize(f, A, err, last)
    call check(.not. allocated(err), 'factorize with 40 scattered dofs last')
    if (allocated(err)) then
      print '(a)', '  ' // err%message
      return
    end if
    call trailing_factor_block(f, nlast, lcc, err)
    call check(size(lcc, 1) == nlast .and. size(lcc, 2) == nlast, 'trailing block has shape (nlast, nlast)')
    upper_zero = .true.
    do k = 2, nlast
      do i = 1, k - 1
        if (lcc(i, k) /= 0.0_dp) upper_zero = .false.
      end do
    end do
    call check(upper_zero .and. all([(lcc(k, k) > 0.0_dp, k = 1, nlast)]), &
               'trailing block lower triangular with a positive diagonal')
    z = inverse_block(f, n, last)
    zinv = inverse_from_factor(lcc)
    call check_small(maxval(abs(zinv - z)) / maxval(abs(z)), tol_round(16), &
                     'Laplacian: (Lcc Lcc'')^-1 = (A^-1)(last,last)')
  end subroutine test_trailing_block_laplacian

  !> Two uncoupled bodies (two grid Laplacians side by side in one matrix),
  !> each with some dofs last: L_cc has one diagonal block per body, found by
  !> trailing_block_end (checked against the zeros of the whole L_cc, read
  !> independently), and each block read alone equals that part of L_cc.
  subroutine test_trailing_block_per_body()
    integer, parameter :: m = 20, n1 = m * m, k1 = 12, k2 = 9
    type(csc_t) :: A1, A
    type(factor_t) :: f
    type(error_t), allocatable :: err
    real(dp), allocatable :: lcc(:,:), blk(:,:)
    integer :: last(k1 + k2), k, e1, e2, nz1
    logical :: zero_off

    call grid_laplacian(m, .true., A1)
    ! A = diag(A1, A1): the second copy's rows shifted by n1
    nz1 = A1%colptr(n1 + 1) - 1
    A%n = 2 * n1
    A%colptr = [A1%colptr(1:n1), A1%colptr + nz1]
    A%rowind = [A1%rowind(1:nz1), A1%rowind(1:nz1) + n1]
    A%val = [A1%val(1:nz1), A1%val(1:nz1)]
    last(1:k1) = [(1 + m * (m - 1) + (k - 1), k = 1, k1)]           ! top row of body 1
    last(k1 + 1:) = [(n1 + 3 + m * (k - 1), k = 1, k2)]             ! a column of body 2
    call factorize(f, A, err, last)
    call check(.not. allocated(err), 'two bodies: factorize with dofs of each last')
    if (allocated(err)) print '(a)', '  ' // err%message
    if (allocated(err)) return
    call check(f%nparts == 2, 'two bodies: A is factorized as two parts')
    call trailing_factor_block(f, k1 + k2, lcc, err)
    zero_off = all(lcc(k1 + 1:, 1:k1) == 0.0_dp)
    call check(zero_off .and. any(lcc(2:k1, 1) /= 0.0_dp), 'two bodies: L_cc is block diagonal (read whole)')
    call trailing_block_end(f, k1 + k2, 1, e1, err)
    call trailing_block_end(f, k1 + k2, k1 + 1, e2, err)
    call check(e1 == k1 .and. e2 == k1 + k2, 'two bodies: trailing_block_end gives the blocks 1..12 and 13..21')
    call trailing_factor_block(f, k1 + k2, blk, err, first=1, count=k1)
    call check(all(blk == lcc(1:k1, 1:k1)), 'two bodies: block 1 read alone = L_cc(1:12, 1:12)')
    call trailing_factor_block(f, k1 + k2, blk, err, first=k1 + 1, count=k2)
    call check(all(blk == lcc(k1 + 1:, k1 + 1:)), 'two bodies: block 2 read alone = L_cc(13:21, 13:21)')
    call trailing_factor_block(f, k1 + k2, blk, err, first=k1, count=k2 + 2)
    call check(allocated(err), 'two bodies: a range past the end of L_cc is an error')
  end subroutine test_trailing_block_per_body

  !> A = diag(A1, A2) with no entry between the blocks.
  subroutine block_diagonal(A1, A2, A)
    type(csc_t), intent(in) :: A1, A2
    type(csc_t), intent(out) :: A
    integer :: nz1, nz2
    nz1 = A1%colptr(A1%n + 1) - 1
    nz2 = A2%colptr(A2%n + 1) - 1
    A%n = A1%n + A2%n
    A%colptr = [A1%colptr(1:A1%n), A2%colptr + nz1]
    A%rowind = [A1%rowind(1:nz1), A2%rowind(1:nz2) + A1%n]
    A%val = [A1%val(1:nz1), A2%val(1:nz2)]
  end subroutine block_diagonal

  !> Bodies that A does not couple are factorized as parts, side by side: an
  !> elasticity block and a Laplacian block of other sizes.  Checked against
  !> the residual, against the same matrix factorized whole (`last` given in
  !> an order that keeps it one part), the halves of the solve against
  !> substitution on L_cc, a range of L_cc across the parts, and the dof a
  !> singular second block is reported at.
  subroutine test_parts()
    type(csc_t) :: A1, A2, A
    type(factor_t) :: f, g
    type(error_t), allocatable :: err
    integer, allocatable :: dof_of(:,:), last(:), back(:)
    real(dp), allocatable :: b(:), x(:), xw(:), lcc(:,:), blk(:,:)
    integer, parameter :: m2 = 105
    integer :: n, n1, k, j

    ! both blocks above side_by_side_min (10000 dofs): the parts run on the threads
    call elasticity(80, 70, .true., A1, dof_of)
    call grid_laplacian(m2, .true., A2)
    call block_diagonal(A1, A2, A)
    n = A%n
    n1 = A1%n
    allocate(b(n), x(n), xw(n))
    b = [(sin(0.37_dp * k) + 0.1_dp, k = 1, n)]

    call factorize(f, A, err)
    call check(.not. allocated(err) .and. f%nparts == 2, 'parts: diag(elasticity, Laplacian) in two parts')
    if (allocated(err)) return
    call check(f%side_by_side == min(2, omp_get_max_threads()), 'parts: factorized side by side on the threads')
    call solve(f, b, x, err)
    call check_small(residual_ratio(A, x, b), tol_round(16), 'parts: scaled residual < 16 eps')
    call check_small(block_residual(f, A, b, 1.3_dp), tol_round(16), &
                     'parts: 3-column block, scaled residual < 16 eps for each')

    ! dofs of both bodies last, ascending: two parts; in the other order: one
    last = [(n1 - 6 + j, j = 1, 6), (n1 + m2 * (m2 - 1) + k, k = 1, 17)]
    call factorize(f, A, err, last)
    call check(.not. allocated(err) .and. f%nparts == 2, 'parts: with `last` ascending, two parts')
    if (allocated(err)) return
    back = [last(7:), last(1:6)]
    call factorize(g, A, err, back)
    call check(.not. allocated(err) .and. g%nparts == 1, 'parts: `last` visiting body 2 first keeps A whole')
    if (allocated(err)) return
    call solve(f, b, x, err)
    call solve(g, b, xw, err)
    ! two factorizations of A solve to cond(A) eps apart: measured 850 eps here
    call check_small(maxval(abs(x - xw)) / maxval(abs(x)), tol_round(4096), 'parts: the same solution as A whole')
    call trailing_factor_block(f, size(last), lcc, err)
    call check_halves(f, n, b, x, last, lcc)
    call trailing_factor_block(f, size(last), blk, err, first=5, count=4)
    call check(all(blk == lcc(5:8, 5:8)) .and. all(blk(3:, 1:2) == 0.0_dp), &
               'parts: a range of L_cc across the two parts = that part of L_cc, zero between')

    ! a singular second block (pure Neumann Laplacian), its corner dof last:
    ! that is the dependent pivot, the last one of the whole factor
    call grid_laplacian(m2, .false., A2)
    call block_diagonal(A1, A2, A)
    call factorize(f, A, err, [n1 + 1])
    call check(allocated(err), 'parts: a singular second block is reported')
    if (allocated(err)) then
      print '(a)', '  ' // err%message
      call check(contains_text(err%message, 'at equation ' // itoa(n1 + 1) // ' (column ' // itoa(n) // ' '), &
                 'parts: the error names equation ' // itoa(n1 + 1) // ' at column ' // itoa(n))
    end if
  end subroutine test_parts

  !> METIS orders two parts side by side as it orders them on one thread: the
  !> same nnz(L) and flop count on every run, with the node groups (METIS on
  !> the node graph) and without (CHOLMOD's own METIS call).  METIS draws its
  !> random numbers per thread; from one sequence for the process, the two
  !> orderings interleaved their draws and nnz(L) changed from run to run.
  subroutine test_metis_side_by_side()
    type(csc_t) :: A1, A2, A
    type(factor_t) :: f
    type(error_t), allocatable :: err
    integer, allocatable :: dof_of(:,:), group(:)
    integer(i8) :: nnz1(2), nnz
    real(dp) :: flops1(2)
    integer :: threads, k, run, grouped, differ
    character(len=*), parameter :: how(2) = ['node groups   ', 'no node groups']

    call check(c2d_metis_per_thread() == 1, 'METIS side by side: its random numbers come from a sequence per thread')
    call elasticity(80, 70, .true., A1, dof_of)
    call grid_laplacian(105, .true., A2)
    call block_diagonal(A1, A2, A)
    group = [((k + 1) / 2, k = 1, A1%n), (A1%n / 2 + k, k = 1, A2%n)]
    threads = omp_get_max_threads()

    call omp_set_num_threads(1)
    do grouped = 1, 2
      call order_metis(f, A, group, grouped == 1, err)
      if (allocated(err)) exit
      nnz1(grouped) = factor_nnz(f)
      flops1(grouped) = factor_flops(f)
    end do
    call omp_set_num_threads(threads)
    if (allocated(err)) then
      call check(.false., 'METIS side by side: one thread: ' // err%message)
      return
    end if

    do grouped = 1, 2
      differ = 0
      do run = 1, 6
        call order_metis(f, A, group, grouped == 1, err)
        if (allocated(err)) exit
        nnz = factor_nnz(f)
        if (nnz /= nnz1(grouped) .or. factor_flops(f) /= flops1(grouped)) differ = differ + 1
      end do
      call check(.not. allocated(err) .and. f%side_by_side == min(2, threads), &
                 'METIS side by side (' // trim(how(grouped)) // '): two parts on ' // itoa(min(2, threads)) // ' threads')
      call check(differ == 0, 'METIS side by side (' // trim(how(grouped)) // '): nnz(L) and flops of 6 runs = one thread''s (' &
                 // itoa(differ) // ' differ)')
    end do

  end subroutine test_metis_side_by_side

  !> A METIS ordering of 20,000 node groups or more is split at its first
  !> level, the two halves ordered as OpenMP tasks: the same nnz(L) whether
  !> another thread of the team takes a half (called from a team of two) or
  !> not (no team), the fill within 5% of CHOLMOD's own METIS on the dof
  !> graph, and a solve to round-off.
  subroutine test_metis_split()
    type(csc_t) :: A
    type(factor_t) :: f
    type(error_t), allocatable :: err
    integer, allocatable :: dof_of(:,:), group(:)
    real(dp), allocatable :: b(:), x(:)
    integer(i8) :: nnz1, nnz_dof
    integer :: k, run, differ

    call elasticity(150, 140, .true., A, dof_of)     ! 150 x 141 = 21,150 free nodes
    group = [((k + 1) / 2, k = 1, A%n)]
    call order_metis(f, A, group, .true., err)
    if (allocated(err)) then
      call check(.false., 'METIS split: ' // err%message)
      return
    end if
    nnz1 = factor_nnz(f)
    allocate(b(A%n), x(A%n))
    b = [(sin(0.11_dp * k), k = 1, A%n)]
    call solve(f, b, x, err)
    call check_small(residual_ratio(A, x, b), tol_round(16), 'METIS split: 42,300 dofs, scaled residual < 16 eps')
    differ = 0
    do run = 1, 3
      !$omp parallel num_threads(2) default(shared)
      !$omp single
      call order_metis(f, A, group, .true., err)
      !$omp end single
      !$omp end parallel
      if (allocated(err)) exit
      if (factor_nnz(f) /= nnz1) differ = differ + 1
    end do
    call check(.not. allocated(err) .and. differ == 0, &
               'METIS split: the halves taken by a team of two give the nnz(L) of one thread (' // itoa(differ) // ' of 3 differ)')
    call order_metis(f, A, group, .false., err)
    if (allocated(err)) return
    nnz_dof = factor_nnz(f)
    call check(real(nnz1, dp) <= 1.05_dp * real(nnz_dof, dp), 'METIS split: nnz(L) ' // itoa(int(nnz1)) // &
               ' within 5% of CHOLMOD''s METIS on the dof graph (' // itoa(int(nnz_dof)) // ')')
  end subroutine test_metis_split

  !> METIS ordering and factorization of A, on the node graph or not.
  subroutine order_metis(f, A, group, by_node, err)
    type(factor_t), intent(inout) :: f
    type(csc_t), intent(in) :: A
    integer, intent(in) :: group(:)
    logical, intent(in) :: by_node
    type(error_t), allocatable, intent(out) :: err
    if (by_node) then
      call analyze_pattern(f, A%n, A%colptr, A%rowind, err, group=group, method='metis')
    else
      call analyze_pattern(f, A%n, A%colptr, A%rowind, err, method='metis')
    end if
    if (.not. allocated(err)) call factorize_values(f, A, err)
  end subroutine order_metis

  !> All dofs last (no METIS part): L_cc is the whole factor of A(last, last),
  !> so L_cc L_cc' equals the dense permuted matrix.
  subroutine test_trailing_block_all()
    integer, parameter :: m = 9
    type(csc_t) :: A
    type(factor_t) :: f
    type(error_t), allocatable :: err
    real(dp), allocatable :: lcc(:,:), dense(:,:), e(:)
    integer, allocatable :: last(:)
    integer :: n, k

    call grid_laplacian(m, .true., A)
    n = A%n
    allocate(dense(n, n), e(n))
    do k = 1, n                                   ! dense A, column by column
      e = 0.0_dp
      e(k) = 1.0_dp
      call csc_symv(A, e, dense(:, k))
    end do
    last = [(1 + mod(7 * k, n), k = 0, n - 1)]    ! a permutation of 1..n (gcd(7, 81) = 1)
    call factorize(f, A, err, last)
    call check(.not. allocated(err), 'factorize with every dof in last')
    if (allocated(err)) return
    call trailing_factor_block(f, n, lcc, err)
    call check_small(maxval(abs(matmul(lcc, transpose(lcc)) - dense(last, last))) / maxval(abs(dense)), &
                     tol_round(4), 'every dof last: Lcc Lcc'' = A(last, last)')
  end subroutine test_trailing_block_all

  !> P1 elasticity, left edge fixed: solve residual, and the trailing block
  !> for the top edge (both components, interleaved), as a contact interface.
  subroutine test_elasticity()
    integer, parameter :: nx = 24, ny = 16
    type(csc_t) :: A
    type(factor_t) :: f
    type(error_t), allocatable :: err
    integer, allocatable :: dof_of(:,:), last(:)
    real(dp), allocatable :: b(:), x(:), lcc(:,:), z(:,:), zinv(:,:)
    integer :: ix, node, k

    call elasticity(nx, ny, .true., A, dof_of)
    allocate(last(2 * nx))
    k = 0
    do ix = nx, 1, -1                               ! top edge without the fixed corner
      node = 1 + ix + (nx + 1) * ny
      last(k + 1:k + 2) = dof_of(:, node)
      k = k + 2
    end do
    call factorize(f, A, err, last)
    call check(.not. allocated(err), 'factorize P1 elasticity with the top edge last')
    if (allocated(err)) then
      print '(a)', '  ' // err%message
      return
    end if
    allocate(b(A%n), x(A%n))
    b = smooth_rhs(A%n, 5)
    call solve(f, b, x, err)
    call check_small(residual_ratio(A, x, b), tol_round(16), 'elasticity: scaled residual < 16 eps')
    call trailing_factor_block(f, size(last), lcc, err)
    allocate(z(size(last), size(last)), zinv(size(last), size(last)))
    z = inverse_block(f, A%n, last)
    zinv = inverse_from_factor(lcc)
    call check_small(maxval(abs(zinv - z)) / maxval(abs(z)), tol_round(32), &
                     'elasticity: (Lcc Lcc'')^-1 = (A^-1)(top edge, top edge)')
    call check_halves(f, A%n, b, x, last, lcc)
  end subroutine test_elasticity

  !> The two halves of a solve, as contact_condensation uses them: backward
  !> after forward is the solve; x(last) = L_cc'^-1 y_c; and a vector that
  !> is zero off `last` goes forward to [0; L_cc^-1 v] (solved here by plain
  !> substitution on the dense L_cc, independent of CHOLMOD's solve).
  subroutine check_halves(f, n, b, x, last, lcc)
    type(factor_t), intent(in) :: f
    integer, intent(in) :: n, last(:)
    real(dp), intent(in) :: b(:), x(:), lcc(:,:)
    real(dp), allocatable :: y(:), x2(:), v(:), yv(:), expect(:)
    type(error_t), allocatable :: err
    integer :: nl, i
    nl = size(last)
    allocate(y(n), x2(n), v(n), yv(n))
    call solve_forward(f, b, y, err)
    call solve_backward(f, y, x2, err)
    call check_small(maxval(abs(x2 - x)) / maxval(abs(x)), tol_round(16), 'elasticity: backward(forward(b)) = A^-1 b')
    ! L_cc' z = y_c by back substitution
    expect = y(n - nl + 1:)
    do i = nl, 1, -1
      expect(i) = (expect(i) - dot_product(lcc(i + 1:, i), expect(i + 1:))) / lcc(i, i)
    end do
    call check_small(maxval(abs(expect - x(last))) / maxval(abs(x)), tol_round(32), &
                     'elasticity: x(last) = Lcc''^-1 y(trailing), y the forward half')
    v = 0.0_dp
    v(last) = smooth_rhs(nl, 3)
    call solve_forward(f, v, yv, err)
    ! L_cc z = v(last) by forward substitution
    expect = v(last)
    do i = 1, nl
      expect(i) = (expect(i) - dot_product(lcc(i, :i - 1), expect(:i - 1))) / lcc(i, i)
    end do
    call check(all(yv(:n - nl) == 0.0_dp), 'elasticity: forward half of a vector on `last` is zero off the block')
    call check_small(maxval(abs(yv(n - nl + 1:) - expect)) / maxval(abs(expect)), tol_round(16), &
                     'elasticity: forward half of [0; v] = [0; Lcc^-1 v]')
  end subroutine check_halves

  !> A free body (no dof held: its rigid-body modes make K singular) is
  !> reported, with the equation a field of the error: err%equation is a dof
  !> of A, the one the message names, and err%singular set (the caller's
  !> test, not the text); METIS and AMD on the node graph.
  subroutine test_singular_equation()
    type(csc_t) :: A
    type(factor_t) :: f
    type(error_t), allocatable :: err
    integer, allocatable :: dof_of(:,:), group(:)
    integer :: k, im
    character(len=5), parameter :: methods(2) = ['metis', 'amd  ']
    call elasticity(30, 20, .false., A, dof_of)
    group = [((k + 1) / 2, k = 1, A%n)]
    do im = 1, 2
      call analyze_pattern(f, A%n, A%colptr, A%rowind, err, group=group, method=trim(methods(im)))
      if (.not. allocated(err)) call factorize_values(f, A, err)
      call check(allocated(err), trim(methods(im)) // ': a free body (singular) is reported')
      if (.not. allocated(err)) cycle
      call check(err%equation >= 1 .and. err%equation <= A%n .and. &
                 contains_text(err%message, 'singular or not positive definite at equation ' // itoa(err%equation) // ' '), &
                 trim(methods(im)) // ': err%equation (' // itoa(err%equation) // ') is the equation the message names')
      call check(err%singular .and. .not. err%no_memory, trim(methods(im)) // ': err%singular set, err%no_memory not')
    end do
  end subroutine test_singular_equation

  !> Singular matrices are reported with the dof of the dependent column.
  subroutine test_singular()
    integer, parameter :: m = 30
    type(csc_t) :: A, B
    type(factor_t) :: f
    type(error_t), allocatable :: err
    integer, allocatable :: dof_of(:,:)
    real(dp), allocatable :: x(:), rhs(:)
    integer :: n, dead, j, p, q

    ! (1) a zero row and column: the pivot of dof `dead` is exactly zero
    call grid_laplacian(m, .true., A)
    n = A%n
    dead = 417
    B%n = n
    allocate(B%colptr(n + 1), B%rowind(csc_nnz(A)), B%val(csc_nnz(A)))
    q = 0
    do j = 1, n
      B%colptr(j) = q + 1
      do p = A%colptr(j), A%colptr(j + 1) - 1
        if (j == dead .or. A%rowind(p) == dead) cycle
        q = q + 1
        B%rowind(q) = A%rowind(p)
        B%val(q) = A%val(p)
      end do
    end do
    B%colptr(n + 1) = q + 1
    call factorize(f, B, err)
    call check(allocated(err), 'zero column: factorize reports an error')
    if (allocated(err)) then
      print '(a)', '  ' // err%message
      call check(contains_text(err%message, 'at equation ' // itoa(dead) // ' (column '), &
                 'zero column: the error names equation ' // itoa(dead))
      call check(err%category == error_numerical, 'zero column: a numerical failure')
    end if
    call check(.not. f%ready, 'zero column: factor not ready')
    allocate(x(n), rhs(n))
    rhs = 1.0_dp
    call solve(f, rhs, x, err)
    call check(allocated(err), 'solve after a failed factorization returns an error')

    ! same with `last` containing the dead dof in the middle
    call factorize(f, B, err, [5, dead, 900])
    call check(allocated(err), 'zero column with last: error')
    if (allocated(err)) then
      call check(contains_text(err%message, 'at equation ' // itoa(dead) // ' (column ' // itoa(n - 1) // ' '), &
                 'zero column with last: equation ' // itoa(dead) // ' at column n-1')
    end if

    ! (2) pure Neumann Laplacian: null vector = constants; with `last` = one
    ! corner dof, every earlier leading block is nonsingular, so the last
    ! pivot (that dof) is the dependent one
    call grid_laplacian(m, .false., A)
    call factorize(f, A, err)
    call check(allocated(err), 'Neumann Laplacian: factorize reports an error')
    if (allocated(err)) print '(a)', '  ' // err%message
    call factorize(f, A, err, [m])
    call check(allocated(err), 'Neumann Laplacian with last=[m]: error')
    if (allocated(err)) then
      print '(a)', '  ' // err%message
      call check(contains_text(err%message, 'at equation ' // itoa(m) // ' (column ' // itoa(A%n) // ' '), &
                 'Neumann Laplacian with last=[m]: equation m at the last column')
    end if

    ! (3) a pair of dofs held by a spring of stiffness 2^-50 only: in the order
    ! given, L = [2 0; 1 2^-25], computed exactly, so CHOLMOD succeeds with a
    ! pivot 2^-50 that only the pivot-ratio check can catch
    call grid_laplacian(m, .true., A)
    n = A%n
    B%n = n + 2
    deallocate(B%colptr, B%rowind, B%val)
    allocate(B%colptr(n + 3), B%rowind(csc_nnz(A) + 3), B%val(csc_nnz(A) + 3))
    B%colptr(1:n + 1) = A%colptr
    B%rowind(1:csc_nnz(A)) = A%rowind
    B%val(1:csc_nnz(A)) = A%val
    q = csc_nnz(A)
    B%rowind(q + 1:q + 3) = [n + 1, n + 1, n + 2]
    B%val(q + 1:q + 3) = [4.0_dp, 2.0_dp, 1.0_dp + 2.0_dp**(-50)]
    B%colptr(n + 2:n + 3) = [q + 2, q + 4]
    call factorize(f, B, err, [n + 1, n + 2])
    call check(allocated(err), 'tiny positive pivot: factorize reports an error')
    if (allocated(err)) then
      print '(a)', '  ' // err%message
      call check(contains_text(err%message, 'at equation ' // itoa(n + 2) // ' (column ' // itoa(n + 2) // ' '), &
                 'tiny positive pivot: equation n+2 at the last column')
    end if
    call check_close(f%min_pivot_ratio, 2.0_dp**(-50) / (1.0_dp + 2.0_dp**(-50)), tol_round(16), &
                     'tiny positive pivot: ratio L(k,k)^2 / A(k,k) = 2^-50 / (1 + 2^-50)')
    call factorize(f, B, err)
    call check(allocated(err), 'tiny positive pivot, default ordering: error')

    ! (4) a free elastic body: three rigid-body modes
    call elasticity(12, 8, .false., A, dof_of)
    call factorize(f, A, err)
    call check(allocated(err), 'unconstrained elasticity: factorize reports an error')
    if (allocated(err)) print '(a)', '  ' // err%message
  end subroutine test_singular

  !> Argument errors come back through err, not as crashes.
  subroutine test_bad_arguments()
    type(csc_t) :: A
    type(factor_t) :: f
    type(error_t), allocatable :: err
    real(dp), allocatable :: lcc(:,:)

    call grid_laplacian(10, .true., A)
    call factorize(f, A, err, [3, 7, 3])
    call check(allocated(err), 'repeated dof in last: error')
    call factorize(f, A, err, [0, 7])
    call check(allocated(err), 'dof out of range in last: error')
    call factorize(f, A, err)
    call check(.not. allocated(err) .and. f%ready, 'refactorize the same factor_t: ok')
    call trailing_factor_block(f, 2, lcc, err)
    call check(allocated(err), 'trailing block of a factor without last: error')
    call factorize(f, A, err, [1, 2, 3])
    call trailing_factor_block(f, 2, lcc, err)
    call check(allocated(err), 'trailing block with the wrong nlast: error')
    call free_factor(f)
    call check(.not. f%ready, 'free_factor: factor no longer ready')
    call free_factor(f)
    call check(.not. f%ready, 'free_factor twice: the factor stays freed')
    A%rowind(2) = A%n
    call factorize(f, A, err)
    call check(allocated(err), 'malformed matrix (row below the diagonal): error')
  end subroutine test_bad_arguments

  !> nnz(L) for the 100x100 grid with the top row last against the default
  !> METIS ordering (informational).
  subroutine test_fill_with_last()
    integer, parameter :: m = 100
    type(csc_t) :: A
    type(factor_t) :: f, g
    type(error_t), allocatable :: err
    integer :: k

    call grid_laplacian(m, .true., A)
    call factorize(f, A, err)
    if (allocated(err)) then
      call check(.false., 'factorize 100x100: ' // err%message)
      return
    end if
    call factorize(g, A, err, [(m * (m - 1) + k, k = 1, m)])
    if (allocated(err)) then
      call check(.false., 'factorize 100x100 with the top row last: ' // err%message)
      return
    end if
    print '(a, i0, a, es10.3, a, f6.3, a)', 'INFO 100x100 grid, metis:          nnz(L) = ', factor_nnz(f), &
          ', flops = ', factor_flops(f), ', factor ', f%time_factorize, ' s'
    print '(a, i0, a, es10.3, a, f6.3, a)', 'INFO 100x100 grid, top row last:   nnz(L) = ', factor_nnz(g), &
          ', flops = ', factor_flops(g), ', factor ', g%time_factorize, ' s'
    print '(a, f7.3)', 'INFO nnz(L) ratio last/metis = ', real(factor_nnz(g), dp) / real(factor_nnz(f), dp)
    print '(a, i0, a, i0)', 'INFO peak memory (bytes): metis ', factor_memory(f), ', last ', factor_memory(g)
  end subroutine test_fill_with_last

  !> Newton's iterates: values that are not positive definite, then
  !> definite ones with the same pattern, factorized on the one analysis (no
  !> analyze_pattern between them): the first fails as singular, naming its
  !> equation, the second solves A x = b to round-off.
  subroutine test_refactor_after_not_posdef()
    type(csc_t) :: A, B
    type(factor_t) :: f
    type(error_t), allocatable :: err
    integer, allocatable :: dof_of(:,:)
    real(dp), allocatable :: x(:), rhs(:)
    integer :: p
    call elasticity(12, 8, .true., A, dof_of)
    B = A
    do p = B%colptr(5), B%colptr(6) - 1                 ! column 5's diagonal made negative
      if (B%rowind(p) == 5) B%val(p) = -B%val(p)
    end do
    call analyze_pattern(f, A%n, A%colptr, A%rowind, err)
    call check(.not. allocated(err), 'refactorization: analyze_pattern')
    if (allocated(err)) return
    call factorize_values(f, B, err)
    call check(allocated(err), 'refactorization: values not positive definite fail')
    if (.not. allocated(err)) return
    call check(err%singular .and. err%equation > 0, 'refactorization: the failure is singular, with its equation')
    deallocate(err)
    call factorize_values(f, A, err)
    call check(.not. allocated(err), 'refactorization: definite values on the same analysis factorize')
    if (allocated(err)) return
    allocate(x(A%n))
    rhs = smooth_rhs(A%n, 2)
    call solve(f, rhs, x, err)
    call check_small(residual_ratio(A, x, rhs), tol_round(16), 'refactorization: scaled residual < 16 eps')
  end subroutine test_refactor_after_not_posdef

  !> The graph of dof groups (the mesh nodes) ordered by METIS and by AMD, in
  !> two halves (analyze_pattern, factorize_values), without and with a block
  !> last: the same solutions and trailing block as the checks above, a fill
  !> close to that of METIS on the dof graph, the ordering named, the dof
  !> graph ordered by AMD too, and a bad group or method rejected.
  subroutine test_node_groups()
    integer, parameter :: nx = 30, ny = 20
    character(len=5), parameter :: methods(2) = ['metis', 'amd  ']
    type(csc_t) :: A
    type(factor_t) :: f, g, h
    type(error_t), allocatable :: err
    integer, allocatable :: dof_of(:,:), last(:), group(:)
    real(dp), allocatable :: b(:), x(:), lcc(:,:), z(:,:), zinv(:,:)
    character(len=:), allocatable :: m
    integer :: node, c, ix, k, im

    call elasticity(nx, ny, .true., A, dof_of)
    allocate(group(A%n))
    group = 0
    do node = 1, size(dof_of, 2)
      do c = 1, 2
        if (dof_of(c, node) > 0) group(dof_of(c, node)) = node
      end do
    end do
    k = 0
    do node = 1, size(dof_of, 2)                        ! compact: 1..(nodes with a free dof)
      if (any(dof_of(:, node) > 0)) then
        k = k + 1
        where (group == node) group = -k
      end if
    end do
    group = -group
    call check(all(group >= 1 .and. group <= A%n), 'node groups: every dof in 1..n')
    allocate(last(2 * nx))
    k = 0
    do ix = nx, 1, -1                                   ! the top edge last, as a contact interface
      last(k + 1:k + 2) = dof_of(:, 1 + ix + (nx + 1) * ny)
      k = k + 2
    end do
    allocate(b(A%n), x(A%n))
    b = smooth_rhs(A%n, 3)
    call factorize(g, A, err)
    if (allocated(err)) return
    z = inverse_block(g, A%n, last)

    do im = 1, size(methods)
      m = trim(methods(im))
      call analyze_pattern(f, A%n, A%colptr, A%rowind, err, group=group, method=m)
      call check(.not. allocated(err), m // ': analyze_pattern with node groups')
      if (allocated(err)) return
      call factorize_values(f, A, err)
      call check(.not. allocated(err), m // ': factorize_values after the grouped analysis')
      if (allocated(err)) return
      call check(factor_ordering(f) == m // '(nodes)', m // ': ordering reported as ' // m // '(nodes): ' // &
                 factor_ordering(f))
      call solve(f, b, x, err)
      call check_small(residual_ratio(A, x, b), tol_round(16), m // ', grouped ordering: scaled residual < 16 eps')
      call check(abs(real(factor_nnz(f), dp) / real(factor_nnz(g), dp) - 1.0_dp) < 0.3_dp, &
                 m // ', grouped ordering: nnz(L) within 30% of METIS on the dof graph')

      call analyze_pattern(h, A%n, A%colptr, A%rowind, err, last=last, group=group, method=m)
      call check(.not. allocated(err), m // ': analyze_pattern with node groups and a block last')
      if (allocated(err)) return
      call factorize_values(h, A, err)
      if (allocated(err)) return
      call check(factor_ordering(h) == m // '(nodes)+last', m // ': ordering reported as ' // m // '(nodes)+last')
      call solve(h, b, x, err)
      call check_small(residual_ratio(A, x, b), tol_round(16), m // ', grouped, block last: scaled residual < 16 eps')
      call trailing_factor_block(h, size(last), lcc, err)
      zinv = inverse_from_factor(lcc)
      ! the inverse of a factor block against A^-1 from a solve: cond(A) eps (measured 97 eps)
      call check_small(maxval(abs(zinv - z)) / maxval(abs(z)), tol_round(1024), &
                       m // ', grouped: (Lcc Lcc'')^-1 = (A^-1)(top edge, top edge)')
    end do

    ! AMD on the dof graph (no groups), without and with the block last
    call analyze_pattern(f, A%n, A%colptr, A%rowind, err, method='amd')
    if (.not. allocated(err)) call factorize_values(f, A, err)
    call check(.not. allocated(err), 'amd on the dof graph: factorized')
    if (allocated(err)) return
    call check(factor_ordering(f) == 'amd', 'amd on the dof graph: reported as amd: ' // factor_ordering(f))
    call solve(f, b, x, err)
    call check_small(residual_ratio(A, x, b), tol_round(16), 'amd on the dof graph: scaled residual < 16 eps')
    call analyze_pattern(h, A%n, A%colptr, A%rowind, err, last=last, method='amd')
    if (.not. allocated(err)) call factorize_values(h, A, err)
    call check(.not. allocated(err), 'amd+last on the dof graph: factorized')
    if (allocated(err)) return
    call check(factor_ordering(h) == 'amd+last', 'amd+last: reported as amd+last: ' // factor_ordering(h))
    call trailing_factor_block(h, size(last), lcc, err)
    zinv = inverse_from_factor(lcc)
    ! as above: cond(A) eps (measured 133 eps)
    call check_small(maxval(abs(zinv - z)) / maxval(abs(z)), tol_round(2048), &
                     'amd+last: (Lcc Lcc'')^-1 = (A^-1)(top edge, top edge)')

    call analyze_pattern(f, A%n, A%colptr, A%rowind, err, group=group, method='nesdis')
    call check(allocated(err), 'an unknown ordering method is rejected')
    group(1) = A%n + 1
    call analyze_pattern(f, A%n, A%colptr, A%rowind, err, group=group)
    call check(allocated(err), 'a group out of 1..n is rejected')
  end subroutine test_node_groups

  !> The status codes as the binding reads them from the C layer: each is
  !> named as the C macro of its value (the C side's table, built from
  !> cholmod.h and cholmod_factor.h by the preprocessor, so a value read
  !> wrongly is named wrongly), they follow CHOLMOD's convention (0 success,
  !> a warning > 0, a failure < 0; the C layer's own <= -100) and no two are
  !> equal; the selectors of a call are distinct within each kind.  A code
  !> that is none of them is named as unknown.
  subroutine test_status_names()
    integer :: codes(9), i
    call check(status_name(cholmod_ok) == 'CHOLMOD_OK', 'status name: CHOLMOD_OK')
    call check(status_name(cholmod_not_posdef) == 'CHOLMOD_NOT_POSDEF', 'status name: CHOLMOD_NOT_POSDEF')
    call check(status_name(cholmod_out_of_memory) == 'CHOLMOD_OUT_OF_MEMORY', 'status name: CHOLMOD_OUT_OF_MEMORY')
    call check(status_name(cholmod_too_large) == 'CHOLMOD_TOO_LARGE', 'status name: CHOLMOD_TOO_LARGE')
    call check(status_name(c2d_chol_no_handle) == 'C2D_CHOL_NO_HANDLE', 'status name: C2D_CHOL_NO_HANDLE')
    call check(status_name(c2d_chol_no_factor) == 'C2D_CHOL_NO_FACTOR', 'status name: C2D_CHOL_NO_FACTOR')
    call check(status_name(c2d_chol_not_super_ll) == 'C2D_CHOL_NOT_SUPER_LL', 'status name: C2D_CHOL_NOT_SUPER_LL')
    call check(status_name(c2d_chol_block_moved) == 'C2D_CHOL_BLOCK_MOVED', 'status name: C2D_CHOL_BLOCK_MOVED')
    call check(status_name(c2d_chol_bad_argument) == 'C2D_CHOL_BAD_ARGUMENT', 'status name: C2D_CHOL_BAD_ARGUMENT')
    call check(status_name(-999) == 'unknown status', 'status name: an unknown code')

    call check(cholmod_ok == 0 .and. cholmod_not_posdef > 0 .and. cholmod_out_of_memory < 0 .and. &
               cholmod_too_large < 0, 'status codes: CHOLMOD''s signs (0 success, warning > 0, failure < 0)')
    codes = [cholmod_ok, cholmod_not_posdef, cholmod_out_of_memory, cholmod_too_large, c2d_chol_no_handle, &
             c2d_chol_no_factor, c2d_chol_not_super_ll, c2d_chol_block_moved, c2d_chol_bad_argument]
    call check(all(codes(5:) <= -100), 'status codes: the C layer''s are <= -100')
    call check(all([(count(codes == codes(i)) == 1, i = 1, size(codes))]), 'status codes: no two equal')
    call check(c2d_order_metis /= c2d_order_amd .and. c2d_name_ordering /= c2d_name_status .and. &
               c2d_solve_whole /= c2d_solve_forward .and. c2d_solve_forward /= c2d_solve_backward .and. &
               c2d_solve_whole /= c2d_solve_backward, 'selectors: distinct within each kind')
  end subroutine test_status_names

end program test_sparse_cholesky
