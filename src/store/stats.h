/*
 * stats.h -- the block's counters (stats.c).
 */
#ifndef IRC_STATS_H
#define IRC_STATS_H

#include "../base/kind.h"

enum {
    IRC__C_INSERTS, IRC__C_EVICTIONS, IRC__C_LOOKUPS, IRC__C_HITS,
    IRC__C_COMPUTES, IRC__C_RAYS, IRC__C_NOT_STORED, IRC__C_WAITS, IRC__C_DETAILS,
    IRC__C_COUNT
};
/* A stripe: the counters, rounded up to whole cache lines. */
#define IRC__STRIPE_BYTES \
    ((IRC__C_COUNT * sizeof(uint64_t) + IRC__ALIGN - 1) / IRC__ALIGN * IRC__ALIGN)


/* The counters, in IRC__STRIPES stripes of whole cache lines each (a part of
 * the block at o_ctr): a thread adds to the stripe its stack's address
 * picks, so threads on other cores rarely write the same line, and
 * irc_cache_stats sums the stripes.  Any thread may use any stripe; the
 * adds stay atomic. */
#define IRC__STRIPES 8u

/* Adds v to counter which (IRC__C_*) in the caller's stripe. */
void irc__count(irc_cache *c, int which, uint64_t v);

/* What one call adds to the counters, gathered as it goes and added once
 * when it succeeds (nothing of a failed call is counted). */
typedef struct irc__counts {
    uint64_t add[IRC__C_COUNT];
} irc__counts;
void irc__count_tally(irc_cache *c, const irc__counts *t);
/* irc_cache_stats: the counters summed over the stripes, the store's
 * counts and the block's sizes. */
int irc__stats(irc_cache *c, irc_stats *out);

#endif
