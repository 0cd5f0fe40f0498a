/*
 * host.c -- the cache where users put it: a small path tracer with a scene
 * and tracer of its own (not the demo's), calling the cache at every
 * sample of every pixel, at many samples a pixel, single-threaded, with
 * the library's defaults and the default port.
 *
 * The scene: a box [-1, 1]^3 open toward the camera (z = +1), white floor,
 * ceiling and back wall, red left and green right wall, two white balls,
 * and a square light just under the ceiling.  A pixel's radiance is the
 * light seen directly, plus direct light at the first hit (one light
 * sample), plus one bounce of indirect light: albedo x E / pi, where E is
 * the irradiance from surfaces lit directly.  E comes either from a path
 * (one cosine-distributed ray, one light sample where it lands: "path") or
 * from the cache, whose records' rays see the same direct light:
 *   free    every sample calls irc_cache_lookup_or_compute_px;
 *   passes  the records are made in 64 fill passes over pixel centres
 *           (examples/passes.c's order), then every sample calls
 *           irc_cache_lookup and, on a miss, the _px call;
 *   open    as passes, with the samples' phase inside one more open pass
 *           (lookups in a pass take no lock; a miss's record shows after
 *           irc_pass_end);
 *   pixel   as passes, but one cache call a pixel: its first sample's E
 *           serves the pixel's other samples.
 * In every cache mode a pixel whose call answered IRC_DETAIL (its own
 * estimate) keeps that E for its later samples.
 * Error is relative RMSE against path tracing at many more samples (its
 * own random numbers) and the mean of the worst 1% of pixels' relative
 * errors.  The library's time is the time inside irc_* calls less the time
 * in the trace callback (two clock reads a call: ~2% of a lookup).  The
 * lookups of the samples are kept and replayed on the final cache with
 * nothing else running: lookups a second, as a profile would see them.
 *
 * Usage: bench_host [width height samples reference_samples]
 * (default 128 96 256 2048); HOST_A=a and HOST_BLEND=b set the cache's
 * accuracy and cfg.irr.blend (the library's defaults otherwise).  HOST_IMAGES=DIR writes each mode's image
 * and its error (red: above the reference, blue: below, full at 25% of
 * the reference) as DIR/MODE.ppm and DIR/MODE-err.ppm.  Exit status 0
 * when every run completed.
 */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench_util.h"

#include "host_scene.h"

enum mode { PATH, FREE, PASSES, OPEN, PIXEL, MODES };
static const char *const mode_name[MODES] = {"path", "free", "passes", "open", "pixel"};

typedef struct run {
    double seconds, library, rel_rmse, worst1, replay_rate;
    unsigned long long records, lookups, misses, details;
    int failed;
} run;

/* Calls the cache for E at x, timing the call. */
static int cache_irradiance(host *h, irc_cache *c, int mode, int fill, const float x[3],
                            const float n[3], float fp, float e[3], run *out)
{
    double t0 = bench_now(), tr = h->t_trace;
    int st = IRC_MISS;
    if (!fill && h->has_detail[h->pixel]) {
        memcpy(e, &h->detail[3 * h->pixel], sizeof(float) * 3);
        return 0;
    }
    if (!fill && mode != FREE) {
        st = irc_cache_lookup(c, x, n, e, NULL);
        if (h->nq < h->cap) {
            float *q = h->q + 6 * h->nq++;
            q[0] = x[0], q[1] = x[1], q[2] = x[2], q[3] = n[0], q[4] = n[1], q[5] = n[2];
        }
        out->lookups++;
    }
    if (st == IRC_MISS) {
        float w = 1.0f;
        st = irc_cache_lookup_or_compute_px(c, x, n, NULL, fp, e, &w, NULL);
        out->misses += !fill && w == 0.0f;
        if (mode == FREE && h->nq < h->cap) {
            float *q = h->q + 6 * h->nq++;
            q[0] = x[0], q[1] = x[1], q[2] = x[2], q[3] = n[0], q[4] = n[1], q[5] = n[2];
            out->lookups++;
        }
    }
    out->library += bench_now() - t0 - (h->t_trace - tr);
    if ((st == IRC_DETAIL || mode == PIXEL) && !fill && st >= 0) {
        h->has_detail[h->pixel] = 1;
        memcpy(&h->detail[3 * h->pixel], e, sizeof(float) * 3);
    }
    out->details += st == IRC_DETAIL && !fill;
    return st < 0 ? st : 0;
}

