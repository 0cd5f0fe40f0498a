/*
 * sampler.h -- hemisphere samples through the host's callback
 * (sampler.c): what every estimator draws its rays with.
 */
#ifndef IRC_SAMPLER_H
#define IRC_SAMPLER_H

#include "cache.h"
/* One stratum's sample: the estimator needs radiance and distance, nothing
 * else, so scratch is 16 bytes a stratum. */
typedef struct irc__sample {
    float l[3];
    float d;         /* hit distance; +inf when escaped; NaN when failed */
} irc__sample;

/* sampler.c */
typedef struct irc__rng { uint64_t key; } irc__rng;
irc__rng irc__rng_for(const float p[3], const float n[3], uint64_t seed);
int irc__accept_hit(const irc_hit *h, irc__sample *s);
void irc__frame(const float n[3], float t1[3], float t2[3]);
int irc__cast(irc__call *k, irc_ray *rays, irc_hit *hits, uint32_t count);

/* The hemisphere around the query's normal into the call's slot, with
 * `extra` super-samples (irc__supersample); t1, t2 get the strata's frame. */
int irc__hemisphere(irc__call *k, float t1[3], float t2[3], uint32_t extra);
int irc__sample_hemisphere(irc__call *k, const float n[3], const float t1[3],
                           const float t2[3], uint32_t first, uint32_t *used);
int irc__supersample(irc__call *k, const float n[3], const float t1[3], const float t2[3],
                     uint32_t extra);

#endif
