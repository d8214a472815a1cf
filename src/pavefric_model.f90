!> Physical and numerical parameters of a scene, with their defaults and
!> their validation. Every message names the namelist group, the variable
!> and the value, so the program and the Python layer report bad input alike.
module pavefric_model
   use pavefric_kinds, only: wp
   use pavefric_error, only: error_type, fatal_error
   use pavefric_format, only: to_str
   implicit none
   private

   public :: model_type, validate_model, shape_flat, shape_rounded, shape_code

   integer, parameter :: shape_flat = 0, shape_rounded = 1

   !> Everything the friction model needs besides the profile and speeds.
   !> SI units throughout.
   type :: model_type
      !> &surface mu_loc: local friction below the profile's resolution (-).
      real(wp) :: mu_loc = 0.5_wp
      !> &pad length: pad length along the sliding direction (m).
      real(wp) :: length = 0.020_wp
      !> &pad width: pad width across the sliding direction (m).
      real(wp) :: width = 0.016_wp
      !> &pad thickness: rubber thickness (m); compression beyond it is flagged.
      real(wp) :: thickness = 0.006_wp
      !> &pad load: normal load on the pad W (N).
      real(wp) :: load = 11.8_wp
      !> &pad shape: 'flat' or 'rounded' (a circular arc of radius `radius`).
      character(len=16) :: shape = "flat"
      !> &pad radius: radius of the rounded pad's arc (m).
      real(wp) :: radius = 0.05_wp
      !> &rubber stiffness: spring modulus per unit length K (N m-3).
      real(wp) :: stiffness = 1.4e8_wp
      !> &rubber viscosity: dashpot viscosity per unit length C (N s m-3).
      real(wp) :: viscosity = 1.0e2_wp
      !> &water depth: water depth, the bearing's inlet film Hin (m); 0 = dry.
      real(wp) :: depth = 0.0_wp
      !> &water viscosity: dynamic viscosity of water eta (Pa s).
      real(wp) :: water_viscosity = 1.0e-3_wp
      !> &water alpha: empirical bearing coefficient (-). Default: the value
      !> fitted on the paper's 20 km/h DFT data (docs/validation.md); the
      !> paper's 105 is in unstated units.
      real(wp) :: alpha = 11.8_wp
      !> &water beta: empirical speed exponent of the bearing (-).
      real(wp) :: beta = 1.75_wp
      !> &numerics theta_max_deg: steepest facet+friction angle (degrees).
      real(wp) :: theta_max_deg = 85.0_wp
      !> &numerics substeps: Kelvin-Voigt time steps per element spacing.
      integer :: substeps = 1
      !> &numerics elements_per_sample: pad elements per profile spacing.
      integer :: elements_per_sample = 1
      !> &numerics position_stride: advance of the pad per step, in steps.
      integer :: position_stride = 1
      !> &numerics wet_tolerance: wet load balance |residual| / W to stop at.
      real(wp) :: wet_tolerance = 1.0e-14_wp
   end type model_type

contains

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

   !> Check every parameter's range; the first violation is reported.
   pure subroutine validate_model(m, error)
      type(model_type), intent(in) :: m
      type(error_type), allocatable, intent(out) :: error

      call nonneg("surface", "mu_loc", m%mu_loc, error); if (allocated(error)) return
      call positive("pad", "length", m%length, error); if (allocated(error)) return
      call positive("pad", "width", m%width, error); if (allocated(error)) return
      call positive("pad", "thickness", m%thickness, error); if (allocated(error)) return
      call positive("pad", "load", m%load, error); if (allocated(error)) return
      if (shape_code(m%shape) < 0) then
         call fatal_error(error, "&pad shape = '" // trim(m%shape) // &
            & "': unknown (expected 'flat' or 'rounded')")
         return
      end if
      if (shape_code(m%shape) == shape_rounded) then
         call positive("pad", "radius", m%radius, error); if (allocated(error)) return
         if (.not. (m%radius > 0.5_wp * m%length)) then
            call fatal_error(error, "&pad radius = " // to_str(m%radius) // &
               & ": must exceed half the pad length (" // to_str(0.5_wp*m%length) // " m)")
            return
         end if
      end if
      call positive("rubber", "stiffness", m%stiffness, error); if (allocated(error)) return
      call nonneg("rubber", "viscosity", m%viscosity, error); if (allocated(error)) return
      call nonneg("water", "depth", m%depth, error); if (allocated(error)) return
      call positive("water", "viscosity", m%water_viscosity, error); if (allocated(error)) return
      call nonneg("water", "alpha", m%alpha, error); if (allocated(error)) return
      call nonneg("water", "beta", m%beta, error); if (allocated(error)) return
      if (.not. (m%theta_max_deg > 0.0_wp .and. m%theta_max_deg < 90.0_wp)) then
         call fatal_error(error, "&numerics theta_max_deg = " // to_str(m%theta_max_deg) // &
            & ": must lie in (0, 90) degrees")
         return
      end if
      call at_least_one("substeps", m%substeps, error); if (allocated(error)) return
      call at_least_one("elements_per_sample", m%elements_per_sample, error)
      if (allocated(error)) return
      call at_least_one("position_stride", m%position_stride, error); if (allocated(error)) return
      if (.not. (m%wet_tolerance >= epsilon(1.0_wp) .and. m%wet_tolerance < 1.0_wp)) then
         call fatal_error(error, "&numerics wet_tolerance = " // to_str(m%wet_tolerance) // &
            & ": must lie in [" // to_str(epsilon(1.0_wp)) // ", 1)")
         return
      end if
   end subroutine validate_model

   !> Finite and > 0 (NaN fails every comparison, so `.not. (x > 0)` catches it).
   pure subroutine positive(group, name, x, error)
      character(len=*), intent(in) :: group, name
      real(wp), intent(in) :: x
      type(error_type), allocatable, intent(out) :: error
      if (.not. (x > 0.0_wp .and. x <= huge(x))) &
         & call fatal_error(error, "&" // group // " " // name // " = " // to_str(x) // &
         & ": must be finite and > 0")
   end subroutine positive

   !> Finite and >= 0.
   pure subroutine nonneg(group, name, x, error)
      character(len=*), intent(in) :: group, name
      real(wp), intent(in) :: x
      type(error_type), allocatable, intent(out) :: error
      if (.not. (x >= 0.0_wp .and. x <= huge(x))) &
         & call fatal_error(error, "&" // group // " " // name // " = " // to_str(x) // &
         & ": must be finite and >= 0")
   end subroutine nonneg

   pure subroutine at_least_one(name, i, error)
      character(len=*), intent(in) :: name
      integer, intent(in) :: i
      type(error_type), allocatable, intent(out) :: error
      if (i < 1) call fatal_error(error, "&numerics " // name // " = " // to_str(i) // &
         & ": must be >= 1")
   end subroutine at_least_one

end module pavefric_model
