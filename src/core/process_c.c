/* SPDX-License-Identifier: MIT */
/* Starting a helper program (gnuplot) without a shell: the arguments go to
   posix_spawnp as a vector, so no byte of a path (a quote, `;`, `$(...)`) is ever parsed as
   a command. Fortran's execute_command_line hands one string to /bin/sh, and cannot say why
   a program did not start. Also here: looking a program up on PATH, and SIGPIPE. */
/* POSIX 2008: posix_spawn, confstr, and the XSI strerror_r (not the GNU one). */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

extern char **environ;

/* Codes of nceig_run_program besides an exit status; process.f90 mirrors them. */
enum { NOT_FOUND = -1, NOT_STARTED = -2 };

/* Run the program of `count` arguments packed NUL-separated in `args` (the first is the
   program, searched on PATH unless it holds a '/'). Its stdin is /dev/null; its stdout and
   stderr go to file `output` (created or truncated) or, when `output` is "", to /dev/null.
   Waits for it. Returns its exit status (0..255), 128 + n when signal n ended it,
   NOT_FOUND when there is no such program (ENOENT), or NOT_STARTED with *error set to the
   errno of what failed (EMFILE, EAGAIN, ENOMEM, EACCES, or opening `output`). */
int nceig_run_program(const char *args, int count, const char *output, int *error)
{
    char **argv;
    const char *arg = args;
    int i, status, result, in_fd = -1, out_fd = -1;
    pid_t pid;
    posix_spawn_file_actions_t actions;
    posix_spawnattr_t attributes;
    sigset_t signals;

    *error = 0;
    if (count < 1) {
        *error = EINVAL;
        return NOT_STARTED;
    }
    argv = malloc(((size_t)count + 1) * sizeof *argv);
    if (argv == NULL) {
        *error = errno;
        return NOT_STARTED;
    }
    for (i = 0; i < count; i++) {
        argv[i] = (char *)arg;
        arg += strlen(arg) + 1;
    }
    argv[count] = NULL;

    /* Opened here, not by the spawn's file actions: a failure to open `output` then has its
       own errno, and ENOENT from the spawn can only mean the program is missing. */
    in_fd = open("/dev/null", O_RDONLY | O_CLOEXEC);
    if (in_fd >= 0)
        out_fd = output[0] == '\0' ? open("/dev/null", O_WRONLY | O_CLOEXEC)
                                   : open(output, O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
    if (in_fd < 0 || out_fd < 0) {
        *error = errno;
        if (in_fd >= 0) close(in_fd);
        free(argv);
        return NOT_STARTED;
    }

    status = posix_spawn_file_actions_init(&actions);
    if (status == 0) {
        status = posix_spawnattr_init(&attributes);
        if (status != 0) posix_spawn_file_actions_destroy(&actions);
    }
    if (status == 0) {
        /* dup2 clears O_CLOEXEC on the copies, so the child keeps exactly 0, 1, 2. */
        status = posix_spawn_file_actions_adddup2(&actions, in_fd, 0);
        if (status == 0) status = posix_spawn_file_actions_adddup2(&actions, out_fd, 1);
        if (status == 0) status = posix_spawn_file_actions_adddup2(&actions, out_fd, 2);
        /* nceig ignores SIGPIPE, and exec keeps an ignored signal ignored: give the child
           the default back (a pipeline the child runs must end as usual), and an empty
           signal mask. Other ignored signals (SIGINT of a background job) stay ignored. */
        sigemptyset(&signals);
        sigaddset(&signals, SIGPIPE);
        if (status == 0) status = posix_spawnattr_setsigdefault(&attributes, &signals);
        sigemptyset(&signals);
        if (status == 0) status = posix_spawnattr_setsigmask(&attributes, &signals);
        if (status == 0)
            status = posix_spawnattr_setflags(&attributes,
                                              POSIX_SPAWN_SETSIGDEF | POSIX_SPAWN_SETSIGMASK);
        /* glibc (2.24 on) reports a failed exec here, not as exit status 127. */
        if (status == 0) status = posix_spawnp(&pid, argv[0], &actions, &attributes, argv, environ);
        posix_spawnattr_destroy(&attributes);
        posix_spawn_file_actions_destroy(&actions);
    }
    close(in_fd);
    close(out_fd);
    free(argv);
    if (status != 0) {
        *error = status;
        return status == ENOENT ? NOT_FOUND : NOT_STARTED;
    }

    /* A signal handled meanwhile (none of nceig's use SA_RESTART) interrupts the wait. */
    while (waitpid(pid, &status, 0) < 0) {
        if (errno == EINTR) continue;
        *error = errno;
        return NOT_STARTED;
    }
    if (WIFEXITED(status)) result = WEXITSTATUS(status);
    else if (WIFSIGNALED(status)) result = 128 + WTERMSIG(status);
    else result = 128;
    return result;
}

/* 1 when `name` is an executable regular file in a folder of PATH (the search execvp makes:
   an empty entry is the current folder; without PATH, the system's default path), or is
   one itself when it holds a '/'. No program is run. */
int nceig_find_program(const char *name)
{
    const char *path, *entry, *end;
    char *candidate;
    size_t name_length = strlen(name), length;
    struct stat info;
    int found = 0;
    char default_path[256];

    if (name_length == 0) return 0;
    if (strchr(name, '/') != NULL)
        return stat(name, &info) == 0 && S_ISREG(info.st_mode) && access(name, X_OK) == 0;
    path = getenv("PATH");
    if (path == NULL) {
        length = confstr(_CS_PATH, default_path, sizeof default_path);
        if (length == 0 || length > sizeof default_path) return 0;
        path = default_path;
    }
    candidate = malloc(strlen(path) + name_length + 2);
    if (candidate == NULL) return 0;
    for (entry = path; !found; entry = end + 1) {
        end = strchr(entry, ':');
        if (end == NULL) end = entry + strlen(entry);
        length = (size_t)(end - entry);
        if (length == 0) {
            candidate[0] = '.';
            length = 1;
        } else {
            memcpy(candidate, entry, length);
        }
        candidate[length] = '/';
        memcpy(candidate + length + 1, name, name_length + 1);
        found = stat(candidate, &info) == 0 && S_ISREG(info.st_mode) &&
                access(candidate, X_OK) == 0;
        if (*end == '\0') break;
    }
    free(candidate);
    return found;
}

/* The system's sentence for `errnum` into buffer[0..capacity) (not NUL-terminated): its
   length. */
int nceig_error_text(int errnum, char *buffer, int capacity)
{
    char text[256];
    size_t length;
    if (strerror_r(errnum, text, sizeof text) != 0) return 0;
    length = strlen(text);
    if (length > (size_t)capacity) length = (size_t)capacity;
    memcpy(buffer, text, length);
    return (int)length;
}

/* Ignore SIGPIPE: a write to a closed pipe (stdout into `head`) then fails with EPIPE, which
   the writer can ignore, instead of killing nceig, possibly before its outputs are
   committed. 0, or -1 with errno. */
int nceig_ignore_broken_pipe(void)
{
    struct sigaction action;
    memset(&action, 0, sizeof action);
    action.sa_handler = SIG_IGN;
    sigemptyset(&action.sa_mask);
    return sigaction(SIGPIPE, &action, NULL);
}
