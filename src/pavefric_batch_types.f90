!> The data of a batch run: its profiles and each profile's results, and
!> their packing into reals (for the journal and for MPI messages).
module pavefric_batch_types
   use pavefric_kinds, only: wp
   use pavefric_scene, only: scene_type
   implicit none
   private

   public :: batch_type, block_type, string_type, block_pack, block_unpack, block_values

   !> A string in an array of strings.
   type :: string_type
      character(len=:), allocatable :: s
   end type string_type

   !> A batch: the scene, the profiles, depths and speeds, and its journal.
   type :: batch_type
      type(scene_type) :: scene
      type(string_type), allocatable :: paths(:), names(:)
      real(wp), allocatable :: depths(:), speeds(:)
      integer :: n_profiles = 0, n_depths = 0, n_speeds = 0
      character(len=:), allocatable :: output, journal, fingerprint
      !> The journal's unit while it is open for appending (newunit numbers
      !> are negative, hence the flag).
      integer :: journal_unit = 0
      logical :: journal_open = .false.
   end type batch_type

   !> One profile's results (arrays are speed x depth).
   type :: block_type
      integer :: index = 0
      !> 1: computed; 2: failed (message says why).
      integer :: status = 0
      logical :: has_texture = .false.
      real(wp) :: mpd = 0, rms_height = 0, rms_slope = 0
      real(wp), allocatable :: mu(:,:), wet(:,:), hydroplaning(:,:), residual(:,:)
      real(wp), allocatable :: n_clamped(:,:)
      logical :: viscous = .false., bearing = .false.
      character(len=:), allocatable :: message
   end type block_type

contains

   !> Number of reals in a packed block.
   pure integer function block_values(batch)
      type(batch_type), intent(in) :: batch
      block_values = 9 + 5 * batch%n_speeds * batch%n_depths
   end function block_values

   !> A block as reals (for the journal and for MPI).
   pure subroutine block_pack(batch, blk, values)
      type(batch_type), intent(in) :: batch
      type(block_type), intent(in) :: blk
      real(wp), intent(out) :: values(:)
      integer :: m
      m = batch%n_speeds * batch%n_depths
      values(1:9) = [real(blk%index, wp), real(blk%status, wp), merge(1.0_wp, 0.0_wp, &
         & blk%has_texture), blk%mpd, blk%rms_height, blk%rms_slope, merge(1.0_wp, 0.0_wp, &
         & blk%viscous), merge(1.0_wp, 0.0_wp, blk%bearing), 0.0_wp]
      values(10:9+m) = reshape(blk%mu, [m])
      values(10+m:9+2*m) = reshape(blk%wet, [m])
      values(10+2*m:9+3*m) = reshape(blk%hydroplaning, [m])
      values(10+3*m:9+4*m) = reshape(blk%residual, [m])
      values(10+4*m:9+5*m) = reshape(blk%n_clamped, [m])
   end subroutine block_pack

   !> The inverse of block_pack.
   pure subroutine block_unpack(batch, values, blk)
      type(batch_type), intent(in) :: batch
      real(wp), intent(in) :: values(:)
      type(block_type), intent(inout) :: blk
      integer :: m, ns, nd
      ns = batch%n_speeds
      nd = batch%n_depths
      m = ns * nd
      blk%index = nint(values(1))
      blk%status = nint(values(2))
      blk%has_texture = values(3) > 0.5_wp
      blk%mpd = values(4)
      blk%rms_height = values(5)
      blk%rms_slope = values(6)
      blk%viscous = values(7) > 0.5_wp
      blk%bearing = values(8) > 0.5_wp
      blk%mu = reshape(values(10:9+m), [ns, nd])
      blk%wet = reshape(values(10+m:9+2*m), [ns, nd])
      blk%hydroplaning = reshape(values(10+2*m:9+3*m), [ns, nd])
      blk%residual = reshape(values(10+3*m:9+4*m), [ns, nd])
      blk%n_clamped = reshape(values(10+4*m:9+5*m), [ns, nd])
      if (.not. allocated(blk%message)) blk%message = ""
   end subroutine block_unpack

end module pavefric_batch_types
