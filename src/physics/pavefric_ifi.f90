!> The International Friction Index (ASTM E1960) from a computed speed sweep,
!> so that a user compares pavefric with a DFT/CTM survey directly, and the
!> model's own speed constant. No I/O; two formulas of the standard and a
!> least-squares line.
!>
!> ASTM E1960: the speed constant from macrotexture, Sp = a + b MPD (km/h,
!> MPD in mm); the friction at 60 km/h of a device measuring FR(S) at S,
!> F60 = A + B FR(S) exp((S - 60)/Sp), with A, B of the DFT at 20 km/h. The
!> model's own speed constant is the slope of ln(mu) against speed, fitted
!> by least squares over the speeds where friction is positive: the Sp a
!> PIARC-style analysis of the computed curve would report.
module pavefric_ifi
   use pavefric_kinds, only: wp
   implicit none
   private

   public :: ifi_type, ifi_from_sweep

   !> Sp = sp_a + sp_b MPD (km/h, MPD in mm), ASTM E1960.
   real(wp), parameter, public :: sp_a = 14.2_wp, sp_b = 89.7_wp
   !> F60 = f60_a + f60_b DFT20 exp(-40 / Sp): the DFT at 20 km/h, ASTM E1960.
   real(wp), parameter, public :: f60_a = 0.081_wp, f60_b = 0.732_wp

   !> The index and the model's speed constant of one speed sweep.
   type :: ifi_type
      !> Whether Sp could be formed (a texture depth), and F60 (with it,
      !> friction at 20 km/h).
      logical :: has_sp = .false., has_f60 = .false.
      !> Sp from the texture (km/h), friction at 20 km/h (computed, or on the
      !> fitted line when 20 km/h was not run and the line's speeds reach
      !> within 20 km/h of it) and F60.
      real(wp) :: sp_texture = 0.0_wp, mu20 = 0.0_wp, f60 = 0.0_wp
      !> Whether friction falls with speed over two speeds or more; then the
      !> model's speed constant (km/h).
      logical :: has_speed_constant = .false.
      real(wp) :: speed_constant = 0.0_wp
   end type ifi_type

contains

   !> The IFI of friction `mu` at `speeds_kmh` on a texture of depth `mpd`
   !> (m; not positive: unknown).
   pure function ifi_from_sweep(speeds_kmh, mu, mpd) result(r)
      real(wp), intent(in) :: speeds_kmh(:), mu(:), mpd
      type(ifi_type) :: r
      real(wp) :: n, sx, sy, sxx, sxy, slope, intercept, det
      integer :: j, at20
      logical :: use(size(mu)), fitted
      use = speeds_kmh > 0.0_wp .and. mu > 0.0_wp
      n = real(count(use), wp)
      slope = 0.0_wp
      intercept = 0.0_wp
      fitted = .false.
      if (n >= 2.0_wp) then
         sx = sum(speeds_kmh, mask=use)
         sy = sum(log(mu), mask=use)
         sxx = sum(speeds_kmh**2, mask=use)
         sxy = sum(speeds_kmh * log(mu), mask=use)
         det = n * sxx - sx * sx
         if (det > 0.0_wp) then
            fitted = .true.
            slope = (n * sxy - sx * sy) / det
            intercept = (sy - slope * sx) / n
            if (slope < 0.0_wp) then
               r%has_speed_constant = .true.
               r%speed_constant = -1.0_wp / slope
            end if
         end if
      end if
      if (.not. mpd > 0.0_wp) return
      r%sp_texture = sp_a + sp_b * mpd * 1.0e3_wp
      r%has_sp = .true.
      at20 = 0
      do j = 1, size(mu)
         if (speeds_kmh(j) == 20.0_wp) at20 = j
      end do
      if (at20 > 0) then
         r%mu20 = mu(at20)
      else if (fitted) then
         ! the line carried at most 20 km/h beyond the speeds it was fitted
         ! on (attack22: F60 from 99,999 and 100,000 km/h)
         if (minval(speeds_kmh, mask=use) > 40.0_wp) return
         r%mu20 = exp(intercept + 20.0_wp * slope)
      else
         return
      end if
      r%f60 = f60_a + f60_b * r%mu20 * exp(-40.0_wp / r%sp_texture)
      r%has_f60 = .true.
   end function ifi_from_sweep

end module pavefric_ifi
