/*
 * compact.c -- records renumbered in the order a query visits them.
 *
 * A node's list links records by id, and ids are given in the order
 * records arrive, so the entries a lookup scans lie scattered over the
 * index and the records it accepts over the pool: one cache miss each.
 * Compaction moves every reference to its place in the index's own order
 * (depth first, children by octant, a node's list before its children,
 * each list in its order), so that each list is a run a lookup reads
 * line after line, and gives every record the id of its home reference in
 * that order, moving the records, their index entries and their CLOCK
 * bits there, so that records near in space sit near in the pool.  The tree is untouched and each list keeps
 * its order, so every query visits the same records in the same order as
 * before: lookups are bit-identical.  Record ids change (irrcache.h, at
 * irc_pass_end and irc_merge).
 */
#include "../block/cache.h"
#include "../block/torn.h"
#include "index.h"
#include "layout.h"

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

/* Pass 1: each record's new id, in its entry's refs: the order of its
 * home reference in the walk (IRC__NIL: none met). */
static void irc__number_homes(irc_cache *c, irc__node *n, void *ud)
{
    uint32_t *k = (uint32_t *)ud, r;
    const irc__ref *refs = irc__refs(c);
    for (r = n->head; r != IRC__NIL; r = refs[r].next)
        if (refs[r].id & IRC__REF_HOME && (refs[r].id & ~IRC__REF_HOME) < irc__st(c)->count)
            irc__ix(c)[refs[r].id & ~IRC__REF_HOME].refs = (*k)++;
}

/* Pass 2: each reference's new place, in its link (the list is read
 * before it is overwritten; the last of a list marked IRC__REF_HOME, no
 * place being that large), the node's head its first new place. */
static void irc__number_list(irc_cache *c, irc__node *n, void *ud)
{
    uint32_t *k = (uint32_t *)ud, r = n->head, nr;
    irc__ref *refs = irc__refs(c);
    if (r == IRC__NIL)
        return;
    n->head = *k;
    for (; r != IRC__NIL; r = nr) {
        nr = refs[r].next;
        refs[r].next = (*k)++ | (nr == IRC__NIL ? IRC__REF_HOME : 0u);
    }
}

/* Pass 3: references to their places, cycle by cycle, each list then a
 * run linked in order; the pool's given-back references after them. */
