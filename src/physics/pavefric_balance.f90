!> The pad's load balance, sum_i F_i(delta) + Wh(delta) = W (Eq. 9 with the
!> hydrodynamic block of Fig. 4).
!>
!> Work is done in shifted coordinates: d_i = c_i - min(c) >= 0 (so min d = 0
!> exactly) and x = delta - min(c). Element i pushes with F_i = kel max(0, x - d_i),
!> kel = l dx_el K_eff. The unknown is x; rounding is then relative to the
!> penetration beyond the first contact, not to the profile's absolute height.
module pavefric_balance
   use pavefric_kinds, only: wp, i8, lanes
   use pavefric_film, only: film_model, film_step_type
   use pavefric_lapack, only: dlasrt
   implicit none
   private

   public :: dry_root, dry_roots, dry_roots_of_c, wet_roots, gap_field, engaged_lanes, &
      & engaged_by_level, lanes

   !> Newton-from-above iterations before the exact sort-and-scan fallback.
   integer, parameter :: max_newton_dry = 24
   !> Safeguarded-Newton iterations of the wet root (bisection bounds it to
   !> about 60 on a double bracket; this is a last resort).
   integer, parameter :: max_iter_wet = 200

contains

   !> Exact root of sum_i max(0, x - d_i) = s (s = W / kel > 0, min d = 0):
   !> the "water-filling" level, by Newton's method on this convex
   !> piecewise-linear function. From a guess x0 below the root, one Newton
   !> step lands above it; from above, Newton descends monotonically and its
   !> active set {d_i < x} only shrinks. Either way it stops when the active
   !> set repeats: x = (s + sum_active d) / m is then the closed form on its
   !> own linear piece, i.e. the root, whatever the guess. No iteration
   !> tolerance is involved. A pathological spread that needs many steps
   !> falls back to the same closed form found by sorting (LAPACK dlasrt).
   pure subroutine dry_root(d, s, x0, x, work)
      real(wp), intent(in) :: d(:), s
      !> Starting guess (the previous position's root is a good one); a guess
      !> that is not > 0 starts from s, an upper bound because min d = 0.
      real(wp), intent(in) :: x0
      real(wp), intent(out) :: x
      !> Workspace of size(d), only touched by the fallback.
      real(wp), intent(inout) :: work(:)
      real(wp) :: sum_active, x_new
      integer :: m, m_prev, i, it, n
      n = size(d)
      x = s
      if (x0 > 0.0_wp .and. x0 < s) x = x0
      m_prev = -1
      do it = 1, max_newton_dry
         sum_active = 0.0_wp
         m = 0
         do i = 1, n
            sum_active = sum_active + merge(d(i), 0.0_wp, d(i) < x)
            m = m + merge(1, 0, d(i) < x)
         end do
         if (m == m_prev) return         ! active set repeats: x is the root
         x_new = (s + sum_active) / real(m, wp)
         ! from above, a non-decreasing step means rounding has stalled
         if (it > 1 .and. m < m_prev .and. x_new >= x) return
         m_prev = m
         x = x_new
      end do
      call sorted_root(d, s, x, work)
   end subroutine dry_root

   !> dry_root for several lanes (speeds) at once: d(lane, element), s, x0 and
   !> x per lane. The element loops run over the lanes innermost (they
   !> vectorise); every lane performs exactly dry_root's operations in the
   !> same order, and a lane that has stopped is left as it is, so each x is
   !> dry_root's to the bit.
   pure subroutine dry_roots(nl, n, d, s, x0, x, work, dl)
      !> Lanes (at most `lanes`, given at run time: the lane loops then compile
      !> to vector loops, a constant count to unrolled scalar code) and elements.
      integer, intent(in) :: nl, n
      real(wp), intent(in) :: d(nl, n)
      real(wp), intent(in) :: s(nl), x0(nl)
      real(wp), intent(out) :: x(nl)
      !> Workspaces of size n, only touched by the fallback.
      real(wp), intent(inout) :: work(:), dl(:)
      logical, dimension(lanes) :: running
      x = s
      where (x0 > 0.0_wp .and. x0 < s) x = x0
      running = .true.
      call newton_passes(nl, n, d, s, x, running, work, dl)
   end subroutine dry_roots

   !> dry_roots on the clearances as they come, c (not shifted by their least
   !> value cmin: each pass takes d = c - cmin, the shift's own subtraction),
   !> started from the first pass a caller took in its own pass over c at a
   !> guess g: the count of the c below g, the sum of their c - g, the
   !> largest of them (below) and the least of the others (above). The first
   !> Newton step from there is x1 = (g - cmin) + (s + sum) / count. Where no
   !> element lies between g and x1 (below < x1 <= above, shifted), the
   !> active set repeats at x1, which is then the root without a pass; that
   !> is taken only where the step's terms are within 4 times x1, so that
   !> it keeps the digits of a tiny compression (a guess far off leaves
   !> them short). Elsewhere passes follow from x1 as in dry_roots (from a
   !> start whose set no pass has seen): one accepts x
   !> where the active set repeats, and x is taken from that pass's own sums,
   !> the root's formula on the shifted clearances (dry_roots' x, to the bit,
   !> where both find it from the same set). Each lane decides alone, so a
   !> lane's root does not depend on the lanes beside it. A lane with no c
   !> below g (no guess: -huge), or whose first step rounding took to 0 or
   !> below, starts from s, dry_roots' own start. x: the root, shifted by
   !> cmin.
   pure subroutine dry_roots_of_c(nl, n, c, cmin, s, g, sums_c, counts, below, above, x, &
         & work, dl)
      integer, intent(in) :: nl, n
      real(wp), intent(in) :: c(nl, n), cmin(nl), s(nl), g(nl), sums_c(nl), counts(nl), &
         & below(nl), above(nl)
      real(wp), intent(out) :: x(nl)
      !> Workspaces of size n, only touched by the fallback.
      real(wp), intent(inout) :: work(:), dl(:)
      logical, dimension(lanes) :: running, confirmed
      integer :: j, m
      do j = 1, nl
         m = nint(counts(j))
         x(j) = s(j)
         if (m > 0) x(j) = (g(j) - cmin(j)) + (s(j) + sums_c(j)) / real(m, wp)
         if (m == 0 .or. .not. x(j) > 0.0_wp) then
            x(j) = s(j)
            confirmed(j) = .false.
         else
            ! taken without a pass only where its terms are of the root's
            ! size (a guess far off, or a tiny compression, would leave it
            ! short of digits) and no element lies between the guess and it
            confirmed(j) = abs(g(j) - cmin(j)) <= 4.0_wp * x(j) .and. &
               & abs(sums_c(j)) <= 4.0_wp * real(m, wp) * x(j) .and. &
               & below(j) - cmin(j) < x(j) .and. above(j) - cmin(j) >= x(j)
            ! An unconfirmed x1 starts the passes as any start does, its
            ! own set not yet seen: the set at g is not the set at x1 where
            ! rounding moved x1 past a clearance, and a pass that found the
            ! same count at x1 would take the root from x1's set without
            ! checking it at the root (a Kelvin-Voigt pad of long memory
            ! under a tiny load keeps clearances within 1e-20 m of the
            ! root: residuals of up to 2e-4 of the load, found by an
            ! attack; tests/test_hard_cases.py)
         end if
      end do
      ! each lane's root its own: a confirmed lane stops whatever the others do
      running(1:nl) = .not. confirmed(1:nl)
      if (.not. any(running(1:nl))) return
      call newton_passes(nl, n, c, s, x, running, work, dl, cmin)
   end subroutine dry_roots_of_c

   !> The dry balance's Newton passes from x (per lane, the lanes `running`),
   !> a start whose active set no pass has seen. Each pass
   !> takes the sum and count of the clearances below x (d, or c - cmin where
   !> cmin is given: the shift's own subtraction, taken in the pass); a lane
   !> stops where the set repeats, x then taken from this pass's sums (the
   !> previous step's x to the bit where it came from a pass: the same set
   !> summed in the same order), or where a step from above does not descend
   !> (rounding has stalled: x, a step whose set a pass has seen, stays);
   !> after max_newton_dry passes, the sort-and-scan root. A root is always
   !> taken from the set of a point a pass has seen.
   pure subroutine newton_passes(nl, n, c, s, x, running, work, dl, cmin)
      integer, intent(in) :: nl, n
      real(wp), intent(in) :: c(nl, n), s(nl)
      real(wp), intent(inout) :: x(nl)
      logical, intent(inout) :: running(lanes)
      real(wp), intent(inout) :: work(:), dl(:)
      real(wp), intent(in), optional :: cmin(nl)
      real(wp), dimension(lanes) :: sum_active, x_new, count
      !> The count of the set each lane's x was taken from (-1: none yet).
      integer, dimension(lanes) :: m, m_prev
      integer :: j, it
      m_prev = -1
      do it = 1, max_newton_dry
         if (present(cmin)) then
            call active_sums_of_c(nl, n, c, cmin, x, sum_active, count)
         else
            call active_sums(nl, n, c, x, sum_active, count)
         end if
         m(1:nl) = nint(count(1:nl))
         do j = 1, nl
            if (.not. running(j)) cycle
            x_new(j) = (s(j) + sum_active(j)) / real(m(j), wp)
            if (m(j) == m_prev(j)) then             ! active set repeats: x is the root
               x(j) = x_new(j)
               running(j) = .false.
               cycle
            end if
            ! from above, a non-decreasing step means rounding has stalled
            if (m(j) < m_prev(j) .and. x_new(j) >= x(j)) then
               running(j) = .false.
               cycle
            end if
            m_prev(j) = m(j)
            x(j) = x_new(j)
         end do
         if (.not. any(running(1:nl))) return
      end do
      do j = 1, nl
         if (.not. running(j)) cycle
         if (present(cmin)) then
            dl = c(j, :) - cmin(j)
         else
            dl = c(j, :)
         end if
         call sorted_root(dl, s(j), x(j), work)
      end do
   end subroutine newton_passes

   !> active_sums on d = c - cmin, taken in the pass.
   pure subroutine active_sums_of_c(nl, n, c, cmin, x, sum_active, count)
      integer, intent(in) :: nl, n
      real(wp), intent(in) :: c(nl, n), cmin(nl), x(nl)
      real(wp), intent(out) :: sum_active(nl), count(nl)
      integer :: i, j
      real(wp) :: d, total, counted
      if (nl == 1) then
         ! one lane: plain loops (as active_sums), the same operations
         total = 0.0_wp
         counted = 0.0_wp
         do i = 1, n
            d = c(1, i) - cmin(1)
            total = total + merge(d, 0.0_wp, d < x(1))
            counted = counted + merge(1.0_wp, 0.0_wp, d < x(1))
         end do
         sum_active(1) = total
         count(1) = counted
         return
      end if
      sum_active = 0.0_wp
      count = 0.0_wp
      do i = 1, n
         do j = 1, nl
            d = c(j, i) - cmin(j)
            sum_active(j) = sum_active(j) + merge(d, 0.0_wp, d < x(j))
            count(j) = count(j) + merge(1.0_wp, 0.0_wp, d < x(j))
         end do
      end do
   end subroutine active_sums_of_c

   !> Per lane, the sum and the count of the d below x: the loop over the
   !> lanes innermost, every shape explicit and given at run time, so that it
   !> compiles to a vector loop with the comparison as a blend (measured:
   !> constant-size lane arrays compile to branches or per-lane scalar
   !> sums). The count in a real (exact below 2**53): one type in the loop.
   pure subroutine active_sums(nl, n, d, x, sum_active, count)
      integer, intent(in) :: nl, n
      real(wp), intent(in) :: d(nl, n), x(nl)
      real(wp), intent(out) :: sum_active(nl), count(nl)
      integer :: i, j
      real(wp) :: total, counted
      if (nl == 1) then
         ! one lane: plain loops (a lane loop of one trip costs more than
         ! the work), the same operations in the same order
         total = 0.0_wp
         counted = 0.0_wp
         do i = 1, n
            total = total + merge(d(1, i), 0.0_wp, d(1, i) < x(1))
            counted = counted + merge(1.0_wp, 0.0_wp, d(1, i) < x(1))
         end do
         sum_active(1) = total
         count(1) = counted
         return
      end if
      sum_active = 0.0_wp
      count = 0.0_wp
      do i = 1, n
         do j = 1, nl
            sum_active(j) = sum_active(j) + merge(d(j, i), 0.0_wp, d(j, i) < x(j))
            count(j) = count(j) + merge(1.0_wp, 0.0_wp, d(j, i) < x(j))
         end do
      end do
   end subroutine active_sums

   !> The same root by sorting d and scanning the pieces.
   pure subroutine sorted_root(d, s, x, work)
      real(wp), intent(in) :: d(:), s
      real(wp), intent(out) :: x
      real(wp), intent(inout) :: work(:)
      real(wp) :: partial
      integer :: m, n, info
      n = size(d)
      work(1:n) = d
      call dlasrt('I', n, work, info)
      partial = 0.0_wp
      do m = 1, n
         partial = partial + work(m)
         x = (s + partial) / real(m, wp)
         if (m == n) exit
         if (x <= work(m+1)) exit
      end do
   end subroutine sorted_root

   !> The wet balance of the lanes where `wet`: per lane, the root of
   !> f(x) = kel sum max(0, x - d_i) + Wh(gap(x)) - W on [lo, x_dry], where Wh
   !> is the film's load for the gap field gap_i = max(0, d_i - x), f(lo) = -W
   !> (no contact, no film load: lo from the film) and f(x_dry) = Wh >= 0.
   !> Both terms are non-decreasing in x, so the root is unique. Newton with
   !> the analytic derivative from x_dry, safeguarded by bisection whenever
   !> a step leaves the bracket or does not halve |f|; it stops when |f| <=
   !> tol W. Each lane's decisions are its own (its numbers do not depend on
   !> the other lanes); the evaluations of all lanes still iterating run as
   !> one pass over the lanes (their sums interleave). x holds the dry roots
   !> on entry (for a wet lane, an upper bound of its dry root will do:
   !> engaged_by_level's; x_dry below stands for it) and, for the wet lanes,
   !> the wet roots on exit; wh the film's load and evaluations the count
   !> added, per lane.
   !> Warm start: a lane whose guess x0 lies strictly inside its bracket
   !> (lo, x_dry) starts there (the previous position's wet root, in this
   !> position's shifted coordinates), else at x_dry. The guess changes only
   !> where the iteration starts: the root is the same to wet_tol.
   pure subroutine wet_roots(nl, n, d, kel, load, film, fsteps, wet, tol, x0, x, wh, &
      & evaluations, gaps, fwork, sum_d)
      integer, intent(in) :: nl, n
      real(wp), intent(in) :: d(nl, n), kel(nl), load, tol
      !> Per lane, the starting guess (anything outside the bracket: none).
      real(wp), intent(in) :: x0(nl)
      class(film_model), intent(in) :: film
      type(film_step_type), intent(in) :: fsteps(nl)
      logical, intent(in) :: wet(nl)
      real(wp), intent(inout) :: x(nl)
      real(wp), intent(out) :: wh(nl)
      integer(i8), intent(inout) :: evaluations(nl)
      !> Workspace (nl, n): the gap fields of the last evaluation (for films
      !> that need the field; see film_model%sums_suffice).
      real(wp), intent(inout) :: gaps(nl, n)
      !> The film's workspace per lane (film%work_size(n), nl), kept by the
      !> caller over a speed's run.
      real(wp), intent(inout) :: fwork(:, :)
      !> Per lane, sum(d) in element order, if the caller has it (engaged_lanes'):
      !> for a film whose sums suffice, its lower bound from it.
      real(wp), intent(in), optional :: sum_d(nl)
      ! fixed-size locals (run-time sizes would be heap allocations)
      real(wp), dimension(lanes) :: lo, hi, f, df, f_old, pushed, contacts, gap_total, n_open
      real(wp) :: x_new
      logical :: running(lanes), use_newton, jumps, stops
      integer :: it, j
      if (film%sums_suffice() .and. .not. film%jumps_at_contact()) then
         call wet_roots_on_pieces(nl, n, d, kel, load, film, fsteps, wet, tol, x0, x, wh, &
            & evaluations, gaps, fwork, sum_d)
         return
      end if
      jumps = film%jumps_at_contact()
      call start_brackets(nl, n, d, film, fsteps, wet, x0, x, lo, hi, wh, running, sum_d)
      if (.not. any(running)) return
      call evaluate_wet(nl, n, d, kel, load, film, fsteps, running, x, f, df, wh, evaluations, &
         & gaps, fwork, pushed, contacts, gap_total, n_open)
      f_old = huge(1.0_wp)
      do it = 1, max_iter_wet
         do j = 1, nl
            if (.not. running(j)) cycle
            call settle(f(j), x(j), tol * load, lo(j), hi(j), stops)
            if (stops) then
               running(j) = .false.
               cycle
            end if
            call newton_step(f(j), df(j), f_old(j), x(j), lo(j), hi(j), x_new, use_newton)
            if (.not. use_newton) then
               x_new = 0.5_wp * (lo(j) + hi(j))
               if (jumps) x_new = breakpoint_split(d(j, :), lo(j), hi(j), x_new)
            end if
            f_old(j) = abs(f(j))
            x(j) = x_new
         end do
         if (.not. any(running)) exit
         call evaluate_wet(nl, n, d, kel, load, film, fsteps, running, x, f, df, wh, evaluations, &
         & gaps, fwork, pushed, contacts, gap_total, n_open)
      end do
      do j = 1, nl
         if (.not. wet(j)) cycle
         if (abs(f(j)) > tol * load) then
            ! The bracket closed on adjacent doubles without |f| reaching
            ! the tolerance. This happens only as the film closes: Eq. 15
            ! grows like ln(1/Hout), so f is continuous but so steep (slope
            ! ~ 1/Hout) that the root falls between two doubles, or lies at
            ! a film thinner than any double (then f jumps to the largest
            ! real at Hout = 0). Take the upper end and let the film carry
            ! what the rubber does not: the intermediate value of Wh between
            ! the two ends, balanced exactly.
            if (f(j) < 0.0_wp) then
               x(j) = hi(j)
               call evaluate_wet(nl, n, d, kel, load, film, fsteps, lane_mask(j), x, f, df, &
                  & wh, evaluations, gaps, fwork, pushed, contacts, gap_total, n_open)
            end if
            wh(j) = max(0.0_wp, load - kel(j) * pushed_at(d(j, :), x(j)))
         end if
      end do
   contains
      pure function lane_mask(jj) result(mask)
         integer, intent(in) :: jj
         logical :: mask(nl)
         mask = .false.
         mask(jj) = .true.
      end function lane_mask

   end subroutine wet_roots

   !> wet_roots for a film whose load depends on the gap field only through
   !> the gaps' sum and the count of open gaps (film_model%sums_suffice, and
   !> no jump where an element touches: the paper's bearing). Between two
   !> touching points (a piece: the contacts d_i < x fixed) the pad's push
   !> and the gaps' sum are linear in x,
   !>     P(y) = P(x) + n_c (y - x),   G(y) = G(x) - n_o (y - x),
   !> so f on the piece is kel P(y) + Wh(G(y), n_o) - W: one film load per
   !> value, no pass over the elements. Each pass over the elements (an
   !> evaluation of f) gives x's piece; safeguarded Newton then runs on that
   !> piece's formula (bisection on its own bracket where a step leaves it
   !> or does not halve the residual) until it balances to tol W. Where no
   !> d_i lies between x and that root (ends included: a cheap pass that
   !> only counts them, all such lanes at once), the root is on x's piece,
   !> f there is the formula's and the lane stops; else the next pass
   !> evaluates f there. The formula and a pass give the same f rounded
   !> differently (by about 1e-15 W), so a root taken from the formula may
   !> miss the tolerance by that much when f is summed element by element.
   !> A root typically takes one or two passes, where Newton with a pass
   !> per step took four to five. The stopping test, the bracket and its
   !> closing are wet_roots': the root is the same to tol W. `evaluations`
   !> counts the passes with the film's load, as wet_roots'; the steps on
   !> a piece's formula and the counting passes are not counted.
   pure subroutine wet_roots_on_pieces(nl, n, d, kel, load, film, fsteps, wet, tol, x0, x, &
      & wh, evaluations, gaps, fwork, sum_d)
      integer, intent(in) :: nl, n
      real(wp), intent(in) :: d(nl, n), kel(nl), load, tol, x0(nl)
      class(film_model), intent(in) :: film
      type(film_step_type), intent(in) :: fsteps(nl)
      logical, intent(in) :: wet(nl)
      real(wp), intent(inout) :: x(nl)
      real(wp), intent(out) :: wh(nl)
      integer(i8), intent(inout) :: evaluations(nl)
      !> evaluate_wet's workspaces (wet_roots').
      real(wp), intent(inout) :: gaps(nl, n), fwork(:, :)
      !> wet_roots'.
      real(wp), intent(in), optional :: sum_d(nl)
      ! fixed-size locals (run-time sizes would be heap allocations)
      real(wp), dimension(lanes) :: lo, hi, f, df, f_old, x_eval, pushed, contacts, &
         & gap_total, n_open, y, fy, dfy, fy_old, ylo, yhi, gm, whm, dwhm, fy_stop, wh_stop, &
         & between
      logical, dimension(lanes) :: running, inner, cand
      real(wp) :: y_new
      logical :: use_newton, stops
      integer :: it, k, j
      integer, parameter :: max_inner = 200
      call start_brackets(nl, n, d, film, fsteps, wet, x0, x, lo, hi, wh, running, sum_d)
      if (.not. any(running)) return
      f_old = huge(1.0_wp)
      do it = 1, max_iter_wet
         ! a pass over the elements: f at x, and x's piece
         x_eval(1:nl) = x
         call evaluate_wet(nl, n, d, kel, load, film, fsteps, running, x, f, df, wh, &
            & evaluations, gaps, fwork, pushed, contacts, gap_total, n_open)
         ! the lanes that balance or whose bracket closed stop; the others
         ! step to their piece's root (or bisect their bracket)
         inner = .false.
         cand = .false.
         do j = 1, nl
            if (.not. running(j)) cycle
            call settle(f(j), x(j), tol * load, lo(j), hi(j), stops)
            if (stops) then
               running(j) = .false.
               cycle
            end if
            if (abs(f(j)) <= 0.5_wp * f_old(j)) then
               inner(j) = .true.                  ! the piece's root
               y(j) = x(j)
               fy(j) = f(j)
               dfy(j) = df(j)
               fy_old(j) = huge(1.0_wp)
               ylo(j) = lo(j)
               yhi(j) = hi(j)
            else
               x(j) = 0.5_wp * (lo(j) + hi(j))    ! the last step did not halve |f|
            end if
            f_old(j) = abs(f(j))
         end do
         if (.not. any(running(1:nl))) exit
         do k = 1, max_inner
            if (.not. any(inner(1:nl))) exit
            do j = 1, nl
               if (.not. inner(j)) cycle
               call newton_step(fy(j), dfy(j), fy_old(j), y(j), ylo(j), yhi(j), y_new, &
                  & use_newton)
               if (.not. use_newton) y_new = 0.5_wp * (ylo(j) + yhi(j))
               fy_old(j) = abs(fy(j))
               y(j) = y_new
               ! the piece's gap sum at y (0 where the piece's open gaps
               ! would all have closed: the film's largest load)
               gm(j) = max(0.0_wp, gap_total(j) - n_open(j) * (y(j) - x(j)))
            end do
            call film%loads_of_sums(nl, n, fsteps, gm, n_open, inner, whm, dwhm)
            do j = 1, nl
               if (.not. inner(j)) cycle
               fy(j) = kel(j) * (pushed(j) + contacts(j) * (y(j) - x(j))) + whm(j) - load
               dfy(j) = kel(j) * contacts(j) + dwhm(j)
               call settle(fy(j), y(j), tol * load, ylo(j), yhi(j), stops)
               if (stops) then
                  inner(j) = .false.
                  x(j) = y(j)
                  if (abs(fy(j)) <= tol * load) then
                     cand(j) = .true.
                     fy_stop(j) = fy(j)
                     wh_stop(j) = whm(j)
                  end if
               end if
            end do
         end do
         do j = 1, nl
            if (inner(j)) x(j) = y(j)
         end do
         ! a root that balances with no d_i between the pass's point and it
         ! (ends included) lies on that point's piece, whose formula is f
         ! there: no pass with the film's load is needed to check it (one
         ! pass counting the d_i between, for all such lanes at once)
         if (any(cand(1:nl))) then
            call breakpoints_between(nl, n, d, cand, x_eval, x, between)
            do j = 1, nl
               if (.not. cand(j) .or. between(j) > 0.0_wp) cycle
               running(j) = .false.
               f(j) = fy_stop(j)
               wh(j) = wh_stop(j)
            end do
            if (.not. any(running(1:nl))) exit
         end if
      end do
      do j = 1, nl
         if (.not. wet(j)) cycle
         ! (a lane the iterations ran out on: the point its f was taken at)
         if (running(j)) x(j) = x_eval(j)
         if (abs(f(j)) > tol * load) then
            ! The bracket closed on adjacent doubles without |f| reaching
            ! the tolerance (wet_roots): the upper end, the film carrying
            ! what the rubber does not.
            if (f(j) < 0.0_wp) x(j) = hi(j)
            wh(j) = max(0.0_wp, load - kel(j) * pushed_at(d(j, :), x(j)))
         end if
      end do
   end subroutine wet_roots_on_pieces

   !> The wet lanes' brackets [lo, x] (lo from the film, x the dry root or an
   !> upper bound of it) and their starting points: the guess x0 where it
   !> lies strictly inside, else x; `running` the wet lanes, wh zero.
   pure subroutine start_brackets(nl, n, d, film, fsteps, wet, x0, x, lo, hi, wh, running, &
      & sum_d_in)
      integer, intent(in) :: nl, n
      real(wp), intent(in) :: d(nl, n), x0(nl)
      class(film_model), intent(in) :: film
      type(film_step_type), intent(in) :: fsteps(nl)
      logical, intent(in) :: wet(nl)
      real(wp), intent(inout) :: x(nl)
      real(wp), intent(out) :: lo(lanes), hi(lanes), wh(nl)
      logical, intent(out) :: running(lanes)
      !> Per lane, sum(d) in element order, if the caller has it.
      real(wp), intent(in), optional :: sum_d_in(nl)
      real(wp) :: sum_d(lanes)
      integer :: j
      wh = 0.0_wp
      running = .false.
      running(1:nl) = wet
      if (film%sums_suffice() .and. present(sum_d_in)) then
         sum_d(1:nl) = sum_d_in
      else if (film%sums_suffice()) then
         ! (lower_bound's row by row was a strided copy per lane)
         call lane_sums(nl, n, d, sum_d)
      end if
      do j = 1, nl
         if (.not. wet(j)) cycle
         if (film%sums_suffice()) then
            lo(j) = min(0.0_wp, film%lower_bound_of_sum(fsteps(j), n, sum_d(j)))
         else
            lo(j) = min(0.0_wp, film%lower_bound(fsteps(j), d(j, :)))
         end if
         hi(j) = x(j)
         if (x0(j) > lo(j) .and. x0(j) < hi(j)) x(j) = x0(j)
      end do
   end subroutine start_brackets

   !> Per lane in `mask`, whether the film engages at the dry root x
   !> (film_model%engages on the gap field max(0, d - x)); the other lanes
   !> are not wet. For a film whose sums suffice, the gaps' sums of all
   !> lanes in one vector pass and engages_of_sums (the same answers); else
   !> each lane's field. dl and gap: workspaces of size n.
   pure subroutine engaged_lanes(nl, n, d, x, film, fsteps, mask, wet, dl, gap, sum_d)
      integer, intent(in) :: nl, n
      real(wp), intent(in) :: d(nl, n), x(nl)
      class(film_model), intent(in) :: film
      type(film_step_type), intent(in) :: fsteps(nl)
      logical, intent(in) :: mask(nl)
      logical, intent(out) :: wet(nl)
      real(wp), intent(inout) :: dl(:), gap(:)
      !> For a film whose sums suffice, each lane's sum(d) in element order
      !> (wet_roots takes it), for the lanes in `mask`; else 0.
      real(wp), intent(out) :: sum_d(nl)
      real(wp), dimension(lanes) :: gap_total, n_open
      real(wp) :: g
      integer :: i, j
      wet = .false.
      sum_d = 0.0_wp
      if (.not. any(mask)) return
      if (film%sums_suffice()) then
         ! the gaps' sums as contact_gap_sums makes them, without the push
         gap_total = 0.0_wp
         n_open = 0.0_wp
         sum_d = 0.0_wp
         do i = 1, n
            do j = 1, nl
               sum_d(j) = sum_d(j) + d(j, i)
               g = max(0.0_wp, d(j, i) - x(j))
               gap_total(j) = gap_total(j) + g
               n_open(j) = n_open(j) + merge(1.0_wp, 0.0_wp, g > 0.0_wp)
            end do
         end do
         do j = 1, nl
            if (mask(j)) wet(j) = film%engages_of_sums(fsteps(j), n, gap_total(j), n_open(j))
         end do
         return
      end if
      do j = 1, nl
         if (.not. mask(j)) cycle
         dl(1:n) = d(j, :)
         call gap_field(dl(1:n), x(j), gap(1:n))
         wet(j) = film%engages(fsteps(j), gap(1:n))
      end do
   end subroutine engaged_lanes

   !> engaged_lanes without the dry roots, for a film whose sums suffice:
   !> lane j engages iff its dry root lies above the film's engage_level
   !> x_e, i.e. iff sum_i max(0, x_e - d_i) < s_j (the push sum increases
   !> strictly above min d = 0, and is 0 below). Two vector passes over the
   !> lanes (the sums of d, then the pushes at x_e), where the dry roots
   !> take about four. At a dry root within rounding of x_e the answer may
   !> differ from engaged_lanes' at the computed root; the film's load
   !> there is nil (its mean gap is H_in), so the wet root is the dry one
   !> either way, to the balance's tolerance.
   pure subroutine engaged_by_level(nl, n, d, s, film, fsteps, mask, wet, sum_d, upper)
      integer, intent(in) :: nl, n
      real(wp), intent(in) :: d(nl, n), s(nl)
      class(film_model), intent(in) :: film
      type(film_step_type), intent(in) :: fsteps(nl)
      logical, intent(in) :: mask(nl)
      logical, intent(out) :: wet(nl)
      !> Each lane's sum(d) in element order (wet_roots takes it).
      real(wp), intent(out) :: sum_d(nl)
      !> Per lane, an upper bound of its dry root (so of its wet one): the
      !> dry balance's Newton step from x_e, which lands at or above the
      !> root of that convex function (raised by 8 ulps against rounding),
      !> or s (min d = 0) if smaller or where no element touches at x_e.
      real(wp), intent(out) :: upper(nl)
      real(wp), dimension(lanes) :: level, pushed, touching
      integer :: i, j
      call lane_sums(nl, n, d, sum_d)
      do j = 1, nl
         level(j) = 0.0_wp                     ! (a lane not asked pushes nothing there)
         if (mask(j)) level(j) = film%engage_level(fsteps(j), n, sum_d(j), s(j))
      end do
      pushed = 0.0_wp
      touching = 0.0_wp
      do i = 1, n
         do j = 1, nl
            pushed(j) = pushed(j) + max(0.0_wp, level(j) - d(j, i))
            touching(j) = touching(j) + merge(1.0_wp, 0.0_wp, d(j, i) < level(j))
         end do
      end do
      do j = 1, nl
         wet(j) = mask(j) .and. pushed(j) < s(j)
         upper(j) = s(j)
         ! (raised by 8 ulps: where the step lands on the root itself, as
         ! it does when x_e lies on the root's piece, the two roundings
         ! differ by an ulp or two; level > 0 where any element touches)
         if (wet(j) .and. touching(j) > 0.0_wp) upper(j) = min(s(j), &
            & (level(j) + (s(j) - pushed(j)) / touching(j)) * (1.0_wp + 8.0_wp * epsilon(1.0_wp)))
      end do
   end subroutine engaged_by_level

   !> Each lane's sum of d in element order, all lanes in one vector pass.
   pure subroutine lane_sums(nl, n, d, total)
      integer, intent(in) :: nl, n
      real(wp), intent(in) :: d(nl, n)
      real(wp), intent(out) :: total(nl)
      integer :: i, j
      total = 0.0_wp
      do i = 1, n
         do j = 1, nl
            total(j) = total(j) + d(j, i)
         end do
      end do
   end subroutine lane_sums

   !> Newton's step from x (f, df there) inside the bracket (lo, hi), taken
   !> (`taken`) only where df is positive and finite, |f| at most half the
   !> last |f| (f_old), and the step lands strictly inside.
   pure subroutine newton_step(f, df, f_old, x, lo, hi, x_new, taken)
      real(wp), intent(in) :: f, df, f_old, x, lo, hi
      real(wp), intent(out) :: x_new
      logical, intent(out) :: taken
      x_new = x
      taken = df > 0.0_wp .and. df < huge(1.0_wp) .and. abs(f) <= 0.5_wp * f_old
      if (.not. taken) return
      x_new = x - f / df
      taken = x_new > lo .and. x_new < hi
   end subroutine newton_step

   !> One step of a wet balance's bracket [lo, hi] at x, where f = f(x):
   !> whether the lane stops (|f| <= tol_load, or the bracket, narrowed to
   !> x on f's side, has closed on adjacent doubles).
   pure subroutine settle(f, x, tol_load, lo, hi, stops)
      real(wp), intent(in) :: f, x, tol_load
      real(wp), intent(inout) :: lo, hi
      logical, intent(out) :: stops
      stops = abs(f) <= tol_load
      if (stops) return
      if (f > 0.0_wp) then
         hi = x
      else
         lo = x
      end if
      stops = hi - lo <= 2.0_wp * epsilon(1.0_wp) * max(abs(lo), abs(hi))
   end subroutine settle

   !> Per lane in `mask`, how many d_i lie between a and b, ends included
   !> (0: the contacts d_i < x and the open gaps d_i > x are the same sets
   !> at every x between, and neither end is a breakpoint); lanes innermost,
   !> a vector loop. The other lanes count nothing.
   pure subroutine breakpoints_between(nl, n, d, mask, a, b, count)
      integer, intent(in) :: nl, n
      real(wp), intent(in) :: d(nl, n), a(nl), b(nl)
      logical, intent(in) :: mask(nl)
      real(wp), intent(out) :: count(nl)
      real(wp) :: lo(lanes), hi(lanes)
      integer :: i, j
      do j = 1, nl
         lo(j) = merge(min(a(j), b(j)), huge(1.0_wp), mask(j))
         hi(j) = merge(max(a(j), b(j)), -huge(1.0_wp), mask(j))
      end do
      count = 0.0_wp
      do i = 1, n
         do j = 1, nl
            count(j) = count(j) + merge(1.0_wp, 0.0_wp, d(j, i) >= lo(j) .and. d(j, i) <= hi(j))
         end do
      end do
   end subroutine breakpoints_between

   !> The pad's push sum max(0, x - d_i) of one lane, in element order.
   pure real(wp) function pushed_at(d, x) result(total)
      real(wp), intent(in) :: d(:), x
      integer :: i
      total = 0.0_wp
      do i = 1, size(d)
         total = total + max(0.0_wp, x - d(i))
      end do
   end function pushed_at

   !> Where to split the bracket (lo, hi) of a film whose load jumps where an
   !> element touches (film_model%jumps_at_contact: at x = d_i, where gap_i
   !> closes; f is continuous between these points and from the right at
   !> each): at the breakpoint inside it nearest to its middle `mid`; with
   !> none inside, and hi one, at the double below hi (the open side of its
   !> jump: if f there still has f(lo)'s sign, the root is the jump and the
   !> bracket has closed); else at mid. A root at a jump is then isolated in
   !> about log2 of the breakpoints in the bracket, plus one, evaluations
   !> (halving the bracket to adjacent doubles took about 50).
   pure real(wp) function breakpoint_split(d, lo, hi, mid) result(x)
      real(wp), intent(in) :: d(:), lo, hi, mid
      real(wp) :: best
      logical :: at_hi
      integer :: i
      x = mid
      best = huge(1.0_wp)
      at_hi = .false.
      do i = 1, size(d)
         if (d(i) > lo .and. d(i) < hi) then
            if (abs(d(i) - mid) < best) then
               best = abs(d(i) - mid)
               x = d(i)
            end if
         else if (d(i) == hi) then
            at_hi = .true.
         end if
      end do
      if (best < huge(1.0_wp)) return
      if (at_hi) x = max(nearest(hi, -1.0_wp), mid)
   end function breakpoint_split

   !> f, df and the film's load of the lanes in `mask` at their x (the other
   !> lanes' values are left as they are); one more evaluation each.
   pure subroutine evaluate_wet(nl, n, d, kel, load, film, fsteps, mask, x, f, df, wh, &
      & evaluations, gaps, fwork, pushed, contacts, gap_total, n_open)
      integer, intent(in) :: nl, n
      real(wp), intent(in) :: d(nl, n), kel(nl), load, x(nl)
      class(film_model), intent(in) :: film
      type(film_step_type), intent(in) :: fsteps(nl)
      logical, intent(in) :: mask(nl)
      real(wp), intent(inout) :: f(nl), df(nl), wh(nl)
      integer(i8), intent(inout) :: evaluations(nl)
      real(wp), intent(inout) :: gaps(nl, n), fwork(:, :)
      !> Per lane, x's piece: the pad's push sum, the contacts and (films
      !> whose sums suffice) the gaps' sum and the open gaps.
      real(wp), intent(out) :: pushed(lanes), contacts(lanes), gap_total(lanes), &
         & n_open(lanes)
      real(wp), dimension(lanes) :: xe, dwh
      integer :: j
      ! the lanes not evaluated sit at a harmless penetration
      do j = 1, nl
         xe(j) = merge(x(j), 0.0_wp, mask(j))
      end do
      if (film%sums_suffice()) then
         call contact_gap_sums(nl, n, d, xe, pushed, contacts, gap_total, n_open)
         call film%loads_of_sums(nl, n, fsteps, gap_total, n_open, mask, wh, dwh)
      else
         call contact_sums(nl, n, d, xe, pushed, contacts, gaps)
         call film%loads(nl, n, fsteps, gaps, mask, wh, dwh, fwork)
         gap_total = 0.0_wp                       ! (not taken: the film has the field)
         n_open = 0.0_wp
      end if
      do j = 1, nl
         if (.not. mask(j)) cycle
         f(j) = kel(j) * pushed(j) + wh(j) - load
         df(j) = kel(j) * contacts(j) + dwh(j)
         evaluations(j) = evaluations(j) + 1
      end do
   end subroutine evaluate_wet

   !> Per lane at penetration x: the pad's push sum max(0, x - d) in element
   !> order (adding +0 out of contact, without branches), the contacts, and
   !> the gap field max(0, d - x).
   pure subroutine contact_sums(nl, n, d, x, pushed, contacts, gaps)
      integer, intent(in) :: nl, n
      real(wp), intent(in) :: d(nl, n), x(nl)
      real(wp), intent(out) :: pushed(nl), contacts(nl), gaps(nl, n)
      integer :: i, j
      real(wp) :: total, counted
      if (nl == 1) then
         total = 0.0_wp                          ! one lane: a plain loop
         counted = 0.0_wp
         do i = 1, n
            total = total + merge(x(1) - d(1, i), 0.0_wp, d(1, i) < x(1))
            counted = counted + merge(1.0_wp, 0.0_wp, d(1, i) < x(1))
            gaps(1, i) = max(0.0_wp, d(1, i) - x(1))
         end do
         pushed(1) = total
         contacts(1) = counted
         return
      end if
      pushed = 0.0_wp
      contacts = 0.0_wp
      do i = 1, n
         do j = 1, nl
            pushed(j) = pushed(j) + merge(x(j) - d(j, i), 0.0_wp, d(j, i) < x(j))
            contacts(j) = contacts(j) + merge(1.0_wp, 0.0_wp, d(j, i) < x(j))
            gaps(j, i) = max(0.0_wp, d(j, i) - x(j))
         end do
      end do
   end subroutine contact_sums

   !> contact_sums without the gap field: per lane, the sum of the gaps
   !> max(0, d - x) in element order and the count of open ones (gap > 0),
   !> the same numbers a pass over the stored field would give.
   pure subroutine contact_gap_sums(nl, n, d, x, pushed, contacts, gap_total, n_open)
      integer, intent(in) :: nl, n
      real(wp), intent(in) :: d(nl, n), x(nl)
      real(wp), intent(out) :: pushed(nl), contacts(nl), gap_total(nl), n_open(nl)
      integer :: i, j
      real(wp) :: total, counted, g, gt, go
      if (nl == 1) then
         total = 0.0_wp                          ! one lane: a plain loop
         counted = 0.0_wp
         gt = 0.0_wp
         go = 0.0_wp
         do i = 1, n
            total = total + merge(x(1) - d(1, i), 0.0_wp, d(1, i) < x(1))
            counted = counted + merge(1.0_wp, 0.0_wp, d(1, i) < x(1))
            g = max(0.0_wp, d(1, i) - x(1))
            gt = gt + g
            go = go + merge(1.0_wp, 0.0_wp, g > 0.0_wp)
         end do
         pushed(1) = total
         contacts(1) = counted
         gap_total(1) = gt
         n_open(1) = go
         return
      end if
      pushed = 0.0_wp
      contacts = 0.0_wp
      gap_total = 0.0_wp
      n_open = 0.0_wp
      do i = 1, n
         do j = 1, nl
            pushed(j) = pushed(j) + merge(x(j) - d(j, i), 0.0_wp, d(j, i) < x(j))
            contacts(j) = contacts(j) + merge(1.0_wp, 0.0_wp, d(j, i) < x(j))
            g = max(0.0_wp, d(j, i) - x(j))
            gap_total(j) = gap_total(j) + g
            n_open(j) = n_open(j) + merge(1.0_wp, 0.0_wp, g > 0.0_wp)
         end do
      end do
   end subroutine contact_gap_sums

   !> The gap under each element at penetration x: max(0, d_i - x); the film
   !> components see this whole field.
   pure subroutine gap_field(d, x, gap)
      real(wp), intent(in) :: d(:), x
      real(wp), intent(out) :: gap(:)
      integer :: i
      do i = 1, size(d)
         gap(i) = max(0.0_wp, d(i) - x)
      end do
   end subroutine gap_field

end module pavefric_balance
