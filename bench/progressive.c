/*
 * progressive.c -- the cache in a progressive path tracer: the image is
 * rendered one sample a pixel at a time over the whole frame (as an
 * interactive renderer shows it converging), in bench/host.c's scene, and
 * measured at 4, 16, 64, 256 and 1,024 samples a pixel against the same
 * host's own light-sampled path tracing at equal relative RMSE.
 *
 * A pixel's radiance is the light seen directly, direct light at the
 * first hit (one light sample) and one bounce of indirect light, albedo x
 * E / pi; E comes from
 *   path    one cosine-distributed ray and one light sample where it lands;
 *   pixel   irc_cache_lookup_pixel with the library's defaults, an
 *           irc_pixel a pixel, and irc_progress after every iteration;
 *   sample  the same calls without irc_pixel: irc_cache_lookup_or_compute_px
 *           at every sample (a host that keeps nothing per pixel);
 *   fixed   irc_cache_lookup_pixel without irc_progress: records as 0.4
 *           made them, one estimate each (what refinement changes).
 * Errors are against path tracing at many more samples (pixel-major, its
 * own random numbers).  That reference is noisy too: an image with error
 * e measures sqrt(e^2 + v / R) for a reference of R samples, v the path
 * tracer's per-sample relative variance (estimated from its own 4-sample
 * image), so the table gives each error with v / R taken out ("rmse")
 * beside the raw one.  Speed-up at equal error: the path tracer's time at
 * the same samples times (its error / the cache's)^2 (its error falls as
 * 1/sqrt(time)), over the cache's time.  Times are the thread's CPU time,
 * without the error measurements; "library" is the time inside irc_*
 * calls less the callback's (monotonic clock: one thread, so the same).
 *
 * The table and CSV are bench/progress_report.h's; its `traced` column is
 * 0 here (this host does not count its rays; cache_rays are the library's).
 *
 * Usage: bench_progressive [width height samples reference_samples]
 * (default 128 96 1024 4096).  PROG_MODES=path,pixel,... chooses modes;
 * PROG_A=a sets the knob.  PROG_IMAGES=DIR writes DIR/MODE-SPP.ppm.
 */
#define _POSIX_C_SOURCE 200809L
#define IRC_EXPERIMENTAL /* irc_progress, irc_cache_lookup_pixel */
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

#include "host_scene.h"
#include "progress_report.h"

enum { PATH, PIXEL, SAMPLE, FIXED, MODES };
static const char *const mode_name[MODES] = {"path", "pixel", "sample", "fixed"};

/* E at the first hit by the mode's means; the library's CPU into *lib. */
static int irradiance(host *h, irc_cache *c, irc_pixel *pix, int mode, const float x[3],
                      const float n[3], float fp, float e[3], double *lib)
{
    double t0, tr;
    int st;
    if (mode == PATH) {
        path_irradiance(h, x, n, e);
        return 0;
    }
    /* the monotonic clock (vDSO, ~30 ns): a thread CPU clock read is a
     * system call, which at two a sample would be most of the time */
    t0 = bench_now();
    tr = h->t_trace;
    if (mode == SAMPLE)
        st = irc_cache_lookup_or_compute_px(c, x, n, NULL, fp, e, NULL, h);
    else
        st = irc_cache_lookup_pixel(c, &pix[h->pixel], x, n, NULL, fp, e, NULL, h);
    *lib += bench_now() - t0 - (h->t_trace - tr);
    return st < 0 ? st : 0;
}

/* One sample through image point (px, py), added to acc. */
static int sample(host *h, irc_cache *c, irc_pixel *pix, int mode, float px, float py,
                  double *acc, double *lib)
{
    const float pixw = 2.0f * tanf(0.5f * fov) / (float)h->h;
    float d[3], x[3], e[3], l[3], fp, cs;
    hit r;
    int k;
    camera(h, px, py, d);
    if (!intersect(eye, d, 1e30f, &r))
        return 0;
    if (r.mat == LIGHT) {
        for (k = 0; k < 3; k++)
            acc[k] += light_le;
        return 0;
    }
    for (k = 0; k < 3; k++)
        x[k] = eye[k] + r.t * d[k];
    cs = fabsf(dot(d, r.n));
    fp = r.t * pixw / sqrtf(cs > 1e-3f ? cs : 1e-3f);
    if (irradiance(h, c, pix, mode, x, r.n, fp, e, lib) < 0)
        return -1;
    direct(h, x, r.n, r.mat, l);
    for (k = 0; k < 3; k++)
        acc[k] += l[k] + albedo[r.mat][k] / PI * e[k];
    return 0;
}

static void write_ppm(const host *h, const char *mode, int s, const double *acc)
{
    char path[512];
    FILE *f;
    int i, k;
    snprintf(path, sizeof path, "%s/%s-%d.ppm", getenv("PROG_IMAGES"), mode, s);
    if (!(f = fopen(path, "wb")))
        return;
    fprintf(f, "P6\n%d %d\n255\n", h->w, h->h);
    for (i = 0; i < h->w * h->h; i++)
        for (k = 0; k < 3; k++) {
            double v = pow(acc[3 * i + k] / s > 0.0 ? acc[3 * i + k] / s : 0.0, 1.0 / 2.2);
            fputc(v >= 1.0 ? 255 : (int)(255.0 * v + 0.5), f);
        }
    fclose(f);
}

