/*
 * bvh.c -- binned SAH build (16 bins per axis on centroid bounds, leaves of
 * at most 4 primitives) and stack-based traversal, nearer child first.
 */
#include "bvh.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#define BINS 16
#define LEAF_MAX 4
#define STACK 64

typedef struct box {
    float lo[3], hi[3];
} box;

typedef struct prim_info {
    box b;
    float c[3];
} prim_info;

static void box_empty(box *b)
{
    int i;
    for (i = 0; i < 3; i++) {
        b->lo[i] = FLT_MAX;
        b->hi[i] = -FLT_MAX;
    }
}

static void box_grow(box *b, const box *o)
{
    int i;
    for (i = 0; i < 3; i++) {
        if (o->lo[i] < b->lo[i]) b->lo[i] = o->lo[i];
        if (o->hi[i] > b->hi[i]) b->hi[i] = o->hi[i];
    }
}

static float box_area(const box *b)
{
    float x = b->hi[0] - b->lo[0], y = b->hi[1] - b->lo[1], z = b->hi[2] - b->lo[2];
    if (x < 0.0f) return 0.0f;
    return 2.0f * (x * y + y * z + z * x);
}

static void prim_bounds(const scene *s, int p, prim_info *pi)
{
    int i, k;
    box_empty(&pi->b);
    if (p >= 0) {
        const triangle *t = &s->tris[p];
        for (k = 0; k < 3; k++)
            for (i = 0; i < 3; i++) {
                if (t->v[k][i] < pi->b.lo[i]) pi->b.lo[i] = t->v[k][i];
                if (t->v[k][i] > pi->b.hi[i]) pi->b.hi[i] = t->v[k][i];
            }
    } else {
        const sphere *sp = &s->spheres[-p - 1];
        for (i = 0; i < 3; i++) {
            pi->b.lo[i] = sp->c[i] - sp->r;
            pi->b.hi[i] = sp->c[i] + sp->r;
        }
    }
    for (i = 0; i < 3; i++)
        pi->c[i] = 0.5f * (pi->b.lo[i] + pi->b.hi[i]);
}

/* Best split of prims[first, first+count) by binned SAH; returns the split
 * count on the left (0 = make a leaf) after partitioning in place. */
static int split(bvh *b, const prim_info *info, int first, int count, const box *nb)
{
    box cb;
    float best = FLT_MAX, leaf_cost = (float)count * box_area(nb);
    int axis, best_axis = -1, best_bin = 0, i, mid;
    box_empty(&cb);
    for (i = first; i < first + count; i++) {
        box c;
        int p = b->prims[i], k;
        const prim_info *pi = &info[p >= 0 ? p : b->s->ntris + (-p - 1)];
        for (k = 0; k < 3; k++)
            c.lo[k] = c.hi[k] = pi->c[k];
        box_grow(&cb, &c);
    }
    for (axis = 0; axis < 3; axis++) {
        box bins[BINS], left[BINS];
        int cnt[BINS], lcnt[BINS], k;
        float ext = cb.hi[axis] - cb.lo[axis], right_area, rc;
        box racc;
        if (!(ext > 0.0f))
            continue;
        for (k = 0; k < BINS; k++) {
            box_empty(&bins[k]);
            cnt[k] = 0;
        }
        for (i = first; i < first + count; i++) {
            int p = b->prims[i];
            const prim_info *pi = &info[p >= 0 ? p : b->s->ntris + (-p - 1)];
            k = (int)((pi->c[axis] - cb.lo[axis]) / ext * BINS);
            if (k >= BINS) k = BINS - 1;
            box_grow(&bins[k], &pi->b);
            cnt[k]++;
        }
        box_empty(&left[0]);
        box_grow(&left[0], &bins[0]);
        lcnt[0] = cnt[0];
        for (k = 1; k < BINS; k++) {
            left[k] = left[k - 1];
            box_grow(&left[k], &bins[k]);
            lcnt[k] = lcnt[k - 1] + cnt[k];
        }
        box_empty(&racc);
        rc = 0.0f;
        for (k = BINS - 1; k > 0; k--) {
            float cost;
            box_grow(&racc, &bins[k]);
            rc += (float)cnt[k];
            right_area = box_area(&racc);
            cost = (float)lcnt[k - 1] * box_area(&left[k - 1]) + rc * right_area;
            if (lcnt[k - 1] > 0 && rc > 0.0f && cost < best) {
                best = cost;
                best_axis = axis;
                best_bin = k;
            }
        }
    }
    if (best_axis < 0 || (count <= LEAF_MAX && best >= leaf_cost))
        return 0;
    mid = first;
    for (i = first; i < first + count; i++) {
        int p = b->prims[i], k;
        const prim_info *pi = &info[p >= 0 ? p : b->s->ntris + (-p - 1)];
        float ext = cb.hi[best_axis] - cb.lo[best_axis];
        k = (int)((pi->c[best_axis] - cb.lo[best_axis]) / ext * BINS);
        if (k >= BINS) k = BINS - 1;
        if (k < best_bin) {
            b->prims[i] = b->prims[mid];
            b->prims[mid++] = p;
        }
    }
    return mid - first;
}

