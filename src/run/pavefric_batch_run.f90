!> Running a batch serially (the program without MPI, and Python), with
!> progress lines, and finishing it into one NetCDF file; the summary of a
!> run (what the program's last lines and exit status report).
module pavefric_batch_run
   use, intrinsic :: iso_fortran_env, only: int64
   use pavefric_kinds, only: wp, pavefric_version
   use pavefric_error, only: error_type, fatal_error, stat_internal
   use pavefric_format, only: to_str
   use pavefric_batch, only: batch_type, block_type, string_type, batch_prepare, batch_compute, &
      & journal_append, journal_close, status_failed
   use pavefric_batch_netcdf, only: write_batch_results
   use pavefric_model, only: model_type
   use pavefric_rubber, only: rubber_model
   use pavefric_film, only: film_model
   use pavefric_components, only: make_components
   use pavefric_run, only: timestamp
   use pavefric_fsys, only: remove_file
   implicit none
   private

   public :: run_batch_serial, batch_finish, progress_type, progress_start, progress_step, &
      & batch_summary_type, summarize, resume_note, max_failures_listed

   !> Failed profiles named in a summary (the output names them all).
   integer, parameter :: max_failures_listed = 10

   !> Progress of a batch run, for log lines.
   type :: progress_type
      integer :: total = 0, done_before = 0, done = 0, failed = 0, every = 1, unit = -1
      integer(int64) :: t0 = 0, rate = 1
   end type progress_type

   !> What a batch run did: the program's summary line and exit status.
   type :: batch_summary_type
      !> Profiles in the batch, done in this run (failed included), taken from the journal,
      !> still to compute, and failed (among all done).
      integer :: total = 0, computed = 0, from_journal = 0, left = 0, failed = 0
      !> Computed profiles with warnings (recorded in the output's n_warnings
      !> and warning_message), and those warnings counted.
      integer :: warned = 0, warnings = 0
      !> Journal lines found damaged (recomputed), profiles changed since.
      integer :: damaged = 0, changed = 0
      !> Every profile is done and the output is written.
      logical :: finished = .false.
      character(len=:), allocatable :: output
      !> "name: message" of the first failed profiles.
      type(string_type), allocatable :: failures(:)
      !> "name: first warning" of the first profiles with warnings.
      type(string_type), allocatable :: warned_profiles(:)
   end type batch_summary_type

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

   !> One more profile done (`failed`: it failed); a log line every `every`
   !> and at the end.
   subroutine progress_step(p, failed)
      type(progress_type), intent(inout) :: p
      logical, intent(in) :: failed
      integer(int64) :: t
      real(wp) :: seconds, rate, left
      integer :: before
      character(len=:), allocatable :: failures
      before = p%done
      p%done = p%done + 1
      if (failed) p%failed = p%failed + 1
      if (p%unit < 0) return
      if (p%done / p%every == before / p%every .and. p%done_before + p%done < p%total) return
      call system_clock(t)
      seconds = max(real(t - p%t0, wp) / real(p%rate, wp), 1.0e-9_wp)
      rate = real(p%done, wp) / seconds
      left = real(p%total - p%done_before - p%done, wp) / max(rate, 1.0e-12_wp)
      failures = ""
      if (p%failed > 0) failures = ", " // to_str(p%failed) // " failed"
      write(p%unit, '(a, i0, a, i0, a, f0.1, a, f0.1, a, i0, a)') "pavefric batch: ", &
         & p%done_before + p%done, "/", p%total, " profiles (", &
         & 100.0_wp * real(p%done_before + p%done, wp) / real(p%total, wp), " %" // failures // &
         & "), ", rate, " profiles/s, ", nint(left), " s left"
      flush(p%unit)
   end subroutine progress_step

   !> The line saying what a resume took from the journal (empty if nothing).
   pure function resume_note(batch) result(text)
      type(batch_type), intent(in) :: batch
      character(len=resume_note_len(batch)) :: text
      character(len=:), allocatable :: deferred_text
      call resume_note_text(batch, deferred_text)
      text = deferred_text
   end function resume_note

   !> The length of resume_note's text.
   pure integer function resume_note_len(batch)
      type(batch_type), intent(in) :: batch
      character(len=:), allocatable :: deferred_text
      call resume_note_text(batch, deferred_text)
      resume_note_len = len(deferred_text)
   end function resume_note_len

   !> The text of resume_note, into a deferred-length argument.
   pure subroutine resume_note_text(batch, text)
      type(batch_type), intent(in) :: batch
      character(len=:), allocatable, intent(out) :: text
      text = ""
      if (batch%journal_taken > 0) call add(text, "resuming: " // to_str(batch%journal_taken) // &
         & " of " // to_str(batch%n_profiles) // " profiles already done")
      if (batch%journal_damaged > 0) call add(text, to_str(batch%journal_damaged) // &
         & " damaged journal line(s) ignored (their profiles are recomputed)")
      if (batch%journal_changed > 0) call add(text, to_str(batch%journal_changed) // &
         & " profile file(s) changed since the journal (recomputed)")
      if (len(text) > 0) text = "pavefric batch: " // text
   contains
      pure subroutine add(text, part)
         character(len=:), allocatable, intent(inout) :: text
         character(len=*), intent(in) :: part
         if (len(text) > 0) text = text // "; "
         text = text // part
      end subroutine add
   end subroutine resume_note_text

   !> The summary of a run that computed `computed` profiles.
   subroutine summarize(batch, blocks, computed, finished, s)
      type(batch_type), intent(in) :: batch
      type(block_type), intent(in) :: blocks(:)
      integer, intent(in) :: computed
      logical, intent(in) :: finished
      type(batch_summary_type), intent(out) :: s
      integer :: i, k, eol
      s%total = batch%n_profiles
      s%computed = computed
      s%from_journal = batch%journal_taken
      s%left = count([(blocks(i)%status == 0, i = 1, size(blocks))])
      s%failed = count([(blocks(i)%status == status_failed, i = 1, size(blocks))])
      s%damaged = batch%journal_damaged
      s%changed = batch%journal_changed
      s%finished = finished
      s%output = batch%output
      allocate(s%failures(min(s%failed, max_failures_listed)))
      k = 0
      do i = 1, size(blocks)
         if (k == size(s%failures)) exit
         if (blocks(i)%status /= status_failed) cycle
         k = k + 1
         s%failures(k)%s = batch%names(i)%s // ": " // blocks(i)%message
      end do
      s%warned = count([(blocks(i)%status /= status_failed .and. blocks(i)%n_warnings > 0, &
         & i = 1, size(blocks))])
      s%warnings = sum([(merge(blocks(i)%n_warnings, 0, blocks(i)%status /= status_failed), &
         & i = 1, size(blocks))])
      allocate(s%warned_profiles(min(s%warned, max_failures_listed)))
      k = 0
      do i = 1, size(blocks)
         if (k == size(s%warned_profiles)) exit
         if (blocks(i)%status == status_failed .or. blocks(i)%n_warnings == 0) cycle
         k = k + 1
         eol = index(blocks(i)%message // achar(10), achar(10))
         s%warned_profiles(k)%s = batch%names(i)%s // ": " // blocks(i)%message(1:eol-1)
         if (blocks(i)%n_warnings > 1) s%warned_profiles(k)%s = s%warned_profiles(k)%s // &
            & " (and " // to_str(blocks(i)%n_warnings - 1) // " more)"
      end do
   end subroutine summarize

   !> Write the NetCDF file from the blocks and remove the journal.
   subroutine batch_finish(batch, blocks, command, error)
      type(batch_type), intent(inout) :: batch
      type(block_type), intent(in) :: blocks(:)
      character(len=*), intent(in) :: command
      type(error_type), allocatable, intent(out) :: error
      logical :: ok
      integer :: i
      type(model_type) :: m
      class(rubber_model), allocatable :: rubber
      class(film_model), allocatable :: film
      character(len=:), allocatable :: film_effect
      do i = 1, size(blocks)
         if (blocks(i)%status == 0) then
            call fatal_error(error, "batch: profile " // to_str(i) // " ('" // &
               & batch%paths(i)%s // "') is not computed yet", stat_internal)
            return
         end if
      end do
      call journal_close(batch, error)
      if (allocated(error)) return
      ! the name of the scene's film (the same wet model at every depth), for
      ! the file's effects where a film ran
      m = batch%scene%model
      m%depth = maxval([0.0_wp, batch%depths])
      call make_components(m, rubber, film)
      film_effect = ""
      if (allocated(film)) call film%effect(film_effect)
      call write_batch_results(batch%output, batch, blocks, timestamp() // " pavefric " // &
         & pavefric_version // ": " // command, film_effect, error)
      if (allocated(error)) return
      ok = remove_file(batch%journal)
   end subroutine batch_finish

   !> Run the batch scene in `path` in this process: compute the profiles the
   !> journal does not hold yet (at most `max_count` when > 0), record each,
   !> and write the NetCDF file once every profile is done (`finished`).
   !> Progress lines go to `log_unit` (none if negative).
   subroutine run_batch_serial(path, output_override, command, log_unit, max_count, out_path, &
         & computed, finished, error, n_total, n_done, summary)
      character(len=*), intent(in) :: path, output_override, command
      integer, intent(in) :: log_unit, max_count
      character(len=:), allocatable, intent(out) :: out_path
      integer, intent(out) :: computed
      logical, intent(out) :: finished
      type(error_type), allocatable, intent(out) :: error
      !> Profiles in the batch, and done after this call.
      integer, intent(out), optional :: n_total, n_done
      !> What the run did (for the program's last lines and exit status).
      type(batch_summary_type), intent(out), optional :: summary
      type(batch_type) :: batch
      type(block_type), allocatable :: blocks(:)
      type(progress_type) :: progress
      character(len=:), allocatable :: note
      integer :: i, pending, limit
      computed = 0
      finished = .false.
      call batch_prepare(path, output_override, batch, blocks, error)
      if (allocated(error)) return
      out_path = batch%output
      pending = count([(blocks(i)%status == 0, i = 1, size(blocks))])
      limit = pending
      if (max_count > 0) limit = min(limit, max_count)
      note = resume_note(batch)
      if (log_unit >= 0 .and. len(note) > 0) write(log_unit, '(a)') note
      call progress_start(progress, batch%n_profiles, pending, batch%scene%batch_progress_every, &
         & log_unit)
      do i = 1, batch%n_profiles
         if (computed >= limit) exit
         if (blocks(i)%status /= 0) cycle
         call batch_compute(batch, i, blocks(i))
         call journal_append(batch, blocks(i), error)
         if (allocated(error)) then
            call journal_close(batch)
            return
         end if
         computed = computed + 1
         call progress_step(progress, blocks(i)%status == status_failed)
      end do
      if (present(n_total)) n_total = batch%n_profiles
      if (present(n_done)) n_done = batch%n_profiles - pending + computed
      if (computed == pending) then
         call batch_finish(batch, blocks, command, error)
         if (allocated(error)) return
         finished = .true.
      else                                 ! stopped early: the journal keeps the work
         call journal_close(batch, error)
         if (allocated(error)) return
      end if
      if (present(summary)) call summarize(batch, blocks, computed, finished, summary)
   end subroutine run_batch_serial

end module pavefric_batch_run