/* One sample through image point (px, py): its radiance into rgb. */
static int sample(host *h, irc_cache *c, int mode, int fill, float px, float py, float rgb[3],
                  run *out)
{
    const float pix = 2.0f * tanf(0.5f * fov) / (float)h->h;
    float d[3], x[3], e[3], l[3], fp;
    hit r;
    int k;
    rgb[0] = rgb[1] = rgb[2] = 0.0f;
    camera(h, px, py, d);
    if (!intersect(eye, d, 1e30f, &r))
        return 0;
    if (r.mat == LIGHT) {
        rgb[0] = rgb[1] = rgb[2] = light_le;
        return 0;
    }
    for (k = 0; k < 3; k++)
        x[k] = eye[k] + r.t * d[k];
    /* a pinhole's footprint: distance x pixel angle / sqrt(cos) */
    fp = r.t * pix / sqrtf(fabsf(dot(d, r.n)) > 1e-3f ? fabsf(dot(d, r.n)) : 1e-3f);
    if (mode == PATH)
        path_irradiance(h, x, r.n, e);
    else if (cache_irradiance(h, c, mode, fill, x, r.n, fp, e, out) < 0)
        return -1;
    direct(h, x, r.n, r.mat, l);
    for (k = 0; k < 3; k++)
        rgb[k] = l[k] + albedo[r.mat][k] / PI * e[k];
    return 0;
}

/* Pass k's pixel offset, coarse to fine (examples/passes.c). */
static void pass_offset(int k, int *ox, int *oy)
{
    int i;
    *ox = *oy = 0;
    for (i = 0; i < PASS_BITS; i++) {
        *ox |= ((k >> (2 * i)) & 1) << (PASS_BITS - 1 - i);
        *oy |= ((k >> (2 * i + 1)) & 1) << (PASS_BITS - 1 - i);
    }
}

/* The fill passes at pixel centres. */
static int fill_passes(host *h, irc_cache *c, run *out)
{
    const int period = 1 << PASS_BITS;
    int k, x, y, ox, oy;
    float rgb[3];
    for (k = 0; k < period * period; k++) {
        pass_offset(k, &ox, &oy);
        if (irc_pass_begin(c) < 0)
            return -1;
        for (y = oy; y < h->h; y += period)
            for (x = ox; x < h->w; x += period)
                if (sample(h, c, PASSES, 1, (float)x + 0.5f, (float)y + 0.5f, rgb, out) < 0)
                    return -1;
        if (irc_pass_end(c, NULL) < 0)
            return -1;
    }
    return 0;
}

/* Renders the image at spp samples a pixel (stratified jitter) into img. */
static int render(host *h, irc_cache *c, int mode, int spp, float *img, run *out)
{
    const int sq = (int)ceil(sqrt((double)spp));
    int x, y, s, k;
    double t0 = bench_now();
    if (mode == PASSES || mode == OPEN || mode == PIXEL)
        if (fill_passes(h, c, out) < 0)
            return -1;
    if (mode == OPEN && irc_pass_begin(c) < 0)
        return -1;
    memset(h->has_detail, 0, (size_t)h->w * (size_t)h->h);
    for (y = 0; y < h->h; y++)
        for (x = 0; x < h->w; x++) {
            double acc[3] = {0, 0, 0};
            h->pixel = y * h->w + x;
            for (s = 0; s < spp; s++) {
                float rgb[3], jx = ((float)(s % sq) + rnd(h)) / (float)sq,
                              jy = ((float)(s / sq % sq) + rnd(h)) / (float)sq;
                if (sample(h, c, mode, 0, (float)x + jx, (float)y + jy, rgb, out) < 0)
                    return -1;
                for (k = 0; k < 3; k++)
                    acc[k] += rgb[k];
            }
            for (k = 0; k < 3; k++)
                img[3 * (y * h->w + x) + k] = (float)(acc[k] / spp);
        }
    if (mode == OPEN) {
        double t1 = bench_now();
        if (irc_pass_end(c, NULL) < 0)
            return -1;
        out->library += bench_now() - t1;
    }
    out->seconds = bench_now() - t0;
    return 0;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? 1 : x > y ? -1 : 0;
}

