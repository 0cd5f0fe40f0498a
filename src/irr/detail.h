/*
 * detail.h -- per-pixel detail (detail.c, cfg.irr.detail_pixels).
 */
#ifndef IRC_DETAIL_H
#define IRC_DETAIL_H

#include "../base/kind.h"

/* The _px call's per-pixel answer near geometry; IRC_MISS when
 * the point is not detail (or the plain path must answer or refuse), with
 * the probes' rays in *probes for that path to count if it succeeds. */
int irc__detail_px(irc_cache *c, const float p[3], const float n[3], float footprint,
                   float rgb[3], float *weight, void *host, uint32_t *probes);

#endif
