/* SPDX-License-Identifier: MIT */
/* errno is a macro (thread-local storage), and struct stat, struct dirent and ESRCH differ
   between systems: none can be reached portably from Fortran's bind(C), so they live here,
   with what needs more than one call: checking that a file reached the disk, swapping two
   directories, a lock, and the signal handler that removes a run's staging folder. */
/* _GNU_SOURCE for renameat2 and RENAME_EXCHANGE (Linux, glibc 2.28); it implies POSIX 2008. */
#define _GNU_SOURCE
#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/file.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/syscall.h>
#include <sys/types.h>
#include <unistd.h>

int nceig_errno(void) { return errno; }

int nceig_is_directory(const char *path)
{
    struct stat info;
    return stat(path, &info) == 0 && S_ISDIR(info.st_mode);
}

/* A directory itself, not a symbolic link to one (lstat does not follow links). */
int nceig_is_real_directory(const char *path)
{
    struct stat info;
    return lstat(path, &info) == 0 && S_ISDIR(info.st_mode);
}

/* 1 when no process `pid` exists: kill with signal 0 only checks, and fails with ESRCH
   exactly then (EPERM means it exists but belongs to another user). */
int nceig_process_gone(int pid)
{
    if (pid <= 0) return 0;
    return kill((pid_t)pid, 0) != 0 && errno == ESRCH;
}

void *nceig_open_directory(const char *path) { return opendir(path); }

void nceig_close_directory(void *directory)
{
    if (directory != NULL) closedir((DIR *)directory);
}

/* The next entry's name into name[0..capacity) (not NUL-terminated): its length, -1 at the
   end, -2 for a name longer than capacity (not copied), or -3 when readdir failed (errno;
   readdir returns NULL both at the end and on an error, and only errno tells them apart).
   "." and ".." are skipped. */
int nceig_next_entry(void *directory, char *name, int capacity)
{
    struct dirent *entry;
    size_t length;
    do {
        errno = 0;
        entry = readdir((DIR *)directory);
        if (entry == NULL) return errno == 0 ? -1 : -3;
    } while (strcmp(entry->d_name, ".") == 0 || strcmp(entry->d_name, "..") == 0);
    length = strlen(entry->d_name);
    if (length > (size_t)capacity) return -2;
    memcpy(name, entry->d_name, length);
    return (int)length;
}

/* fsync `fd`; file systems that cannot sync a directory say EINVAL (or EROFS), which is no
   loss of data. */
static int sync_fd(int fd)
{
    if (fsync(fd) == 0 || errno == EINVAL || errno == EROFS) return 0;
    return -1;
}

/* `op` applied to `path` opened read-only; its result, with the errno it left (close
   must not overwrite it); -1 with errno when `path` cannot be opened. */
static int on_opened(const char *path, int (*op)(int))
{
    int status, saved;
    int fd = open(path, O_RDONLY | O_CLOEXEC);
    if (fd < 0) return -1;
    status = op(fd);
    saved = errno;
    close(fd);
    errno = saved;
    return status;
}

/* After a Fortran unit was closed: 0 when file `path` holds `expected` bytes; -1 with errno
   set when it cannot be examined; -2 when it is shorter or longer, with its size in *actual.
   libgfortran (12) ignores a failed write(2) when it flushes its buffer, even at CLOSE, so
   its iostat cannot tell a full disk. */
int nceig_check_written(const char *path, long long expected, long long *actual)
{
    struct stat info;
    if (stat(path, &info) != 0) return -1;
    *actual = (long long)info.st_size;
    return (long long)info.st_size == expected ? 0 : -2;
}

/* Write to disk every file of the file system holding `path` (Linux syncfs, which since
   Linux 5.8 also reports a write-back error, e.g. ENOSPC found late, of any file there);
   elsewhere sync(). One call instead of an fsync per file: 3 times faster for 60 files. */
int nceig_sync_filesystem(const char *path)
{
#ifdef __linux__
    return on_opened(path, syncfs);
#else
    (void)path;
    sync();
    return 0;
#endif
}

/* fsync a file or directory by name (a directory: so that renames in it are durable). */
int nceig_sync_path(const char *path)
{
    return on_opened(path, sync_fd);
}

/* Put directory `from` where `to` is. When `to` exists they are swapped in one step
   (renameat2 RENAME_EXCHANGE: a reader of `to` sees the old or the new directory, never
   none); where the file system cannot (NFS, some FUSE: EINVAL), or when `exchange` is 0,
   `to` is first renamed `aside` and `from` then renamed `to`, a moment without `to`.
   Returns 1 when swapped (`from` now names the old directory), 2 when set aside (`aside`
   names it), 0 when `to` did not exist, -1 with errno (nothing moved). */
