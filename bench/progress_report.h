/*
 * progress_report.h -- what the progressive hosts (bench/progressive.c,
 * bench/pathtracer.c) measure at each checkpoint and how they report it:
 * the image's error against a reference, that error with the
 * reference's own noise taken out, the speed-up at equal error over the
 * host's path tracing, the table and the CSV for the plot.  Static: one
 * program includes it.
 */
#ifndef BENCH_PROGRESS_REPORT_H
#define BENCH_PROGRESS_REPORT_H

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

#include "irrcache.h"

#define CHECKS 5
static const int check_spp[CHECKS] = {4, 16, 64, 256, 1024};

/* One mode at one checkpoint. */
typedef struct point {
    double cpu, library, rmse, raw, worst1;
    unsigned long long traced;     /* rays the host cast (0: not counted) */
    unsigned long long records, computes, details, cache_rays; /* irc_stats */
    int done;
} point;

/* The thread's CPU time: a system call, so once a checkpoint, never a
 * sample. */
static double cpu_now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static int cmp_desc(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? 1 : x > y ? -1 : 0;
}

/* Relative RMSE of the n-pixel image acc / s against ref (luminance) into
 * pt->raw, and the mean relative error of its worst 1% of pixels. */
static void measure(int n, const double *acc, int s, const float *ref, point *pt)
{
    const int worst = n / 100 > 0 ? n / 100 : 1;
    double se = 0.0, sr = 0.0, w = 0.0, *rel = malloc(sizeof(double) * (size_t)n);
    int i;
    for (i = 0; i < n; i++) {
        const double a = (acc[3 * i] + acc[3 * i + 1] + acc[3 * i + 2]) / (3.0 * s),
                     b = (ref[3 * i] + ref[3 * i + 1] + ref[3 * i + 2]) / 3.0;
        se += (a - b) * (a - b);
        sr += b * b;
        if (rel)
            rel[i] = fabs(a - b) / (b > 1e-3 ? b : 1e-3);
    }
    pt->raw = sqrt(se / sr);
    if (rel) {
        qsort(rel, (size_t)n, sizeof(double), cmp_desc);
        for (i = 0; i < worst; i++)
            w += rel[i];
        pt->worst1 = w / worst;
        free(rel);
    }
}

/* A checkpoint: the CPU time and the library's so far, the image's
 * error, and the cache's counters (c NULL: none). */
static void checkpoint(point *pt, double cpu, double library, int n, const double *acc, int s,
                       const float *ref, irc_cache *c)
{
    irc_stats st;
    pt->cpu = cpu;
    pt->library = library;
    measure(n, acc, s, ref, pt);
    if (c && irc_cache_stats(c, &st) == IRC_OK) {
        pt->records = st.records;
        pt->computes = st.computes;
        pt->details = st.details;
        pt->cache_rays = st.rays;
    }
    pt->done = 1;
}

/* An image of error e measures sqrt(e^2 + v / R) against an R-sample
 * reference; v, the path tracer's per-sample relative variance, comes
 * from its own 4-sample image (raw^2 = v (1/4 + 1/R)).  Sets every
 * point's rmse, path's (pts[0]) measured first. */
static void denoise(point (*pts)[CHECKS], int modes, int ref_spp)
{
    const double v = pts[0][0].done ? pts[0][0].raw * pts[0][0].raw / (0.25 + 1.0 / ref_spp)
                                    : 0.0;
    int m, q;
    for (m = 0; m < modes; m++)
        for (q = 0; q < CHECKS; q++) {
            const double e2 = pts[m][q].raw * pts[m][q].raw - v / ref_spp;
            pts[m][q].rmse = e2 > 0.0 ? sqrt(e2) : 0.0;
        }
}

/* The table (speed-up at equal error: path's time at the same samples x
 * (its error / the mode's)^2, its error falling as 1/sqrt(time), over the
 * mode's time), and with csv the rows mode,spp,cpu_s,rmse. */
static void report(const char *const *names, point (*pts)[CHECKS], int modes, const char *csv)
{
    FILE *f = csv ? fopen(csv, "w") : NULL;
    int m, q;
    printf("%-7s %6s %9s %8s %8s %8s %8s %9s %11s %9s %9s %8s %11s\n", "mode", "spp", "cpu_s",
           "rmse", "raw", "worst1%", "speedup", "library", "traced", "records", "computes",
           "details", "cache_rays");
    if (f)
        fprintf(f, "mode,spp,cpu_s,rmse\n");
    for (m = 0; m < modes; m++)
        for (q = 0; q < CHECKS; q++) {
            const point *x = &pts[m][q], *b = &pts[0][q];
            const double up = x->rmse > 0.0 && b->done
                                  ? b->cpu * (b->rmse / x->rmse) * (b->rmse / x->rmse) / x->cpu
                                  : 0.0;
            if (!x->done)
                continue;
            printf("%-7s %6d %9.2f %8.4f %8.4f %8.4f %7.2fx %8.1f%% %11llu %9llu %9llu %8llu "
                   "%11llu\n",
                   names[m], check_spp[q], x->cpu, x->rmse, x->raw, x->worst1, up,
                   100.0 * x->library / x->cpu, x->traced, x->records, x->computes, x->details,
                   x->cache_rays);
            if (f)
                fprintf(f, "%s,%d,%.4f,%.6f\n", names[m], check_spp[q], x->cpu, x->rmse);
        }
    if (f)
        fclose(f);
}

#endif
