/*
 * shexp.c -- the SH-gradient paper's experiments on the sh scene (experiments/README.md:
 * "SH records").  The object (the scene's sphere) is the receiver: the
 * incident radiance comes from the rest of the scene (three small coloured
 * emitters and the ground they light), sampled at free points.
 *
 *   1. Fig. 8: the relative RMS error of the extrapolated incident radiance
 *      (red channel, over the sphere of directions, by Parseval from the
 *      coefficients) against a record computed at the point itself, as the
 *      point moves away from the sample, without and with the gradient
 *      (Eq. 14), with and without a blocker that changes what is visible.
 *   2. Shading: the object shaded from SH (diffuse by the clamped-cosine
 *      convolution, glossy by the Phong lobe) with one record at its centre
 *      (without / with gradient), eight records (without / with gradients,
 *      Eq. 15-16), against a record at every pixel's point; relative RMSE
 *      over the object's pixels, and the ground truth's own noise (two
 *      seeds).
 *   3. The cost of a record without and with the gradient (library time,
 *      a host of zero cost, and with this scene's host).
 *
 *   shexp [SCENE [W [M N]]]    (defaults: demo/scenes/sh.scene 48 64 256)
 */
#define _POSIX_C_SOURCE 200809L
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "render.h"
#include "shobj.h"

#define PI 3.14159265358979323846
#define BANDS SHOBJ_BANDS
#define NC SHOBJ_NC

/* |a - b| / |b| over the red channel's coefficients: by Parseval the RMS of
 * the radiance difference over the sphere relative to the radiance's RMS. */
static double rel_rms(const irc_sh *a, const irc_sh *b)
{
    double num = 0.0, den = 0.0;
    int i;
    for (i = 0; i < NC; i++) {
        num += (a->c[0][i] - b->c[0][i]) * (double)(a->c[0][i] - b->c[0][i]);
        den += b->c[0][i] * (double)b->c[0][i];
    }
    return sqrt(num / den);
}

static void extrapolate(const irc_sh *r, const float p[3], int grad, irc_sh *out)
{
    int ch, i, k;
    *out = *r;
    for (ch = 0; ch < 3; ch++)
        for (i = 0; i < NC; i++)
            for (k = 0; k < 3 && grad; k++)
                out->c[ch][i] += r->grad[ch][i][k] * (p[k] - r->p[k]);
}

/* Fig. 8: along a path perpendicular to the red light's direction. */
static int fig8(const scene *s, uint32_t m, uint32_t n)
{
    const float red[3] = {-0.7071f, 0.4243f, -0.5657f}; /* sh.obj's red direction */
    const float path[3] = {0.6247f, 0.0f, -0.7809f};    /* perpendicular to it */
    int v, t;
    printf("Fig. 8: relative RMS error of the extrapolated incident radiance (red),\n"
           "point moved a distance t from the sample, %ux%u strata x 2, L = %d\n",
           m, n, BANDS);
    printf("   t    no blocker: none  gradient   noise    blocker: none  gradient   noise\n");
    {
        double err[2][3][11];
        for (v = 0; v < 2; v++) {
            sphere bl;
            scene copy;
            sh_env e;
            void *block = NULL, *block2 = NULL;
            irc_cache *c, *c2;
            irc_sh r0;
            float o[3] = {0, 0, 0};
            int k;
            /* A black ball of radius 0.08 on the way to the red light (1.2
             * of its 2.0), beside the light's image from the path's start:
             * moving along the path slides it over the light. */
            for (k = 0; k < 3; k++)
                bl.c[k] = 1.2f * red[k] - 0.1f * path[k];
            bl.r = 0.08f;
            bl.mat = 0;
            if (sh_env_init(&e, s, &copy, v ? &bl : NULL) < 0 ||
                !(c = sh_env_cache(&e, IRC_FEATURE_SH_GRADIENT, m, n, &block)))
                return -1;
            e.seed = 11;
            if (!(c2 = sh_env_cache(&e, IRC_FEATURE_SH, m, n, &block2)))
                return -1;
            e.seed = 0;
            if (irc_sh_compute(c, o, NULL, &r0, NULL) < 0)
                return -1;
            for (t = 0; t <= 10; t++) {
                float p[3];
                irc_sh truth, ex, other;
                for (k = 0; k < 3; k++)
                    p[k] = 0.1f * (float)t * path[k] + 0.0f;
                /* The truth's own noise: the same point, another seed. */
                e.seed = 11;
                if (irc_sh_compute(c2, p, NULL, &other, NULL) < 0)
                    return -1;
                e.seed = 0;
                if (irc_sh_compute(c, p, NULL, &truth, NULL) < 0)
                    return -1;
                err[v][2][t] = rel_rms(&other, &truth);
                extrapolate(&r0, p, 0, &ex);
                err[v][0][t] = rel_rms(&ex, &truth);
                extrapolate(&r0, p, 1, &ex);
                err[v][1][t] = rel_rms(&ex, &truth);
            }
            irc_fini(c);
            irc_fini(c2);
            free(block);
            free(block2);
            sh_env_free(&e, &copy);
        }
        for (t = 0; t <= 10; t++)
            printf("  %.1f   %16.4f %9.4f %7.4f %16.4f %9.4f %7.4f\n", 0.1 * t, err[0][0][t],
                   err[0][1][t], err[0][2][t], err[1][0][t], err[1][1][t], err[1][2][t]);
    }
    return 0;
}

