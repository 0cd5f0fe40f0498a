/*
 * stats.c -- the counters, in stripes of whole cache lines so that threads on
 * other cores rarely write the same line (stats.h, IRC__STRIPES), and
 * irc_cache_stats, which sums them and reports the block's bytes.
 */
#include "../block/cache.h"
#include "../block/check.h"
#include "../index/index.h"
#include "../index/layout.h"
#include "lock.h"
#include "stats.h"

static inline uint64_t *irc__stripe(const irc_cache *c, uint32_t s)
{
    return (uint64_t *)(void *)irc__part(c, c->o_ctr + (size_t)s * IRC__STRIPE_BYTES);
}

/* The calling thread's stripe: its stack's address above 64 KiB
 * granules, hashed (threads' stacks lie megabytes apart; one thread's
 * calls stay within one granule or two). */
static uint32_t irc__my_stripe(void)
{
    unsigned char here;
    uint64_t a = (uint64_t)(uintptr_t)&here >> 16;
    return (uint32_t)((a * 0x9e3779b97f4a7c15ull) >> 61) % IRC__STRIPES;
}

void irc__count(irc_cache *c, int which, uint64_t v)
{
    c->port->fetch_add(&irc__stripe(c, irc__my_stripe())[which], v);
}

void irc__count_tally(irc_cache *c, const irc__counts *t)
{
    uint64_t *stripe = irc__stripe(c, irc__my_stripe());
    int i;
    for (i = 0; i < IRC__C_COUNT; i++)
        if (t->add[i])
            c->port->fetch_add(&stripe[i], t->add[i]);
}

static uint64_t irc__counter(const irc_cache *c, int which)
{
    uint64_t sum = 0;
    uint32_t s;
    for (s = 0; s < IRC__STRIPES; s++)
        sum += c->port->load(&irc__stripe(c, s)[which]);
    return sum;
}

int irc__stats(irc_cache *c, irc_stats *out)
{
    int st = irc__enter(c, NULL);
    if (st < 0)
        return st;
    if (!out)
        return IRC_ERR_NULL;
    if (irc__read_lock(c) < 0)
        return IRC_ERR_PORT;
    IRC_MEMSET(out, 0, sizeof *out);
    out->records = irc__st(c)->count;
    out->index_nodes = irc__st(c)->nodes_used;
    out->index_refs = irc__st(c)->refs_live;
    irc__read_unlock(c);
    out->capacity = c->capacity;
    out->inserts = irc__counter(c, IRC__C_INSERTS);
    out->evictions = irc__counter(c, IRC__C_EVICTIONS);
    out->lookups = irc__counter(c, IRC__C_LOOKUPS);
    out->hits = irc__counter(c, IRC__C_HITS);
    out->computes = irc__counter(c, IRC__C_COMPUTES);
    out->not_stored = irc__counter(c, IRC__C_NOT_STORED);
    out->waits = irc__counter(c, IRC__C_WAITS);
    out->details = irc__counter(c, IRC__C_DETAILS);
    out->rays = irc__counter(c, IRC__C_RAYS);
    out->index_nodes_max = c->node_cap;
    out->index_refs_max = c->ref_cap;
    out->record_bytes = c->rec_size;
    out->bytes_records = (size_t)c->capacity * c->rec_size;
    out->bytes_index = (size_t)c->capacity * sizeof(irc__ixe) +
                       (size_t)c->node_cap * sizeof(irc__node) +
                       (size_t)c->ref_cap * sizeof(irc__ref) +
                       (c->o_used ? ((size_t)c->capacity + 63u) / 64u * 8u : 0u);
    out->bytes_scratch = (size_t)c->cfg.threads * c->slot_bytes;
    out->bytes_total = c->total_bytes;
    return IRC_OK;
}
