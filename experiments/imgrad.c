/*
 * imgrad.c -- the image and its gradient at a point of the image plane
 * (imgrad.h).
 */
#define IRC_EXPERIMENTAL /* irc_cache_lookup_gradient (irrcache.h) */
#include "imgrad.h"

#include <float.h>
#include <stdlib.h>
#include <math.h>
#include <string.h>

#define PI 3.14159265358979323846
#define MAX_LIGHT 256
#define HALF 0.5f /* the central differences' half step, pixels */
/* IMG_GRADIENT_FAST re-shades with at most this many of the pixel's light
 * samples (every k-th of those that reached the light, their sum scaled
 * back): an importance needs no more, and the gradient's cost then stays
 * put while a pixel's grows with its samples. */
#define FAST_SAMPLES 4

float lum3(const float c[3])
{
    return 0.2126f * c[0] + 0.7152f * c[1] + 0.0722f * c[2];
}

/* A surface, not a primitive: spheres by index, meshes with vertex normals
 * by material, flat triangles by material and plane (two triangles of one
 * wall are one object; a box's faces are not). */
static int object_of(const scene *s, int prim, const surface *sf)
{
    const triangle *t;
    uint64_t h;
    float d;
    int i;
    if (prim < 0)
        return -prim + (1 << 24);
    t = &s->tris[prim];
    if (t->has_n)
        return (1 << 25) + t->mat;
    d = sf->ng[0] * t->v[0][0] + sf->ng[1] * t->v[0][1] + sf->ng[2] * t->v[0][2];
    h = hash64((uint64_t)(uint32_t)t->mat);
    for (i = 0; i < 3; i++)
        h = hash64(h ^ (uint64_t)(int64_t)lrintf(sf->ng[i] * 1000.0f));
    h = hash64(h ^ (uint64_t)(int64_t)llrint((double)d * 1000.0));
    return (int)(h & 0xffffffu);
}

/* The shading a moved surface gets from the frozen samples: emission plus
 * direct light toward -d. */
static void shade(const light_sample *ls, int n, int samples, const surface *sf,
                  const float d[3], float out[3])
{
    emitted(sf, out);
    direct_eval(ls, n, samples, sf, d, out);
}

/* The point moved off pixels along the image's axis (0: x, 1: y): the
 * surface the moved camera ray meets on the same primitive, and the ray's
 * direction; returns 0 and the point itself when that ray leaves the
 * primitive. */
static int side(const renderer *r, const cam_frame *cf, float x, float y, int axis, float off,
                int prim, const surface *sf, const float d[3], surface *s, float dd[3])
{
    bvh_hit h;
    camera_ray_at(cf, &r->s->cam, x + (axis ? 0.0f : off), y + (axis ? off : 0.0f), dd);
    if (hit_surface_of(r->s, prim, cf->eye, dd, &h)) {
        surface_at(r->s, cf->eye, dd, &h, s);
        return 1;
    }
    *s = *sf;
    memcpy(dd, d, sizeof(float[3]));
    return 0;
}

/* E's gradient from the cache at a surface (irc_cache_lookup_gradient:
 * the records' gradients, not the lookups' differences, which jump where
 * records enter and leave reach): 0 on a miss or without a cache. */
static int cached_gradient(const renderer *r, const surface *sf, float e[3], irc_gradient *g)
{
    float p[3], w;
    if (r->o.mode != MODE_CACHE || (r->o.features & IRC_FEATURE_SH))
        return 0;
    cache_point(sf, p);
    return irc_cache_lookup_gradient(r->cache, p, sf->nsm, e, g, &w) == IRC_OK;
}

/* kd/pi times E's change from s[0] to s[1] over step, to first order. */
static void indirect_part(const irc_gradient *g, const float kd[3], const surface s[2],
                          float step, float out[3])
{
    float dp[3], dn[3];
    int c, k;
    for (k = 0; k < 3; k++) {
        dp[k] = s[1].p[k] - s[0].p[k];
        dn[k] = s[1].nsm[k] - s[0].nsm[k];
    }
    for (c = 0; c < 3; c++) {
        float de = 0.0f;
        for (k = 0; k < 3; k++)
            de += g->dp[c][k] * dp[k] + g->dn[c][k] * dn[k];
        out[c] = kd[c] * de / step;
    }
}

