!> What a result variable is, as the component that produces it declares
!> it: name, units, meaning, storage type, dimensions and when it is
!> written. The model's output table (pavefric_outputs) gathers the
!> declarations of the pad and its balance, the rubber, the facets and each
!> wet model into the file's order.
module pavefric_output_spec
   implicit none
   private

   public :: output_var_type, output_var
   public :: out_double, out_int64, out_int, out_flag, dim_speed, dim_position_speed
   public :: when_always, when_series, when_friction_film, when_friction_film_series, &
      & when_error_estimate, when_film_report_series

   !> Storage types (NetCDF: double, int64, int, byte 0/1 with flag meanings).
   integer, parameter :: out_double = 1, out_int64 = 2, out_int = 3, out_flag = 4
   !> Dimensions: per speed, or per position and speed (series).
   integer, parameter :: dim_speed = 1, dim_position_speed = 2
   !> When a variable is written: always; with &output series; when a film
   !> that changes the local friction ran at any speed; both; when the run
   !> estimated mu's error (&numerics tolerance or error_estimate).
   integer, parameter :: when_always = 0, when_series = 1, when_friction_film = 2, &
      & when_friction_film_series = 3, when_error_estimate = 4, when_film_report_series = 5

   !> One result variable.
   type :: output_var_type
      character(len=:), allocatable :: name, units, long_name
      integer :: type = out_double
      integer :: dims = dim_speed
      !> When it is written (when_*).
      integer :: when = when_always
      !> Who declares it: 'pad', 'rubber', 'facets', 'numerics' or a wet model's name.
      character(len=:), allocatable :: owner
   end type output_var_type

contains

   !> A declaration (type default double, dims per speed, written always).
   pure function output_var(owner, name, units, long_name, type, dims, when) result(v)
      character(len=*), intent(in) :: owner, name, units, long_name
      integer, intent(in), optional :: type, dims, when
      type(output_var_type) :: v
      v%owner = owner
      v%name = name
      v%units = units
      v%long_name = long_name
      if (present(type)) v%type = type
      if (present(dims)) v%dims = dims
      if (present(when)) v%when = when
   end function output_var

end module pavefric_output_spec
