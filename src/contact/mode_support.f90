!> mode_support: which free rigid modes the contact constraint rows hold.
!>
!> A body's free rigid modes R (rigid_modes) are held by contact only if the
!> rows of B that are there see them: the combination R c is resisted when it
!> opens or closes some gap, H c = B R c /= 0.  Frictionless contact gives
!> normal rows only, so a rigid motion that is tangential to the contact
!> surface everywhere is not held by it: a translation along a flat contact,
!> the rotation of a ring about the centre of a circular contact (every
!> normal passes through the centre).  A pair with friction adds its
!> tangential rows T to H = C R, C = [B; T]: friction holds such a motion
!> (within the cone; whether the load fits in it is friction_modes' test).
!>
!> The decision, made before anything is solved, from the SVD of H (dgesvd):
!>  - columns in comparable units: mode j is scaled to a unit root-mean-square
!>    nodal displacement of its body (R(:, j) sqrt(nnode)), so that a
!>    singular value is the gap opened by a rigid motion of unit size;
!>  - the reference of body b, ref_b, is the largest column norm of its
!>    scaled modes: what a motion of unit size normal to the contact opens;
!>  - a right singular vector v (singular value s) is held when
!>        s > tau_b ref_b   (summed over the bodies v involves, |v_b| weights),
!>    tau_b = max(1e-10, theta_b), theta_b the median turning angle (radians)
!>    between consecutive segments of the contact polylines of the pairs
!>    that touch body b, on each side (slave rows, covered master nodes) on
!>    its own, the larger of the two (the median: a true corner of the
!>    geometry is exact in the polygon and must not count; each side: a
!>    finely meshed flat must not outvote the curve facing it).
!> Why theta_b: on a polygonal boundary the discrete normals (nodal normals,
!> and the mortar rows' average of the master motion over the support of phi_i)
!> differ from the exact ones by up to the angle the polygon turns between two
!> segments.  A rigid motion of unit size, tangential to the exact boundary,
!> therefore opens discrete gaps of relative size up to theta_b (less on
!> smooth uniform meshes, theta_b^2): the rotation of a ring on a polygonal
!> circle gives H c of order h/R, not 0.  Such a "hold" lives in the mesh's
!> defect: it changes sign and size from one mesh to the next, and a load of
!> order of the round-off turns it into an arbitrary rigid motion (an
!> amplitude 1/s of the load).  Below theta_b the mode cannot be told from one
!> that the exact geometry does not hold, so it is not held; above it the hold
!> rests on a lever arm longer than the polygon's defect and is genuine (a block
!> on a flat has theta_b = 0: every nonzero s above round-off holds).
!>
!> An unheld combination v must be unloaded: the load along it, |v'e| (scaled),
!> is compared with sum_j |v_j| sum_d |f_d| |R(d, j)| (the largest load along the
!> modes that the same nodal forces could give) with the same tau: a pressure
!> on a polygonal arc has exactly no moment about the arc's centre, gravity on
!> an unsymmetric mesh of a symmetric body a moment of the mesh's defect.  A
!> loaded one has no equilibrium (exit 1, naming the body and the motion).
!>
!> Programming interface
!>   type(mode_split_t)                           held basis, unheld combinations
!>   split_free_modes(cs, bodies, fl, fext, sp)   H, e and the decision
module mode_support
  use kinds, only: dp
  use lapack_interfaces, only: dgesvd
  use body, only: body_t
  use contact_set, only: contact_set_t
  use rigid_modes, only: floating_t
  implicit none
  private
  public :: mode_split_t, split_free_modes

  type :: mode_split_t
    real(dp), allocatable :: h(:,:)          !< (nrow + ntan, k) H = C R, normal then tangential rows
    real(dp), allocatable :: e(:)            !< (k) e = R' f_ext
    real(dp), allocatable :: held(:,:)       !< (k, kh) basis of the held combinations
    real(dp), allocatable :: unheld(:,:)     !< (k, nu) the combinations no contact row holds
    integer, allocatable :: unheld_body(:)   !< (nu) body of each (the largest component)
    real(dp), allocatable :: load(:)         !< (nu) load along each, relative to its scale
    real(dp), allocatable :: load_tol(:)     !< (nu) what of load(:) the direction's uncertainty explains
    logical, allocatable :: loaded(:)        !< (nu) load above load_tol: no equilibrium
    real(dp), allocatable :: tau(:)          !< (nbody) resolution of the body's contact normals
  end type mode_split_t

  real(dp), parameter :: tau_exact = 1.0e-10_dp    !< round-off floor on flat contacts

contains

  !> H = C R, e = R' f and the held / unheld combinations of the free modes.
  !>   cs     (in)  contact rows (normal and tangential: 1..nrow+ntan)
  !>   bodies (in)  the bodies (meshes, dof0)
  !>   fl     (in)  the free modes, fl%k >= 0
  !>   fext   (in)  (ndof) external nodal forces
  !>   sp     (out) the decision; size(sp%held, 2) + size(sp%unheld, 2) = fl%k
  subroutine split_free_modes(cs, bodies, fl, fext, sp)
    type(contact_set_t), intent(in) :: cs
    type(body_t), intent(in) :: bodies(:)
    type(floating_t), intent(in) :: fl
    real(dp), intent(in) :: fext(:)
    type(mode_split_t), intent(out) :: sp
    real(dp), allocatable :: hs(:,:), a(:,:), s(:), vt(:,:), work(:), cscale(:), ref(:), es(:), s_unheld(:)
    real(dp) :: u1(1, 1), wq(1), vb, threshold, lscale, s_held
    logical, allocatable :: involved(:)
    integer :: k, nr, j, r, kk, i, b, info, nb
    logical, allocatable :: is_held(:)

    k = fl%k
    nr = cs%nrow + cs%ntan
    nb = size(bodies)
    allocate(sp%h(nr, k), sp%e(k), cscale(k), ref(nb), s(k), vt(k, k))
    sp%h = 0.0_dp
    do j = 1, k
      do r = 1, nr
        do kk = cs%bptr(r), cs%bptr(r + 1) - 1
          sp%h(r, j) = sp%h(r, j) + cs%bval(kk) * fl%r(cs%cdof(cs%bcol(kk)), j)     ! H = C R
        end do
      end do
      sp%e(j) = dot_product(fl%r(:, j), fext)                                        ! e = R' f
      cscale(j) = sqrt(real(bodies(fl%mode_body(j))%mesh%nnode, dp))                  ! unit rms motion
    end do
    call body_resolution(cs, bodies, sp%tau)

    ! SVD of the scaled H: H D = U S V', D = diag(cscale)
    hs = sp%h
    do j = 1, k
      hs(:, j) = hs(:, j) * cscale(j)
    end do
    ref = 0.0_dp
    do j = 1, k
      b = fl%mode_body(j)
      if (nr > 0) ref(b) = max(ref(b), norm2(hs(:, j)))
    end do
    s = 0.0_dp
    vt = 0.0_dp
    do j = 1, k
      vt(j, j) = 1.0_dp
    end do
    if (nr > 0 .and. k > 0) then
      a = hs
      call dgesvd('N', 'A', nr, k, a, nr, s(1:min(nr, k)), u1, 1, vt, k, wq, -1, info)
      allocate(work(max(1, int(wq(1)))))
      call dgesvd('N', 'A', nr, k, a, nr, s(1:min(nr, k)), u1, 1, vt, k, work, size(work), info)
    end if

    ! held when s_i > sum_b |v_b| tau_b ref_b
    allocate(is_held(k))
    es = sp%e * cscale
    do i = 1, k
      threshold = 0.0_dp
      do b = 1, nb
        vb = norm2(pack(vt(i, :), fl%mode_body == b))
        threshold = threshold + vb * sp%tau(b) * ref(b)
      end do
      is_held(i) = s(i) > threshold .and. s(i) > 0.0_dp
    end do
    sp%unheld = transpose(vt(pack([(i, i = 1, size(is_held))], .not. is_held), :))
    s_unheld = pack(s, .not. is_held)
    s_held = huge(1.0_dp)
    if (any(is_held)) s_held = minval(pack(s, is_held))
    allocate(sp%unheld_body(size(sp%unheld, 2)), sp%load(size(sp%unheld, 2)), sp%loaded(size(sp%unheld, 2)), &
             sp%load_tol(size(sp%unheld, 2)), involved(k))
    do i = 1, size(sp%unheld, 2)
      sp%unheld_body(i) = fl%mode_body(maxloc(abs(sp%unheld(:, i)), dim=1))
      ! load along v relative to the load along every mode of the bodies v moves
      do j = 1, k
        involved(j) = norm2(pack(sp%unheld(:, i), fl%mode_body == fl%mode_body(j))) > 1.0e-8_dp
      end do
      lscale = norm2(pack(es, involved))
      sp%load(i) = 0.0_dp
      if (lscale > 0.0_dp) sp%load(i) = abs(dot_product(sp%unheld(:, i), es)) / lscale
      ! v is known to within an angle s_i / s_held (its singular value over the
      ! gap to the held ones, Wedin): a load component below that is no load
      sp%load_tol(i) = max(1.0e-9_dp, s_unheld(i) / s_held)
      sp%loaded(i) = sp%load(i) > sp%load_tol(i)
    end do
    ! back to the modes' own amplitudes: alpha = D alpha_scaled
    do j = 1, k
      sp%unheld(j, :) = sp%unheld(j, :) * cscale(j)
    end do
    call choose_held(fl, sp%unheld, sp%held)
  end subroutine split_free_modes

  !> A basis of combinations that completes the unheld ones, translations
  !> first.  The equilibrium of a body is enforced along the held
  !> combinations only: along a complement of the unheld ones, which one
  !> decides which balance is dropped.  An unheld rotation about P drops the
  !> moment about P, not a force: the rotation-free combinations of each body
  !> are taken first (its force balance stays exact), then the modes
  !> themselves, each kept when independent of those already taken.
  !>   fl     (in)  the modes
  !>   unheld (in)  (k, nu) the unheld combinations
  !>   held   (out) (k, k - nu) the held ones
  subroutine choose_held(fl, unheld, held)
    type(floating_t), intent(in) :: fl
    real(dp), intent(in) :: unheld(:,:)
    real(dp), allocatable, intent(out) :: held(:,:)
    real(dp), allocatable :: q(:,:), cand(:,:), rot(:)
    integer :: k, nq, j, b, jmax, i
    k = fl%k
    allocate(held(k, 0), q(k, 0), cand(k, 0))
    if (size(unheld, 2) == 0) then          ! every combination is held: the modes themselves
      deallocate(held)
      allocate(held(k, k), source=0.0_dp)
      do j = 1, k
        held(j, j) = 1.0_dp
      end do
      return
    end if
    ! rotation-free combinations of each body: e_j - (rot_j / rot_jmax) e_jmax
    allocate(rot(k))
    rot = fl%coef(3, :) / fl%norm
    do b = 1, maxval(fl%mode_body)
      if (.not. any(fl%mode_body == b)) cycle
      jmax = maxloc(abs(rot), mask=fl%mode_body == b, dim=1)
      do j = 1, k
        if (fl%mode_body(j) /= b .or. j == jmax) cycle
        cand = reshape([cand, [(0.0_dp, i = 1, k)]], [k, size(cand, 2) + 1])
        cand(j, size(cand, 2)) = 1.0_dp
        if (abs(rot(jmax)) > 0.0_dp) cand(jmax, size(cand, 2)) = -rot(j) / rot(jmax)
      end do
    end do
    do j = 1, k                              ! then the modes themselves
      cand = reshape([cand, [(merge(1.0_dp, 0.0_dp, i == j), i = 1, k)]], [k, size(cand, 2) + 1])
    end do
    ! greedy: keep a candidate independent of the unheld and the kept ones
    do j = 1, size(unheld, 2)
      call add_independent(q, unheld(:, j))
    end do
    do j = 1, size(cand, 2)
      if (size(q, 2) == k) exit
      nq = size(q, 2)
      call add_independent(q, cand(:, j))
      if (size(q, 2) > nq) held = reshape([held, cand(:, j)], [k, size(held, 2) + 1])
    end do
  end subroutine choose_held

  !> Gram-Schmidt (twice): append v / |v| to the orthonormal columns of q when
  !> its part outside span(q) is above 1e-6 of |v|.
  subroutine add_independent(q, v)
    real(dp), allocatable, intent(inout) :: q(:,:)
    real(dp), intent(in) :: v(:)
    real(dp), allocatable :: r(:)
    integer :: pass
    r = v
    do pass = 1, 2
      r = r - matmul(q, matmul(transpose(q), r))
    end do
    if (norm2(r) <= 1.0e-6_dp * norm2(v)) return
    q = reshape([q, r / norm2(r)], [size(v), size(q, 2) + 1])
  end subroutine add_independent


  !> tau(b) = max(1e-10, the median turning angle between consecutive
  !> segments of the contact polylines of the pairs touching body b, on the
  !> slave side at the nodes that carry a row, on the master side at the
  !> covered nodes, the larger of the two sides' medians).  The median, not
  !> the largest: a contact that cannot resist a rotation about P lies on a
  !> circle about P along its whole length, where every angle is about h/R,
  !> while a true corner of the geometry (exact in the polygon) is one node
  !> among many and must not blur the others.  Each side on its own: the
  !> defect is that of the rougher polygon, and a finely meshed flat on the
  !> other side (a disk of 1024 rim nodes in a V notch meshed at h/6: 510
  !> angles of 6e-3 against 668 of 0) must not outvote it.
  subroutine body_resolution(cs, bodies, tau)
    type(contact_set_t), intent(in) :: cs
    type(body_t), intent(in) :: bodies(:)
    real(dp), allocatable, intent(out) :: tau(:)
    integer :: ip, i, b, ns, nm
    real(dp), allocatable :: slave_angles(:), master_angles(:)
    allocate(tau(size(bodies)))
    tau = tau_exact
    do b = 1, size(bodies)
      allocate(slave_angles(0), master_angles(0))
      do ip = 1, cs%npair
        if (cs%pair(ip)%spec%slave_body /= b .and. cs%pair(ip)%spec%master_body /= b) cycle
        ns = size(cs%pair(ip)%snode)
        do i = 2, ns - 1
          if (cs%pair(ip)%row(i)) slave_angles = [slave_angles, turning(cs%pair(ip)%xs(:, i - 1:i + 1))]
        end do
        nm = size(cs%pair(ip)%mnode)
        do i = 2, nm - 1
          if (cs%pair(ip)%mcov(i) > 0.0_dp) master_angles = [master_angles, &
            turning(bodies(cs%pair(ip)%spec%master_body)%mesh%x(:, cs%pair(ip)%mnode(i - 1:i + 1)))]
        end do
      end do
      if (size(slave_angles) > 0) tau(b) = max(tau(b), median(slave_angles))
      if (size(master_angles) > 0) tau(b) = max(tau(b), median(master_angles))
      deallocate(slave_angles, master_angles)
    end do
  end subroutine body_resolution

  !> Median of a (the lower one for an even count), by quickselect.
  function median(a) result(m)
    real(dp), intent(in) :: a(:)
    real(dp) :: m
    real(dp), allocatable :: w(:)
    real(dp) :: pivot, t
    integer :: lo, hi, i, j, kth
    w = a
    kth = (size(w) + 1) / 2
    lo = 1
    hi = size(w)
    do while (lo < hi)
      pivot = w((lo + hi) / 2)
      i = lo
      j = hi
      do while (i <= j)
        do while (w(i) < pivot)
          i = i + 1
        end do
        do while (w(j) > pivot)
          j = j - 1
        end do
        if (i <= j) then
          t = w(i)
          w(i) = w(j)
          w(j) = t
          i = i + 1
          j = j - 1
        end if
      end do
      if (kth <= j) then
        hi = j
      else if (kth >= i) then
        lo = i
      else
        exit
      end if
    end do
    m = w(kth)
  end function median

  !> Angle (radians, in [0, pi]) between segments p1-p2 and p2-p3.
  pure real(dp) function turning(p) result(theta)
    real(dp), intent(in) :: p(2, 3)
    real(dp) :: t1(2), t2(2)
    t1 = p(:, 2) - p(:, 1)
    t2 = p(:, 3) - p(:, 2)
    theta = abs(atan2(t1(1) * t2(2) - t1(2) * t2(1), dot_product(t1, t2)))
  end function turning

end module mode_support
