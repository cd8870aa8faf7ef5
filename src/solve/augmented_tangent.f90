!> augmented_tangent: the contact rows that hold a Newton iterate, added to
!> the tangent it factorizes (doc/theory.md, "Finite strain: hyperelastic
!> bodies", the contact linearization).
!>
!> Why.  A body held by contact alone, or whose section can turn or slide
!> only against its contacts (an O-ring's section between a cover and a
!> groove), has modes that its own tangent K barely resists: the section's
!> turn, and in axisymmetry its shift along the axis and its turn about the
!> ring's circle.  Under the squeeze's compressive stress the initial-stress
!> part of K makes such a mode's curvature negative while the contacts hold
!> it: the equilibrium is stable, K alone is not positive definite, and a
!> Cholesky factor of K does not exist.  The rows that hold the iterate,
!>     K~ = K + sum_{i in A} rho_i c_i' c_i,   r~ = r + sum_{i in A} rho_i c_i' h_i,
!> with h_i = c_i du the row's target, the gap a closed normal row closes,
!> make K~ positive definite on the modes the rows hold (Finsler's lemma: K~
!> is definite for rho large enough when K is definite on the rows' kernel,
!> which a stable equilibrium is).  The contact problem on K~ has the same
!> solution as on K whenever its rows in A stay closed: there c_i du = h_i
!> and the added terms vanish (an augmented Lagrangian).  The caller marks
!> normal rows only (newton_step's holding_rows): the turn and the axial
!> shift are held by the normal rows, and a sticking tangential row may
!> reach its cone within the iterate.  A row of A that the contact problem
!> opens only changes the iterate's direction; the residual, and so the
!> answer, are K's.
!>
!> rho_i = the mean of K's diagonal over the row's free dofs of bodies /
!> |c_i|^2 over them: the row as stiff as the body at its nodes, so that
!> K~'s conditioning stays K's.  A RIGID's free dofs on the row (one that its
!> FORCE moves) get the row's terms but no say in rho: a rotation's entries
!> have another unit, and their diagonal is only the soft dofs' share.
!>
!> Programming interface
!>   cover_rows(cs, eq, k, grown)   K's pattern grown to hold every row's couplings
!>                                  (grown = .true. when it had to be rebuilt)
!>   cover_dofs(dofs, eq, k, grown) K's pattern grown to couple the given dofs (a RIGID's)
!>   augment_rows(cs, active, h, eq, dubar, nbody, k, rhs)
!>                                  K~ and r~ for the rows marked active
module augmented_tangent
  use kinds, only: dp
  use contact_set, only: contact_set_t
  use sparse_matrix, only: csc_t, csc_from_triplets
  use body, only: find_row
  implicit none
  private
  public :: cover_rows, cover_dofs, augment_rows

