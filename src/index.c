/*
 * index.c -- an octree over record positions, inside the caller's block.
 *
 * A record sits in the deepest node whose children are at least as large as
 * its reach a*R_i (a loose octree: a subtree's records reach at most one
 * node size past its cube).  Cubes lie on a power-of-two grid, so every
 * centre is exact in double and placement never depends on rounding.  Each node keeps the largest reach in its
 * subtree, and a query descends only into children whose cube lies within
 * that reach of the query point, which is exact: a record whose sphere holds
 * p lies in a cube no farther from p than the record's reach.
 *
 * A leaf with more than IRC__SPLIT records splits when the node pool has a
 * block of 8 free; the root doubles toward records that land outside it.
 * When the pool is spent, lists grow instead: slower, never wrong.
 */
#include "cache.h"

#define IRC__SPLIT 8u
#define IRC__DEPTH 40    /* keeps centres exact: see irc__index_insert */
#define IRC__ROOT_MAX 1e39

typedef struct irc__cube {
    double c[3];
    double h; /* half the edge */
} irc__cube;

static void irc__node_empty(irc__node *n)
{
    n->child = 0;
    n->head = IRC__NIL;
    n->reach = -1.0f;
    n->count = 0;
}

void irc__index_reset(irc_cache *c)
{
    irc__node_empty(&c->nodes[0]);
    c->nodes_used = 1;
    c->root_set = 0;
}

static double irc__reach(const irc_cache *c, uint32_t id)
{
    return (double)c->cfg.accuracy * irc__rec_at(c, id)->r;
}

static int irc__inside(const irc__cube *q, const float p[3])
{
    return fabs(p[0] - q->c[0]) <= q->h && fabs(p[1] - q->c[1]) <= q->h &&
           fabs(p[2] - q->c[2]) <= q->h;
}

static int irc__octant(const irc__cube *q, const float p[3])
{
    return (p[0] >= q->c[0]) | (p[1] >= q->c[1]) << 1 | (p[2] >= q->c[2]) << 2;
}

static void irc__child_cube(const irc__cube *q, int oct, irc__cube *out)
{
    int i;
    out->h = 0.5 * q->h;
    for (i = 0; i < 3; i++)
        out->c[i] = q->c[i] + (oct >> i & 1 ? out->h : -out->h);
}

static uint32_t irc__block_alloc(irc_cache *c)
{
    uint32_t b = c->nodes_used, i;
    if (c->node_cap - b < 8u)
        return 0;
    for (i = 0; i < 8; i++)
        irc__node_empty(&c->nodes[b + i]);
    c->nodes_used += 8;
    return b;
}

static void irc__root_cube(const irc_cache *c, irc__cube *q)
{
    q->c[0] = c->root_c[0];
    q->c[1] = c->root_c[1];
    q->c[2] = c->root_c[2];
    q->h = c->root_h;
}

static void irc__push(irc_cache *c, irc__node *n, uint32_t id, double reach)
{
    c->next[id] = n->head;
    n->head = id;
    n->count++;
    if (reach > n->reach)
        n->reach = (float)reach;
}

/* The node a record belongs in by the placement rule; the path's reaches
 * grow to cover it when grow is set. */
static irc__node *irc__home(irc_cache *c, const float p[3], double reach,
                            int grow, irc__cube *q, int *depth)
{
    irc__node *n = &c->nodes[0];
    irc__root_cube(c, q);
    *depth = 0;
    for (;;) {
        if (grow && reach > n->reach)
            n->reach = (float)reach;
        if (!n->child || !irc__inside(q, p) || 0.5 * q->h < reach ||
            *depth >= IRC__DEPTH) {
            return n;
        } else {
            int oct = irc__octant(q, p);
            irc__cube cq;
            irc__child_cube(q, oct, &cq);
            *q = cq;
            n = &c->nodes[n->child + (uint32_t)oct];
            ++*depth;
        }
    }
}

static void irc__split(irc_cache *c, irc__node *n, const irc__cube *q)
{
    uint32_t b = irc__block_alloc(c), id, keep = IRC__NIL, nid;
    if (!b)
        return;
    n->child = b;
    n->count = 0;
    for (id = n->head; id != IRC__NIL; id = nid) {
        double reach = irc__reach(c, id);
        const float *p = irc__rec_at(c, id)->p;
        nid = c->next[id];
        if (0.5 * q->h >= reach && irc__inside(q, p)) {
            irc__push(c, &c->nodes[b + (uint32_t)irc__octant(q, p)], id, reach);
        } else {
            c->next[id] = keep;
            keep = id;
            n->count++;
        }
    }
    n->head = keep;
}

/* The cell of edge 2h (h a power of two) on the grid of that edge that
 * holds x: every centre derived from it by halving is exact in double. */
static double irc__cell_centre(double x, double h)
{
    return (floor(x / (2.0 * h)) + 0.5) * (2.0 * h);
}

/* Doubles the root: its parent on the power-of-two grid becomes the root, so
 * the old root is exactly one of the new root's children.  The records the
 * old root held that no longer fit a child (too large, or outside its cube)
 * move up. */
