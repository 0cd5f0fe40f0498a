/*
 * sampler.h -- hemisphere samples through the host's callback
 * (sampler.c): what every estimator draws its rays with.
 */
#ifndef IRC_SAMPLER_H
#define IRC_SAMPLER_H

#include "../block/form.h"
#include "grid.h"

/* One stratum's sample: the estimator needs radiance and distance, nothing
 * else, so scratch is 16 bytes a stratum. */
typedef struct irc__sample {
    float l[3];
    float d;         /* hit distance; +inf when escaped; NaN when failed */
} irc__sample;

/* A slot's parts (kind.h, IRC__S_*), where life.c placed them; s is
 * the start of the slot's working area, where its samples lie. */
static inline unsigned char *irc__slot_part(const irc_cache *c, const void *s, int part)
{
    return (unsigned char *)(uintptr_t)s + c->soff[part];
}
static inline irc_ray *irc__slot_rays(const irc_cache *c, unsigned char *slot)
{
    return (irc_ray *)(void *)irc__slot_part(c, slot, IRC__S_RAYS);
}
static inline float *irc__slot_dirs(const irc_cache *c, const irc__sample *s)
{
    return (float *)(void *)irc__slot_part(c, s, IRC__S_DIRS);
}
static inline float *irc__slot_normals(const irc_cache *c, const irc__sample *s)
{
    return (float *)(void *)irc__slot_part(c, s, IRC__S_NORMALS);
}
/* sampler.c */
typedef struct irc__rng { uint64_t key; } irc__rng;
irc__rng irc__rng_for(const float p[3], const float n[3], uint64_t seed);
int irc__accept_hit(const irc_hit *h, irc__sample *s);

/* The hemisphere around the query's normal into the call's slot on grid
 * g, with `extra` super-samples (irc__supersample); t1, t2 get the
 * strata's frame. */
int irc__hemisphere(irc__call *k, const irc__grid *g, float t1[3], float t2[3],
                    uint32_t extra);
int irc__sample_hemisphere(irc__call *k, const irc__grid *g, const float n[3],
                           const float t1[3], const float t2[3], uint32_t first);
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