/* Renders sample-major up to spp, measuring at the checkpoints. */
static int render(host *h, irc_cache *c, int mode, int spp, const float *ref, point *pts)
{
    const int n = h->w * h->h;
    double *acc = calloc((size_t)n * 3, sizeof(double)), lib = 0.0, spent = 0.0, t0;
    irc_pixel *pix = calloc((size_t)n, sizeof(irc_pixel));
    int s, i, q = 0, failed = 0;
    if (!acc || !pix)
        return -1;
    t0 = cpu_now();
    for (s = 0; s < spp && !failed; s++) {
        for (i = 0; i < n && !failed; i++) {
            h->pixel = i;
            failed = sample(h, c, pix, mode, (float)(i % h->w) + rnd(h),
                            (float)(i / h->w) + rnd(h), &acc[3 * i], &lib) < 0;
        }
        if (c && mode != FIXED) {
            double u = bench_now(), tr = h->t_trace;
            failed |= irc_progress(c, (uint32_t)s + 1u, h) < 0;
            lib += bench_now() - u - (h->t_trace - tr);
        }
        while (q < CHECKS && check_spp[q] == s + 1) {
            double u = cpu_now();
            checkpoint(&pts[q], u - t0 - spent, lib, n, acc, s + 1, ref, c);
            if (getenv("PROG_IMAGES"))
                write_ppm(h, mode_name[mode], s + 1, acc);
            spent += cpu_now() - u;
            q++;
        }
    }
    free(acc);
    free(pix);
    return failed ? -1 : 0;
}

/* The reference: path tracing pixel-major at ref_spp. */
static void reference(host *h, int ref_spp, float *ref)
{
    int i, s, k;
    for (i = 0; i < h->w * h->h; i++) {
        double acc[3] = {0, 0, 0};
        h->pixel = i;
        for (s = 0; s < ref_spp; s++)
            (void)sample(h, NULL, NULL, PATH, (float)(i % h->w) + rnd(h),
                         (float)(i / h->w) + rnd(h), acc, NULL);
        for (k = 0; k < 3; k++)
            ref[3 * i + k] = (float)(acc[k] / ref_spp);
    }
}

static int wanted(int mode)
{
    const char *m = getenv("PROG_MODES");
    return !m || strstr(m, mode_name[mode]) != NULL;
}

int main(int argc, char **argv)
{
    host h = {0};
    int spp = 1024, ref_spp = 4096, mode, failed = 0;
    static point pts[MODES][CHECKS];
    float *ref;
    double t0;
    setvbuf(stdout, NULL, _IOLBF, 0); /* rows as they come: runs are long */
    if (argc == 5) {
        h.w = atoi(argv[1]);
        h.h = atoi(argv[2]);
        spp = atoi(argv[3]);
        ref_spp = atoi(argv[4]);
    } else {
        h.w = 128;
        h.h = 96;
    }
    if (h.w <= 0 || h.h <= 0 || spp <= 0 || ref_spp <= 0)
        return fprintf(stderr, "usage: bench_progressive [width height samples ref_samples]\n"), 2;
    if (!(ref = malloc(sizeof(float) * 3 * (size_t)h.w * (size_t)h.h)))
        return 1;
    h.rng = 0x2545f4914f6cdd1dull;
    t0 = cpu_now();
    reference(&h, ref_spp, ref);
    printf("%s %dx%d, progressive to %d samples a pixel; reference: path tracing at %d "
           "(%.1f s)\n",
           irc_version_string(), h.w, h.h, spp, ref_spp, cpu_now() - t0);
    for (mode = PATH; mode < MODES; mode++) {
        irc_config cfg = IRC_CONFIG_INIT; /* the library's defaults */
        irc_cache *c = NULL;
        size_t bytes;
        if (mode != PATH && !wanted(mode))
            continue;
        h.rng = 0x9e3779b97f4a7c15ull + (unsigned long long)mode;
        h.t_trace = 0.0;
        cfg.trace = trace;
        cfg.context = &h;
        cfg.accuracy = getenv("PROG_A") ? (float)atof(getenv("PROG_A")) : 0.0f;
        if (mode != PATH) {
            const uint32_t max = (uint32_t)(h.w * h.h);
            if (irc_footprint(&cfg, max, &bytes) < 0 || !(cfg.buffer = malloc(bytes)))
                return 1;
            cfg.buffer_size = bytes;
            if (irc_init(&cfg, max, &c) < 0)
                return 1;
            if (mode != FIXED && irc_progress(c, 0, &h) < 0)
                return 1;
        }
        if (render(&h, c, mode, spp, ref, pts[mode]) < 0) {
            printf("%s failed\n", mode_name[mode]);
            failed = 1;
        }
        if (c) {
            irc_stats st;
            if (irc_cache_stats(c, &st) == IRC_OK)
                printf("%s: block %.1f MB (%llu records used, %zu bytes each)%s\n",
                       mode_name[mode], (double)bytes / 1048576.0,
                       (unsigned long long)st.records, st.record_bytes,
                       mode == SAMPLE ? "" : "; irc_pixel store 120 bytes a pixel");
            irc_fini(c);
        }
        free(cfg.buffer);
    }
    denoise(pts, MODES, ref_spp);
    report(mode_name, pts, MODES, getenv("PROG_CSV"));
    free(ref);
    return failed;
}
