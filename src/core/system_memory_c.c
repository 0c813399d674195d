/* SPDX-License-Identifier: MIT */
/* The address-space limit of the process (ulimit -v), and the threads that may still map
   memory: struct rlimit, RLIM_INFINITY and the /proc/self/task listing are not reachable
   portably from Fortran's bind(C). Under a limit too small for OpenBLAS's buffers, OpenBLAS
   retries its failed mmap for ever (inside CHOLMOD, or in its own threads), so the run
   checks first. */
#define _GNU_SOURCE
#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/syscall.h>
#include <time.h>
#include <unistd.h>

/* The soft RLIMIT_AS in bytes, or -1 when there is none (or it cannot be read). */
long long nceig_address_space_limit(void)
{
    struct rlimit limit;
    if (getrlimit(RLIMIT_AS, &limit) != 0 || limit.rlim_cur == RLIM_INFINITY)
        return -1;
    return (long long)limit.rlim_cur;
}

/* The threads of this process, the caller's aside, that are running or runnable (state R or
   D in /proc/self/task/TID/stat); -1 when the listing cannot be read. */
static int count_running_threads(void)
{
    long self = syscall(SYS_gettid);
    int running = 0;
    struct dirent *entry;
    DIR *tasks = opendir("/proc/self/task");
    if (tasks == NULL) return -1;
    while ((entry = readdir(tasks)) != NULL) {
        char path[16 + 256 + 8], text[512], *state;   /* "/proc/self/task/" NAME "/stat" */
        FILE *file;
        size_t length;
        if (entry->d_name[0] < '0' || entry->d_name[0] > '9') continue;
        if (atol(entry->d_name) == self) continue;
        snprintf(path, sizeof path, "/proc/self/task/%s/stat", entry->d_name);
        file = fopen(path, "r");
        if (file == NULL) continue;   /* the thread ended meanwhile */
        length = fread(text, 1, sizeof text - 1, file);
        fclose(file);
        text[length] = '\0';
        /* "tid (name) S ...": the name may hold blanks and parentheses, the state follows
           the last ')'. */
        state = strrchr(text, ')');
        if (state != NULL && (state[2] == 'R' || state[2] == 'D')) running++;
    }
    closedir(tasks);
    return running;
}

/* Wait, at most `seconds`, until no other thread of the process runs, polling every 10 ms:
   the number still running then (0 at once when all sleep; -1 when /proc cannot tell).
   OpenBLAS's threads map their buffers as they start, then spin (sched_yield) for a moment
   of at most about 0.4 s (OPENBLAS_THREAD_TIMEOUT) and sleep; one whose mmap fails retries
   for ever, running. */
int nceig_wait_for_sleeping_threads(double seconds)
{
    struct timespec pause = {0, 10000000};
    int polls = (int)(seconds * 100.0), running = count_running_threads();
    while (running > 0 && polls-- > 0) {
        nanosleep(&pause, NULL);
        running = count_running_threads();
    }
    return running;
}
