/*
 * estimator.h -- the irradiance record's estimators: irradiance and
 * radius (irradiance.c), gradients (gradient.c), visibility gradients
 * (visibility.c), the Hessian (hessian.c), and the scratch they share in a
 * thread's slot.
 */
#ifndef IRC_ESTIMATOR_H
#define IRC_ESTIMATOR_H

#include "../base/kind.h"
#include "../sample/sampler.h"

/* The irradiance record kind (kind_irr.c): its number in a block, and its
 * record's parts (kind.h) in their order. */
#define IRC__KIND_IRR_ID 1u
extern const irc__kind irc__kind_irr;
/* The kind's gradient lookup (irc_cache_lookup_gradient): its accumulator
 * answers into an irc__grad_out. */
extern const irc__acc irc__irr_grad_lookup;
typedef struct irc__grad_out {
    float *rgb;
    irc_gradient *grad;
} irc__grad_out;
enum { IRC__P_GRAD_T, IRC__P_GRAD_R, IRC__P_ELLIPSE, IRC__P_GUARD };
/* Its scratch slot's parts (kind.h), placed in this order after the
 * sampler's rays: the gradients' inverse hit distances and five rows of
 * boundary weights (gradient.c); the Hessian's rows of vertices and
 * triangle radiances (hessian.c), which take the rays' and the gradients'
 * bytes first (the Hessian runs after the last ray is cast and the
 * gradients are summed, and both fill their parts before they read them)
 * and ask only for what those lack; the strata's edges and their
 * crossings (visibility.c). */
enum { IRC__S_INV = IRC__S_KIND, IRC__S_HESS, IRC__S_EDGES, IRC__S_CROSS };

/* A gradient in the record's tangent frame (t1, t2 of the decoded normal),
 * one 2D vector per channel as int16 mantissas, each channel with its own
 * power-of-two scale 2^ex[c], so a dim channel keeps its relative
 * precision beside a bright one: 16 bytes. */
typedef struct irc__grad {
    int16_t g[6];    /* g[2c] along t1, g[2c+1] along t2 */
    int8_t ex[3];
    uint8_t unused;
} irc__grad;

/* An anisotropic record's ellipse (caches with IRC_FEATURE_HESSIAN): the
 * major axis, octahedral like the normal, and minor/major in (0, 1]; the
 * head's r is the major radius, so the index needs nothing else: 8 bytes. */
typedef struct irc__aniso {
    uint32_t axis;
    float q;
} irc__aniso;
/* hessian.c */
void irc__hessian(const irc_cache *c, const irc__sample *s, const float *dirs,
                  const float n[3], float h[3][6]);
void irc__eigen2(float a, float b, float c, float *l0, float *l1, float u[2]);

/* visibility.c */
int irc__grad_visibility(irc__call *k, int netvis, float g[3][3]);
/* Net visibility over 2 pi from a sampled hemisphere (Eq. 47). */
float irc__net_visibility(const irc_cache *c, const irc__sample *s);

/* irradiance.c: the irradiance record's estimator */
int irc__irr_compute(irc__call *k, void *rec);
/* One estimate on grid `level` at k's query (k->draw its random numbers):
 * a record built as a plain one is, without visibility gradients or
 * super-samples, or E alone (cosine-weighted strata: E = pi x the mean
 * radiance of the usable strata). */
int irc__irr_on_grid(irc__call *k, uint32_t level, irc_record *out);
int irc__irr_estimate_on(irc__call *k, uint32_t level, float e[3]);

/* progressive.c: records and per-pixel estimates whose rays follow the
 * host's samples (irc_progress).  The level for samples a pixel; a record
 * at level k->progress - 1; a new per-pixel E at level 0; an estimate at
 * level `from` taken to level `to` by independent draws
 * (IRC_ERR_NOSAMPLES from one of them skips it). */
/* Samples a pixel at which a record has the configured grid's rays: 2^10
 * (2^8 cost the Sponza atrium and floor views 1.7-2.4x the time at 64 and
 * 256 samples for 0-19% less error; docs/DESIGN.md, "Progressive hosts";
 * a build may try another). */
#ifndef IRC__PROGRESS_FULL_LOG2
#define IRC__PROGRESS_FULL_LOG2 10u
#endif
#define IRC__PROGRESS_FULL (1u << IRC__PROGRESS_FULL_LOG2)
#define IRC__PROGRESS_TOP 24u   /* the last level */
uint32_t irc__progress_level(const irc_cache *c, uint32_t samples);
uint32_t irc__progress_full(const irc_cache *c);
/* The level a kept per-pixel estimate is refined to in a cache at
 * `level`: top levels below it (T0 2^(l - top) rays, about one a sample a
 * pixel has had, as path tracing would cast for it: a detail pixel serves
 * itself alone, where a record's rays serve (a R / footprint)^2 pixels). */
