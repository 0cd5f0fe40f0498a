/*
 * kind.h -- what the store and a record kind agree on: the record's head,
 * a query, a computation in progress, a kind's table (its config, its
 * record's parts, its scratch, compute, check, pack, unpack, answer) and a
 * lookup accumulator's table (weigh, begin, accumulate, finish, find).  The
 * kinds are listed in one place, kinds.c; the store reaches them only
 * through these tables.  A kind's own files: kind_irr.c and the irradiance
 * estimators (estimator.h), kind_sh.c and the SH estimator (shrec.h).
 */
#ifndef IRC_KIND_H
#define IRC_KIND_H

#include "../util.h"
#include "irrcache.h"

/* No record (an id, a list's end). */
#define IRC__NIL 0xffffffffu
/* The radius cap as a float: compared as the literal, an x87 build (i386)
 * keeps 1e30 unrounded and finds the stored cap above it. */
#define IRC__CAP ((float)IRC_RADIUS_CAP)
/* irc__rec.n of a record at a free point (a kind with free_points). */
#define IRC__FREE 0xffffffffu

/* Stored record: the position and radius come first so that the index's
 * distance test touches one cache line.  32 bytes; the kind's parts
 * follow. */
typedef struct irc__rec {
    float p[3];
    float r;         /* R_i */
    float e[3];
    uint32_t n;      /* octahedral normal, 16 + 16 bits; IRC__FREE = none */
} irc__rec;

/* The CLOCK bits a lookup set, so that a call that then fails clears them
 * and leaves the block as it was (store.c).  Past IRC__MARKS new bits it
 * sets no more: a use bit is a hint. */
#define IRC__MARKS 8u
typedef struct irc__marks {
    uint32_t id[IRC__MARKS];
    uint32_t n;
} irc__marks;

/* A validated query: the point, and the unit normal (zero for a free
 * point). */
typedef struct irc__query {
    float p[3];
    float n[3];
    float g[3];             /* the geometric normal on n's side, when under */
    int under;              /* rays leaving below g fail uncast (trace.c) */
    int free;
    const uint32_t *hidden; /* records the lookup leaves out (cfg.
                               check_visibility): n_hidden ids, ascending */
    uint32_t n_hidden;
    const uint32_t *among;  /* non-NULL: the walk visits these n_among ids,
                               in order, instead of the index's lists (a
                               confirmed lookup's second walk: the ids its
                               first walk accepted, in its order) */
    uint32_t n_among;
    irc__marks *marks;      /* NULL: a lookup that cannot fail after it reads */
    int place;              /* in a cache whose lookups reach past a R:
                               a miss unless a record lies within a R
                               (form.h, w_inner), the rule of every call
                               but a progressive pixel's loose look */
} irc__query;

/* One record computation in progress: the cache, its claimed scratch
 * slot, the host's per-call pointer, the query, and rays cast so far. */
typedef struct irc__call {
    irc_cache *c;
    unsigned char *slot;
    void *host;
    irc__query q;
    uint32_t rays;
    float footprint;  /* a pixel's width at the query, 0 = none */
    uint32_t visibility_only; /* args->visibility_only while casting: an
                                 irc_visibility (confirm.c, detail.c), or 0 */
    uint32_t progress;  /* the cache's progressive level + 1 (irc_progress),
                           0 = not progressive */
    uint32_t draw;      /* which of a point's independent estimates this is:
                           0 the first, k > 0 a refinement's (progressive.c) */
} irc__call;

/* A record's parts after its 32-byte head, each numbered by its kind (0 ..
 * IRC__PARTS - 1), which lists those a config asks for in order
 * (irc__kind.parts); life.c places them one after another and the
 * block's header keeps their byte offsets (irc_cache.off[id], 0 =
 * absent).  A part's fields are `lead` bytes of width w1, then the rest of
 * width w2: the snapshot's byte order and the merge order walk them field
 * by field.  `sane` says what a part a cache could have made holds
 * (verify.c): anything, finite floats, or an ellipse's minor/major ratio
 * in (0, 1] at byte 4. */
#define IRC__PARTS 8u
enum { IRC__SANE_ANY, IRC__SANE_FINITE, IRC__SANE_ELLIPSE };
typedef struct irc__recpart {
    uint8_t id, w1, w2, sane;
    uint32_t lead, bytes;
} irc__recpart;

/* A scratch slot's working area: the samples (at 0), then its parts.
 * The sampler's are numbered here: one batch of rays and of hits, and
 * each sample's direction and hit normal (for kinds that keep them).  A
 * kind numbers up to four parts of its own from IRC__S_KIND (the
 * irradiance kind's: estimator.h).  life.c places the rays first, then
 * the kind's parts in its numbering, then the directions and normals (a
 * part of 0 bytes takes no room), so a kind's first parts follow the rays
 * directly (the Hessian's rows run over the rays' bytes into its own);
 * the block keeps each one's byte offset, irc_cache.soff[IRC__S_*]. */
enum { IRC__S_RAYS, IRC__S_DIRS, IRC__S_NORMALS, IRC__S_KIND, IRC__S_COUNT = IRC__S_KIND + 4 };

/* Bytes of the sampler's batch of rays and hits. */
static inline uint64_t irc__rays_bytes(const irc_config *cfg)
{
    return (uint64_t)cfg->max_batch * (sizeof(irc_ray) + sizeof(irc_hit));
}

