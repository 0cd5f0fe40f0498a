/*
 * sampling.c -- the quad-tree of squares that places adaptive samples, and
 * the image rebuilt from them (sampling.h).
 */
#include "sampling.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

typedef struct ad_square {
    float x, y, side;  /* centre and side, pixels */
    int sample;        /* its sample */
    int edge;          /* on an object boundary: split before the rest */
    float jump;        /* a region boundary's: |delta luminance| / side, a
                          floor under its sample's importance */
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
    int *pos;          /* sample -> heap slot of the square it centres, or
                          -1 (one live square a sample at most) */
    int *at;           /* open addressing on position: sample index or -1 */
    unsigned mask;     /* its size - 1 (a power of two, >= 2 cap) */
} ad_state;

/* Where a sample for the point (x, y) goes: there, or (at_pixels) at the
 * centre of the pixel holding it (the lower right one when (x, y) is a
 * pixel corner), kept inside the image. */
static void place(const ad_opts *o, float *x, float *y)
{
    if (!o->at_pixels)
        return;
    *x = floorf(*x) + 0.5f;
    *y = floorf(*y) + 0.5f;
    if (*x > (float)o->width - 0.5f) *x = (float)o->width - 0.5f;
    if (*y > (float)o->height - 0.5f) *y = (float)o->height - 0.5f;
}

/* The table slot that holds the sample at (x, y), or the empty one where
 * it would go. */
static unsigned slot_of(const ad_state *a, float x, float y)
{
    unsigned h = (unsigned)(long)(4.0f * x) * 0x9e3779b1u ^ (unsigned)(long)(4.0f * y) * 0x85ebca77u;
    for (h = (h ^ h >> 15) & a->mask; a->at[h] >= 0; h = (h + 1) & a->mask)
        if (a->s[a->at[h]].x == x && a->s[a->at[h]].y == y)
            break;
    return h;
}

/* The sample already at (x, y), or -1. */
static int find_sample(const ad_state *a, float x, float y)
{
    return a->at[slot_of(a, x, y)];
}

/* The sample at (x, y) after place(): one already there (squares of two
 * pixels share theirs with a child, border samples with the squares along
 * the border), or a new one, evaluated.  Returns its index or the
 * evaluator's negative value. */
static int add_sample(ad_state *a, float x, float y)
{
    ad_sample *t;
    unsigned h;
    int st;
    place(a->o, &x, &y);
    h = slot_of(a, x, y);
    if (a->at[h] >= 0)
        return a->at[h];
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
    a->at[h] = a->n;
    return a->n++;
}

static double priority(const ad_state *a, const ad_square *q)
{
    if (q->side <= a->o->min_side)
        return -1.0; /* never split */
    if (q->edge) /* before the rest, larger squares first */
        return 1e30 * q->side;
    return (double)fmaxf(a->s[q->sample].importance, q->jump) * q->side * q->side;
}

/* Heap slot i gets q; pos follows each live square's sample. */
static void heap_set(ad_state *a, int i, ad_square q)
{
    a->q[i] = q;
    a->pos[q.sample] = i;
}

static void sift_up(ad_state *a, int i)
{
    const ad_square q = a->q[i];
    while (i > 0 && a->q[(i - 1) / 2].priority < q.priority) {
        heap_set(a, i, a->q[(i - 1) / 2]);
        i = (i - 1) / 2;
    }
    heap_set(a, i, q);
}

static void heap_push(ad_state *a, ad_square q)
{
    q.priority = priority(a, &q);
    a->q[a->nq] = q;
    sift_up(a, a->nq++);
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
        heap_set(a, i, a->q[c]);
        i = c;
    }
    if (a->nq > 0)
        heap_set(a, i, last);
    a->pos[top.sample] = -1;
    return top;
}

static float luma(const ad_sample *s)
{
    return 0.2126f * s->rgb[0] + 0.7152f * s->rgb[1] + 0.0722f * s->rgb[2];
}

/* Square q (not in the heap yet) against sample b: another object makes
 * it an edge; another region of the same object (a shadow edge between
 * them) gives it the luminance jump over its side, the mass of the delta
 * a region boundary puts into the gradient (Eq. 34, first-order paper)
 * spread over the square, as a floor under its importance.  With
 * both_ways, b's own square, if it waits in the heap, gets the same and
 * moves up: a boundary is found from whichever side is sampled second. */
static void compare(ad_state *a, ad_square *q, int b, int both_ways)
{
    const ad_sample *me = &a->s[q->sample], *o = &a->s[b];
    ad_square *n = both_ways && a->pos[b] >= 0 ? &a->q[a->pos[b]] : NULL;
    float j;
    if (me->object != o->object) {
        q->edge = 1;
        if (n)
            n->edge = 1;
    } else if (me->region != o->region) {
        j = fabsf(luma(me) - luma(o));
        q->jump = fmaxf(q->jump, j / q->side);
        if (n)
            n->jump = fmaxf(n->jump, j / n->side);
    }
    if (n) {
        n->priority = priority(a, n);
        sift_up(a, a->pos[b]);
    }
}

/* q against the samples of the squares of its size beside it, where they
 * exist. */