/* Depth stays below the traversal stack's size: deeper ranges become leaves. */
static void build_node(bvh *b, const prim_info *info, int node, int first, int count,
                       int depth)
{
    bvh_node *n = &b->nodes[node];
    box nb;
    int i, left;
    box_empty(&nb);
    for (i = first; i < first + count; i++) {
        int p = b->prims[i];
        box_grow(&nb, &info[p >= 0 ? p : b->s->ntris + (-p - 1)].b);
    }
    memcpy(n->lo, nb.lo, sizeof nb.lo);
    memcpy(n->hi, nb.hi, sizeof nb.hi);
    left = count > 1 && depth < STACK - 4 ? split(b, info, first, count, &nb) : 0;
    if (left == 0) {
        n->first = first;
        n->count = count;
        return;
    }
    n->first = b->nnodes;
    n->count = 0;
    b->nnodes += 2;
    build_node(b, info, n->first, first, left, depth + 1);
    build_node(b, info, b->nodes[node].first + 1, first + left, count - left, depth + 1);
}

int bvh_build(bvh *b, const scene *s)
{
    prim_info *info;
    int i, n = s->ntris + s->nspheres;
    memset(b, 0, sizeof *b);
    b->s = s;
    b->nprims = n;
    b->prims = malloc(sizeof(int) * (size_t)(n > 0 ? n : 1));
    b->nodes = malloc(sizeof(bvh_node) * (size_t)(2 * n + 1));
    info = malloc(sizeof(prim_info) * (size_t)(n > 0 ? n : 1));
    if (!b->prims || !b->nodes || !info) {
        free(info);
        bvh_free(b);
        return -1;
    }
    for (i = 0; i < s->ntris; i++) {
        b->prims[i] = i;
        prim_bounds(s, i, &info[i]);
    }
    for (i = 0; i < s->nspheres; i++) {
        b->prims[s->ntris + i] = -(i + 1);
        prim_bounds(s, -(i + 1), &info[s->ntris + i]);
    }
    b->nnodes = 1;
    if (n > 0) {
        build_node(b, info, 0, 0, n, 0);
    } else {
        box_empty((box *)(void *)b->nodes[0].lo);
        b->nodes[0].first = 0;
        b->nodes[0].count = 0;
    }
    free(info);
    return 0;
}

void bvh_free(bvh *b)
{
    if (b->rays.release)
        b->rays.release(b->rays.ctx);
    free(b->nodes);
    free(b->prims);
    memset(b, 0, sizeof *b);
}

/* Moller-Trumbore; with `plane` set, the triangle's plane (barycentrics
 * unbounded). */