int nceig_replace_directory(const char *from, const char *to, const char *aside, int exchange)
{
    struct stat info;
    int saved;
    if (lstat(to, &info) != 0) {
        if (errno != ENOENT) return -1;
        if (rename(from, to) == 0) return 0;
        if (errno != EEXIST && errno != ENOTEMPTY) return -1;
        /* made meanwhile: replace it after all */
    }
#ifdef RENAME_EXCHANGE
    if (exchange) {
        if (renameat2(AT_FDCWD, from, AT_FDCWD, to, RENAME_EXCHANGE) == 0) return 1;
        if (errno != EINVAL && errno != ENOSYS && errno != ENOTSUP && errno != EOPNOTSUPP)
            return -1;
    }
#else
    (void)exchange;
#endif
    if (rename(to, aside) != 0) return -1;
    if (rename(from, to) == 0) return 2;
    saved = errno;
    (void)rename(aside, to);
    errno = saved;
    return -1;
}

/* 1 when directory `path` can be replaced by renaming in `parent`: both on one file system
   (not a mount point), `path` not `parent` itself ('/'), and `parent` writable by us. */
int nceig_can_replace(const char *path, const char *parent)
{
    struct stat own, up;
    if (lstat(path, &own) != 0 || stat(parent, &up) != 0) return 0;
    if (own.st_dev != up.st_dev || own.st_ino == up.st_ino) return 0;
    return access(parent, W_OK | X_OK) == 0;
}

/* The target of the symbolic link `path` into buffer[0..capacity) (not NUL-terminated): its
   length, or -1 when `path` is no link (or its target does not fit). */
int nceig_link_target(const char *path, char *buffer, int capacity)
{
    struct stat info;
    ssize_t length;
    if (capacity <= 0 || lstat(path, &info) != 0 || !S_ISLNK(info.st_mode)) return -1;
    length = readlink(path, buffer, (size_t)capacity);
    if (length < 0 || length >= capacity) return -1;
    return (int)length;
}

/* 1 when `path` has a write permission bit and the caller may write it: a directory its
   owner made read-only (chmod a-w) counts as such even for root, whom access() lets by. */
int nceig_may_write(const char *path)
{
    struct stat info;
    if (stat(path, &info) != 0) return 0;
    return (info.st_mode & 0222) != 0 && access(path, W_OK) == 0;
}

/* Make `to` a new name (hard link) of file `from`; a symbolic link is linked, not followed. */
int nceig_link(const char *from, const char *to) { return link(from, to); }

/* Give directory `to` the permission bits of `from` (best effort: the swap must not change
   what others may read). */
void nceig_copy_mode(const char *from, const char *to)
{
    struct stat info;
    if (stat(from, &info) == 0) (void)chmod(to, info.st_mode & 07777);
}

/* Remove `name` in the directory open as `dir_fd`, and everything below it, never following
   a symbolic link (links are removed, not their targets). Best effort. */
