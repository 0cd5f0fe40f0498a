/*
 * shexp.c -- the SH-gradient paper's experiments on the sh scene (README:
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

#include "bvh.h"
#include "irrcache.h"
#include "scene.h"
#include "render.h"
#include "shade.h"

#define PI 3.14159265358979323846
#define BANDS 5
#define NC (BANDS * BANDS)

typedef struct env {
    const scene *s;
    bvh b;
    lights l;
    uint64_t seed;
} env;

/* Radiance reaching the ray's origin: emission (the lights) plus the
 * direct light on what it hits (4 light samples). */
static int env_trace(const irc_trace_args *a)
{
    const env *e = (const env *)a->context;
    uint32_t i;
    for (i = 0; i < a->count; i++) {
        const float *o = a->rays[i].org, *d = a->rays[i].dir;
        irc_hit *h = &a->hits[i];
        bvh_hit bh;
        if (!bvh_intersect(&e->b, o, d, 0.0f, FLT_MAX, &bh)) {
            h->status = IRC_RAY_ESCAPED;
            env_radiance(&e->s->env, d, h->radiance);
        } else {
            surface sf;
            float em[3];
            uint64_t rays = 0, key = e->seed;
            uint32_t bits[6];
            int k;
            memcpy(bits, o, 12);
            memcpy(bits + 3, d, 12);
            for (k = 0; k < 6; k++)
                key = hash64(key ^ bits[k]);
            surface_at(e->s, o, d, &bh, &sf);
            h->status = IRC_RAY_HIT;
            h->dist = bh.t;
            memcpy(h->normal, sf.ng, sizeof h->normal);
            direct_light(&e->b, &e->l, &sf, d, 4, key, h->radiance, &rays);
            emitted(&sf, em);
            for (k = 0; k < 3; k++)
                h->radiance[k] += em[k];
        }
    }
    return 0;
}

/* The scene without its spheres (the object), plus an optional blocker
 * sphere of a black material added to the copy. */
static int env_init(env *e, const scene *src, scene *copy, const sphere *blocker)
{
    *copy = *src;
    copy->spheres = NULL;
    copy->nspheres = 0;
    copy->mats = malloc(sizeof(material) * (size_t)(src->nmats + 1));
    memcpy(copy->mats, src->mats, sizeof(material) * (size_t)src->nmats);
    memset(&copy->mats[src->nmats], 0, sizeof(material));
    copy->nmats = src->nmats + 1;
    if (blocker) {
        copy->spheres = malloc(sizeof *blocker);
        *copy->spheres = *blocker;
        copy->spheres->mat = src->nmats;
        copy->nspheres = 1;
    }
    memset(e, 0, sizeof *e);
    e->s = copy;
    return bvh_build(&e->b, copy) < 0 || lights_build(&e->l, copy) < 0 ? -1 : 0;
}

static void env_free(env *e, scene *copy)
{
    bvh_free(&e->b);
    lights_free(&e->l);
    free(copy->spheres);
    free(copy->mats);
}

/* A cache on env e; free points reach everywhere (radius 10, a = 10). */
static irc_cache *make_cache(env *e, uint32_t features, uint32_t m, uint32_t n, void **block)
{
    irc_config cfg;
    irc_cache *c;
    size_t bytes;
    memset(&cfg, 0, sizeof cfg);
    cfg.trace = env_trace;
    cfg.context = e;
    cfg.max_batch = 64;
    cfg.features = features;
    cfg.strata_theta = m;
    cfg.strata_phi = n;
    cfg.sh_bands = BANDS;
    cfg.accuracy = 10.0f;
    cfg.min_radius = 10.0f;
    cfg.max_radius = 11.0f;
    cfg.seed = e->seed;
    if (irc_footprint(&cfg, 64, &bytes) < 0 || !(*block = malloc(bytes)))
        return NULL;
    cfg.buffer = *block;
    cfg.buffer_size = bytes;
    return irc_init(&cfg, 64, &c) == IRC_OK ? c : NULL;
}

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
            env e;
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
            if (env_init(&e, s, &copy, v ? &bl : NULL) < 0 ||
                !(c = make_cache(&e, IRC_FEATURE_SH_GRADIENT, m, n, &block)))
                return -1;
            e.seed = 11;
            if (!(c2 = make_cache(&e, IRC_FEATURE_SH, m, n, &block2)))
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
            env_free(&e, &copy);
        }
        for (t = 0; t <= 10; t++)
            printf("  %.1f   %16.4f %9.4f %7.4f %16.4f %9.4f %7.4f\n", 0.1 * t, err[0][0][t],
                   err[0][1][t], err[0][2][t], err[1][0][t], err[1][1][t], err[1][2][t]);
    }
    return 0;
}

