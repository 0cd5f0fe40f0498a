/*
 * cache.h -- internal structures shared by the files of src/.  Nothing here
 * is part of the public API; tests may include it to reach the internals.
 */
#ifndef IRC_CACHE_H
#define IRC_CACHE_H

#include "irrcache.h"
#include "util.h"

#define IRC__MAGIC 0x69726331u /* "irc1" */
#define IRC__NIL 0xffffffffu
#define IRC__ALIGN 64u

/* Stored record: the position and radius come first so that the index's
 * distance test touches one cache line.  32 bytes; gradients follow. */
typedef struct irc__rec {
    float p[3];
    float r;         /* R_i */
    float e[3];
    uint32_t n;      /* octahedral normal, 16 + 16 bits */
} irc__rec;

/* A gradient in the record's tangent frame (t1, t2 of the decoded normal),
 * one 2D vector per channel, as int16 times one shared scale: 16 bytes. */
typedef struct irc__grad {
    float scale;
    int16_t g[6];    /* g[2c] along t1, g[2c+1] along t2 */
} irc__grad;

/* Octree node.  Its cube is implied by the path from the root. */
typedef struct irc__node {
    uint32_t child;  /* first of 8 consecutive children, 0 = leaf */
    uint32_t head;   /* first record stored at this node (IRC__NIL = none) */
    float reach;     /* largest a*R_i of any record in this subtree */
    uint32_t count;  /* records stored at this node itself */
} irc__node;

enum {
    IRC__C_INSERTS, IRC__C_EVICTIONS, IRC__C_LOOKUPS,
    IRC__C_HITS, IRC__C_COMPUTES, IRC__C_RAYS, IRC__C_COUNT
};

/* One stratum's sample: the estimator needs radiance and distance, nothing
 * else, so scratch is 16 bytes a stratum. */
typedef struct irc__sample {
    float l[3];
    float d;         /* hit distance; +inf when escaped; NaN when failed */
} irc__sample;

struct irc_cache {
    uint32_t magic;
    uint32_t capacity;
    irc_config cfg;          /* defaults applied; buffer = the caller's */
    const irc_port *port;
    uint32_t rec_size;       /* 32, 48 or 64 */
    uint32_t off_t, off_r;   /* byte offsets of the gradients, 0 = absent */
    uint32_t strata;         /* M * N */
    uint32_t slot_samples;   /* samples a scratch slot holds: M N, or 2 M N
                                in an SH cache (free points: two hemispheres) */
    uint32_t keep_geom;      /* the sampler keeps directions and hit normals */
    uint32_t sh_n, sh_ch;    /* SH cache: L*L coefficients, channels; else 0 */
    uint32_t off_sh, off_shg;/* byte offsets of SH coefficients and gradients,
                                0 = absent */
    uint32_t node_cap;       /* nodes in the pool (1 + 8 k) */
    size_t slot_bytes;       /* scratch bytes per thread slot */
    size_t total_bytes;      /* bytes of the block in use from the cache on */
    void *lock;
    unsigned char *records;
    uint32_t *next;          /* per record: next record in its node's list */
    irc__node *nodes;
    uint64_t *used;          /* CLOCK bits, NULL without eviction */
    unsigned char *scratch;
    /* Mutable under the write lock. */
    uint32_t count;          /* records in slots [0, count) */
    uint32_t nodes_used;
    uint32_t hand;           /* CLOCK hand */
    uint32_t root_set;
    double root_c[3];        /* the root cube, on the power-of-two grid */
    double root_h;           /* half its edge, a power of two */
    /* Atomic. */
    uint64_t slots_busy;     /* bit t: scratch slot t in use */
    uint64_t ctr[IRC__C_COUNT];
};

/* config.c */
int irc__check_vec(const float v[3]);
int irc__check_normal(const float n[3], double unit[3]);

/* sampler.c */
typedef struct irc__rng { uint64_t key; } irc__rng;
irc__rng irc__rng_for(const float p[3], const float n[3], uint64_t seed);
int irc__accept_hit(const irc_hit *h, irc__sample *s);
void irc__direction(const irc__rng *rng, uint32_t j, uint32_t k, uint32_t m,
                    uint32_t nphi, int uniform, const double n[3], const double t1[3],
                    const double t2[3], float dir[3]);
void irc__rng_pair(const irc__rng *rng, uint32_t i, double *u1, double *u2);
void irc__frame(const double n[3], double t1[3], double t2[3]);
int irc__sample_hemisphere(irc_cache *c, unsigned char *slot, const float p[3],
                           const double n[3], const double t1[3],
                           const double t2[3], uint32_t first, uint32_t *used);

/* sh.c */
#define IRC__SH_MAX_BANDS 5
#define IRC__FREE 0xffffffffu /* irc__rec.n of a free-point SH record */
#define IRC__NC (IRC__SH_MAX_BANDS * IRC__SH_MAX_BANDS)
void irc__sh_eval(int bands, const double s[3], double *y, double (*grad)[3]);

/* shgrad.c: an SH record's samples summed, in double. */
typedef struct irc__shsum {
    double c[3][IRC__NC];
    double g[3][3 * IRC__NC]; /* d c_i / dp at [3 i + k] */
    double e[3];
    double inv_d;
    uint32_t used, total;
} irc__shsum;
int irc__sh_sample(irc_cache *c, unsigned char *slot, const float p[3], const double *un,
                   irc__shsum *a);

