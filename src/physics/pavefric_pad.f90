!> The DFT pad as a component: its &pad variables (declared here, next to
!> the geometry they describe), the cross-check they need, and the shape of
!> its undeformed bottom. The pad of N elements of length element_length
!> (or the profile's spacing) presses with the load over its length and
!> width; its rubber is a rubber law (pavefric_rubber_models).
module pavefric_pad
   use pavefric_kinds, only: wp
   use pavefric_error, only: error_type, fatal_error
   use pavefric_format, only: to_str
   use pavefric_params, only: param_spec_type, param_value_type, real_param, text_param, &
      & real_value, text_value
   implicit none
   private

   public :: pad_parameters, pad_n_parameters, check_pad, pad_bottom
   public :: shape_flat, shape_rounded, shape_code

   !> The variables the pad declares.
   integer, parameter :: pad_n_parameters = 7
   !> Codes of the pad's shapes.
   integer, parameter :: shape_flat = 0, shape_rounded = 1

contains

   !> The &pad group.
   pure function pad_parameters() result(s)
      type(param_spec_type) :: s(pad_n_parameters)
      s(1) = real_param("pad", "length", "0.020", "m", "model", &
         & "pad length L along the sliding direction; the pad has N = nint(L / dx) " // &
         & "elements (23 at 0.87 mm)", lower=0.0_wp, lower_strict=.true., upper=100.0_wp, &
         & plausible_lower=1.0e-3_wp, plausible_upper=1.0_wp, &
         & plausible_note="a DFT pad is 20 mm long, a tyre's contact about 0.15 m")
      s(2) = real_param("pad", "width", "0.016", "m", "model", &
         & "pad width l across the sliding direction (at least a micrometre: the " // &
         & "element springs l dx K scale the pushes W / (l dx K), which a width of 1e-305 m " // &
         & "took beyond double precision)", lower=1.0e-6_wp, &
         & upper=100.0_wp, plausible_lower=1.0e-3_wp, plausible_upper=1.0_wp, &
         & plausible_note="a DFT pad is 16 mm wide, a tyre about 0.2 m")
      s(3) = real_param("pad", "thickness", "0.006", "m", "model", &
         & "rubber thickness; compression beyond it is reported (max_compression, a " // &
         & "warning): the linear model has no hard floor", lower=0.0_wp, lower_strict=.true., &
         & upper=100.0_wp, plausible_lower=1.0e-4_wp, plausible_upper=0.1_wp, &
         & plausible_note="rubber treads are millimetres thick")
      s(4) = real_param("pad", "load", "11.8", "N", "model", &
         & "normal load W on the pad (at least 1e-12 N: the pushes and their sums " // &
         & "scale with it, and a load of 1e-320 N made them subnormal numbers whose friction " // &
         & "was 0/0)", lower=1.0e-12_wp, upper=1.0e9_wp, &
         & plausible_lower=0.1_wp, plausible_upper=1.0e5_wp, &
         & plausible_note="a DFT slider carries 11.8 N, a car tyre about 4e3 N")
      s(5) = text_param("pad", "shape", "flat", "", "model", &
         & "'flat' (h_i = 0) or 'rounded' (a circular arc of radius across the length: " // &
         & "h_i = R - sqrt(R^2 - x_i^2), x_i from the pad centre)", choices="flat rounded")
      s(6) = real_param("pad", "radius", "0.05", "m", "model", &
         & "arc radius of a rounded pad; must exceed length / 2", lower=0.0_wp, &
         & lower_strict=.true., upper=1.0e12_wp)
      s(7) = real_param("pad", "element_length", "0.87e-3", "m", "model", &
         & "length of a pad element along the sliding direction, a property of the pad, " // &
         & "not of the instrument: the profile is low-pass filtered (the mean height over " // &
         & "one element length) and resampled to this spacing before the pad slides over " // &
         & "it, so mu_loc stands for the texture finer than element_length (default: the " // &
         & "paper's CTM spacing, for which its mu_loc values hold; docs/model.md). A closed " // &
         & "profile is resampled to a whole number of elements round its circumference. " // &
         & "0 = the profile's own spacing (the paper's discretisation).", &
         & lower=0.0_wp, upper=1.0_wp, plausible_lower=0.0_wp, plausible_upper=5.0e-3_wp, &
         & plausible_note="the paper's elements are 0.87 mm (its CTM's spacing)")
   end function pad_parameters

   !> Integer code of a pad shape name; -1 when unknown.
   pure function shape_code(name) result(code)
      character(len=*), intent(in) :: name
      integer :: code
      select case (trim(adjustl(name)))
      case ("flat")
         code = shape_flat
      case ("rounded")
         code = shape_rounded
      case default
         code = -1
      end select
   end function shape_code

   !> What spans the pad's variables: a rounded pad's arc must be wider
   !> than the pad (each value's own range is checked by the table).
   pure subroutine check_pad(specs, values, error)
      type(param_spec_type), intent(in) :: specs(:)
      type(param_value_type), intent(in) :: values(:)
      type(error_type), allocatable, intent(out) :: error
      character(len=:), allocatable :: shape
      real(wp) :: radius, length
      call text_value(specs, values, "pad", "shape", shape)
      if (shape_code(shape) < 0) then
         call fatal_error(error, "&pad shape = '" // shape // "': unknown (expected " // &
            & "'flat' or 'rounded')")
         return
      end if
      if (shape_code(shape) == shape_rounded) then
         radius = real_value(specs, values, "pad", "radius")
         length = real_value(specs, values, "pad", "length")
         if (.not. (radius > 0.5_wp * length)) then
            call fatal_error(error, "&pad radius = " // to_str(radius) // &
               & ": must exceed half the pad length (" // to_str(0.5_wp * length) // " m)")
         end if
      end if
   end subroutine check_pad

   !> The undeformed pad bottom h_i above the reference plane of each of
   !> n_el elements of width dx_el: 0 for a flat pad; for a rounded one the
   !> sagitta of a circular arc of radius r at the element's centre x_i
   !> (from the pad's centre), h_i = r - sqrt(r^2 - x_i^2).
   pure subroutine pad_bottom(shape, r, dx_el, h)
      integer, intent(in) :: shape
      real(wp), intent(in) :: r, dx_el
      real(wp), intent(out) :: h(:)
      real(wp) :: xc
      integer :: i, n_el
      n_el = size(h)
      h = 0.0_wp
      if (shape /= shape_rounded) return
      do i = 1, n_el
         xc = (real(i, wp) - 0.5_wp - 0.5_wp * real(n_el, wp)) * dx_el
         if (r < 1.0e150_wp) then
            h(i) = r - sqrt(r**2 - xc**2)
         else
            ! R**2 would overflow: the same sagitta without the square,
            ! x**2 / (R + sqrt(R - x) sqrt(R + x)) (a flat pad as R grows).
            h(i) = xc**2 / (r + sqrt(r - xc) * sqrt(r + xc))
         end if
      end do
   end subroutine pad_bottom

end module pavefric_pad