static void remove_below(int dir_fd, const char *name)
{
    int fd;
    DIR *dir;
    struct dirent *entry;
    if (unlinkat(dir_fd, name, 0) == 0 || (errno != EISDIR && errno != EPERM)) return;
    fd = openat(dir_fd, name, O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
    if (fd < 0) return;
    dir = fdopendir(fd);
    if (dir == NULL) {
        close(fd);
        return;
    }
    while ((entry = readdir(dir)) != NULL) {
        if (strcmp(entry->d_name, ".") == 0 || strcmp(entry->d_name, "..") == 0) continue;
        remove_below(fd, entry->d_name);
    }
    closedir(dir);
    (void)unlinkat(dir_fd, name, AT_REMOVEDIR);
}

/* rm -r `path`, without following links. Best effort. */
void nceig_remove_tree(const char *path) { remove_below(AT_FDCWD, path); }

/* Open (creating) `path` and take an exclusive flock on it, waiting for other holders:
   the descriptor, or -1 with errno. The lock ends with nceig_unlock or with the process. */
int nceig_lock(const char *path)
{
    int saved;
    int fd = open(path, O_RDWR | O_CREAT | O_CLOEXEC, 0666);
    if (fd < 0) return -1;
    while (flock(fd, LOCK_EX) != 0) {
        if (errno == EINTR) continue;
        saved = errno;
        close(fd);
        errno = saved;
        return -1;
    }
    return fd;
}

void nceig_unlock(int fd)
{
    if (fd >= 0) close(fd);
}

/* The canonical absolute path of `path` (links resolved) into buffer[0..capacity): its
   length, or -1. */
int nceig_real_path(const char *path, char *buffer, int capacity)
{
    size_t length;
    char *resolved = realpath(path, NULL);
    if (resolved == NULL) return -1;
    length = strlen(resolved);
    if (length > (size_t)capacity) {
        free(resolved);
        return -1;
    }
    memcpy(buffer, resolved, length);
    free(resolved);
    return (int)length;
}

/* ---- Cleanup on SIGTERM, SIGINT, SIGHUP, SIGXCPU ----
   While a run writes its staging folder, these signals remove the folder (its files, then
   itself) and the parent directories the run created, then end the process by the same
   signal with its default action. Only async-signal-safe calls are made in the handler
   (open, getdents64, unlinkat, rmdir, close, sigaction, sigprocmask, write, raise) on static
   storage; the signal may arrive on any thread (OpenMP and BLAS start some). During the
   commit the handler only notes the signal: the commit finishes (or fails and cleans up),
   then nceig_cleanup_disarm ends the process by it. The nceig program blocks these signals
   in every thread and takes them in a thread of its own (program_start_c.c), which hands
   each to nceig_signal_on_main: a library's handler (METIS's) never sees them. */

enum { N_SIGNALS = 4 };
static const int cleanup_signals[N_SIGNALS] = {SIGTERM, SIGINT, SIGHUP, SIGXCPU};
static struct sigaction previous_actions[N_SIGNALS];
static int installed[N_SIGNALS];
static char staging_path[PATH_MAX + 1];
static int created_levels;               /* parents of the staging folder this run made */
static volatile sig_atomic_t armed;      /* staging_path is complete and to be removed */
static volatile sig_atomic_t holding;    /* in the commit: defer the signal */
static volatile sig_atomic_t pending;    /* the signal deferred */
static char run_name[PATH_MAX + 1];      /* the input file, for the line a signal prints */
static volatile sig_atomic_t run_named;

static void remove_staging_now(void)
{
    char buffer[4096];
    char path[PATH_MAX + 1];
    long n, offset;
    size_t length;
    int fd, level;

    fd = open(staging_path, O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
    if (fd >= 0) {
        /* Unlinking while reading: read again from the start until nothing is left. */
        for (;;) {
            int removed = 0;
            (void)lseek(fd, 0, SEEK_SET);
            n = syscall(SYS_getdents64, fd, buffer, sizeof buffer);
            if (n <= 0) break;
            for (offset = 0; offset < n;) {
                /* struct linux_dirent64: u64 ino, s64 off, u16 reclen, u8 type, name */
                unsigned short record;
                const char *name = buffer + offset + 19;
                memcpy(&record, buffer + offset + 16, sizeof record);
                if (strcmp(name, ".") != 0 && strcmp(name, "..") != 0 &&
                    unlinkat(fd, name, 0) == 0)
                    removed = 1;
                offset += record;
            }
            if (!removed) break;
        }
        close(fd);
    }
    (void)rmdir(staging_path);
    /* The created parents are the last levels of the staging folder's own parent. */
    length = strlen(staging_path);
    memcpy(path, staging_path, length + 1);
    for (level = 0; level < created_levels; level++) {
        while (length > 0 && path[length - 1] != '/') length--;
        while (length > 1 && path[length - 1] == '/') length--;
        if (length <= 1) break;
        path[length] = '\0';
        if (rmdir(path) != 0) break;
    }
}

static void write_text(const char *text)
{
    size_t length = strlen(text);
    while (length > 0) {
        ssize_t written = write(2, text, length);
        if (written <= 0) return;
        text += written;
        length -= (size_t)written;
    }
}

/* One line on stderr naming the run and the signal (the nceig program only: run_named),
   then the end of the process by `signal_number` and its default action: exit status
   128 + n to the shell. SIGXCPU's default action dumps core: not for a time limit. */
static void end_by_signal(int signal_number)
{
    int i;
    struct sigaction default_action;
    sigset_t unblock;
    if (run_named) {
        write_text("nceig: ");
        write_text(run_name);
        write_text(signal_number == SIGTERM  ? ": stopped by SIGTERM\n"
                   : signal_number == SIGINT ? ": stopped by SIGINT\n"
                   : signal_number == SIGHUP ? ": stopped by SIGHUP\n"
                                             : ": stopped by SIGXCPU: the CPU time limit "
                                               "(ulimit -t) is reached\n");
    }
    for (i = 0; i < N_SIGNALS; i++)
        if (installed[i]) (void)sigaction(cleanup_signals[i], &previous_actions[i], NULL);
    if (signal_number == SIGXCPU) {
        struct rlimit no_core;
        if (getrlimit(RLIMIT_CORE, &no_core) == 0) {
            no_core.rlim_cur = 0;
            (void)setrlimit(RLIMIT_CORE, &no_core);
        }
    }
    memset(&default_action, 0, sizeof default_action);
    default_action.sa_handler = SIG_DFL;
    sigemptyset(&default_action.sa_mask);
    (void)sigaction(signal_number, &default_action, NULL);
    sigemptyset(&unblock);
    sigaddset(&unblock, signal_number);
    (void)sigprocmask(SIG_UNBLOCK, &unblock, NULL);
    (void)raise(signal_number);
}

/* On the main thread: note the signal during the commit, else remove the staging folder
   (if any) and end the process by it. */
void nceig_signal_on_main(int signal_number)
{
    int saved = errno;
    if (holding) {
        pending = signal_number;
        errno = saved;
        return;
    }
    if (armed) {
        armed = 0;
        remove_staging_now();
    }
    end_by_signal(signal_number);
    errno = saved;
}

/* The name the line of end_by_signal gives the run (the input file). */
void nceig_signal_set_name(const char *name)
{
    size_t length = strlen(name);
    if (length > PATH_MAX) length = PATH_MAX;
    run_named = 0;
    memcpy(run_name, name, length);
    run_name[length] = '\0';
    run_named = 1;
}

static void on_signal(int signal_number)
{
    int saved = errno;
    /* A thread of OpenMP or BLAS got it: hand it to the main thread (whose thread id is the
       process id), which writes the staging folder, so that the removal does not race with
       a file being created there. */
    if (syscall(SYS_gettid) != (long)getpid()) {
        (void)syscall(SYS_tgkill, (long)getpid(), (long)getpid(), (long)signal_number);
        errno = saved;
        return;
    }
    nceig_signal_on_main(signal_number);
    errno = saved;
}

/* Remove staging folder `path` and the last `levels` directories of its parent on one of
   the signals. Signals the process ignores (as a shell's background jobs ignore SIGINT) are
   left ignored. 0, or -1 when `path` is too long to keep. */
int nceig_cleanup_arm(const char *path, int levels)
{
    struct sigaction action;
    size_t length = strlen(path);
    int i;
    if (length > PATH_MAX) return -1;
    armed = 0;
    holding = 0;
    pending = 0;
    memcpy(staging_path, path, length + 1);
    created_levels = levels;
    armed = 1;
    /* A file over the size limit (ulimit -f) must fail its write(2) with EFBIG, which
       close_output reports like a full disk, not kill the run with its staging folder
       left (SIGXFSZ's default action). For the rest of the process: no write is wanted
       past the limit. */
    (void)signal(SIGXFSZ, SIG_IGN);
    memset(&action, 0, sizeof action);
    action.sa_handler = on_signal;
    sigemptyset(&action.sa_mask);
    for (i = 0; i < N_SIGNALS; i++) sigaddset(&action.sa_mask, cleanup_signals[i]);
    for (i = 0; i < N_SIGNALS; i++) {
        struct sigaction current;
        if (installed[i]) continue;
        if (sigaction(cleanup_signals[i], NULL, &current) != 0) continue;
        if (current.sa_handler == SIG_IGN) continue;
        if (sigaction(cleanup_signals[i], &action, &previous_actions[i]) == 0) installed[i] = 1;
    }
    return 0;
}

/* From here the commit owns the staging folder: a signal waits for nceig_cleanup_disarm. */
void nceig_cleanup_hold(void) { holding = 1; }

/* The staging folder is gone (committed or removed): restore the previous handlers, and
   deliver a signal that came during the commit. */
void nceig_cleanup_disarm(void)
{
    int i, deferred;
    armed = 0;
    for (i = 0; i < N_SIGNALS; i++) {
        if (installed[i]) (void)sigaction(cleanup_signals[i], &previous_actions[i], NULL);
        installed[i] = 0;
    }
    holding = 0;
    deferred = pending;
    pending = 0;
    if (deferred != 0) end_by_signal(deferred);
}