static int irc__grow(irc_cache *c)
{
    irc__cube old, nq;
    uint32_t b, id, nid, keep = IRC__NIL;
    irc__node *was;
    int i, oct = 0;
    if (2.0 * c->root_h > IRC__ROOT_MAX || !(b = irc__block_alloc(c)))
        return 0;
    irc__root_cube(c, &old);
    nq.h = 2.0 * old.h;
    for (i = 0; i < 3; i++) {
        nq.c[i] = irc__cell_centre(old.c[i], nq.h);
        oct |= (old.c[i] >= nq.c[i]) << i;
    }
    was = &c->nodes[b + (uint32_t)oct];
    *was = c->nodes[0];
    irc__node_empty(&c->nodes[0]);
    c->nodes[0].child = b;
    c->nodes[0].reach = was->reach;
    for (i = 0; i < 3; i++)
        c->root_c[i] = nq.c[i];
    c->root_h = nq.h;
    was->count = 0;
    for (id = was->head; id != IRC__NIL; id = nid) {
        nid = c->next[id];
        if (irc__reach(c, id) > old.h || !irc__inside(&old, irc__rec_at(c, id)->p)) {
            irc__push(c, &c->nodes[0], id, irc__reach(c, id));
        } else {
            c->next[id] = keep;
            keep = id;
            was->count++;
        }
    }
    was->head = keep;
    return 1;
}

void irc__index_insert(irc_cache *c, uint32_t id)
{
    const float *p = irc__rec_at(c, id)->p;
    double reach = irc__reach(c, id);
    irc__cube q;
    irc__node *n;
    int depth, i;
    if (!c->root_set) {
        /* Start the root at the first record's reach or at 1/64 of its
         * distance from the origin, whichever is larger; the latter keeps
         * every cube centre within 2^52 of its size, so exact. */
        double m = fabs(p[0]);
        if (fabs(p[1]) > m) m = fabs(p[1]);
        if (fabs(p[2]) > m) m = fabs(p[2]);
        m *= 1.0 / 64.0;
        if (reach > m) m = reach;
        if (m < 1e-30) m = 1e-30;
        frexp(m, &i);
        c->root_h = ldexp(1.0, i);
        for (i = 0; i < 3; i++)
            c->root_c[i] = irc__cell_centre(p[i], c->root_h);
        c->root_set = 1;
    }
    irc__root_cube(c, &q);
    while (!irc__inside(&q, p) && irc__grow(c))
        irc__root_cube(c, &q);
    n = irc__home(c, p, reach, 1, &q, &depth);
    irc__push(c, n, id, reach);
    if (!n->child && n->count > IRC__SPLIT && depth < IRC__DEPTH && irc__inside(&q, p))
        irc__split(c, n, &q);
}

void irc__index_remove(irc_cache *c, uint32_t id)
{
    irc__cube q;
    int depth;
    irc__node *n = irc__home(c, irc__rec_at(c, id)->p, irc__reach(c, id), 0, &q, &depth);
    uint32_t *link = &n->head;
    while (*link != IRC__NIL && *link != id)
        link = &c->next[*link];
    IRC_ASSERT(*link == id);
    if (*link == id) {
        *link = c->next[id];
        n->count--;
    }
    /* Reaches are left as they are: an upper bound stays exact. */
}

static void irc__query_node(const irc_cache *c, const irc__node *n,
                            const irc__cube *q, const float p[3],
                            irc__visit_fn fn, void *ud)
{
    double part[3][2], hc = 0.5 * q->h, pad = hc * 1e-9;
    int oct, i, k;
    if (n->head != IRC__NIL)
        fn(ud, n->head);
    if (!n->child)
        return;
    /* Squared distance from p to each child's cube, axis by axis: child
     * bit k of axis i sits at centre c_i - hc (k = 0) or c_i + hc (k = 1). */
    for (i = 0; i < 3; i++)
        for (k = 0; k < 2; k++) {
            double o = fabs(p[i] - (q->c[i] + (k ? hc : -hc))) - hc;
            part[i][k] = o > 0.0 ? o * o : 0.0;
        }
    for (oct = 0; oct < 8; oct++) {
        const irc__node *ch = &c->nodes[n->child + (uint32_t)oct];
        double r, d2;
        if (ch->reach < 0.0f)
            continue;
        d2 = part[0][oct & 1] + part[1][oct >> 1 & 1] + part[2][oct >> 2 & 1];
        /* The pad covers the float rounding of the stored reach. */
        r = (double)ch->reach * (1.0 + 1e-6) + pad;
        if (d2 <= r * r) {
            irc__cube cq;
            irc__child_cube(q, oct, &cq);
            irc__query_node(c, ch, &cq, p, fn, ud);
        }
    }
}

void irc__index_query(const irc_cache *c, const float p[3], irc__visit_fn fn,
                      void *ud)
{
    irc__cube q;
    if (!c->root_set)
        return;
    irc__root_cube(c, &q);
    irc__query_node(c, &c->nodes[0], &q, p, fn, ud);
}
