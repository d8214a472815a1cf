!> NetCDF profile input: one file holding many profiles (a survey), as
!> docs/profiles.md describes. Two layouts of the variable `height`:
!> - 2-D `height(profile, point)`: every profile has the point dimension's
!>   length (a 1-D `height(point)` is a file of one profile);
!> - CF contiguous ragged array: `height(obs)` and a count variable over the
!>   profile dimension whose attribute `sample_dimension` names `obs`;
!>   profile i is the next count(i) values.
!> Spacing: a `distance` coordinate (over `point`, `profile x point`, or
!> `obs`) or a `dx` variable (scalar or over `profile`); neither: the
!> scene's dx. Names: the variable with `cf_role = "profile_id"` (or named
!> `profile_name`), characters or strings; none: "1", "2", ... Optional
!> `chainage(profile)` (distance along the road). Units come from each
!> variable's `units` (m, mm, um, km); a height or distance without units is
!> in the scene's height_unit, like a text file. Packed heights
!> (scale_factor, add_offset) of any numeric type are unpacked; _FillValue
!> (else the type's netCDF default fill), every missing_value, values outside
!> valid_min/valid_max/valid_range (all in packed units, as CF says) and NaN
!> are dropouts; Inf is an error. Sizes and offsets are 64-bit (C calls
!> where netcdf-fortran's are default integers).
!>
!> Every netCDF call is checked and its error names the file and what was
!> read. A catalogue can stay open over many reads (a batch) or open and
!> close the file on each.
module pavefric_profile_netcdf
   use, intrinsic :: iso_c_binding, only: c_int, c_size_t, c_ptr, c_char, c_null_char, &
      & c_f_pointer, c_associated, c_double
   use, intrinsic :: ieee_arithmetic, only: ieee_is_nan
   use netcdf
   use pavefric_kinds, only: wp, i8
   use pavefric_error, only: error_type, fatal_error, stat_memory, stat_io, stat_internal
   use pavefric_format, only: to_str, to_lower
   use pavefric_profile_types, only: raw_profile_type
   use pavefric_profile_file, only: check_profile_file
   implicit none
   private

   public :: profile_catalog_type, profile_label_type
   public :: open_profile_catalog, close_profile_catalog, list_profiles, read_catalog_profile
   public :: find_profile, read_netcdf_profile, is_netcdf_magic, first_duplicate_label

   !> A profile's name.
   type :: profile_label_type
      character(len=:), allocatable :: s
   end type profile_label_type

   !> The profiles a NetCDF file holds, and where their values are.
   type :: profile_catalog_type
      !> The file.
      character(len=:), allocatable :: path
      !> Number of profiles.
      integer :: n_profiles = 0
      !> Their names (the file's profile ids, else "1", "2", ...).
      type(profile_label_type), allocatable :: names(:)
      !> Distance along the road (m) of each profile, when the file gives it.
      logical :: has_chainage = .false.
      real(wp), allocatable :: chainage(:)
      !> Number of points of each profile, and the first one's index in the
      !> sample dimension (1 for the 2-D layout).
      integer(i8), allocatable :: first(:), count(:)
      !> 'dense' (height over profile x point, or one profile) or 'ragged'.
      character(len=:), allocatable :: layout
      !> Open file id while open (-1: closed; reads then open it themselves).
      integer :: ncid = -1
      ! variables and how to read them
      integer :: height_id = 0, height_ndims = 0
      integer :: distance_id = 0, distance_ndims = 0
      integer :: dx_id = 0, dx_ndims = 0
      !> Metres per unit of heights and distances (0: the caller's unit).
      real(wp) :: z_metres = 0.0_wp, x_metres = 0.0_wp
      !> Packing and missing values of `height`.
      real(wp) :: scale = 1.0_wp, offset = 0.0_wp
      logical :: has_fill = .false., has_missing = .false.
      real(wp) :: fill = 0.0_wp
      !> Every value of `missing_value` (CF allows a vector).
      real(wp), allocatable :: missing(:)
      !> The valid range of the packed values (valid_min, valid_max or
      !> valid_range); outside it a value is missing.
      logical :: has_valid = .false.
      real(wp) :: valid_min = -huge(1.0_wp), valid_max = huge(1.0_wp)
   end type profile_catalog_type

   interface
      function c_nc_get_vara_string(ncid, varid, start, count, strings) &
            & bind(C, name="nc_get_vara_string") result(status)
         import :: c_int, c_size_t, c_ptr
         integer(c_int), value :: ncid, varid
         integer(c_size_t), intent(in) :: start(*), count(*)
         type(c_ptr), intent(out) :: strings(*)
         integer(c_int) :: status
      end function c_nc_get_vara_string
      function c_nc_free_string(n, strings) bind(C, name="nc_free_string") result(status)
         import :: c_int, c_size_t, c_ptr
         integer(c_size_t), value :: n
         type(c_ptr), intent(inout) :: strings(*)
         integer(c_int) :: status
      end function c_nc_free_string
      function c_nc_inq_dimlen(ncid, dimid, length) bind(C, name="nc_inq_dimlen") &
            & result(status)
         import :: c_int, c_size_t
         integer(c_int), value :: ncid, dimid
         integer(c_size_t), intent(out) :: length
         integer(c_int) :: status
      end function c_nc_inq_dimlen
      function c_nc_get_vara_double(ncid, varid, start, count, values) &
            & bind(C, name="nc_get_vara_double") result(status)
         import :: c_int, c_size_t, c_double
         integer(c_int), value :: ncid, varid
         integer(c_size_t), intent(in) :: start(*), count(*)
         real(c_double), intent(out) :: values(*)
         integer(c_int) :: status
      end function c_nc_get_vara_double
      function c_strlen(s) bind(C, name="strlen") result(n)
         import :: c_ptr, c_size_t
         type(c_ptr), value :: s
         integer(c_size_t) :: n
      end function c_strlen
   end interface

   !> The netCDF library's default fill values (unwritten values).
   real(wp), parameter :: default_fill_double = 9.9692099683868690e36_wp
   real(wp), parameter :: default_fill_float = real(9.9692099683868690e36, wp)
   !> ... of the integer types (netcdf.h NC_FILL_*); bytes have none that
   !> readers must honour (the NetCDF User Guide: a byte's every value is data).
   real(wp), parameter :: default_fill_short = -32767.0_wp, default_fill_int = -2147483647.0_wp, &
      & default_fill_ushort = 65535.0_wp, default_fill_uint = 4294967295.0_wp, &
      & default_fill_int64 = -9223372036854775806.0_wp, &
      & default_fill_uint64 = 18446744073709551614.0_wp

contains

   !> Whether the first bytes of a file are a netCDF (classic, 64-bit
   !> offset, CDF-5) or HDF5 (netCDF-4) signature.
   pure logical function is_netcdf_magic(head)
      character(len=*), intent(in) :: head
      is_netcdf_magic = .false.
      if (len(head) >= 4) then
         if (head(1:3) == "CDF" .and. (head(4:4) == achar(1) .or. head(4:4) == achar(2) .or. &
               & head(4:4) == achar(5))) is_netcdf_magic = .true.
      end if
      if (len(head) >= 8) then
         if (head(1:8) == char(137) // "HDF" // achar(13) // achar(10) // achar(26) // &
               & achar(10)) is_netcdf_magic = .true.
      end if
   end function is_netcdf_magic

   !> The profiles of a NetCDF file (names, chainage, layout); the file is
   !> closed again.
   subroutine list_profiles(path, cat, error)
      character(len=*), intent(in) :: path
      type(profile_catalog_type), intent(out) :: cat
      type(error_type), allocatable, intent(out) :: error
      call open_profile_catalog(path, cat, error)
      call close_profile_catalog(cat)
   end subroutine list_profiles

   !> Open a NetCDF profile file and read its catalogue; it stays open for
   !> read_catalog_profile until close_profile_catalog.
   subroutine open_profile_catalog(path, cat, error)
      character(len=*), intent(in) :: path
      type(profile_catalog_type), intent(out) :: cat
      type(error_type), allocatable, intent(out) :: error
      integer :: status, ncid, ndims, nvars, xtype, dimids(nf90_max_var_dims), k
      integer :: count_id, profile_dim, sample_dim, count_ndims
      integer(i8) :: nsample
      character(len=nf90_max_name) :: dimname
      character(len=:), allocatable :: text

      cat%path = path
      call check_profile_file(path, error)
      if (allocated(error)) return
      status = nf90_open(path, nf90_nowrite, ncid)
      if (status /= nf90_noerr) then
         call fatal_error(error, "&surface profile_file = '" // path // &
            & "': cannot open as NetCDF (" // trim(nf90_strerror(status)) // "); a text " // &
            & "profile? set &surface format = 'auto'")
         return
      end if
      cat%ncid = ncid

      ! height: the values, 1-D or 2-D
      status = nf90_inq_varid(ncid, "height", cat%height_id)
      if (status /= nf90_noerr) then
         call fail(cat, "no variable 'height' (a NetCDF profile file holds height over " // &
            & "(profile, point) or a ragged height(obs) with a count variable)", error)
         return
      end if
      call check(cat, nf90_inquire_variable(ncid, cat%height_id, xtype=xtype, ndims=ndims, &
         & dimids=dimids), "variable 'height'", error)
      if (allocated(error)) return
      if (xtype == nf90_char .or. xtype == 12) then
         call fail(cat, "variable 'height' is text, not numbers", error)
         return
      end if
      if (ndims < 1 .or. ndims > 2) then
         call fail(cat, "variable 'height' has " // to_str(ndims) // &
            & " dimensions (expected (profile, point), (point) or a ragged (obs))", error)
         return
      end if
      cat%height_ndims = ndims
      sample_dim = dimids(1)                       ! Fortran order: the fastest first
      call dim_length(cat, sample_dim, nsample, error)
      if (allocated(error)) return
      profile_dim = -1
      count_id = 0
      if (ndims == 2) then
         profile_dim = dimids(2)
      else
         ! a ragged array: a variable with sample_dimension = this dimension
         call check(cat, nf90_inquire_dimension(ncid, sample_dim, name=dimname), &
            & "dimensions", error)
         if (allocated(error)) return
         call check(cat, nf90_inquire(ncid, nVariables=nvars), "variables", error)
         if (allocated(error)) return
         do k = 1, nvars
            if (nf90_inquire_attribute(ncid, k, "sample_dimension") /= nf90_noerr) cycle
            call text_attribute(cat, k, "sample_dimension", text, error)
            if (allocated(error)) return
            if (trim(text) /= trim(dimname)) cycle
            count_id = k
            call check(cat, nf90_inquire_variable(ncid, k, ndims=count_ndims, dimids=dimids), &
               & "the count variable", error)
            if (allocated(error)) return
            if (count_ndims /= 1) then
               call fail(cat, "the count variable (sample_dimension = '" // trim(dimname) // &
                  & "') must have one dimension, the profiles", error)
               return
            end if
            profile_dim = dimids(1)
            exit
         end do
      end if

      ! the profiles and where each one's points are
      if (profile_dim < 0) then
         cat%layout = "dense"
         cat%n_profiles = 1
         allocate(cat%first(1), cat%count(1))
         cat%first = 1
         cat%count = nsample
      else
         call dim_length(cat, profile_dim, nsample, error, profiles=.true.)
         if (allocated(error)) return
         if (count_id == 0) then
            cat%layout = "dense"
            call dim_length(cat, sample_dim, nsample, error)
            if (allocated(error)) return
            allocate(cat%first(cat%n_profiles), cat%count(cat%n_profiles), stat=count_ndims)
            if (count_ndims /= 0) then
               call fail(cat, "not enough memory for " // to_str(cat%n_profiles) // &
                  & " profiles", error, stat_memory)
               return
            end if
            cat%first = 1
            cat%count = nsample
         else
            cat%layout = "ragged"
            call ragged_counts(cat, count_id, sample_dim, error)
            if (allocated(error)) return
         end if
      end if
      if (cat%n_profiles == 0) then
         call fail(cat, "holds no profiles (the profile dimension is empty)", error)
         return
      end if

      ! units and packing of the heights
      call length_unit(cat, cat%height_id, "height", cat%z_metres, error)
      if (allocated(error)) return
      call real_attribute(cat, cat%height_id, "scale_factor", cat%scale, error)
      if (allocated(error)) return
      call real_attribute(cat, cat%height_id, "add_offset", cat%offset, error)
      if (allocated(error)) return
      cat%has_fill = nf90_inquire_attribute(ncid, cat%height_id, "_FillValue") == nf90_noerr
      if (cat%has_fill) call real_attribute(cat, cat%height_id, "_FillValue", cat%fill, error)
      if (allocated(error)) return
      if (.not. cat%has_fill) then
         cat%has_fill = .true.
         select case (xtype)
         case (nf90_double)
            cat%fill = default_fill_double
         case (nf90_float)
            cat%fill = default_fill_float
         case (nf90_short)
            cat%fill = default_fill_short
         case (nf90_int)
            cat%fill = default_fill_int
         case (nf90_ushort)
            cat%fill = default_fill_ushort
         case (nf90_uint)
            cat%fill = default_fill_uint
         case (nf90_int64)
            cat%fill = default_fill_int64
         case (nf90_uint64)
            cat%fill = default_fill_uint64
         case default
            cat%has_fill = .false.
         end select
      end if
      cat%has_missing = nf90_inquire_attribute(ncid, cat%height_id, "missing_value") == &
         & nf90_noerr
      if (cat%has_missing) call real_attribute(cat, cat%height_id, "missing_value", &
         & cat%fill, error, all_values=cat%missing)
      if (allocated(error)) return
      ! CF: values outside valid_min..valid_max (or valid_range) are missing
      call valid_range(cat, error)
      if (allocated(error)) return

      ! spacing: distances, or dx
      call spacing_variables(cat, sample_dim, profile_dim, error)
      if (allocated(error)) return
      call profile_names(cat, profile_dim, error)
      if (allocated(error)) return
      call check_names(cat, error)
      if (allocated(error)) return
      call chainage_variable(cat, profile_dim, error)
   end subroutine open_profile_catalog

   !> Names index the profiles (find_profile, a batch's output): each must
   !> be given and differ from every other.
   subroutine check_names(cat, error)
      type(profile_catalog_type), intent(inout) :: cat
      type(error_type), allocatable, intent(out) :: error
      integer :: k, i, j
      do k = 1, cat%n_profiles
         if (len_trim(cat%names(k)%s) == 0) then
            call fail(cat, "profile " // to_str(k) // " of " // to_str(cat%n_profiles) // &
               & " has an empty name; every profile needs a name of its own (or drop the " // &
               & "names variable: the profiles are then named 1, 2, ...)", error)
            return
         end if
      end do
      call first_duplicate_label(cat%names, i, j)
      if (i == 0) return
      if (i < 0) then
         call fail(cat, "not enough memory to check the names of " // to_str(cat%n_profiles) // &
            & " profiles", error, stat_memory)
         return
      end if
      call fail(cat, "profiles " // to_str(min(i, j)) // " and " // to_str(max(i, j)) // &
         & " are both named '" // cat%names(i)%s // "'; every profile needs a name of its " // &
         & "own (names index the profiles and the output)", error)
   end subroutine check_names

   !> Indices of two equal names (i = 0 when all differ; i = -1 when memory
   !> is short): a merge sort of the indices, then neighbours compared;
   !> n log n for long lists.
   subroutine first_duplicate_label(s, i, j)
      type(profile_label_type), intent(in) :: s(:)
      integer, intent(out) :: i, j
      integer, allocatable :: order(:), work(:)
      integer :: k, n
      n = size(s)
      i = 0
      j = 0
      allocate(order(n), work(n), stat=k)
      if (k /= 0) then
         i = -1
         return
      end if
      order = [(k, k = 1, n)]
      call sort(1, n)
      do k = 1, n - 1
         if (s(order(k))%s == s(order(k+1))%s .and. &
               & len(s(order(k))%s) == len(s(order(k+1))%s)) then
            i = order(k)
            j = order(k+1)
            return
         end if
      end do
   contains
      recursive subroutine sort(lo, hi)
         integer, intent(in) :: lo, hi
         integer :: mid, a, b, k
         if (hi <= lo) return
         mid = (lo + hi) / 2
         call sort(lo, mid)
         call sort(mid + 1, hi)
         a = lo
         b = mid + 1
         do k = lo, hi
            if (b > hi) then
               work(k) = order(a); a = a + 1
            else if (a > mid) then
               work(k) = order(b); b = b + 1
            else if (.not. llt(s(order(b))%s, s(order(a))%s)) then
               work(k) = order(a); a = a + 1
            else
               work(k) = order(b); b = b + 1
            end if
         end do
         order(lo:hi) = work(lo:hi)
      end subroutine sort
   end subroutine first_duplicate_label

   !> Close the file of an open catalogue (its contents stay).
   subroutine close_profile_catalog(cat)
      type(profile_catalog_type), intent(inout) :: cat
      integer :: status
      if (cat%ncid >= 0) status = nf90_close(cat%ncid)
      cat%ncid = -1
   end subroutine close_profile_catalog

   !> Index of the profile named `name`; empty: the file's only profile.
   subroutine find_profile(cat, name, i, error)
      type(profile_catalog_type), intent(in) :: cat
      character(len=*), intent(in) :: name
      integer, intent(out) :: i
      type(error_type), allocatable, intent(out) :: error
      integer :: k, hits
      i = 0
      if (len_trim(name) == 0) then
         if (cat%n_profiles == 1) then
            i = 1
         else
            call fatal_error(error, "&surface profile_name: not given, and '" // cat%path // &
               & "' holds " // to_str(cat%n_profiles) // " profiles (" // some_names(cat) // &
               & "): name one")
         end if
         return
      end if
      hits = 0
      do k = 1, cat%n_profiles
         if (cat%names(k)%s == trim(name)) then
            hits = hits + 1
            if (i == 0) i = k
         end if
      end do
      if (hits == 0) then
         call fatal_error(error, "&surface profile_name = '" // trim(name) // &
            & "': no such profile in '" // cat%path // "' (it holds " // &
            & to_str(cat%n_profiles) // ": " // some_names(cat) // ")")
         i = 0
      else if (hits > 1) then
         call fatal_error(error, "&surface profile_name = '" // trim(name) // "': " // &
            & to_str(hits) // " profiles of '" // cat%path // "' have this name")
         i = 0
      end if
   end subroutine find_profile

   !> The profile named `name` (empty: the only one) of a NetCDF file.
   subroutine read_netcdf_profile(path, name, factor, raw, error)
      character(len=*), intent(in) :: path, name
      real(wp), intent(in) :: factor
      type(raw_profile_type), intent(out) :: raw
      type(error_type), allocatable, intent(out) :: error
      type(profile_catalog_type) :: cat
      integer :: i
      call open_profile_catalog(path, cat, error)
      if (.not. allocated(error)) call find_profile(cat, name, i, error)
      if (.not. allocated(error)) call read_catalog_profile(cat, i, factor, raw, error)
      call close_profile_catalog(cat)
   end subroutine read_netcdf_profile

   !> Profile i (1-based) of a catalogue, heights and distances times the
   !> file's units (or `factor` metres per unit where it states none).
   subroutine read_catalog_profile(cat, i, factor, raw, error)
      type(profile_catalog_type), intent(inout) :: cat
      integer, intent(in) :: i
      real(wp), intent(in) :: factor
      type(raw_profile_type), intent(out) :: raw
      type(error_type), allocatable, intent(out) :: error
      real(wp), allocatable :: z(:)
      real(wp) :: zf, xf, dx(1), v
      integer :: status, st, k
      integer(i8) :: n
      logical :: opened_here

      if (i < 1 .or. i > cat%n_profiles) then
         call fatal_error(error, "profile " // to_str(i) // " of '" // cat%path // &
            & "': out of range (it holds " // to_str(cat%n_profiles) // ")", stat_internal)
         return
      end if
      opened_here = cat%ncid < 0
      if (opened_here) then
         status = nf90_open(cat%path, nf90_nowrite, cat%ncid)
         if (status /= nf90_noerr) then
            cat%ncid = -1
            call fatal_error(error, "&surface profile_file = '" // cat%path // &
               & "': cannot open as NetCDF (" // trim(nf90_strerror(status)) // ")")
            return
         end if
      end if
      raw%format = "netcdf"
      raw%path = cat%path
      raw%name = cat%names(i)%s
      raw%has_chainage = cat%has_chainage
      if (cat%has_chainage) raw%chainage = cat%chainage(i)
      n = cat%count(i)
      if (n > huge(1)) then
         call fatal_error(error, where(cat, i) // ": holds " // to_str(n) // " points, more " // &
            & "than " // to_str(huge(1)) // "; split the profile into shorter ones")
         call done()
         return
      end if
      if (n == 0) then
         call fatal_error(error, where(cat, i) // ": holds no heights")
         call done()
         return
      end if
      allocate(z(n), raw%valid(n), raw%line(n), stat=st)
      if (st /= 0) then
         call fatal_error(error, where(cat, i) // ": not enough memory for " // to_str(n) // &
            & " points", stat_memory)
         call done()
         return
      end if
      zf = cat%z_metres
      if (zf <= 0.0_wp) zf = factor
      xf = cat%x_metres
      if (xf <= 0.0_wp) xf = factor
      call get_values(cat, cat%height_id, cat%height_ndims, i, z, "height", error)
      if (allocated(error)) then
         call done()
         return
      end if
      do k = 1, int(n)
         raw%line(k) = k
         v = z(k)
         raw%valid(k) = .not. (ieee_is_nan(v) .or. (cat%has_fill .and. v == cat%fill))
         if (raw%valid(k) .and. cat%has_missing) raw%valid(k) = .not. any(v == cat%missing)
         if (raw%valid(k) .and. cat%has_valid) raw%valid(k) = v >= cat%valid_min .and. &
            & v <= cat%valid_max
         if (.not. raw%valid(k)) then
            z(k) = 0.0_wp
            cycle
         end if
         if (cat%scale /= 1.0_wp .or. cat%offset /= 0.0_wp) v = v * cat%scale + cat%offset
         if (.not. (abs(v) <= huge(v))) then
            call fatal_error(error, where(cat, i) // ", point " // to_str(k) // ": height " // &
               & to_str(v) // " is not finite")
            call done()
            return
         end if
         z(k) = v * zf
      end do
      call move_alloc(z, raw%z)
      if (cat%distance_id > 0) then
         allocate(raw%x(n), stat=st)
         if (st /= 0) then
            call fatal_error(error, where(cat, i) // ": not enough memory for " // &
               & to_str(n) // " distances", stat_memory)
            call done()
            return
         end if
         call get_values(cat, cat%distance_id, cat%distance_ndims, i, raw%x, "distance", error)
         if (allocated(error)) then
            call done()
            return
         end if
         do k = 1, int(n)
            if (.not. (abs(raw%x(k)) <= huge(v))) then
               call fatal_error(error, where(cat, i) // ", point " // to_str(k) // &
                  & ": distance " // to_str(raw%x(k)) // " is not finite")
               call done()
               return
            end if
            raw%x(k) = raw%x(k) * xf
            if (k > 1) then
               if (.not. raw%x(k) > raw%x(k-1)) then
                  call fatal_error(error, where(cat, i) // ", point " // to_str(k) // &
                     & ": distances do not increase")
                  call done()
                  return
               end if
            end if
         end do
         raw%has_x = .true.
      else if (cat%dx_id > 0) then
         if (cat%dx_ndims == 0) then
            call check(cat, nf90_get_var(cat%ncid, cat%dx_id, dx(1)), "variable 'dx'", error)
         else
            call check(cat, nf90_get_var(cat%ncid, cat%dx_id, dx, start=[i], count=[1]), &
               & "variable 'dx'", error)
         end if
         if (allocated(error)) then
            call done()
            return
         end if
         if (.not. (dx(1) > 0.0_wp .and. dx(1) <= huge(v))) then
            call fatal_error(error, where(cat, i) // ": dx = " // to_str(dx(1)) // &
               & ": must be finite and > 0")
            call done()
            return
         end if
         raw%dx = dx(1) * xf
      end if
      call done()
   contains
      subroutine done()
         if (opened_here) call close_profile_catalog(cat)
      end subroutine done
   end subroutine read_catalog_profile

   !> Values of profile i of a 1-D (single or ragged) or 2-D variable.
   subroutine get_values(cat, varid, ndims, i, values, what, error)
      type(profile_catalog_type), intent(inout) :: cat
      integer, intent(in) :: varid, ndims, i
      real(wp), intent(out) :: values(:)
      character(len=*), intent(in) :: what
      type(error_type), allocatable, intent(out) :: error
      integer :: status
      integer(c_size_t) :: start(2), count(2)
      ! the C call: 64-bit offsets (a ragged profile past 2^31 points); C's
      ! dimension order is the reverse of Fortran's, ids count from 0
      if (ndims == 2) then
         start = [int(i - 1, c_size_t), 0_c_size_t]
         count = [1_c_size_t, int(size(values), c_size_t)]
      else if (cat%layout == "ragged") then
         start(1) = int(cat%first(i) - 1, c_size_t)
         count(1) = int(size(values), c_size_t)
      else
         start(1) = 0
         count(1) = int(size(values), c_size_t)
      end if
      status = int(c_nc_get_vara_double(int(cat%ncid, c_int), int(varid - 1, c_int), start, &
         & count, values))
      if (status /= nf90_noerr) call fatal_error(error, where(cat, i) // ": reading '" // &
         & what // "' failed (" // trim(nf90_strerror(status)) // ")", stat_io)
   end subroutine get_values

   !> Counts of a ragged layout, their offsets, and their check against the
   !> sample dimension.
   subroutine ragged_counts(cat, count_id, sample_dim, error)
      type(profile_catalog_type), intent(inout) :: cat
      integer, intent(in) :: count_id, sample_dim
      type(error_type), allocatable, intent(out) :: error
      integer(i8), allocatable :: c(:)
      integer(i8) :: nsample, total
      integer :: k, st
      character(len=nf90_max_name) :: name
      call check(cat, nf90_inquire_variable(cat%ncid, count_id, name=name), "the count variable", &
         & error)
      if (allocated(error)) return
      call dim_length(cat, sample_dim, nsample, error)
      if (allocated(error)) return
      allocate(c(cat%n_profiles), cat%first(cat%n_profiles), cat%count(cat%n_profiles), stat=st)
      if (st /= 0) then
         call fail(cat, "not enough memory for " // to_str(cat%n_profiles) // " profiles", &
            & error, stat_memory)
         return
      end if
      call check(cat, nf90_get_var(cat%ncid, count_id, c), "the count variable", error)
      if (allocated(error)) return
      total = 0
      do k = 1, cat%n_profiles
         if (c(k) < 0) then
            call fail(cat, "count of profile " // to_str(k) // " is " // to_str(c(k)) // &
               & " (must be >= 0)", error)
            return
         end if
         ! checked before adding: a sum past 2^63 would wrap and pass
         if (c(k) > nsample - total) then
            call fail(cat, "variable '" // trim(name) // "' (the ragged counts): profile " // &
               & to_str(k) // " has count " // to_str(c(k)) // ", but only " // &
               & to_str(nsample - total) // " of the " // to_str(nsample) // " points of " // &
               & "'height' are left after profiles 1 to " // to_str(k - 1) // "; fix the " // &
               & "counts so that they add up to the sample dimension", error)
            return
         end if
         cat%first(k) = total + 1
         cat%count(k) = c(k)
         total = total + c(k)
      end do
      if (total /= nsample) then
         call fail(cat, "the counts add up to " // to_str(total) // " points but 'height' has " &
            & // to_str(nsample) // " (variable '" // trim(name) // "')", error)
      end if
   end subroutine ragged_counts

   !> The `distance` or `dx` variable, checked against the layout.
   subroutine spacing_variables(cat, sample_dim, profile_dim, error)
      type(profile_catalog_type), intent(inout) :: cat
      integer, intent(in) :: sample_dim, profile_dim
      type(error_type), allocatable, intent(out) :: error
      integer :: varid, ndims, dimids(nf90_max_var_dims)
      logical :: ok
      if (nf90_inq_varid(cat%ncid, "distance", varid) == nf90_noerr) then
         call check(cat, nf90_inquire_variable(cat%ncid, varid, ndims=ndims, dimids=dimids), &
            & "variable 'distance'", error)
         if (allocated(error)) return
         ok = .false.
         if (ndims == 1) ok = dimids(1) == sample_dim
         if (ndims == 2 .and. cat%height_ndims == 2) ok = dimids(1) == sample_dim .and. &
            & dimids(2) == profile_dim
         if (.not. ok) then
            call fail(cat, "variable 'distance' must have the dimensions of 'height' or " // &
               & "its point dimension alone", error)
            return
         end if
         cat%distance_id = varid
         ! distance(point) shared by the profiles of a 2-D layout: read as 1-D
         cat%distance_ndims = ndims
         if (ndims == 1 .and. cat%layout == "dense") cat%distance_ndims = 1
         call length_unit(cat, varid, "distance", cat%x_metres, error)
      else if (nf90_inq_varid(cat%ncid, "dx", varid) == nf90_noerr) then
         call check(cat, nf90_inquire_variable(cat%ncid, varid, ndims=ndims, dimids=dimids), &
            & "variable 'dx'", error)
         if (allocated(error)) return
         ok = ndims == 0
         if (ndims == 1) ok = dimids(1) == profile_dim
         if (.not. ok) then
            call fail(cat, "variable 'dx' must be a scalar or have the profile dimension", error)
            return
         end if
         cat%dx_id = varid
         cat%dx_ndims = ndims
         call length_unit(cat, varid, "dx", cat%x_metres, error)
      end if
   end subroutine spacing_variables

   !> Names of the profiles: the variable with cf_role = "profile_id", else
   !> `profile_name`; characters (profile, length) or strings (profile).
   subroutine profile_names(cat, profile_dim, error)
      type(profile_catalog_type), intent(inout) :: cat
      integer, intent(in) :: profile_dim
      type(error_type), allocatable, intent(out) :: error
      integer :: nvars, k, varid, xtype, ndims, dimids(nf90_max_var_dims), st, len_chars
      integer(i8) :: nchar, at
      character(len=:), allocatable :: text, chars
      type(c_ptr), allocatable :: ptrs(:)
      integer(c_size_t) :: start(1), count(1)
      character(kind=c_char), pointer :: p(:)
      integer(c_size_t) :: m

      allocate(cat%names(cat%n_profiles), stat=st)
      if (st /= 0) then
         call fail(cat, "not enough memory for " // to_str(cat%n_profiles) // " names", error, &
            & stat_memory)
         return
      end if
      varid = 0
      call check(cat, nf90_inquire(cat%ncid, nVariables=nvars), "variables", error)
      if (allocated(error)) return
      do k = 1, nvars
         if (nf90_inquire_attribute(cat%ncid, k, "cf_role") /= nf90_noerr) cycle
         call text_attribute(cat, k, "cf_role", text, error)
         if (allocated(error)) return
         if (trim(text) == "profile_id") then
            varid = k
            exit
         end if
      end do
      if (varid == 0) then
         if (nf90_inq_varid(cat%ncid, "profile_name", k) == nf90_noerr) varid = k
      end if
      if (varid == 0) then
         do k = 1, cat%n_profiles
            cat%names(k)%s = to_str(k)
         end do
         return
      end if
      call check(cat, nf90_inquire_variable(cat%ncid, varid, xtype=xtype, ndims=ndims, &
         & dimids=dimids), "the profile names", error)
      if (allocated(error)) return
      if (xtype == nf90_char) then
         ok_char: block
            if (ndims == 1 .and. profile_dim < 0) then
               exit ok_char                               ! one profile, one name
            else if (ndims == 2) then
               if (dimids(2) == profile_dim) exit ok_char
            end if
            call fail(cat, "the profile names must be characters over (profile, length)", error)
            return
         end block ok_char
         call dim_length(cat, dimids(1), nchar, error)
         if (allocated(error)) return
         if (nchar > 65536) then
            call fail(cat, "the profile names are " // to_str(nchar) // " characters " // &
               & "long (at most 65536)", error)
            return
         end if
         len_chars = int(nchar)
         ! all names in one read: (length, profile) in Fortran order; the
         ! size in 64 bits (65,537 names of 32,768 characters pass 2^31)
         allocate(character(len=int(len_chars, i8) * cat%n_profiles) :: chars, stat=st)
         if (st /= 0) then
            call fail(cat, "not enough memory for " // to_str(cat%n_profiles) // " names", &
               & error, stat_memory)
            return
         end if
         if (len(chars) > 0) then
            if (ndims == 2) then
               call check(cat, nf90_get_var(cat%ncid, varid, chars, start=[1, 1], &
                  & count=[len_chars, cat%n_profiles]), "the profile names", error)
            else
               call check(cat, nf90_get_var(cat%ncid, varid, chars, start=[1], &
                  & count=[len_chars]), "the profile names", error)
            end if
         end if
         if (allocated(error)) return
         do k = 1, cat%n_profiles
            at = int(k - 1, i8) * len_chars
            text = chars(at + 1:at + len_chars)
            m = index(text, c_null_char)
            if (m > 0) then
               cat%names(k)%s = trim(text(1:m-1))
            else
               cat%names(k)%s = trim(text)
            end if
         end do
      else if (xtype == 12) then                     ! NC_STRING
         if (.not. ((ndims == 1 .and. dimids(1) == profile_dim) .or. &
               & (ndims == 0 .and. profile_dim < 0))) then
            call fail(cat, "the profile names must be strings over the profile dimension", error)
            return
         end if
         allocate(ptrs(cat%n_profiles), stat=st)
         if (st /= 0) then
            call fail(cat, "not enough memory for " // to_str(cat%n_profiles) // " names", &
               & error, stat_memory)
            return
         end if
         start = 0
         count = int(cat%n_profiles, c_size_t)
         st = c_nc_get_vara_string(int(cat%ncid, c_int), int(varid - 1, c_int), start, count, &
            & ptrs)
         if (st /= nf90_noerr) then
            call fail(cat, "reading the profile names failed (" // trim(nf90_strerror(st)) // &
               & ")", error, stat_io)
            return
         end if
         do k = 1, cat%n_profiles
            cat%names(k)%s = ""
            if (.not. c_associated(ptrs(k))) cycle
            m = c_strlen(ptrs(k))
            call c_f_pointer(ptrs(k), p, [m])
            text = repeat(" ", int(m))
            do st = 1, int(m)
               text(st:st) = p(st)
            end do
            cat%names(k)%s = trim(text)
         end do
         st = c_nc_free_string(int(cat%n_profiles, c_size_t), ptrs)
      else
         call fail(cat, "the profile names must be text (characters or strings)", error)
      end if
   end subroutine profile_names

   !> `chainage(profile)`, in metres.
   subroutine chainage_variable(cat, profile_dim, error)
      type(profile_catalog_type), intent(inout) :: cat
      integer, intent(in) :: profile_dim
      type(error_type), allocatable, intent(out) :: error
      integer :: varid, ndims, dimids(nf90_max_var_dims), k
      real(wp) :: f
      if (nf90_inq_varid(cat%ncid, "chainage", varid) /= nf90_noerr) return
      call check(cat, nf90_inquire_variable(cat%ncid, varid, ndims=ndims, dimids=dimids), &
         & "variable 'chainage'", error)
      if (allocated(error)) return
      if (.not. ((ndims == 1 .and. dimids(1) == profile_dim) .or. &
            & (ndims == 0 .and. profile_dim < 0))) then
         call fail(cat, "variable 'chainage' must have the profile dimension", error)
         return
      end if
      allocate(cat%chainage(cat%n_profiles), stat=k)
      if (k /= 0) then
         call fail(cat, "not enough memory for " // to_str(cat%n_profiles) // " chainages", &
            & error, stat_memory)
         return
      end if
      call check(cat, nf90_get_var(cat%ncid, varid, cat%chainage), "variable 'chainage'", error)
      if (allocated(error)) return
      call length_unit(cat, varid, "chainage", f, error)
      if (allocated(error)) return
      if (f <= 0.0_wp) f = 1.0_wp                   ! chainage without units: metres
      do k = 1, cat%n_profiles
         if (.not. (abs(cat%chainage(k)) <= huge(f))) then
            call fail(cat, "variable 'chainage': profile " // to_str(k) // " ('" // &
               & cat%names(k)%s // "') has chainage " // to_str(cat%chainage(k)) // &
               & "; chainage must be finite (a distance along the road)", error)
            return
         end if
         cat%chainage(k) = cat%chainage(k) * f
         if (abs(cat%chainage(k)) > 1.0e9_wp) then
            ! NetCDF's default fill value of doubles is 9.97e36
            call fail(cat, "variable 'chainage': profile " // to_str(k) // " ('" // &
               & cat%names(k)%s // "') has chainage " // to_str(cat%chainage(k)) // &
               & " m, farther than any road (1e9 m); a fill value or missing datum? " // &
               & "give every profile its distance along the road", error)
            return
         end if
      end do
      cat%has_chainage = .true.
   end subroutine chainage_variable

   !> Metres per unit of a variable's `units` (0 when it has none).
   subroutine length_unit(cat, varid, what, f, error)
      type(profile_catalog_type), intent(inout) :: cat
      integer, intent(in) :: varid
      character(len=*), intent(in) :: what
      real(wp), intent(out) :: f
      type(error_type), allocatable, intent(out) :: error
      character(len=:), allocatable :: units
      f = 0.0_wp
      if (nf90_inquire_attribute(cat%ncid, varid, "units") /= nf90_noerr) return
      call text_attribute(cat, varid, "units", units, error)
      if (allocated(error)) return
      select case (to_lower(trim(adjustl(units))))
      case ("m", "metre", "metres", "meter", "meters")
         f = 1.0_wp
      case ("mm", "millimetre", "millimetres", "millimeter", "millimeters", "1e-3 m")
         f = 1.0e-3_wp
      case ("um", char(194) // char(181) // "m", char(206) // char(188) // "m", &
            & "micrometre", "micrometres", "micrometer", "micrometers", "micron", "microns", &
            & "1e-6 m")
         f = 1.0e-6_wp
      case ("km", "kilometre", "kilometres", "kilometer", "kilometers")
         f = 1.0e3_wp
      case default
         call fail(cat, "variable '" // what // "': units = '" // units // &
            & "' is not a length unit pavefric knows (m, mm, um, km)", error)
      end select
   end subroutine length_unit

   !> A text attribute's value.
   subroutine text_attribute(cat, varid, name, text, error)
      type(profile_catalog_type), intent(inout) :: cat
      integer, intent(in) :: varid
      character(len=*), intent(in) :: name
      character(len=:), allocatable, intent(out) :: text
      type(error_type), allocatable, intent(out) :: error
      integer :: xtype, n
      text = ""
      call check(cat, nf90_inquire_attribute(cat%ncid, varid, name, xtype=xtype, len=n), &
         & "attribute " // name, error)
      if (allocated(error)) return
      if (xtype /= nf90_char) then
         call fail(cat, "attribute '" // name // "' must be text", error)
         return
      end if
      text = repeat(" ", n)
      if (n > 0) call check(cat, nf90_get_att(cat%ncid, varid, name, text), "attribute " // &
         & name, error)
   end subroutine text_attribute

   !> A numeric attribute's (first) value, if present; else `value` stays.
   subroutine real_attribute(cat, varid, name, value, error, all_values)
      type(profile_catalog_type), intent(inout) :: cat
      integer, intent(in) :: varid
      character(len=*), intent(in) :: name
      real(wp), intent(inout) :: value
      type(error_type), allocatable, intent(out) :: error
      !> Every value of the attribute (`value` is then left as it is).
      real(wp), allocatable, intent(out), optional :: all_values(:)
      integer :: xtype, n
      real(wp), allocatable :: values(:)
      if (nf90_inquire_attribute(cat%ncid, varid, name, xtype=xtype, len=n) /= nf90_noerr) return
      if (xtype == nf90_char .or. xtype == 12 .or. n < 1) then
         call fail(cat, "attribute '" // name // "' of 'height' must be a number", error)
         return
      end if
      allocate(values(n), stat=xtype)
      if (xtype /= 0) then
         call fail(cat, "attribute '" // name // "' of 'height' has " // to_str(n) // &
            & " values, more than memory holds (it should have one or two)", error)
         return
      end if
      call check(cat, nf90_get_att(cat%ncid, varid, name, values), "attribute " // name, error)
      if (allocated(error)) return
      if (present(all_values)) then
         call move_alloc(values, all_values)
         return
      end if
      value = values(1)
   end subroutine real_attribute

   !> The valid range of `height` (CF: valid_range, or valid_min and
   !> valid_max, in the packed values' units).
   subroutine valid_range(cat, error)
      type(profile_catalog_type), intent(inout) :: cat
      type(error_type), allocatable, intent(out) :: error
      character(len=11), parameter :: names(3) = [character(len=11) :: "valid_range", &
         & "valid_min", "valid_max"]
      integer :: k
      real(wp), allocatable :: values(:)
      cat%has_valid = any([(nf90_inquire_attribute(cat%ncid, cat%height_id, trim(names(k))) == &
         & nf90_noerr, k = 1, 3)])
      if (nf90_inquire_attribute(cat%ncid, cat%height_id, "valid_range") == nf90_noerr) then
         call real_attribute(cat, cat%height_id, "valid_range", cat%valid_min, error, &
            & all_values=values)
         if (allocated(error)) return
         if (size(values) /= 2) then
            call fail(cat, "variable 'height': valid_range has " // to_str(size(values)) // &
               & " values (must be two: min and max)", error)
            return
         end if
         cat%valid_min = values(1)
         cat%valid_max = values(2)
      else
         call real_attribute(cat, cat%height_id, "valid_min", cat%valid_min, error)
         if (allocated(error)) return
         call real_attribute(cat, cat%height_id, "valid_max", cat%valid_max, error)
         if (allocated(error)) return
      end if
      if (.not. cat%valid_min <= cat%valid_max) then
         call fail(cat, "variable 'height': valid minimum " // to_str(cat%valid_min) // &
            & " above valid maximum " // to_str(cat%valid_max) // "; fix valid_range " // &
            & "(or valid_min, valid_max)", error)
      end if
   end subroutine valid_range

   !> Length of a dimension (profiles: sets n_profiles).
   subroutine dim_length(cat, dimid, n, error, profiles)
      type(profile_catalog_type), intent(inout) :: cat
      integer, intent(in) :: dimid
      integer(i8), intent(out) :: n
      type(error_type), allocatable, intent(out) :: error
      logical, intent(in), optional :: profiles
      integer(c_size_t) :: length
      n = 0
      ! nc_inq_dimlen: nf90_inquire_dimension's default integer reads a
      ! dimension of 2^32 + 2000 as 2000
      call check(cat, int(c_nc_inq_dimlen(int(cat%ncid, c_int), int(dimid - 1, c_int), length)), &
         & "dimensions", error)
      if (allocated(error)) return
      if (length > int(huge(n), c_size_t)) then
         call fail(cat, "a dimension of " // to_str(real(length, wp)) // " values is too " // &
            & "long", error)
         return
      end if
      n = int(length, i8)
      if (present(profiles)) then
         if (profiles) then
            if (n > huge(1)) then
               call fail(cat, "holds " // to_str(n) // " profiles, more than " // &
                  & to_str(huge(1)) // " (split it into several files)", error)
               return
            end if
            cat%n_profiles = int(n)
         end if
      end if
   end subroutine dim_length

   !> "path, profile 'name'" for messages.
   pure function where(cat, i) result(text)
      type(profile_catalog_type), intent(in) :: cat
      integer, intent(in) :: i
      character(len=where_len(cat, i)) :: text
      character(len=:), allocatable :: deferred_text
      call where_text(cat, i, deferred_text)
      text = deferred_text
   end function where

   !> The length of where's text.
   pure integer function where_len(cat, i)
      type(profile_catalog_type), intent(in) :: cat
      integer, intent(in) :: i
      character(len=:), allocatable :: deferred_text
      call where_text(cat, i, deferred_text)
      where_len = len(deferred_text)
   end function where_len

   !> The text of where, into a deferred-length argument.
   pure subroutine where_text(cat, i, text)
      type(profile_catalog_type), intent(in) :: cat
      integer, intent(in) :: i
      character(len=:), allocatable, intent(out) :: text
      text = cat%path // ", profile " // to_str(i)
      if (allocated(cat%names)) then
         if (allocated(cat%names(i)%s)) text = cat%path // ", profile '" // cat%names(i)%s // "'"
      end if
   end subroutine where_text

   !> The first few names, for messages.
   pure function some_names(cat) result(text)
      type(profile_catalog_type), intent(in) :: cat
      character(len=some_names_len(cat)) :: text
      character(len=:), allocatable :: deferred_text
      call some_names_text(cat, deferred_text)
      text = deferred_text
   end function some_names

   !> The length of some_names's text.
   pure integer function some_names_len(cat)
      type(profile_catalog_type), intent(in) :: cat
      character(len=:), allocatable :: deferred_text
      call some_names_text(cat, deferred_text)
      some_names_len = len(deferred_text)
   end function some_names_len

   !> The text of some_names, into a deferred-length argument.
   pure subroutine some_names_text(cat, text)
      type(profile_catalog_type), intent(in) :: cat
      character(len=:), allocatable, intent(out) :: text
      integer :: k
      text = ""
      do k = 1, min(cat%n_profiles, 5)
         if (k > 1) text = text // ", "
         text = text // "'" // cat%names(k)%s // "'"
      end do
      if (cat%n_profiles > 5) text = text // ", ..."
   end subroutine some_names_text

   !> Check a netCDF status; on failure, an error naming the file and what
   !> was read, and the file closed.
   subroutine check(cat, status, what, error)
      type(profile_catalog_type), intent(inout) :: cat
      integer, intent(in) :: status
      character(len=*), intent(in) :: what
      type(error_type), allocatable, intent(out) :: error
      if (status == nf90_noerr) return
      call fail(cat, "reading " // what // " failed (" // trim(nf90_strerror(status)) // ")", &
         & error, stat_io)
   end subroutine check

   !> An error about the file; closes it.
   subroutine fail(cat, message, error, stat)
      type(profile_catalog_type), intent(inout) :: cat
      character(len=*), intent(in) :: message
      type(error_type), allocatable, intent(out) :: error
      integer, intent(in), optional :: stat
      call fatal_error(error, "&surface profile_file = '" // cat%path // "': " // message, stat)
      call close_profile_catalog(cat)
   end subroutine fail

end module pavefric_profile_netcdf
