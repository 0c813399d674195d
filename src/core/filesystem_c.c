/* SPDX-License-Identifier: MIT */
/* errno is a macro (thread-local storage), and struct stat, struct dirent and ESRCH differ
   between systems: none can be reached portably from Fortran's bind(C), so they live here. */
/* POSIX 2008 for lstat and kill under a strict -std=c11. */
#define _POSIX_C_SOURCE 200809L
#include <dirent.h>
#include <errno.h>
#include <signal.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/types.h>

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
   end, or -2 for a name longer than capacity (not copied). "." and ".." are skipped. */
int nceig_next_entry(void *directory, char *name, int capacity)
{
    struct dirent *entry;
    size_t length;
    do {
        entry = readdir((DIR *)directory);
        if (entry == NULL) return -1;
    } while (strcmp(entry->d_name, ".") == 0 || strcmp(entry->d_name, "..") == 0);
    length = strlen(entry->d_name);
    if (length > (size_t)capacity) return -2;
    memcpy(name, entry->d_name, length);
    return (int)length;
}
