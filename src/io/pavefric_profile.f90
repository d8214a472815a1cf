!> Texture profiles: reading them (plain text, CSV, laser profiler export,
!> NetCDF) and checking and refining heights. No physics here.
!>
!> The readers live in pavefric_profile_text (one pass over the file's
!> bytes) and pavefric_profile_netcdf (many profiles in one file); this
!> module chooses between them and is what the rest of pavefric uses.
module pavefric_profile
   use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
   use pavefric_kinds, only: wp
   use pavefric_heights, only: refine_profile, check_heights
   use pavefric_error, only: error_type, fatal_error
   use pavefric_format, only: to_str, round_sig
   use pavefric_profile_types, only: profile_type, raw_profile_type, point_location
   use pavefric_profile_file, only: read_file_head, read_whole_file
   use pavefric_profile_text, only: detect_text_format, parse_plain, parse_table
   use pavefric_profile_netcdf, only: profile_catalog_type, profile_label_type, &
      & open_profile_catalog, close_profile_catalog, list_profiles, read_catalog_profile, &
      & find_profile, read_netcdf_profile, is_netcdf_magic, first_duplicate_label
   implicit none
   private

   public :: profile_type, read_profile_text, unit_factor, refine_profile, check_heights
   public :: raw_profile_type, read_raw_profile, detect_format, point_location
   public :: profile_catalog_type, profile_label_type, open_profile_catalog, &
      & close_profile_catalog, list_profiles, read_catalog_profile, find_profile, &
      & first_duplicate_label