contains

  !> Grow K's pattern, when it lacks them, by the couplings c_i' c_i of every
  !> row (normal and tangential) between free dofs: a row couples slave nodes
  !> that share no element (the modified multiplier's three nodes) and, body
  !> against body, slave and master nodes.  The values are lost (K is
  !> assembled after this), the pattern keeps every entry it had.
  !>   cs    (in)    the iterate's contact rows
  !>   eq    (in)    (ndof) free equation numbers
  !>   k     (inout) K's pattern
  !>   grown (out)   .true. when the pattern was rebuilt (its analysis is stale)
  subroutine cover_rows(cs, eq, k, grown)
    type(contact_set_t), intent(in) :: cs
    integer, intent(in) :: eq(:)
    type(csc_t), intent(inout) :: k
    logical, intent(out) :: grown
    integer, allocatable :: rows(:), cols(:)
    type(csc_t) :: wider
    integer :: pass, nmiss, nold, j, p
    nold = k%colptr(k%n + 1) - 1
    ! pass 1 counts the missing couplings, pass 2 lists them after K's own
    ! entries (a coupling two rows share is listed twice: the triplets sum)
    nmiss = 0
    do pass = 1, 2
      if (pass == 2) then
        if (nmiss == 0) exit
        allocate(rows(nold + nmiss), cols(nold + nmiss))
        do j = 1, k%n
          rows(k%colptr(j):k%colptr(j + 1) - 1) = k%rowind(k%colptr(j):k%colptr(j + 1) - 1)
          cols(k%colptr(j):k%colptr(j + 1) - 1) = j
        end do
        nmiss = 0
      end if
      call missing(pass == 2)
    end do
    grown = nmiss > 0
    if (.not. grown) return
    call csc_from_triplets(k%n, rows, cols, [(0.0_dp, p = 1, nold + nmiss)], wider)
    k = wider
  contains
    !> Count (and, when keep, list after position nold) the couplings of
    !> the rows between free dofs a <= b that K's pattern lacks.
    subroutine missing(keep)
      logical, intent(in) :: keep
      integer :: i, p1, p2, a, b, pos
      do i = 1, cs%nrow + cs%ntan
        do p1 = cs%bptr(i), cs%bptr(i + 1) - 1
          a = eq(cs%cdof(cs%bcol(p1)))
          if (a == 0) cycle
          do p2 = cs%bptr(i), cs%bptr(i + 1) - 1
            b = eq(cs%cdof(cs%bcol(p2)))
            if (b < a) cycle                           ! K's upper triangle (b = 0 is fixed)
            if (k%colptr(b + 1) > k%colptr(b)) then
              pos = find_row(k, a, b)
              if (k%rowind(pos) == a) cycle
            end if
            nmiss = nmiss + 1
            if (keep) then
              rows(nold + nmiss) = a
              cols(nold + nmiss) = b
            end if
          end do
        end do
      end do
    end subroutine missing
  end subroutine cover_rows

  !> Grow K's pattern, when it lacks them, by the couplings between the
  !> given dofs that are free (a RIGID's three: no element couples them, and
  !> the soft dofs' stiffness needs their diagonal).
  !>   dofs  (in)    the dofs
  !>   eq    (in)    (ndof) free equation numbers
  !>   k     (inout) K's pattern
  !>   grown (out)   .true. when the pattern was rebuilt
  subroutine cover_dofs(dofs, eq, k, grown)
    integer, intent(in) :: dofs(:), eq(:)
    type(csc_t), intent(inout) :: k
    logical, intent(out) :: grown
    integer, allocatable :: rows(:), cols(:)
    type(csc_t) :: wider
    integer :: i, j, a, b, nold, p, pos
    nold = k%colptr(k%n + 1) - 1
    allocate(rows(nold), cols(nold))
    do j = 1, k%n
      rows(k%colptr(j):k%colptr(j + 1) - 1) = k%rowind(k%colptr(j):k%colptr(j + 1) - 1)
      cols(k%colptr(j):k%colptr(j + 1) - 1) = j
    end do
    grown = .false.
    do i = 1, size(dofs)
      a = eq(dofs(i))
      if (a == 0) cycle
      do j = 1, size(dofs)
        b = eq(dofs(j))
        if (b < a) cycle                               ! K's upper triangle (b = 0 is fixed)
        if (k%colptr(b + 1) > k%colptr(b)) then
          pos = find_row(k, a, b)
          if (k%rowind(pos) == a) cycle
        end if
        rows = [rows, a]
        cols = [cols, b]
        grown = .true.
      end do
    end do
    if (.not. grown) return
    call csc_from_triplets(k%n, rows, cols, [(0.0_dp, p = 1, size(rows))], wider)
    k = wider
  end subroutine cover_dofs

  !> K~ = K + sum rho_i c_i,f' c_i,f and r~ = r + sum rho_i c_i,f' (h_i - c_i,d dubar_d)
  !> over the rows marked active (module header); K's pattern holds the rows'
  !> couplings (cover_rows).
  !>   cs     (in)    the iterate's rows, normal then tangential
  !>   active (in)    (nrow + ntan) the rows that hold the iterate
  !>   h      (in)    (nrow + ntan) each active row's target c_i du
  !>   eq     (in)    (ndof) free equation numbers
  !>   dubar  (in)    (ndof) the fixed dofs' increments
  !>   nbody  (in)    the bodies' dofs are 1..nbody (the RIGIDs' follow)
  !>   k      (inout) K's values, K~'s on exit
  !>   rhs    (inout) (nfree) r, r~ on exit
  subroutine augment_rows(cs, active, h, eq, dubar, nbody, k, rhs)
    type(contact_set_t), intent(in) :: cs
    logical, intent(in) :: active(:)
    real(dp), intent(in) :: h(:), dubar(:)
    integer, intent(in) :: eq(:), nbody
    type(csc_t), intent(inout) :: k
    real(dp), intent(inout) :: rhs(:)
    real(dp) :: rho, cc, diag, target
    integer :: i, p, q, a, b, nf, pos
    do i = 1, cs%nrow + cs%ntan
      if (.not. active(i)) cycle
      cc = 0.0_dp
      diag = 0.0_dp
      nf = 0
      target = h(i)
      do p = cs%bptr(i), cs%bptr(i + 1) - 1
        a = eq(cs%cdof(cs%bcol(p)))
        if (a == 0) then
          target = target - cs%bval(p) * dubar(cs%cdof(cs%bcol(p)))
        else if (cs%cdof(cs%bcol(p)) <= nbody) then
          cc = cc + cs%bval(p)**2
          diag = diag + k%val(find_row(k, a, a))
          nf = nf + 1
        end if
      end do
      if (nf == 0 .or. cc <= 0.0_dp) cycle
      rho = diag / nf / cc
      do p = cs%bptr(i), cs%bptr(i + 1) - 1
        a = eq(cs%cdof(cs%bcol(p)))
        if (a == 0) cycle
        rhs(a) = rhs(a) + rho * cs%bval(p) * target
        do q = cs%bptr(i), cs%bptr(i + 1) - 1
          b = eq(cs%cdof(cs%bcol(q)))
          if (b == 0 .or. b < a) cycle               ! K's upper triangle (a row's dofs are distinct)
          pos = find_row(k, a, b)
          k%val(pos) = k%val(pos) + rho * cs%bval(p) * cs%bval(q)
        end do
      end do
    end do
  end subroutine augment_rows

end module augmented_tangent
