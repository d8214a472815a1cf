!> The program's batch driver: MPI when built with it (profiles shared
!> round-robin among the ranks, OpenMP inside each), serial otherwise. Rank 0
!> records every finished profile in the journal and writes the NetCDF file;
!> the result is the same, bit for bit, whatever the number of ranks.
module pavefric_batch_mpi
#ifdef WITH_MPI
   use mpi
#endif
   use, intrinsic :: iso_fortran_env, only: output_unit
   use pavefric_kinds, only: wp
   use pavefric_error, only: error_type
   use pavefric_batch, only: batch_type, block_type, batch_prepare, batch_compute, &
      & journal_append, block_pack, block_unpack, block_values
   use pavefric_batch_run, only: run_batch_serial, batch_finish, progress_type, progress_start, &
      & progress_step
   implicit none
   private

   public :: run_batch_program, parallel_init, parallel_finalize, is_root

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
      call MPI_Initialized(mpi_running, ierr)
#else
      mpi_running = .false.
#endif
   end function mpi_running

   !> Whether this process is rank 0 (or the only one).
   logical function is_root()
#ifdef WITH_MPI
      integer :: rank, ierr
      is_root = .true.
      if (.not. mpi_running()) return
      call MPI_Comm_rank(MPI_COMM_WORLD, rank, ierr)
      is_root = rank == 0
#else
      is_root = .true.
#endif
   end function is_root

   !> Run a batch scene; `finished` is false when it stopped early (--max-profiles).
   subroutine run_batch_program(path, output_override, command, max_profiles, out_path, &
         & finished, error)
      character(len=*), intent(in) :: path, output_override, command
      !> Stop after computing this many profiles (0: all).
      integer, intent(in) :: max_profiles
      character(len=:), allocatable, intent(out) :: out_path
      logical, intent(out) :: finished
      type(error_type), allocatable, intent(out) :: error
