/* shade.c -- surfaces, environment, lights and the BRDF (see shade.h). */
#include "shade.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#define PI 3.14159265358979323846

uint64_t hash64(uint64_t x)
{
    x ^= x >> 30;
    x *= 0xbf58476d1ce4e5b9ull;
    x ^= x >> 27;
    x *= 0x94d049bb133111ebull;
    return x ^ (x >> 31);
}

double rnd(uint64_t key, uint32_t i)
{
    return (double)(hash64(key + 0x9e3779b97f4a7c15ull * (i + 1)) >> 11) * (1.0 / 9007199254740992.0);
}

float dot3(const float a[3], const float b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static void normalize3(float v[3])
{
    float l = sqrtf(dot3(v, v));
    if (l > 0.0f) {
        v[0] /= l;
        v[1] /= l;
        v[2] /= l;
    }
}

static void tri_normal(const triangle *t, float n[3])
{
    float e1[3], e2[3];
    int i;
    for (i = 0; i < 3; i++) {
        e1[i] = t->v[1][i] - t->v[0][i];
        e2[i] = t->v[2][i] - t->v[0][i];
    }
    n[0] = e1[1] * e2[2] - e1[2] * e2[1];
    n[1] = e1[2] * e2[0] - e1[0] * e2[2];
    n[2] = e1[0] * e2[1] - e1[1] * e2[0];
}

static double luminance(const float c[3])
{
    return 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2];
}

int lights_build(lights *l, const scene *s)
{
    int i;
    memset(l, 0, sizeof *l);
    l->tri = malloc(sizeof(int) * (size_t)(s->ntris + 1));
    l->cdf = malloc(sizeof(double) * (size_t)(s->ntris + 1));
    if (!l->tri || !l->cdf) {
        lights_free(l);
        return -1;
    }
    for (i = 0; i < s->ntris; i++) {
        const material *m = &s->mats[s->tris[i].mat];
        float n[3];
        double power;
        if (luminance(m->ke) <= 0.0)
            continue;
        tri_normal(&s->tris[i], n);
        power = 0.5 * sqrt((double)dot3(n, n)) * luminance(m->ke);
        l->total += power;
        l->tri[l->count] = i;
        l->cdf[l->count++] = l->total;
    }
    return 0;
}

void lights_free(lights *l)
{
    free(l->tri);
    free(l->cdf);
    memset(l, 0, sizeof *l);
}

/* Procedural bumps h(p) = A sin(Fx) sin(Fy) sin(Fz): the shading normal
 * tilts against the tangential part of grad h. */
static void bump(const material *m, const float p[3], float n[3])
{
    float f = m->bump_freq, a = m->bump, g[3], gn;
    float sx = sinf(f * p[0]), sy = sinf(f * p[1]), sz = sinf(f * p[2]);
    int i;
    g[0] = a * f * cosf(f * p[0]) * sy * sz;
    g[1] = a * f * sx * cosf(f * p[1]) * sz;
    g[2] = a * f * sx * sy * cosf(f * p[2]);
    gn = dot3(g, n);
    for (i = 0; i < 3; i++)
        n[i] -= g[i] - gn * n[i];
    normalize3(n);
}

void surface_at(const scene *s, const float o[3], const float d[3], const bvh_hit *h,
                surface *out)
{
    int i;
    for (i = 0; i < 3; i++)
        out->p[i] = o[i] + h->t * d[i];
    if (h->prim >= 0) {
        const triangle *t = &s->tris[h->prim];
        float w = 1.0f - h->u - h->v;
        tri_normal(t, out->ng);
        out->m = &s->mats[t->mat];
        for (i = 0; i < 3; i++)
            out->ns[i] = t->has_n ? w * t->n[0][i] + h->u * t->n[1][i] + h->v * t->n[2][i]
                                  : out->ng[i];
    } else {
        const sphere *sp = &s->spheres[-h->prim - 1];
        for (i = 0; i < 3; i++)
            out->ng[i] = out->p[i] - sp->c[i];
        memcpy(out->ns, out->ng, sizeof out->ns);
        out->m = &s->mats[sp->mat];
    }
    normalize3(out->ng);
    normalize3(out->ns);
    out->front = dot3(out->ng, d) < 0.0f;
    if (!out->front)
        for (i = 0; i < 3; i++)
            out->ng[i] = -out->ng[i];
    if (dot3(out->ns, out->ng) < 0.0f)
        for (i = 0; i < 3; i++)
            out->ns[i] = -out->ns[i];
    memcpy(out->nsm, out->ns, sizeof out->nsm);
    if (out->m->bump > 0.0f)
        bump(out->m, out->p, out->ns);
}

