/*
 * bench.c -- speed against error (make bench).  For every shipped scene it
 * renders the one-bounce indirect term kd/pi E with every method:
 *   brute force at several rays per shading point;
 *   the cache without gradients, with translational + rotational
 *   gradients, with visibility gradients, and with SH records (on the
 *   scenes that are glossy or lit by near sources), each over a sweep of
 *   the accuracy a; and the translational + rotational cache over a sweep
 *   of strata;
 * and measures each run against a brute-force reference: relative RMSE
 * (sqrt(sum (a-b)^2 / sum b^2) over pixels and channels) and the 99th
 * percentile of the per-pixel relative error |A - B| / (B + 0.05 mean B)
 * (A, B the channel sums; the floor keeps black pixels from dividing by 0).
 *
 * The reference is brute force with REF rays at every STRIDE-th pixel in x
 * and y (errors are measured on that lattice), rendered twice with other
 * seeds and averaged; its own noise, the RMSE between the two over 2, is
 * reported.  References are cached in build/bench/ and reused.
 *
 * Writes build/bench/bench.csv, build/bench/table.md (bench/notes.md's table),
 * one data file per scene and method and build/bench/plot.gp for gnuplot.
 *   bench [quick]
 * BENCH_SCENES and BENCH_METHODS (comma-separated names) restrict a run to
 * some scenes and methods, for experiments; such a run leaves bench/notes.md
 * alone (bench.sh).
 */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "bench.h"
#include "image.h"

static const bscene scenes[] = {
    /* The real scenes (make real-scenes): brute force on the reference's
     * lattice only, its time scaled to the whole image. */
    {"sponza-atrium", "build/scenes/sponza-atrium.scene", 640, 480, 160, 120, 0, 0, 0, 8, 0, 0},
    {"sponza-arcade", "build/scenes/sponza-arcade.scene", 640, 480, 160, 120, 0, 0, 0, 8, 0, 0},
    {"sponza-gallery", "build/scenes/sponza-gallery.scene", 640, 480, 160, 120, 0, 0, 0, 8, 0, 0},
    {"sponza-floor", "build/scenes/sponza-floor.scene", 640, 480, 160, 120, 0, 0, 0, 8, 0, 0},
    {"sponza-capitals", "build/scenes/sponza-capitals.scene", 640, 480, 160, 120, 0, 0, 0, 8, 0, 0},
    /* Furnished interiors (bench/notes.md, "The corpus"): their models
     * are not shipped. */
    {"breakfast-table", "build/scenes/breakfast-room-table.scene", 640, 480, 160, 120, 0, 0, 0, 8,
     0, 1},
    {"breakfast-chairs", "build/scenes/breakfast-room-chairs.scene", 640, 480, 160, 120, 0, 0, 0, 8,
     0, 1},
    {"greywhite-windows", "build/scenes/grey-white-room-windows.scene", 640, 480, 160, 120, 0, 0, 0,
     8, 0, 1},
    {"greywhite-fireplace", "build/scenes/grey-white-room-fireplace.scene", 640, 480, 160, 120, 0, 0,
     0, 8, 0, 1},
    /* A sunlit kitchen of 1M triangles, many small objects (bench/notes.md,
     * "The corpus"): not shipped either. */
    {"kitchen-window", "build/scenes/country-kitchen-window.scene", 640, 480, 160, 120, 0, 0, 0, 8,
     0, 1},
    {"kitchen-island", "build/scenes/country-kitchen-island.scene", 640, 480, 160, 120, 0, 0, 0, 8,
     0, 1},
    {"kitchen-table", "build/scenes/country-kitchen-table.scene", 640, 480, 160, 120, 0, 0, 0, 8,
     0, 1},
    {"cornell", "demo/scenes/cornell.scene", 512, 512, 128, 128, 0, 0, 0, 0, 0, 0},
    {"fig5", "demo/scenes/fig5.scene", 256, 192, 128, 96, 1, 0, 0, 0, 0, 0},
    {"fig15", "demo/scenes/fig15.scene", 256, 256, 96, 96, 0, 0, 0, 0, 0, 0},
    /* The ground's lit spots under three small emitters: one light sample
     * a secondary hit left a 16384-ray reference 3.5% noisy. */
    {"sh", "demo/scenes/sh.scene", 128, 128, 64, 64, 1, 16, 65536, 0, 0, 0},
    /* Several bounces (make bench-bounces): only when BENCH_SCENES names
     * them. */
    {"bounces3-cornell", "demo/scenes/cornell.scene", 256, 256, 64, 64, 0, 0, 0, 0, 3, 0},
    {"bounces2-cornell", "demo/scenes/cornell.scene", 256, 256, 64, 64, 0, 0, 0, 0, 2, 0},
    {"bounces2-sponza-atrium", "build/scenes/sponza-atrium.scene", 640, 480, 160, 120, 0, 0, 0, 8,
     2, 0},
};


