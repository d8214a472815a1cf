!> The program's batch driver: MPI when built with it, serial otherwise.
!>
!> Under MPI, rank 0 alone decides the work: it reads (or starts) the
!> journal, and hands the pending profiles out as ranks become free, the
!> largest files first (so the last to finish are small: the ranks end
!> together), two queued per rank. Rank 0 computes too, taking the next
!> profile in the same order and answering the others between two of its
!> own: a rank's queued profile was handed out before the one rank 0 took,
!> so it is at least as large, and no rank waits for rank 0 to answer.
!> Rank 0 records every result in the journal and
!> writes the NetCDF file, so the result is the same, bit for bit, whatever
!> the number of ranks and the order profiles finish in. An error on any
!> rank ends every rank with the same message and exit status (no rank is
!> left waiting).
module pavefric_batch_mpi
#ifdef WITH_MPI
   use mpi
#endif
   use, intrinsic :: iso_fortran_env, only: int64
   use pavefric_kinds, only: wp
   use pavefric_error, only: error_type, fatal_error
   use pavefric_format, only: to_str
   use pavefric_batch, only: batch_type, block_type, batch_setup, batch_prepare, batch_compute, &
      & journal_append, journal_close, block_pack, block_unpack, block_values, profile_cost, &
      & status_failed
   use pavefric_batch_types, only: block_allocate
   use pavefric_batch_hash, only: digest_len
   use pavefric_batch_run, only: run_batch_serial, batch_finish, progress_type, progress_start, &
      & progress_step, batch_summary_type, summarize, resume_note
   implicit none
   private

   public :: run_batch_program, parallel_init, parallel_finalize, is_root, agree_error

#ifdef WITH_MPI
   integer, parameter :: tag_work = 1, tag_result = 2, tag_text = 3
   !> Profiles queued at each worker rank.
   integer, parameter :: queue_depth = 2
#endif

contains

   !> Start MPI when built with it and launched by an MPI launcher (mpirun,
   !> srun): a plain run does not pay for MPI's start-up.
   subroutine parallel_init()
#ifdef WITH_MPI
      integer :: ierr
      if (launched_by_mpi()) call MPI_Init(ierr)
#endif
   end subroutine parallel_init

   subroutine parallel_finalize()
#ifdef WITH_MPI
      integer :: ierr
      logical :: up, down
      call MPI_Initialized(up, ierr)
      call MPI_Finalized(down, ierr)
      if (up .and. .not. down) call MPI_Finalize(ierr)
