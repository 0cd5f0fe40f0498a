/*
 * compact.c -- records renumbered in the order a query visits them.
 *
 * A node's list links records by id, and ids are given in the order
 * records arrive, so the entries a lookup scans lie scattered over the
 * index and the records it accepts over the pool: one cache miss each.
 * Compaction gives every record the id of its place in the index's own
 * order (depth first, children by octant, a node's list before its
 * children, each list in its order), moving the records, their index
 * entries and their CLOCK bits there.  Afterwards each list is a run of
 * consecutive ids, so a lookup's entries share lines, and records near in
 * space sit near in the pool.  The tree is untouched and each list keeps
 * its order, so every query visits the same records in the same order as
 * before: lookups are bit-identical.  Record ids change (irrcache.h, at
 * irc_pass_end and irc_merge).
 */
#include "cache.h"
#include "index.h"

/* Depth-first walk of the nodes that hold records or children: calls fn
 * on every node in the order queries visit them.  An explicit stack of a
 * frame a level (the index never goes deeper than its depth field). */
typedef void (*irc__node_fn)(irc_cache *c, irc__node *n, void *ud);

static void irc__walk_nodes(irc_cache *c, irc__node_fn fn, void *ud)
{
    struct { uint32_t block; uint8_t next; } st[IRC__LEVELS + 1];
    irc__node *nodes = irc__nodes(c);
    int top = 0;
    fn(c, &nodes[0], ud);
    if (!nodes[0].child)
        return;
    st[0].block = nodes[0].child;
    st[0].next = 0;
    for (;;) {
        irc__node *n;
        if (st[top].next == 8) {
            if (top == 0)
                return;
            top--;
            continue;
        }
        n = &nodes[st[top].block + st[top].next++];
        fn(c, n, ud);
        if (n->child && top < IRC__LEVELS) {
            top++;
            st[top].block = n->child;
            st[top].next = 0;
        }
    }
}

/* Pass 1: the records the index holds, counted. */
static void irc__count_list(irc_cache *c, irc__node *n, void *ud)
{
    uint32_t id;
    for (id = n->head; id != IRC__NIL; id = irc__ix(c)[id].next)
        ++*(uint32_t *)ud;
}

/* Pass 2: each record's new id, in its entry's link (the list is read
 * before it is overwritten); the node's head becomes its first new id. */
static void irc__number_list(irc_cache *c, irc__node *n, void *ud)
{
    uint32_t *k = (uint32_t *)ud, id = n->head, nid;
    if (id == IRC__NIL)
        return;
    n->head = *k;
    for (; id != IRC__NIL; id = nid) {
        nid = irc__ix(c)[id].next;
        irc__ix(c)[id].next = (*k)++;
    }
}

/* Pass 4: lists as runs.  A list ends where the next list (in walk order,
 * so in id order) begins, the last at count. */
typedef struct irc__runs {
    uint32_t open; /* first id of the list not yet closed, or IRC__NIL */
} irc__runs;

static void irc__close_run(irc_cache *c, uint32_t first, uint32_t end)
{
    uint32_t id;
    for (id = first; id + 1 < end; id++)
        irc__ix(c)[id].next = id + 1;
    irc__ix(c)[end - 1].next = IRC__NIL;
}

static void irc__link_list(irc_cache *c, irc__node *n, void *ud)
{
    irc__runs *r = (irc__runs *)ud;
    if (n->head == IRC__NIL)
        return;
    if (r->open != IRC__NIL)
        irc__close_run(c, r->open, n->head);
    r->open = n->head;
}

static void irc__swap_used(irc_cache *c, uint32_t a, uint32_t b)
{
    uint64_t *used = irc__used(c), ba, bb;
    if (!used)
        return;
    ba = used[a >> 6] >> (a & 63u) & 1u;
    bb = used[b >> 6] >> (b & 63u) & 1u;
    if (ba != bb) {
        used[a >> 6] ^= 1ull << (a & 63u);
        used[b >> 6] ^= 1ull << (b & 63u);
    }
}

/* Pass 3: the permutation applied in place, cycle by cycle: each swap
 * puts one record (with its entry and bit) at its new id for good. */
static void irc__permute(irc_cache *c, uint32_t count)
{
    irc__ixe *ix = irc__ix(c), e;
    uint32_t i, to;
    for (i = 0; i < count; i++)
        while ((to = ix[i].next) != i) {
            irc__rec_swap(c, i, to);
            e = ix[i];
            ix[i] = ix[to];
            ix[to] = e;
            irc__swap_used(c, i, to);
        }
}

void irc__index_compact(irc_cache *c)
{
    uint32_t n = 0, k = 0;
    irc__runs runs;
    irc__walk_nodes(c, irc__count_list, &n);
    /* Every slot below count is indexed; if not, ids cannot be a
     * permutation, and the lists are left as they are. */
    IRC_ASSERT(n == c->home->count);
    if (n != c->home->count || n == 0)
        return;
    irc__walk_nodes(c, irc__number_list, &k);
    irc__permute(c, n);
    runs.open = IRC__NIL;
    irc__walk_nodes(c, irc__link_list, &runs);
    irc__close_run(c, runs.open, n);
}

/* Inserted one after another, records split the leaves they land in
 * while the node pool lasts (about a quarter of a node a record), and the
 * lists of those that come after grow instead.  Records that arrive in
 * space order (a pass or a merge, sorted) spent the pool on the
 * first part of the scene: on bench-core's box, in order of x, a third
 * of the records sat in lists at depths 3 and 4 and a lookup scanned 306
 * entries, against 38 when the same records arrived in random order.  So
 * the bulk paths build the index in a scattered order, which spreads the
 * splits over the scene: record k * 2654435761 mod n for k = 0 .. n - 1
 * (a prime above IRC_MAX_RECORDS, so every record once), the same order
 * for the same records whatever the threads. */
void irc__index_clear(irc_cache *c)
{
    IRC_MEMSET(irc__ix(c), 0, (size_t)c->capacity * sizeof(irc__ixe));
    IRC_MEMSET(irc__nodes(c), 0, (size_t)c->home->nodes_used * sizeof(irc__node));
    irc__index_reset(c);
}

void irc__index_rebuild(irc_cache *c)
{
    const uint32_t n = c->home->count;
    uint64_t k;
    for (k = 0; k < n; k++)
        irc__index_insert(c, (uint32_t)(k * 2654435761u % n));
}
