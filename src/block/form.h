/*
 * form.h -- the cache's form: what a block is (its identity, its resolved
 * config, its records' and scratch slots' parts) and where each of its
 * parts lies, all fixed when the cache is made; the pointers marked
 * "attached" are set anew on attach.  The kinds, the sampler and the
 * estimators read this; the store's mutable state (the records' count,
 * the index's pools and root, the pass) is cache.h's, which only the
 * block, index, store and persistence layers include.  Nothing here is
 * part of the public API; tests may include it to reach the internals.
 */
#ifndef IRC_FORM_H
#define IRC_FORM_H

#include "../base/kind.h"
#include "../util.h"
#include "irrcache.h"

#define IRC__MAGIC 0x69726332u /* "irc2" */
#define IRC__ALIGN 64u

/* What a block must agree on to be re-attached (irc_attach): the layout's
 * version, pointer and size_t widths, byte order. */
#define IRC__LAYOUT_VERSION 23u
#define IRC__ABI                                                           \
    (IRC__LAYOUT_VERSION | (uint32_t)sizeof(void *) << 8 |                 \
     (uint32_t)sizeof(size_t) << 16 | (uint32_t)sizeof(double) << 24)



/* The cache, at the start of its part of the block.  Everything after it
 * (its state first, then the lock, the slots, the records, the index) is
 * reached by offsets from the cache itself, so a block copied to another
 * address works once irc_attach has re-set the four pointers marked
 * "attached". */
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
    uint32_t off[IRC__PARTS]; /* each part's byte offset by its kind's
                                number, 0 = absent */
    irc__recpart parts[IRC__PARTS]; /* the record's parts, in order */
    uint32_t n_parts;
    uint32_t strata;         /* M * N */
    float reach_a;           /* a lookup's reach over R: a, or a x
                                cfg.irr.blend */
    float w_inner;           /* the weight of a record at the edge of a R
                                when lookups reach past it (blend > 1):
                                a lookup-or-compute whose records all weigh
                                at most this computes one; 0 otherwise */
    uint32_t slot_samples;   /* samples a scratch slot holds (the kind's) */
    uint32_t keep_geom;      /* the sampler keeps directions and hit normals */
    uint32_t node_cap;       /* nodes in the pool (1 + 8 k) */
    uint32_t ref_cap;        /* references in the pool (index.c) */
    size_t lock_bytes;       /* room reserved for the port's lock */
    size_t slot_bytes;       /* scratch bytes per thread slot */
    size_t slot_rec;         /* where in a slot its record lies */
    size_t soff[IRC__S_COUNT];/* the slot's parts (IRC__S_*) */
    size_t total_bytes;      /* bytes of the block in use from the cache on */
    /* Offsets from the address of home. */
    size_t o_state,          /* the mutable state (cache.h) */
           o_lock, o_scratch, o_records, o_ix, o_nodes, o_refs, o_ctr,
           o_used,           /* o_used 0: no CLOCK */
           o_gtab;           /* the strata's table (sample/grid.c) */
};


static inline unsigned char *irc__part(const irc_cache *c, size_t off)
{
    return (unsigned char *)(uintptr_t)c->home + off;
}

static inline void *irc__lock(const irc_cache *c) { return irc__part(c, c->o_lock); }
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

/* A record's reach a R (Ward's accuracy times its radius; blend a R when
 * lookups blend wider, cfg.irr.blend), written once so that the index's
 * bounds, the weights' first test and the estimators agree on it to the
 * bit. */
static inline float irc__reach(const irc_cache *c, float radius)
{
    return c->reach_a * radius;
}

/* The first test of every weight (weight.c), inlined where records are scanned: most
 * candidates fail it, and it needs only the record's first 16 bytes. */
static inline int irc__within_reach(const irc_cache *c, const irc__rec *r, const float p[3])
{
    float dx = (float)p[0] - r->p[0], dy = (float)p[1] - r->p[1],
           dz = (float)p[2] - r->p[2], ra = irc__reach(c, r->r);
    float d2 = dx * dx + dy * dy + dz * dz;
    /* d2 == 0: a record serves its own point even when (a R)^2 underflows
     * (an open-sky record's R is FLT_MIN) */
    return d2 < ra * ra || d2 == 0.0f;
}

#endif /* IRC_FORM_H */
