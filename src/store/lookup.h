/*
 * lookup.h -- what a kind's public calls drive (lookup.c): computing in a
 * scratch slot, looking up, and lookup-or-compute.
 */
#ifndef IRC_LOOKUP_H
#define IRC_LOOKUP_H

#include "../base/kind.h"

/* Runs fn in a claimed slot; its rays in *rays and whether it waited in
 * *waited, counted by the caller (nothing of a failed call is). */
int irc__compute_quiet(irc_cache *c, const irc__kind *want, const float p[3], const float n[3],
                       void *out, void *host, int (*fn)(irc__call *k, void *out),
                       uint32_t *rays, int *waited);
/* The same, counted (a record computed when record is set). */
int irc__compute(irc_cache *c, const irc__kind *want, const float p[3], const float n[3],
                 void *out, void *host, int (*fn)(irc__call *k, void *out), int record);
int irc__lookup(irc_cache *c, const irc__kind *want, const irc__acc *ops, const float p[3],
                const float n[3], void *out, float *weight);
/* The record it computes on a miss is built in the claimed slot; rays0:
 * rays the call cast before (counted with its own, only if it succeeds). */
int irc__lookup_or_compute(irc_cache *c, const irc__kind *want, float footprint, const float p[3],
                           const float n[3], void *out, float *weight, void *host,
                           uint32_t rays0);

/* irc_cache_neighbours: the ids a lookup at (p, n) would use. */
int irc__neighbours(irc_cache *c, const float p[3], const float n[3], uint32_t *ids,
                    uint32_t cap, uint32_t *count);

#endif
