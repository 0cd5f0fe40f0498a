/*
 * shobj.c -- the `sh` scene's object as a receiver (shobj.h).
 */
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "shobj.h"

#define PI 3.14159265358979323846

/* Radiance reaching the ray's origin: emission (the lights) plus the
 * direct light on what it hits (4 light samples, keyed by the ray so a
 * seed gives one answer per ray whatever the order). */
int sh_env_trace(const irc_trace_args *a)
{
    const sh_env *e = (const sh_env *)a->context;
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

int sh_env_init(sh_env *e, const scene *src, scene *copy, const sphere *blocker)
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
    e->min_radius = 10.0f;
    return bvh_build(&e->b, copy) < 0 || lights_build(&e->l, copy) < 0 ? -1 : 0;
}

void sh_env_free(sh_env *e, scene *copy)
{
    bvh_free(&e->b);
    lights_free(&e->l);
    free(copy->spheres);
    free(copy->mats);
}

irc_cache *sh_env_cache(sh_env *e, uint32_t features, uint32_t m, uint32_t n, void **block)
{
    irc_config cfg;
    irc_cache *c;
    size_t bytes;
    memset(&cfg, 0, sizeof cfg);
    cfg.version = IRC_CONFIG_VERSION;
    cfg.trace = sh_env_trace;
    cfg.context = e;
    cfg.max_batch = 64;
    cfg.features = features;
    cfg.strata_theta = m;
    cfg.strata_phi = n;
    cfg.sh.bands = SHOBJ_BANDS;
    cfg.accuracy = 10.0f;
    cfg.min_radius = e->min_radius;
    cfg.max_radius = 11.0f;
    cfg.seed = e->seed;
    cfg.sh.power = e->power;
    if (irc_footprint(&cfg, 64, &bytes) < 0 || !(*block = malloc(bytes)))
        return NULL;
    cfg.buffer = *block;
    cfg.buffer_size = bytes;
    return irc_init(&cfg, 64, &c) == IRC_OK ? c : NULL;
}

void sh_shade(const irc_sh *c, const material *m, const float n[3], const float d[3],
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

static void normalize3(float v[3])
{
    float len = sqrtf(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    v[0] /= len;
    v[1] /= len;
    v[2] /= len;
}

static void cross3(const float a[3], const float b[3], float out[3])
{
    out[0] = a[1] * b[2] - a[2] * b[1];
    out[1] = a[2] * b[0] - a[0] * b[2];
    out[2] = a[0] * b[1] - a[1] * b[0];
}

int sh_object_pixels(const camera *cam, const sphere *o, int w, float *pts, int *pix)
{
    float f[3], u[3], rt[3], tn = tanf(0.5f * cam->fov_deg * (float)PI / 180.0f);
    int x, y, k, cnt = 0;
    for (k = 0; k < 3; k++)
        f[k] = cam->look[k] - cam->eye[k];
    normalize3(f);
    cross3(f, cam->up, rt);
    normalize3(rt);
    cross3(rt, f, u);
    for (y = 0; y < w; y++)
        for (x = 0; x < w; x++) {
            float d[3], oc[3], b = 0.0f, cc = 0.0f, disc, t;
            float sx = (2.0f * (x + 0.5f) / w - 1.0f) * tn, sy = (1.0f - 2.0f * (y + 0.5f) / w) * tn;
            for (k = 0; k < 3; k++)
                d[k] = f[k] + sx * rt[k] + sy * u[k];
            normalize3(d);
            for (k = 0; k < 3; k++) {
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
            if (pix)
                pix[cnt] = y * w + x;
            cnt++;
        }
    return cnt;
}

double sh_rel_rmse(const float *a, const float *b, int n)
{
    double num = 0.0, den = 0.0;
    int i;
    for (i = 0; i < 3 * n; i++) {
        num += (a[i] - b[i]) * (double)(a[i] - b[i]);
        den += b[i] * (double)b[i];
    }
    return sqrt(num / den);
}

int sh_truth(sh_env *e, const material *m, const float *pts, int np, uint32_t mm,
             uint32_t nn, float *out)
{
    void *block = NULL;
    irc_cache *c = sh_env_cache(e, IRC_FEATURE_SH, mm, nn, &block);
    int i;
    if (!c)
        return -1;
    for (i = 0; i < np; i++) {
        irc_sh r;
        if (irc_sh_compute(c, pts + 9 * i, NULL, &r, NULL) < 0)
            return -1;
        sh_shade(&r, m, pts + 9 * i + 3, pts + 9 * i + 6, out + 3 * i);
    }
    irc_fini(c);
    free(block);
    return 0;
}

int sh_method(sh_env *e, const material *m, const float *pts, int np, const float (*at)[3],
              int count, uint32_t features, uint32_t mm, uint32_t nn, float *out)
{
    void *block = NULL;
    irc_cache *c = sh_env_cache(e, features, mm, nn, &block);
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
        sh_shade(&r, m, pts + 9 * i + 3, pts + 9 * i + 6, out + 3 * i);
    }
    irc_fini(c);
    free(block);
    return 0;
}
