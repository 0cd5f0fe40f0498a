/* scenes.c -- analytic reference hosts (see scenes.h). */
#include "scenes.h"

#include <stdio.h>

#include "block/cache.h" /* the lock's place in the block, on purpose */

#include <math.h>
#include <stdlib.h>
#include <string.h>

void scene_init(tscene *s)
{
    memset(s, 0, sizeof *s);
}

void scene_sphere_plane(tscene *s)
{
    scene_init(s);
    s->sky_a[0] = s->sky_a[1] = s->sky_a[2] = 1.0f;
    s->has_sphere = 1;
    s->centre[2] = 2.0;
    s->radius = 1.0;
}

void scene_disk_plane(tscene *s)
{
    scene_init(s);
    s->sky_a[0] = s->sky_a[1] = s->sky_a[2] = 1.0f;
    s->has_disk = 1;
    s->disk_c[2] = 1.0;
    s->disk_r = 0.8;
}

void scene_box_plane(tscene *s)
{
    static const double lo[3] = {-0.5, -0.3, 1.0}, hi[3] = {1.1, 0.7, 1.8};
    scene_init(s);
    s->sky_a[0] = s->sky_a[1] = s->sky_a[2] = 1.0f;
    s->has_box = 1;
    memcpy(s->box_lo, lo, sizeof lo);
    memcpy(s->box_hi, hi, sizeof hi);
}

static double hit_sphere(const tscene *s, const float o[3], const float d[3])
{
    double oc[3], b, c, disc, t;
    int i;
    for (i = 0; i < 3; i++)
        oc[i] = (double)o[i] - s->centre[i];
    b = oc[0] * d[0] + oc[1] * d[1] + oc[2] * d[2];
    c = oc[0] * oc[0] + oc[1] * oc[1] + oc[2] * oc[2] - s->radius * s->radius;
    disc = b * b - c;
    if (disc < 0.0)
        return -1.0;
    /* The nearer root, in the form that does not cancel. */
    t = -b - sqrt(disc);
    if (t <= 0.0)
        t = c / (-b - sqrt(disc)) > 0.0 ? c / (-b - sqrt(disc)) : -1.0;
    return t;
}

/* Slab test; returns the entry distance (> 0) and the face's axis/side. */
static double hit_box(const tscene *s, const float o[3], const float d[3], int *axis, int *side)
{
    double t0 = 0.0, t1 = 1e300;
    int i, ax = -1, sd = 0;
    for (i = 0; i < 3; i++) {
        double inv = 1.0 / d[i], a = (s->box_lo[i] - o[i]) * inv, b = (s->box_hi[i] - o[i]) * inv;
        int lo_first = a < b;
        if (!lo_first) {
            double x = a;
            a = b;
            b = x;
        }
        if (a > t0) {
            t0 = a;
            ax = i;
            sd = lo_first ? 0 : 1;
        }
        if (b < t1)
            t1 = b;
    }
    if (t0 > t1 || ax < 0)
        return -1.0;
    *axis = ax;
    *side = sd;
    return t0;
}

static void inject(tscene *s, irc_hit *h)
{
    switch (s->fail_kind) {
    case FAIL_RAY: h->status = IRC_RAY_FAILED; break;
    case FAIL_NEG_DIST: h->status = IRC_RAY_HIT; h->dist = -1.0f; break;
    case FAIL_NAN_DIST: h->status = IRC_RAY_HIT; h->dist = NAN; break;
    case FAIL_ZERO_DIST: h->status = IRC_RAY_HIT; h->dist = 0.0f; break;
    case FAIL_INF_RADIANCE: h->radiance[1] = INFINITY; break;
    case FAIL_NAN_RADIANCE: h->radiance[0] = NAN; break;
    case FAIL_NEG_RADIANCE: h->radiance[2] = -1.0f; break;
    case FAIL_ZERO_NORMAL:
        h->status = IRC_RAY_HIT;
        h->dist = 1.0f;
        h->normal[0] = h->normal[1] = h->normal[2] = 0.0f;
        break;
    case FAIL_BAD_STATUS: h->status = 7; break;
    case FAIL_INF_DIST: h->status = IRC_RAY_HIT; h->dist = INFINITY; break;
    case FAIL_NAN_NORMAL:
        h->status = IRC_RAY_HIT;
        h->dist = 1.0f;
        h->normal[0] = NAN;
        break;
    case FAIL_UNTOUCHED: h->status = -1; break;
    default: break;
    }
}

double scene_sky(const tscene *s, const double d[3], int c)
{
    double v = s->sky_a[c] + s->sky_b[c] * d[2];
    if (s->lobe_l[c] != 0.0f) {
        double t = d[0] * s->lobe_dir[0] + d[1] * s->lobe_dir[1] + d[2] * s->lobe_dir[2];
        if (t > 0.0)
            v += s->lobe_l[c] * pow(t, s->lobe_k);
    }
    return v;
}

