/* SPDX-License-Identifier: MIT */
/* Which BLAS the process runs on: the library that provides dgemm_ (found by dladdr, so a
 * Debian alternative or an LD_PRELOAD is seen as it really resolves), OpenBLAS's own
 * configuration string and thread count when that library is OpenBLAS. The reference BLAS
 * makes the factorization about 5x slower, so a run says which one it had. Below: what
 * blas_threads.f90 needs to give OpenBLAS a thread count per factorization (the user's
 * environment, the cores, the load of other processes). */
#define _GNU_SOURCE
#include <dlfcn.h>
#include <math.h>
#include <sched.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

/* The largest count OpenBLAS had after nceig_blas_set_threads in this process, 0 if none:
 * the report's blas_threads. OpenBLAS's own count is process-wide state; this mirrors it. */
static int largest_threads_set = 0;

static void copy_text(char *to, int capacity, const char *from)
{
    size_t n;
    if (capacity <= 0)
        return;
    n = from ? strlen(from) : 0;
    if (n >= (size_t)capacity)
        n = (size_t)capacity - 1;
    if (n > 0)
        memcpy(to, from, n);
    to[n] = '\0';
}

/* library: path of the object that defines dgemm_ ("" if unknown); config: OpenBLAS's
 * configuration ("" for another BLAS); *threads: the largest count nceig gave OpenBLAS,
 * else OpenBLAS's thread count, else 1. */
void nceig_blas_info(char *library, int library_capacity, char *config, int config_capacity,
                     int *threads)
{
    Dl_info info;
    void *dgemm = dlsym(RTLD_DEFAULT, "dgemm_");
    char *(*get_config)(void) = (char *(*)(void))dlsym(RTLD_DEFAULT, "openblas_get_config");
    int (*get_threads)(void) = (int (*)(void))dlsym(RTLD_DEFAULT, "openblas_get_num_threads");

    copy_text(library, library_capacity, "");
    if (dgemm && dladdr(dgemm, &info) && info.dli_fname)
        copy_text(library, library_capacity, info.dli_fname);
    copy_text(config, config_capacity, get_config ? get_config() : "");
    *threads = get_threads ? get_threads() : 1;
    if (largest_threads_set > 0)
        *threads = largest_threads_set;
}

/* ---- The thread count nceig gives the BLAS (blas_threads.f90 holds the rule). ---- */



/* The thread count the environment gives OpenBLAS, read as OpenBLAS reads it when it
 * loads: the first positive of OPENBLAS_NUM_THREADS, GOTO_NUM_THREADS, OMP_NUM_THREADS; 0
 * when none is set to a positive count (OpenBLAS then starts one thread per core). */
int nceig_blas_environment_threads(void)
{
    static const char *const names[] = {"OPENBLAS_NUM_THREADS", "GOTO_NUM_THREADS",
                                        "OMP_NUM_THREADS"};
    size_t i;
    for (i = 0; i < sizeof names / sizeof names[0]; i++) {
        const char *text = getenv(names[i]);
        long count = text ? strtol(text, NULL, 10) : 0;
        if (count > 0)
            return count > 4096 ? 4096 : (int)count;
    }
    return 0;
}

/* Set OpenBLAS's thread count, found at run time (a reference BLAS has no such call and
 * keeps its one thread; nceig does not link against OpenBLAS by name). */
void nceig_blas_set_threads(int threads)
{
    void (*set_threads)(int) = (void (*)(int))dlsym(RTLD_DEFAULT, "openblas_set_num_threads");
    int (*get_threads)(void) = (int (*)(void))dlsym(RTLD_DEFAULT, "openblas_get_num_threads");
    int now;
    if (!set_threads || threads < 1)
        return;
    set_threads(threads);
    /* what OpenBLAS took (it caps the count at its cores), not what was asked */
    now = get_threads ? get_threads() : threads;
    if (now > largest_threads_set)
        largest_threads_set = now;
}

int nceig_blas_largest_threads_set(void) { return largest_threads_set; }

/* The cores this process may run on (its affinity mask, as taskset or a batch system's
 * cgroup cpuset leaves it), at least 1. */
int nceig_cpu_count(void)
{
    cpu_set_t set;
    long online;
    if (sched_getaffinity(0, sizeof set, &set) == 0 && CPU_COUNT(&set) > 0)
        return CPU_COUNT(&set);
    online = sysconf(_SC_NPROCESSORS_ONLN);
    return online > 0 ? (int)online : 1;
}

/* The 1-minute load average that other processes make: /proc/loadavg's first number less
 * this process's own part of it. The kernel's average follows r (1 - exp(-t / 60)) for a
 * process that has kept r cores busy for t seconds; r is this process's CPU seconds over
 * its age. -1 when the load average cannot be read. */
double nceig_load_of_others(void)
{
    double load[1], uptime = 0.0, age, cpu, own;
    unsigned long long start_ticks = 0;
    char line[1024], *after_name;
    struct timespec used;
    FILE *file;
    int field;

    if (getloadavg(load, 1) < 1)
        return -1.0;
    /* the process's start (field 22 of /proc/self/stat, clock ticks after boot) */
    file = fopen("/proc/self/stat", "r");
    if (!file)
        return load[0];
    after_name = fgets(line, sizeof line, file) ? strrchr(line, ')') : NULL;
    fclose(file);
    if (!after_name)
        return load[0];
    after_name += 2;                 /* ") " : field 3 follows */
    for (field = 3; field < 22 && after_name; field++) {
        after_name = strchr(after_name, ' ');
        if (after_name)
            after_name++;
    }
    if (!after_name || sscanf(after_name, "%llu", &start_ticks) != 1)
        return load[0];
    file = fopen("/proc/uptime", "r");
    if (!file)
        return load[0];
    if (fscanf(file, "%lf", &uptime) != 1)
        uptime = 0.0;
    fclose(file);
    age = uptime - (double)start_ticks / (double)sysconf(_SC_CLK_TCK);
    if (age <= 0.0 || clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &used) != 0)
        return load[0];
    cpu = (double)used.tv_sec + 1e-9 * (double)used.tv_nsec;
    own = cpu / age * (1.0 - exp(-age / 60.0));
    return load[0] > own ? load[0] - own : 0.0;
}