static double elapsed(const struct timespec *t0)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)(t.tv_sec - t0->tv_sec) + 1e-9 * (double)(t.tv_nsec - t0->tv_nsec);
}

/* The lattice errors are measured on: every stride-th pixel from an odd
 * offset, so that it never meets the coarse fill passes' pixels (multiples
 * of powers of two), where records are made and a lookup answers with its
 * own record: measured there, a cache's interpolation would go unseen. */
int lattice_offset(const ctx *c)
{
    return c->stride / 2 + 1;
}

static int on_lattice(const ctx *c, int i)
{
    const int o = lattice_offset(c), x = i % c->w - o, y = i / c->w - o;
    return x >= 0 && y >= 0 && x % c->stride == 0 && y % c->stride == 0;
}

/* Shell sort, ascending: enough for a lattice of some 20k pixels. */
static void sort(double *v, int m)
{
    int gap, i, j;
    for (gap = m / 2; gap > 0; gap /= 2)
        for (i = gap; i < m; i++) {
            double x = v[i];
            for (j = i; j >= gap && v[j - gap] > x; j -= gap)
                v[j] = v[j - gap];
            v[j] = x;
        }
}

/* Over the lattice: relative RMSE, percentiles of the per-pixel relative
 * error, the share of the squared error in the worst 1% of pixels, the
 * pixels lit more than 25% of the mean above the reference (leaks) and
 * the bias of the mean. */
static void measure(const ctx *c, const float *img, const float *ref, run *r)
{
    const int n = c->w * c->h;
    double se = 0.0, sr = 0.0, mean = 0.0, sa = 0.0, sb = 0.0, top;
    double *rel = malloc(sizeof(double) * (size_t)n), *sq = malloc(sizeof(double) * (size_t)n);
    int i, k, m = 0;
    for (i = 0; i < n; i++)
        if (on_lattice(c, i)) {
            mean += ref[3 * i] + ref[3 * i + 1] + ref[3 * i + 2];
            m++;
        }
    mean /= m;
    r->leaks = 0;
    for (i = 0, m = 0; i < n; i++) {
        double a = 0.0, b = 0.0, sp = 0.0;
        if (!on_lattice(c, i))
            continue;
        for (k = 0; k < 3; k++) {
            sp += (img[3 * i + k] - ref[3 * i + k]) * (double)(img[3 * i + k] - ref[3 * i + k]);
            sr += ref[3 * i + k] * (double)ref[3 * i + k];
            a += img[3 * i + k];
            b += ref[3 * i + k];
        }
        se += sp;
        sq[m] = sp;
        sa += a;
        sb += b;
        /* light where the reference has far less: a leak, as seen */
        r->leaks += a - b > 0.25 * mean;
        rel[m++] = fabs(a - b) / (b + 0.05 * mean);
    }
    sort(rel, m);
    sort(sq, m);
    for (i = m - 1, top = 0.0; i >= m - (m + 99) / 100; i--)
        top += sq[i];
    r->worst1 = se > 0.0 ? top / se : 0.0;
    r->bias = sb > 0.0 ? sa / sb - 1.0 : 0.0;
    free(sq);
    /* Outliers seen, not averaged away: the 99.9th percentile, the worst
     * pixel, and how many are over 10%. */
    r->rmse = sr > 0.0 ? sqrt(se / sr) : 0.0;
    r->p99 = rel[(int)(0.99 * (m - 1))];
    r->p999 = rel[(int)(0.999 * (m - 1))];
    r->maxe = rel[m - 1];
    for (i = 0, r->over10 = 0; i < m; i++)
        r->over10 += rel[i] > 0.1;
    free(rel);
}

/* BENCH_IMAGES=1: the run's image, and its error on the lattice (red:
 * above the reference, blue: below, by |A - B| / mean, each lattice pixel
 * a block), as PNGs in OUT, to look at where the error sits. */