#endif
   end subroutine parallel_finalize

   !> Whether an MPI launcher started this process (Open MPI, MPICH/Hydra,
   !> PMIx and SLURM's srun set these).
   logical function launched_by_mpi()
      character(len=*), parameter :: names(5) = [character(len=20) :: &
         & "OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_RANK", "PMI_RANK", "MPI_LOCALNRANKS"]
      integer :: k, length, stat
      launched_by_mpi = .false.
      do k = 1, size(names)
         call get_environment_variable(trim(names(k)), length=length, status=stat)
         if (stat == 0) launched_by_mpi = .true.
      end do
   end function launched_by_mpi

   !> Whether MPI is running in this process.
   logical function mpi_running()
#ifdef WITH_MPI
      integer :: ierr
      logical :: down
      call MPI_Initialized(mpi_running, ierr)
      if (mpi_running) then
         call MPI_Finalized(down, ierr)
         mpi_running = .not. down
      end if
#else
      mpi_running = .false.
#endif
   end function mpi_running

   !> This rank and the number of ranks (0 and 1 without MPI).
   subroutine rank_and_size(rank, nranks)
      integer, intent(out) :: rank, nranks
#ifdef WITH_MPI
      integer :: ierr
#endif
      rank = 0
      nranks = 1
#ifdef WITH_MPI
      if (.not. mpi_running()) return
      call MPI_Comm_rank(MPI_COMM_WORLD, rank, ierr)
      call MPI_Comm_size(MPI_COMM_WORLD, nranks, ierr)
#endif
   end subroutine rank_and_size

   !> Whether this process is rank 0 (or the only one).
   logical function is_root()
      integer :: rank, nranks
      call rank_and_size(rank, nranks)
      is_root = rank == 0
   end function is_root

   !> Collective (every rank calls it): afterwards every rank holds the same
   !> error, the one of the lowest rank that had one, or none. Without MPI
   !> it does nothing.
   subroutine agree_error(error)
      type(error_type), allocatable, intent(inout) :: error
#ifdef WITH_MPI
      integer :: rank, nranks, ierr, first, info(2)
      character(len=:), allocatable :: message
      call rank_and_size(rank, nranks)
      if (nranks == 1) return
      call MPI_Allreduce(merge(rank, nranks, allocated(error)), first, 1, MPI_INTEGER, MPI_MIN, &
         & MPI_COMM_WORLD, ierr)
      if (first == nranks) return
      info = 0
      if (rank == first) info = [error%stat, len(error%message)]
      call MPI_Bcast(info, 2, MPI_INTEGER, first, MPI_COMM_WORLD, ierr)
      allocate(character(len=info(2)) :: message)
      if (rank == first) message = error%message
      if (info(2) > 0) call MPI_Bcast(message, info(2), MPI_CHARACTER, first, MPI_COMM_WORLD, ierr)
      if (allocated(error)) deallocate(error)
      call fatal_error(error, message, info(1))
#endif
   end subroutine agree_error

   !> Run a batch scene; every rank returns the same error (or none) and the
   !> same summary's `finished` and `failed`, so that all exit alike.
   subroutine run_batch_program(path, output_override, command, max_profiles, log_unit, &
         & summary, error)
      character(len=*), intent(in) :: path, output_override, command
      !> Stop after computing this many profiles (0: all).
      integer, intent(in) :: max_profiles
      !> Where rank 0 writes progress lines (the program: stderr; none if
      !> negative, --quiet).
      integer, intent(in) :: log_unit
      type(batch_summary_type), intent(out) :: summary
      type(error_type), allocatable, intent(out) :: error
      character(len=:), allocatable :: out_path
      integer :: computed, rank, nranks
      logical :: finished
#ifdef WITH_MPI
      type(batch_type) :: batch
      type(block_type), allocatable :: blocks(:)
      character(len=digest_len) :: fingerprint
      integer :: ierr, outcome(4)
      real(wp) :: cpu0, cpu1
      real(wp), allocatable :: cpu(:)
#endif
      call rank_and_size(rank, nranks)
      if (nranks == 1) then
         call run_batch_serial(path, output_override, command, log_unit, max_profiles, &
            & out_path, computed, finished, error, summary=summary)
         return
      end if
#ifdef WITH_MPI
      ! Rank 0 reads the scene and the journal (or starts one); the others
      ! only read the scene and the profile list, and check they read the
      ! same inputs as rank 0. Any error ends every rank.
      if (rank == 0) then
         call batch_prepare(path, output_override, batch, blocks, error)
      else
         call batch_setup(path, output_override, batch, error)
      end if
      fingerprint = ""
      if (rank == 0 .and. .not. allocated(error)) fingerprint = batch%fingerprint
      call MPI_Bcast(fingerprint, digest_len, MPI_CHARACTER, 0, MPI_COMM_WORLD, ierr)
      if (rank > 0 .and. .not. allocated(error) .and. len_trim(fingerprint) > 0 .and. &
            & fingerprint /= batch%fingerprint) call fatal_error(error, "MPI rank " // &
            & to_str(rank) // " read other inputs than rank 0 (the scene or its profiles " // &
            & "changed while the ranks started); run the batch again")
      call agree_error(error)
      if (allocated(error)) return

      call cpu_time(cpu0)
      if (rank == 0) then
         call serve_and_compute(batch, blocks, nranks, max_profiles, command, log_unit, summary, &
            & error)
      else
         call work(batch)
      end if
      ! how evenly the work was shared: each rank's CPU time (unaffected by
      ! other jobs on the node, unlike wall time)
      call cpu_time(cpu1)
      allocate(cpu(nranks))
      cpu1 = cpu1 - cpu0
      call MPI_Gather(cpu1, 1, MPI_DOUBLE_PRECISION, cpu, 1, MPI_DOUBLE_PRECISION, 0, &
         & MPI_COMM_WORLD, ierr)
      if (rank == 0 .and. .not. allocated(error) .and. log_unit >= 0) then
         write(log_unit, '(a, *(1x, f0.2))') "pavefric batch: CPU seconds per rank:", cpu
         write(log_unit, '(a, f0.3, a)') "pavefric batch: the busiest rank ", &
            & maxval(cpu) / max(sum(cpu) / nranks, tiny(1.0_wp)), " x the mean"
      end if
      ! rank 0 tells every rank how it ended
      call agree_error(error)
      if (allocated(error)) return
      outcome = [merge(1, 0, summary%finished), summary%failed, summary%total, summary%left]
      call MPI_Bcast(outcome, 4, MPI_INTEGER, 0, MPI_COMM_WORLD, ierr)
      if (rank > 0) then
         summary%finished = outcome(1) == 1
         summary%failed = outcome(2)
         summary%total = outcome(3)
         summary%left = outcome(4)
      end if
