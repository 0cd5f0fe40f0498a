/*
 * cache.h -- internal structures shared by the files of src/.  Nothing here
 * is part of the public API; tests may include it to reach the internals.
 */
#ifndef IRC_CACHE_H
#define IRC_CACHE_H

#include "irrcache.h"
#include "util.h"
#include "index.h"

#define IRC__MAGIC 0x69726332u /* "irc2" */
#define IRC__NIL 0xffffffffu
#define IRC__ALIGN 64u
/* The radius cap as a float: compared as the literal, an x87 build (i386)
 * keeps 1e30 unrounded and finds the stored cap above it. */
#define IRC__CAP ((float)IRC_RADIUS_CAP)

/* What a block must agree on to be re-attached (irc_attach): the layout's
 * version, pointer and size_t widths, byte order. */
#define IRC__LAYOUT_VERSION 13u
#define IRC__ABI                                                           \
    (IRC__LAYOUT_VERSION | (uint32_t)sizeof(void *) << 8 |                 \
     (uint32_t)sizeof(size_t) << 16 | (uint32_t)sizeof(double) << 24)

/* Stored record: the position and radius come first so that the index's
 * distance test touches one cache line.  32 bytes; the kind's payload
 * (gradients, SH coefficients) follows. */
typedef struct irc__rec {
    float p[3];
    float r;         /* R_i */
    float e[3];
    uint32_t n;      /* octahedral normal, 16 + 16 bits; IRC__FREE = none */
} irc__rec;

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

enum {
    IRC__C_INSERTS, IRC__C_EVICTIONS, IRC__C_LOOKUPS, IRC__C_HITS,
    IRC__C_COMPUTES, IRC__C_RAYS, IRC__C_NOT_STORED, IRC__C_WAITS, IRC__C_COUNT
}; /* IRC__C_COUNT * 8 bytes: one stripe, at most a cache line */

#define IRC__SH_MAX_BANDS 5
#define IRC__FREE 0xffffffffu /* irc__rec.n of a free-point SH record */
#define IRC__NC (IRC__SH_MAX_BANDS * IRC__SH_MAX_BANDS)
/* The largest packed record: 32 + 25 coefficients x 3 channels x (1 + 3). */
#define IRC__REC_MAX (32u + IRC__NC * 3u * 4u * 4u)

/* A validated query: the point, and the unit normal (zero for a free
 * point). */
/* The CLOCK bits a lookup-or-compute set, so that a call that then fails
 * clears them and leaves the block as it was (store.c).  Past IRC__MARKS
 * new bits it sets no more: a use bit is a hint. */
#define IRC__MARKS 8u
typedef struct irc__marks {
    uint32_t id[IRC__MARKS];
    uint32_t n;
} irc__marks;

typedef struct irc__query {
    float p[3];
    float n[3];
    int free;
    const uint32_t *hidden; /* records the lookup leaves out (cfg.
                               check_visibility): n_hidden ids, ascending */
    uint32_t n_hidden;
    irc__marks *marks;      /* NULL: a lookup that cannot fail after it reads */
} irc__query;

/* A lookup's running sums live in the frame of the kind's find (4 floats
 * for irradiance, 1.2 KB for SH), passed on as void *: a union of every
 * kind's would put the largest on every kind's stack, and a frame that
 * outlived the lookup would sit under the record computation that may
 * follow it. */

/* One record computation in progress: the cache, its claimed scratch
 * slot, the host's per-call pointer, the query, and rays cast so far. */
typedef struct irc__call {
    irc_cache *c;
    unsigned char *slot;
    void *host;
    irc__query q;
    uint32_t rays;
    float footprint;  /* a pixel's width at the query, 0 = none */
    uint32_t sight;   /* 1 while casting confirming rays (sight.c) */
} irc__call;

/* A record's parts after its 32-byte head, each owned by its kind, which
 * lists those a config asks for in order (irc__kind.parts); layout.c
 * places them one after another and the block's header keeps their byte
 * offsets (irc_cache.off[id], 0 = absent).  A part's fields are `lead`
 * bytes of width w1, then the rest of width w2: the snapshot's byte order
 * and the merge order walk them field by field.  `sane` says what a part
 * a cache could have made holds (verify.c): anything, finite floats, or an
 * ellipse's minor/major ratio in (0, 1] at byte 4. */
enum { IRC__P_GRAD_T, IRC__P_GRAD_R, IRC__P_ELLIPSE, IRC__P_GUARD, IRC__P_SH, IRC__P_SH_GRAD,
       IRC__P_COUNT };