static void save_images(const ctx *c, const bscene *b, const run *r, const float *img)
{
    const int n = c->w * c->h, s = c->stride;
    float *err = calloc((size_t)n * 3, sizeof(float));
    double mean = 0.0;
    char path[256], e[256];
    int i, k, m = 0;
    if (!err)
        return;
    for (i = 0; i < n; i++)
        if (on_lattice(c, i)) {
            mean += c->ref[3 * i] + c->ref[3 * i + 1] + c->ref[3 * i + 2];
            m++;
        }
    mean /= m;
    for (i = 0; i < n; i++) {
        const int o = lattice_offset(c), x = i % c->w, y = i / c->w;
        const int j = (y < o ? o : y - (y - o) % s) * c->w + (x < o ? o : x - (x - o) % s);
        double d = 0.0;
        for (k = 0; k < 3; k++)
            d += img[3 * j + k] - c->ref[3 * j + k];
        err[3 * i + (d > 0.0 ? 0 : 2)] = (float)(fabs(d) / mean);
    }
    { /* the ten worst lattice pixels, by squared error */
        int worst[10] = {-1, -1, -1, -1, -1, -1, -1, -1, -1, -1}, q;
        double wv[10] = {0};
        for (i = 0; i < n; i++) {
            double d = 0.0;
            if (!on_lattice(c, i))
                continue;
            for (k = 0; k < 3; k++)
                d += (img[3 * i + k] - c->ref[3 * i + k]) * (double)(img[3 * i + k] - c->ref[3 * i + k]);
            for (q = 10; q > 0 && d > wv[q - 1]; q--)
                if (q < 10) {
                    wv[q] = wv[q - 1];
                    worst[q] = worst[q - 1];
                }
            if (q < 10) {
                wv[q] = d;
                worst[q] = i;
            }
        }
        printf("    worst pixels (x y: image, reference, in means):");
        for (q = 0; q < 10 && worst[q] >= 0; q++)
            printf(" %d %d: %.2f %.2f;", worst[q] % c->w, worst[q] / c->w,
                   (img[3 * worst[q]] + img[3 * worst[q] + 1] + img[3 * worst[q] + 2]) / mean,
                   (c->ref[3 * worst[q]] + c->ref[3 * worst[q] + 1] + c->ref[3 * worst[q] + 2]) / mean);
        printf("\n");
    }
    snprintf(path, sizeof path, OUT "/%s-%s-%g-%ux%u.png", b->name, r->method, r->param, r->m, r->n);
    png_write(path, c->w, c->h, img, 4.0f, e, sizeof e);
    strcpy(path + strlen(path) - 3, "exr");
    exr_write(path, c->w, c->h, img, 0, e, sizeof e);
    snprintf(path, sizeof path, OUT "/%s-%s-%g-%ux%u-err.png", b->name, r->method, r->param, r->m,
             r->n);
    png_write(path, c->w, c->h, err, 1.0f, e, sizeof e);
    free(err);
}

/* Which tracer casts the rays: Embree where the bench was built with it
 * (the Makefile does where Embree is installed), unless BENCH_RAYS=bvh. */
const char *bench_rays(void)
{
#ifdef BENCH_EMBREE
    const char *v = getenv("BENCH_RAYS");
    if (!(v && !strcmp(v, "bvh")))
        return "Embree";
#endif
    return "the demo's BVH";
}

static int render(ctx *c, const render_opts *o, float *img, render_stats *st)
{
    renderer r;
    char err[256];
    int e;
    if (renderer_init(&r, &c->s, o, err, sizeof err) < 0) {
        fprintf(stderr, "bench: %s\n", err);
        return -1;
    }
#ifdef BENCH_EMBREE
    if (!strcmp(bench_rays(), "Embree") && bvh_embree(&r.b, err, sizeof err) < 0) {
        fprintf(stderr, "bench: %s\n", err);
        renderer_free(&r);
        return -1;
    }
#endif
    memset(img, 0, sizeof(float) * 3 * (size_t)c->w * c->h);
    e = render_image(&r, img, st);
    renderer_free(&r);
    if (e < 0)
        fprintf(stderr, "bench: render failed: %s\n", irc_strerror(e));
    return e < 0 ? -1 : 0;
}

render_opts base_opts(const ctx *c)
{
    render_opts o;
    memset(&o, 0, sizeof o);
    o.threads = c->threads;
    o.show = SHOW_INDIRECT;
    o.light_samples = 1;
    o.seed = 7;
    o.accuracy = 0.2f;
    o.strata_m = DEF_M;
    o.strata_n = DEF_N;
    /* the header's sizing rule: max_records = pixels (a run that evicts
     * or leaves records unstored says so) */
    o.max_records = c->w * c->h;
    o.secondary_samples = c->secondary;
    o.bounces = c->bounces;
    experiment_opts(&o);
    return o;
}

