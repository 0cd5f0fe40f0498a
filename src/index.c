/*
 * index.c -- an octree over record positions, inside the caller's block.
 *
 * A record sits in the deepest node whose children are at least as large as
 * its reach a*R_i (a loose octree: a subtree's records reach at most one
 * node size past its cube).  Cubes lie on a power-of-two grid, so every
 * centre is exact in double and placement never depends on rounding.
 * Each node keeps the largest reach in its subtree, and a query descends
 * only into children whose cube lies within that reach of the query point,
 * which is exact: a record whose sphere holds p lies in a cube no farther
 * from p than the record's reach.  In a node's list a query tests each
 * record's index entry (cache.h, irc__ixe: position and reach in 16-bit
 * steps of the node's cube, rounded so the test admits a superset) and
 * hands over only the records that pass, for the caller's exact test.
 *
 * A leaf with more than IRC__SPLIT records splits when the node pool has a
 * block of 8 free.  The root is not tied to a grid through the origin: a
 * scene centred on the origin would otherwise need a cube that holds 0 in
 * its interior, which no cube of such a grid does, and its records would
 * pile up in the root's list.  While the root is a leaf it is resized
 * freely; when it first splits it is fitted to its records' positions
 * (not their reaches, which may be 1e30); afterwards it doubles toward
 * records that land outside it, the old root becoming one of its children.
 * Centres stay exact because the root's half edge is kept at least 1/32 of
 * its centre's largest coordinate, splits stop at depth IRC__DEPTH and
 * growth at IRC__LEVELS.
 * When the pool is spent, lists grow instead: slower, never wrong.
 */
#include "cache.h"
#include "index.h"

#ifndef IRC__SPLIT
#define IRC__SPLIT 16u
#endif
#define IRC__DEPTH 40    /* with the root's h >= |c|/32: centres within 2^45 of
                            their size, so exact in double */
/* The widest root: the walk's integer point needs a root whose half edge
 * and 2^57 over it are floats (query.c).  Records beyond it (coordinates
 * past 1e30, where a squared distance is past FLT_MAX anyway) stay in the
 * root's list, always candidates. */
#define IRC__ROOT_MAX 0x1p99

typedef struct irc__cube {
    double c[3];
    double h; /* half the edge */
} irc__cube;

static void irc__node_empty(irc__node *n)
{
    n->child = 0;
    n->head = IRC__NIL;
    n->reach = -1.0f;
}

void irc__index_reset(irc_cache *c)
{
    irc__node_empty(&irc__nodes(c)[0]);
    c->home->nodes_used = 1;
    c->home->root_set = 0;
    c->home->depth = 0;
}

static double irc__reach(const irc_cache *c, uint32_t id)
{
    return (double)c->cfg.accuracy * (double)irc__rec_at(c, id)->r;
}

static int irc__inside(const irc__cube *q, const float p[3])
{
    return IRC_FABS((double)p[0] - q->c[0]) <= q->h && IRC_FABS((double)p[1] - q->c[1]) <= q->h &&
           IRC_FABS((double)p[2] - q->c[2]) <= q->h;
}

/* The root holds no point on its upper faces.  When it grows, the old
 * root becomes a child, and a face it shares with a new sibling is its
 * lower face on every axis but those it grows up along, where it is its
 * upper face; the octant rule sends a point on a shared face to the
 * upper side.  So no record is ever where removal, following that rule,
 * would not look (test_index_grow_faces). */
static int irc__in_root(const irc__cube *q, const float p[3])
{
    int i;
    for (i = 0; i < 3; i++)
        if (!((double)p[i] >= q->c[i] - q->h && (double)p[i] < q->c[i] + q->h))
            return 0;
    return 1;
}

static int irc__octant(const irc__cube *q, const float p[3])
{
    return ((double)p[0] >= q->c[0]) | ((double)p[1] >= q->c[1]) << 1 |
           ((double)p[2] >= q->c[2]) << 2;
}

