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

/* A grid of strata: M rows in theta, N columns in phi, and its table of
 * angles and weights (gradient.c).  Level 0 is the configured grid; level
 * l halves M and N l times, for records that serve few pixels
 * (irradiance.c, "Records that cost what they serve"). */
#define IRC__GRIDS 3u
typedef struct irc__grid {
    uint32_t m, nphi, strata, level;
    const float *tab;
} irc__grid;

/* gradient.c: the grids' tables, made at init from the config alone */
uint32_t irc__grid_levels(uint32_t m, uint32_t nphi);
uint64_t irc__gtab_bytes(uint32_t m, uint32_t nphi);
void irc__gtab_fill(uint32_t m, uint32_t nphi, void *tab);
void irc__grid_at(const irc_cache *c, uint32_t level, irc__grid *g);

/* sampler.c */
typedef struct irc__rng { uint64_t key; } irc__rng;
irc__rng irc__rng_for(const float p[3], const float n[3], uint64_t seed);
int irc__accept_hit(const irc_hit *h, irc__sample *s);
int irc__cast(irc__call *k, irc_ray *rays, irc_hit *hits, uint32_t count);

/* The hemisphere around the query's normal into the call's slot on grid
 * g, with `extra` super-samples (irc__supersample); t1, t2 get the
 * strata's frame. */
int irc__hemisphere(irc__call *k, const irc__grid *g, float t1[3], float t2[3],
                    uint32_t extra);
int irc__sample_hemisphere(irc__call *k, const irc__grid *g, const float n[3],
                           const float t1[3], const float t2[3], uint32_t first,
                           uint32_t *used);
int irc__supersample(irc__call *k, const irc__grid *g, const float n[3], const float t1[3],
                     const float t2[3], uint32_t extra);
/* The samples of grid `from` (level l) refined into grid `to` (level l -
 * 1) in place, the first samples having been drawn on level top: each
 * sample moves to the finer stratum it lies in, and the other three
 * strata of its 2 x 2 block get a ray each.  Every finer stratum then
 * holds one sample uniform within it, as if sampled anew. */
int irc__refine(irc__call *k, uint32_t top, const irc__grid *from, const irc__grid *to,
                const float t1[3], const float t2[3]);

#endif