/* The two references (cached by scene, size, lattice, rays and seed), and
 * their average. */
static int reference(ctx *c, const bscene *b)
{
    float *one[2];
    int k, i, n = c->w * c->h;
    for (k = 0; k < 2; k++) {
        char path[256], err[256];
        int rw, rh;
        char bn[16] = ""; /* one bounce: the name references always had */
        /* "-ua": rays below the surface left out at every bounce, not
         * only at the camera's hits ("-u"; bench/notes.md, "Rays under the
         * surface") */
        if (c->bounces > 1)
            snprintf(bn, sizeof bn, "-b%d-ua", c->bounces);
        snprintf(path, sizeof path, OUT "/ref-%s-%dx%d-s%d-o%d-r%d-l%d%s-u-seed%d.exr", b->name,
                 c->w, c->h, c->stride, lattice_offset(c), c->ref_rays, c->secondary, bn, k + 1);
        if (exr_read(path, &rw, &rh, &one[k], err, sizeof err) == 0 && rw == c->w && rh == c->h) {
            printf("  reference %d: %s (cached)\n", k + 1, path);
            continue;
        }
        {
            render_opts o = base_opts(c);
            render_stats st;
            o.mode = MODE_REFERENCE;
            o.ref_rays = c->ref_rays;
            o.stride = c->stride;
            o.stride_offset = lattice_offset(c);
            o.seed = (uint64_t)k + 1001;
            one[k] = malloc(sizeof(float) * 3 * (size_t)n);
            if (render(c, &o, one[k], &st) < 0 ||
                exr_write(path, c->w, c->h, one[k], 0, err, sizeof err) < 0)
                return -1;
            printf("  reference %d: %d rays at every %dth pixel, %.1f s\n", k + 1, c->ref_rays,
                   c->stride, st.wall);
        }
    }
    c->ref = malloc(sizeof(float) * 3 * (size_t)n);
    for (i = 0; i < 3 * n; i++)
        c->ref[i] = 0.5f * (one[0][i] + one[1][i]);
    {
        run noise;
        measure(c, one[0], one[1], &noise);
        c->ref_noise = 0.5 * noise.rmse; /* of the average of two */
    }
    free(one[0]);
    free(one[1]);
    return 0;
}

/* Record noise (bench/notes.md, "Noise and bias"): two renders that
 * differ only in the cache's seed differ by the records' noise alone, so
 * noise^2 = sum (T1 - T2)^2 / 2 over the lattice, relative to the
 * reference's sum of squares.  Its share of the run's squared error is
 * what averaging records could remove; the rest is bias (interpolation,
 * leaks). */
static int record_noise(ctx *c, const render_opts *o, const float *img, run *r)
{
    render_opts o2 = *o;
    render_stats st;
    const int n = c->w * c->h;
    float *two = malloc(sizeof(float) * 3 * (size_t)n);
    double *dd = malloc(sizeof(double) * (size_t)n);
    double sd = 0.0, sr = 0.0, top = 0.0;
    int i, k, m = 0;
    r->noise = -1.0;
    o2.seed = o->seed + 1;
    if (!two || !dd || render(c, &o2, two, &st) < 0) {
        free(two);
        free(dd);
        return -1;
    }
    for (i = 0; i < n; i++)
        if (on_lattice(c, i)) {
            dd[m] = 0.0;
            for (k = 0; k < 3; k++) {
                const double d = (double)img[3 * i + k] - two[3 * i + k];
                dd[m] += d * d;
                sr += c->ref[3 * i + k] * (double)c->ref[3 * i + k];
            }
            sd += dd[m++];
        }
    sort(dd, m);
    for (i = m - 1; i >= m - (m + 99) / 100; i--)
        top += dd[i];
    r->noise = sr > 0.0 ? sqrt(sd / 2.0 / sr) : 0.0;
    r->noise_top1 = sd > 0.0 ? top / sd : 0.0;
    free(two);
    free(dd);
    return 0;
}

static double pct(double part, double whole)
{
    return whole > 0.0 ? 100.0 * part / whole : 0.0;
}

