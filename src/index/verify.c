/*
 * Verification before trust: what irc_attach and irc_join check in a
 * block's records and index before any call reads them (the header is
 * life.c's irc__header_sane).  A block mapped from a file may be torn or
 * damaged; every link a lookup or an insert follows must stay in bounds
 * and every walk must end.  Linear in the block: each node and each list
 * entry is visited at most once, or the block is refused.
 */
#include "../block/cache.h"
#include "../bytes.h"
#include "layout.h"
#include "verify.h"

int irc__rec_head_sane(const irc_cache *c, const irc__rec *r)
{
    return irc__finite3(r->p) && irc__finite3(r->e) && irc__finite(r->r) && r->r > 0.0f &&
           r->e[0] >= 0.0f && r->e[1] >= 0.0f && r->e[2] >= 0.0f &&
           (r->n != IRC__FREE || c->kind->free_points);
}

/* A float of a record as the block holds it, or as a snapshot does
 * (little-endian bits). */
static float irc__float_at(const unsigned char *b, int le)
{
    const uint32_t u = (uint32_t)(le ? irc__le_get(b, 4) : irc__native_get(b, 4));
    float f;
    IRC_MEMCPY(&f, &u, 4);
    return f;
}

int irc__parts_sane(const irc_cache *c, const unsigned char *rec, int le)
{
    uint32_t i, at;
    for (i = 0; i < c->n_parts; i++) {
        const irc__recpart *p = &c->parts[i];
        const unsigned char *b = rec + c->off[p->id];
        if (p->sane == IRC__SANE_ELLIPSE) {
            const float q = irc__float_at(b + 4, le);
            if (!(q > 0.0f && q <= 1.0f))
                return 0;
        } else if (p->sane == IRC__SANE_FINITE) {
            for (at = 0; at + 4 <= p->bytes; at += 4)
                if (!irc__finite(irc__float_at(b + at, le)))
                    return 0;
        }
    }
    return 1;
}

int irc__rec_sane(const irc_cache *c, uint32_t id)
{
    const irc__rec *r = irc__rec_at(c, id);
    return irc__rec_head_sane(c, r) && irc__parts_sane(c, (const unsigned char *)r, 0);
}

/* A node's own fields: its children a block of 8 inside the pool, its
 * list's head a reference taken from the pool, its reach finite (-1:
 * empty). */
static int irc__node_sane(const irc_cache *c, const irc__node *n)
{
    const uint32_t used = irc__st(c)->nodes_used;
    if (n->child && (n->child > used || used - n->child < 8u || (n->child - 1u) % 8u))
        return 0;
    if (n->head != IRC__NIL && n->head >= irc__st(c)->refs_used)
        return 0;
    return irc__finite(n->reach);
}

/* Each record's references must number what its entry says (a removal
 * asserts it finds them all) and one of them be its home (range walks
 * take records there): counted without memory of our own, as sums over
 * the lists of a 64-bit hash of each reference's record, against the
 * entries' counts times the same hashes.  A reference moved to another
 * record, or a count changed, moves a sum by a hash's difference, zero
 * with probability 2^-64. */
typedef struct irc__tally {
    uint32_t entries;
    uint64_t all, homes;
} irc__tally;

static uint64_t irc__id_hash(uint32_t id)
{
    uint64_t h = ((uint64_t)id + 1u) * 0x9e3779b97f4a7c15ull;
    h ^= h >> 29;
    h *= 0xbf58476d1ce4e5b9ull;
    return h ^ h >> 32;
}

/* A list's references: each taken from the pool, to a stored record, its
 * homes first (range walks stop at the first other); together the lists
 * may not hold more than the pool's live count. */
static int irc__list_sane(const irc_cache *c, uint32_t r, irc__tally *t)
{
    const irc__ref *refs = irc__refs(c);
    uint32_t others = 0;
    for (; r != IRC__NIL; r = refs[r].next) {
        uint32_t id;
        if (r >= irc__st(c)->refs_used)
            return 0;
        id = refs[r].id & ~IRC__REF_HOME;
        if (id >= irc__st(c)->count ||
            ++t->entries > irc__st(c)->refs_live || (others && (refs[r].id & IRC__REF_HOME)))
            return 0;
        others |= !(refs[r].id & IRC__REF_HOME);
        t->all += irc__id_hash(id);
        t->homes += (refs[r].id & IRC__REF_HOME) ? irc__id_hash(id) : 0u;
    }
    return 1;
}

/* The records' entries: a finite reach, as many references as the
 * pool's live count and indexed records as the header says, each
 * record's own references and home as the lists hold them (t), and none
 * for a slot past the stored records (an insert takes the next slot as
 * unindexed). */
static int irc__entries_sane(const irc_cache *c, const irc__tally *t)
{
    const irc__ixe *ix = irc__ix(c);
    uint64_t refs = 0, all = 0, homes = 0;
    uint32_t id, indexed = 0;
    for (id = 0; id < irc__st(c)->count; id++) {
        if (!(ix[id].reach >= 0.0f) || !irc__finite(ix[id].reach))
            return 0;
        refs += ix[id].refs;
        indexed += ix[id].refs != 0;
        all += ix[id].refs * irc__id_hash(id);
        homes += ix[id].refs ? irc__id_hash(id) : 0u;
    }
    for (; id < c->capacity; id++)
        if (ix[id].refs)
            return 0;
    return refs == irc__st(c)->refs_live && indexed == irc__st(c)->indexed && all == t->all &&
           homes == t->homes;
}

/* The pool's given-back chain: references below refs_used, as many as are
 * not live. */
static int irc__free_sane(const irc_cache *c)
{
    uint32_t r, n = 0;
    for (r = irc__st(c)->ref_free; r != IRC__NIL; r = irc__refs(c)[r].next)
        if (r >= irc__st(c)->refs_used || ++n > irc__st(c)->refs_used - irc__st(c)->refs_live)
            return 0;
    return n == irc__st(c)->refs_used - irc__st(c)->refs_live;
}

/* The tree from the root, depth first with a stack of one frame a level:
 * a node met twice (a cycle, or a block shared by two parents) shows as
 * more visits than nodes, or a path deeper than the index allows.  The
 * lists are walked on the way; together they hold the pool's live
 * references, and those not in them are in its chain of given-back ones. */
static int irc__tree_sane(const irc_cache *c)
{
    const irc__node *nodes = irc__nodes(c);
    uint32_t stack[IRC__LEVELS + 2], top = 0, visits = 1;
    unsigned char next[IRC__LEVELS + 2];
    irc__tally t = {0, 0, 0};
    if (!irc__node_sane(c, &nodes[0]) || !irc__list_sane(c, nodes[0].head, &t))
        return 0;
    stack[0] = 0;
    next[0] = 0;
    while (top != (uint32_t)-1) {
        const irc__node *n = &nodes[stack[top]];
        uint32_t k;
        if (!n->child || next[top] == 8u) {
            top--;
            continue;
        }
        k = n->child + next[top]++;
        if (++visits > irc__st(c)->nodes_used || top + 1u > IRC__LEVELS ||
            !irc__node_sane(c, &nodes[k]) || !irc__list_sane(c, nodes[k].head, &t))
            return 0;
        stack[++top] = k;
        next[top] = 0;
    }
    return t.entries == irc__st(c)->refs_live && irc__free_sane(c) && irc__entries_sane(c, &t);
}

int irc__block_sane(const irc_cache *c)
{
    uint32_t id;
    for (id = 0; id < irc__st(c)->count; id++)
        if (!irc__rec_sane(c, id))
            return 0;
    return irc__tree_sane(c);
}
