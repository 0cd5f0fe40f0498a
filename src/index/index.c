/*
 * index.c -- an octree over record reaches, inside the caller's block.
 *
 * A record's reach a*R_i spans a box; the record is referenced (index.h,
 * irc__ref) in every node its box overlaps at its level, the deepest
 * whose cells are at least as wide as the box, so at most two a side and
 * eight in all, or in a leaf above that level where the tree is not yet
 * that deep.  Those nodes' cubes cover the box, so every point the record
 * may serve lies in one of them, and a lookup follows the one path of
 * nodes that holds its point, from the root down, testing each list
 * (pbrt-v2's irradiance cache keeps its octree so).  One of a record's
 * references, its home, sits in the node whose cube holds its position:
 * walks over a range take only homes, which the cube tests prune exactly
 * as before, and see each record once.
 *
 * Coordinates are turned into integers, 2^-58 root edges from the root's
 * low corner (query.c), and a cell at depth d spans 2^(58 - d) of them:
 * which cells a box overlaps, and which cell holds a point, are integer
 * comparisons, and a lookup's point rounds down exactly (query.c), so it
 * always meets the nodes its record's box was placed in.  The box is
 * widened by a relative 1e-5 and 1e-6 of the position's size, more than
 * the roundings of the box's ends in double and of the exact test a
 * candidate then passes.  A record whose box is not inside the root, or
 * whose reach is wider than the root, is referenced once, in the root's
 * list, which every walk scans.
 *
 * A leaf is tried for a split when its list passes IRC__SPLIT references
 * and every IRC__SPLIT after; it splits when the node pool has a block of
 * 8 free and most of its references belong to records whose level lies
 * deeper, which move to the children their boxes overlap.  The root is
 * not tied to a grid through the origin: a scene centred on the origin
 * would otherwise need a cube that holds 0 in its interior, which no cube
 * of such a grid does.  While the root is a leaf it is resized freely to
 * its records' positions and the boxes no wider than their spread (not
 * reaches of 1e30); afterwards it doubles toward records and box corners
 * that land outside it, the old root becoming one of its children.  Centres
 * stay exact because the root's half edge is kept at least 1/32 of its
 * centre's largest coordinate, splits stop at depth IRC__DEPTH and growth
 * at IRC__LEVELS.
 *
 * References come from a pool of the block's (life.c; cells.c takes
 * and gives them) that always keeps one for each record not yet indexed:
 * when it runs short a record is placed a level up, in fewer and larger
 * nodes, and leaves stop splitting.  Slower then, never wrong.
 */
#include "../block/cache.h"
#include "cells.h"
#include "index.h"
#include "layout.h"

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

void irc__index_reset(irc_cache *c)
{
    irc__node_empty(&irc__nodes(c)[0]);
    irc__st(c)->nodes_used = 1;
    irc__st(c)->refs_used = 0;
    irc__st(c)->ref_free = IRC__NIL;
    irc__st(c)->refs_live = 0;
    irc__st(c)->indexed = 0;
    irc__st(c)->refs_taken = 0;
    irc__st(c)->compacted = 0;
    irc__st(c)->root_set = 0;
    irc__st(c)->depth = 0;
}

/* The reaches on the path to the home of a record at cell point at, down
 * to depth d, grown to cover reach. */
static void irc__reach_path(irc_cache *c, const int64_t at[3], int d, float reach)
{
    irc__node *n = &irc__nodes(c)[0];
    int k;
    for (k = 0;; k++) {
        if (reach > n->reach)
            n->reach = reach;
        if (k == d || !n->child)
            return;
        n = &irc__nodes(c)[n->child + (uint32_t)((at[0] >> (57 - k) & 1) |
                                                 (at[1] >> (57 - k) & 1) << 1 |
                                                 (at[2] >> (57 - k) & 1) << 2)];
    }
}

/* One placement: counts the nodes (push unset) or references the record
 * in each, noting the leaves that may now split. */
