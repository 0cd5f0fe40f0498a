/*
 * stats.h -- the block's counters (stats.c).
 */
#ifndef IRC_STATS_H
#define IRC_STATS_H

#include "../kind/kind.h"

/* Adds v to counter which (IRC__C_*) in the caller's stripe. */
void irc__count(irc_cache *c, int which, uint64_t v);

#endif
