/*
 * trace.h -- the host's trace callback (trace.c).
 */
#ifndef IRC_TRACE_H
#define IRC_TRACE_H

#include "../base/kind.h"

/* Casts count rays through cfg.trace with the call's arguments; k->rays
 * counts them.  IRC_OK, IRC_ERR_CALLBACK for a positive return, or the
 * callback's negative code. */
int irc__cast(irc__call *k, irc_ray *rays, irc_hit *hits, uint32_t count);
/* irc__cast of rays whose distances alone are read, flagged to the host
 * as such: why is an irc_visibility. */
int irc__cast_visibility(irc__call *k, irc_ray *rays, irc_hit *hits, uint32_t count,
                         uint32_t why);
/* A hit of a ray cast with visibility_only: 1 a hit (its dist > 0 and
 * finite), 0 escaped or failed, IRC_ERR_CALLBACK for a bad status or
 * distance; nothing else of it is read. */
int irc__visibility_hit(const irc_hit *h);

#endif