int add_run(ctx *c, const char *method, double param, const render_opts *o, const bscene *b,
            FILE *csv)
{
    run *r = &c->runs[c->nruns];
    const char *nz = getenv("BENCH_NOISE");
    r->m = o->mode == MODE_CACHE ? o->strata_m : 0;
    r->n = o->mode == MODE_CACHE ? o->strata_n : 0;
    r->noise = -1.0;
    float *img = malloc(sizeof(float) * 3 * (size_t)c->w * c->h);
    if (!img || c->nruns == MAX_RUNS || render(c, o, img, &r->st) < 0)
        return -1;
    /* record noise: a second render (quick runs: only with BENCH_NOISE=1) */
    if (o->mode == MODE_CACHE && (nz ? strcmp(nz, "0") != 0 : !c->quick) &&
        record_noise(c, o, img, r) < 0)
        return -1;
    if (o->stride > 1) { /* a lattice stands for the image */
        const int s = o->stride, off = o->stride_offset;
        const double f = (double)c->w * c->h /
                         (double)(((c->w - off + s - 1) / s) * ((c->h - off + s - 1) / s));
        r->st.wall *= f;
        r->st.cpu *= f;
        r->st.trace_s *= f;
        r->st.rays = (uint64_t)((double)r->st.rays * f);
    }
    snprintf(r->method, sizeof r->method, "%s", method);
    r->param = param;
    measure(c, img, c->ref, r);
    if (getenv("BENCH_IMAGES"))
        save_images(c, b, r, img);
    free(img);
    c->nruns++;
    fprintf(csv, "%s,%s,%g,%ux%u,%.4f,%.4f,%.4f,%llu,%llu,%zu,%zu,%.5f,%.5f,%.5f,%.5f,%.5f,%d,"
                 "%.4f,%d,%.5f,%.4f,%.5f,%.4f,%.4f,%.4f\n",
            b->name, method, param, r->m, r->n, r->st.wall, r->st.trace_s, r->st.cache_s,
            (unsigned long long)r->st.rays, (unsigned long long)r->st.records,
            (size_t)r->st.records * r->st.record_bytes, r->st.cache_bytes, r->rmse, r->p99,
            c->ref_noise, r->p999, r->maxe, r->over10, r->worst1, r->leaks, r->bias, r->st.cpu,
            r->noise, r->st.lookup_s, r->st.gather_s, r->st.pass_s);
    fflush(csv);
    printf("  %-10s %5g %4ux%-4u %7.2f CPU s, rel RMSE %.4f", method, param, r->m, r->n,
           r->st.cpu, r->rmse);
    if (r->noise >= 0.0)
        printf(" (record noise %.4f: %.0f%% of the squared error, %.0f%% of it in 1%% of the "
               "pixels)", r->noise,
               r->rmse > 0.0 ? 100.0 * r->noise * r->noise / (r->rmse * r->rmse) : 0.0,
               100.0 * r->noise_top1);
    printf(", p99 %.4f, p99.9 %.4f, max %.4f, "
           "%d px > 10%%, worst 1%% %.0f%%, leaks %d, bias %+.2f%%, records %llu, "
           "cache %.1f%% of thread time\n",
           r->p99, r->p999, r->maxe, r->over10,
           100.0 * r->worst1, r->leaks, 100.0 * r->bias, (unsigned long long)r->st.records,
           100.0 * r->st.cache_s / r->st.cpu);
    if (o->mode == MODE_CACHE)
        printf("  %-10s the library's own CPU (outside the callback) %.1f%% of the render: "
               "lookups %.1f%%, record and detail sampling with inserts %.1f%%, pass ends "
               "%.1f%% (%s)\n",
               method, pct(r->st.cache_s, r->st.cpu), pct(r->st.lookup_s, r->st.cpu),
               pct(r->st.gather_s, r->st.cpu), pct(r->st.pass_s, r->st.cpu), bench_rays());
    if (o->mode == MODE_CACHE && !(o->features & IRC_FEATURE_SH))
        printf("  %-10s rays %llu, lookups %llu, hits %llu, records %llu, per-pixel detail "
               "estimates %llu\n",
               method, (unsigned long long)r->st.rays, (unsigned long long)r->st.lookups,
               (unsigned long long)r->st.hits, (unsigned long long)r->st.records,
               (unsigned long long)r->st.details);
    if (r->st.evictions || r->st.not_stored)
        printf("  %-10s the pool of %d records (one a pixel) filled: %llu evicted, %llu not "
               "stored\n", method, c->w * c->h, (unsigned long long)r->st.evictions,
               (unsigned long long)r->st.not_stored);
    return 0;
}


/* Equal record count (Cornell box, as Schwarzhaupt et al. compare radius
 * rules): each radius rule's a is searched until the fill makes about
 * `target` records (records go as 1/a^2), then the RMSE at exactly
 * `target` is interpolated in log-log between the two runs that bracket
 * it.  32x128 strata (4096 rays a record, their paper's count), so that
 * record noise does not hide the placement.  The radius rules are compared
 * without the leak guard, as the paper's are; the last row adds it (it
 * cuts reach short where a record saw geometry, so it needs records near
 * occluders that no a removes). */
