/*
 * detail.h -- per-pixel detail (detail.c, cfg.irr.detail_pixels).
 */
#ifndef IRC_DETAIL_H
#define IRC_DETAIL_H

#include "../store/lookup.h"

/* The _px call's per-pixel answer near geometry, between the halves of a
 * lookup-or-compute (lookup.h), for px's checked query: IRC_DETAIL (rgb
 * written), IRC_MISS when the point is not detail or no slot is to be had
 * (the lookup answers), or a negative code; its rays and counts go to
 * px's tally. */
int irc__detail_px(irc_cache *c, irc__loc *px, float rgb[3], void *host);

#endif
