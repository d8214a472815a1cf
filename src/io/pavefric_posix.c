/* POSIX services Fortran lacks: the identity and kind of a file (stat),
 * a canonical path (realpath), and removal of temporary outputs when the
 * program is killed by SIGTERM, SIGINT or SIGHUP.
 *
 * Why global state here: a signal handler receives no argument but the
 * signal number, so the names of the temporary files being written must sit
 * where it can find them. This registry is the one piece of process-wide
 * mutable state in pavefric. It holds only names, is written with atomic
 * operations (a slot is claimed, filled, then published), and the handler
 * only reads published slots and calls unlink(2), signal(2), raise(3),
 * pthread_self, pthread_kill and pthread_sigmask, which are
 * async-signal-safe. Nothing else in pavefric reads it.
 *
 * The handlers are installed by the program only (pavefric_install_cleanup,
 * from main.f90): the Python extension registers names too, but never
 * replaces the interpreter's handlers (SIGINT is KeyboardInterrupt there). */
#define _XOPEN_SOURCE 700   /* realpath(3) is XSI */
#include <dirent.h>
#include <errno.h>
#include <limits.h>
#include <pthread.h>
#include <stdio.h>
#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

/* ---- file identity ------------------------------------------------------ */

/* Kinds of file, as pavefric_fsys names them. */
enum { PF_MISSING = 0, PF_REGULAR = 1, PF_DIRECTORY = 2, PF_CHAR_DEVICE = 3,
       PF_BLOCK_DEVICE = 4, PF_FIFO = 5, PF_SOCKET = 6, PF_OTHER = 7 };

/* Device, inode and kind of the file `path` names, symbolic links
 * followed. Returns 0 (kind PF_MISSING when nothing is there, a dangling
 * link included) or the errno of a stat that failed otherwise. */
int pavefric_file_id(const char *path, long long *dev, long long *ino, int *kind)
{
    struct stat st;
    *dev = 0;
    *ino = 0;
    *kind = PF_MISSING;
    if (stat(path, &st) != 0) {
        if (errno == ENOENT || errno == ENOTDIR) return 0;
        return errno;
    }
    *dev = (long long)st.st_dev;
    *ino = (long long)st.st_ino;
    if (S_ISREG(st.st_mode)) *kind = PF_REGULAR;
    else if (S_ISDIR(st.st_mode)) *kind = PF_DIRECTORY;
    else if (S_ISCHR(st.st_mode)) *kind = PF_CHAR_DEVICE;
    else if (S_ISBLK(st.st_mode)) *kind = PF_BLOCK_DEVICE;
    else if (S_ISFIFO(st.st_mode)) *kind = PF_FIFO;
    else if (S_ISSOCK(st.st_mode)) *kind = PF_SOCKET;
    else *kind = PF_OTHER;
    return 0;
}

/* Whether an existing file may be replaced by this process: 1, or 0 when
 * it is read-only: no write permission for this process (access(2), links
 * followed) or no write bit at all in its mode (a file made read-only on
 * purpose, which root's access would pass). 1 when nothing is there. */
int pavefric_may_replace(const char *path)
{
    struct stat st;
    if (stat(path, &st) != 0) return 1;
    if ((st.st_mode & 0222) == 0) return 0;
    return access(path, W_OK) == 0 ? 1 : 0;
}

/* The permission bits of the existing file `path` (links followed) into
 * *mode; 0 on success, -1 when nothing is there, else the errno. */
int pavefric_file_mode(const char *path, int *mode)
{
    struct stat st;
    *mode = 0;
    if (stat(path, &st) != 0) return errno == ENOENT || errno == ENOTDIR ? -1 : errno;
    *mode = (int)(st.st_mode & 07777);
    return 0;
}

/* Give `tmp` the permission bits of the file it replaces, `path`, so that a
 * private result (0600) stays private; nothing when `path` is missing.
 * Returns 0 or the errno of the chmod. */
int pavefric_keep_mode(const char *path, const char *tmp)
{
    int mode;
    if (pavefric_file_mode(path, &mode) != 0) return 0;
    return chmod(tmp, (mode_t)mode) == 0 ? 0 : errno;
}

/* Whether `path` is itself a symbolic link (not followed): 1 or 0; 0 when
 * nothing is there or it cannot be inspected (the callers' stat says why). */
int pavefric_is_symlink(const char *path)
{
    struct stat st;
    if (lstat(path, &st) != 0) return 0;
    return S_ISLNK(st.st_mode) ? 1 : 0;
}

/* ---- stale temporaries -------------------------------------------------- */

/* What ends every temporary's name. The form `<path>.tmp<PID>.pavefric` is
 * made and recognised here only: pavefric_temporary_name builds it (the
 * Fortran writers and Python's atomic_output call it), and
 * pavefric_temporary_pid recognises it (the sweep below and the batch,
 * which leaves its own temporaries out of a directory's profiles). */