/* The object's shading at its surface point p (normal n, view ray d) from
 * the coefficients: kd/pi E(n) + ks (Ns+2)/(2 pi) G(r, Ns), unshadowed. */
static void shade_sh(const irc_sh *c, const material *m, const float n[3], const float d[3],
                     float out[3])
{
    float e[3], g[3], r[3], dn = d[0] * n[0] + d[1] * n[1] + d[2] * n[2];
    int k;
    for (k = 0; k < 3; k++)
        r[k] = d[k] - 2.0f * dn * n[k];
    irc_sh_irradiance(c, n, e);
    irc_sh_glossy(c, r, m->ns, g);
    for (k = 0; k < 3; k++)
        out[k] = m->kd[k] / (float)PI * e[k] +
                 m->ks[k] * (m->ns + 2.0f) / (2.0f * (float)PI) * g[k];
}

/* The object's pixels: point, normal and view direction of each, from the
 * scene's camera at w x w. */
static int object_pixels(const scene *s, int w, float *pts)
{
    const camera *cam = &s->cam;
    const sphere *o = &s->spheres[0];
    float f[3], u[3], rt[3], len = 0.0f, tn = tanf(0.5f * cam->fov_deg * (float)PI / 180.0f);
    int x, y, k, cnt = 0;
    for (k = 0; k < 3; k++) {
        f[k] = cam->look[k] - cam->eye[k];
        len += f[k] * f[k];
    }
    for (k = 0; k < 3; k++)
        f[k] /= sqrtf(len);
    rt[0] = f[1] * cam->up[2] - f[2] * cam->up[1];
    rt[1] = f[2] * cam->up[0] - f[0] * cam->up[2];
    rt[2] = f[0] * cam->up[1] - f[1] * cam->up[0];
    len = sqrtf(rt[0] * rt[0] + rt[1] * rt[1] + rt[2] * rt[2]);
    for (k = 0; k < 3; k++)
        rt[k] /= len;
    u[0] = rt[1] * f[2] - rt[2] * f[1];
    u[1] = rt[2] * f[0] - rt[0] * f[2];
    u[2] = rt[0] * f[1] - rt[1] * f[0];
    for (y = 0; y < w; y++)
        for (x = 0; x < w; x++) {
            float d[3], oc[3], b = 0.0f, cc = 0.0f, disc, t;
            float sx = (2.0f * (x + 0.5f) / w - 1.0f) * tn, sy = (1.0f - 2.0f * (y + 0.5f) / w) * tn;
            len = 0.0f;
            for (k = 0; k < 3; k++) {
                d[k] = f[k] + sx * rt[k] + sy * u[k];
                len += d[k] * d[k];
            }
            for (k = 0; k < 3; k++) {
                d[k] /= sqrtf(len);
                oc[k] = cam->eye[k] - o->c[k];
                b += oc[k] * d[k];
                cc += oc[k] * oc[k];
            }
            disc = b * b - (cc - o->r * o->r);
            if (disc <= 0.0f)
                continue;
            t = -b - sqrtf(disc);
            for (k = 0; k < 3; k++) {
                float p = cam->eye[k] + t * d[k];
                pts[9 * cnt + 3 + k] = (p - o->c[k]) / o->r;
                pts[9 * cnt + k] = o->c[k] + o->r * pts[9 * cnt + 3 + k];
                pts[9 * cnt + 6 + k] = d[k];
            }
            cnt++;
        }
    return cnt;
}

static double rel_rmse(const float *a, const float *b, int n)
{
    double num = 0.0, den = 0.0;
    int i;
    for (i = 0; i < 3 * n; i++) {
        num += (a[i] - b[i]) * (double)(a[i] - b[i]);
        den += b[i] * (double)b[i];
    }
    return sqrt(num / den);
}