int scene_trace(const irc_trace_args *a)
{
    tscene *s = (tscene *)a->context;
    uint32_t r;
    for (r = 0; r < a->count; r++) {
        const float *o = a->rays[r].org, *d = a->rays[r].dir;
        irc_hit *h = &a->hits[r];
        double t = s->has_sphere ? hit_sphere(s, o, d) : -1.0;
        double tp = -1.0;
        int c;
        if (s->has_box) {
            int ax, sd;
            double tb = hit_box(s, o, d, &ax, &sd);
            if (tb > 0.0 && (t <= 0.0 || tb < t)) {
                h->status = IRC_RAY_HIT;
                h->dist = (float)tb;
                h->normal[0] = h->normal[1] = h->normal[2] = 0.0f;
                h->normal[ax] = sd ? 1.0f : -1.0f;
                h->radiance[0] = h->radiance[1] = h->radiance[2] = 0.0f;
                goto next;
            }
        }
        if (s->has_disk && d[2] > 0.0f && o[2] < s->disk_c[2]) {
            double td = (s->disk_c[2] - o[2]) / d[2];
            double x = o[0] + td * d[0] - s->disk_c[0], y = o[1] + td * d[1] - s->disk_c[1];
            if (x * x + y * y < s->disk_r * s->disk_r && (t <= 0.0 || td < t)) {
                h->status = IRC_RAY_HIT;
                h->dist = (float)td;
                h->normal[0] = h->normal[1] = 0.0f;
                h->normal[2] = -1.0f;
                h->radiance[0] = h->radiance[1] = h->radiance[2] = 0.0f;
                goto next;
            }
        }
        if (s->has_plane && d[2] < 0.0f && o[2] > s->plane_z)
            tp = (s->plane_z - o[2]) / d[2];
        if (t > 0.0 && (tp <= 0.0 || t < tp)) {
            h->status = IRC_RAY_HIT;
            h->dist = (float)t;
            for (c = 0; c < 3; c++) {
                h->normal[c] = (float)((o[c] + t * d[c] - s->centre[c]) / s->radius);
                h->radiance[c] = s->sphere_l[c];
            }
        } else if (tp > 0.0) {
            h->status = IRC_RAY_HIT;
            h->dist = (float)tp;
            h->normal[0] = h->normal[1] = 0.0f;
            h->normal[2] = 1.0f;
            for (c = 0; c < 3; c++)
                h->radiance[c] = s->plane_l[c];
        } else {
            h->status = IRC_RAY_ESCAPED;
            double dd[3];
            dd[0] = d[0]; dd[1] = d[1]; dd[2] = d[2];
            for (c = 0; c < 3; c++)
                h->radiance[c] = (float)scene_sky(s, dd, c);
        }
    next:
        /* Injection counts calls: single-threaded tests only. */
        if (s->fail_every && ++s->calls % s->fail_every == 0)
            inject(s, h);
    }
    return s->return_code;
}

double sphere_plane_e(const tscene *s, const double p[3])
{
    double dx = s->centre[0] - p[0], dy = s->centre[1] - p[1], h = s->centre[2] - p[2];
    double d = sqrt(dx * dx + dy * dy + h * h);
    return TPI * s->sky_a[0] * (1.0 - s->radius * s->radius * h / (d * d * d));
}

/* E = pi L (1 - r^2 h / d^3), so grad_p E = 3 pi L r^2 h (p - C) / d^5 in
 * the plane. */
void sphere_plane_grad(const tscene *s, const double p[3], double g[3])
{
    double dx = p[0] - s->centre[0], dy = p[1] - s->centre[1], h = s->centre[2] - p[2];
    double d = sqrt(dx * dx + dy * dy + h * h);
    double k = 3.0 * TPI * s->sky_a[0] * s->radius * s->radius * h / pow(d, 5.0);
    g[0] = k * dx;
    g[1] = k * dy;
    g[2] = 0.0;
}

double disk_plane_e(const tscene *s, const double p[3])
{
    double h = s->disk_c[2] - p[2], dx = p[0] - s->disk_c[0], dy = p[1] - s->disk_c[1];
    double a2 = dx * dx + dy * dy, r2 = s->disk_r * s->disk_r;
    double f = 0.5 * (1.0 - (h * h + a2 - r2) / sqrt(pow(h * h + a2 + r2, 2.0) - 4.0 * a2 * r2));
    return TPI * s->sky_a[0] * (1.0 - f);
}

/* Lambert: F = 1/(2 pi) sum_i gamma_i n.(R_i x R_i+1)/|R_i x R_i+1| over the
 * polygon's edges, gamma_i the angle the edge subtends; the absolute value
 * makes the winding irrelevant. */