/* Relative RMSE over the image's luminance and the mean relative error of
 * its worst 1% of pixels. */
static void compare(const host *h, const float *img, const float *ref, run *out)
{
    const int n = h->w * h->h;
    double se = 0.0, sr = 0.0, *rel = malloc(sizeof(double) * (size_t)n), w = 0.0;
    int i, worst = n / 100 > 0 ? n / 100 : 1;
    for (i = 0; i < n; i++) {
        double a = (img[3 * i] + img[3 * i + 1] + img[3 * i + 2]) / 3.0,
               b = (ref[3 * i] + ref[3 * i + 1] + ref[3 * i + 2]) / 3.0;
        se += (a - b) * (a - b);
        sr += b * b;
        if (rel)
            rel[i] = fabs(a - b) / (b > 1e-3 ? b : 1e-3);
    }
    out->rel_rmse = sqrt(se / sr);
    if (rel) {
        qsort(rel, (size_t)n, sizeof(double), cmp_double);
        for (i = 0; i < worst; i++)
            w += rel[i];
        out->worst1 = w / worst;
        free(rel);
    }
}

/* A binary PPM: the image clamped to [0, 1] and gamma 2.2, or with ref,
 * the error |img - ref| / (0.25 ref) in red above and blue below. */
static void write_ppm(const host *h, const char *mode, const char *tail, const float *img,
                      const float *ref)
{
    char path[512];
    FILE *f;
    int i, k;
    snprintf(path, sizeof path, "%s/%s%s.ppm", getenv("HOST_IMAGES"), mode, tail);
    if (!(f = fopen(path, "wb")))
        return;
    fprintf(f, "P6\n%d %d\n255\n", h->w, h->h);
    for (i = 0; i < h->w * h->h; i++) {
        unsigned char px[3];
        for (k = 0; k < 3; k++) {
            double v = img[3 * i + k];
            if (ref) {
                double a = (img[3 * i] + img[3 * i + 1] + img[3 * i + 2]) / 3.0,
                       b = (ref[3 * i] + ref[3 * i + 1] + ref[3 * i + 2]) / 3.0;
                v = (k == 1) ? 0.0 : ((k == 0) == (a > b)) ? fabs(a - b) / (0.25 * b + 1e-6) : 0.0;
            } else {
                v = pow(v > 0.0 ? v : 0.0, 1.0 / 2.2);
            }
            px[k] = (unsigned char)(v >= 1.0 ? 255 : 255.0 * v + 0.5);
        }
        fwrite(px, 1, 3, f);
    }
    fclose(f);
}

/* Replays the kept lookups on the final cache. */
static void replay(host *h, irc_cache *c, run *out)
{
    double t0, sum = 0.0;
    size_t i;
    float rgb[3];
    if (!h->nq)
        return;
    t0 = bench_now();
    for (i = 0; i < h->nq; i++) {
        const float *q = h->q + 6 * i;
        if (irc_cache_lookup(c, q, q + 3, rgb, NULL) == IRC_OK)
            sum += rgb[0];
    }
    out->replay_rate = (double)h->nq / (bench_now() - t0);
    if (sum < 0.0) /* keeps the loop's work live */
        out->failed = 1;
}