#define NRULES 5
static const char *const rules[NRULES] = {"split", "grad", "hess0", "hess", "hess-guard"};
static const char *const rule_names[NRULES] = {
    "split sphere (no gradients)", "gradient-clamped (trans + rot)", "Hessian radii, no gradients",
    "Hessian radii + trans + rot", "the same with the leak guard (the default)"};
static const uint32_t rule_feats[NRULES] = {
    IRC_FEATURE_NONE, IRC_FEATURE_TRANSLATION | IRC_FEATURE_ROTATION, IRC_FEATURE_HESSIAN,
    IRC_FEATURE_HESSIAN | IRC_FEATURE_TRANSLATION | IRC_FEATURE_ROTATION,
    IRC_FEATURE_HESSIAN | IRC_FEATURE_TRANSLATION | IRC_FEATURE_ROTATION};

typedef struct eqrec {
    double rmse, p99, maxe, a, records, cache_share;
    int over10;
} eqrec;

static int equal_records(ctx *c, const bscene *b, int rule, double target, FILE *csv, eqrec *out)
{
    double a = 0.5, lo_rec = 0, hi_rec = 0;
    const run *lo = NULL, *hi = NULL;
    int it;
    char name[32];
    snprintf(name, sizeof name, "eq-%s", rules[rule]);
    for (it = 0; it < 8 && !(lo && hi && hi_rec < 1.25 * lo_rec); it++) {
        render_opts o = base_opts(c);
        const run *r;
        o.mode = MODE_CACHE;
        o.features = rule_feats[rule];
        o.leak_guard = rule == 4 ? IRC_ON : IRC_OFF;
        o.accuracy = (float)a;
        o.strata_m = 32;
        o.strata_n = 128;
        if (add_run(c, name, a, &o, b, csv) < 0)
            return -1;
        r = &c->runs[c->nruns - 1];
        if ((double)r->st.records <= target && (!lo || r->st.records > lo_rec)) {
            lo = r;
            lo_rec = (double)r->st.records;
        }
        if ((double)r->st.records >= target && (!hi || r->st.records < hi_rec)) {
            hi = r;
            hi_rec = (double)r->st.records;
        }
        /* the next a from the nearest run, aiming a little past target on
         * the side not yet bracketed */
        a *= sqrt((double)r->st.records / (target * (lo ? 1.1 : 0.9)));
        if (a > 4.0)
            a = 4.0;
    }
    if (!lo || !hi) { /* the count is out of this rule's reach (a <= 4) */
        const run *near = lo ? lo : hi;
        memset(out, 0, sizeof *out);
        out->rmse = -2.0;
        out->records = near ? (double)near->st.records : 0.0;
        return 0;
    }
    {
        double u = hi_rec > lo_rec ? (log(target) - log(lo_rec)) / (log(hi_rec) - log(lo_rec)) : 0;
        const run *near = u < 0.5 ? lo : hi;
        out->rmse = exp(log(lo->rmse) + u * (log(hi->rmse) - log(lo->rmse)));
        out->p99 = near->p99;
        out->maxe = near->maxe;
        out->over10 = near->over10;
        out->a = near->param;
        out->records = (double)near->st.records;
        out->cache_share = 100.0 * near->st.cache_s / (c->threads * near->st.wall);
    }
    return 0;
}