uint32_t irc__detail_level(const irc_cache *c, uint32_t level);
int irc__irr_progressive(irc__call *k, irc_record *out);
int irc__irr_progressive_e(irc__call *k, float e[3]);
int irc__irr_refine(irc__call *k, irc_record *rec, uint32_t from, uint32_t to);
int irc__irr_refine_e(irc__call *k, float e[3], uint32_t from, uint32_t to);
void irc__gradients(const irc_cache *c, const irc__grid *g, const irc__sample *s,
                    const float mean[3], const float t1[3], const float t2[3], float gt[3][3],
                    float gr[3][3]);

/* A visibility discontinuity on an edge between two neighbouring strata:
 * the bracket [wa, wb] around the silhouette, a on the blocker's side, b on
 * the visible side, narrowed by bisection rays (visibility.c). */
typedef struct irc__cross {
    float wa[3], wb[3];
    float da, db;          /* distances; db = +inf when b escaped */
    float la[3], lb[3];    /* radiances */
    float na[3];           /* the blocker's unit normal at a */
    float dnear, dfar;     /* the two strata's original distances */
    float wp[3], np[3], dp;/* the blocker side before a: direction, normal,
                              depth; dp NaN until a moves */
    float ws[3], ds;       /* the silhouette's direction and depth, once
                              the rounds are done */
    int ok;                /* a silhouette (not a continuous surface) */
} irc__cross;

/* Slot floats the gradients need: the strata's inverse distances and five
 * padded rows (gradient.c). */
static inline uint64_t irc__gscratch_floats(uint32_t strata, uint32_t nphi)
{
    return (uint64_t)strata + 5u * irc__pad4(nphi);
}

/* The Hessian's rows (hessian.c): a row of vertices or of a channel of
 * triangle radiances holds a float per column, column N repeating column
 * 0 (a last block of four lanes may read it); a family of edges is taken
 * a chunk of columns at a time, its sums added to the record's Hessian
 * once a chunk: 32 columns, but 8 in rows of fewer than 64, where
 * IRC_FOOTPRINT_BOUND, which counts bytes a stratum, leaves less room. */
#define IRC__HESS_FIELDS 7u
static inline uint32_t irc__hstride(uint32_t nphi)
{
    return (nphi + 3u) / 4u * 4u + 1u;
}
static inline uint32_t irc__hchunk(uint32_t nphi)
{
    return nphi >= 64u ? 32u : nphi >= 8u ? 8u : (nphi + 3u) / 4u * 4u;
}
/* Its floats: two rows of vertices, two of radiances, three channels
 * each, and a chunk of edges' six terms and three weights (none where
 * there is no Hessian to take: fewer than 2 rows or 3 columns). */
static inline uint64_t irc__hscratch_floats(uint32_t m, uint32_t nphi)
{
    if (m < 2 || nphi < 3)
        return 0;
    return (2u * IRC__HESS_FIELDS + 6u) * (uint64_t)irc__hstride(nphi) + 9u * irc__hchunk(nphi);
}

static inline float *irc__slot_inv(const irc_cache *c, const irc__sample *s)
{
    return (float *)(void *)irc__slot_part(c, s, IRC__S_INV);
}
/* Edges: H and V per stratum, then one zenith spoke per column; then the
 * crossings, one per edge at most. */
static inline int32_t *irc__slot_edges(const irc_cache *c, const irc__sample *s)
{
    return (int32_t *)(void *)irc__slot_part(c, s, IRC__S_EDGES);
}
static inline irc__cross *irc__slot_cross(const irc_cache *c, const irc__sample *s)
{
    return (irc__cross *)(void *)irc__slot_part(c, s, IRC__S_CROSS);
}
/* The Hessian's rows (hessian.c): from the rays' part on, over the
 * gradients' into its own (kind.h). */
static inline float *irc__slot_hess(const irc_cache *c, const irc__sample *s)
{
    return (float *)(void *)irc__slot_part(c, s, IRC__S_RAYS);
}

/* The sector (of 16, 22.5 degrees each, counter-clockwise from x) holding
 * the tangent direction (x, y), from signs and comparisons with tan(22.5
 * degrees): the leak guard's lookups need no trig. */
static inline int irc__sector(float x, float y)
{
    const float t = 0.41421356237309503f, ax = x < 0.0f ? -x : x, ay = y < 0.0f ? -y : y;
    int sub = ay < t * ax ? 0 : ay < ax ? 1 : ax > t * ay ? 2 : 3;
    if (y >= 0.0f)
        return x >= 0.0f ? sub : 7 - sub;
    return x < 0.0f ? 8 + sub : 15 - sub;
}

#endif
