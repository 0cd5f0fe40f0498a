/*
 * host_scene.h -- the scene and tracer of the path-tracing hosts
 * (bench/host.c, bench/progressive.c): a box [-1, 1]^3 open toward the
 * camera (z = +1), white floor, ceiling and back wall, red left and green
 * right wall, two white balls, a square light just under the ceiling; the
 * cache's trace callback (each hit sends back its direct light), the
 * camera, and one path's estimate of E.  Static: one program includes it.
 */
#ifndef BENCH_HOST_SCENE_H
#define BENCH_HOST_SCENE_H

#include <math.h>
#include <string.h>

#include "bench_util.h"

#define PI 3.14159265358979f
#define EPS 1e-4f
#define PASS_BITS 3 /* fill passes 8 pixels apart: 64 of them */

enum { WHITE, RED, GREEN, LIGHT, MATERIALS };
static const float albedo[MATERIALS][3] = {
    {0.75f, 0.75f, 0.75f}, {0.75f, 0.2f, 0.2f}, {0.2f, 0.75f, 0.2f}, {0, 0, 0}};
static const float light_y = 0.998f, light_half = 0.3f, light_le = 10.0f;
static const float ball_c[2][3] = {{-0.45f, -0.6f, -0.35f}, {0.5f, -0.7f, 0.25f}};
static const float ball_r[2] = {0.4f, 0.3f};
static const float eye[3] = {0.0f, 0.0f, 3.6f}, fov = 0.7f; /* radians, vertical */

typedef struct hit {
    float t, n[3];
    int mat;
} hit;

typedef struct host {
    int w, h;
    unsigned long long rng;
    double t_trace;      /* seconds inside the trace callback */
    float *q;            /* the samples' lookup queries, 6 floats each */
    size_t nq, cap;
    /* A pixel's per-pixel estimate (IRC_DETAIL), kept for its later
     * samples: computed once a pixel, not once a sample. */
    float *detail;       /* 3 a pixel */
    unsigned char *has_detail;
    int pixel;           /* the pixel being sampled; -1: the fill passes */
} host;