enum { IRC__SANE_ANY, IRC__SANE_FINITE, IRC__SANE_ELLIPSE };
typedef struct irc__recpart {
    uint8_t id, w1, w2, sane;
    uint32_t lead, bytes;
} irc__recpart;

/* A scratch slot's working area, part by part in this order: the samples
 * (at 0), one batch of rays and of hits; with translational or rotational
 * gradients the inverse hit distances and five rows of boundary weights
 * (gradient.c); with VISIBILITY, HESSIAN or SH each sample's direction and
 * hit normal; with VISIBILITY the strata's edges and their crossings; with
 * HESSIAN a depth per sample.  layout.c places them (a part a config does
 * not use takes no room) and the block keeps each one's byte offset,
 * irc_cache.soff[IRC__S_*] (estimator.h reads them). */
enum { IRC__S_RAYS, IRC__S_INV, IRC__S_DIRS, IRC__S_NORMALS, IRC__S_EDGES, IRC__S_CROSS,
       IRC__S_DEPTHS, IRC__S_COUNT };

/* A record kind: what the store needs to check, pack, weigh and
 * accumulate one kind of record (kind_irr.c, kind_sh.c).  The public
 * structs differ (irc_record, irc_sh); the store sees them as void. */
typedef struct irc__kind {
    int free_points;        /* queries may omit the normal */
    int (*compute)(irc__call *k, void *rec);
    int (*check)(const irc_cache *c, const void *rec, float un[3]);
    void (*pack)(const irc_cache *c, const void *rec, const float un[3], void *dst);
    void (*unpack)(const irc_cache *c, const void *src, void *rec);
    int (*weigh)(const irc_cache *c, const irc__rec *r, const irc__query *q, float *w,
                 float ni[3]);
    void (*begin)(const irc_cache *c, void *acc);
    void (*accumulate)(const irc_cache *c, const irc__rec *r, const irc__query *q, float w,
                       const float ni[3], void *acc);
    int (*finish)(const irc_cache *c, const irc__query *q, const void *acc, float w,
                  void *out);
    void (*answer)(const irc_cache *c, const void *rec, void *out);
    /* irc__lookup_once with an accumulator of the kind's own. */
    int (*find)(irc_cache *c, const irc__query *q, void *out, float *weight);
    /* The parts a record of this resolved config carries, in order;
     * returns how many (<= IRC__P_COUNT). */
    uint32_t (*parts)(const irc_config *cfg, irc__recpart *out);
    /* The kind's own config fields, defaults applied and checked, and its
     * defaults for the irc_switch fields left at IRC_DEFAULT (config.c
     * resolves the rest); IRC_OK or IRC_ERR_CONFIG. */
    int (*resolve)(irc_config *cfg);
} irc__kind;

/* The block stores which kind it holds by number (a pointer to the table
 * would not survive irc_attach in another process). */
enum { IRC__KIND_IRR = 1, IRC__KIND_SH = 2 };
extern const irc__kind irc__kind_irr, irc__kind_sh;
/* The kind a resolved config's records are, as a table and by number. */
const irc__kind *irc__kind_of(uint32_t features);
uint32_t irc__kind_id_of(uint32_t features);
int irc__features_built(uint32_t features);

/* The cache, at the start of its part of the block.  Everything after it
 * is reached by offsets from the cache itself, so a block copied to
 * another address works once irc_attach has re-set the four pointers
 * marked "attached". */