typedef struct irc__place {
    uint32_t id, count, n_leaves, push;
    irc__cell leaves[8];
    int depths[8];
    const irc__box *b;
} irc__place;

static void irc__place_at(irc_cache *c, const irc__cell *x, int d, void *ud)
{
    irc__place *pl = (irc__place *)ud;
    irc__cube q;
    int home;
    pl->count++;
    if (!pl->push)
        return;
    home = irc__holds(x, d, pl->b->at);
    irc__cell_cube(c, x->lo, d, &q);
    irc__ref_push(c, x->node, &q, pl->id, home);
    if (home)
        irc__reach_path(c, pl->b->at, d, irc__ix(c)[pl->id].reach);
    if (!irc__nodes(c)[x->node].child && d < IRC__DEPTH && pl->n_leaves < 8) {
        pl->leaves[pl->n_leaves] = *x;
        pl->depths[pl->n_leaves++] = d;
    }
}

/* A record's box and the level it goes to (0 for a box not inside the
 * root: its one reference goes to the root's list). */
static int irc__placement(const irc_cache *c, uint32_t id, irc__box *b)
{
    const float *p = irc__rec_at(c, id)->p;
    const double half = irc__half(p, (double)irc__ix(c)[id].reach);
    irc__box_of(c, p, half, b);
    return b->inside ? irc__level(c, half, IRC__DEPTH) : 0;
}

/* Whether a reference in a node of depth d moves down when it splits:
 * its record's level lies deeper.  Sets the record's box and the
 * children it goes to. */
static int irc__moves(const irc_cache *c, uint32_t id, const irc__cell *x, int d,
                      irc__box *b, unsigned *mask)
{
    if (irc__placement(c, id, b) <= d)
        return 0;
    *mask = irc__overlapped(x, d, b);
    return *mask != 0;
}

/* Splits leaf x of depth d when the pool has a block and the references
 * its records' moves take. */
static void irc__split(irc_cache *c, const irc__cell *x, int d)
{
    irc__node *n = &irc__nodes(c)[x->node];
    irc__ref *refs = irc__refs(c);
    uint32_t r, nr, keep = IRC__NIL, *tail = &keep, extra = 0, moving = 0, len = 0, b;
    irc__box bx;
    unsigned mask;
    if (c->node_cap - irc__st(c)->nodes_used < 8u)
        return;
    for (r = n->head; r != IRC__NIL; r = refs[r].next, len++)
        if (irc__moves(c, refs[r].id & ~IRC__REF_HOME, x, d, &bx, &mask)) {
            extra += irc__popcount(mask) - 1u;
            moving++;
        }
    /* Not for a list that would mostly stay: its nodes would be spent
     * on nothing. */
    if (2u * moving <= len || extra > irc__spare(c) || !(b = irc__block_alloc(c)))
        return;
    n->child = b;
    if ((uint32_t)d + 1u > irc__st(c)->depth)
        irc__st(c)->depth = (uint32_t)d + 1u;
    for (r = n->head; r != IRC__NIL; r = nr) {
        const uint32_t id = refs[r].id & ~IRC__REF_HOME;
        unsigned oct;
        int homed;
        nr = refs[r].next;
        if (!irc__moves(c, id, x, d, &bx, &mask)) {
            *tail = r; /* in order: the list's homes stay first */
            tail = &refs[r].next;
            continue;
        }
        homed = !(refs[r].id & IRC__REF_HOME);
        for (oct = 0; oct < 8; oct++) {
            irc__cell y;
            irc__cube q;
            int i, home;
            if (!(mask >> oct & 1u))
                continue;
            for (i = 0; i < 3; i++)
                y.lo[i] = x->lo[i] + ((oct >> i & 1) ? IRC__ONE >> (d + 1) : 0);
            y.node = b + oct;
            /* the child that holds the position; the last one if rounding
             * put it in none (its box's ends are computed afresh) */
            home = !homed && (irc__holds(&y, d + 1, bx.at) || mask >> oct == 1u);
            homed |= home;
            irc__cell_cube(c, y.lo, d + 1, &q);
            irc__ref_push(c, y.node, &q, id, home);
            if (home && irc__ix(c)[id].reach > irc__nodes(c)[y.node].reach)
                irc__nodes(c)[y.node].reach = irc__ix(c)[id].reach;
        }
        irc__ix(c)[id].refs += irc__popcount(mask) - 1u;
        irc__ref_give(c, r);
    }
    *tail = IRC__NIL;
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
    irc__st(c)->root_h = IRC_LDEXP(1.0, e);
    for (i = 0; i < 3; i++)
        irc__st(c)->root_c[i] = irc__cell_centre(mid[i], irc__st(c)->root_h);
    for (;;) {
        for (i = 0; i < 3; i++)
            if (lo[i] < irc__st(c)->root_c[i] - irc__st(c)->root_h || hi[i] >= irc__st(c)->root_c[i] + irc__st(c)->root_h)
                break;
        if (i == 3)
            break;
        irc__st(c)->root_h *= 2.0;
    }
    if (irc__st(c)->root_h > IRC__ROOT_MAX) {
        irc__st(c)->root_h = IRC__ROOT_MAX;
        irc__st(c)->root_c[0] = irc__st(c)->root_c[1] = irc__st(c)->root_c[2] = 0.0;
    }
    IRC_ASSERT(irc__index_root_sane(c)); /* what the walk relies on */
}

