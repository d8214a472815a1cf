!> Texture metrics of a profile: mean profile depth (ISO 13473-1 / ASTM
!> E1845), RMS height and RMS slope. No friction physics here.
module pavefric_texture
   use pavefric_kinds, only: wp
   use pavefric_error, only: error_type, fatal_error
   use pavefric_format, only: to_str
   implicit none
   private

   public :: texture_type, texture_metrics, mean_profile_depth

   !> Texture metrics of one profile (SI units).
   type :: texture_type
      !> Mean profile depth (m): the mean of the segments' mean segment depths.
      real(wp) :: mpd = 0.0_wp
      !> Number of complete segments, and how many were valid and averaged.
      integer :: n_segments = 0
      integer :: n_valid = 0
      !> RMS height about the mean (m).
      real(wp) :: rms_height = 0.0_wp
      !> RMS of the slope between neighbouring samples at the profile's own
      !> spacing (-).
      real(wp) :: rms_slope = 0.0_wp
   end type texture_type


contains

   !> All metrics of heights z (m) at spacing dx (m); MPD over segments of
   !> `segment_length` (m, ISO: 0.1), with or without slope suppression.
   subroutine texture_metrics(z, dx, closed, segment_length, slope_suppression, tex, error, &
         & dropout_fraction, spike, msd)
      real(wp), intent(in) :: z(:), dx, segment_length
      logical, intent(in) :: closed, slope_suppression
      !> Optional per-sample quality from preprocessing (see mean_profile_depth).
      real(wp), intent(in), optional :: dropout_fraction(:)
      logical, intent(in), optional :: spike(:)
      !> Optional: each segment's mean segment depth (m), valid or not.
      real(wp), intent(out), optional :: msd(:)
      type(texture_type), intent(out) :: tex
      type(error_type), allocatable, intent(out) :: error
      real(wp) :: mean, scale
      integer :: n
      n = size(z)
      if (n < 2) then
         call fatal_error(error, "texture: a profile needs at least two points")
         return
      end if
      call mean_profile_depth(z, dx, segment_length, slope_suppression, tex%mpd, &
         & tex%n_segments, error, msd=msd, dropout_fraction=dropout_fraction, spike=spike, &
         & n_valid=tex%n_valid)
      if (allocated(error)) return
      scale = maxval(abs(z))
      if (scale > 1.0e100_wp) then
         ! squares would overflow: the same sums on heights scaled to <= 1
         mean = sum(z / scale) / real(n, wp)
         tex%rms_height = scale * sqrt(sum((z / scale - mean)**2) / real(n, wp))
         if (closed) then
            tex%rms_slope = scale * (sqrt((sum((z(2:n) / scale - z(1:n-1) / scale)**2) + &
               & (z(1) / scale - z(n) / scale)**2) / real(n, wp)) / dx)
         else
            tex%rms_slope = scale * (sqrt(sum((z(2:n) / scale - z(1:n-1) / scale)**2) / &
               & real(n - 1, wp)) / dx)
         end if
         return
      end if
      mean = sum(z) / real(n, wp)
      tex%rms_height = sqrt(sum((z - mean)**2) / real(n, wp))
      if (closed) then
         tex%rms_slope = sqrt((sum((z(2:n) - z(1:n-1))**2) + (z(1) - z(n))**2) &
            & / real(n, wp)) / dx
      else
         tex%rms_slope = sqrt(sum((z(2:n) - z(1:n-1))**2) / real(n - 1, wp)) / dx
      end if
   end subroutine texture_metrics

   !> Mean profile depth: the profile is cut into consecutive segments of
   !> nint(segment_length/dx) samples from its start (an incomplete last
   !> segment is not used). In each segment, with slope suppression, the
   !> least-squares line is removed (ASTM E1845); the mean segment depth is
   !> the average of the highest points of the two halves minus the segment's
   !> mean height. MPD is the mean over the segments.
   pure subroutine mean_profile_depth(z, dx, segment_length, slope_suppression, mpd, &
         & n_segments, error, msd, dropout_fraction, spike, n_valid)
      real(wp), intent(in) :: z(:), dx, segment_length
      logical, intent(in) :: slope_suppression
      real(wp), intent(out) :: mpd
      integer, intent(out) :: n_segments
      type(error_type), allocatable, intent(out) :: error
      !> Optional: each segment's mean segment depth (m).
      real(wp), intent(out), optional :: msd(:)
      !> Optional per-sample quality (ISO 13473-1): a segment with more than
      !> 10 % dropouts or 5 % spikes is not valid and not averaged.
      real(wp), intent(in), optional :: dropout_fraction(:)
      logical, intent(in), optional :: spike(:)
      !> Optional: number of valid segments averaged.
      integer, intent(out), optional :: n_valid
      real(wp), allocatable :: seg(:)
      real(wp) :: depth, mean, slope, centre, sxx
      integer :: ns, k, i, half, nv

      mpd = 0.0_wp
      n_segments = 0
      if (.not. (dx > 0.0_wp) .or. .not. (segment_length > 0.0_wp)) then
         call fatal_error(error, "texture: dx = " // to_str(dx) // " and segment length = " // &
            & to_str(segment_length) // " must be > 0")
         return
      end if
      ns = nint(segment_length / dx)
      if (ns < 4) then
         call fatal_error(error, "texture: a segment of " // to_str(segment_length) // &
            & " m holds fewer than 4 samples at dx = " // to_str(dx) // " m")
         return
      end if
      n_segments = size(z) / ns
      if (n_segments < 1) then
         call fatal_error(error, "texture: the profile (" // to_str(size(z)) // " points, " // &
            & to_str(size(z) * dx) // " m) is shorter than one segment of " // &
            & to_str(segment_length) // " m")
         return
      end if
      allocate(seg(ns))
      centre = 0.5_wp * real(ns + 1, wp)
      sxx = real(ns, wp) * (real(ns, wp)**2 - 1.0_wp) / 12.0_wp
      half = ns / 2
      nv = 0
      do k = 1, n_segments
         seg = z((k-1)*ns + 1 : k*ns)
         if (slope_suppression) then
            ! the least-squares line through the segment, in closed form about
            ! the segment's centre (sample offsets c_i = i - (ns+1)/2, their
            ! sum of squares ns (ns^2 - 1) / 12): no LAPACK call per segment
            ! (dgels was 5 % of a 10-million-point run)
            mean = sum(seg) / real(ns, wp)
            slope = 0.0_wp
            do i = 1, ns
               slope = slope + (real(i, wp) - centre) * (seg(i) - mean)
            end do
            slope = slope / sxx
            do i = 1, ns
               seg(i) = seg(i) - mean - slope * (real(i, wp) - centre)
            end do
         end if
         depth = 0.5_wp * (maxval(seg(1:half)) + maxval(seg(half+1:ns))) - sum(seg) / real(ns, wp)
         if (present(msd)) then
            if (k <= size(msd)) msd(k) = depth
         end if
         if (present(dropout_fraction)) then
            if (sum(dropout_fraction((k-1)*ns + 1 : k*ns)) > 0.1_wp * real(ns, wp)) cycle
         end if
         if (present(spike)) then
            if (count(spike((k-1)*ns + 1 : k*ns)) > 0.05_wp * real(ns, wp)) cycle
         end if
         mpd = mpd + depth
         nv = nv + 1
      end do
      if (present(n_valid)) n_valid = nv
      if (nv == 0) then
         mpd = 0.0_wp
         call fatal_error(error, "texture: no valid segment (each has more than 10 % " // &
            & "dropouts or 5 % spikes)")
         return
      end if
      mpd = mpd / real(nv, wp)
   end subroutine mean_profile_depth

end module pavefric_texture