static int equal_records_table(ctx *c, const bscene *b, FILE *csv, FILE *md)
{
    static const double targets[2] = {1700, 500};
    eqrec e[2][NRULES];
    int t, k;
    for (t = 0; t < 2; t++)
        for (k = 0; k < NRULES; k++)
            if (!wanted("BENCH_RULES", rules[k]))
                e[t][k].rmse = -1.0;
            else if (equal_records(c, b, k, targets[t], csv, &e[t][k]) < 0)
                return -1;
    fprintf(md, "\n**%s at equal record count** (32x128 strata; RMSE interpolated to the "
                "count; p99, max, px > 10%% and cache share from the nearest run)\n\n"
                "| radius rule | 1700 records: rel. RMSE (vs split) | p99 / max, px > 10%% | "
                "500 records: rel. RMSE (vs split) | p99 / max, px > 10%% |\n|---|---|---|---|---|\n",
            b->name);
    for (k = 0; k < NRULES; k++) {
        if (e[0][k].rmse == -1.0)
            continue;
        fprintf(md, "| %s |", rule_names[k]);
        for (t = 0; t < 2; t++)
            if (e[t][k].rmse == -2.0)
                fprintf(md, " not reached (%g records at a = 4) | |", e[t][k].records);
            else
                fprintf(md, " %.4f (%.2fx) | %.4f / %.3f, %d |", e[t][k].rmse,
                        e[t][0].rmse > 0.0 ? e[t][k].rmse / e[t][0].rmse : 0.0, e[t][k].p99,
                        e[t][k].maxe, e[t][k].over10);
        fprintf(md, "\n");
        printf("  equal records: %-9s 1700: %.4f (a %.3f, %g rec, max/p99 %.1f)  500: %.4f (a %.3f, "
               "%g rec, max/p99 %.1f)\n", rules[k], e[0][k].rmse, e[0][k].a, e[0][k].records,
               e[0][k].maxe / e[0][k].p99, e[1][k].rmse, e[1][k].a, e[1][k].records,
               e[1][k].maxe / e[1][k].p99);
    }
    return 0;
}


/* Brute force at 16 .. 4096 rays per point; each cache method at five a
 * (the real scenes four; quick: 16 .. 256 rays, a = 0.4 and 0.3, whose
 * records take 256 and 1,024 rays: a check that runs, not a frontier),
 * the strata following a (the library's knob: one sweep is the frontier). */
static int sweep(ctx *c, const bscene *b, FILE *csv)
{
    static const int brute[] = {16, 64, 256, 1024, 4096};
    static const double a_full[] = {0.4, 0.3, 0.2, 0.15, 0.1}, a_quick[] = {0.4, 0.3},
                        a_real[] = {0.4, 0.3, 0.2, 0.1};
    static const uint32_t feats[NMETHODS] = {
        0, IRC_FEATURE_NONE, IRC_FEATURE_TRANSLATION | IRC_FEATURE_ROTATION,
        IRC_FEATURE_VISIBILITY | IRC_FEATURE_TRANSLATION | IRC_FEATURE_ROTATION,
        IRC_FEATURE_HESSIAN | IRC_FEATURE_TRANSLATION | IRC_FEATURE_ROTATION,
        IRC_FEATURE_SH | IRC_FEATURE_SH_GRADIENT};
    double a_set[8];
    const int n_set = bench_a_list(a_set, 8);
    int nb = c->quick ? 3 : 5, na = c->quick ? 2 : 5;
    const double *as = c->quick ? a_quick : a_full;
    /* The real scenes: four a. */
    const int coarse = b->stride && !c->quick;
    int i, m;
    if (coarse) {
        as = a_real;
        na = 4;
    }
    if (n_set) { /* BENCH_A=0.4,0.2: these a */
        na = n_set;
        as = a_set;
    }
    for (i = 0; i < nb && wanted("BENCH_METHODS", "brute"); i++) {
        render_opts o = base_opts(c);
        o.mode = MODE_REFERENCE;
        o.ref_rays = brute[i];
        o.stride = b->stride ? c->stride : 0;
        o.stride_offset = lattice_offset(c);
        if (add_run(c, "brute", o.ref_rays, &o, b, csv) < 0)
            return -1;
    }
    for (m = 1; m < NMETHODS; m++)
        if ((strcmp(methods[m], "sh") || b->sh) && wanted("BENCH_METHODS", methods[m]))
            for (i = 0; i < na; i++) {
                render_opts o = base_opts(c);
                o.mode = MODE_CACHE;
                o.features = feats[m];
                o.accuracy = (float)as[i];
                experiment_opts(&o);
                if (add_run(c, methods[m], as[i], &o, b, csv) < 0)
                    return -1;
            }
    return 0;
}