/* The root holds no point on its upper faces: a point on a face shared by
 * two cells belongs to the upper one (its integer image, query.c). */
static int irc__in_root(const irc__cube *q, const float p[3])
{
    int i;
    for (i = 0; i < 3; i++)
        if (!((double)p[i] >= q->c[i] - q->h && (double)p[i] < q->c[i] + q->h))
            return 0;
    return 1;
}

/* Refits a leaf root to the positions it holds and p, and to their
 * reaches' boxes where a box is no wider than the positions' spread (a
 * wider one is placed in the root's list whatever the root); its
 * references, all homes, are quantized again. */
static void irc__root_refit(irc_cache *c, const float p[3])
{
    double lo[3], hi[3], span = 0.0;
    irc__cube q;
    irc__ref *refs = irc__refs(c);
    const uint32_t head = irc__nodes(c)[0].head;
    uint32_t r;
    int i;
    for (i = 0; i < 3; i++)
        lo[i] = hi[i] = (double)p[i];
    for (r = head; r != IRC__NIL; r = refs[r].next)
        for (i = 0; i < 3; i++) {
            double x = (double)irc__rec_at(c, refs[r].id & ~IRC__REF_HOME)->p[i];
            if (x < lo[i]) lo[i] = x;
            if (x > hi[i]) hi[i] = x;
        }
    for (i = 0; i < 3; i++)
        if (hi[i] - lo[i] > span)
            span = hi[i] - lo[i];
    for (r = head; r != IRC__NIL; r = refs[r].next) {
        const float *x = irc__rec_at(c, refs[r].id & ~IRC__REF_HOME)->p;
        const double half = irc__half(x, (double)irc__ix(c)[refs[r].id & ~IRC__REF_HOME].reach);
        for (i = 0; half <= span && i < 3; i++) {
            if ((double)x[i] - half < lo[i]) lo[i] = (double)x[i] - half;
            if ((double)x[i] + half > hi[i]) hi[i] = (double)x[i] + half;
        }
    }
    irc__root_fit(c, lo, hi);
    irc__root_cube(c, &q);
    for (r = head; r != IRC__NIL; r = refs[r].next) {
        const uint32_t id = refs[r].id & ~IRC__REF_HOME;
        irc__quantize(&refs[r], &q, irc__rec_at(c, id)->p, irc__reach_now(c, id));
    }
}