/* visibility.c */
int irc__grad_visibility(irc_cache *c, unsigned char *slot, const float p[3],
                         const double n[3], int netvis, double g[3][3], uint32_t *rays);

/* record.c */
int irc__slot_claim(irc_cache *c, uint32_t *t);
int irc__sample_at(irc_cache *c, const float p[3], const float n[3], const void *out,
                   double un[3], double t1[3], double t2[3], uint32_t *t);
void irc__slot_release(irc_cache *c, uint32_t t);
void irc__record_build(const irc_cache *c, const irc__sample *s,
                       const double n[3], const double t1[3],
                       const double t2[3], double gvis[3][3], irc_record *out);
uint32_t irc__oct_encode(const double n[3]);
void irc__oct_decode(uint32_t code, float n[3]);
void irc__record_pack(const irc_cache *c, const irc_record *in, void *dst);
void irc__record_unpack(const irc_cache *c, const void *src, irc_record *out);
int irc__record_check(const irc_record *r);

/* weight.c */
int irc__weigh(const irc_cache *c, const irc__rec *r, const float p[3],
               const float n[3], double *w, float ni[3]);
void irc__extrapolate(const irc_cache *c, const irc__rec *r, const float ni[3],
                      const float p[3], const float n[3], double out[3]);

/* cache.c */
int irc__check_cache(const irc_cache *c);
int irc__store(irc_cache *c, const void *packed);
void irc__mark_used(irc_cache *c, uint32_t id);
int irc__count_lookup(irc_cache *c, int st);
int irc__count_miss(irc_cache *c, int ins);
void irc__count_compute(irc_cache *c, uint64_t rays);

/* index.c */
/* Called with the first record of each visited node's list. */
typedef void (*irc__visit_fn)(void *ud, uint32_t head);
void irc__index_reset(irc_cache *c);
void irc__index_insert(irc_cache *c, uint32_t id);
void irc__index_remove(irc_cache *c, uint32_t id);
void irc__index_query(const irc_cache *c, const float p[3], irc__visit_fn fn,
                      void *ud);

static inline irc__rec *irc__rec_at(const irc_cache *c, uint32_t id)
{
    return (irc__rec *)(void *)(c->records + (size_t)id * c->rec_size);
}

/* A visibility discontinuity on an edge between two neighbouring strata:
 * the bracket [wa, wb] around the silhouette, a on the blocker's side, b on
 * the visible side, narrowed by bisection rays (visibility.c). */
typedef struct irc__cross {
    float wa[3], wb[3];
    float da, db;          /* distances; db = +inf when b escaped */
    float la[3], lb[3];    /* radiances */
    float na[3];           /* the blocker's unit normal at a */
    float dnear, dfar;     /* the two strata's original distances */
    int ok;                /* a silhouette (not a continuous surface) */
} irc__cross;

/* A thread's scratch slot: the samples (slot_samples of them), one batch of
 * rays and hits, two weights per row of strata for the translational
 * gradient; with IRC_FEATURE_VISIBILITY or SH each sample's direction and
 * hit normal; with VISIBILITY per stratum two edge indices and room for two
 * crossings (plus a spoke and a crossing per column). */
static inline irc_ray *irc__slot_rays(const irc_cache *c, unsigned char *slot)
{
    return (irc_ray *)(void *)(slot + (size_t)c->slot_samples * sizeof(irc__sample));
}

static inline double *irc__slot_rows(const irc_cache *c, const irc__sample *s)
{
    return (double *)(void *)((unsigned char *)(void *)(irc__sample *)s +
                              (size_t)c->slot_samples * sizeof(irc__sample) +
                              (size_t)c->cfg.max_batch * (sizeof(irc_ray) + sizeof(irc_hit)));
}

static inline float *irc__slot_dirs(const irc_cache *c, const irc__sample *s)
{
    return (float *)(void *)(irc__slot_rows(c, s) + 2u * c->cfg.strata_theta);
}

static inline float *irc__slot_normals(const irc_cache *c, const irc__sample *s)
{
    return irc__slot_dirs(c, s) + 3u * c->slot_samples;
}

static inline int32_t *irc__slot_edges(const irc_cache *c, const irc__sample *s)
{
    return (int32_t *)(void *)(irc__slot_normals(c, s) + 3u * c->slot_samples);
}

/* Edges: H and V per stratum, then one zenith spoke per column; then the
 * crossings, one per edge at most. */
static inline irc__cross *irc__slot_cross(const irc_cache *c, const irc__sample *s)
{
    return (irc__cross *)(void *)(irc__slot_edges(c, s) + 2u * c->strata + c->cfg.strata_phi);
}

/* The first test of irc__weigh, inlined where records are scanned: most
 * candidates fail it, and it needs only the record's first 16 bytes. */
static inline int irc__within_reach(const irc_cache *c, const irc__rec *r, const float p[3])
{
    double dx = (double)p[0] - r->p[0], dy = (double)p[1] - r->p[1],
           dz = (double)p[2] - r->p[2], ra = (double)c->cfg.accuracy * r->r;
    return dx * dx + dy * dy + dz * dz < ra * ra;
}

#endif