static int shading(const scene *s, int w, uint32_t mm, uint32_t nn)
{
    static const float centre[1][3] = {{0, 0, 0}};
    float corners[8][3], *pts = malloc(sizeof(float) * 9 * (size_t)w * w);
    float *ref = malloc(sizeof(float) * 3 * (size_t)w * w), *ref2, *img;
    const material *m = &s->mats[s->spheres[0].mat];
    scene copy;
    sh_env e;
    int np, i, k;
    static const char *names[4] = {"1 sample, no gradient", "1 sample + gradient",
                                   "8 samples, no gradients", "8 samples + gradients"};
    for (i = 0; i < 8; i++)
        for (k = 0; k < 3; k++)
            corners[i][k] = s->spheres[0].c[k] + 0.5f * s->spheres[0].r * (i >> k & 1 ? 1 : -1);
    np = sh_object_pixels(&s->cam, &s->spheres[0], w, pts, NULL);
    ref2 = malloc(sizeof(float) * 3 * (size_t)np);
    img = malloc(sizeof(float) * 3 * (size_t)np);
    if (sh_env_init(&e, s, &copy, NULL) < 0)
        return -1;
    printf("\nShading the object from SH, L = %d, %ux%u strata x 2 per record, "
           "%d object pixels (%dx%d view):\n", BANDS, mm, nn, np, w, w);
    e.seed = 1;
    if (sh_truth(&e, m, pts, np, mm, nn, ref) < 0)
        return -1;
    e.seed = 2;
    if (sh_truth(&e, m, pts, np, mm, nn, ref2) < 0)
        return -1;
    printf("  ground truth (a record per pixel) vs the same with another seed: "
           "relative RMSE %.4f\n", sh_rel_rmse(ref2, ref, np));
    e.seed = 3;
    for (i = 0; i < 4; i++) {
        int st = sh_method(&e, m, pts, np, i < 2 ? centre : (const float(*)[3])corners,
                        i < 2 ? 1 : 8, i % 2 ? IRC_FEATURE_SH_GRADIENT : IRC_FEATURE_SH, mm, nn, img);
        if (st < 0)
            return -1;
        printf("  %-26s relative RMSE %.4f\n", names[i], sh_rel_rmse(img, ref, np));
    }
    sh_env_free(&e, &copy);
    free(pts);
    free(ref);
    free(ref2);
    free(img);
    return 0;
}

