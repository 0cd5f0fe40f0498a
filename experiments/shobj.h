/*
 * shobj.h -- what the SH-gradient paper's experiments (shexp.c, shanim.c)
 * share: the `sh` scene's object as a receiver of the rest of the scene.
 * The environment is the scene without its spheres (the object does not
 * light or shadow its surroundings); records sit at free points and see
 * the three emitters and the ground they light (4 light samples a hit).
 * The object is shaded unshadowed from SH coefficients: a convex sphere's
 * only self-occlusion is its own tangent plane, which the clamped cosine
 * and the lobe's cut at the horizon already carry.
 */
#ifndef EXPERIMENTS_SHOBJ_H
#define EXPERIMENTS_SHOBJ_H

#include "bvh.h"
#include "irrcache.h"
#include "scene.h"
#include "shade.h"

#define SHOBJ_BANDS 5
#define SHOBJ_NC (SHOBJ_BANDS * SHOBJ_BANDS)

typedef struct sh_env {
    const scene *s;
    bvh b;
    lights l;
    uint64_t seed; /* the records' sampling pattern and the hits' light samples */
    float power;   /* Eq. 16's exponent b (0: the library's default) */
    float min_radius; /* the records' least R_j: 10 (sh_env_init's) makes
                         every record's R_j 10, so weights are |p - p_j|^-b
                         and every record reaches every point */
} sh_env;

/* copy = src without its spheres, plus `blocker` (may be NULL) of a black
 * material; e traces copy.  0 or -1. */
int sh_env_init(sh_env *e, const scene *src, scene *copy, const sphere *blocker);
void sh_env_free(sh_env *e, scene *copy);

/* The trace callback (context: the sh_env). */
int sh_env_trace(const irc_trace_args *a);

/* A cache of SH records (L = SHOBJ_BANDS, m x n strata a hemisphere, room
 * for 64, a = 10, R_j at least e->min_radius); *block is the caller's to
 * free after irc_fini.  NULL on failure. */
irc_cache *sh_env_cache(sh_env *e, uint32_t features, uint32_t m, uint32_t n, void **block);

/* Outgoing radiance at a surface point of normal n seen along d:
 * kd/pi E(n) + ks (Ns+2)/(2 pi) G(r, Ns) from the coefficients. */
void sh_shade(const irc_sh *c, const material *m, const float n[3], const float d[3],
              float out[3]);

/* The pixels of a w x w view from `cam` that see sphere o: 9 floats each
 * (point, normal, view direction) in pts, the pixel's index y*w + x in
 * pix (may be NULL).  Returns the count. */
int sh_object_pixels(const camera *cam, const sphere *o, int w, float *pts, int *pix);

/* sqrt(sum (a-b)^2 / sum b^2) over n RGB triples. */
double sh_rel_rmse(const float *a, const float *b, int n);

/* A record at every pixel's point, shaded there.  0 or -1. */
int sh_truth(sh_env *e, const material *m, const float *pts, int np, uint32_t mm,
             uint32_t nn, float *out);

/* Records at `count` points `at` (with gradients when features says so),
 * looked up at every pixel and shaded.  0 or -1. */
int sh_method(sh_env *e, const material *m, const float *pts, int np, const float (*at)[3],
              int count, uint32_t features, uint32_t mm, uint32_t nn, float *out);

#endif
