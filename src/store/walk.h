/*
 * walk.h -- one lookup's pass over the index (walk.c).
 */
#ifndef IRC_WALK_H
#define IRC_WALK_H

#include "../base/kind.h"

/* The records a lookup at q uses, weighed and accumulated with ops (the
 * accumulator of the cache's kind, or one that answers more from the same
 * records: a gradient lookup) into acc, finished into out. */
int irc__lookup_once(irc_cache *c, const irc__acc *ops, const irc__query *q, void *out,
                     float *weight, void *acc);
/* The ids of up to cap records a lookup at q would use; *found gets how
 * many there are in all. */
int irc__collect(irc_cache *c, const irc__query *q, uint32_t *ids, uint32_t cap,
                 uint32_t *found);
/* The positions and coded normals of records ids[0 .. n - 1], read as a
 * lookup reads (under the read lock, or in a pass without). */
int irc__positions(irc_cache *c, const uint32_t *ids, uint32_t n, float (*pos)[3],
                   uint32_t *nrm);
/* A failed call takes back the CLOCK bits its lookups set. */
void irc__unmark_used(irc_cache *c, const irc__marks *m);

#endif