static int sky_trace(const irc_trace_args *a)
{
    uint32_t i;
    for (i = 0; i < a->count; i++) {
        a->hits[i].status = IRC_RAY_ESCAPED;
        a->hits[i].radiance[0] = a->hits[i].radiance[1] = a->hits[i].radiance[2] =
            1.0f + a->rays[i].dir[2];
    }
    return 0;
}

/* Microseconds per record, best of 3 runs of `reps`. */
static double per_record(irc_cache *c, int reps)
{
    double best = 1e30;
    int run, i;
    for (run = 0; run < 3; run++) {
        double t0 = render_clock();
        for (i = 0; i < reps; i++) {
            float p[3] = {0.001f * i, 0, 0};
            irc_sh r;
            if (irc_sh_compute(c, p, NULL, &r, NULL) < 0)
                return -1.0;
        }
        if (render_clock() - t0 < best)
            best = render_clock() - t0;
    }
    return 1e6 * best / reps;
}

static int cost(const scene *s)
{
    static const uint32_t strata[2][2] = {{16, 64}, {32, 128}};
    static const uint32_t bands[2] = {3, 5};
    scene copy;
    sh_env e;
    int i, j, h;
    if (sh_env_init(&e, s, &copy, NULL) < 0)
        return -1;
    printf("\nCost of a free-point record (microseconds; two hemispheres of MxN):\n"
           "  host        L  strata     coefficients  + gradient   ratio\n");
    for (h = 0; h < 2; h++)
        for (j = 0; j < 2; j++)
            for (i = 0; i < 2; i++) {
                double t[2];
                int g;
                for (g = 0; g < 2; g++) {
                    irc_config cfg;
                    irc_cache *c;
                    size_t bytes;
                    void *block;
                    memset(&cfg, 0, sizeof cfg);
                    cfg.version = IRC_CONFIG_VERSION;
                    cfg.trace = h ? sh_env_trace : sky_trace;
                    cfg.context = &e;
                    cfg.max_batch = 64;
                    cfg.features = g ? IRC_FEATURE_SH_GRADIENT : IRC_FEATURE_SH;
                    cfg.strata_theta = strata[i][0];
                    cfg.strata_phi = strata[i][1];
                    cfg.sh.bands = bands[j];
                    irc_footprint(&cfg, 4, &bytes);
                    block = malloc(bytes);
                    cfg.buffer = block;
                    cfg.buffer_size = bytes;
                    if (irc_init(&cfg, 4, &c) < 0)
                        return -1;
                    t[g] = per_record(c, h ? 20 : 200);
                    irc_fini(c);
                    free(block);
                }
                printf("  %-10s  %u  %3ux%-4u  %12.1f  %10.1f  %6.2f\n",
                       h ? "sh scene" : "zero-cost", bands[j], strata[i][0], strata[i][1],
                       t[0], t[1], t[1] / t[0]);
            }
    sh_env_free(&e, &copy);
    return 0;
}

int main(int argc, char **argv)
{
    const char *path = argc > 1 ? argv[1] : "demo/scenes/sh.scene";
    int w = argc > 2 ? atoi(argv[2]) : 48;
    uint32_t mm = argc > 4 ? (uint32_t)atoi(argv[3]) : 64, nn = argc > 4 ? (uint32_t)atoi(argv[4]) : 256;
    scene s;
    char err[512];
    if (scene_load(path, &s, err, sizeof err) < 0) {
        fprintf(stderr, "%s\n", err);
        return 1;
    }
    if (s.nspheres < 1 || w < 8) {
        fprintf(stderr, "shexp: the scene's first sphere is the object; W >= 8\n");
        return 1;
    }
    if (fig8(&s, mm, nn) < 0 || shading(&s, w, mm, nn) < 0 || cost(&s) < 0) {
        fprintf(stderr, "shexp: failed\n");
        return 1;
    }
    scene_free(&s);
    return 0;
}
