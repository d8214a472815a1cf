!> Running a batch serially (the program without MPI, and Python), with
!> progress lines, and finishing it into one NetCDF file.
module pavefric_batch_run
   use, intrinsic :: iso_fortran_env, only: int64
   use pavefric_kinds, only: wp, pavefric_version
   use pavefric_error, only: error_type, fatal_error
   use pavefric_format, only: to_str
   use pavefric_batch, only: batch_type, block_type, batch_prepare, batch_compute, &
      & journal_append, journal_close
   use pavefric_batch_netcdf, only: write_batch_results
   use pavefric_run, only: timestamp
   use pavefric_fsys, only: remove_file
   implicit none
   private

   public :: run_batch_serial, batch_finish, progress_type, progress_start, progress_step

   !> Progress of a batch run, for log lines.
   type :: progress_type
      integer :: total = 0, done_before = 0, done = 0, every = 1, unit = -1
      integer(int64) :: t0 = 0, rate = 1
   end type progress_type

contains

   !> Start counting: `pending` profiles to compute of `total`.
   subroutine progress_start(p, total, pending, every, unit)
      type(progress_type), intent(out) :: p
      integer, intent(in) :: total, pending, every, unit
      p%total = total
      p%done_before = total - pending
      p%unit = unit
      p%every = every
      if (p%every <= 0) p%every = max(1, pending / 20)
      call system_clock(p%t0, p%rate)
   end subroutine progress_start

   !> One more profile done; a log line every `every` and at the end.
   subroutine progress_step(p, n)
      type(progress_type), intent(inout) :: p
      integer, intent(in) :: n
      integer(int64) :: t
      real(wp) :: seconds, rate, left
      integer :: before
      before = p%done
      p%done = p%done + n
      if (p%unit < 0) return
      if (p%done / p%every == before / p%every .and. p%done_before + p%done < p%total) return
      call system_clock(t)
      seconds = max(real(t - p%t0, wp) / real(p%rate, wp), 1.0e-9_wp)
      rate = real(p%done, wp) / seconds
      left = real(p%total - p%done_before - p%done, wp) / max(rate, 1.0e-12_wp)
      write(p%unit, '(a, i0, a, i0, a, f0.1, a, f0.1, a, i0, a)') "pavefric batch: ", &
         & p%done_before + p%done, "/", p%total, " profiles (", &
         & 100.0_wp * real(p%done_before + p%done, wp) / real(p%total, wp), " %), ", rate, &
         & " profiles/s, ", nint(left), " s left"
      flush(p%unit)
   end subroutine progress_step

   !> Write the NetCDF file from the blocks and remove the journal.
   subroutine batch_finish(batch, blocks, command, error)
      type(batch_type), intent(inout) :: batch
      type(block_type), intent(in) :: blocks(:)
      character(len=*), intent(in) :: command
      type(error_type), allocatable, intent(out) :: error
      logical :: ok
      integer :: i
      do i = 1, size(blocks)
         if (blocks(i)%status == 0) then
            call fatal_error(error, "batch: profile " // to_str(i) // " ('" // &
               & batch%paths(i)%s // "') is not computed yet")
            return
         end if
      end do
      call journal_close(batch)
      call write_batch_results(batch%output, batch, blocks, timestamp() // " pavefric " // &
         & pavefric_version // ": " // command, error)
      if (allocated(error)) return
      ok = remove_file(batch%journal)
   end subroutine batch_finish

   !> Run the batch scene in `path` in this process: compute the profiles the
   !> journal does not hold yet (at most `max_count` when > 0), record each, and write the NetCDF file once
   !> every profile is done (`finished`). Progress lines go to `log_unit`
   !> (none if negative).
   subroutine run_batch_serial(path, output_override, command, log_unit, max_count, out_path, &
         & computed, finished, error, n_total, n_done)
      character(len=*), intent(in) :: path, output_override, command
      integer, intent(in) :: log_unit, max_count
      character(len=:), allocatable, intent(out) :: out_path
      integer, intent(out) :: computed
      logical, intent(out) :: finished
      type(error_type), allocatable, intent(out) :: error
      !> Profiles in the batch, and done after this call.
      integer, intent(out), optional :: n_total, n_done
      type(batch_type) :: batch
      type(block_type), allocatable :: blocks(:)
      type(progress_type) :: progress
      integer :: i, pending, limit
      computed = 0
      finished = .false.
      call batch_prepare(path, output_override, batch, blocks, error)
      if (allocated(error)) return
      out_path = batch%output
      pending = count([(blocks(i)%status == 0, i = 1, size(blocks))])
      limit = pending
      if (max_count > 0) limit = min(limit, max_count)
      if (log_unit >= 0 .and. pending < batch%n_profiles) write(log_unit, '(a, i0, a, i0, a)') &
         & "pavefric batch: resuming: ", batch%n_profiles - pending, " of ", batch%n_profiles, &
         & " profiles already done"
      call progress_start(progress, batch%n_profiles, pending, batch%scene%batch_progress_every, &
         & log_unit)
      do i = 1, batch%n_profiles
         if (computed >= limit) exit
         if (blocks(i)%status /= 0) cycle
         call batch_compute(batch, i, blocks(i))
         call journal_append(batch, blocks(i), error)
         if (allocated(error)) return
         computed = computed + 1
         call progress_step(progress, 1)
      end do
      if (present(n_total)) n_total = batch%n_profiles
      if (present(n_done)) n_done = batch%n_profiles - pending + computed
      if (computed < pending) then           ! stopped early: the journal keeps the work
         call journal_close(batch)
         return
      end if
      call batch_finish(batch, blocks, command, error)
      finished = .not. allocated(error)
   end subroutine run_batch_serial

end module pavefric_batch_run