/* Ground truth: a record at every pixel's point (seeded twice). */
static int truth(env *e, const material *m, const float *pts, int np, uint32_t mm,
                 uint32_t nn, float *out)
{
    void *block = NULL;
    irc_cache *c = make_cache(e, IRC_FEATURE_SH, mm, nn, &block);
    int i;
    if (!c)
        return -1;
    for (i = 0; i < np; i++) {
        irc_sh r;
        if (irc_sh_compute(c, pts + 9 * i, NULL, &r, NULL) < 0)
            return -1;
        shade_sh(&r, m, pts + 9 * i + 3, pts + 9 * i + 6, out + 3 * i);
    }
    irc_fini(c);
    free(block);
    return 0;
}

/* One method: records at `count` points, looked up at every pixel. */
static int method(env *e, const material *m, const float *pts, int np, const float (*at)[3],
                  int count, uint32_t features, uint32_t mm, uint32_t nn, float *out)
{
    void *block = NULL;
    irc_cache *c = make_cache(e, features, mm, nn, &block);
    int i;
    if (!c)
        return -1;
    for (i = 0; i < count; i++) {
        irc_sh r;
        if (irc_sh_compute(c, at[i], NULL, &r, NULL) < 0 || irc_sh_insert(c, &r) < 0)
            return -1;
    }
    for (i = 0; i < np; i++) {
        irc_sh r;
        if (irc_sh_lookup(c, pts + 9 * i, NULL, &r, NULL) != IRC_OK)
            return -1;
        shade_sh(&r, m, pts + 9 * i + 3, pts + 9 * i + 6, out + 3 * i);
    }
    irc_fini(c);
    free(block);
    return 0;
}

static int shading(const scene *s, int w, uint32_t mm, uint32_t nn)
{
    static const float centre[1][3] = {{0, 0, 0}};
    float corners[8][3], *pts = malloc(sizeof(float) * 9 * (size_t)w * w);
    float *ref = malloc(sizeof(float) * 3 * (size_t)w * w), *ref2, *img;
    const material *m = &s->mats[s->spheres[0].mat];
    scene copy;
    env e;
    int np, i, k;
    static const char *names[4] = {"1 sample, no gradient", "1 sample + gradient",
                                   "8 samples, no gradients", "8 samples + gradients"};
    for (i = 0; i < 8; i++)
        for (k = 0; k < 3; k++)
            corners[i][k] = s->spheres[0].c[k] + 0.5f * s->spheres[0].r * (i >> k & 1 ? 1 : -1);
    np = object_pixels(s, w, pts);
    ref2 = malloc(sizeof(float) * 3 * (size_t)np);
    img = malloc(sizeof(float) * 3 * (size_t)np);
    if (env_init(&e, s, &copy, NULL) < 0)
        return -1;
    printf("\nShading the object from SH, L = %d, %ux%u strata x 2 per record, "
           "%d object pixels (%dx%d view):\n", BANDS, mm, nn, np, w, w);
    e.seed = 1;
    if (truth(&e, m, pts, np, mm, nn, ref) < 0)
        return -1;
    e.seed = 2;
    if (truth(&e, m, pts, np, mm, nn, ref2) < 0)
        return -1;
    printf("  ground truth (a record per pixel) vs the same with another seed: "
           "relative RMSE %.4f\n", rel_rmse(ref2, ref, np));
    e.seed = 3;
    for (i = 0; i < 4; i++) {
        int st = method(&e, m, pts, np, i < 2 ? centre : (const float(*)[3])corners,
                        i < 2 ? 1 : 8, i % 2 ? IRC_FEATURE_SH_GRADIENT : IRC_FEATURE_SH, mm, nn, img);
        if (st < 0)
            return -1;
        printf("  %-26s relative RMSE %.4f\n", names[i], rel_rmse(img, ref, np));
    }
    env_free(&e, &copy);
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
    env e;
    int i, j, h;
    if (env_init(&e, s, &copy, NULL) < 0)
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
                    cfg.trace = h ? env_trace : sky_trace;
                    cfg.context = &e;
                    cfg.max_batch = 64;
                    cfg.features = g ? IRC_FEATURE_SH_GRADIENT : IRC_FEATURE_SH;
                    cfg.strata_theta = strata[i][0];
                    cfg.strata_phi = strata[i][1];
                    cfg.sh_bands = bands[j];
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
    env_free(&e, &copy);
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
