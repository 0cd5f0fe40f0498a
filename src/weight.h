/*
 * weight.h -- whether a record counts at a query, its weight and its
 * extrapolated value (weight.c).
 */
#ifndef IRC_WEIGHT_H
#define IRC_WEIGHT_H

#include "cache.h"
/* weight.c */
int irc__weigh(const irc_cache *c, const irc__rec *r, const float p[3],
               const float n[3], float *w, float ni[3]);
void irc__extrapolate(const irc_cache *c, const irc__rec *r, const float ni[3],
                      const float p[3], const float n[3], float out[3]);
void irc__extrapolate_grad(const irc_cache *c, const irc__rec *r, const float ni[3],
                           const float val[3], float f, irc_gradient *g);
float irc__grad_scale(const irc__grad *g, int ch);

/* The first test of irc__weigh, inlined where records are scanned: most
 * candidates fail it, and it needs only the record's first 16 bytes. */
static inline int irc__within_reach(const irc_cache *c, const irc__rec *r, const float p[3])
{
    float dx = (float)p[0] - r->p[0], dy = (float)p[1] - r->p[1],
           dz = (float)p[2] - r->p[2], ra = (float)c->cfg.accuracy * r->r;
    float d2 = dx * dx + dy * dy + dz * dz;
    /* d2 == 0: a record serves its own point even when (a R)^2 underflows
     * (an open-sky record's R is FLT_MIN) */
    return d2 < ra * ra || d2 == 0.0f;
}

#endif