#define PF_TEMP_SUFFIX ".pavefric"

/* `<path>.tmp<this process's PID>.pavefric` into out (outlen bytes, not
 * terminated). Returns its length, which may exceed outlen (call again with
 * a larger buffer), or -1. */
int pavefric_temporary_name(const char *path, char *out, int outlen)
{
    char tail[64];
    int nt = snprintf(tail, sizeof tail, ".tmp%lld" PF_TEMP_SUFFIX, (long long)getpid());
    size_t np = strlen(path);
    if (nt < 0 || np > (size_t)INT_MAX - (size_t)nt) return -1;
    if (np + (size_t)nt <= (size_t)outlen) {
        memcpy(out, path, np);
        memcpy(out + np, tail, (size_t)nt);
    }
    return (int)(np + (size_t)nt);
}

/* The PID in `name` when it is exactly `<base>.tmp<PID>.pavefric` (base a
 * file's last path component, the PID one to nine digits, not 0); else 0. */
long long pavefric_temporary_pid(const char *base, const char *name)
{
    size_t baselen = strlen(base);
    const char *p, *digits;
    long long pid = 0;
    if (baselen == 0 || strncmp(name, base, baselen) != 0) return 0;
    p = name + baselen;
    if (strncmp(p, ".tmp", 4) != 0) return 0;
    digits = p += 4;
    for (; *p >= '0' && *p <= '9'; ++p) {
        if (p - digits >= 9) return 0;             /* more digits than a PID has */
        pid = pid * 10 + (*p - '0');
    }
    if (p == digits || strcmp(p, PF_TEMP_SUFFIX) != 0) return 0;
    return pid;
}

/* Remove the temporaries `<path>.tmp<PID>.pavefric` that a writer killed
 * outright (SIGKILL, a node failure: no handler runs) left beside `path`:
 * regular files of this user whose PID names no live process on this host,
 * other than this process. Only names of exactly that form
 * (pavefric_temporary_pid): a user's own `<path>.tmp123`, or any other
 * name, is never touched. Each writer calls it before it starts its own
 * temporary, so a re-run cleans up after the run that was killed. On a
 * file system shared between hosts a PID is only checked on this host: two
 * hosts writing one output at once is refused nowhere else either.
 * Returns how many were removed. */
int pavefric_remove_stale_temporaries(const char *path)
{
    const char *slash = strrchr(path, '/');
    const char *base = slash ? slash + 1 : path;
    size_t dirlen = slash ? (size_t)(slash - path) : 0;
    size_t baselen = strlen(base);
    char dir[PATH_MAX], full[PATH_MAX];
    DIR *d;
    struct dirent *e;
    int removed = 0;
    pid_t self = getpid();
    if (baselen == 0) return 0;
    if (slash) {
        if (dirlen == 0) dirlen = 1;           /* "/name": the root */
        if (dirlen >= sizeof dir) return 0;
        memcpy(dir, path, dirlen);
        dir[dirlen] = '\0';
    } else {
        strcpy(dir, ".");
    }
    d = opendir(dir);
    if (!d) return 0;
    while ((e = readdir(d)) != NULL) {
        const char *n = e->d_name;
        long long pid = pavefric_temporary_pid(base, n);
        struct stat st;
        if (pid <= 0 || (pid_t)pid == self) continue;
        if (kill((pid_t)pid, 0) == 0 || errno != ESRCH) continue;   /* alive, or not ours to ask */
        if (snprintf(full, sizeof full, "%s/%s", dir, n) >= (int)sizeof full) continue;
        if (lstat(full, &st) != 0 || !S_ISREG(st.st_mode) || st.st_uid != geteuid()) continue;
        if (unlink(full) == 0) ++removed;
    }
    closedir(d);
    return removed;
}

/* The canonical absolute path of an existing file (realpath(3)) into out
 * (outlen bytes, not terminated). Returns its length, which may exceed
 * outlen (call again with a larger buffer), or -1 when it cannot be
 * resolved. */
int pavefric_realpath(const char *path, char *out, int outlen)
{
    char *full = realpath(path, NULL);
    if (full == NULL) return -1;
    size_t n = strlen(full);
    if (n <= (size_t)outlen) memcpy(out, full, n);
    free(full);
    return n > INT_MAX ? -1 : (int)n;
}

/* ---- temporary files removed on a fatal signal -------------------------- */

#define PF_TEMP_SLOTS 32
#define PF_TEMP_PATH 4096

enum { SLOT_FREE = 0, SLOT_FILLING = 1, SLOT_LIVE = 2 };

static int slot_state[PF_TEMP_SLOTS];
static char slot_path[PF_TEMP_SLOTS][PF_TEMP_PATH];

/* Record `path` as a temporary file to remove if a fatal signal arrives.
 * Returns its slot, or -1 when the name is too long or all slots are taken
 * (the file is then simply not protected). */
