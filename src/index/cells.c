/*
 * cells.c -- the index's cells and pools (index.c): a cube from its path,
 * a record's box in integer units and the level it is placed at, the
 * nodes a box overlaps, and the references and node blocks taken from the
 * block's pools.
 */
#include "../block/cache.h"
#include "cells.h"
#include "index.h"
#include "layout.h"

#define IRC__FRONT 8 /* cells a box can overlap at one depth */

void irc__node_empty(irc__node *n)
{
    n->child = 0;
    n->head = IRC__NIL;
    n->reach = -1.0f;
}

void irc__root_cube(const irc_cache *c, irc__cube *q)
{
    q->c[0] = irc__st(c)->root_c[0];
    q->c[1] = irc__st(c)->root_c[1];
    q->c[2] = irc__st(c)->root_c[2];
    q->h = irc__st(c)->root_h;
}

/* The cube of the cell of depth d with low corner lo (units). */
void irc__cell_cube(const irc_cache *c, const int64_t lo[3], int d, irc__cube *q)
{
    const double unit = 2.0 * irc__st(c)->root_h * 0x1p-58;
    int i;
    q->h = IRC_LDEXP(irc__st(c)->root_h, -d);
    for (i = 0; i < 3; i++)
        q->c[i] = irc__st(c)->root_c[i] - irc__st(c)->root_h + (double)lo[i] * unit + q->h;
}

/* The half edge of the box a record of this reach is placed by: wider
 * than the reach by what the roundings need (index.c's file comment). */
double irc__half(const float p[3], double reach)
{
    double m = IRC_FABS((double)p[0]);
    if (IRC_FABS((double)p[1]) > m) m = IRC_FABS((double)p[1]);
    if (IRC_FABS((double)p[2]) > m) m = IRC_FABS((double)p[2]);
    return reach * (1.0 + 1e-5) + m * 1e-6 + 1e-30;
}

/* floor((x - lo) K) in units for the root's low corner lo, K = 2^57 / h:
 * x K is exact in double (a power of two), lo K an exact integer
 * (irc__index_root_sane), so the floor is the one a lookup's point takes
 * (query.c); (x - lo) K would round to lo's precision.  Clamped to 2^61
 * units (8 root edges) either side of lo K, far outside the root: the
 * clamp is relative, since a root may lie 33 half edges from the origin,
 * where x K itself passes 2^62 (a clamp of x K at 2^61 put every box of
 * a scene at 1000 outside the root, and every record in its one list);
 * |lo K| + 2^61 < 2^63 converts. */
static int64_t irc__units(double x, double k, double lok)
{
    double v = IRC_FLOOR(x * k);
    v = v < lok - 0x1p61 ? lok - 0x1p61 : v > lok + 0x1p61 ? lok + 0x1p61 : v;
    return (int64_t)v - (int64_t)lok;
}

/* The box clipped to the root (inside: it needed no clipping). */
void irc__box_of(const irc_cache *c, const float p[3], double half, irc__box *b)
{
    const double k = 0x1p57 / irc__st(c)->root_h; /* units a length */
    const int64_t top = IRC__ONE - 1;
    int i;
    b->inside = 1;
    for (i = 0; i < 3; i++) {
        const double lok = (irc__st(c)->root_c[i] - irc__st(c)->root_h) * k;
        const int64_t x0 = irc__units((double)p[i] - half, k, lok),
                      x1 = irc__units((double)p[i] + half, k, lok),
                      xc = irc__units((double)p[i], k, lok);
        b->inside &= x0 >= 0 && x1 <= top;
        b->lo[i] = x0 < 0 ? 0 : x0 > top ? top : x0;
        b->hi[i] = x1 < 0 ? 0 : x1 > top ? top : x1;
        b->at[i] = xc < 0 ? 0 : xc > top ? top : xc;
    }
}

/* The deepest level whose cells' edge is at least the box's 2 half: the
 * box then overlaps at most two a side. */
int irc__level(const irc_cache *c, double half, int cap)
{
    double h = irc__st(c)->root_h;
    int d = 0;
    while (d < cap && 0.5 * h >= half) {
        h *= 0.5;
        d++;
    }
    return d;
}

/* Sets a reference's position and reach in the steps of cube q's frame,
 * the position rounded to the nearest step (at most half a step off per
 * axis) and the reach up, so a query's test on references (query.c) can
 * only admit more than the exact test. */
void irc__quantize(irc__ref *e, const irc__cube *q, const float p[3], double reach)
{
    const double inv = 16383.75 / q->h, r = -IRC_FLOOR(-reach * inv);
    int i, in = r < (double)IRC__IX_ANY;
    for (i = 0; i < 3; i++)
        in &= IRC_FABS((double)p[i] - q->c[i]) <= 2.0 * q->h;
    if (!in) {
        e->q[0] = e->q[1] = e->q[2] = 0;
        e->rq = IRC__IX_ANY;
        return;
    }
    for (i = 0; i < 3; i++)
        e->q[i] = (uint16_t)IRC_FLOOR(((double)p[i] - (q->c[i] - 2.0 * q->h)) * inv + 0.5);
    e->rq = (uint16_t)r;
}

/* References an insertion may take beyond the one kept for it. */
uint32_t irc__spare(const irc_cache *c)
{
    const irc__state *h = irc__st(c);
    return c->ref_cap - h->refs_live - (c->capacity - h->indexed);
}