static void irc__child_cube(const irc__cube *q, int oct, irc__cube *out)
{
    int i;
    out->h = 0.5 * q->h;
    for (i = 0; i < 3; i++)
        out->c[i] = q->c[i] + (oct >> i & 1 ? out->h : -out->h);
}

/* Sets id's entry for the list of the node with cube q.  The position is
 * rounded to the nearest step (at most half a step off per axis) and the
 * reach up, so a query's test on entries (irc__scan) can only admit more
 * than the exact test. */
static void irc__quantize(const irc_cache *c, uint32_t id, const irc__cube *q, double reach)
{
    irc__ixe *e = &irc__ix(c)[id];
    const float *p = irc__rec_at(c, id)->p;
    double inv = 32767.5 / q->h, r = -IRC_FLOOR(-reach * inv);
    int i;
    if (!irc__inside(q, p) || !(r < (double)IRC__IX_ANY)) {
        e->q[0] = e->q[1] = e->q[2] = 0;
        e->rq = IRC__IX_ANY;
        return;
    }
    for (i = 0; i < 3; i++)
        e->q[i] = (uint16_t)IRC_FLOOR(((double)p[i] - (q->c[i] - q->h)) * inv + 0.5);
    e->rq = (uint16_t)r;
}

/* Records in a list, counted up to limit. */
static uint32_t irc__list_len(const irc_cache *c, uint32_t id, uint32_t limit)
{
    uint32_t n = 0;
    for (; id != IRC__NIL && n < limit; id = irc__ix(c)[id].next)
        n++;
    return n;
}

static uint32_t irc__block_alloc(irc_cache *c)
{
    uint32_t b = c->home->nodes_used, i;
    if (c->node_cap - b < 8u)
        return 0;
    for (i = 0; i < 8; i++)
        irc__node_empty(&irc__nodes(c)[b + i]);
    c->home->nodes_used += 8;
    return b;
}

static void irc__root_cube(const irc_cache *c, irc__cube *q)
{
    q->c[0] = c->home->root_c[0];
    q->c[1] = c->home->root_c[1];
    q->c[2] = c->home->root_c[2];
    q->h = c->home->root_h;
}

static void irc__push(irc_cache *c, irc__node *n, const irc__cube *q, uint32_t id,
                      double reach)
{
    irc__quantize(c, id, q, reach);
    irc__ix(c)[id].next = n->head;
    n->head = id;
    if (reach > (double)n->reach)
        n->reach = (float)reach;
}

/* The node a record belongs in by the placement rule; the path's reaches
 * grow to cover it when grow is set. */
static irc__node *irc__home(irc_cache *c, const float p[3], double reach,
                            int grow, irc__cube *q, int *depth)
{
    irc__node *n = &irc__nodes(c)[0];
    irc__root_cube(c, q);
    *depth = 0;
    for (;;) {
        if (grow && reach > (double)n->reach)
            n->reach = (float)reach;
        if (!n->child || !irc__inside(q, p) || 0.5 * q->h < reach ||
            *depth >= IRC__DEPTH) {
            return n;
        } else {
            int oct = irc__octant(q, p);
            irc__cube cq;
            irc__child_cube(q, oct, &cq);
            *q = cq;
            n = &irc__nodes(c)[n->child + (uint32_t)oct];
            ++*depth;
        }
    }
}

static void irc__split(irc_cache *c, irc__node *n, const irc__cube *q, int depth)
{
    uint32_t b = irc__block_alloc(c), id, keep = IRC__NIL, nid;
    if (!b)
        return;
    n->child = b;
    if ((uint32_t)depth + 1u > c->home->depth)
        c->home->depth = (uint32_t)depth + 1u;
    for (id = n->head; id != IRC__NIL; id = nid) {
        double reach = irc__reach(c, id);
        const float *p = irc__rec_at(c, id)->p;
        nid = irc__ix(c)[id].next;
        if (0.5 * q->h >= reach && irc__inside(q, p)) {
            int oct = irc__octant(q, p);
            irc__cube cq;
            irc__child_cube(q, oct, &cq);
            irc__push(c, &irc__nodes(c)[b + (uint32_t)oct], &cq, id, reach);
        } else {
            irc__ix(c)[id].next = keep;
            keep = id;
        }
    }
    n->head = keep;
}