#ifdef WITH_MPI
      type(batch_type) :: batch
      type(block_type), allocatable :: blocks(:)
      type(progress_type) :: progress
      integer, allocatable :: pending(:)
      real(wp), allocatable :: buf(:)
      character(len=4096) :: msg
      integer :: rank, nranks, ierr, i, k, nv, limit, received, expected, stat(MPI_STATUS_SIZE)
      logical :: flag
      real(wp), allocatable :: outbox(:,:)
      character(len=4096), allocatable :: notes(:)
      integer, allocatable :: requests(:)
      integer :: mine, nreq, j
      integer, parameter :: tag_values = 1, tag_message = 2

      finished = .false.
      nranks = 1
      rank = 0
      if (mpi_running()) then
         call MPI_Comm_rank(MPI_COMM_WORLD, rank, ierr)
         call MPI_Comm_size(MPI_COMM_WORLD, nranks, ierr)
      end if
      if (nranks == 1) then
         call run_batch_serial(path, output_override, command, output_unit, max_profiles, &
            & out_path, k, finished, error)
         return
      end if
      ! every rank reads the scene and the journal (read only on ranks > 0)
      if (rank == 0) then
         call batch_prepare(path, output_override, batch, blocks, error)
      end if
      call MPI_Barrier(MPI_COMM_WORLD, ierr)
      if (rank > 0) call batch_prepare_readonly(path, output_override, batch, blocks, error)
      if (allocated(error)) return
      out_path = batch%output
      pending = pack([(i, i = 1, batch%n_profiles)], [(blocks(i)%status == 0, i = 1, &
         & batch%n_profiles)])
      limit = size(pending)
      if (max_profiles > 0) limit = min(limit, max_profiles)
      pending = pending(1:limit)
      nv = block_values(batch)
      allocate(buf(nv))
      if (rank == 0) then
         if (batch%n_profiles - count([(blocks(i)%status == 0, i = 1, batch%n_profiles)]) > 0) &
            & write(output_unit, '(a, i0, a, i0, a)') "pavefric batch: resuming: ", &
            & count([(blocks(i)%status /= 0, i = 1, batch%n_profiles)]), " of ", &
            & batch%n_profiles, " profiles already done"
         write(output_unit, '(a, i0, a, i0, a)') "pavefric batch: ", size(pending), &
            & " profiles on ", nranks, " MPI ranks"
         call progress_start(progress, batch%n_profiles, count([(blocks(i)%status == 0, &
            & i = 1, batch%n_profiles)]), batch%scene%batch_progress_every, output_unit)
         received = 0
         expected = size(pending) - size(pending(1::nranks))
         do k = 1, size(pending), nranks
            call batch_compute(batch, pending(k), blocks(pending(k)))
            call journal_append(batch, blocks(pending(k)), error)
            if (allocated(error)) call MPI_Abort(MPI_COMM_WORLD, 1, ierr)
            call progress_step(progress, 1)
            call drain(.false.)
         end do
         do while (received < expected)
            call drain(.true.)
         end do
         ! finish once every profile is done (max_profiles may stop a run early)
         if (all([(blocks(i)%status /= 0, i = 1, batch%n_profiles)])) then
            call batch_finish(batch, blocks, command, error)
            finished = .not. allocated(error)
         end if
      else
         ! Non-blocking sends, one buffer each: a rank never waits for rank 0
         ! (busy computing its own share) to receive; all complete at the end.
         mine = size(pending(1 + rank::nranks))
         allocate(outbox(nv, mine), notes(mine), requests(2 * mine))
         nreq = 0
         j = 0
         do k = 1 + rank, size(pending), nranks
            j = j + 1
            call batch_compute(batch, pending(k), blocks(pending(k)))
            call block_pack(batch, blocks(pending(k)), outbox(:, j))
            nreq = nreq + 1
            call MPI_Isend(outbox(:, j), nv, MPI_DOUBLE_PRECISION, 0, tag_values, &
               & MPI_COMM_WORLD, requests(nreq), ierr)
            ! the reason is sent only for a failed profile
            if (blocks(pending(k))%status == 2) then
               notes(j) = blocks(pending(k))%message
               nreq = nreq + 1
               call MPI_Isend(notes(j), max(1, len_trim(notes(j))), MPI_CHARACTER, 0, &
                  & tag_message, MPI_COMM_WORLD, requests(nreq), ierr)
            end if
         end do
         call MPI_Waitall(nreq, requests, MPI_STATUSES_IGNORE, ierr)
      end if
      call MPI_Bcast(finished, 1, MPI_LOGICAL, 0, MPI_COMM_WORLD, ierr)
   contains
      subroutine drain(wait)
         logical, intent(in) :: wait
         integer :: src, nchar
         do
            if (received >= expected) return
            if (wait) then
               call MPI_Probe(MPI_ANY_SOURCE, tag_values, MPI_COMM_WORLD, stat, ierr)
            else
               call MPI_Iprobe(MPI_ANY_SOURCE, tag_values, MPI_COMM_WORLD, flag, stat, ierr)
               if (.not. flag) return
            end if
            src = stat(MPI_SOURCE)
            call MPI_Recv(buf, nv, MPI_DOUBLE_PRECISION, src, tag_values, MPI_COMM_WORLD, &
               & stat, ierr)
            i = nint(buf(1))
            call block_unpack(batch, buf, blocks(i))
            blocks(i)%message = ""
            if (blocks(i)%status == 2) then
               call MPI_Probe(src, tag_message, MPI_COMM_WORLD, stat, ierr)
               call MPI_Get_count(stat, MPI_CHARACTER, nchar, ierr)
               msg = ""
               call MPI_Recv(msg, nchar, MPI_CHARACTER, src, tag_message, MPI_COMM_WORLD, &
                  & stat, ierr)
               blocks(i)%message = msg(1:nchar)
            end if
            call journal_append(batch, blocks(i), error)
            if (allocated(error)) call MPI_Abort(MPI_COMM_WORLD, 1, ierr)
            received = received + 1
            call progress_step(progress, 1)
            if (wait) return
         end do
      end subroutine drain
#else
      integer :: computed
      call run_batch_serial(path, output_override, command, output_unit, max_profiles, out_path, &
         & computed, finished, error)
#endif
   end subroutine run_batch_program

#ifdef WITH_MPI
   !> batch_prepare on ranks > 0: rank 0 has already (re)started the journal.
   subroutine batch_prepare_readonly(path, output_override, batch, blocks, error)
      character(len=*), intent(in) :: path, output_override
      type(batch_type), intent(out) :: batch
      type(block_type), allocatable, intent(out) :: blocks(:)
      type(error_type), allocatable, intent(out) :: error
      ! the journal exists now, so batch_prepare only reads it (restart on)
      call batch_prepare(path, output_override, batch, blocks, error, read_only=.true.)
   end subroutine batch_prepare_readonly
#endif

end module pavefric_batch_mpi
