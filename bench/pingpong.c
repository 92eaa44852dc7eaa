/* Where the host put our two cores (bench/README.md, twenty-third session): the round trip of
 * one cache line between a thread on CPU 0 and one on CPU 1, in ns (each thread waits for the
 * other's write, then writes back). Prints the minimum, median and maximum over 21 batches of
 * 20 000 round trips. On the 2-core host of issue 14 the median is either about 51-67 ns (the
 * two vCPUs on cores that share an L3) or about 330-380 ns (on two AMD core complexes: a line
 * either core writes goes through the I/O die), and it changes with the host's scheduling,
 * minutes apart. Independent processes do not care; two threads that share data do.
 *
 *   gcc -O2 -pthread bench/pingpong.c -o /tmp/pingpong && /tmp/pingpong
 */
#define _GNU_SOURCE
#include <pthread.h>
#include <sched.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

#define TRIPS 20000
#define BATCHES 21

static _Alignas(128) _Atomic long flag;

static double now(void) {
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return t.tv_sec + t.tv_nsec * 1e-9;
}

static int pin(int cpu) {
    cpu_set_t set;
    CPU_ZERO(&set);
    CPU_SET(cpu, &set);
    return pthread_setaffinity_np(pthread_self(), sizeof set, &set);
}

/* CPU 1's side: answers each odd value with the next even one. */
static void *pong(void *unused) {
    (void)unused;
    if (pin(1) != 0) {
        fprintf(stderr, "pingpong: cannot run a thread on CPU 1\n");
        exit(2);
    }
    for (long i = 0; i < (long)TRIPS * BATCHES; i++) {
        while (atomic_load_explicit(&flag, memory_order_acquire) != 2 * i + 1) {
        }
        atomic_store_explicit(&flag, 2 * i + 2, memory_order_release);
    }
    return NULL;
}

static int by_value(const void *a, const void *b) {
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

int main(void) {
    if (pin(0) != 0) {
        fprintf(stderr, "pingpong: cannot run a thread on CPU 0\n");
        return 2;
    }
    pthread_t other;
    if (pthread_create(&other, NULL, pong, NULL) != 0) {
        fprintf(stderr, "pingpong: cannot start a thread\n");
        return 2;
    }
    double ns[BATCHES];
    long k = 0;
    for (int b = 0; b < BATCHES; b++) {
        double t0 = now();
        for (int i = 0; i < TRIPS; i++, k++) {
            atomic_store_explicit(&flag, 2 * k + 1, memory_order_release);
            while (atomic_load_explicit(&flag, memory_order_acquire) != 2 * k + 2) {
            }
        }
        ns[b] = (now() - t0) / TRIPS * 1e9;
    }
    pthread_join(other, NULL);
    qsort(ns, BATCHES, sizeof ns[0], by_value);
    printf("round trip between CPU 0 and CPU 1: min %.0f ns, median %.0f ns, max %.0f ns\n", ns[0],
           ns[BATCHES / 2], ns[BATCHES - 1]);
    return 0;
}