/* What a kind's scratch holds for a resolved config: bytes of each part
 * but the rays (the sampler's directions and normals, the kind's own),
 * samples per slot, and whether the sampler keeps each sample's direction
 * and hit normal. */
typedef struct irc__scratch {
    uint64_t bytes[IRC__S_COUNT];
    uint32_t samples;
    uint32_t keep_geom;
} irc__scratch;

/* How a lookup weighs and sums records: a kind's plain lookup, or one
 * that answers more from the same records (irc_cache_lookup_gradient).
 * find runs irc__lookup_once with the accumulator on its own frame: a
 * union of every accumulator would put the largest (1.2 KB for SH) on
 * every lookup's stack. */
typedef struct irc__acc {
    int (*weigh)(const irc_cache *c, const irc__rec *r, const irc__query *q, float *w,
                 float ni[3]);
    void (*begin)(const irc_cache *c, void *acc);
    void (*accumulate)(const irc_cache *c, const irc__rec *r, const irc__query *q, float w,
                       const float ni[3], void *acc);
    int (*finish)(const irc_cache *c, const irc__query *q, const void *acc, float w,
                  void *out);
    int (*find)(irc_cache *c, const irc__query *q, void *out, float *weight);
    /* weigh and accumulate in one (optional, for queries that hide no
     * record): the record's weight, or 0 when it does not count */
    float (*take)(const irc_cache *c, const irc__rec *r, const irc__query *q, void *acc);
} irc__acc;

/* A record kind: its config, its record, its scratch, and what the store
 * calls to make, check, store and answer one.  The public structs differ
 * (irc_record, irc_sh); the store sees them as void. */
typedef struct irc__kind {
    uint32_t id;            /* its number in a block (a pointer would not
                               survive irc_attach in another process) */
    uint32_t features;      /* the IRC_FEATURE_* bits that choose it; the
                               first kind listed takes a config with none */
    uint32_t unbuilt;       /* of those, the ones this build leaves out
                               (util.h IRC_NO_*): IRC_ERR_UNSUPPORTED */
    int free_points;        /* queries may omit the normal */
    int uniform;            /* rows of equal solid angle (else Ward's
                               cosine-weighted rows) */
    uint32_t record_bytes;  /* its public record (built in a scratch slot) */
    uint32_t cfg_at, cfg_bytes; /* its fields in irc_config (zero in the
                               config of another kind) */
    uint32_t snap_at[2];    /* config words a snapshot's header keeps
                               (offsets in irc_config of uint32 fields;
                               0: none), so that a snapshot names them */
    /* Its fields of the config, defaults applied and checked, and its
     * features' implications and defaults for the irc_switch fields left
     * at IRC_DEFAULT (config.c resolves the rest); IRC_OK, IRC_ERR_CONFIG,
     * or IRC_ERR_UNSUPPORTED for what this build leaves out. */
    int (*resolve)(irc_config *cfg);
    /* The parts a record of this resolved config carries, in order;
     * returns how many (<= IRC__PARTS). */
    uint32_t (*parts)(const irc_config *cfg, irc__recpart *out);
    void (*scratch)(const irc_config *cfg, irc__scratch *out);
    int (*compute)(irc__call *k, void *rec);
    int (*check)(const irc_cache *c, const void *rec, float un[3]);
    void (*pack)(const irc_cache *c, const void *rec, const float un[3], void *dst);
    void (*unpack)(const irc_cache *c, const void *src, void *rec);
    void (*answer)(const irc_cache *c, const void *rec, void *out);
    /* answer's value mixed into the neighbours' weighted mean that out
     * already holds, of total weight w > 0 (lookups that reach past a R:
     * cfg.irr.blend); NULL for a kind whose lookups never do */
    void (*mix_in)(const irc_cache *c, const void *rec, void *out, float w);
    /* Its fields and features of a resolved config as a host writes them
     * (irc_cache_config: a switch as IRC_ON or IRC_OFF, bare records by
     * name); NULL: as resolved */
    void (*publish)(irc_config *cfg);
    /* Its lookups' reach over R and the weight a record at a R gets, from
     * the resolved config (cfg.irr.blend); NULL: a, and Ward's weights
     * (w_inner 0) */
    void (*reach)(const irc_config *cfg, float *reach_a, float *w_inner);
    const irc__acc *lookup; /* its plain lookup's accumulator */
} irc__kind;

/* A kind's defaults for the irc_switch fields a config left at
 * IRC_DEFAULT (IRC_ON or IRC_OFF each). */
static inline void irc__switch_defaults(irc_config *cfg, uint32_t clamp, uint32_t sight)
{
    if (cfg->clamp_neighbours == IRC_DEFAULT)
        cfg->clamp_neighbours = clamp;
    if (cfg->check_visibility == IRC_DEFAULT)
        cfg->check_visibility = sight;
}

/* kinds.c: the kinds this build has, and the one a config or a block
 * names (NULL: none). */
const irc__kind *irc__kind_of(uint32_t features);
const irc__kind *irc__kind_by_id(uint32_t id);
/* All the kinds' feature bits; IRC_ERR_CONFIG for bits no kind knows or
 * of two kinds, IRC_ERR_UNSUPPORTED for a kind this build leaves out. */
int irc__kind_features(uint32_t features);
/* IRC_ERR_CONFIG unless every other kind's config fields are zero. */
int irc__kind_fields_alone(const irc__kind *k, const irc_config *cfg);

#endif
