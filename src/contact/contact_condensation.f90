!> contact_condensation: the contact problem condensed onto the constraint rows
!> (the Delassus matrix) and the recovery of the displacement.
!>
!> With K u = f - B' mu (the KKT system of min 1/2 u'Ku - f'u, B u <= g) and
!> u0 = K^-1 f, the final gap is  g - B u = q + W mu  with
!>     W = B K^-1 B'      q = g - B u0
!> and (mu, q + W mu) solve LCP(W, q).  Only the contact dofs C enter B, so
!> W = B_C (K^-1)_CC B_C'.  The contact dofs are ordered last in the Cholesky
!> factorization, K = L L' with L = [L_rr 0; L_cr L_cc], hence
!> (K^-1)_CC = (L_cc L_cc')^-1 and
!>     X = L_cc^-1 B_C'  (dtrsm),   W = X' X  (dsyrk)
!> at the cost of a dense triangular solve, not of ncdof sparse solves.  K
!> does not couple two bodies, so L_cc has one diagonal block per body that
!> has contact dofs: the solve runs block by block (half the flops of the
!> whole block for two bodies of equal share), W = sum_b X_b' X_b.
!>
!> A block of nb dofs reached by mb rows costs nb^2 mb / 2 + mb^2 nb / 2
!> multiply-adds that way.  Where a row touches one dof of the block (a flat
!> slave side: nb = mb), its share is cheaper from the inverse,
!>     Z_b = (L_b L_b')^-1  (LAPACK dpotri, nb^3 / 3),   W_b = B_b Z_b B_b'
!> with B_b sparse: a third of the flops.  Each block takes the cheaper way
!> (inverse_pays; SOLVER condense= forces one); the answer is the same to
!> round-off.
!>
!> One solve in all.  With y = L^-1 P f (the forward half of u0 = K^-1 f),
!> the contact dofs of u0 are the end of the backward half,
!>     u0_C = L_cc'^-1 y_c,
!> which is all that q needs; and the contact forces -B' mu reach only the
!> trailing pivots, so the forward half of the recovery is
!>     L^-1 P (f - B' mu) = y - [0; X mu]
!> (X_b mu = L_b^-1 (B_b' mu) by one triangular solve for a block condensed
!> by its inverse) and one backward solve gives u.  The displacement costs one forward and
!> one backward solve, not two solves.
!>
!> Programming interface
!>   contact_equations(cs, eq, last)        free equations of the contact dofs, in
!>                                          the order to be factorized last
!>   type(condensed_t)                      what recover needs, per block of L_cc
!>   condense(cs, eq, factor, y, u0, w, q, cd, err [, method])
!>                                          W (nc, nc), q (nc), nc = nrow + ntan,
!>                                          u0 on the contact dofs from y, and X_b
!>                                          or L_b in cd for recover
!>   constraint_values(cs, u, v)            v = C u, C = [B; T] (the tangential
!>                                          rows T of friction pairs after B)
!>   contact_forces(cs, mu, fc)             fc = -B' mu on every dof (fc sized ndof)
!>   recover(eq, factor, y, cd, u0, mu, u, err)  u = K^-1 (f - C' mu) by one backward
!>                                          solve (y overwritten, cd's arrays released)
!>   condensed_report(cd)                   how each block was condensed, one line
!>   condensed_blocks(cd)                   the same as numbers: (3, blocks) dofs, rows,
!>                                          1 by its inverse / 0 by triangular solves
module contact_condensation
  use kinds, only: dp, i8
  use lapack_interfaces, only: dgemv, dpotri, dsyrk, dtrsm, dtrsv
  use strings, only: int_to_str
  use errors, only: error_t, set_out_of_memory, set_error
  use contact_set, only: contact_set_t
  use sparse_cholesky, only: factor_t, trailing_factor_block, trailing_block_end, solve_backward
  implicit none
  private
  public :: contact_equations, condense, contact_forces, recover, constraint_values, condensed_report, &
            condensed_blocks

  !> What condense keeps of one diagonal block of L_cc (the contact dofs of
  !> one body) for the recovery.
  type :: condensed_block_t
    integer :: s = 1, e = 0                  !< free contact dofs s..e (rows of L_cc)
    integer :: c1 = 1, c2 = 0                !< the constraint rows that reach them (none: c1 > c2)
    logical :: inverse = .false.             !< the block's share of W came from (L_b L_b')^-1
    real(dp), allocatable :: a(:,:)          !< inverse: L_b (nb, nb); else X_b = L_b^-1 C_b' (nb, c2-c1+1)
    integer, allocatable :: cptr(:), crow(:) !< inverse: C_b' by columns c1..c2 (CSC), rows 1..nb
    real(dp), allocatable :: cval(:)
  end type condensed_block_t

  !> The condensation's per-block factors, kept for the recovery.
  type, public :: condensed_t
    integer :: nfc = 0                       !< free contact dofs
    type(condensed_block_t), allocatable :: block(:)
  end type condensed_t

contains

  !> Free equations of the contact dofs (ascending dof order): the block
  !> ordered last in the factorization.
  subroutine contact_equations(cs, eq, last)
    type(contact_set_t), intent(in) :: cs
    integer, intent(in) :: eq(:)
    integer, allocatable, intent(out) :: last(:)
    integer :: k, n
    n = count(eq(cs%cdof) > 0)
    allocate(last(n))
    n = 0
    do k = 1, cs%ncdof
      if (eq(cs%cdof(k)) > 0) then
        n = n + 1
        last(n) = eq(cs%cdof(k))
      end if
    end do
  end subroutine contact_equations

  !> W = C_C (K^-1)_CC C_C' and q = g - C u0, C = [B; T] (T: tangential rows
  !> of friction pairs, g = 0 there; C = B without friction).
  !>   cs     (in)  constraint rows; factor (in) K = L L' with contact_equations last
  !>   eq     (in)  (ndof) free equation numbers
  !>   y      (in)  (nfree) the forward half L^-1 P f of u0's solve
  !>   u0     (inout) (ndof) on entry the prescribed values on the fixed dofs;
  !>                on exit also u0 = K^-1 f on the free contact dofs
  !>                (u0_C = L_cc'^-1 y_c; the other free dofs are not set)
  !>   w      (out) (nc, nc) symmetric positive semi-definite, nc = nrow + ntan
  !>   q      (out) (nc)
  !>   cd     (out) per block of L_cc, what recover needs (X_b, or L_b)
  !>   err    (out) allocated when the trailing block cannot be had
  !>   method (in, optional) 'auto' (default), 'solve' or 'inverse': how each
  !>          block's share of W is had (module header)
  subroutine condense(cs, eq, factor, y, u0, w, q, cd, err, method)
    type(contact_set_t), intent(in) :: cs
    integer, intent(in) :: eq(:)
    type(factor_t), intent(inout) :: factor
    real(dp), intent(in) :: y(:)
    real(dp), intent(inout) :: u0(:)
    real(dp), allocatable, intent(out) :: w(:,:), q(:)
    type(condensed_t), intent(out) :: cd
    type(error_t), allocatable, intent(out) :: err
    character(len=*), intent(in), optional :: method
    integer :: nc, nfc, r, k, i, j, s, e, nblock, b, nb, st
    integer, allocatable :: fcol(:), bend(:)
    real(dp), allocatable :: lcc(:,:), uc(:)
    character(len=:), allocatable :: how

    how = 'auto'
    if (present(method)) how = method
    nc = cs%nrow + cs%ntan
    ! column of each contact dof in the free block (0 when fixed)
    allocate(fcol(cs%ncdof))
    nfc = 0
    do k = 1, cs%ncdof
      if (eq(cs%cdof(k)) > 0) then
        nfc = nfc + 1
        fcol(k) = nfc
      else
        fcol(k) = 0
      end if
    end do
    cd%nfc = nfc
    allocate(w(nc, nc), source=0.0_dp, stat=st)
    if (st /= 0) then
      call set_out_of_memory(err, 'condensing the contact problem (W of ' // int_to_str(nc) // ' x ' // &
                             int_to_str(nc) // ')', 8_i8 * int(nc, i8) * int(nc, i8))
      return
    end if
    if (nfc == 0 .or. nc == 0) then
      allocate(cd%block(0))
      call gap_offsets()
      return
    end if
    ! the diagonal blocks of L_cc: bodies that K does not couple give L_cc a
    ! block per body
    allocate(bend(nfc))
    nblock = 0
    s = 1
    do while (s <= nfc)
      call trailing_block_end(factor, nfc, s, e, err)
      if (allocated(err)) then
        if (.not. err%no_memory) &
          err%message = 'cannot extract the contact block of the Cholesky factor: ' // err%message
        return
      end if
      nblock = nblock + 1
      bend(nblock) = e
      s = e + 1
    end do
    ! Each block is read out of the factor only when it is used (the whole
    ! L_cc is never held), and only the constraint rows that reach it enter
    ! its share of W
    allocate(cd%block(nblock))
    uc = y(size(y) - nfc + 1:)
    s = 1
    do b = 1, nblock
      e = bend(b)
      nb = e - s + 1
      call trailing_factor_block(factor, nfc, lcc, err, first=s, count=nb)
      if (allocated(err)) then
        if (.not. err%no_memory) &
          err%message = 'cannot extract the contact block of the Cholesky factor: ' // err%message
        return
      end if
      ! the end of the backward half of u0 = K^-1 f: u0_C = L_cc'^-1 y_c
      call dtrsm('L', 'L', 'T', 'N', nb, 1, 1.0_dp, lcc, nb, uc(s), nfc)
      associate(bk => cd%block(b))
        bk%s = s
        bk%e = e
        call block_columns(cs, fcol, bk)
        if (bk%c1 <= bk%c2) then
          bk%inverse = how == 'inverse' .or. &
                       (how == 'auto' .and. inverse_pays(nb, bk%c2 - bk%c1 + 1, size(bk%crow)))
          if (bk%inverse) then
            call inverse_share(lcc, bk, w, nc, err)
            if (allocated(err)) return
          else
            call solve_share(lcc, bk, w, nc)
          end if
        end if
      end associate
      if (allocated(lcc)) deallocate(lcc)
      s = e + 1
    end do
    do k = 1, cs%ncdof
      if (fcol(k) > 0) u0(cs%cdof(k)) = uc(fcol(k))
    end do
    call gap_offsets()
    do j = 1, nc                                    ! the shares fill the upper triangle
      do i = j + 1, nc
        w(i, j) = w(j, i)
      end do
    end do

  contains

    !> q = g - C u0 (fixed contact dofs carry their prescribed values; g = 0
    !> on tangential rows)
    subroutine gap_offsets()
      allocate(q(nc))
      do r = 1, nc
        q(r) = 0.0_dp
        if (r <= cs%nrow) q(r) = cs%g(r)
        do k = cs%bptr(r), cs%bptr(r + 1) - 1
          q(r) = q(r) - cs%bval(k) * u0(cs%cdof(cs%bcol(k)))
        end do
      end do
    end subroutine gap_offsets
  end subroutine condense

  !> The columns c1..c2 of C_C' (constraint rows) with an entry in the
  !> block's free contact dofs s..e, and those entries by columns (CSC, rows
  !> local to the block, repeated entries kept: every use sums them).
  subroutine block_columns(cs, fcol, bk)
    type(contact_set_t), intent(in) :: cs
    integer, intent(in) :: fcol(:)
    type(condensed_block_t), intent(inout) :: bk
    integer :: r, k, col, n
    bk%c1 = cs%nrow + cs%ntan + 1
    bk%c2 = 0
    n = 0
    do r = 1, cs%nrow + cs%ntan
      do k = cs%bptr(r), cs%bptr(r + 1) - 1
        col = fcol(cs%bcol(k))
        if (col < bk%s .or. col > bk%e) cycle
        n = n + 1
        bk%c1 = min(bk%c1, r)
        bk%c2 = r
      end do
    end do
    if (bk%c1 > bk%c2) return
    allocate(bk%cptr(bk%c2 - bk%c1 + 2), bk%crow(n), bk%cval(n))
    n = 0
    bk%cptr(1) = 1
    do r = bk%c1, bk%c2
      do k = cs%bptr(r), cs%bptr(r + 1) - 1
        col = fcol(cs%bcol(k))
        if (col < bk%s .or. col > bk%e) cycle
        n = n + 1
        bk%crow(n) = col - bk%s + 1
        bk%cval(n) = cs%bval(k)
      end do
      bk%cptr(r - bk%c1 + 2) = n + 1
    end do
  end subroutine block_columns

  !> Whether the block's share of W costs less from the inverse of L_b L_b'
  !> than by triangular solves, with nb dofs, mb constraint rows and nnz
  !> entries of C_b, in multiply-adds weighted by their measured speed:
  !>   solves   nb^2 mb / 2 (dtrsm) + mb^2 nb / 2 (dsyrk)
  !>   inverse  1.3 nb^3 / 3 (dpotri, 1.3: it ran at 30 Gflop/s where dtrsm
  !>            and dsyrk ran at 39-49) + 20 nnz (nb + mb / 2) (the sparse
  !>            products with C_b, at 1.7 Gflop/s)
  !> (two-body Signorini, 1000 to 5000 slave nodes, 2 threads).  A flat
  !> slave side (one dof per row, nnz = mb = nb) costs a third to a half by
  !> the inverse; a master side (some 44 entries per row) from about 4000
  !> dofs up.
  pure logical function inverse_pays(nb, mb, nnz)
    integer, intent(in) :: nb, mb, nnz
    real(dp) :: n, m
    n = real(nb, dp)
    m = real(mb, dp)
    inverse_pays = 1.3_dp * n**3 / 3 + 20 * real(nnz, dp) * (n + m / 2) < n**2 * m / 2 + m**2 * n / 2
  end function inverse_pays

  !> W(c1:c2, c1:c2) += X_b' X_b (upper), X_b = L_b^-1 C_b' by triangular
  !> solves; X_b is kept for the recovery.
  subroutine solve_share(lcc, bk, w, ldw)
    real(dp), intent(in) :: lcc(:,:)
    type(condensed_block_t), intent(inout) :: bk
    integer, intent(in) :: ldw
    real(dp), intent(inout) :: w(ldw, *)
    integer :: nb, mb, j, k
    nb = bk%e - bk%s + 1
    mb = bk%c2 - bk%c1 + 1
    allocate(bk%a(nb, mb), source=0.0_dp)
    do j = 1, mb
      do k = bk%cptr(j), bk%cptr(j + 1) - 1
        bk%a(bk%crow(k), j) = bk%a(bk%crow(k), j) + bk%cval(k)
      end do
    end do
    deallocate(bk%cptr, bk%crow, bk%cval)
    call dtrsm('L', 'L', 'N', 'N', nb, mb, 1.0_dp, lcc, nb, bk%a, nb)
    call dsyrk('U', 'T', mb, nb, 1.0_dp, bk%a, nb, 1.0_dp, w(bk%c1, bk%c1), ldw)
  end subroutine solve_share

  !> W(c1:c2, c1:c2) += C_b Z C_b' (upper), Z = (L_b L_b')^-1 by LAPACK
  !> dpotri; L_b (lcc, moved) and C_b are kept for the recovery.
  subroutine inverse_share(lcc, bk, w, ldw, err)
    real(dp), allocatable, intent(inout) :: lcc(:,:)
    type(condensed_block_t), intent(inout) :: bk
    integer, intent(in) :: ldw
    real(dp), intent(inout) :: w(ldw, *)
    type(error_t), allocatable, intent(out) :: err
    real(dp), allocatable :: z(:,:), t(:,:)
    integer :: nb, mb, info
    nb = bk%e - bk%s + 1
    mb = bk%c2 - bk%c1 + 1
    allocate(z, source=lcc, stat=info)
    if (info /= 0) then
      call set_out_of_memory(err, 'condensing the contact problem (the inverse of a contact block of ' // &
                             int_to_str(nb) // ' x ' // int_to_str(nb) // ')', 8_i8 * int(nb, i8) * int(nb, i8))
      return
    end if
    call dpotri('L', nb, z, nb, info)
    if (info /= 0) then
      call set_error(err, 'the contact block of the Cholesky factor is singular (LAPACK dpotri info ' // &
                     int_to_str(info) // ')')
      return
    end if
    call fill_upper(z)
    ! T = Z C_b' (nb, mb), then W += C_b T, both by the columns of C_b'
    allocate(t(nb, mb), stat=info)
    if (info /= 0) then
      call set_out_of_memory(err, 'condensing the contact problem (a block of ' // int_to_str(nb) // ' x ' // &
                             int_to_str(mb) // ')', 8_i8 * int(nb, i8) * int(mb, i8))
      return
    end if
    call sparse_product(nb, mb, size(bk%crow), bk%cptr, bk%crow, bk%cval, z, t)
    deallocate(z)
    call sparse_share(nb, mb, size(bk%crow), bk%cptr, bk%crow, bk%cval, t, ldw, w(bk%c1, bk%c1))
    call move_alloc(lcc, bk%a)
  end subroutine inverse_share

  !> T = Z C' for a dense Z (nb, nb) and C' (nb, mb) by columns (CSC).
  !> Neighbouring columns of C' (neighbouring slave nodes) use nearly the
  !> same columns of Z: T is made by tiles of 64 columns and 512 rows, so
  !> that the pieces of Z a tile reads stay in cache from column to column.
  subroutine sparse_product(nb, mb, nnz, cptr, crow, cval, z, t)
    integer, intent(in) :: nb, mb, nnz, cptr(mb + 1), crow(nnz)
    real(dp), intent(in) :: cval(nnz), z(nb, nb)
    real(dp), intent(out) :: t(nb, mb)
    integer, parameter :: tile_rows = 512, tile_cols = 64
    integer :: i0, i1, j0, j, k
    !$omp parallel do private(i0, i1, j, k) schedule(static)
    do j0 = 1, mb, tile_cols
      do i0 = 1, nb, tile_rows
        i1 = min(i0 + tile_rows - 1, nb)
        do j = j0, min(j0 + tile_cols - 1, mb)
          t(i0:i1, j) = 0.0_dp
          do k = cptr(j), cptr(j + 1) - 1
            t(i0:i1, j) = t(i0:i1, j) + cval(k) * z(i0:i1, crow(k))
          end do
        end do
      end do
    end do
    !$omp end parallel do
  end subroutine sparse_product

  !> W(i, j) += (C T)(i, j) for i <= j, C' (nb, mb) by columns (CSC), T (nb, mb);
  !> W from its first row and column, leading dimension ldw.
  subroutine sparse_share(nb, mb, nnz, cptr, crow, cval, t, ldw, w)
    integer, intent(in) :: nb, mb, nnz, cptr(mb + 1), crow(nnz), ldw
    real(dp), intent(in) :: cval(nnz), t(nb, mb)
    real(dp), intent(inout) :: w(ldw, *)
    integer :: i, j, k
    real(dp) :: acc
    !$omp parallel do private(i, k, acc) schedule(dynamic, 8)
    do j = 1, mb
      do i = 1, j
        acc = 0.0_dp
        do k = cptr(i), cptr(i + 1) - 1
          acc = acc + cval(k) * t(crow(k), j)
        end do
        w(i, j) = w(i, j) + acc
      end do
    end do
    !$omp end parallel do
  end subroutine sparse_share

  !> The upper triangle of a square matrix from its lower one, by tiles.
  subroutine fill_upper(a)
    real(dp), intent(inout) :: a(:,:)
    integer, parameter :: tile = 64
    integer :: n, i0, j0, i, j
    n = size(a, 1)
    !$omp parallel do private(i0, i, j) schedule(dynamic)
    do j0 = 1, n, tile
      do i0 = 1, j0, tile                           ! tile (i0, j0) above the diagonal
        do j = j0, min(j0 + tile - 1, n)
          do i = i0, min(i0 + tile - 1, j - 1)
            a(i, j) = a(j, i)
          end do
        end do
      end do
    end do
    !$omp end parallel do
  end subroutine fill_upper

  !> One line on how W was had, block by block (for the run's report).
  function condensed_report(cd) result(line)
    type(condensed_t), intent(in) :: cd
    character(len=:), allocatable :: line
    integer, allocatable :: blk(:,:)
    integer :: b
    line = ''
    blk = condensed_blocks(cd)
    do b = 1, size(blk, 2)
      if (len(line) > 0) line = line // ', '
      line = line // int_to_str(blk(1, b)) // ' dofs x ' // int_to_str(blk(2, b)) // ' rows '
      if (blk(3, b) == 1) then
        line = line // 'by its inverse (dpotri)'
      else
        line = line // 'by triangular solves (dtrsm)'
      end if
    end do
  end function condensed_report

  !> The blocks of L_cc that constraint rows reach, in order: blk(:, b) =
  !> [dofs, rows, 1 when its share of W came from its inverse, else 0].
  function condensed_blocks(cd) result(blk)
    type(condensed_t), intent(in) :: cd
    integer, allocatable :: blk(:,:)
    integer :: b, m
    m = 0
    if (allocated(cd%block)) m = count(cd%block%c1 <= cd%block%c2)
    allocate(blk(3, m))
    m = 0
    if (.not. allocated(cd%block)) return
    do b = 1, size(cd%block)
      associate(bk => cd%block(b))
        if (bk%c1 > bk%c2) cycle
        m = m + 1
        blk(:, m) = [bk%e - bk%s + 1, bk%c2 - bk%c1 + 1, merge(1, 0, bk%inverse)]
      end associate
    end do
  end function condensed_blocks

  !> v = C u: the values of every constraint row (B u, then T u) at u.
  !>   cs (in) rows; u (in) (ndof); v (out) (nrow + ntan)
  subroutine constraint_values(cs, u, v)
    type(contact_set_t), intent(in) :: cs
    real(dp), intent(in) :: u(:)
    real(dp), intent(out) :: v(:)
    integer :: r, k
    do r = 1, cs%nrow + cs%ntan
      v(r) = 0.0_dp
      do k = cs%bptr(r), cs%bptr(r + 1) - 1
        v(r) = v(r) + cs%bval(k) * u(cs%cdof(cs%bcol(k)))
      end do
    end do
  end subroutine constraint_values

  !> Nodal contact forces fc = -C' mu on all dofs (zero away from contact);
  !> mu holds the normal multipliers (nrow), followed by the tangential ones
  !> (ntan) when there is friction.
  subroutine contact_forces(cs, mu, fc)
    type(contact_set_t), intent(in) :: cs
    real(dp), intent(in) :: mu(:)
    real(dp), intent(inout) :: fc(:)
    integer :: r, k
    fc = 0.0_dp
    do r = 1, size(mu)
      do k = cs%bptr(r), cs%bptr(r + 1) - 1
        fc(cs%cdof(cs%bcol(k))) = fc(cs%cdof(cs%bcol(k))) - cs%bval(k) * mu(r)
      end do
    end do
  end subroutine contact_forces

  !> u = K^-1 (f - C' mu): the backward half of the solve, of y - [0; X mu]
  !> (y the forward half L^-1 P f, X = L_cc^-1 C_C' from condense: X_b mu,
  !> or L_b^-1 (C_b' mu) by one triangular solve for a block condensed by
  !> its inverse); u takes u0's prescribed values on the fixed dofs.
  !>   y  (inout) (nfree) overwritten;  cd (inout) from condense, its arrays
  !>   released before the solve
  !>   u0 (in) (ndof), only its fixed dofs read;  mu (in) (nc);  u (out) (ndof)
  !>   err (out) allocated when the solve fails (no valid factor, CHOLMOD's error)
  subroutine recover(eq, factor, y, cd, u0, mu, u, err)
    integer, intent(in) :: eq(:)
    type(factor_t), intent(inout) :: factor
    real(dp), intent(inout), contiguous :: y(:)
    type(condensed_t), intent(inout) :: cd
    real(dp), intent(in) :: u0(:), mu(:)
    real(dp), intent(out) :: u(:)
    type(error_t), allocatable, intent(out) :: err
    real(dp), allocatable :: du(:), t(:)
    integer :: i, nfree, b, nb, mb, o, j, k
    nfree = size(y)
    do b = 1, size(cd%block)
      associate(bk => cd%block(b))
        if (bk%c1 <= bk%c2 .and. size(mu) >= bk%c2) then
          nb = bk%e - bk%s + 1
          mb = bk%c2 - bk%c1 + 1
          o = nfree - cd%nfc + bk%s                      ! y's entry of the block's first dof
          if (bk%inverse) then
            allocate(t(nb), source=0.0_dp)
            do j = 1, mb
              do k = bk%cptr(j), bk%cptr(j + 1) - 1
                t(bk%crow(k)) = t(bk%crow(k)) + bk%cval(k) * mu(bk%c1 + j - 1)
              end do
            end do
            call dtrsv('L', 'N', 'N', nb, bk%a, nb, t, 1)
            y(o:o + nb - 1) = y(o:o + nb - 1) - t
            deallocate(t)
          else
            call dgemv('N', nb, mb, -1.0_dp, bk%a, nb, mu(bk%c1:bk%c2), 1, 1.0_dp, y(o:o + nb - 1), 1)
          end if
        end if
        if (allocated(bk%a)) deallocate(bk%a)          ! before the solve: a lower peak
      end associate
    end do
    allocate(du(nfree))
    call solve_backward(factor, y, du, err)
    u = u0
    if (allocated(err)) return
    do i = 1, size(eq)
      if (eq(i) > 0) u(i) = du(eq(i))
    end do
  end subroutine recover

end module contact_condensation