#endif
   end subroutine run_batch_program

#ifdef WITH_MPI
   !> Rank 0: hand out the pending profiles (largest first) to the other
   !> ranks as they become free, compute the next one itself between
   !> messages, record every result, and write the file when all are done.
   subroutine serve_and_compute(batch, blocks, nranks, max_profiles, command, log_unit, &
         & summary, error)
      type(batch_type), intent(inout) :: batch
      type(block_type), intent(inout) :: blocks(:)
      integer, intent(in) :: nranks, max_profiles
      !> Progress lines here (none if negative).
      integer, intent(in) :: log_unit
      character(len=*), intent(in) :: command
      type(batch_summary_type), intent(out) :: summary
      type(error_type), allocatable, intent(out) :: error
      type(progress_type) :: progress
      integer, allocatable :: pending(:), order(:), outstanding(:)
      integer(int64), allocatable :: cost(:)
      logical, allocatable :: stopped(:)
      real(wp), allocatable :: values(:)
      character(len=:), allocatable :: note
      integer :: i, k, w, q, front, back, computed, nv, ierr
      logical :: finished

      nv = block_values(batch)
      allocate(values(nv))
      pending = pack([(i, i = 1, batch%n_profiles)], [(blocks(i)%status == 0, i = 1, &
         & batch%n_profiles)])
      if (max_profiles > 0 .and. max_profiles < size(pending)) pending = pending(1:max_profiles)
      ! largest files first (a stable sort: ties keep the profile order)
      allocate(cost(size(pending)))
      do k = 1, size(pending)
         cost(k) = profile_cost(batch, pending(k))
      end do
      order = sorted_by_cost(pending, cost)
      front = 1
      back = size(order)
      computed = 0

      note = resume_note(batch)
      if (log_unit >= 0) then
         if (len(note) > 0) write(log_unit, '(a)') note
         write(log_unit, '(a, i0, a, i0, a)') "pavefric batch: ", size(order), &
            & " profiles on ", nranks, " MPI ranks"
         flush(log_unit)
      end if
      call progress_start(progress, batch%n_profiles, count([(blocks(i)%status == 0, &
         & i = 1, batch%n_profiles)]), batch%scene%batch_progress_every, log_unit)

      allocate(outstanding(nranks - 1), stopped(nranks - 1))
      outstanding = 0
      stopped = .false.
      do q = 1, queue_depth
         do w = 1, nranks - 1
            if (front <= back) then
               call MPI_Send(order(front), 1, MPI_INTEGER, w, tag_work, MPI_COMM_WORLD, ierr)
               front = front + 1
               outstanding(w) = outstanding(w) + 1
            end if
         end do
      end do
      do w = 1, nranks - 1
         if (outstanding(w) == 0) call stop_worker(w)
      end do

      do
         call serve(.false.)
         if (front <= back .and. .not. allocated(error)) then
            i = order(front)
            front = front + 1
            call batch_compute(batch, i, blocks(i))
            call record(i)
            cycle
         end if
         if (all(stopped)) exit
         call serve(.true.)
      end do

      if (allocated(error)) then
         call journal_close(batch)
         return
      end if
      finished = all([(blocks(i)%status /= 0, i = 1, batch%n_profiles)])
      if (finished) then
         call batch_finish(batch, blocks, command, error)
      else
         call journal_close(batch, error)
      end if
      if (allocated(error)) return
      call summarize(batch, blocks, computed, finished, summary)
   contains
      !> Receive the results that arrived (wait for one when `wait`), and
      !> give the rank that sent each its next profile, or stop it.
      subroutine serve(wait)
         logical, intent(in) :: wait
         integer :: status(MPI_STATUS_SIZE), nchar, j
         logical :: flag
         character(len=:), allocatable :: text
         do
            if (all(stopped)) return
            if (wait) then
               call MPI_Probe(MPI_ANY_SOURCE, tag_result, MPI_COMM_WORLD, status, ierr)
            else
               call MPI_Iprobe(MPI_ANY_SOURCE, tag_result, MPI_COMM_WORLD, flag, status, ierr)
               if (.not. flag) return
            end if
            w = status(MPI_SOURCE)
            call MPI_Recv(values, nv, MPI_DOUBLE_PRECISION, w, tag_result, MPI_COMM_WORLD, &
               & status, ierr)
            call MPI_Probe(w, tag_text, MPI_COMM_WORLD, status, ierr)
            call MPI_Get_count(status, MPI_CHARACTER, nchar, ierr)
            allocate(character(len=nchar) :: text)
            call MPI_Recv(text, nchar, MPI_CHARACTER, w, tag_text, MPI_COMM_WORLD, status, ierr)
            outstanding(w) = outstanding(w) - 1
            if (.not. allocated(error)) then
               j = nint(values(1))
               call block_allocate(batch, blocks(j))
               call block_unpack(batch, values, blocks(j))
               blocks(j)%digest = text(1:digest_len)
               blocks(j)%message = text(digest_len+1:)
               call record(j)
            end if
            deallocate(text)
            if (front <= back .and. .not. allocated(error)) then
               call MPI_Send(order(front), 1, MPI_INTEGER, w, tag_work, MPI_COMM_WORLD, ierr)
               front = front + 1
               outstanding(w) = outstanding(w) + 1
            else if (outstanding(w) == 0) then
               call stop_worker(w)
            end if
            if (wait) return
         end do
      end subroutine serve

      subroutine stop_worker(rank)
         integer, intent(in) :: rank
         integer :: stop_index
         stop_index = 0
         call MPI_Send(stop_index, 1, MPI_INTEGER, rank, tag_work, MPI_COMM_WORLD, ierr)
         stopped(rank) = .true.
      end subroutine stop_worker

      !> A finished profile into the journal (an error stops handing out work).
      subroutine record(j)
         integer, intent(in) :: j
         call journal_append(batch, blocks(j), error)
         if (allocated(error)) return
         computed = computed + 1
         call progress_step(progress, blocks(j)%status == status_failed)
      end subroutine record
   end subroutine serve_and_compute

   !> Ranks > 0: compute the profiles rank 0 sends until it says stop (0),
   !> sending each result back without waiting for rank 0 to take it.
   subroutine work(batch)
      type(batch_type), intent(inout) :: batch
      type(block_type) :: blk
      real(wp), allocatable :: outbox(:,:)
      type :: text_type
         character(len=:), allocatable :: s
      end type text_type
      type(text_type) :: texts(queue_depth)
      integer :: requests(2 * queue_depth), slot, i, nv, ierr, status(MPI_STATUS_SIZE)
      nv = block_values(batch)
      allocate(outbox(nv, queue_depth))
      requests = MPI_REQUEST_NULL
      slot = 0
      do
         call MPI_Recv(i, 1, MPI_INTEGER, 0, tag_work, MPI_COMM_WORLD, status, ierr)
         if (i <= 0) exit
         slot = mod(slot, queue_depth) + 1
         call MPI_Waitall(2, requests(2*slot-1:2*slot), MPI_STATUSES_IGNORE, ierr)
         call batch_compute(batch, i, blk)
         call block_pack(batch, blk, outbox(:, slot))
         texts(slot)%s = blk%digest // blk%message
         call MPI_Isend(outbox(:, slot), nv, MPI_DOUBLE_PRECISION, 0, tag_result, &
            & MPI_COMM_WORLD, requests(2*slot-1), ierr)
         call MPI_Isend(texts(slot)%s, len(texts(slot)%s), MPI_CHARACTER, 0, tag_text, &
            & MPI_COMM_WORLD, requests(2*slot), ierr)
      end do
      call MPI_Waitall(2 * queue_depth, requests, MPI_STATUSES_IGNORE, ierr)
   end subroutine work

   !> `pending` ordered by decreasing cost, ties in their order (merge sort).
   function sorted_by_cost(pending, cost) result(order)
      integer, intent(in) :: pending(:)
      integer(int64), intent(in) :: cost(:)
      integer, allocatable :: order(:)
      integer, allocatable :: idx(:), work(:)
      integer :: k
      allocate(idx(size(pending)), work(size(pending)))
      do k = 1, size(pending)
         idx(k) = k
      end do
      call sort(1, size(idx))
      order = pending(idx)
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
               work(k) = idx(a); a = a + 1
            else if (a > mid) then
               work(k) = idx(b); b = b + 1
            else if (cost(idx(a)) >= cost(idx(b))) then
               work(k) = idx(a); a = a + 1
            else
               work(k) = idx(b); b = b + 1
            end if
         end do
         idx(lo:hi) = work(lo:hi)
      end subroutine sort
   end function sorted_by_cost
#endif

end module pavefric_batch_mpi