int main(int argc, char **argv)
{
    host h = {0};
    int spp = 256, ref_spp = 2048, mode, failed = 0;
    float *img, *ref;
    run r0;
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
        return fprintf(stderr, "usage: bench_host [width height samples reference_samples]\n"), 2;
    img = malloc(sizeof(float) * 3 * (size_t)h.w * (size_t)h.h);
    ref = malloc(sizeof(float) * 3 * (size_t)h.w * (size_t)h.h);
    h.cap = (size_t)h.w * (size_t)h.h * (size_t)spp;
    h.q = malloc(sizeof(float) * 6 * h.cap);
    h.detail = malloc(sizeof(float) * 3 * (size_t)h.w * (size_t)h.h);
    h.has_detail = malloc((size_t)h.w * (size_t)h.h);
    if (!img || !ref || !h.q || !h.detail || !h.has_detail)
        return fprintf(stderr, "out of memory\n"), 1;
    h.rng = 0x2545f4914f6cdd1dull;
    memset(&r0, 0, sizeof r0);
    if (render(&h, NULL, PATH, ref_spp, ref, &r0) < 0)
        return 1;
    printf("%s %dx%d, %d samples a pixel; reference: path tracing at %d (%.1f s)\n",
           irc_version_string(), h.w, h.h, spp, ref_spp, r0.seconds);
    printf("%-7s %8s %9s %8s %8s %9s %10s %10s %8s %12s\n", "mode", "seconds", "rel_rmse",
           "worst1%", "records", "library", "lookups", "misses", "details", "replayed/s");
    for (mode = PATH; mode < MODES; mode++) {
        irc_config cfg = IRC_CONFIG_INIT; /* the library's defaults */
        irc_cache *c = NULL;
        irc_stats st = {0};
        run r;
        size_t bytes;
        const uint32_t max = (uint32_t)(h.w * h.h);
        memset(&r, 0, sizeof r);
        h.nq = 0;
        h.t_trace = 0.0;
        h.rng = 0x9e3779b97f4a7c15ull;
        cfg.trace = trace;
        cfg.context = &h;
        /* HOST_A: the knob (irrcache.h: the strata follow it) */
        cfg.accuracy = getenv("HOST_A") ? (float)atof(getenv("HOST_A")) : 0.0f;
        cfg.irr.blend = getenv("HOST_BLEND") ? (float)atof(getenv("HOST_BLEND")) : 0.0f;
        if (mode != PATH) {
            if (irc_footprint(&cfg, max, &bytes) < 0 || !(cfg.buffer = malloc(bytes)))
                return 1;
            cfg.buffer_size = bytes;
            if (irc_init(&cfg, max, &c) < 0)
                return 1;
        }
        if (render(&h, c, mode, spp, img, &r) < 0) {
            printf("%-7s failed\n", mode_name[mode]);
            failed = 1;
        } else {
            compare(&h, img, ref, &r);
            if (getenv("HOST_IMAGES")) {
                write_ppm(&h, mode_name[mode], "", img, NULL);
                write_ppm(&h, mode_name[mode], "-err", img, ref);
                if (mode == PATH)
                    write_ppm(&h, "reference", "", ref, NULL);
            }
            if (c) {
                replay(&h, c, &r);
                irc_cache_stats(c, &st);
            }
            printf("%-7s %8.2f %9.4f %8.4f %8llu %8.1f%% %10llu %10llu %8llu %12.0f\n",
                   mode_name[mode], r.seconds, r.rel_rmse, r.worst1,
                   (unsigned long long)st.records, 100.0 * r.library / r.seconds, r.lookups,
                   r.misses, r.details, r.replay_rate);
        }
        if (c)
            irc_fini(c);
        free(cfg.buffer);
        failed |= r.failed;
    }
    free(img);
    free(ref);
    free(h.q);
    free(h.detail);
    free(h.has_detail);
    return failed;
}
