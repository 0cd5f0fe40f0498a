/*
 * weight.h -- whether a record counts at a query, its weight and its
 * extrapolated value (weight.c).
 */
#ifndef IRC_WEIGHT_H
#define IRC_WEIGHT_H

#include "../base/kind.h"
#include "estimator.h"
/* weight.c */
/* shaped: the record's ellipse and leak guard count (the irradiance
 * kind's parts; 0 for a kind that borrows the weight) */
int irc__weigh(const irc_cache *c, const irc__rec *r, const float p[3],
               const float n[3], int shaped, float *w, float ni[3]);
void irc__extrapolate(const irc_cache *c, const irc__rec *r, const float ni[3],
                      const float p[3], const float n[3], float out[3]);
/* both for a record with no ellipse and no guard: its weight, or 0 */
float irc__weigh_extrapolate(const irc_cache *c, const irc__rec *r, const float p[3],
                             const float n[3], float out[3]);
void irc__extrapolate_grad(const irc_cache *c, const irc__rec *r, const float ni[3],
                           const float val[3], float f, irc_gradient *g);
float irc__grad_scale(const irc__grad *g, int ch);
/* The biweight (1 - t^2)^2, t in [0, 1): a record's weight at t = e /
 * (blend a) in lookups that reach past a R */
float irc__biweight(float t);

#endif
