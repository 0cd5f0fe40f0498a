/*
 * adaptive.c -- the quad-tree of squares that places adaptive samples, and
 * the image rebuilt from them (adaptive.h).
 */
#include "adaptive.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

typedef struct ad_square {
    float x, y, side;  /* centre and side, pixels */
    int sample;        /* its sample */
    int edge;          /* on an object boundary: split before the rest */
    double priority;
} ad_square;

typedef struct ad_state {
    const ad_opts *o;
    ad_eval_fn eval;
    void *ctx;
    ad_sample *s;
    int n, cap;
    ad_square *q;      /* a max-heap by priority; a square a sample at most,
                          so cap bounds it too */
    int nq;
} ad_state;

static int add_sample(ad_state *a, float x, float y)
{
    ad_sample *t;
    int st;
    if (a->n == a->cap)
        return -1;
    t = &a->s[a->n];
    memset(t, 0, sizeof *t);
    t->x = x;
    t->y = y;
    if ((st = a->eval(a->ctx, t)) < 0)
        return st;
    if (!(t->importance >= 0.0f))
        t->importance = 0.0f;
    return a->n++;
}

static double priority(const ad_state *a, const ad_square *q)
{
    if (q->side <= a->o->min_side)
        return -1.0; /* never split */
    if (q->edge)
        return HUGE_VAL;
    return (double)a->s[q->sample].importance * q->side * q->side;
}

static void heap_push(ad_state *a, ad_square q)
{
    int i = a->nq++;
    q.priority = priority(a, &q);
    while (i > 0 && a->q[(i - 1) / 2].priority < q.priority) {
        a->q[i] = a->q[(i - 1) / 2];
        i = (i - 1) / 2;
    }
    a->q[i] = q;
}

static ad_square heap_pop(ad_state *a)
{
    ad_square top = a->q[0], last = a->q[--a->nq];
    int i = 0;
    for (;;) {
        int c = 2 * i + 1;
        if (c >= a->nq)
            break;
        if (c + 1 < a->nq && a->q[c + 1].priority > a->q[c].priority)
            c++;
        if (a->q[c].priority <= last.priority)
            break;
        a->q[i] = a->q[c];
        i = c;
    }
    if (a->nq > 0)
        a->q[i] = last;
    return top;
}

/* The first squares, one a block, and the border samples: block corners
 * along the image's edges.  A block whose sample sees another object
 * than a neighbouring block's is on a boundary. */
static int first_squares(ad_state *a)
{
    const int b = a->o->block, bw = a->o->width / b, bh = a->o->height / b;
    ad_square *grid = malloc(sizeof *grid * (size_t)bw * (size_t)bh);
    int i, j, k, st;
    if (!grid)
        return -1;
    for (j = 0; j <= bh; j++)
        for (i = 0; i <= bw; i++)
            if ((i == 0 || i == bw || j == 0 || j == bh) &&
                (st = add_sample(a, (float)(i * b), (float)(j * b))) < 0) {
                free(grid);
                return st;
            }
    for (j = 0; j < bh; j++)
        for (i = 0; i < bw; i++) {
            ad_square *q = &grid[j * bw + i];
            q->x = (float)(i * b) + 0.5f * (float)b;
            q->y = (float)(j * b) + 0.5f * (float)b;
            q->side = (float)b;
            q->edge = 0;
            if ((q->sample = add_sample(a, q->x, q->y)) < 0) {
                st = q->sample;
                free(grid);
                return st;
            }
        }
    for (k = 0; k < bw * bh; k++) {
        const int i0 = k % bw, j0 = k / bw, obj = a->s[grid[k].sample].object;
        if ((i0 > 0 && a->s[grid[k - 1].sample].object != obj) ||
            (i0 + 1 < bw && a->s[grid[k + 1].sample].object != obj) ||
            (j0 > 0 && a->s[grid[k - bw].sample].object != obj) ||
            (j0 + 1 < bh && a->s[grid[k + bw].sample].object != obj))
            grid[k].edge = 1;
        heap_push(a, grid[k]);
    }
    free(grid);
    return 0;
}

/* Splits the most important square into four, each with a sample at its
 * centre.  A child is on a boundary when it sees another object than a
 * sibling beside it or than the square did: the boundary runs through it
 * or along it.  A square split for a boundary its children do not see
 * (one found between blocks) passes nothing on. */
static int split(ad_state *a)
{
    const ad_square q = heap_pop(a);
    ad_square c[4];
    int k, obj[4];
    for (k = 0; k < 4; k++) {
        c[k].side = 0.5f * q.side;
        c[k].x = q.x + (k & 1 ? 0.25f : -0.25f) * q.side;
        c[k].y = q.y + (k & 2 ? 0.25f : -0.25f) * q.side;
        if ((c[k].sample = add_sample(a, c[k].x, c[k].y)) < 0)
            return c[k].sample;
        obj[k] = a->s[c[k].sample].object;
    }
    for (k = 0; k < 4; k++) {
        c[k].edge = obj[k] != obj[k ^ 1] || obj[k] != obj[k ^ 2] ||
                    obj[k] != a->s[q.sample].object;
        heap_push(a, c[k]);
    }
    return 0;
}