static int hit_tri(const triangle *t, const float o[3], const float d[3], float tmin,
                   float tmax, float *tt, float *uu, float *vv, int plane)
{
    float e1[3], e2[3], pv[3], tv[3], qv[3], det, inv, u, v, th;
    int i;
    for (i = 0; i < 3; i++) {
        e1[i] = t->v[1][i] - t->v[0][i];
        e2[i] = t->v[2][i] - t->v[0][i];
        tv[i] = o[i] - t->v[0][i];
    }
    pv[0] = d[1] * e2[2] - d[2] * e2[1];
    pv[1] = d[2] * e2[0] - d[0] * e2[2];
    pv[2] = d[0] * e2[1] - d[1] * e2[0];
    det = e1[0] * pv[0] + e1[1] * pv[1] + e1[2] * pv[2];
    if (det == 0.0f)
        return 0;
    inv = 1.0f / det;
    u = (tv[0] * pv[0] + tv[1] * pv[1] + tv[2] * pv[2]) * inv;
    if (!plane && (u < 0.0f || u > 1.0f))
        return 0;
    qv[0] = tv[1] * e1[2] - tv[2] * e1[1];
    qv[1] = tv[2] * e1[0] - tv[0] * e1[2];
    qv[2] = tv[0] * e1[1] - tv[1] * e1[0];
    v = (d[0] * qv[0] + d[1] * qv[1] + d[2] * qv[2]) * inv;
    if (!plane && (v < 0.0f || u + v > 1.0f))
        return 0;
    th = (e2[0] * qv[0] + e2[1] * qv[1] + e2[2] * qv[2]) * inv;
    if (!(th > tmin && th < tmax))
        return 0;
    *tt = th;
    *uu = u;
    *vv = v;
    return 1;
}

/* The nearer root of |o + t d - c| = r in the form that does not cancel,
 * else the farther one (origin inside). */
static int hit_sphere(const sphere *s, const float o[3], const float d[3], float tmin,
                      float tmax, float *tt)
{
    double oc[3], b, c, disc, q, t0, t1, dd;
    int i;
    for (i = 0; i < 3; i++)
        oc[i] = (double)o[i] - s->c[i];
    dd = (double)d[0] * d[0] + (double)d[1] * d[1] + (double)d[2] * d[2];
    b = oc[0] * d[0] + oc[1] * d[1] + oc[2] * d[2];
    c = oc[0] * oc[0] + oc[1] * oc[1] + oc[2] * oc[2] - (double)s->r * s->r;
    disc = b * b - dd * c;
    if (disc < 0.0)
        return 0;
    q = -(b + (b >= 0.0 ? sqrt(disc) : -sqrt(disc)));
    t0 = q / dd;
    t1 = q != 0.0 ? c / q : t0;
    if (t0 > t1) {
        double x = t0;
        t0 = t1;
        t1 = x;
    }
    if (t0 > tmin && t0 < tmax) {
        *tt = (float)t0;
        return 1;
    }
    if (t1 > tmin && t1 < tmax) {
        *tt = (float)t1;
        return 1;
    }
    return 0;
}

static int hit_prim(const scene *s, int p, const float o[3], const float d[3], float tmin,
                    float tmax, bvh_hit *h, int plane)
{
    float t, u = 0.0f, v = 0.0f;
    int ok = p >= 0 ? hit_tri(&s->tris[p], o, d, tmin, tmax, &t, &u, &v, plane)
                    : hit_sphere(&s->spheres[-p - 1], o, d, tmin, tmax, &t);
    if (ok) {
        h->t = t;
        h->prim = p;
        h->u = u;
        h->v = v;
    }
    return ok;
}