int main(int argc, char **argv)
{
    ctx c;
    FILE *csv, *md, *gp;
    char host[256] = "unknown machine", line[512], date[64];
    struct timespec t0;
    time_t now = time(NULL);
    size_t k;
    memset(&c, 0, sizeof c);
    setvbuf(stdout, NULL, _IOLBF, 0);
    c.quick = argc > 1 && !strcmp(argv[1], "quick");
    c.threads = getenv("BENCH_THREADS") ? atoi(getenv("BENCH_THREADS")) : 0;
    if (c.threads < 1)
        c.threads = (int)sysconf(_SC_NPROCESSORS_ONLN);
    clock_gettime(CLOCK_MONOTONIC, &t0);
    mkdir("build", 0777);
    mkdir(OUT, 0777);
    {
        FILE *f = fopen("/proc/cpuinfo", "r");
        while (f && fgets(line, sizeof line, f))
            if (!strncmp(line, "model name", 10) && strchr(line, ':')) {
                snprintf(host, sizeof host, "%s", strchr(line, ':') + 2);
                host[strcspn(host, "\n")] = 0;
                break;
            }
        if (f)
            fclose(f);
    }
    strftime(date, sizeof date, "%Y-%m-%d", gmtime(&now));
    csv = fopen(OUT "/bench.csv", "w");
    md = fopen(OUT "/table.md", "w");
    gp = fopen(OUT "/plot.gp", "w");
    if (!csv || !md || !gp) {
        fprintf(stderr, "bench: cannot write in " OUT "\n");
        return 1;
    }
    fprintf(csv, "scene,method,param,strata,wall_s,trace_thread_s,cache_thread_s,rays,records,"
                 "record_bytes_used,block_bytes,rel_rmse,p99_rel_err,ref_noise,p999_rel_err,max_rel_err,"
                 "pixels_over_10pct,worst1_share,leaks,bias,cpu_s,record_noise,lookup_thread_s,"
                 "gather_thread_s,pass_thread_s\n");
    printf("rays: %s\n", bench_rays());
    fprintf(md, "`make bench%s` on %s (%d threads), %s; rays from %s. Indirect light kd/pi E (one bounce but in bounce scenes) "
                "only. Speedups are brute force's time to the same error over the method's: brute "
                "force's from a power law fitted over its runs (its exponent in each scene's "
                "title; \"ext\": extrapolated, at most 2x in error beyond its runs), the "
                "method's interpolated along its curve (log-log); plots in `" OUT "/SCENE.png`.\n",
            c.quick ? " BENCH_QUICK=1" : "", host, c.threads, date, bench_rays());
    fprintf(gp, "set terminal pngcairo size 900,600\nset logscale xy\nset xlabel 'CPU "
                "seconds'\nset ylabel 'relative RMSE'\nset key top right\n");
    for (k = 0; k < sizeof scenes / sizeof scenes[0]; k++) {
        const bscene *b = &scenes[k];
        char err[512];
        const int named = getenv("BENCH_SCENES") && *getenv("BENCH_SCENES");
        if ((!wanted("BENCH_SCENES", b->name) && !wanted_family(b->name)) ||
            (b->bounces > 1 && !named))
            continue;
        /* quick: one real view, unless BENCH_SCENES names others */
        if (c.quick && b->stride && !named && strcmp(b->name, "sponza-atrium"))
            continue;
        if (scene_load(b->path, &c.s, err, sizeof err) < 0) {
            fprintf(stderr, "%s\n", err);
            if (b->optional) {
                printf("%s: skipped, its model is absent (bench/README.md, \"Scenes and models\")\n",
                       b->name);
                continue;
            }
            return 1;
        }
        c.w = c.quick ? b->qw : b->w;
        c.h = c.quick ? b->qh : b->h;
        if (getenv("BENCH_SIZE") && sscanf(getenv("BENCH_SIZE"), "%dx%d", &c.w, &c.h) != 2) {
            fprintf(stderr, "bench: BENCH_SIZE=WxH\n");
            return 1;
        }
        c.s.cam.width = c.w;
        c.s.cam.height = c.h;
        c.nruns = 0;
        c.secondary = b->secondary;
        c.bounces = b->bounces;
        c.stride = b->stride ? b->stride : 4;
        c.ref_rays = b->ref_rays ? (c.quick ? b->ref_rays / 4 : b->ref_rays)
                                 : (c.quick ? 4096 : 16384);
        printf("%s at %dx%d\n", b->name, c.w, c.h);
        if (reference(&c, b) < 0 ||
            (b->bounces > 1 ? bounce_sweep(&c, b, csv) : sweep(&c, b, csv)) < 0)
            return 1;
        table(&c, b, md);
        defaults_table(&c, b, md);
        if (!strcmp(b->name, "cornell") && !c.quick && wanted("BENCH_METHODS", "equal") &&
            equal_records_table(&c, b, csv, md) < 0)
            return 1;
        data_files(&c, b, gp);
        free(c.ref);
        scene_free(&c.s);
    }
    corpus_summary(&c, md);
    fprintf(md, "\nTotal bench time %.0f s.\n", elapsed(&t0));
    fclose(csv);
    fclose(md);
    fclose(gp);
    printf("wrote " OUT "/bench.csv, " OUT "/table.md, " OUT "/plot.gp (%.0f s)\n", elapsed(&t0));
    return 0;
}
