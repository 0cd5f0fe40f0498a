/*
 * lookup.h -- what a kind's public calls drive (lookup.c): computing in a
 * scratch slot, looking up, and lookup-or-compute.
 */
#ifndef IRC_LOOKUP_H
#define IRC_LOOKUP_H

#include "../base/kind.h"
#include "stats.h"

/* Runs fn in a claimed slot for a checked query; its rays in *rays and
 * whether it waited in *waited, for the caller to count (nothing of a
 * failed call is). */
int irc__compute_at(irc_cache *c, const irc__query *q, void *out, void *host,
                    int (*fn)(irc__call *k, void *out), uint32_t *rays, int *waited);
/* Checks the query, then computes and counts (a record computed when
 * record is set). */
int irc__compute(irc_cache *c, const irc__kind *want, const float p[3], const float n[3],
                 void *out, void *host, int (*fn)(irc__call *k, void *out), int record);
int irc__lookup(irc_cache *c, const irc__kind *want, const irc__acc *ops, const float p[3],
                const float n[3], void *out, float *weight);

/* A lookup-or-compute in two halves, so that a kind's step between them
 * (the _px call's per-pixel answer, detail.c) takes the checked query and
 * adds to the same tally: irc__loc_open checks everything once (the
 * cache, out, p, n, ng (NULL: none), then the footprint:
 * IRC_ERR_NONFINITE, IRC_ERR_RANGE when negative); irc__loc_finish takes
 * the step's status: IRC_MISS looks up and computes on a miss, in the
 * claimed slot; any other counts the tally (on success) and returns it.
 * The counters are written there only.  Every lookup-or-compute runs
 * through them (loc), the plain calls with no step between. */
typedef struct irc__loc {
    irc__query q;
    float footprint;
    irc__counts tally;
    int loose;   /* any record within the lookups' reach answers (blend a
                    R), not only within a R: a kept answer's point looked
                    up again (progress.c) */
} irc__loc;
int irc__loc_open(irc_cache *c, const irc__kind *want, const float p[3], const float n[3],
                 const float ng[3], float footprint, const void *out, irc__loc *px);
int irc__loc_finish(irc_cache *c, irc__loc *px, int st, void *out, float *weight, void *host);
/* Both halves with no step between and no footprint (SH records). */
int irc__lookup_or_compute(irc_cache *c, const irc__kind *want, const float p[3],
                           const float n[3], void *out, float *weight, void *host);

/* The query's geometric normal ng (NULL: none; IRC_ERR_NORMAL when zero
 * or not finite), turned to n's side: its rays that leave below it fail
 * uncast, and where n and ng lie more than 60 degrees apart the query
 * gathers around ng instead (IRC__GATHER_COS, lookup.c). */
int irc__query_ground(irc__query *q, const float ng[3]);

/* irc_cache_neighbours: the ids a lookup at (p, n) would use. */
int irc__neighbours(irc_cache *c, const float p[3], const float n[3], uint32_t *ids,
                    uint32_t cap, uint32_t *count);

#endif
