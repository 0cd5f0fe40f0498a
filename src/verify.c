/*
 * Verification before trust: what irc_attach and irc_join check in a
 * block's records and index before any call reads them (the header is
 * layout.c's irc__header_sane).  A block mapped from a file may be torn or
 * damaged; every link a lookup or an insert follows must stay in bounds
 * and every walk must end.  Linear in the block: each node and each list
 * entry is visited at most once, or the block is refused.
 */
#include "cache.h"
#include "index.h"

int irc__rec_head_sane(const irc_cache *c, const irc__rec *r)
{
    return irc__finite3(r->p) && irc__finite3(r->e) && irc__finite(r->r) && r->r > 0.0f &&
           r->e[0] >= 0.0f && r->e[1] >= 0.0f && r->e[2] >= 0.0f &&
           (r->n != IRC__FREE || c->kind_id == IRC__KIND_SH);
}

int irc__rec_sane(const irc_cache *c, uint32_t id)
{
    const irc__rec *r = irc__rec_at(c, id);
    const unsigned char *b = (const unsigned char *)r;
    uint32_t i;
    if (!irc__rec_head_sane(c, r))
        return 0;
    if (c->off_a) {
        irc__aniso a;
        IRC_MEMCPY(&a, b + c->off_a, sizeof a);
        if (!(a.q > 0.0f && a.q <= 1.0f))
            return 0;
    }
    for (i = c->off_sh; c->off_sh && i + 4 <= c->rec_size; i += 4) {
        float f;
        IRC_MEMCPY(&f, b + i, 4);
        if (!irc__finite(f))
            return 0;
    }
    return 1;
}

/* A node's own fields: its children a block of 8 inside the pool, its
 * list's head a stored record, its reach finite (-1: empty). */
static int irc__node_sane(const irc_cache *c, const irc__node *n)
{
    const uint32_t used = c->home->nodes_used;
    if (n->child && (n->child > used || used - n->child < 8u || (n->child - 1u) % 8u))
        return 0;
    if (n->head != IRC__NIL && n->head >= c->home->count)
        return 0;
    return irc__finite(n->reach);
}

/* The tree from the root, depth first with a stack of one frame a level:
 * a node met twice (a cycle, or a block shared by two parents) shows as
 * more visits than nodes, or a path deeper than the index allows.  The
 * records' lists are walked on the way; together they may not hold more
 * entries than there are records. */
static int irc__tree_sane(const irc_cache *c)
{
    const irc__node *nodes = irc__nodes(c);
    const irc__ixe *ix = irc__ix(c);
    uint32_t stack[IRC__LEVELS + 2], top = 0, visits = 1, entries = 0, id;
    unsigned char next[IRC__LEVELS + 2];
    if (!irc__node_sane(c, &nodes[0]))
        return 0;
    for (id = nodes[0].head; id != IRC__NIL; id = ix[id].next)
        if (id >= c->home->count || ++entries > c->home->count)
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
        if (++visits > c->home->nodes_used || top + 1u > IRC__LEVELS || !irc__node_sane(c, &nodes[k]))
            return 0;
        for (id = nodes[k].head; id != IRC__NIL; id = ix[id].next)
            if (id >= c->home->count || ++entries > c->home->count)
                return 0;
        stack[++top] = k;
        next[top] = 0;
    }
    return 1;
}

int irc__block_sane(const irc_cache *c)
{
    uint32_t id;
    for (id = 0; id < c->home->count; id++)
        if (!irc__rec_sane(c, id))
            return 0;
    return irc__tree_sane(c);
}
