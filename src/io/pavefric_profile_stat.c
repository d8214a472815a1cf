/* What kind of file a profile path names, before it is opened: opening a
 * FIFO blocks until a writer appears and a device such as /dev/zero never
 * ends, so readers refuse anything that is not a regular file first.
 * Fortran has no portable stat(2); this is the whole of it. */
#include <sys/stat.h>

/* 0 regular file, 1 directory, 2 character device, 3 block device,
 * 4 FIFO, 5 socket, 6 other; -1 when the path cannot be examined (missing,
 * permission): the caller's open then reports why. Symbolic links are
 * followed. */
int pavefric_file_kind(const char *path)
{
    struct stat st;
    if (stat(path, &st) != 0) return -1;
    if (S_ISREG(st.st_mode)) return 0;
    if (S_ISDIR(st.st_mode)) return 1;
    if (S_ISCHR(st.st_mode)) return 2;
    if (S_ISBLK(st.st_mode)) return 3;
    if (S_ISFIFO(st.st_mode)) return 4;
    if (S_ISSOCK(st.st_mode)) return 5;
    return 6;
}