static int hit_box(const bvh_node *n, const float o[3], const float inv[3], float tmin,
                   float tmax, float *tnear)
{
    int i;
    for (i = 0; i < 3; i++) {
        float t0 = (n->lo[i] - o[i]) * inv[i], t1 = (n->hi[i] - o[i]) * inv[i];
        if (t0 > t1) {
            float x = t0;
            t0 = t1;
            t1 = x;
        }
        /* NaN from 0 * inf (origin on a slab plane) must not cull. */
        if (t0 > tmin) tmin = t0;
        if (t1 < tmax) tmax = t1;
    }
    *tnear = tmin;
    return tmin <= tmax;
}

static int traverse(const bvh *b, const float o[3], const float d[3], float tmin,
                    float tmax, bvh_hit *h, int any)
{
    int stack[STACK], sp = 0, node = 0, found = 0, i;
    float inv[3], tn;
    for (i = 0; i < 3; i++)
        inv[i] = 1.0f / d[i];
    if (b->nprims == 0 || !hit_box(&b->nodes[0], o, inv, tmin, tmax, &tn))
        return 0;
    for (;;) {
        const bvh_node *n = &b->nodes[node];
        if (n->count > 0) {
            for (i = n->first; i < n->first + n->count; i++)
                if (hit_prim(b->s, b->prims[i], o, d, tmin, tmax, h, 0)) {
                    found = 1;
                    if (any)
                        return 1;
                    tmax = h->t;
                }
        } else {
            float t0, t1;
            int a = n->first, c = n->first + 1;
            int h0 = hit_box(&b->nodes[a], o, inv, tmin, tmax, &t0);
            int h1 = hit_box(&b->nodes[c], o, inv, tmin, tmax, &t1);
            if (h0 && h1) {
                if (t1 < t0) {
                    int x = a;
                    a = c;
                    c = x;
                }
                stack[sp++] = c; /* depth < STACK - 4 bounds sp */
                node = a;
                continue;
            }
            if (h0 || h1) {
                node = h0 ? a : c;
                continue;
            }
        }
        if (sp == 0)
            return found;
        node = stack[--sp];
    }
}

/* The spheres by a loop, behind another tracer's triangles (few, if any). */
static int spheres(const scene *s, const float o[3], const float d[3], float tmin, float tmax,
                   bvh_hit *h, int any)
{
    int i, found = 0;
    for (i = 1; i <= s->nspheres; i++)
        if (hit_prim(s, -i, o, d, tmin, tmax, h, 0)) {
            found = 1;
            if (any)
                return 1;
            tmax = h->t;
        }
    return found;
}

int bvh_intersect(const bvh *b, const float o[3], const float d[3], float tmin,
                  float tmax, bvh_hit *h)
{
    int found;
    if (!b->rays.intersect)
        return traverse(b, o, d, tmin, tmax, h, 0);
    found = b->rays.intersect(b->rays.ctx, o, d, tmin, tmax, h);
    return spheres(b->s, o, d, tmin, found ? h->t : tmax, h, 0) || found;
}

int bvh_occluded(const bvh *b, const float o[3], const float d[3], float tmin, float tmax)
{
    bvh_hit h;
    if (!b->rays.occluded)
        return traverse(b, o, d, tmin, tmax, &h, 1);
    return b->rays.occluded(b->rays.ctx, o, d, tmin, tmax) ||
           spheres(b->s, o, d, tmin, tmax, &h, 1);
}

int brute_intersect(const scene *s, const float o[3], const float d[3], float tmin,
                    float tmax, bvh_hit *h)
{
    int i, found = 0;
    for (i = -s->nspheres; i < s->ntris; i++) /* spheres are -(k + 1) */
        if (hit_prim(s, i, o, d, tmin, tmax, h, 0)) {
            found = 1;
            tmax = h->t;
        }
    return found;
}

int hit_surface_of(const scene *s, int prim, const float o[3], const float d[3], bvh_hit *h)
{
    return hit_prim(s, prim, o, d, 0.0f, FLT_MAX, h, 1);
}