/* One part of the move: the shading with only the point (what 0), the
 * normal (1) or the view (2) taken from either side, differenced. */
static void part(const light_sample *ls, int n, int samples, const surface *sf,
                 const float d[3], const surface s[2], float dd[2][3], int what, float step,
                 float scale, float out[3])
{
    float f[2][3];
    int k, c;
    for (k = 0; k < 2; k++) {
        surface m = *sf;
        if (what == 0)
            memcpy(m.p, s[k].p, sizeof m.p);
        if (what == 1)
            memcpy(m.ns, s[k].ns, sizeof m.ns);
        shade(ls, n, samples, &m, what == 2 ? dd[k] : d, f[k]);
    }
    for (c = 0; c < 3; c++)
        out[c] = scale * (f[1][c] - f[0][c]) / step;
}

/* One axis of the gradient (axis 0: x, 1: y): each part as a central
 * difference over +-HALF pixel (a side whose ray leaves the surface makes
 * it one-sided), or (fast) a forward one, the point and HALF beyond it
 * (behind it when that side leaves the surface). */
static void axis_gradient(const renderer *r, const cam_frame *cf, float x, float y, int axis,
                          int prim, const surface *sf, const float d[3],
                          const light_sample *ls, int n, int samples, float scale,
                          const irc_gradient *ge, const float centre[3], int level,
                          img_point *out)
{
    const int parts = level == IMG_GRADIENT_PARTS;
    surface s[2];
    float dd[2][3], f[2][3], kd[3], step;
    int ok[2], k, c;
    if (level == IMG_GRADIENT_FAST) { /* the point and HALF beyond it, or behind it */
        ok[0] = 0;
        s[0] = *sf;
        memcpy(dd[0], d, sizeof dd[0]);
        if (!(ok[1] = side(r, cf, x, y, axis, HALF, prim, sf, d, &s[1], dd[1])))
            ok[0] = side(r, cf, x, y, axis, -HALF, prim, sf, d, &s[0], dd[0]);
    } else {
        for (k = 0; k < 2; k++)
            ok[k] = side(r, cf, x, y, axis, k ? HALF : -HALF, prim, sf, d, &s[k], dd[k]);
    }
    if (!ok[0] && !ok[1])
        return;
    step = (ok[0] && ok[1] ? 2.0f : 1.0f) * HALF;
    for (c = 0; c < 3; c++)
        kd[c] = sf->m->kd[c] / (float)PI;
    if (!parts) { /* the whole move at once: two shadings, not six */
        for (k = 0; k < 2; k++) {
            if (level == IMG_GRADIENT_FAST && ok[k] == 0) /* the point: done once */
                memcpy(f[k], centre, sizeof f[k]);
            else
                shade(ls, n, samples, &s[k], dd[k], f[k]);
        }
        if (ge)
            indirect_part(ge, kd, s, step, out->ind[axis]);
        for (c = 0; c < 3; c++)
            out->grad[axis][c] = scale * (f[1][c] - f[0][c]) / step + out->ind[axis][c];
        return;
    }
    /* SV: the point moves, normal and view held; CDV: the normal turns
     * (curvature and bumps), point and view held; DV: the view turns. */
    part(ls, n, samples, sf, d, s, dd, 0, step, scale, out->sv[axis]);
    part(ls, n, samples, sf, d, s, dd, 1, step, scale, out->cdv[axis]);
    part(ls, n, samples, sf, d, s, dd, 2, step, scale, out->dv[axis]);
    if (ge)
        indirect_part(ge, kd, s, step, out->ind[axis]);
    for (c = 0; c < 3; c++)
        out->grad[axis][c] =
            out->sv[axis][c] + out->cdv[axis][c] + out->dv[axis][c] + out->ind[axis][c];
}

/* The direct light's key: a pixel centre keeps the full render's (render.c,
 * shade_pixel), so that samples there match its pixels. */