int pavefric_temp_register(const char *path)
{
    size_t n = strlen(path);
    if (n >= PF_TEMP_PATH) return -1;
    for (int i = 0; i < PF_TEMP_SLOTS; ++i) {
        int expected = SLOT_FREE;
        if (__atomic_compare_exchange_n(&slot_state[i], &expected, SLOT_FILLING, 0,
                                        __ATOMIC_ACQUIRE, __ATOMIC_RELAXED)) {
            memcpy(slot_path[i], path, n + 1);
            __atomic_store_n(&slot_state[i], SLOT_LIVE, __ATOMIC_RELEASE);
            return i;
        }
    }
    return -1;
}

/* Forget the temporary file `path` (renamed into place or removed). */
void pavefric_temp_release(const char *path)
{
    for (int i = 0; i < PF_TEMP_SLOTS; ++i) {
        if (__atomic_load_n(&slot_state[i], __ATOMIC_ACQUIRE) == SLOT_LIVE &&
            strcmp(slot_path[i], path) == 0) {
            __atomic_store_n(&slot_state[i], SLOT_FREE, __ATOMIC_RELEASE);
            return;
        }
    }
}

/* Number of temporary files registered now (for tests). */
int pavefric_temp_count(void)
{
    int n = 0;
    for (int i = 0; i < PF_TEMP_SLOTS; ++i)
        if (__atomic_load_n(&slot_state[i], __ATOMIC_ACQUIRE) == SLOT_LIVE) ++n;
    return n;
}

static const int cleanup_signals[] = { SIGTERM, SIGINT, SIGHUP };
#define N_CLEANUP_SIGNALS (int)(sizeof cleanup_signals / sizeof cleanup_signals[0])

/* The thread that installed the handlers: the program's main thread, the
 * only one that writes and renames outputs. */
static pthread_t main_thread;

/* Remove every live temporary file, then die of the same signal with its
 * default action, so the parent sees "killed by SIGTERM" (exit status 143
 * in a shell), as without the handler. A signal sent to the process may
 * land on any thread (OpenMP, MPI progress threads); it is passed on to the
 * main thread, so the removal cannot race with that thread renaming the
 * same temporary file into place and then failing with a spurious error. */
static void cleanup_handler(int sig)
{
    if (!pthread_equal(pthread_self(), main_thread)) {
        pthread_kill(main_thread, sig);
        return;
    }
    for (int i = 0; i < PF_TEMP_SLOTS; ++i)
        if (__atomic_load_n(&slot_state[i], __ATOMIC_ACQUIRE) == SLOT_LIVE)
            (void)unlink(slot_path[i]);
    signal(sig, SIG_DFL);
    sigset_t set;
    sigemptyset(&set);
    sigaddset(&set, sig);
    pthread_sigmask(SIG_UNBLOCK, &set, NULL);
    raise(sig);   /* delivered at once: the process ends here */
}

/* Install the handlers (the program only). A signal ignored on entry stays
 * ignored (nohup, background jobs). SIGXFSZ is ignored, so a file-size
 * limit (ulimit -f, batch systems) makes the write fail with EFBIG and the
 * program report it, instead of being killed with a core dump. Returns 0,
 * or the errno of a sigaction that failed. */
int pavefric_install_cleanup(void)
{
    struct sigaction sa, old;
    main_thread = pthread_self();
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = cleanup_handler;
    sigemptyset(&sa.sa_mask);
    for (int k = 0; k < N_CLEANUP_SIGNALS; ++k) sigaddset(&sa.sa_mask, cleanup_signals[k]);
    for (int k = 0; k < N_CLEANUP_SIGNALS; ++k) {
        if (sigaction(cleanup_signals[k], NULL, &old) != 0) return errno;
        if (old.sa_handler == SIG_IGN) continue;
        if (sigaction(cleanup_signals[k], &sa, NULL) != 0) return errno;
    }
    if (signal(SIGXFSZ, SIG_IGN) == SIG_ERR) return errno;
    return 0;
}

/* Test hook: when the environment variable PAVEFRIC_TEST_PAUSE equals
 * `point` ("create": a temporary output was just created; "commit": it is
 * complete and about to be renamed into place), stop this process with
 * SIGSTOP, so a test can send a signal at a known point of the write. */
void pavefric_test_pause(const char *point)
{
    const char *v = getenv("PAVEFRIC_TEST_PAUSE");
    if (v != NULL && strcmp(v, point) == 0) {
        raise(SIGSTOP);
        /* A signal sent while stopped may be taken by another thread (glibc's
         * raise blocks every signal in this one until it returns), whose
         * handler passes it on to this thread. Give it time to arrive, so the
         * test sees the signal act at this point, not a moment later. */
        struct timespec pause = { 0, 300000000L };
        while (nanosleep(&pause, &pause) != 0 && errno == EINTR) { }
    }
}