const float *gather_normal(const surface *sf)
{
    return dot3(sf->nsm, sf->ng) >= 0.5f ? sf->nsm : sf->ng;
}

float ray_offset(const float p[3])
{
    float m = fabsf(p[0]);
    if (fabsf(p[1]) > m) m = fabsf(p[1]);
    if (fabsf(p[2]) > m) m = fabsf(p[2]);
    return 1e-5f * (1.0f + m);
}

void cosine_dir(const float n[3], double u1, double u2, float out[3])
{
    float t1[3], t2[3], sgn = n[2] >= 0.0f ? 1.0f : -1.0f;
    float a = -1.0f / (sgn + n[2]), b = n[0] * n[1] * a;
    double st = sqrt(u1), ct = sqrt(1.0 - u1), ph = 2.0 * PI * u2;
    int c;
    t1[0] = 1.0f + sgn * n[0] * n[0] * a; t1[1] = sgn * b; t1[2] = -sgn * n[0];
    t2[0] = b; t2[1] = sgn + n[1] * n[1] * a; t2[2] = -n[1];
    for (c = 0; c < 3; c++)
        out[c] = (float)(st * (cos(ph) * t1[c] + sin(ph) * t2[c]) + ct * n[c]);
}

void env_radiance(const environment *e, const float d[3], float out[3])
{
    int i;
    float g = 0.0f;
    if (e->kind == ENV_NONE) {
        out[0] = out[1] = out[2] = 0.0f;
        return;
    }
    if (e->kind == ENV_GAUSSIAN) {
        float c = dot3(d, e->dir), ang, sig = e->sigma_deg * (float)(PI / 180.0);
        ang = acosf(c > 1.0f ? 1.0f : c < -1.0f ? -1.0f : c);
        g = expf(-ang * ang / (2.0f * sig * sig));
    }
    for (i = 0; i < 3; i++)
        out[i] = e->base[i] + g * e->peak[i];
}

void emitted(const surface *sf, float out[3])
{
    int i;
    for (i = 0; i < 3; i++)
        out[i] = sf->front ? sf->m->ke[i] : 0.0f;
}

/* Lambert plus normalised Phong: kd/pi + ks (ns+2)/(2pi) max(0, r.wi)^ns,
 * r the mirror of the outgoing direction -d. */
static void brdf(const surface *sf, const float d[3], const float wi[3], float f[3])
{
    const material *m = sf->m;
    float spec = 0.0f;
    int i;
    if (m->ks[0] + m->ks[1] + m->ks[2] > 0.0f) {
        float dn = dot3(d, sf->ns), r[3], c;
        for (i = 0; i < 3; i++)
            r[i] = d[i] - 2.0f * dn * sf->ns[i];
        c = dot3(r, wi);
        spec = c > 0.0f ? (m->ns + 2.0f) / (2.0f * (float)PI) * powf(c, m->ns) : 0.0f;
    }
    for (i = 0; i < 3; i++)
        f[i] = m->kd[i] / (float)PI + m->ks[i] * spec;
}

static int pick_light(const lights *l, double u)
{
    int lo = 0, hi = l->count - 1;
    u *= l->total;
    while (lo < hi) {
        int mid = (lo + hi) / 2;
        if (l->cdf[mid] < u)
            lo = mid + 1;
        else
            hi = mid;
    }
    return lo;
}

/* The direction from sf's lifted origin to y, its squared length, and the
 * two cosines; 0 when the light faces away or lies below either normal.
 * The shadow ray runs from the lifted origin o to y, so its length and
 * its end are measured from o, not from the surface. */