static uint32_t irc__ref_take(irc_cache *c)
{
    irc__state *h = irc__st(c);
    uint32_t r = h->ref_free;
    if (r != IRC__NIL)
        h->ref_free = irc__refs(c)[r].next;
    else
        r = h->refs_used++;
    h->refs_live++;
    h->refs_taken++;
    return r;
}

void irc__ref_give(irc_cache *c, uint32_t r)
{
    irc__refs(c)[r].next = irc__st(c)->ref_free;
    irc__st(c)->ref_free = r;
    irc__st(c)->refs_live--;
}

/* The reach a reference of id bounds: its radius's now, which neighbour
 * clamping may have shrunk since the record was placed by the reach in
 * its entry (test_index_reach_tight). */
double irc__reach_now(const irc_cache *c, uint32_t id)
{
    const float now = irc__reach(c, irc__rec_at(c, id)->r), placed = irc__ix(c)[id].reach;
    return (double)(now < placed ? now : placed);
}

/* A new reference to id at the head of node's list, whose cube is q. */
void irc__ref_push(irc_cache *c, uint32_t node, const irc__cube *q, uint32_t id,
                   int home)
{
    const uint32_t r = irc__ref_take(c);
    irc__ref *e = &irc__refs(c)[r];
    irc__node *n = &irc__nodes(c)[node];
    uint32_t *link = &n->head;
    irc__quantize(e, q, irc__rec_at(c, id)->p, irc__reach_now(c, id));
    e->id = id | (home ? IRC__REF_HOME : 0u);
    /* A list holds its homes first, so that range walks, which take only
     * homes, stop at the first reference that is not one (query.c). */
    while (!home && *link != IRC__NIL && (irc__refs(c)[*link].id & IRC__REF_HOME))
        link = &irc__refs(c)[*link].next;
    e->next = *link;
    *link = r;
}

/* Calls fn on the nodes a box overlaps down to depth L: every one (all
 * set) or those where its references go, the leaves above L and the
 * nodes of depth L.  Depth by depth, at most IRC__FRONT at each (a box no
 * wider than the cells of its level overlaps at most 8). */
void irc__cover(irc_cache *c, const irc__box *b, int L, int all, irc__cell_fn fn,
                void *ud)
{
    irc__cell f[2][IRC__FRONT];
    int nf = 1, cur = 0, d;
    f[0][0].node = 0;
    f[0][0].lo[0] = f[0][0].lo[1] = f[0][0].lo[2] = 0;
    for (d = 0; nf; d++, cur ^= 1) {
        int nn = 0, k;
        for (k = 0; k < nf; k++) {
            const irc__cell *x = &f[cur][k];
            const irc__node *n = &irc__nodes(c)[x->node];
            const int64_t e = IRC__ONE >> (d + 1);
            unsigned oct, mask;
            if (all || d >= L || !n->child)
                fn(c, x, d, ud);
            if (d >= L || !n->child || d >= IRC__LEVELS)
                continue;
            for (mask = irc__overlapped(x, d, b); mask && nn < IRC__FRONT; mask &= mask - 1u) {
                irc__cell *y = &f[cur ^ 1][nn++];
                int i;
                for (oct = 0; !(mask >> oct & 1u); oct++)
                    ;
                for (i = 0; i < 3; i++)
                    y->lo[i] = x->lo[i] + ((oct >> i & 1) ? e : 0);
                y->node = n->child + oct;
            }
        }
        nf = nn;
    }
}

int irc__holds(const irc__cell *x, int d, const int64_t at[3])
{
    const int64_t e = IRC__ONE >> d;
    return at[0] - x->lo[0] < e && at[1] - x->lo[1] < e && at[2] - x->lo[2] < e &&
           at[0] >= x->lo[0] && at[1] >= x->lo[1] && at[2] >= x->lo[2];
}

uint32_t irc__list_len(const irc_cache *c, uint32_t r, uint32_t limit)
{
    uint32_t n = 0;
    for (; r != IRC__NIL && n < limit; r = irc__refs(c)[r].next)
        n++;
    return n;
}

uint32_t irc__block_alloc(irc_cache *c)
{
    uint32_t b = irc__st(c)->nodes_used, i;
    if (c->node_cap - b < 8u)
        return 0;
    for (i = 0; i < 8; i++)
        irc__node_empty(&irc__nodes(c)[b + i]);
    irc__st(c)->nodes_used += 8;
    return b;
}

/* The children of cell x (depth d) that box b overlaps, as bits. */
unsigned irc__overlapped(const irc__cell *x, int d, const irc__box *b)
{
    /* per axis, which halves the box meets (bit 0 the lower, 1 the
     * upper); a child is met where its halves are on all three axes */
    static const unsigned char spread[4][3] = {{0x00, 0x00, 0x00}, {0x55, 0x33, 0x0f},
                                               {0xaa, 0xcc, 0xf0}, {0xff, 0xff, 0xff}};
    const int64_t e = IRC__ONE >> (d + 1);
    unsigned mask = 0xffu;
    int i;
    for (i = 0; i < 3; i++) {
        const int64_t mid = x->lo[i] + e;
        const unsigned halves = (unsigned)(b->lo[i] < mid && b->hi[i] >= x->lo[i]) |
                                (unsigned)(b->lo[i] < mid + e && b->hi[i] >= mid) << 1;
        mask &= spread[halves][i];
    }
    return mask;
}

unsigned irc__popcount(unsigned m)
{
    unsigned n = 0;
    for (; m; m &= m - 1)
        n++;
    return n;
}