static uint64_t light_key(float x, float y)
{
    const float fx = x - 0.5f, fy = y - 0.5f;
    uint32_t bx, by;
    if (fx == floorf(fx) && fy == floorf(fy) && fx >= 0.0f && fy >= 0.0f)
        return hash64((uint64_t)(uint32_t)fy << 32 | (uint32_t)fx);
    memcpy(&bx, &x, 4);
    memcpy(&by, &y, 4);
    return hash64(hash64(0x9e3779b97f4a7c15ull ^ bx) ^ (uint64_t)by << 32);
}

int image_point(renderer *r, const cam_frame *cf, float x, float y, int grads, uint64_t key,
                img_point *out)
{
    light_sample ls[MAX_LIGHT];
    const int samples = r->o.light_samples < MAX_LIGHT ? r->o.light_samples : MAX_LIGHT;
    double t0;
    float d[3], p[3], pn[6], e[3];
    render_stats st;
    bvh_hit bh;
    surface sf;
    uint64_t rays = 0;
    irc_gradient ge;
    int c, n, axis, err, have = 0;
    memset(out, 0, sizeof *out);
    if (!key)
        key = light_key(x, y);
    camera_ray_at(cf, &r->s->cam, x, y, d);
    if (!bvh_intersect(&r->b, cf->eye, d, 0.0f, FLT_MAX, &bh)) {
        env_radiance(&r->s->env, d, out->rgb);
        out->object = -1;
        return 0;
    }
    surface_at(r->s, cf->eye, d, &bh, &sf);
    out->object = object_of(r->s, bh.prim, &sf);
    cache_point(&sf, p);
    memcpy(pn, p, sizeof p);
    memcpy(pn + 3, sf.nsm, sizeof sf.nsm);
    /* A gradient wanted: one lookup gives E and its gradient; a miss takes
     * the renderer's way (a record), then looks again. */
    if (grads)
        have = cached_gradient(r, &sf, e, &ge);
    if (!have && (err = render_points(r, pn, 1, e, &st)) < 0)
        return err;
    n = direct_samples(&r->b, &r->l, &sf, 0, samples, samples, key, ls, &rays);
    out->lit = rays == 0 ? -1 : 2 * (uint64_t)n >= rays; /* rays: samples facing sf */
    shade(ls, n, samples, &sf, d, out->rgb);
    for (c = 0; c < 3; c++) {
        out->indirect[c] = sf.m->kd[c] / (float)PI * e[c];
        out->rgb[c] += out->indirect[c];
    }
    out->curvature = bh.prim < 0 ? 1.0f / r->s->spheres[-bh.prim - 1].r : 0.0f;
    out->depth = (sf.p[0] - cf->eye[0]) * cf->f[0] + (sf.p[1] - cf->eye[1]) * cf->f[1] +
                 (sf.p[2] - cf->eye[2]) * cf->f[2];
    out->cos_view = -(sf.ng[0] * d[0] + sf.ng[1] * d[1] + sf.ng[2] * d[2]);
    out->exponent = sf.m->ks[0] + sf.m->ks[1] + sf.m->ks[2] > 0.0f ? sf.m->ns : 0.0f;
    if (grads) {
        const int most = grads == IMG_GRADIENT_FAST ? FAST_SAMPLES : MAX_LIGHT,
                  k = (samples + most - 1) / most;
        light_sample *sub = ls;
        float centre[3] = {0.0f, 0.0f, 0.0f}, e2[3];
        int m = n, j;
        t0 = render_clock();
        if (k > 1) /* in place: the shading above is done with them */
            for (j = m = 0; j < n; j += k)
                sub[m++] = ls[j];
        if (!have)
            have = cached_gradient(r, &sf, e2, &ge);
        if (grads == IMG_GRADIENT_FAST)
            shade(sub, m, samples, &sf, d, centre);
        for (axis = 0; axis < 2; axis++)
            axis_gradient(r, cf, x, y, axis, bh.prim, &sf, d, sub, m, samples,
                          m ? (float)n / (float)m : 0.0f, have ? &ge : NULL, centre, grads,
                          out);
        out->grad_s = render_clock() - t0;
    }
    return 0;
}