struct irc_cache {
    uint32_t magic;
    uint32_t abi;            /* IRC__ABI of the build that made the block */
    uint32_t capacity;
    uint32_t kind_id;
    irc_config cfg;          /* defaults applied; its trace, context, port and
                                buffer are attached */
    const irc__kind *kind;   /* attached */
    const irc_port *port;    /* attached: cfg.port */
    irc_cache *home;         /* attached: the cache in the block, through
                                which every part and all mutable state are
                                reached: itself, or for a view (irc_join)
                                the shared block's cache as this process
                                maps it */
    char port_name[16];      /* the port that made the lock (views must
                                use the same) */
    uint32_t rec_size;       /* packed record bytes */
    uint32_t off[IRC__P_COUNT]; /* each part's byte offset, 0 = absent */
    irc__recpart parts[IRC__P_COUNT]; /* the record's parts, in order */
    uint32_t n_parts;
    uint32_t strata;         /* M * N */
    uint32_t slot_samples;   /* samples a scratch slot holds: M N, or 2 M N
                                in an SH cache (free points: two hemispheres) */
    uint32_t keep_geom;      /* the sampler keeps directions and hit normals */
    uint32_t sh_n, sh_ch;    /* SH cache: L*L coefficients, channels; else 0 */
    uint32_t node_cap;       /* nodes in the pool (1 + 8 k) */
    size_t lock_bytes;       /* room reserved for the port's lock */
    size_t slot_bytes;       /* scratch bytes per thread slot */
    size_t slot_rec;         /* where in a slot its record lies */
    size_t soff[IRC__S_COUNT];/* the slot's parts (IRC__S_*) */
    size_t total_bytes;      /* bytes of the block in use from the cache on */
    /* Offsets from the address of home. */
    size_t o_lock, o_scratch, o_records, o_ix, o_nodes, o_ctr,
           o_used,           /* o_used 0: no CLOCK */
           o_gtab;           /* the strata's table (gradient.c) */
    /* Mutable under the write lock; read and written through home. */
    uint32_t count;          /* records in slots [0, count) */
    uint32_t nodes_used;
    uint32_t hand;           /* CLOCK hand */
    uint32_t root_set;
    uint32_t depth;          /* the index's deepest node level */
    uint32_t pass_open;      /* a fill pass is open (irc_pass_begin) */
    uint32_t pass_base;      /* count when it opened: its records go to
                                slots [pass_base, capacity) */
    double root_c[3];        /* the root cube: centre exact in double */
    double root_h;           /* half its edge, a power of two */
    /* Atomic. */
    uint64_t pending;        /* slots the open pass has reserved (never past
                                its room) */
    uint64_t packed;         /* of those, records whole in their slots */
    uint64_t torn;           /* slots being written (repair.c): two ids + 1,
                                low and high word, 0 = none */
    uint64_t writing;        /* 1 while a writer holds the lock */
};

/* The counters, in IRC__STRIPES stripes of one cache line each (a part of
 * the block at o_ctr): a thread adds to the stripe its stack's address
 * picks, so threads on other cores rarely write the same line, and
 * irc_cache_stats sums the stripes.  Any thread may use any stripe; the
 * adds stay atomic. */
#define IRC__STRIPES 8u

static inline unsigned char *irc__part(const irc_cache *c, size_t off)
{
    return (unsigned char *)(uintptr_t)c->home + off;
}

static inline void *irc__lock(const irc_cache *c) { return irc__part(c, c->o_lock); }
static inline irc__ixe *irc__ix(const irc_cache *c)
{
    return (irc__ixe *)(void *)irc__part(c, c->o_ix);
}
static inline irc__node *irc__nodes(const irc_cache *c)
{
    return (irc__node *)(void *)irc__part(c, c->o_nodes);
}
static inline uint64_t *irc__stripe(const irc_cache *c, uint32_t s)
{
    return (uint64_t *)(void *)irc__part(c, c->o_ctr + (size_t)s * IRC__ALIGN);
}
static inline uint64_t *irc__used(const irc_cache *c)
{
    return c->o_used ? (uint64_t *)(void *)irc__part(c, c->o_used) : NULL;
}
static inline const void *irc__gtab(const irc_cache *c)
{
    return irc__part(c, c->o_gtab);
}
/* A scratch slot: a head of IRC__ALIGN bytes whose first word is its
 * owner (0: free; else the claiming process's port token, slots.c), then
 * slot_bytes - IRC__ALIGN bytes of working area, which irc__slot gives. */
static inline uint64_t *irc__slot_owner(const irc_cache *c, uint32_t t)
{
    return (uint64_t *)(void *)irc__part(c, c->o_scratch + (size_t)t * c->slot_bytes);
}
static inline unsigned char *irc__slot(const irc_cache *c, uint32_t t)
{
    return irc__part(c, c->o_scratch + (size_t)t * c->slot_bytes + IRC__ALIGN);
}
/* The record a lookup-or-compute builds in slot t (an irc_record or an
 * irc_sh, by the cache's kind). */
static inline void *irc__slot_record(const irc_cache *c, uint32_t t)
{
    return irc__slot(c, t) + c->slot_rec;
}
static inline irc__rec *irc__rec_at(const irc_cache *c, uint32_t id)
{
    return (irc__rec *)(void *)irc__part(c, c->o_records + (size_t)id * c->rec_size);
}

/* check.c */
int irc__check_vec(const float v[3]);
int irc__check_normal(const float n[3], float unit[3]);

