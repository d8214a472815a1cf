/* The batch journal's file I/O on plain POSIX descriptors: each line is one
 * write(2) whose result is checked. gfortran's FLUSH statement does not
 * report a failed write (a full disk gave iostat = 0 and lost the lines),
 * so the journal does not go through a Fortran unit. */
#include <errno.h>
#include <fcntl.h>
#include <string.h>
#include <unistd.h>

/* Open `path` for appending (created or emptied when `create`): the
 * descriptor, or -errno. */
int pavefric_journal_open(const char *path, int create)
{
    int flags = O_WRONLY | O_APPEND | O_CLOEXEC;
    int fd;
    if (create) flags |= O_CREAT | O_TRUNC;
    do {
        fd = open(path, flags, 0666);
    } while (fd < 0 && errno == EINTR);
    return fd >= 0 ? fd : -errno;
}

/* Write all n bytes: 0, or the errno of the failure. */
int pavefric_journal_write(int fd, const char *buf, long n)
{
    while (n > 0) {
        ssize_t k = write(fd, buf, (size_t)n);
        if (k < 0) {
            if (errno == EINTR) continue;
            return errno;
        }
        if (k == 0) return EIO;
        buf += k;
        n -= (long)k;
    }
    return 0;
}

/* Close: 0, or the errno of the failure. */
int pavefric_journal_close(int fd)
{
    return close(fd) == 0 ? 0 : errno;
}