/* Whether pixel (x, y) and its 8 neighbours see one object. */
static int one_object(const img_point *ip, int w, int x, int y)
{
    const int o = ip[y * w + x].object;
    int dx, dy, same = o >= 0;
    for (dy = -1; dy <= 1; dy++)
        for (dx = -1; dx <= 1; dx++)
            same &= ip[(y + dy) * w + x + dx].object == o;
    return same;
}

/* One part's luminance (0: direct, the rest; 1: indirect) and its
 * gradient along axis a (-1: the value). */
static double lum_part(const img_point *p, int part, int a)
{
    if (a < 0)
        return part ? lum3(p->indirect) : (double)lum3(p->rgb) - lum3(p->indirect);
    return part ? lum3(p->ind[a]) : (double)lum3(p->grad[a]) - lum3(p->ind[a]);
}

static int cmp_double(const void *a, const void *b)
{
    const double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* One part's gradient against central differences of that part's image,
 * at pixels whose 3 x 3 neighbours see one object: relative L2 error, and
 * the median and 90th percentile of the per-pixel relative error where
 * |grad| is above a tenth of its mean. */
static int part_check(const img_point *ip, int w, int h, int part, grad_part *out)
{
    double num = 0.0, den = 0.0, mean = 0.0, *rel = malloc(sizeof *rel * (size_t)w * (size_t)h);
    int x, y, n = 0, nr = 0, pass;
    if (!rel)
        return -1;
    for (pass = 0; pass < 2; pass++) { /* the mean first, then the errors */
        for (y = 1; y < h - 1; y++)
            for (x = 1; x < w - 1; x++) {
                const img_point *c = &ip[y * w + x];
                const double gx = lum_part(c, part, 0), gy = lum_part(c, part, 1),
                             g = sqrt(gx * gx + gy * gy),
                             fx = 0.5 * (lum_part(c + 1, part, -1) - lum_part(c - 1, part, -1)),
                             fy = 0.5 * (lum_part(c + w, part, -1) - lum_part(c - w, part, -1)),
                             e = sqrt((gx - fx) * (gx - fx) + (gy - fy) * (gy - fy));
                if (!one_object(ip, w, x, y))
                    continue;
                if (pass == 0) {
                    mean += g;
                    n++;
                    continue;
                }
                num += e * e;
                den += g * g;
                if (g > 0.1 * mean)
                    rel[nr++] = e / g;
            }
        if (pass == 0)
            mean = n ? mean / n : 0.0;
    }
    qsort(rel, (size_t)nr, sizeof *rel, cmp_double);
    out->pixels = n;
    out->strong = nr;
    out->l2 = den > 0.0 ? sqrt(num / den) : 0.0;
    out->median = nr ? rel[nr / 2] : 0.0;
    out->p90 = nr ? rel[nr * 9 / 10] : 0.0;
    free(rel);
    return 0;
}

int image_gradient_check(renderer *r, const cam_frame *cf, int w, int h, int level,
                         grad_check *out)
{
    const uint64_t key = 0x5eedull;
    img_point *ip = malloc(sizeof *ip * (size_t)w * (size_t)h);
    int x, y, st = 0;
    const int frozen = r->o.frozen;
    memset(out, 0, sizeof *out);
    if (!ip)
        return -1;
    /* The cache is held as it is: records added while the image is shaded
     * would make E jump between neighbouring pixels. */
    r->o.frozen = 1;
    for (y = 0; y < h && st == 0; y++)
        for (x = 0; x < w && st == 0; x++)
            st = image_point(r, cf, (float)x + 0.5f, (float)y + 0.5f, level, key, &ip[y * w + x]);
    r->o.frozen = frozen;
    if (st == 0 && (part_check(ip, w, h, 0, &out->direct) < 0 ||
                    part_check(ip, w, h, 1, &out->indirect) < 0))
        st = -1;
    free(ip);
    return st;
}
