!> Making an instrument profile fit for analysis (ISO 13473-1): trimming the
!> reference plates, handling dropouts, resampling, removing spikes and
!> low-pass filtering. Each step is optional and counted in a report.
module pavefric_preprocess
   use pavefric_kinds, only: wp, pi
   use pavefric_error, only: error_type, fatal_error, stat_memory
   use pavefric_format, only: to_str, round_sig
   use pavefric_profile_types, only: raw_profile_type, point_location
   use pavefric_params, only: param_spec_type, param_value_type, text_param, logical_param, &
      & real_param, real_value, logical_value, text_value
   implicit none
   private

   public :: preprocess_type, preprocess_report_type, clean_profile_type, preprocess, &
      & validate_preprocess, butterworth_filtfilt
   public :: preprocess_parameters, preprocess_n_parameters, preprocess_from_values

   !> The variables preprocessing declares (the &preprocess group).
   integer, parameter :: preprocess_n_parameters = 8

   !> The &preprocess options (SI units).
   type :: preprocess_type
      !> 'error' (a dropout stops the run, naming file and line) or 'interpolate'.
      character(len=16) :: dropouts = "error"
      !> Trim reference plates (long runs far from the surface's heights) at the ends.
      logical :: trim_plates = .true.
      !> A point further than this from the median height is off the surface (m).
      real(wp) :: plate_threshold = 0.010_wp
      !> Shortest run of such points that is a plate, not a spike (m).
      real(wp) :: plate_min_length = 0.005_wp
      !> Distance trimmed beyond a plate's edge (m).
      real(wp) :: plate_buffer = 0.002_wp
      !> A jump |dz| >= spike_slope * dx flags both points as a spike (0: off).
      real(wp) :: spike_slope = 0.0_wp
      !> Resample by averaging into bins of this spacing (m; 0: keep the spacing).
      real(wp) :: resample_dx = 0.0_wp
      !> Low-pass cut-off wavelength (m) of a 2nd-order Butterworth filter run
      !> forwards and backwards (ISO 13473-1:2019 Annex D: 2.4 mm; 0: off).
      real(wp) :: lowpass_wavelength = 0.0_wp
   end type preprocess_type

   !> What preprocessing did.
   type :: preprocess_report_type
      character(len=:), allocatable :: format
      integer :: points_read = 0
      integer :: trimmed_start = 0, trimmed_end = 0
      integer :: dropouts = 0
      integer :: spikes = 0
      integer :: points_out = 0
      real(wp) :: dx_in = 0.0_wp, dx_out = 0.0_wp
      logical :: resampled = .false., filtered = .false.
   end type preprocess_report_type

   !> A profile fit for analysis, with per-sample quality for texture metrics.
   type :: clean_profile_type
      real(wp), allocatable :: z(:)
      real(wp) :: dx = 0.0_wp
      !> Share of each sample's raw points that were dropouts.
      real(wp), allocatable :: dropout_fraction(:)
      !> Whether a sample was flagged as a spike.
      logical, allocatable :: spike(:)
      type(preprocess_report_type) :: report
   end type clean_profile_type

contains

   !> The &preprocess group, one variable per step's option.
   pure function preprocess_parameters() result(s)
      type(param_spec_type) :: s(preprocess_n_parameters)
      real(wp), parameter :: big = huge(1.0_wp)
      s(1) = text_param("preprocess", "dropouts", "error", "", "profile", &
         & "'error': a dropout (empty or NaN height) stops the run naming file and line; " // &
         & "'interpolate': linear interpolation (ISO 13473-1)", choices="error interpolate")
      s(2) = logical_param("preprocess", "trim_plates", ".true.", "profile", &
         & "cut reference plates (long runs far from the surface's heights) at the ends")
      s(3) = real_param("preprocess", "plate_threshold", "0.010", "m", "profile", &
         & "a point this far from the median height is off the surface", lower=0.0_wp, &
         & lower_strict=.true., upper=big)
      s(4) = real_param("preprocess", "plate_min_length", "0.005", "m", &
         & "profile", "shortest run of such points that is a plate, not a spike", &
         & lower=0.0_wp, upper=big)
      s(5) = real_param("preprocess", "plate_buffer", "0.002", "m", "profile", &
         & "distance cut beyond a plate's edge", lower=0.0_wp, upper=big)
      s(6) = real_param("preprocess", "spike_slope", "0", "1", "profile", &
         & "a jump >= spike_slope x spacing flags both its points as a spike (0: off; " // &
         & "ISO 13473-1: 3 at 0.5-1 mm spacing)", lower=0.0_wp, upper=big)
      s(7) = real_param("preprocess", "resample_dx", "0", "m", "profile", &
         & "resample by averaging into bins of this spacing (0: keep the spacing)", &
         & lower=0.0_wp, upper=big)
      s(8) = real_param("preprocess", "lowpass_wavelength", "0", "m", &
         & "profile", "cut-off wavelength of a 2nd-order Butterworth low-pass run forwards " // &
         & "and backwards (0: off; ISO 13473-1: 2.4e-3)", lower=0.0_wp, upper=big)
   end function preprocess_parameters

   !> The options from the scene's values (`specs` and `values`: the whole
   !> table; preprocessing reads its own by group and name).
   pure function preprocess_from_values(specs, values) result(p)
      type(param_spec_type), intent(in) :: specs(:)
      type(param_value_type), intent(in) :: values(:)
      type(preprocess_type) :: p
      character(len=:), allocatable :: dropouts
      call text_value(specs, values, "preprocess", "dropouts", dropouts)
      p%dropouts = dropouts
      p%trim_plates = logical_value(specs, values, "preprocess", "trim_plates")
      p%plate_threshold = real_value(specs, values, "preprocess", "plate_threshold")
      p%plate_min_length = real_value(specs, values, "preprocess", "plate_min_length")
      p%plate_buffer = real_value(specs, values, "preprocess", "plate_buffer")
      p%spike_slope = real_value(specs, values, "preprocess", "spike_slope")
      p%resample_dx = real_value(specs, values, "preprocess", "resample_dx")
      p%lowpass_wavelength = real_value(specs, values, "preprocess", "lowpass_wavelength")
   end function preprocess_from_values

   !> Check the options; messages name &preprocess and the variable.
   pure subroutine validate_preprocess(p, error)
      type(preprocess_type), intent(in) :: p
      type(error_type), allocatable, intent(out) :: error
      if (trim(p%dropouts) /= "error" .and. trim(p%dropouts) /= "interpolate") then
         call fatal_error(error, "&preprocess dropouts = '" // trim(p%dropouts) // &
            & "': unknown (expected 'error' or 'interpolate')")
      else if (.not. (p%plate_threshold > 0.0_wp)) then
         call fatal_error(error, "&preprocess plate_threshold = " // to_str(p%plate_threshold) // &
            & ": must be > 0")
      else if (.not. (p%plate_min_length >= 0.0_wp)) then
         call fatal_error(error, "&preprocess plate_min_length = " // &
            & to_str(p%plate_min_length) // ": must be >= 0")
      else if (.not. (p%plate_buffer >= 0.0_wp)) then
         call fatal_error(error, "&preprocess plate_buffer = " // to_str(p%plate_buffer) // &
            & ": must be >= 0")
      else if (.not. (p%spike_slope >= 0.0_wp)) then
         call fatal_error(error, "&preprocess spike_slope = " // to_str(p%spike_slope) // &
            & ": must be >= 0 (0: off)")
      else if (.not. (p%resample_dx >= 0.0_wp)) then
         call fatal_error(error, "&preprocess resample_dx = " // to_str(p%resample_dx) // &
            & ": must be >= 0 (0: off)")
      else if (.not. (p%lowpass_wavelength >= 0.0_wp)) then
         call fatal_error(error, "&preprocess lowpass_wavelength = " // &
            & to_str(p%lowpass_wavelength) // ": must be >= 0 (0: off)")
      end if
   end subroutine validate_preprocess

   !> Run the steps in ISO 13473-1's order. `dx` is the spacing to use when
   !> the file gave neither distances nor a spacing of its own (raw%dx).
   !> Work arrays are allocated with stat= after their sizes are known (a
   !> failure is an error with stat_memory, never an abort), and no array
   !> expression makes a profile-sized temporary.
   subroutine preprocess(raw, dx, p, clean, error)
      type(raw_profile_type), intent(in) :: raw
      real(wp), intent(in) :: dx
      type(preprocess_type), intent(in) :: p
      type(clean_profile_type), intent(out) :: clean
      type(error_type), allocatable, intent(out) :: error
      real(wp), allocatable :: x(:), z(:), frac(:)
      logical, allocatable :: ok(:), plate(:)
      real(wp) :: med, x_start, x_end, step, spacing
      integer :: n, m, i, i0, i1, k, st

      call validate_preprocess(p, error)
      if (allocated(error)) return
      n = size(raw%z)
      clean%report%format = raw%format
      clean%report%points_read = n
      spacing = dx
      if (raw%dx > 0.0_wp) spacing = raw%dx
      allocate(x(n), stat=st)
      if (st /= 0) then
         call memory_error(raw, n, error)
         return
      end if
      if (raw%has_x) then
         x(:) = raw%x
      else
         do i = 1, n
            x(i) = real(i - 1, wp) * spacing
         end do
      end if

      call trim_reference_plates()
      if (allocated(error)) return
      call keep_points()
      if (allocated(error)) return
      call mend_dropouts()
      if (allocated(error)) return
      call resample_or_check_spacing()
      if (allocated(error)) return
      call replace_spikes()
      if (allocated(error)) return
      deallocate(x, ok)
      call low_pass()
      if (allocated(error)) return
      clean%report%points_out = n
      clean%report%dx_out = clean%dx
   contains
      !> 1. Reference plates at the ends: runs of points far from the
      !> median height, longer than plate_min_length, cut with a buffer.
      subroutine trim_reference_plates()
         i0 = 1
         i1 = n
         x_start = -huge(1.0_wp)
         if (p%trim_plates .and. count(raw%valid) > 0) then
            call valid_median(raw%z, raw%valid, med, st)
            if (st == 0) allocate(plate(n), stat=st)
            if (st /= 0) then
               call memory_error(raw, n, error)
               return
            end if
            ! a dropout continues the state of the point before it (forward fill)
            do i = 1, n
               if (raw%valid(i)) then
                  plate(i) = abs(raw%z(i) - med) > p%plate_threshold
               else if (i > 1) then
                  plate(i) = plate(i-1)
               else
                  plate(i) = .false.
               end if
            end do
            call plate_bounds(x, plate, p%plate_min_length, x_start, x_end)
            deallocate(plate)
            if (x_start > -huge(1.0_wp)) then
               x_start = x_start + p%plate_buffer
               do while (i0 <= n)
                  if (x(i0) >= x_start) exit
                  i0 = i0 + 1
               end do
            end if
            if (x_end < huge(1.0_wp)) then
               x_end = x_end - p%plate_buffer
               do while (i1 >= i0)
                  if (x(i1) < x_end) exit
                  i1 = i1 - 1
               end do
            end if
            clean%report%trimmed_start = i0 - 1
            clean%report%trimmed_end = n - i1
            ! (with nothing trimmed, a profile too short is the pad's check's to name)
            if (i1 - i0 + 1 < 2 .and. (i0 > 1 .or. i1 < n)) then
               call fatal_error(error, raw%path // ": nothing is left of the profile after " // &
                  & "trimming reference plates; set &preprocess trim_plates = .false. or a " // &
                  & "larger plate_threshold, and check the heights' unit (&surface height_unit)")
               return
            end if
         end if
      end subroutine trim_reference_plates

      !> The kept points; distances from the trimming boundary (the
      !> resampling bins start there). The line of point k is raw%line(i0+k-1).
      subroutine keep_points()
         m = i1 - i0 + 1
         allocate(z(m), ok(m), stat=st)
         if (st /= 0) then
            call memory_error(raw, m, error)
            return
         end if
         z(:) = raw%z(i0:i1)
         ok(:) = raw%valid(i0:i1)
         if (x_start > -huge(1.0_wp)) then
            do k = 1, m
               x(k) = x(i0 + k - 1) - x_start
            end do
         else if (i0 > 1) then
            do k = 1, m
               x(k) = x(i0 + k - 1)
            end do
         end if

      end subroutine keep_points

      !> 2. Dropouts: an error naming file and line, or interpolated.
      subroutine mend_dropouts()
         clean%report%dropouts = count(.not. ok)
         if (clean%report%dropouts > 0) then
            if (trim(p%dropouts) == "error") then
               k = findloc(ok, .false., dim=1)
               call fatal_error(error, point_location(raw, raw%line(i0 + k - 1)) // &
                  & ": dropout (no valid height); set &preprocess dropouts = 'interpolate' " // &
                  & "to interpolate dropouts (ISO 13473-1)")
               return
            end if
            if (count(ok) == 0) then
               call fatal_error(error, raw%path // ": every height is a dropout (NaN or " // &
                  & "empty), nothing to interpolate; check the height column (&surface " // &
                  & "z_column) and the file")
               return
            end if
            call interpolate_gaps(x(1:m), z, ok)
         end if
         allocate(frac(m), stat=st)
         if (st /= 0) then
            call memory_error(raw, m, error)
            return
         end if
         do k = 1, m
            frac(k) = merge(0.0_wp, 1.0_wp, ok(k))
         end do

      end subroutine mend_dropouts

      !> 3. Resampling into bins, or the file's own (uniform) spacing.
      subroutine resample_or_check_spacing()
         clean%report%dx_in = (x(m) - x(1)) / real(max(m - 1, 1), wp)
         if (p%resample_dx > 0.0_wp) then
            call resample_bins(x(1:m), z, frac, p%resample_dx, clean%z, clean%dropout_fraction, &
               & error)
            if (allocated(error)) then
               error%message = raw%path // ": " // error%message
               return
            end if
            deallocate(z, frac)
            clean%dx = p%resample_dx
            clean%report%resampled = .true.
         else
            if (m < 2) then
               clean%dx = spacing
            else
               clean%dx = clean%report%dx_in
               do i = 2, m
                  step = x(i) - x(i-1)
                  if (abs(step - clean%dx) > 0.05_wp * clean%dx) then
                     call fatal_error(error, point_location(raw, raw%line(i0 + i - 1)) // &
                        & ": spacing " // to_str(round_sig(step, 4)) // " m against the mean " // &
                        & to_str(round_sig(clean%dx, 4)) // " m (more than 5 % off): resample " // &
                        & "it (&preprocess resample_dx)")
                     return
                  end if
               end do
            end if
            if (.not. raw%has_x) clean%dx = spacing
            call move_alloc(z, clean%z)
            call move_alloc(frac, clean%dropout_fraction)
         end if
         n = size(clean%z)

      end subroutine resample_or_check_spacing

      !> 4. Spikes: a jump of at least spike_slope * dx flags both its
      !> points, which are then interpolated.
      subroutine replace_spikes()
         allocate(clean%spike(n), stat=st)
         if (st /= 0) then
            call memory_error(raw, n, error)
            return
         end if
         clean%spike = .false.
         if (p%spike_slope > 0.0_wp .and. n > 2) then
            do i = 1, n - 1
               if (abs(clean%z(i+1) - clean%z(i)) >= p%spike_slope * clean%dx) then
                  clean%spike(i) = .true.
                  clean%spike(i+1) = .true.
               end if
            end do
            clean%report%spikes = count(clean%spike)
            if (clean%report%spikes > 0 .and. clean%report%spikes < n) then
               ! n <= m: x and ok have room
               do i = 1, n
                  x(i) = real(i - 1, wp) * clean%dx
                  ok(i) = .not. clean%spike(i)
               end do
               call interpolate_gaps(x(1:n), clean%z, ok(1:n))
            end if
         end if
      end subroutine replace_spikes

      !> 5. The low-pass filter (ISO 13473-1 Annex D).
      subroutine low_pass()
         if (p%lowpass_wavelength > 0.0_wp) then
            call butterworth_filtfilt(clean%z, clean%dx, p%lowpass_wavelength, error)
            if (allocated(error)) then
               error%message = raw%path // ": " // error%message
               return
            end if
            clean%report%filtered = .true.
         end if
      end subroutine low_pass
   end subroutine preprocess

   !> Not enough memory for the work arrays of n points.
   pure subroutine memory_error(raw, n, error)
      type(raw_profile_type), intent(in) :: raw
      integer, intent(in) :: n
      type(error_type), allocatable, intent(out) :: error
      call fatal_error(error, raw%path // ": not enough memory to preprocess " // to_str(n) // &
         & " points", stat_memory)
   end subroutine memory_error

   !> Median of the valid heights (a selection in a copy: O(n), the same
   !> value as sorting). st /= 0 when the copy cannot be allocated.
   pure subroutine valid_median(z, valid, med, st)
      real(wp), intent(in) :: z(:)
      logical, intent(in) :: valid(:)
      real(wp), intent(out) :: med
      integer, intent(out) :: st
      real(wp), allocatable :: s(:)
      integer :: n, i, k
      med = 0.0_wp
      n = count(valid)
      allocate(s(n), stat=st)
      if (st /= 0) return
      k = 0
      do i = 1, size(z)
         if (valid(i)) then
            k = k + 1
            s(k) = z(i)
         end if
      end do
      if (mod(n, 2) == 1) then
         call select_kth(s, (n + 1) / 2, med)
      else
         ! the lower middle, then the smallest of the upper half
         call select_kth(s, n / 2, med)
         med = 0.5_wp * (med + minval(s(n/2+1:n)))
      end if
   end subroutine valid_median

   !> v = the k-th smallest of a (reordered in place so that a(1:k-1) <= a(k) <=
   !> a(k+1:)): Hoare's selection with a median-of-three pivot.
   pure subroutine select_kth(a, k, v)
      real(wp), intent(inout) :: a(:)
      integer, intent(in) :: k
      real(wp), intent(out) :: v
      real(wp) :: pivot, t
      integer :: lo, hi, i, j, mid
      lo = 1
      hi = size(a)
      do while (hi > lo)
         mid = lo + (hi - lo) / 2
         ! median of three, placed at mid
         if (a(mid) < a(lo)) call swap(a(mid), a(lo))
         if (a(hi) < a(lo)) call swap(a(hi), a(lo))
         if (a(hi) < a(mid)) call swap(a(hi), a(mid))
         pivot = a(mid)
         i = lo
         j = hi
         do while (i <= j)
            do while (a(i) < pivot)
               i = i + 1
            end do
            do while (pivot < a(j))
               j = j - 1
            end do
            if (i <= j) then
               t = a(i)
               a(i) = a(j)
               a(j) = t
               i = i + 1
               j = j - 1
            end if
         end do
         if (k <= j) then
            hi = j
         else if (k >= i) then
            lo = i
         else
            exit                               ! a(j+1:i-1) all equal the pivot
         end if
      end do
      v = a(k)
   contains
      pure subroutine swap(p, q)
         real(wp), intent(inout) :: p, q
         real(wp) :: r
         r = p
         p = q
         q = r
      end subroutine swap
   end subroutine select_kth

   !> End of the last plate run in the first half, start of the first in the
   !> second half (-huge / huge when there is none). A run counts when it
   !> spans at least `min_length`.
   pure subroutine plate_bounds(x, plate, min_length, x_start, x_end)
      real(wp), intent(in) :: x(:), min_length
      logical, intent(in) :: plate(:)
      real(wp), intent(out) :: x_start, x_end
      integer :: i, j, n, mid
      n = size(x)
      mid = (n + 1) / 2
      x_start = -huge(1.0_wp)
      x_end = huge(1.0_wp)
      i = 1
      do while (i <= n)
         if (.not. plate(i)) then
            i = i + 1
            cycle
         end if
         j = i
         do while (j < n)
            if (.not. plate(j+1)) exit
            j = j + 1
         end do
         if (x(j) - x(i) >= min_length) then
            if (j < mid .and. j < n) then
               x_start = x(j + 1)
            else if (i > mid .and. x_end == huge(1.0_wp)) then
               x_end = x(i)
            end if
         end if
         i = j + 1
      end do
   end subroutine plate_bounds

   !> Fill invalid points: linear in x between valid neighbours; before the
   !> first (after the last) valid point, its value.
   pure subroutine interpolate_gaps(x, z, ok)
      real(wp), intent(in) :: x(:)
      real(wp), intent(inout) :: z(:)
      logical, intent(in) :: ok(:)
      integer :: i, k, left, right, n, first, last
      n = size(z)
      first = findloc(ok, .true., dim=1)
      last = findloc(ok, .true., dim=1, back=.true.)
      if (first == 0) return
      z(1:first-1) = z(first)
      z(last+1:n) = z(last)
      left = first
      i = first + 1
      do while (i <= last)
         if (ok(i)) then
            left = i
            i = i + 1
            cycle
         end if
         right = i
         do while (.not. ok(right))
            right = right + 1
         end do
         do k = i, right - 1
            z(k) = z(left) + (z(right) - z(left)) * (x(k) - x(left)) / (x(right) - x(left))
         end do
         i = right
      end do
   end subroutine interpolate_gaps

   !> Average into bins ((k-1) target, k target], k = ceil(x/target) (the first
   !> point's bin at least 1), as ISO 13473-1 resampling does. The number of
   !> bins is known before anything is allocated: more bins than points means
   !> an empty bin, an error, so the arrays are never larger than the input.
   pure subroutine resample_bins(x, z, frac, target, zr, fr, error)
      real(wp), intent(in) :: x(:), z(:), frac(:), target
      real(wp), allocatable, intent(out) :: zr(:), fr(:)
      type(error_type), allocatable, intent(out) :: error
      integer, allocatable :: cnt(:)
      integer :: i, k, nb, st
      real(wp) :: bins
      bins = max(1.0_wp, real(ceiling(min(x(size(x)) / target, real(huge(1), wp))), wp))
      if (bins > real(size(x), wp)) then
         call fatal_error(error, "&preprocess resample_dx = " // to_str(target) // &
            & ": finer than the data's spacing (" // to_str(size(x)) // " points over " // &
            & to_str(round_sig(x(size(x)), 4)) // " m, about " // &
            & to_str(round_sig(x(size(x)) / max(size(x) - 1, 1), 3)) // " m apart, would " // &
            & "need " // to_str(bins) // " bins, some of them empty); give resample_dx >= " // &
            & "the data's spacing, or 0 to keep it")
         return
      end if
      nb = int(bins)
      allocate(zr(nb), fr(nb), cnt(nb), stat=st)
      if (st /= 0) then
         call fatal_error(error, "&preprocess resample_dx = " // to_str(target) // &
            & ": not enough memory for " // to_str(nb) // " bins", stat_memory)
         return
      end if
      zr = 0.0_wp
      fr = 0.0_wp
      cnt = 0
      do i = 1, size(x)
         k = max(1, ceiling(x(i) / target))
         k = min(k, nb)
         zr(k) = zr(k) + z(i)
         fr(k) = fr(k) + frac(i)
         cnt(k) = cnt(k) + 1
      end do
      if (any(cnt == 0)) then
         call fatal_error(error, "&preprocess resample_dx = " // to_str(target) // &
            & ": finer than the data's spacing (a bin holds no point); give resample_dx >= " // &
            & "the data's spacing, or 0 to keep it")
         return
      end if
      do k = 1, nb
         zr(k) = zr(k) / real(cnt(k), wp)
         fr(k) = fr(k) / real(cnt(k), wp)
      end do
   end subroutine resample_bins

   !> 2nd-order Butterworth low-pass (cut-off wavelength `wavelength`) run
   !> forwards and backwards, with odd extension of 9 points at each end and
   !> steady-state initial conditions (as SciPy's sosfiltfilt).
   pure subroutine butterworth_filtfilt(z, dx, wavelength, error)
      real(wp), intent(inout) :: z(:)
      real(wp), intent(in) :: dx, wavelength
      type(error_type), allocatable, intent(out) :: error
      integer, parameter :: pad = 9
      real(wp), allocatable :: e(:)
      real(wp) :: k, norm, b0, b1, b2, a1, a2
      integer :: n, i
      n = size(z)
      if (n <= pad) then
         call fatal_error(error, "&preprocess lowpass_wavelength: the low-pass filter " // &
            & "needs more than " // to_str(pad) // " points, the profile has " // to_str(n) // &
            & "; give a longer profile, or lowpass_wavelength = 0 (off)")
         return
      end if
      if (.not. (wavelength > 2.0_wp * dx)) then
         call fatal_error(error, "&preprocess lowpass_wavelength = " // to_str(wavelength) // &
            & ": must exceed two samples (" // to_str(2.0_wp * dx) // " m)")
         return
      end if
      ! bilinear transform with pre-warping (= scipy.signal.butter(2, 2 dx / wavelength))
      k = tan(pi * dx / wavelength)
      norm = 1.0_wp / (1.0_wp + sqrt(2.0_wp) * k + k * k)
      b0 = k * k * norm
      b1 = 2.0_wp * b0
      b2 = b0
      a1 = 2.0_wp * (k * k - 1.0_wp) * norm
      a2 = (1.0_wp - sqrt(2.0_wp) * k + k * k) * norm
      allocate(e(n + 2 * pad), stat=i)
      if (i /= 0) then
         call fatal_error(error, "the low-pass filter: not enough memory for " // to_str(n) // &
            & " points", stat_memory)
         return
      end if
      e(pad+1:pad+n) = z
      do i = 1, pad
         e(pad + 1 - i) = 2.0_wp * z(1) - z(1 + i)
         e(pad + n + i) = 2.0_wp * z(n) - z(n - i)
      end do
      call pass(e, 1, size(e), 1)
      call pass(e, size(e), 1, -1)
      z = e(pad+1:pad+n)
   contains
      !> One filter pass over s(first), s(first+step), ..., s(last).
      pure subroutine pass(s, first, last, step)
         real(wp), intent(inout) :: s(:)
         integer, intent(in) :: first, last, step
         real(wp) :: s1, s2, xin, y
         integer :: j
         ! transposed direct form II, steady state for a constant input s(first)
         s2 = (b2 - a2) * s(first)
         s1 = (b1 - a1) * s(first) + s2
         do j = first, last, step
            xin = s(j)
            y = b0 * xin + s1
            s1 = b1 * xin - a1 * y + s2
            s2 = b2 * xin - a2 * y
            s(j) = y
         end do
      end subroutine pass
   end subroutine butterworth_filtfilt

end module pavefric_preprocess