static void compare_neighbours(ad_state *a, ad_square *q)
{
    int k;
    for (k = 0; k < 4; k++) {
        const ad_sample *me = &a->s[q->sample];
        const int i = find_sample(a, me->x + (k == 0 ? -q->side : k == 1 ? q->side : 0.0f),
                                  me->y + (k == 2 ? -q->side : k == 3 ? q->side : 0.0f));
        if (i >= 0 && i != q->sample)
            compare(a, q, i, 1);
    }
}

/* The first squares, one a block, and the border samples: block corners
 * along the image's edges.  A block whose sample sees another object
 * than a neighbouring block's is on a boundary. */
static int first_squares(ad_state *a)
{
    const int b = a->o->block, bw = a->o->width / b, bh = a->o->height / b;
    int i, j, st;
    for (j = 0; j <= bh; j++)
        for (i = 0; i <= bw; i++)
            if ((i == 0 || i == bw || j == 0 || j == bh) &&
                (st = add_sample(a, (float)(i * b), (float)(j * b))) < 0)
                return st;
    for (j = 0; j < bh; j++)
        for (i = 0; i < bw; i++) {
            ad_square q;
            memset(&q, 0, sizeof q);
            q.x = (float)(i * b) + 0.5f * (float)b;
            q.y = (float)(j * b) + 0.5f * (float)b;
            q.side = (float)b;
            if ((q.sample = add_sample(a, q.x, q.y)) < 0)
                return q.sample;
            compare_neighbours(a, &q);
            heap_push(a, q);
        }
    return 0;
}

/* Splits the most important square into four, each with a sample at its
 * centre.  A child is on a boundary when it sees another object than a
 * sibling beside it, the square or a neighbour of its size: the boundary
 * runs through it or along it. */
static int split(ad_state *a)
{
    const ad_square q = heap_pop(a);
    ad_square c[4];
    int k;
    for (k = 0; k < 4; k++) {
        memset(&c[k], 0, sizeof c[k]);
        c[k].side = 0.5f * q.side;
        c[k].x = q.x + (k & 1 ? 0.25f : -0.25f) * q.side;
        c[k].y = q.y + (k & 2 ? 0.25f : -0.25f) * q.side;
        if ((c[k].sample = add_sample(a, c[k].x, c[k].y)) < 0)
            return c[k].sample;
    }
    for (k = 0; k < 4; k++) {
        compare(a, &c[k], c[k ^ 1].sample, 0);
        compare(a, &c[k], c[k ^ 2].sample, 0);
        if (q.sample != c[k].sample)
            compare(a, &c[k], q.sample, 0);
        compare_neighbours(a, &c[k]);
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
        !(o->min_side == 1.0f || o->min_side == 0.5f || o->min_side == 0.25f) ||
        (o->at_pixels && o->min_side != 1.0f))
        return -1;
    budget = (int)(o->budget * o->width * o->height);
    memset(&a, 0, sizeof a);
    a.o = o;
    a.eval = eval;
    a.ctx = ctx;
    /* Every split adds 3 squares and 4 samples; the first pass adds the
     * blocks and the border. */
    a.cap = budget + 4 + (o->width / o->block + 1) * (o->height / o->block + 1) * 2;
    for (a.mask = 1; a.mask < 2u * (unsigned)a.cap; a.mask *= 2)
        ;
    a.s = malloc(sizeof *a.s * (size_t)a.cap);
    a.q = malloc(sizeof *a.q * (size_t)a.cap);
    a.at = malloc(sizeof *a.at * (size_t)a.mask);
    a.pos = malloc(sizeof *a.pos * (size_t)a.cap);
    if (!a.s || !a.q || !a.at || !a.pos) {
        free(a.s);
        free(a.q);
        free(a.at);
        free(a.pos);
        return -1;
    }
    memset(a.at, 0xff, sizeof *a.at * (size_t)a.mask);
    memset(a.pos, 0xff, sizeof *a.pos * (size_t)a.cap);
    a.mask--;
    st = first_squares(&a);
    while (st == 0 && a.n < budget && a.nq > 0 && a.q[0].priority >= 0.0 && a.n + 4 <= a.cap)
        st = split(&a);
    free(a.q);
    free(a.at);
    free(a.pos);
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
    float lo[2] = {HUGE_VALF, HUGE_VALF}, hi[2] = {-HUGE_VALF, -HUGE_VALF};
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
        lo[0] = fminf(lo[0], s[i].x);
        lo[1] = fminf(lo[1], s[i].y);
        hi[0] = fmaxf(hi[0], s[i].x);
        hi[1] = fmaxf(hi[1], s[i].y);
    }
    if (lo[0] > 0.5f || lo[1] > 0.5f || hi[0] < (float)width - 0.5f ||
        hi[1] < (float)height - 0.5f)
        st = -1; /* some pixel centre outside */
    for (i = 0; i < n; i++) {
        const float x = s[i].x, y = s[i].y;
        if (x == lo[0] && y == lo[1]) corner[0] = i;
        if (x == hi[0] && y == lo[1]) corner[1] = i;
        if (x == hi[0] && y == hi[1]) corner[2] = i;
        if (x == lo[0] && y == hi[1]) corner[3] = i;
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
