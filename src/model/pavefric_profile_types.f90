!> The profile types every reader fills (text, CSV, laser export, NetCDF).
!> No I/O here; pavefric_profile re-exports them, with point_location.
module pavefric_profile_types
   use pavefric_kinds, only: wp
   use pavefric_format, only: to_str
   implicit none
   private

   public :: profile_type, raw_profile_type, point_location

   !> A profile of heights z at a uniform spacing.
   type :: profile_type
      !> Heights (m), positive up.
      real(wp), allocatable :: z(:)
      !> Spacing (m); 0 when the file gave no distances.
      real(wp) :: dx = 0.0_wp
      !> Whether the file held a distance column.
      logical :: has_x = .false.
      !> The distances (m), when the file held them.
      real(wp), allocatable :: x(:)
   end type profile_type

   !> A profile as an instrument file delivers it: distances (if any),
   !> heights, which points are dropouts, and the file line of each point.
   type :: raw_profile_type
      !> Distances (m), when the file had them.
      real(wp), allocatable :: x(:)
      !> Heights (m); undefined where `valid` is false.
      real(wp), allocatable :: z(:)
      !> False for a dropout (empty, NaN or missing height).
      logical, allocatable :: valid(:)
      !> Line of the file each point came from (text formats); the point's
      !> index within its profile (NetCDF).
      integer, allocatable :: line(:)
      !> Whether distances were read.
      logical :: has_x = .false.
      !> Spacing (m) the file states without a distance per point (a NetCDF
      !> `dx`); 0 when it states none. Preprocessing uses it before any default.
      real(wp) :: dx = 0.0_wp
      !> The format that was read: 'plain', 'captif', 'csv' or 'netcdf'.
      character(len=:), allocatable :: format
      !> The file.
      character(len=:), allocatable :: path
      !> The profile's name in a multi-profile file (NetCDF); empty otherwise.
      character(len=:), allocatable :: name
      !> Distance along the road (m) of the profile, when the file gives it.
      real(wp) :: chainage = 0.0_wp
      logical :: has_chainage = .false.
   end type raw_profile_type

contains

   !> Where a point of a profile came from, for messages, from its entry in
   !> raw%line: 'path:line' for a text file, "path, profile 'name', point k"
   !> for NetCDF.
   pure function point_location(raw, line) result(text)
      type(raw_profile_type), intent(in) :: raw
      integer, intent(in) :: line
      character(len=point_location_len(raw, line)) :: text
      character(len=:), allocatable :: deferred_text
      call point_location_text(raw, line, deferred_text)
      text = deferred_text
   end function point_location

   !> The length of point_location's text.
   pure integer function point_location_len(raw, line)
      type(raw_profile_type), intent(in) :: raw
      integer, intent(in) :: line
      character(len=:), allocatable :: deferred_text
      call point_location_text(raw, line, deferred_text)
      point_location_len = len(deferred_text)
   end function point_location_len

   !> The text of point_location, into a deferred-length argument.
   pure subroutine point_location_text(raw, line, text)
      type(raw_profile_type), intent(in) :: raw
      integer, intent(in) :: line
      character(len=:), allocatable, intent(out) :: text
      text = raw%path // ":" // to_str(line)
      if (allocated(raw%format)) then
         if (raw%format == "netcdf") text = raw%path // ", profile '" // raw%name // &
            & "', point " // to_str(line)
      end if
   end subroutine point_location_text

end module pavefric_profile_types