static void irc__permute_refs(irc_cache *c, uint32_t live)
{
    irc__ref *refs = irc__refs(c), e;
    uint32_t i, to, r, nr, k = live;
    for (r = irc__st(c)->ref_free; r != IRC__NIL; r = nr) {
        nr = refs[r].next;
        refs[r].next = k++;
    }
    for (i = 0; i < live; i++)
        while ((to = refs[i].next & ~IRC__REF_HOME) != i) {
            e = refs[i];
            refs[i] = refs[to];
            refs[to] = e;
        }
    for (i = 0; i < live; i++)
        refs[i].next = (refs[i].next & IRC__REF_HOME) ? IRC__NIL : i + 1u;
    irc__st(c)->refs_used = live;
    irc__st(c)->ref_free = IRC__NIL;
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

/* Each record's count of references, from the lists. */
static void irc__count_list(irc_cache *c, irc__node *n, void *ud)
{
    const irc__ref *refs = irc__refs(c);
    uint32_t r;
    (void)ud;
    for (r = n->head; r != IRC__NIL; r = refs[r].next)
        if ((refs[r].id & ~IRC__REF_HOME) < irc__st(c)->count)
            irc__ix(c)[refs[r].id & ~IRC__REF_HOME].refs++;
}

static void irc__recount(irc_cache *c, uint32_t count)
{
    uint32_t i;
    for (i = 0; i < count; i++)
        irc__ix(c)[i].refs = 0;
    irc__walk_nodes(c, irc__count_list, NULL);
}

/* Pass 4: the records' permutation applied in place, cycle by cycle: each
 * swap puts one record (with its entry and bit) at its new id for good;
 * the references renamed first. */
static void irc__permute(irc_cache *c, uint32_t count, uint32_t live)
{
    irc__ixe *ix = irc__ix(c), e;
    irc__ref *refs = irc__refs(c);
    uint32_t i, to;
    for (i = 0; i < live; i++)
        refs[i].id = ix[refs[i].id & ~IRC__REF_HOME].refs | (refs[i].id & IRC__REF_HOME);
    for (i = 0; i < count; i++)
        while ((to = ix[i].refs) != i) {
            irc__rec_swap(c, i, to);
            e = ix[i];
            ix[i] = ix[to];
            ix[to] = e;
            irc__swap_used(c, i, to);
        }
    irc__recount(c, count);
}

/* Every reference of the pool below refs_used is in a list or given
 * back: else there is no permutation of them. */
static int irc__refs_whole(const irc_cache *c)
{
    const irc__state *h = irc__st(c);
    uint32_t r, n = 0;
    for (r = h->ref_free; r != IRC__NIL && n <= h->refs_used; r = irc__refs(c)[r].next)
        n++;
    return n + h->refs_live == h->refs_used;
}

/* Every record below count has one home, and the references are whole:
 * else there is no permutation, and the index is left as it is. */
static int irc__homes_numbered(irc_cache *c)
{
    const irc__state *h = irc__st(c);
    uint32_t r, k = 0;
    if (h->indexed != h->count || !irc__refs_whole(c))
        return 0;
    for (r = 0; r < h->count; r++)
        irc__ix(c)[r].refs = IRC__NIL;
    irc__walk_nodes(c, irc__number_homes, &k);
    for (r = 0; r < h->count; r++)
        if (irc__ix(c)[r].refs == IRC__NIL)
            break;
    return k == h->count && r == h->count;
}

void irc__index_compact(irc_cache *c)
{
    const uint32_t count = irc__st(c)->count, live = irc__st(c)->refs_live;
    uint32_t k = 0;
    if (count == 0)
        return;
    if (!irc__homes_numbered(c)) {
        IRC_ASSERT(0);
        irc__recount(c, count);
        return;
    }
    irc__walk_nodes(c, irc__number_list, &k);
    irc__permute_refs(c, live);
    irc__permute(c, count, live);
    irc__st(c)->refs_taken = 0;
    irc__st(c)->compacted = count;
}

/* Filled freely, references are taken in the order records arrive, so a
 * list's lie scattered over the pool and a lookup reads each on a line of
 * its own (at 1e6 records in random order, five times slower than after
 * a pass).  When a quarter as many references have been taken since the
 * lists were last laid out as runs as the lists hold (while the pool
 * grows, or turns over under CLOCK eviction), they are laid out again:
 * records stay where they are (ids do not change) and every list keeps
 * its order (lookups bit for bit the same).  That moves each reference
 * about four times for each one taken, and leaves at most a fifth of the
 * lists' references out of their runs (a doubling rule left up to half:
 * random lookups at 1e6 records ran at 0.13-0.44 M/s by where the fill
 * stopped). */
void irc__index_tidy(irc_cache *c)
{
    irc__state *h = irc__st(c);
    uint32_t k = 0;
    if (h->refs_taken < 4096u || h->refs_taken < h->refs_live / 4u || !irc__refs_whole(c))
        return;
    irc__walk_nodes(c, irc__number_list, &k);
    irc__permute_refs(c, h->refs_live);
    h->refs_taken = 0;
}

/* Inserted one after another, records split the leaves they land in
 * while the node pool lasts (about a quarter of a node a record), and the
 * lists of those that come after grow instead.  Records that arrive in
 * space order (a merge, sorted) spent the pool on the first part of the
 * scene: on bench-core's box, in order of x, a third of the records sat
 * in lists at depths 3 and 4 and a lookup scanned 306 entries, against 38
 * when the same records arrived in random order.  So the bulk paths
 * (merges, repairs) build the index in a scattered order, which spreads the
 * splits over the scene: record k * 2654435761 mod n for k = 0 .. n - 1
 * (a prime above IRC_MAX_RECORDS, so every record once), the same order
 * for the same records whatever the threads. */
void irc__index_clear(irc_cache *c)
{
    IRC_MEMSET(irc__ix(c), 0, (size_t)c->capacity * sizeof(irc__ixe));
    IRC_MEMSET(irc__nodes(c), 0, (size_t)irc__st(c)->nodes_used * sizeof(irc__node));
    IRC_MEMSET(irc__refs(c), 0, (size_t)irc__st(c)->refs_used * sizeof(irc__ref));
    irc__index_reset(c);
}

void irc__index_rebuild(irc_cache *c)
{
    const uint32_t n = irc__st(c)->count;
    uint64_t k;
    for (k = 0; k < n; k++)
        irc__index_insert(c, (uint32_t)(k * 2654435761u % n));
}

void irc__forget_locked(irc_cache *c)
{
    irc__st(c)->hand = 0;
    if (c->o_used)
        IRC_MEMSET(irc__used(c), 0, ((size_t)c->capacity + 63u) / 64u * sizeof(uint64_t));
    irc__index_clear(c);
}

void irc__clear_locked(irc_cache *c)
{
    irc__st(c)->count = 0;
    IRC_MEMSET(irc__rec_at(c, 0), 0, (size_t)c->capacity * c->rec_size);
    irc__forget_locked(c);
}