/* layout.c: the block's parts, and the config rules (config.c) */
int irc__config_resolve(const irc_config *in, irc_config *out);
int irc__port_ok(const irc_port *p);

/* store.c: the ids of up to cap records a lookup at q would use; *found
 * gets how many there are in all. */
int irc__collect(irc_cache *c, const irc__query *q, uint32_t *ids, uint32_t cap,
                 uint32_t *found);
/* store.c: the positions of records ids[0 .. n - 1], read as a lookup
 * reads (under the read lock, or in a pass without). */
int irc__positions(irc_cache *c, const uint32_t *ids, uint32_t n, float (*pos)[3]);
/* slots.c: claim a scratch slot (waiting unless cfg.no_wait; IRC_OK or
 * IRC_ERR_BUSY; *waited set when it waited), and give it back zeroed. */
int irc__slot_claim(irc_cache *c, uint32_t *t, int *waited);
void irc__slot_release(irc_cache *c, uint32_t t);
/* verify.c: whether the records and index of c's block are ones a cache
 * could have made, every link in bounds and every walk finite. */
int irc__block_sane(const irc_cache *c);
/* verify.c: a record's head as a cache could have made it (finite p and
 * E, E >= 0, R > 0, a free point only in an SH cache); the snapshot
 * reader checks decoded heads with it too. */
int irc__rec_head_sane(const irc_cache *c, const irc__rec *r);
/* verify.c: record id whole as a cache could have made it (its head, its
 * ellipse, its SH words finite). */
int irc__rec_sane(const irc_cache *c, uint32_t id);
/* verify.c: the parts after a record's head as the part table says a
 * cache makes them; rec in the block's byte order, or (le) a snapshot's. */
int irc__parts_sane(const irc_cache *c, const unsigned char *rec, int le);
/* repair.c: the lock through the library, so that a writer's death is
 * repaired; slots being written named in the block (irc__mark, b IRC__NIL
 * for one slot); records swapped in place. */
int irc__write_lock(irc_cache *c);
void irc__write_unlock(irc_cache *c);
int irc__read_lock(irc_cache *c);
void irc__read_unlock(irc_cache *c);
void irc__mark(irc_cache *c, uint32_t a, uint32_t b);
void irc__unmark(irc_cache *c);
void irc__rec_swap(irc_cache *c, uint32_t i, uint32_t j);
void irc__repair_locked(irc_cache *c);
/* sight.c: the kind's find at k->q, leaving out the records out of the
 * query's sight when cfg.check_visibility asks (k->c, k->host set). */
int irc__find_in_sight(irc__call *k, void *out, float *weight);

/* store.c: the handle, insert and eviction, the lookup driver; every
 * public call goes through it. */
int irc__enter(const irc_cache *c, const irc__kind *want);
int irc__compute(irc_cache *c, const irc__kind *want, const float p[3], const float n[3],
                 void *out, void *host, int (*fn)(irc__call *k, void *out), int record);
int irc__insert(irc_cache *c, const irc__kind *want, const void *rec);
/* The caller holds the write lock: forget drops the index, the list links
 * and CLOCK's bits, keeping the records; clear drops the records too. */
void irc__forget_locked(irc_cache *c);
void irc__clear_locked(irc_cache *c);
/* Takes the write lock for a call a fill pass forbids: IRC_OK with the
 * lock held, or IRC_ERR_PORT / IRC_ERR_STATE (a pass is open) without. */
int irc__write_lock_idle(irc_cache *c);
/* The caller holds the write lock: the record in slot id (below count)
 * joins the index, clamped by its neighbours if the config asks. */
void irc__commit_locked(irc_cache *c, uint32_t id);

/* A lookup weighs and accumulates with ops: the cache's kind (want), or a
 * table that shares its records and answers more (a gradient lookup). */
int irc__lookup_once(irc_cache *c, const irc__kind *ops, const irc__query *q, void *out,
                     float *weight, void *acc);
int irc__lookup(irc_cache *c, const irc__kind *want, const irc__kind *ops, const float p[3],
                const float n[3], void *out, float *weight);
/* The record it computes on a miss is built in the claimed slot. */
int irc__lookup_or_compute(irc_cache *c, const irc__kind *want, float footprint, const float p[3],
                           const float n[3], void *out, float *weight, void *host);
int irc__record_get(irc_cache *c, const irc__kind *want, uint32_t id, void *out);
/* stats.c: adds v to counter which (IRC__C_*) in the caller's stripe. */
void irc__count(irc_cache *c, int which, uint64_t v);

#endif
