/* The library's only process-wide state: one mutex, and what fork() needs.
 *
 * The files lock. API sessions (pavefric_session) take it around their file
 * I/O: reading a scene file, reading its profile file (text or NetCDF),
 * writing the results (NetCDF). Two reasons: netCDF-C (and the HDF5 under
 * it) is not thread-safe, and the Fortran runtime refuses to connect one
 * file to two units at once ("File already opened in another unit"), so
 * two handles reading one scene file on two threads would fail. Everything
 * else (namelist parsing, preprocessing, the run itself, results, messages)
 * runs without a lock: it works on the handle's own data only. (An earlier
 * lock around every API call hid races on the hidden static variables in
 * which gfortran keeps the length of a deferred-length character function
 * result; the library has none now: docs/api.md, "Threads".)
 *
 * fork(). The lock is taken before a fork and released after it in parent
 * and child (pthread_atfork), so a child never inherits it held by a thread
 * that does not exist there. And libgomp keeps each thread's OpenMP thread
 * pool across fork(): in the child the pool's threads are gone, and the
 * next parallel region on the thread that forked waits for them forever.
 * So a thread that ran a parallel region of the library and then forked
 * runs the library's regions on one thread in the child (same results:
 * the thread count never changes a bit); threads the child creates get
 * pools of their own and run in parallel as usual. */
#include <pthread.h>

static pthread_mutex_t files_lock = PTHREAD_MUTEX_INITIALIZER;

void pavefric_lock_files(void)
{
    pthread_mutex_lock(&files_lock);
}

void pavefric_unlock_files(void)
{
    pthread_mutex_unlock(&files_lock);
}

/* Per thread: it ran a parallel region of the library (so libgomp gave it
 * a pool), and its pool is a copy from before a fork (unusable). */
static _Thread_local int ran_parallel = 0;
static _Thread_local int pool_forked = 0;

/* 1 if the calling thread may start a parallel region with more than one
 * thread, 0 if it must use one (its OpenMP pool came through a fork). */
int pavefric_parallel_ok(void)
{
    if (pool_forked) return 0;
    ran_parallel = 1;
    return 1;
}

static void before_fork(void)
{
    pthread_mutex_lock(&files_lock);
}

static void after_fork_parent(void)
{
    pthread_mutex_unlock(&files_lock);
}

static void after_fork_child(void)
{
    pthread_mutex_unlock(&files_lock);
    if (ran_parallel) pool_forked = 1;
}

__attribute__((constructor)) static void register_fork_handlers(void)
{
    pthread_atfork(before_fork, after_fork_parent, after_fork_child);
}
