/*
 * cache.h -- the store's mutable state: the records' count, the index's
 * pools and root, the CLOCK hand, the open pass and the writer's marks.
 * It lies in the block right after the cache (form.h), at o_state, and is
 * read and written through home, under the write lock but for the fields
 * marked atomic.  Only the block, index, store and persistence layers
 * include this; the kinds see the cache's form alone.
 */
#ifndef IRC_CACHE_H
#define IRC_CACHE_H

#include "form.h"

typedef struct irc__state {
    uint32_t count;          /* records in slots [0, count) */
    uint32_t nodes_used;
    uint32_t refs_used;      /* references ever taken from the pool's end */
    uint32_t ref_free;       /* first reference given back, IRC__NIL = none */
    uint32_t refs_live;      /* references in lists */
    uint32_t indexed;        /* records with references */
    uint32_t refs_taken;     /* references taken since the lists were last
                                laid out as runs (compact.c) */
    uint32_t hand;           /* CLOCK hand */
    uint32_t root_set;
    uint32_t depth;          /* the index's deepest node level */
    uint32_t pass_open;      /* a fill pass is open (irc_pass_begin) */
    uint32_t pass_base;      /* count when it opened: its records go to
                                slots [pass_base, capacity) */
    uint32_t compacted;      /* count when the records were last renumbered
                                in the index's order (compact.c) */
    uint32_t progress;       /* progressive level + 1 (irc_progress), 0 =
                                not progressive */
    double root_c[3];        /* the root cube: centre exact in double */
    double root_h;           /* half its edge, a power of two */
    /* Atomic. */
    uint64_t pending;        /* slots the open pass has reserved (never past
                                its room) */
    uint64_t packed;         /* of those, records whole in their slots */
    uint64_t torn;           /* slots being written (torn.c): two ids + 1,
                                low and high word, 0 = none */
    uint64_t writing;        /* 1 while a writer holds the lock */
} irc__state;

/* The state, through home (a view reads and writes the shared block's). */
static inline irc__state *irc__st(const irc_cache *c)
{
    return (irc__state *)(void *)irc__part(c, c->o_state);
}

#endif
