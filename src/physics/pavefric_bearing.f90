!> The hydrodynamic pseudo-bearing of Kane et al. (2017), Eqs. 13-15.
!>
!> Wh = alpha 6 eta V**beta l L**2 / Hout**2 * B(a),  a = Hin/Hout,
!> B(a) = [ln a - 2(a-1)/(a+1)] / (a-1)**2.
!> Written as Wh = P / Hin**2 * g(a) with g(a) = a**2 B(a), which stays finite
!> as Hout -> 0 for as long as a does, and expanded in e = a - 1 near a = 1,
!> where the bracket cancels catastrophically.
module pavefric_bearing
   use pavefric_kinds, only: wp
   implicit none
   private

   public :: bearing_prefactor, hydro_load, hydro_loads, bracket_over_e2, series_threshold

   !> Below this e = a - 1 the series is used (closed-form relative error
   !> there is about 12 eps / e**2 = 4e-14; the series' truncation is < 1e-18).
   real(wp), parameter :: series_threshold = 0.25_wp
   integer, parameter :: n_terms = 32
   !> Above this e = a - 1, hydro_load scales its terms (a**2 would overflow
   !> near 1e154; 1e100 leaves a margin for the prefactor).
   real(wp), parameter :: huge_ratio = 1.0e100_wp
   integer :: n_
   !> Coefficients of B(e) = sum_{n>=3} c_n e**(n-2), c_n = (-1)**(n+1) (1/n - 2**(1-n)).
   real(wp), parameter :: coef(3:n_terms+2) = [( real((-1)**(n_+1), wp) &
      & * (1.0_wp/real(n_, wp) - 2.0_wp**(1-n_)), n_ = 3, n_terms+2 )]

contains

   !> P = alpha 6 eta V**beta l L**2 (Eq. 15's prefactor), SI units.
   pure function bearing_prefactor(alpha, beta, eta, speed, width, length) result(p)
      real(wp), intent(in) :: alpha, beta, eta, speed, width, length
      real(wp) :: p
      p = alpha * 6.0_wp * eta * speed**beta * width * length**2
   end function bearing_prefactor

   !> B(a) = [ln a - 2(a-1)/(a+1)]/(a-1)**2 and dB/da, given e = a - 1 >= 0.
   pure subroutine bracket_over_e2(e, b, db)
      real(wp), intent(in) :: e
      real(wp), intent(out) :: b, db
      real(wp) :: sr, dsr
      integer :: n
      if (e < series_threshold) then
         ! B = e S(e), S = sum_{n>=3} c_n e**(n-3): Horner on S and dS/de.
         sr = coef(n_terms+2)
         dsr = 0.0_wp
         do n = n_terms+1, 3, -1
            dsr = dsr * e + sr
            sr = sr * e + coef(n)
         end do
         b = e * sr
         db = sr + e * dsr
      else
         call bracket_closed_form(e, b, db)
      end if
   end subroutine bracket_over_e2

   !> B and dB/da in closed form, for e = a - 1 >= series_threshold.
   pure subroutine bracket_closed_form(e, b, db)
      real(wp), intent(in) :: e
      real(wp), intent(out) :: b, db
      real(wp) :: a, p
      a = 1.0_wp + e
      p = log(a) - 2.0_wp * e / (a + 1.0_wp)
      b = p / e**2
      db = 1.0_wp / (a * (a + 1.0_wp)**2) - 2.0_wp * p / e**3
   end subroutine bracket_closed_form

   !> Load carried by the film (Eq. 15) and its derivative with respect to
   !> the outlet film h_out. Zero when h_out >= h_in (no wedge); the largest
   !> finite real when h_out is 0 or so small that a overflows (a film cannot
   !> be squeezed to zero thickness).
   pure subroutine hydro_load(prefactor, h_in, h_out, wh, dwh_dhout)
      real(wp), intent(in) :: prefactor, h_in, h_out
      real(wp), intent(out) :: wh, dwh_dhout
      real(wp) :: e, a, b, db, g, dg, r, q, p
      ! No wedge, or a bearing with no strength (alpha = 0 or V = 0): no load,
      ! even as the film closes.
      if (h_out >= h_in .or. prefactor <= 0.0_wp) then
         wh = 0.0_wp
         dwh_dhout = 0.0_wp
         return
      end if
      if (h_out <= h_in * 1.0e-250_wp) then
         wh = huge(1.0_wp)
         dwh_dhout = -huge(1.0_wp)
         return
      end if
      e = (h_in - h_out) / h_out          ! = a - 1, without the rounding of a
      a = 1.0_wp + e
      if (e > huge_ratio) then
         ! A film thinner than 1e-100 of the water: a**2 and e**2 would
         ! overflow (and a**2 B(a) give Inf x 0). The same g and dg/da from
         ! ratios of order 1: r = a/e, q = e/(a+1), B = (ln a - 2q)/e**2,
         ! g = r**2 (ln a - 2q), dB/da = 1/(a (a+1)**2) - 2 (ln a - 2q)/e**3.
         r = a / e
         q = e / (a + 1.0_wp)
         p = log(a) - 2.0_wp * q
         g = r * r * p
         dg = 2.0_wp * r * p / e + r * r * (q * q / a - 2.0_wp * p / e)
         wh = prefactor / h_in**2 * g
         dwh_dhout = max(-huge(1.0_wp), -prefactor / h_in**3 * ((dg * a) * a))
         return
      end if
      call bracket_over_e2(e, b, db)
      call load_of_bracket(a, b, db, prefactor / h_in**2, prefactor / h_in**3, wh, dwh_dhout)
   end subroutine hydro_load

   !> Wh = (P / Hin**2) g(a) and dWh/dHout = -(P / Hin**3) g'(a) a**2 from
   !> B(a), dB/da and the two scales, g(a) = a**2 B(a) (da/dHout = -a**2/Hin).
   pure subroutine load_of_bracket(a, b, db, scale2, scale3, wh, dwh_dhout)
      real(wp), intent(in) :: a, b, db, scale2, scale3
      real(wp), intent(out) :: wh, dwh_dhout
      real(wp) :: g, dg
      g = a * a * b
      dg = 2.0_wp * a * b + a * a * db
      wh = scale2 * g
      dwh_dhout = -(scale3 * dg * a * a)
   end subroutine load_of_bracket

   !> hydro_load of the films in `active` (the others' wh and dwh_dhout are
   !> left as they are), given each one's prefactor P and its scales
   !> P / h_in**2 and P / h_in**3 (computed once a speed: the two divisions
   !> hydro_load takes per call). A wedge of moderate ratio (the usual case:
   !> 0.25 <= a - 1 <= 1e100) is evaluated in line, by hydro_load's own
   !> operations (the same numbers); the rest call hydro_load. One call for
   !> all the lanes of a step: the balance calls this at every Newton step
   !> on a piece.
   pure subroutine hydro_loads(nl, prefactor, scale2, scale3, h_in, h_out, active, wh, &
      & dwh_dhout)
      integer, intent(in) :: nl
      real(wp), intent(in) :: prefactor(nl), scale2(nl), scale3(nl), h_in, h_out(nl)
      logical, intent(in) :: active(nl)
      real(wp), intent(inout) :: wh(nl), dwh_dhout(nl)
      real(wp) :: e, b, db
      integer :: j
      do j = 1, nl
         if (.not. active(j)) cycle
         if (h_out(j) < h_in .and. prefactor(j) > 0.0_wp .and. h_out(j) > h_in * 1.0e-250_wp) then
            e = (h_in - h_out(j)) / h_out(j)
            if (e >= series_threshold .and. e <= huge_ratio) then
               call bracket_closed_form(e, b, db)
               call load_of_bracket(1.0_wp + e, b, db, scale2(j), scale3(j), wh(j), &
                  & dwh_dhout(j))
               cycle
            end if
         end if
         call hydro_load(prefactor(j), h_in, h_out(j), wh(j), dwh_dhout(j))
      end do
   end subroutine hydro_loads

end module pavefric_bearing