/* Whether the root irc__grow would make toward p is one the walk can
 * use.  A root the index made always is (its centre lies on a grid of
 * its first half edge, so a grown one's corners stay floats, and |centre|
 * <= 33 h becomes <= 17 of the doubled h); an attached block's root only
 * passed irc__index_root_sane, and a damaged one's centre may carry bits
 * below that grid that growth pushes out of float.  Refused, the record
 * stays in the root's list, as past IRC__ROOT_MAX. */
static int irc__grown_ok(const irc_cache *c, const float p[3])
{
    double at[3];
    int i;
    for (i = 0; i < 3; i++)
        at[i] = irc__st(c)->root_c[i] +
                ((double)p[i] >= irc__st(c)->root_c[i] + irc__st(c)->root_h ? irc__st(c)->root_h
                                                                      : -irc__st(c)->root_h);
    return irc__root_ok(at, 2.0 * irc__st(c)->root_h);
}

/* Doubles a root that has children toward p: the old root becomes the
 * child on the side away from p.  The references the old root held whose
 * boxes are not inside it move up. */
static int irc__grow(irc_cache *c, const float p[3])
{
    irc__cube old, now;
    irc__ref *refs = irc__refs(c);
    uint32_t b, r, nr, keep = IRC__NIL, *tail = &keep, up = IRC__NIL;
    irc__node *was, *nodes;
    int i, oct = 0;
    if (2.0 * irc__st(c)->root_h > IRC__ROOT_MAX || irc__st(c)->depth >= IRC__LEVELS ||
        !irc__grown_ok(c, p) || !(b = irc__block_alloc(c)))
        return 0;
    nodes = irc__nodes(c);
    for (r = nodes[0].head; r != IRC__NIL; r = nr) {
        irc__box bx;
        nr = refs[r].next;
        irc__placement(c, refs[r].id & ~IRC__REF_HOME, &bx);
        if (bx.inside) {
            *tail = r;
            tail = &refs[r].next;
        } else {
            refs[r].next = up;
            up = r;
        }
    }
    *tail = IRC__NIL;
    nodes[0].head = keep;
    irc__st(c)->depth++;
    irc__root_cube(c, &old);
    for (i = 0; i < 3; i++) {
        /* up only where p lies past the upper face (irc__in_root) */
        int below = !((double)p[i] >= old.c[i] + old.h);
        oct |= below << i;
        irc__st(c)->root_c[i] = old.c[i] + (below ? -old.h : old.h);
    }
    irc__st(c)->root_h = 2.0 * old.h;
    was = &nodes[b + (uint32_t)oct];
    *was = nodes[0];
    irc__node_empty(&nodes[0]);
    nodes[0].child = b;
    nodes[0].reach = was->reach;
    irc__root_cube(c, &now);
    for (r = up; r != IRC__NIL; r = nr) {
        const uint32_t id = refs[r].id & ~IRC__REF_HOME;
        nr = refs[r].next;
        irc__quantize(&refs[r], &now, irc__rec_at(c, id)->p, irc__reach_now(c, id));
        refs[r].next = nodes[0].head;
        nodes[0].head = r;
    }
    IRC_ASSERT(irc__index_root_sane(c));
    return 1;
}

/* Makes the root's cube hold p: a leaf root is refitted (no node is
 * spent), a root with children grows toward p. */
static void irc__root_cover(irc_cache *c, const float p[3])
{
    irc__cube q;
    if (!irc__st(c)->root_set) {
        double at[3];
        at[0] = (double)p[0]; at[1] = (double)p[1]; at[2] = (double)p[2];
        irc__root_fit(c, at, at);
        irc__st(c)->root_set = 1;
    }
    irc__root_cube(c, &q);
    if (irc__in_root(&q, p))
        return;
    if (!irc__nodes(c)[0].child) {
        if (irc__st(c)->root_h < IRC__ROOT_MAX) /* else p stays outside, in the list */
            irc__root_refit(c, p);
        return;
    }
    do
        irc__root_cube(c, &q);
    while (!irc__in_root(&q, p) && irc__grow(c, p));
}

