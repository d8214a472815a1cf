/* NetCDF-4 outputs built in memory and written to disk by pavefric itself.
 *
 * Why: when a write to disk fails inside HDF5 (a full disk, a quota, a
 * file-size limit), netCDF-C 4.9 cannot close the file any more: nc_close
 * returns the error with the HDF5 file still open, nc_abort crashes while
 * listing the objects left open, and HDF5's exit handler crashes closing
 * it (SIGSEGV, exit 139; in Python a segfault after PavefricError). So
 * HDF5 never writes to disk here: the file lives in memory (nc_create_mem)
 * until it is complete, and its bytes are then written with write(2),
 * whose failures are ordinary errors with an errno. */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <fcntl.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include <netcdf.h>
#include <netcdf_mem.h>

void pavefric_test_pause(const char *point);

/* The end of the HDF5 data in a file image: the "end of file address" of
 * its superblock (HDF5 File Format Specification, section II.A), read
 * little-endian; superblock versions 0 and 1 keep it after two addresses
 * at byte 24 (v0) or 28 (v1), versions 2 and 3 at byte 12. The in-memory
 * image is a buffer that grew in steps, so it ends in unused bytes.
 * Returns n (the whole image) when the superblock is not understood. */
static size_t hdf5_end_of_file(const unsigned char *p, size_t n)
{
    static const unsigned char signature[8] = { 0x89, 'H', 'D', 'F', '\r', '\n', 0x1a, '\n' };
    size_t base, osize;
    if (n < 48 || memcmp(p, signature, 8) != 0) return n;
    switch (p[8]) {
    case 0: osize = p[13]; base = 24; break;
    case 1: osize = p[13]; base = 28; break;
    case 2: case 3: osize = p[9]; base = 12; break;
    default: return n;
    }
    if (osize < 2 || osize > 8 || base + 3 * osize > n) return n;
    unsigned long long eof = 0;
    for (size_t k = 0; k < osize; ++k)
        eof |= (unsigned long long)p[base + 2 * osize + k] << (8 * k);
    if (eof < base + 3 * osize || eof > n) return n;
    return (size_t)eof;
}

/* Create an in-memory NetCDF-4 file named `path` (nothing is created on
 * disk); returns the netCDF status. */
int pavefric_nc_create_mem(const char *path, int *ncid)
{
    return nc_create_mem(path, NC_NETCDF4, 65536, ncid);
}

/* Close the in-memory file `ncid` and write its bytes to a new file `path`
 * (mode 0666 less umask), flushed with fsync. *nc_status gets the netCDF
 * status of the close, *err the errno of a failed unlink of a stale file
 * there, open, write, fsync or close (0 on success). A file that could not
 * be written is left for the caller to remove. */
void pavefric_nc_close_to_file(int ncid, const char *path, int *nc_status, int *err)
{
    NC_memio mem;
    memset(&mem, 0, sizeof mem);
    *err = 0;
    *nc_status = nc_close_memio(ncid, &mem);
    if (*nc_status != NC_NOERR) {
        free(mem.memory);
        return;
    }
    /* a fresh file: never write through a link left at the temporary name */
    if (unlink(path) != 0 && errno != ENOENT) {
        *err = errno;
        free(mem.memory);
        return;
    }
    int fd = open(path, O_WRONLY | O_CREAT | O_EXCL, 0666);
    if (fd < 0) {
        *err = errno;
        free(mem.memory);
        return;
    }
    pavefric_test_pause("create");
    const char *p = mem.memory;
    size_t left = hdf5_end_of_file(mem.memory, mem.size);
    while (left > 0) {
        ssize_t n = write(fd, p, left);
        if (n < 0) {
            if (errno == EINTR) continue;
            *err = errno;
            break;
        }
        p += n;
        left -= (size_t)n;
    }
    if (*err == 0 && fsync(fd) != 0 && errno != EINVAL && errno != EROFS) *err = errno;
    if (close(fd) != 0 && *err == 0) *err = errno;
    free(mem.memory);
}

/* The text of an errno into out (outlen bytes, not terminated); returns
 * its length (at most outlen). */
int pavefric_strerror(int err, char *out, int outlen)
{
    /* strerror_r, not strerror: strerror may format unknown numbers into
     * a static buffer, and API calls run on several threads at once */
    char local[256];
    const char *text = local;
    local[0] = '\0';
#if defined(__GLIBC__) && defined(_GNU_SOURCE)
    text = strerror_r(err, local, sizeof local);
#else
    if (strerror_r(err, local, sizeof local) != 0) local[0] = '\0';
#endif
    size_t n = strlen(text);
    if (n > (size_t)outlen) n = (size_t)outlen;
    memcpy(out, text, n);
    return (int)n;
}

/* pavefric_strerror as a subroutine (Fortran: pure, so os_message is) */
void pavefric_strerror_into(int err, char *out, int outlen, int *written)
{
    *written = pavefric_strerror(err, out, outlen);
}
