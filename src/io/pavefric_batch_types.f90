!> The data of a batch run: its profiles and each profile's results, and
!> their packing into reals (for the journal and for MPI messages).
module pavefric_batch_types
   use pavefric_kinds, only: wp
   use pavefric_scene, only: scene_type
   use pavefric_profile, only: profile_catalog_type
   use pavefric_batch_hash, only: digest_len, no_digest
   implicit none
   private

   public :: batch_type, block_type, string_type, block_pack, block_unpack, block_values
   public :: block_allocate, block_clear, n_head, status_computed, status_failed, printable_utf8

   !> Profile status: not computed yet, computed, failed (message says why).
   integer, parameter :: status_computed = 1, status_failed = 2

   !> Reals before the result arrays in a packed block (see block_pack).
   integer, parameter :: n_head = 19

   !> A string in an array of strings.
   type :: string_type
      character(len=:), allocatable :: s
   end type string_type

   !> A batch: the scene, the profiles, depths and speeds, and its journal.
   type :: batch_type
      type(scene_type) :: scene
      type(string_type), allocatable :: paths(:), names(:)
      !> Chainage (m) of each profile, when the profile list gives it.
      real(wp), allocatable :: chainage(:)
      logical :: has_chainage = .false.
      real(wp), allocatable :: depths(:), speeds(:)
      integer :: n_profiles = 0, n_depths = 0, n_speeds = 0
      character(len=:), allocatable :: output, journal
      !> SHA-256 of the scene text, version, profile paths, chainages, depths
      !> and speeds; each journal line carries its profile file's own digest.
      character(len=digest_len) :: fingerprint = ""
      !> The journal's file descriptor while it is open for appending.
      integer :: journal_unit = -1
      logical :: journal_open = .false.
      !> The journal ends in a line cut short (a kill): end it before appending.
      logical :: journal_cut = .false.
      !> What reading the journal found: profiles taken from it, damaged lines
      !> ignored, profiles whose file changed since (recomputed).
      integer :: journal_taken = 0, journal_damaged = 0, journal_changed = 0
      !> The profiles are those of one NetCDF file (&batch profiles names it):
      !> its catalogue, kept open, and the file's digest (one for all profiles).
      logical :: from_netcdf = .false.
      type(profile_catalog_type) :: catalog
      character(len=digest_len) :: source_digest = ""
   end type batch_type

   !> One profile's results (arrays are speed x depth).
   type :: block_type
      integer :: index = 0
      !> 0: not computed yet; status_computed; status_failed (message says why).
      integer :: status = 0
      !> SHA-256 of the profile file's bytes when it was computed.
      character(len=digest_len) :: digest = no_digest
      logical :: has_texture = .false.
      real(wp) :: mpd = 0, rms_height = 0, rms_slope = 0
      !> The preprocessing record (preprocess_report_type of pavefric_preprocess).
      integer :: points_read = 0, trimmed_start = 0, trimmed_end = 0, dropouts = 0, &
         & spikes = 0, points_used = 0
      logical :: resampled = .false., filtered = .false.
      real(wp) :: dx_in = 0, dx = 0
      real(wp), allocatable :: mu(:,:), wet(:,:), hydroplaning(:,:), residual(:,:)
      !> mu's parts: the rubber's (hysteresis) and the local friction's (adhesion).
      real(wp), allocatable :: mu_hysteresis(:,:), mu_adhesion(:,:)
      !> mu's estimated error from the time step (&numerics error_estimate
      !> or tolerance); -1 where the run made none.
      real(wp), allocatable :: mu_error(:,:)
      !> elements_per_sample of the finest pass that made mu_error (more than
      !> the scene's where the pad's elements were halved; the scene's with
      !> a tolerance); -1 where the run made no estimate.
      real(wp), allocatable :: estimate_eps(:,:)
      !> elements_per_sample of the run the results come from (more than the
      !> scene's where &numerics min_contacts refined the pad); 0 where the
      !> profile failed.
      real(wp), allocatable :: eps_used(:,:)
      real(wp), allocatable :: n_clamped(:,:)
      logical :: viscous = .false., bearing = .false.
      !> Warnings about the profile and its results (those a single scene of
      !> it records), distinct lines counted.
      integer :: n_warnings = 0
      !> Failed: why. Computed: its warnings, one a line (the first
      !> max_block_warnings of them), empty when there are none.
      character(len=:), allocatable :: message
   end type block_type

contains

   !> Number of reals in a packed block.
   pure integer function block_values(batch)
      type(batch_type), intent(in) :: batch
      block_values = n_head + 10 * batch%n_speeds * batch%n_depths
   end function block_values

   !> Result arrays of the batch's shape, zero.
   pure subroutine block_allocate(batch, blk)
      type(batch_type), intent(in) :: batch
      type(block_type), intent(inout) :: blk
      integer :: ns, nd
      ns = batch%n_speeds
      nd = batch%n_depths
      if (allocated(blk%mu)) deallocate(blk%mu, blk%wet, blk%hydroplaning, blk%residual, &
         & blk%n_clamped)
      if (allocated(blk%mu_hysteresis)) deallocate(blk%mu_hysteresis, blk%mu_adhesion)
      if (allocated(blk%mu_error)) deallocate(blk%mu_error)
      if (allocated(blk%estimate_eps)) deallocate(blk%estimate_eps)
      if (allocated(blk%eps_used)) deallocate(blk%eps_used)
      allocate(blk%mu(ns, nd), blk%wet(ns, nd), blk%hydroplaning(ns, nd), blk%residual(ns, nd), &
         & blk%n_clamped(ns, nd), blk%mu_hysteresis(ns, nd), blk%mu_adhesion(ns, nd), &
         & blk%mu_error(ns, nd), blk%estimate_eps(ns, nd), blk%eps_used(ns, nd))
      call block_clear(blk)
   end subroutine block_allocate

   !> A block's results as before any run (a failed profile's): zero, and
   !> -1 where "none was made" differs from 0.
   pure subroutine block_clear(blk)
      type(block_type), intent(inout) :: blk
      blk%mu = 0; blk%wet = 0; blk%hydroplaning = 0; blk%residual = 0; blk%n_clamped = 0
      blk%mu_hysteresis = 0; blk%mu_adhesion = 0; blk%mu_error = -1; blk%estimate_eps = -1
      blk%eps_used = 0
      blk%viscous = .false.
      blk%bearing = .false.
   end subroutine block_clear

   !> A block as reals (for the journal and for MPI); the digest and the
   !> message travel beside them as text.
   pure subroutine block_pack(batch, blk, values)
      type(batch_type), intent(in) :: batch
      type(block_type), intent(in) :: blk
      real(wp), intent(out) :: values(:)
      integer :: m, k
      m = batch%n_speeds * batch%n_depths
      values(1:n_head) = [real(blk%index, wp), real(blk%status, wp), flag(blk%has_texture), &
         & blk%mpd, blk%rms_height, blk%rms_slope, flag(blk%viscous), flag(blk%bearing), &
         & real(blk%points_read, wp), real(blk%trimmed_start, wp), real(blk%trimmed_end, wp), &
         & real(blk%dropouts, wp), real(blk%spikes, wp), real(blk%points_used, wp), &
         & flag(blk%resampled), flag(blk%filtered), blk%dx_in, blk%dx, &
         & real(blk%n_warnings, wp)]
      k = n_head
      values(k+1:k+m) = reshape(blk%mu, [m]);           k = k + m
      values(k+1:k+m) = reshape(blk%wet, [m]);          k = k + m
      values(k+1:k+m) = reshape(blk%hydroplaning, [m]); k = k + m
      values(k+1:k+m) = reshape(blk%residual, [m]);     k = k + m
      values(k+1:k+m) = reshape(blk%n_clamped, [m]);    k = k + m
      values(k+1:k+m) = reshape(blk%mu_hysteresis, [m]); k = k + m
      values(k+1:k+m) = reshape(blk%mu_adhesion, [m]);   k = k + m
      values(k+1:k+m) = reshape(blk%mu_error, [m]);     k = k + m
      values(k+1:k+m) = reshape(blk%estimate_eps, [m]); k = k + m
      values(k+1:k+m) = reshape(blk%eps_used, [m])
   contains
      pure real(wp) function flag(yes)
         logical, intent(in) :: yes
         flag = merge(1.0_wp, 0.0_wp, yes)
      end function flag
   end subroutine block_pack

   !> The inverse of block_pack. `valid` (optional) is false when the values
   !> cannot be a block of this batch: an index out of range, a status or flag
   !> that is not one, a count that is not a whole number >= 0.
   pure subroutine block_unpack(batch, values, blk, valid)
      type(batch_type), intent(in) :: batch
      real(wp), intent(in) :: values(:)
      type(block_type), intent(inout) :: blk
      logical, intent(out), optional :: valid
      integer :: m, ns, nd, k
      logical :: ok
      ns = batch%n_speeds
      nd = batch%n_depths
      m = ns * nd
      ok = size(values) == block_values(batch)
      if (ok) ok = whole(values(1), 1.0_wp, real(batch%n_profiles, wp)) .and. &
         & whole(values(2), 1.0_wp, 2.0_wp) .and. whole(values(3), 0.0_wp, 1.0_wp) .and. &
         & whole(values(7), 0.0_wp, 1.0_wp) .and. whole(values(8), 0.0_wp, 1.0_wp) .and. &
         & all([(whole(values(k), 0.0_wp, 2.0e9_wp), k = 9, 14)]) .and. &
         & whole(values(15), 0.0_wp, 1.0_wp) .and. whole(values(16), 0.0_wp, 1.0_wp) .and. &
         & whole(values(19), 0.0_wp, 2.0e9_wp)
      if (present(valid)) valid = ok
      if (.not. ok) return
      blk%index = nint(values(1))
      blk%status = nint(values(2))
      blk%has_texture = values(3) > 0.5_wp
      blk%mpd = values(4)
      blk%rms_height = values(5)
      blk%rms_slope = values(6)
      blk%viscous = values(7) > 0.5_wp
      blk%bearing = values(8) > 0.5_wp
      blk%points_read = nint(values(9))
      blk%trimmed_start = nint(values(10))
      blk%trimmed_end = nint(values(11))
      blk%dropouts = nint(values(12))
      blk%spikes = nint(values(13))
      blk%points_used = nint(values(14))
      blk%resampled = values(15) > 0.5_wp
      blk%filtered = values(16) > 0.5_wp
      blk%dx_in = values(17)
      blk%dx = values(18)
      blk%n_warnings = nint(values(19))
      k = n_head
      blk%mu = reshape(values(k+1:k+m), [ns, nd]);           k = k + m
      blk%wet = reshape(values(k+1:k+m), [ns, nd]);          k = k + m
      blk%hydroplaning = reshape(values(k+1:k+m), [ns, nd]); k = k + m
      blk%residual = reshape(values(k+1:k+m), [ns, nd]);     k = k + m
      blk%n_clamped = reshape(values(k+1:k+m), [ns, nd]);     k = k + m
      blk%mu_hysteresis = reshape(values(k+1:k+m), [ns, nd]); k = k + m
      blk%mu_adhesion = reshape(values(k+1:k+m), [ns, nd]);   k = k + m
      blk%mu_error = reshape(values(k+1:k+m), [ns, nd]);     k = k + m
      blk%estimate_eps = reshape(values(k+1:k+m), [ns, nd]); k = k + m
      blk%eps_used = reshape(values(k+1:k+m), [ns, nd])
      if (.not. allocated(blk%message)) blk%message = ""
   contains
      !> Whether v is a whole number in [lo, hi] (NaN is not).
      pure logical function whole(v, lo, hi)
         real(wp), intent(in) :: v, lo, hi
         whole = v >= lo .and. v <= hi
         if (whole) whole = v == aint(v)
      end function whole
   end subroutine block_unpack

   !> `s` as printable UTF-8: control characters become blanks and bytes
   !> that are not valid UTF-8 (a message quoting a binary file) become '?',
   !> so that the journal stays text and readers of the NetCDF file can
   !> decode its strings.
   pure function printable_utf8(s) result(t)
      character(len=*), intent(in) :: s
      character(len=len(s)) :: t
      integer :: i, n, m, c, c2, k
      logical :: ok
      t = s
      n = len(s)
      i = 1
      do while (i <= n)
         c = iachar(t(i:i))
         if (c < 32 .or. c == 127) then
            t(i:i) = " "
            i = i + 1
            cycle
         end if
         if (c < 128) then
            i = i + 1
            cycle
         end if
         m = 0
         if (c >= 194 .and. c <= 223) m = 1
         if (c >= 224 .and. c <= 239) m = 2
         if (c >= 240 .and. c <= 244) m = 3
         ok = m > 0 .and. i + m <= n
         if (ok) then
            do k = 1, m
               ok = ok .and. iachar(t(i+k:i+k)) >= 128 .and. iachar(t(i+k:i+k)) <= 191
            end do
         end if
         if (ok) then                     ! no overlong forms, surrogates, > U+10FFFF
            c2 = iachar(t(i+1:i+1))
            if (c == 224) ok = c2 >= 160
            if (c == 237) ok = c2 <= 159
            if (c == 240) ok = c2 >= 144
            if (c == 244) ok = c2 <= 143
         end if
         if (ok) then
            i = i + m + 1
         else
            t(i:i) = "?"
            i = i + 1
         end if
      end do
   end function printable_utf8

end module pavefric_batch_types