static float dot(const float a[3], const float b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
static float rnd(host *h) { return (float)bench_xorshift(&h->rng); }

/* The nearest hit of o + t d, t in (0, tmax); 0 if none. */
static int intersect(const float o[3], const float d[3], float tmax, hit *r)
{
    /* walls: axis, coordinate, inward normal sign, material */
    static const struct { int a; float c, s; int mat; } wall[5] = {
        {1, -1.0f, 1.0f, WHITE}, {1, 1.0f, -1.0f, WHITE}, {2, -1.0f, 1.0f, WHITE},
        {0, -1.0f, 1.0f, RED}, {0, 1.0f, -1.0f, GREEN}};
    int i, k, found = 0;
    r->t = tmax;
    for (i = 0; i < 5; i++) {
        int a = wall[i].a;
        float t;
        if (d[a] == 0.0f)
            continue;
        t = (wall[i].c - o[a]) / d[a];
        if (t > 0.0f && t < r->t) {
            int in = 1;
            for (k = 0; k < 3; k++)
                if (k != a && fabsf(o[k] + t * d[k]) > 1.0f)
                    in = 0;
            if (in) {
                r->t = t;
                r->n[0] = r->n[1] = r->n[2] = 0.0f;
                r->n[a] = wall[i].s;
                r->mat = wall[i].mat;
                found = 1;
            }
        }
    }
    if (d[1] > 0.0f) { /* the light faces down */
        float t = (light_y - o[1]) / d[1];
        if (t > 0.0f && t < r->t && fabsf(o[0] + t * d[0]) <= light_half &&
            fabsf(o[2] + t * d[2]) <= light_half) {
            r->t = t;
            r->n[0] = r->n[2] = 0.0f;
            r->n[1] = -1.0f;
            r->mat = LIGHT;
            found = 1;
        }
    }
    for (i = 0; i < 2; i++) {
        float oc[3], b, c, disc, t;
        for (k = 0; k < 3; k++)
            oc[k] = o[k] - ball_c[i][k];
        b = dot(oc, d);
        c = dot(oc, oc) - ball_r[i] * ball_r[i];
        disc = b * b - c;
        if (disc <= 0.0f)
            continue;
        t = -b - sqrtf(disc);
        if (t > 0.0f && t < r->t) {
            r->t = t;
            for (k = 0; k < 3; k++)
                r->n[k] = (oc[k] + t * d[k]) / ball_r[i];
            r->mat = WHITE;
            found = 1;
        }
    }
    return found;
}

/* Radiance leaving x (normal n, material m) by direct light: one sample of
 * the light's area, L = rho/pi Le cos cos' A / d^2 when unoccluded. */
static void direct(host *h, const float x[3], const float n[3], int m, float out[3])
{
    float y[3] = {(2.0f * rnd(h) - 1.0f) * light_half, light_y, (2.0f * rnd(h) - 1.0f) * light_half};
    float o[3], d[3], d2, dist, cx, cl, g;
    hit r;
    int k;
    out[0] = out[1] = out[2] = 0.0f;
    for (k = 0; k < 3; k++) {
        o[k] = x[k] + EPS * n[k];
        d[k] = y[k] - o[k];
    }
    d2 = dot(d, d);
    dist = sqrtf(d2);
    for (k = 0; k < 3; k++)
        d[k] /= dist;
    cx = dot(d, n);
    cl = d[1];
    if (cx <= 0.0f || cl <= 0.0f)
        return;
    if (intersect(o, d, dist * (1.0f - 1e-4f), &r) && r.mat != LIGHT)
        return;
    g = light_le * cx * cl * (4.0f * light_half * light_half) / d2 / PI;
    for (k = 0; k < 3; k++)
        out[k] = albedo[m][k] * g;
}

/* The cache's rays: what each hit sends back is its direct light only
 * (the light itself sends nothing: direct light at the record's point is
 * the shading's own sample). */
static int trace(const irc_trace_args *a)
{
    host *h = (host *)a->context;
    double t0 = bench_now();
    uint32_t i;
    for (i = 0; i < a->count; i++) {
        float o[3];
        irc_hit *e = &a->hits[i];
        hit r;
        int k;
        for (k = 0; k < 3; k++)
            o[k] = a->rays[i].org[k] + EPS * a->n[k];
        if (!intersect(o, a->rays[i].dir, 1e30f, &r)) {
            e->status = IRC_RAY_ESCAPED;
            e->radiance[0] = e->radiance[1] = e->radiance[2] = 0.0f;
            continue;
        }
        e->status = IRC_RAY_HIT;
        e->dist = r.t;
        if (a->visibility_only)
            continue;
        for (k = 0; k < 3; k++)
            e->normal[k] = r.n[k];
        if (r.mat == LIGHT) {
            e->radiance[0] = e->radiance[1] = e->radiance[2] = 0.0f;
        } else {
            float y[3] = {o[0] + r.t * a->rays[i].dir[0], o[1] + r.t * a->rays[i].dir[1],
                          o[2] + r.t * a->rays[i].dir[2]};
            direct(h, y, r.n, r.mat, e->radiance);
        }
    }
    h->t_trace += bench_now() - t0;
    return 0;
}

/* The camera ray through image point (x, y) in pixels. */
static void camera(const host *h, float x, float y, float d[3])
{
    const float th = tanf(0.5f * fov);
    float l;
    d[0] = (2.0f * x / (float)h->w - 1.0f) * th * (float)h->w / (float)h->h;
    d[1] = (1.0f - 2.0f * y / (float)h->h) * th;
    d[2] = -1.0f;
    l = sqrtf(dot(d, d));
    d[0] /= l;
    d[1] /= l;
    d[2] /= l;
}

/* E at x by one path: a cosine-distributed direction, direct light where
 * it lands; E = pi L for that density. */
static void path_irradiance(host *h, const float x[3], const float n[3], float e[3])
{
    float d[3], o[3], u = rnd(h), v = rnd(h);
    hit r;
    int k;
    bench_cosine_dir(n, u, v, d);
    for (k = 0; k < 3; k++)
        o[k] = x[k] + EPS * n[k];
    e[0] = e[1] = e[2] = 0.0f;
    if (intersect(o, d, 1e30f, &r) && r.mat != LIGHT) {
        float y[3] = {o[0] + r.t * d[0], o[1] + r.t * d[1], o[2] + r.t * d[2]};
        direct(h, y, r.n, r.mat, e);
        for (k = 0; k < 3; k++)
            e[k] *= PI;
    }
}

#endif