static double polygon_ff(double v[4][3], const double p[3])
{
    double f = 0.0;
    int i, k;
    for (i = 0; i < 4; i++) {
        double a[3], b[3], c[3], la = 0, lb = 0, lc, g;
        for (k = 0; k < 3; k++) {
            a[k] = v[i][k] - p[k];
            b[k] = v[(i + 1) % 4][k] - p[k];
        }
        c[0] = a[1] * b[2] - a[2] * b[1];
        c[1] = a[2] * b[0] - a[0] * b[2];
        c[2] = a[0] * b[1] - a[1] * b[0];
        for (k = 0; k < 3; k++) {
            la += a[k] * a[k];
            lb += b[k] * b[k];
        }
        lc = sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
        g = acos((a[0] * b[0] + a[1] * b[1] + a[2] * b[2]) / sqrt(la * lb));
        f += g * c[2] / lc; /* receiver normal +z */
    }
    return fabs(f) / (2.0 * TPI);
}

double box_plane_e(const tscene *s, const double p[3])
{
    double f = 0.0;
    int ax, sd;
    for (ax = 0; ax < 3; ax++)
        for (sd = 0; sd < 2; sd++) {
            double plane = sd ? s->box_hi[ax] : s->box_lo[ax], v[4][3];
            int a1 = (ax + 1) % 3, a2 = (ax + 2) % 3, k;
            /* the face faces p when p lies on its outer side */
            if (sd ? p[ax] <= plane : p[ax] >= plane)
                continue;
            for (k = 0; k < 4; k++) {
                v[k][ax] = plane;
                v[k][a1] = (k == 1 || k == 2) ? s->box_hi[a1] : s->box_lo[a1];
                v[k][a2] = (k >= 2) ? s->box_hi[a2] : s->box_lo[a2];
            }
            f += polygon_ff(v, p);
        }
    return TPI * s->sky_a[0] * (1.0 - f);
}

irc_config scene_config(tscene *s, uint32_t features, uint32_t m, uint32_t n)
{
    irc_config cfg;
    memset(&cfg, 0, sizeof cfg);
    cfg.version = IRC_CONFIG_VERSION;
    cfg.trace = scene_trace;
    cfg.context = s;
    /* 0: bare records, and records keep the radii they are given or
     * computed with: what the closed forms here are for (the library's own
     * defaults, both gradients, neighbour clamping and confirming rays, are
     * test_defaults' and t_sight's) */
    cfg.features = features ? features : IRC_FEATURE_NONE;
    cfg.clamp_neighbours = IRC_OFF;
    cfg.check_visibility = IRC_OFF;
    cfg.strata_theta = m;
    cfg.strata_phi = n;
    return cfg;
}

irc_config sh_config(tscene *s, uint32_t features, uint32_t m, uint32_t n, uint32_t bands)
{
    irc_config cfg = scene_config(s, features, m, n);
    cfg.sh.bands = bands;
    return cfg;
}

void disk_record(irc_record *r, float e, float rad)
{
    memset(r, 0, sizeof *r);
    r->n[2] = 1.0f;
    r->e[0] = r->e[1] = r->e[2] = e;
    r->radius = rad;
}

irc_cache *block_cache(irc_config *cfg, uint32_t records, size_t guard)
{
    size_t bytes;
    irc_cache *c;
    if (irc_footprint(cfg, records, &bytes) != IRC_OK)
        return NULL;
    cfg->buffer = malloc(bytes + guard);
    cfg->buffer_size = bytes;
    memset((char *)cfg->buffer + bytes, 0xA5, guard);
    if (irc_init(cfg, records, &c) != IRC_OK) {
        free(cfg->buffer);
        cfg->buffer = NULL;
        return NULL;
    }
    return c;
}

int block_guard_ok(const irc_config *cfg, size_t guard)
{
    const unsigned char *g = (const unsigned char *)cfg->buffer + cfg->buffer_size;
    size_t i;
    for (i = 0; i < guard; i++)
        if (g[i] != 0xA5)
            return 0;
    return 1;
}

void block_free(irc_config *cfg)
{
    free(cfg->buffer);
    cfg->buffer = NULL;
}

double xrand(unsigned long long *state)
{
    unsigned long long x = (*state += 0x9e3779b97f4a7c15ull);
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
    x ^= x >> 31;
    return (double)(x >> 11) * (1.0 / 9007199254740992.0);
}

/* The block against a copy taken before a call, but for the port's lock
 * object (the header's promise: glibc's rwlock keeps phase bits). */
int block_same(const irc_config *cfg, const unsigned char *copy, const irc_cache *c)
{
    const unsigned char *b = (const unsigned char *)cfg->buffer;
    size_t lo = (size_t)((const unsigned char *)irc__lock(c) - b), hi = lo + c->port->lock_size, o;
    for (o = 0; o < cfg->buffer_size; o++)
        if ((o < lo || o >= hi) && copy[o] != b[o]) {
            printf("  first difference at byte %zu\n", o);
            return 0;
        }
    return 1;
}
