/*
 * bench.h -- what make bench's driver (bench.c: the runs) and its report
 * (report.c: the table and the plots' data) share.
 */
#ifndef BENCH_BENCH_H
#define BENCH_BENCH_H

#include <stdio.h>

#include "render.h"

#define OUT "build/bench"
#define MAX_RUNS 192

/* Cache runs leave the strata to the library, which takes them from a
 * (irrcache.h, strata_theta): such runs record strata 0 x 0, and the
 * tables call them the defaults. */
#define DEF_M 0u
#define DEF_N 0u

typedef struct bscene {
    const char *name, *path;
    int w, h, qw, qh; /* full and quick sizes */
    int sh;           /* glossy or near lights: SH records too */
    int secondary;    /* light samples at secondary hits, every method and
                         the reference alike (0: 1) */
    int ref_rays;     /* the reference's rays a pixel (0: the default) */
    int stride;       /* the reference's lattice (0: 4); brute force then
                         renders that lattice only, its time scaled by the
                         image's pixels over the lattice's (a pixel's cost
                         does not depend on its neighbours) */
    int bounces;      /* > 1: bounces of indirect light, every method and
                         the reference alike; such a scene runs only when
                         BENCH_SCENES names it (bounces.c's sweep) */
    int optional;     /* a corpus view whose model is not shipped (make
                         real-scenes copies it from CORPUS when there):
                         skipped, with a line saying so, when absent */
} bscene;

typedef struct run {
    char method[32];
    double param;          /* rays per point, or a */
    uint32_t m, n;         /* strata (cache runs) */
    render_stats st;
    double rmse, p99, p999, maxe; /* relative errors of pixels */
    int over10;                   /* pixels more than 10% off */
    double worst1;                /* share of the squared error in the
                                     worst 1% of pixels */
    int leaks;                    /* pixels above the reference by more
                                     than 25% of its mean */
    double bias;                  /* mean over the reference's, - 1 */
    double noise;                 /* cache runs: the record noise's relative
                                     RMSE, from a second run with another
                                     seed (sqrt(sum (T1 - T2)^2 / 2 / sum
                                     R^2)); -1: not measured (BENCH_NOISE=0) */
    double noise_top1;            /* the share of that noise's square in the
                                     1% of pixels where the runs differ most */
} run;

typedef struct ctx {
    int quick, threads, stride, ref_rays, w, h;
    int secondary; /* the scene's (bscene) */
    int bounces;   /* the scene's (bscene; 0: 1) */
    scene s;
    float *ref;            /* the averaged reference (lattice pixels) */
    double ref_noise;
    run runs[MAX_RUNS];
    int nruns;
    /* Over the scenes run so far, the corpus's summary (corpus_summary):
     * sums of log speedup of the defaults at equal relative RMSE, and of
     * the translational + rotational cache at each error level. */
    double gm_log, lvl_log[4];
    int gm_n, lvl_n[4];
} ctx;

/* The error levels the tables give a time and speedup for. */
#define NLEVELS 4
extern const double levels[NLEVELS];

/* bench.c: "Embree" or "the demo's BVH" (BENCH_RAYS) */
const char *bench_rays(void);

#define NMETHODS 8
extern const char *const methods[NMETHODS];      /* short names (CSV, BENCH_METHODS) */
extern const char *const method_names[NMETHODS]; /* the table's */

/* The table of one scene's runs (bench/notes.md, "Speed against error"). */
void table(ctx *c, const bscene *b, FILE *md);
/* Each cache method at the defaults against brute force at equal error. */
void defaults_table(ctx *c, const bscene *b, FILE *md);
/* The geometric means over the scenes run (bench/README.md). */
void corpus_summary(const ctx *c, FILE *md);
/* One data file per method for gnuplot, and its lines in plot.gp. */
void data_files(const ctx *c, const bscene *b, FILE *gp);

/* bench.c's: every run's settings before its own (the scene's, BENCH_SET's),
 * a lattice's offset, and one run rendered, measured and written out. */
render_opts base_opts(const ctx *c);
int lattice_offset(const ctx *c);
int add_run(ctx *c, const char *method, double param, const render_opts *o, const bscene *b,
            FILE *csv);
/* select.c: whether the comma-separated list in VAR names NAME (unset:
 * all do), BENCH_METHODS's shorthand, a scene named by its family
 * (BENCH_SCENES=sponza: sponza-atrium, sponza-arcade), and BENCH_SET's
 * settings laid over o. */
int wanted(const char *var, const char *name);
int wanted_method(const char *name);
int wanted_family(const char *name);
void experiment_opts(render_opts *o);
/* BENCH_A="0.4,0.2": the a values a sweep runs instead of its own (up to
 * max); returns how many, 0 when BENCH_A is unset. */
int bench_a_list(double *out, int max);

/* A scene of several bounces (bounces.c): path tracing, the cache at the
 * first level with path-traced gathers, and a cache at every level. */
int bounce_sweep(ctx *c, const bscene *b, FILE *csv);

#endif
