/* Memory bandwidth with 1 and 2 threads (bench/README.md, thirteenth session): each of T
 * threads streams over its own part of a buffer of MB MiB (read, scale, add, write), 30
 * times; prints GB/s read + written. On the 2-core host of issue 14 one thread got 33-44 GB/s
 * and two 45-51 GB/s: a step bound by streaming memory cannot run 1.8x as fast on two.
 *
 *   gcc -O2 -pthread bench/membw.c -o /tmp/membw && /tmp/membw 256 1 && /tmp/membw 256 2
 */
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

static long n;
static int threads;
static double *a;
static const int iterations = 30;

static double now(void) {
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return t.tv_sec + t.tv_nsec * 1e-9;
}

static void *run(void *arg) {
    long id = (long)arg;
    double *p = a + id * (n / threads);
    for (int it = 0; it < iterations; it++)
        for (long i = 0; i < n / threads; i++)
            p[i] = p[i] * 1.0000001 + 1.0;
    return NULL;
}

int main(int argc, char **argv) {
    if (argc != 3) {
        fprintf(stderr, "usage: membw MIB THREADS (1 to 8)\n");
        return 2;
    }
    long mib = atol(argv[1]);
    threads = atoi(argv[2]);
    if (mib < 1 || threads < 1 || threads > 8) {
        fprintf(stderr, "usage: membw MIB THREADS (1 to 8)\n");
        return 2;
    }
    n = mib * 1024 * 1024 / 8;
    a = malloc(n * sizeof(double));
    if (!a) {
        fprintf(stderr, "no memory for %ld MiB\n", mib);
        return 1;
    }
    for (long i = 0; i < n; i++)
        a[i] = (double)i;
    pthread_t t[8];
    double t0 = now();
    for (long i = 0; i < threads; i++)
        pthread_create(&t[i], NULL, run, (void *)i);
    for (int i = 0; i < threads; i++)
        pthread_join(t[i], NULL);
    double t1 = now();
    printf("%ld MiB, %d threads: %.2f GB/s (read + written)\n", mib, threads,
           2.0 * n * 8 * iterations / (t1 - t0) / 1e9);
    return 0;
}