/* The cell of edge 2h (h a power of two) on the grid of that edge that
 * holds x: every centre derived from it by halving is exact in double. */
static double irc__cell_centre(double x, double h)
{
    return (IRC_FLOOR(x / (2.0 * h)) + 0.5) * (2.0 * h);
}

static double irc__max3(const double v[3])
{
    double m = IRC_FABS(v[0]);
    if (IRC_FABS(v[1]) > m) m = IRC_FABS(v[1]);
    if (IRC_FABS(v[2]) > m) m = IRC_FABS(v[2]);
    return m;
}

/* A root cube around the box [lo, hi]: half edge a power of two no less
 * than half the box's extent and 1/32 of its centre's distance from the
 * origin (exactness), doubled about its centre until the box fits below
 * its upper faces (irc__in_root). */
static void irc__root_fit(irc_cache *c, const double lo[3], const double hi[3])
{
    double mid[3], ext[3], m;
    int i, e;
    for (i = 0; i < 3; i++) {
        mid[i] = 0.5 * (lo[i] + hi[i]);
        ext[i] = 0.5 * (hi[i] - lo[i]);
    }
    m = irc__max3(mid) * (1.0 / 32.0);
    if (irc__max3(ext) > m) m = irc__max3(ext);
    if (m < 1e-30) m = 1e-30;
    IRC_FREXP(m, &e);
    c->home->root_h = IRC_LDEXP(1.0, e);
    for (i = 0; i < 3; i++)
        c->home->root_c[i] = irc__cell_centre(mid[i], c->home->root_h);
    for (;;) {
        for (i = 0; i < 3; i++)
            if (lo[i] < c->home->root_c[i] - c->home->root_h || hi[i] >= c->home->root_c[i] + c->home->root_h)
                break;
        if (i == 3)
            break;
        c->home->root_h *= 2.0;
    }
    if (c->home->root_h > IRC__ROOT_MAX) {
        c->home->root_h = IRC__ROOT_MAX;
        c->home->root_c[0] = c->home->root_c[1] = c->home->root_c[2] = 0.0;
    }
    IRC_ASSERT(irc__index_root_sane(c->home)); /* what the walk relies on */
}

/* Refits a leaf root to the positions it holds and p. */
static void irc__root_refit(irc_cache *c, const float p[3])
{
    double lo[3], hi[3];
    irc__cube q;
    uint32_t id;
    int i;
    for (i = 0; i < 3; i++)
        lo[i] = hi[i] = (double)p[i];
    for (id = irc__nodes(c)[0].head; id != IRC__NIL; id = irc__ix(c)[id].next)
        for (i = 0; i < 3; i++) {
            double x = (double)irc__rec_at(c, id)->p[i];
            if (x < lo[i]) lo[i] = x;
            if (x > hi[i]) hi[i] = x;
        }
    irc__root_fit(c, lo, hi);
    irc__root_cube(c, &q);
    for (id = irc__nodes(c)[0].head; id != IRC__NIL; id = irc__ix(c)[id].next)
        irc__quantize(c, id, &q, irc__reach(c, id));
}

/* Doubles a root that has children toward p: the old root becomes the
 * child on the side away from p.  The records the old root held that no
 * longer fit a child (too large, or outside its cube) move up. */
