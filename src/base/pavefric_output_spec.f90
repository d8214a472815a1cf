!> What a result variable is, as the component that produces it declares
!> it: name, units, meaning, storage type, dimensions and when it is
!> written. The model's output table (pavefric_outputs) gathers the
!> declarations of the pad and its balance, the rubber, the facets and each
!> wet model into the file's order.
module pavefric_output_spec
   implicit none
   private

   public :: output_var_type, output_var, short_long_name
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
      !> The variable's name in a few words (a plot's axis label: the
      !> NetCDF long_name); long_name is its whole description (the NetCDF
      !> comment where longer, docs/outputs.md). Empty: short_long_name's.
      character(len=:), allocatable :: short
      integer :: type = out_double
      integer :: dims = dim_speed
      !> When it is written (when_*).
      integer :: when = when_always
      !> Who declares it: 'pad', 'rubber', 'facets', 'numerics' or a wet model's name.
      character(len=:), allocatable :: owner
   end type output_var_type

contains

   !> A declaration (type default double, dims per speed, written always).
   pure function output_var(owner, name, units, long_name, type, dims, when, short) result(v)
      character(len=*), intent(in) :: owner, name, units, long_name
      integer, intent(in), optional :: type, dims, when
      character(len=*), intent(in), optional :: short
      type(output_var_type) :: v
      v%owner = owner
      v%name = name
      v%units = units
      v%long_name = long_name
      if (present(short)) then
         v%short = short
      else
         call short_long_name(long_name, v%short)
      end if
      if (present(type)) v%type = type
      if (present(dims)) v%dims = dims
      if (present(when)) v%when = when
   end function output_var

   !> A description's first words as a name: the whole where it has at most
   !> 80 characters, else up to its first ": ", " (", "; ", ". " or ", ",
   !> and at most up to the last blank within 80 characters.
   pure subroutine short_long_name(text, short)
      character(len=*), intent(in) :: text
      character(len=:), allocatable, intent(out) :: short
      integer, parameter :: limit = 80
      character(len=2), parameter :: seps(5) = [": ", " (", "; ", ". ", ", "]
      integer :: cut, i, k
      if (len(text) <= limit) then
         short = text
         return
      end if
      cut = len(text)
      do k = 1, size(seps)
         i = index(text, seps(k))
         if (i > 1) cut = min(cut, i - 1)
      end do
      if (cut > limit) then
         cut = index(text(1:limit + 1), " ", back=.true.) - 1
         if (cut < 1) cut = limit
      end if
      short = text(1:cut)
   end subroutine short_long_name

end module pavefric_output_spec