/* Step 1: a root that holds the record's position and, when its reach's
 * box is smaller than the root, the box's corners too, rounded outward (a
 * box the root cuts, records on the face it was fitted to, would be
 * placed in the root's list); a root leaf grown past SPLIT is fitted to
 * its records first. */
static void irc__insert_root(irc_cache *c, const float p[3], double half)
{
    irc__root_cover(c, p);
    if (!irc__nodes(c)[0].child && irc__st(c)->root_h < IRC__ROOT_MAX &&
        irc__list_len(c, irc__nodes(c)[0].head, IRC__SPLIT) >= IRC__SPLIT)
        irc__root_refit(c, p);
    if (half < irc__st(c)->root_h) {
        float lo[3], hi[3];
        int i;
        for (i = 0; i < 3; i++) {
            lo[i] = (float)((double)p[i] - half * (1.0 + 1e-6) - 1e-30);
            hi[i] = (float)((double)p[i] + half * (1.0 + 1e-6) + 1e-30);
        }
        irc__root_cover(c, lo);
        irc__root_cover(c, hi);
    }
}

/* Step 2: the level to place at, L or above.  A level up while the
 * references it takes are more than the pool can spare: at the root it
 * takes one, which the pool keeps.  Counted only when the pool could be
 * short: a box no wider than the cells of its level is cut by at most one
 * of their faces an axis, and every node it is placed in holds whole
 * pieces of it, so it takes 8 at most. */
static int irc__insert_level(irc_cache *c, const irc__box *b, int L, irc__place *pl)
{
    while (irc__spare(c) + 1u < 8u) {
        pl->count = 0;
        if (b->inside)
            irc__cover(c, b, L, 0, irc__place_at, pl);
        if (pl->count <= irc__spare(c) + 1u || L == 0)
            break;
        L--;
    }
    return L;
}

/* Step 3: the references pushed, in the nodes the box meets at level L,
 * or in the root's list for a box outside the root's frame. */
static void irc__insert_refs(irc_cache *c, uint32_t id, const irc__box *b, int L,
                             irc__place *pl)
{
    pl->push = 1;
    pl->count = 0;
    if (b->inside) {
        irc__cover(c, b, L, 0, irc__place_at, pl);
    } else {
        irc__cube q;
        const float reach = irc__ix(c)[id].reach;
        irc__root_cube(c, &q);
        irc__ref_push(c, 0, &q, id, 1);
        if (reach > irc__nodes(c)[0].reach)
            irc__nodes(c)[0].reach = reach;
        pl->count = 1;
    }
}

/* Step 4: the leaves the references went to, split where their lists
 * grew.  A leaf is tried when its list passes SPLIT and every SPLIT
 * references after: one that may not split (no nodes or references to
 * spare, or a list mostly of its own level) is not tried again each time,
 * and a child that took a long list from its parent's split is split in
 * its turn. */
static void irc__insert_splits(irc_cache *c, const irc__place *pl)
{
    uint32_t k;
    for (k = 0; k < pl->n_leaves; k++) {
        const uint32_t len = irc__list_len(c, irc__nodes(c)[pl->leaves[k].node].head, IRC__NIL);
        if (len > IRC__SPLIT && (len - 1u) % IRC__SPLIT == 0)
            irc__split(c, &pl->leaves[k], pl->depths[k]);
    }
}

void irc__index_insert(irc_cache *c, uint32_t id)
{
    const float *p = irc__rec_at(c, id)->p;
    irc__ixe *e = &irc__ix(c)[id];
    irc__place pl;
    irc__box b;
    int L;
    IRC_ASSERT(e->refs == 0);
    e->reach = irc__reach(c, irc__rec_at(c, id)->r);
    irc__insert_root(c, p, irc__half(p, (double)e->reach));
    L = irc__placement(c, id, &b);
    IRC_MEMSET(&pl, 0, sizeof pl);
    pl.id = id;
    pl.b = &b;
    L = irc__insert_level(c, &b, L, &pl);
    irc__insert_refs(c, id, &b, L, &pl);
    IRC_ASSERT(pl.count <= 8u); /* what lets irc__insert_level skip the count */
    e->refs = pl.count;
    irc__st(c)->indexed++;
    irc__insert_splits(c, &pl);
}