static int irc__grow(irc_cache *c, const float p[3])
{
    irc__cube old, now;
    uint32_t b, id, nid, keep = IRC__NIL;
    irc__node *was, *nodes;
    int i, oct = 0;
    if (2.0 * c->home->root_h > IRC__ROOT_MAX || c->home->depth >= IRC__LEVELS ||
        !(b = irc__block_alloc(c)))
        return 0;
    c->home->depth++;
    nodes = irc__nodes(c);
    irc__root_cube(c, &old);
    for (i = 0; i < 3; i++) {
        /* up only where p lies past the upper face (irc__in_root) */
        int below = !((double)p[i] >= old.c[i] + old.h);
        oct |= below << i;
        c->home->root_c[i] = old.c[i] + (below ? -old.h : old.h);
    }
    c->home->root_h = 2.0 * old.h;
    was = &nodes[b + (uint32_t)oct];
    *was = nodes[0];
    irc__node_empty(&nodes[0]);
    nodes[0].child = b;
    nodes[0].reach = was->reach;
    irc__root_cube(c, &now);
    for (id = was->head; id != IRC__NIL; id = nid) {
        nid = irc__ix(c)[id].next;
        if (irc__reach(c, id) > old.h || !irc__inside(&old, irc__rec_at(c, id)->p)) {
            irc__push(c, &nodes[0], &now, id, irc__reach(c, id));
        } else {
            irc__ix(c)[id].next = keep;
            keep = id;
        }
    }
    was->head = keep;
    IRC_ASSERT(irc__index_root_sane(c->home));
    return 1;
}

/* Makes the root's cube hold p: a leaf root is refitted (no node is
 * spent), a root with children grows toward p. */
static void irc__root_cover(irc_cache *c, const float p[3])
{
    irc__cube q;
    if (!c->home->root_set) {
        double at[3];
        at[0] = (double)p[0]; at[1] = (double)p[1]; at[2] = (double)p[2];
        irc__root_fit(c, at, at);
        c->home->root_set = 1;
    }
    irc__root_cube(c, &q);
    if (irc__in_root(&q, p))
        return;
    if (!irc__nodes(c)[0].child) {
        if (c->home->root_h < IRC__ROOT_MAX) /* else p stays outside, in the list */
            irc__root_refit(c, p);
        return;
    }
    do
        irc__root_cube(c, &q);
    while (!irc__in_root(&q, p) && irc__grow(c, p));
}

void irc__index_insert(irc_cache *c, uint32_t id)
{
    const float *p = irc__rec_at(c, id)->p;
    double reach = irc__reach(c, id);
    irc__cube q;
    irc__node *n;
    int depth;
    irc__root_cover(c, p);
    if (!irc__nodes(c)[0].child && c->home->root_h < IRC__ROOT_MAX &&
        irc__list_len(c, irc__nodes(c)[0].head, IRC__SPLIT) >= IRC__SPLIT)
        irc__root_refit(c, p);
    n = irc__home(c, p, reach, 1, &q, &depth);
    irc__push(c, n, &q, id, reach);
    if (!n->child && depth < IRC__DEPTH && irc__inside(&q, p) &&
        irc__list_len(c, n->head, IRC__SPLIT + 1u) > IRC__SPLIT)
        irc__split(c, n, &q, depth);
}

/* Unlinks id from the first list on the path to its home that holds it:
 * neighbour clamping may have shrunk its reach since it was placed, which
 * only moves its home deeper along the same path. */
static int irc__unlink(irc_cache *c, irc__node *n, uint32_t id)
{
    uint32_t *link = &n->head;
    while (*link != IRC__NIL && *link != id)
        link = &irc__ix(c)[*link].next;
    if (*link != id)
        return 0;
    *link = irc__ix(c)[id].next;
    return 1;
}

void irc__index_remove(irc_cache *c, uint32_t id)
{
    const float *p = irc__rec_at(c, id)->p;
    irc__node *n = &irc__nodes(c)[0];
    irc__cube q;
    int depth = 0, found;
    irc__root_cube(c, &q);
    while (!(found = irc__unlink(c, n, id)) && n->child && irc__inside(&q, p) &&
           depth < IRC__LEVELS) {
        int oct = irc__octant(&q, p);
        irc__cube cq;
        irc__child_cube(&q, oct, &cq);
        q = cq;
        n = &irc__nodes(c)[n->child + (uint32_t)oct];
        depth++;
    }
    IRC_ASSERT(found);
    (void)found;
    /* Reaches are left as they are: an upper bound stays exact. */
}
