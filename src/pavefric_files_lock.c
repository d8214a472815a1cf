/* One lock around the file I/O of API sessions (pavefric_session): the
 * Fortran runtime refuses to connect one file to two units at once ("File
 * already opened in another unit"), and netCDF-C is not thread-safe. So two
 * scene handles used from two threads read their scene and profile files
 * and write their NetCDF files one at a time; their runs (the model itself)
 * go in parallel. The only process-wide state of the library, and it is
 * a mutex, not data. */
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

/* One lock around every call of the C/Fortran API on a scene handle
 * (pavefric_api): handles used from several threads at once were measured
 * (tests/test_api.py, gfortran 12) to corrupt the namelist text a
 * concurrent call was building, now and then, while a run went on in
 * another thread; the cause inside the Fortran runtime was not found. So
 * API calls run one at a time; a run's own parallelism (OpenMP over the
 * speeds) is unchanged. */
static pthread_mutex_t api_lock = PTHREAD_MUTEX_INITIALIZER;

void pavefric_api_lock(void)
{
    pthread_mutex_lock(&api_lock);
}

void pavefric_api_unlock(void)
{
    pthread_mutex_unlock(&api_lock);
}
