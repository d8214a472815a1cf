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