contains

   !> The format of a profile file from its content: 'netcdf' when it starts
   !> with a netCDF or HDF5 signature, 'captif' when a line starts with
   !> '*****DATA*****' (laser profiler export), 'csv' when the first
   !> non-comment line holds commas and a letter, 'plain' otherwise.
   subroutine detect_format(path, format, error)
      character(len=*), intent(in) :: path
      character(len=:), allocatable, intent(out) :: format
      type(error_type), allocatable, intent(out) :: error
      character(len=8) :: head
      character(len=:), allocatable :: buf
      integer :: nread
      call read_file_head(path, head, nread, error)
      if (allocated(error)) return
      if (is_netcdf_magic(head(1:nread))) then
         format = "netcdf"
         return
      end if
      call read_whole_file(path, buf, error)
      if (allocated(error)) return
      format = detect_text_format(buf)
   end subroutine detect_format

   !> Read an instrument, text or NetCDF profile with its dropouts. `format`:
   !> 'auto', 'plain', 'captif', 'csv' or 'netcdf'. Heights (and distances)
   !> are converted with `factor` metres per unit unless the file states its
   !> unit ('(mm)' in a CAPTIF or CSV header, `units` in NetCDF). For CSV,
   !> `x_column` and `z_column` name the columns (empty: the first whose name
   !> holds 'dist' or 'x', and the first holding 'height', 'depth', 'elev' or
   !> 'z'). `profile_name` chooses a profile of a multi-profile NetCDF file
   !> (absent or empty: the file's only profile).
   subroutine read_raw_profile(path, format, factor, x_column, z_column, raw, error, profile_name)
      character(len=*), intent(in) :: path, format, x_column, z_column
      real(wp), intent(in) :: factor
      type(raw_profile_type), intent(out) :: raw
      type(error_type), allocatable, intent(out) :: error
      character(len=*), intent(in), optional :: profile_name
      character(len=:), allocatable :: fmt, buf, name
      character(len=8) :: head
      integer :: nread

      fmt = trim(adjustl(format))
      name = ""
      if (present(profile_name)) name = trim(profile_name)
      select case (fmt)
      case ("auto", "plain", "captif", "csv", "netcdf")
      case default
         call fatal_error(error, "&surface format = '" // fmt // &
            & "': unknown (expected 'auto', 'plain', 'captif', 'csv' or 'netcdf')")
         return
      end select
      if (fmt == "auto") then
         call read_file_head(path, head, nread, error)
         if (allocated(error)) return
         if (is_netcdf_magic(head(1:nread))) fmt = "netcdf"
      end if
      if (fmt == "netcdf") then
         call read_netcdf_profile(path, name, factor, raw, error)
         return
      end if
      call read_whole_file(path, buf, error)
      if (allocated(error)) return
      if (fmt == "auto") fmt = detect_text_format(buf)
      if (len(name) > 0) then
         call fatal_error(error, "&surface profile_name = '" // name // "': '" // path // &
            & "' is a " // fmt // " file of one profile (profile_name chooses a profile of " // &
            & "a NetCDF file)")
         return
      end if
      raw%format = fmt
      raw%path = path
      raw%name = ""
      if (fmt == "plain") then
         call parse_plain(buf, path, factor, .true., raw, error)
         if (allocated(error)) return
         deallocate(buf)
         ! the distances' spacing is preprocess's to check (as a table's), where
         ! &preprocess resample_dx can mend it
      else
         call parse_table(buf, path, fmt, factor, x_column, z_column, raw, error)
      end if
   end subroutine read_raw_profile

   !> Metres per unit for a height unit name; 0 when unknown.
   pure function unit_factor(name) result(f)
      character(len=*), intent(in) :: name
      real(wp) :: f
      select case (trim(adjustl(name)))
      case ("m")
         f = 1.0_wp
      case ("mm")
         f = 1.0e-3_wp
      case ("um")
         f = 1.0e-6_wp
      case default
         f = 0.0_wp
      end select
   end function unit_factor

   !> Read a profile from a text file: one column of heights, or two columns
   !> (distance, height), both in `factor` metres per unit, by the plain
   !> format's rules (pavefric_profile_text, docs/profiles.md). A two-column
   !> file must have a uniform spacing (within 1 %).
   subroutine read_profile_text(path, factor, prof, error, keep_nan, lines)
      character(len=*), intent(in) :: path
      real(wp), intent(in) :: factor
      type(profile_type), intent(out) :: prof
      type(error_type), allocatable, intent(out) :: error
      !> Keep NaN heights (dropouts, as NaN) instead of refusing them.
      logical, intent(in), optional :: keep_nan
      !> The file line of each point.
      integer, allocatable, intent(out), optional :: lines(:)
      type(raw_profile_type) :: raw
      character(len=:), allocatable :: buf
      logical :: nan_ok
      real(wp) :: nan
      nan_ok = .false.
      if (present(keep_nan)) nan_ok = keep_nan
      call read_whole_file(path, buf, error)
      if (allocated(error)) return
      call parse_plain(buf, path, factor, nan_ok, raw, error)
      if (allocated(error)) return
      deallocate(buf)
      if (raw%has_x) then
         call check_uniform(path, raw%x, error)
         if (allocated(error)) return
         prof%dx = (raw%x(size(raw%x)) - raw%x(1)) / real(size(raw%x) - 1, wp)
         call move_alloc(raw%x, prof%x)
      end if
      prof%has_x = raw%has_x
      if (nan_ok .and. .not. all(raw%valid)) then
         nan = ieee_value(nan, ieee_quiet_nan)
         where (.not. raw%valid) raw%z = nan
      end if
      call move_alloc(raw%z, prof%z)
      if (present(lines)) call move_alloc(raw%line, lines)
   end subroutine read_profile_text

   !> A two-column plain file's distances: at least two, increasing, each
   !> step within 1 % of the mean.
   subroutine check_uniform(path, x, error)
      character(len=*), intent(in) :: path
      real(wp), intent(in) :: x(:)
      type(error_type), allocatable, intent(out) :: error
      real(wp) :: dx, step
      integer :: n, i
      n = size(x)
      if (n < 2) then
         call fatal_error(error, path // ": a distance column needs at least two points")
         return
      end if
      dx = (x(n) - x(1)) / real(n - 1, wp)
      if (.not. (dx > 0.0_wp)) then
         call fatal_error(error, path // ": distances do not increase")
         return
      end if
      do i = 2, n
         step = x(i) - x(i-1)
         if (abs(step - dx) > 0.01_wp * dx) then
            call fatal_error(error, path // ": non-uniform spacing at data point " // &
               & to_str(i) // " (step " // to_str(round_sig(step, 4)) // " m against the " // &
               & "mean " // to_str(round_sig(dx, 4)) // " m, more than 1 % off): the " // &
               & "distances must be evenly spaced; resample the profile (a scene: &preprocess " // &
               & "resample_dx)")
            return
         end if
      end do
   end subroutine check_uniform



end module pavefric_profile