static int light_geometry(const surface *sf, const float y[3], const float nl[3], float o[3],
                          float w[3], float *dist2, float *cx, float *cy)
{
    const float eps = ray_offset(sf->p);
    float dist;
    int i;
    for (i = 0; i < 3; i++) {
        o[i] = sf->p[i] + eps * sf->ng[i];
        w[i] = y[i] - o[i];
    }
    *dist2 = dot3(w, w);
    dist = sqrtf(*dist2);
    for (i = 0; i < 3; i++)
        w[i] /= dist;
    *cx = dot3(sf->ns, w);
    *cy = -dot3(nl, w);
    return !(*cx <= 0.0f || *cy <= 0.0f || dot3(sf->ng, w) <= 0.0f);
}

int direct_samples(const bvh *b, const lights *l, const surface *sf, int k0, int k1,
                   int samples, uint64_t key, light_sample *out, uint64_t *rays)
{
    const scene *s = b->s;
    int k, i, n = 0;
    if (l->count == 0 || samples <= 0)
        return 0;
    for (k = k0; k < k1; k++) {
        int li = pick_light(l, (k + rnd(key, 3u * k)) / samples);
        const triangle *t = &s->tris[l->tri[li]];
        const material *lm = &s->mats[t->mat];
        double u1 = rnd(key, 3u * k + 1), u2 = rnd(key, 3u * k + 2), su = sqrt(u1);
        light_sample *ls = &out[n];
        float w[3], o[3], dist2, cx, cy;
        for (i = 0; i < 3; i++)
            ls->y[i] = (float)((1.0 - su) * t->v[0][i] + su * (1.0 - u2) * t->v[1][i] +
                               su * u2 * t->v[2][i]);
        tri_normal(t, ls->nl);
        normalize3(ls->nl);
        if (!light_geometry(sf, ls->y, ls->nl, o, w, &dist2, &cx, &cy))
            continue;
        ++*rays;
        if (bvh_occluded(b, o, w, 0.0f, sqrtf(dist2) - ray_offset(ls->y)))
            continue;
        /* P(triangle) = area lum / total, uniform on it: per unit area, */
        ls->pdf = (float)(luminance(lm->ke) / l->total);
        ls->ke = lm->ke;
        n++;
    }
    return n;
}

void direct_eval(const light_sample *ls, int n, int samples, const surface *sf, const float d[3],
                 float out[3])
{
    int k, i;
    for (k = 0; k < n; k++) {
        float w[3], o[3], dist2, cx, cy, f[3];
        if (!light_geometry(sf, ls[k].y, ls[k].nl, o, w, &dist2, &cx, &cy))
            continue;
        brdf(sf, d, w, f);
        for (i = 0; i < 3; i++)
            out[i] += f[i] * ls[k].ke[i] * cx * cy / (dist2 * ls[k].pdf * samples);
    }
}

/* The sun's light leaving sf toward -d, added to out: f e cos, one shadow
 * ray toward it (a delta light: no samples to average). */
static void sun_light(const bvh *b, const surface *sf, const float d[3], float out[3],
                      uint64_t *rays)
{
    const sun *u = &b->s->sun;
    const float eps = ray_offset(sf->p);
    float o[3], f[3], c = dot3(sf->ns, u->dir);
    int i;
    if (!u->on || c <= 0.0f || dot3(sf->ng, u->dir) <= 0.0f)
        return;
    for (i = 0; i < 3; i++)
        o[i] = sf->p[i] + eps * sf->ng[i];
    ++*rays;
    if (bvh_occluded(b, o, u->dir, 0.0f, FLT_MAX))
        return;
    brdf(sf, d, u->dir, f);
    for (i = 0; i < 3; i++)
        out[i] += f[i] * u->e[i] * c;
}

void direct_light(const bvh *b, const lights *l, const surface *sf, const float d[3],
                  int samples, uint64_t key, float out[3], uint64_t *rays)
{
    light_sample buf[16];
    int k;
    out[0] = out[1] = out[2] = 0.0f;
    for (k = 0; k < samples; k += 16) {
        const int k1 = samples - k < 16 ? samples : k + 16;
        direct_eval(buf, direct_samples(b, l, sf, k, k1, samples, key, buf, rays), samples, sf,
                    d, out);
    }
    sun_light(b, sf, d, out, rays);
}