int adaptive_sample(const ad_opts *o, ad_eval_fn eval, void *ctx, ad_sample **out, int *count)
{
    ad_state a;
    int st, budget;
    *out = NULL;
    *count = 0;
    if (o->block < 1 || o->width < o->block || o->height < o->block ||
        o->width % o->block || o->height % o->block || !(o->budget > 0.0) ||
        !(o->min_side == 1.0f || o->min_side == 0.5f || o->min_side == 0.25f))
        return -1;
    budget = (int)(o->budget * o->width * o->height);
    memset(&a, 0, sizeof a);
    a.o = o;
    a.eval = eval;
    a.ctx = ctx;
    /* Every split adds 3 squares and 4 samples; the first pass adds the
     * blocks and the border. */
    a.cap = budget + 4 + (o->width / o->block + 1) * (o->height / o->block + 1) * 2;
    a.s = malloc(sizeof *a.s * (size_t)a.cap);
    a.q = malloc(sizeof *a.q * (size_t)a.cap);
    if (!a.s || !a.q) {
        free(a.s);
        free(a.q);
        return -1;
    }
    st = first_squares(&a);
    while (st == 0 && a.n < budget && a.nq > 0 && a.q[0].priority >= 0.0 && a.n + 4 <= a.cap)
        st = split(&a);
    free(a.q);
    if (st < 0) {
        free(a.s);
        return st;
    }
    *out = a.s;
    *count = a.n;
    return 0;
}

/* Pixel centres inside triangle (a, b, c) get its linear interpolation. */
static void raster(const ad_sample *a, const ad_sample *b, const ad_sample *c, int w, int h,
                   float *rgb)
{
    const double area = ((double)b->x - a->x) * ((double)c->y - a->y) -
                        ((double)b->y - a->y) * ((double)c->x - a->x);
    const float lo_x = fminf(a->x, fminf(b->x, c->x)), hi_x = fmaxf(a->x, fmaxf(b->x, c->x)),
                lo_y = fminf(a->y, fminf(b->y, c->y)), hi_y = fmaxf(a->y, fmaxf(b->y, c->y));
    int x0 = (int)floorf(lo_x - 0.5f), x1 = (int)ceilf(hi_x - 0.5f), y0 = (int)floorf(lo_y - 0.5f),
        y1 = (int)ceilf(hi_y - 0.5f), x, y, k;
    if (area == 0.0)
        return;
    if (x0 < 0) x0 = 0;
    if (y0 < 0) y0 = 0;
    if (x1 > w - 1) x1 = w - 1;
    if (y1 > h - 1) y1 = h - 1;
    for (y = y0; y <= y1; y++)
        for (x = x0; x <= x1; x++) {
            const double px = x + 0.5, py = y + 0.5;
            const double wa = (((double)b->x - px) * ((double)c->y - py) -
                               ((double)b->y - py) * ((double)c->x - px)) / area,
                         wb = (((double)c->x - px) * ((double)a->y - py) -
                               ((double)c->y - py) * ((double)a->x - px)) / area,
                         wc = 1.0 - wa - wb;
            if (wa < -1e-9 || wb < -1e-9 || wc < -1e-9)
                continue;
            for (k = 0; k < 3; k++)
                rgb[3 * ((size_t)y * (size_t)w + (size_t)x) + (size_t)k] =
                    (float)(wa * a->rgb[k] + wb * b->rgb[k] + wc * c->rgb[k]);
        }
}

int adaptive_reconstruct(const ad_sample *s, int n, int width, int height, float unit,
                         float *rgb)
{
    long long *xy;
    int *order, *tri = NULL, ntri = 0, i, k, st = 0, corner[4] = {-1, -1, -1, -1};
    if (n < 4 || width < 1 || height < 1 || !(unit > 0.0f && unit <= 1.0f) ||
        (double)width / unit > 8192.0 || (double)height / unit > 8192.0)
        return -1;
    xy = malloc(sizeof *xy * 2 * (size_t)n);
    order = malloc(sizeof *order * (size_t)n);
    if (!xy || !order) {
        free(xy);
        free(order);
        return -1;
    }
    /* Corners first, in cyclic order; every position on the grid of unit. */
    for (i = 0; i < n; i++) {
        const float x = s[i].x, y = s[i].y;
        if (x == 0.0f && y == 0.0f) corner[0] = i;
        if (x == (float)width && y == 0.0f) corner[1] = i;
        if (x == (float)width && y == (float)height) corner[2] = i;
        if (x == 0.0f && y == (float)height) corner[3] = i;
        if (floorf(x / unit) != x / unit || floorf(y / unit) != y / unit || x < 0.0f ||
            y < 0.0f || x > (float)width || y > (float)height)
            st = -1;
    }
    for (k = 0; k < 4; k++)
        if (corner[k] < 0)
            st = -1;
    if (st == 0) {
        int m = 4;
        for (k = 0; k < 4; k++)
            order[k] = corner[k];
        for (i = 0; i < n; i++)
            if (i != corner[0] && i != corner[1] && i != corner[2] && i != corner[3])
                order[m++] = i;
        for (i = 0; i < n; i++) {
            xy[2 * i] = (long long)(s[order[i]].x / unit);
            xy[2 * i + 1] = (long long)(s[order[i]].y / unit);
        }
        st = delaunay(xy, n, &tri, &ntri);
    }
    if (st == 0) {
        memset(rgb, 0, sizeof *rgb * 3 * (size_t)width * (size_t)height);
        for (k = 0; k < ntri; k++)
            raster(&s[order[tri[3 * k]]], &s[order[tri[3 * k + 1]]], &s[order[tri[3 * k + 2]]],
                   width, height, rgb);
    }
    free(tri);
    free(xy);
    free(order);
    return st;
}