/* Removal: every list of a node the record's box overlaps, unlinked of
 * its references.  The box's ends are the same doubles as at placement
 * and a cell's faces are exact, so it meets the same cells whatever the
 * root has become since (only deeper by its growths); clipped to the
 * root, whose list is always searched (a record placed there may fit a
 * root grown since). */
typedef struct irc__unlink {
    uint32_t id, found;
} irc__unlink;

static void irc__unlink_at(irc_cache *c, const irc__cell *x, int d, void *ud)
{
    irc__unlink *u = (irc__unlink *)ud;
    irc__ref *refs = irc__refs(c);
    uint32_t *link = &irc__nodes(c)[x->node].head;
    (void)d;
    while (*link != IRC__NIL) {
        const uint32_t r = *link;
        if ((refs[r].id & ~IRC__REF_HOME) == u->id) {
            *link = refs[r].next;
            irc__ref_give(c, r);
            u->found++;
        } else {
            link = &refs[r].next;
        }
    }
}

/* fn on every node that may hold a reference of record id: those its
 * placement reach's box overlaps, down to its level as the root now
 * stands (deeper by the root's growths than when it was placed, never by
 * more). */
static void irc__cover_placed(irc_cache *c, uint32_t id, irc__cell_fn fn, void *ud)
{
    const float *p = irc__rec_at(c, id)->p;
    const double half = irc__half(p, (double)irc__ix(c)[id].reach);
    irc__box b;
    irc__box_of(c, p, half, &b);
    irc__cover(c, &b, irc__level(c, half, IRC__LEVELS), 1, fn, ud);
}

void irc__index_remove(irc_cache *c, uint32_t id)
{
    irc__ixe *e = &irc__ix(c)[id];
    irc__unlink u;
    u.id = id;
    u.found = 0;
    irc__cover_placed(c, id, irc__unlink_at, &u);
    IRC_ASSERT(u.found == e->refs);
    if (e->refs)
        irc__st(c)->indexed--;
    e->refs = 0;
    /* Reaches are left as they are: an upper bound stays exact. */
}

/* A record's radius shrank since it was placed (neighbour clamping's
 * back pass): its references keep their nodes and places in their lists,
 * but their reach bounds are quantized again from the radius now, so
 * that lookups stop fetching the record where it no longer reaches.
 * Filled in passes, the index is no longer rebuilt from the clamped
 * radii, and on the atrium at 320 x 240, a = 0.4, 36% of the records a
 * lookup fetched lay beyond their reach without this (1.5% with). */
typedef struct irc__tight {
    uint32_t id;
    double reach;
} irc__tight;

static void irc__tighten_at(irc_cache *c, const irc__cell *x, int d, void *ud)
{
    const irc__tight *t = (const irc__tight *)ud;
    irc__ref *refs = irc__refs(c);
    irc__cube q;
    uint32_t r;
    for (r = irc__nodes(c)[x->node].head; r != IRC__NIL; r = refs[r].next)
        if ((refs[r].id & ~IRC__REF_HOME) == t->id && refs[r].rq != IRC__IX_ANY) {
            irc__cell_cube(c, x->lo, d, &q);
            irc__quantize(&refs[r], &q, irc__rec_at(c, t->id)->p, t->reach);
        }
}

void irc__index_tighten(irc_cache *c, uint32_t id)
{
    const irc__ixe *e = &irc__ix(c)[id];
    irc__tight t;
    t.id = id;
    t.reach = irc__reach_now(c, id);
    if (e->refs && t.reach < (double)e->reach)
        irc__cover_placed(c, id, irc__tighten_at, &t);
}
