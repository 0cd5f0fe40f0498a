/*
 * life.c -- a cache's life in the caller's block: its parts and their
 * sizes, init, attach, join and fini.
 *
 * Byte 0 of the block holds the distance (1..64) from the block's start to
 * the cache, which sits on the first 64-byte boundary after byte 0; from
 * there on:
 *   struct irc_cache | its state | lock | scratch slots | records | index entries | nodes |
 *   references | counter stripes | CLOCK bits (only with eviction) | the strata's table
 *   (the columns' angles for the sampler and the gradients' weights)
 * each part on a 64-byte boundary, reached by its offset from the cache.
 * So the footprint carries 64 bytes of slack, and irc_attach can find the
 * cache in a block copied to any address.
 */
#include "../block/cache.h"
#include "../block/check.h"
#include "../index/index.h"
#include "../index/layout.h"
#include "../index/verify.h"
#include "../irr/estimator.h"
#include "../sample/sampler.h"
#include "../store/lock.h"
#include "../store/stats.h"
#include "config.h"

typedef struct irc__layout {
    uint64_t state, lock, scratch, records, ix, nodes, refs, ctr, used, gtab, total;
    uint64_t slot_bytes, slot_rec, lock_bytes;
    uint64_t soff[IRC__S_COUNT];
    uint32_t rec_size, off[IRC__PARTS], n_parts, node_cap, ref_cap, samples, keep_geom;
    irc__recpart parts[IRC__PARTS];
} irc__layout;

static uint64_t irc__up(uint64_t x)
{
    return (x + (IRC__ALIGN - 1)) & ~(uint64_t)(IRC__ALIGN - 1);
}

/* Index pool: the root plus one block of 8 children per 8 records.  A
 * leaf splits when more than 16 references sit in it and most of them
 * belong deeper; records lie on surfaces, which fill about half of a
 * split's 8 children: records on a unit box (bench/anchor.c) used 0.59
 * nodes a record filled freely and all of the pool built in a pass (1.58
 * with four times the pool, for 1.6% fewer instructions a lookup).  When
 * the pool runs out, leaves simply grow longer (lookups stay exact, only
 * slower).  irc_stats reports the nodes used. */
#ifndef IRC__NODE_DIV
#define IRC__NODE_DIV 4u
#endif
static uint32_t irc__node_cap(uint32_t capacity)
{
    return 1u + 8u * (capacity / IRC__NODE_DIV + 8u);
}

/* Reference pool: eight a record, as many as a record can take (a box no
 * wider than the cells of its level overlaps at most two a side), so the
 * pool never runs short of a full cache's (index.c keeps one in reserve
 * for every record not yet indexed, and places records a level up, in
 * fewer and larger nodes, when it would: lookups stay exact, only slower;
 * a block made by a build with IRC__REFS below 8 may).  The box workload
 * of bench/anchor.c takes 5.1-5.9 a record.  irc_stats reports the
 * references used. */
#ifndef IRC__REFS
#define IRC__REFS 8u
#endif
static uint32_t irc__ref_cap(uint32_t capacity)
{
    const uint64_t n = (uint64_t)capacity * IRC__REFS + 64u;
    return n < 0xffffff00u ? (uint32_t)n : 0xffffff00u; /* below IRC__NIL */
}

/* Record bytes: the 32-byte head, then the parts the kind lists, one
 * after another. */
static void irc__record_layout(const irc_config *cfg, const irc__kind *k, irc__layout *l)
{
    uint32_t i;
    IRC_MEMSET(l->off, 0, sizeof l->off);
    IRC_MEMSET(l->parts, 0, sizeof l->parts);
    l->rec_size = (uint32_t)sizeof(irc__rec);
    l->n_parts = k->parts(cfg, l->parts);
    for (i = 0; i < l->n_parts; i++) {
        l->off[l->parts[i].id] = l->rec_size;
        l->rec_size += l->parts[i].bytes;
    }
}

/* A scratch slot's working area, its parts one after another in kind.h's
 * order (IRC__S_*): the samples, the sampler's batch of rays and hits,
 * the kind's parts, the sampler's directions and normals; returns its
 * bytes. */
static uint64_t irc__slot_layout(const irc_config *cfg, const irc__kind *k, irc__layout *l)
{
    irc__scratch s;
    uint64_t at;
    int i;
    IRC_MEMSET(&s, 0, sizeof s);
    k->scratch(cfg, &s);
    s.bytes[IRC__S_RAYS] = irc__rays_bytes(cfg);
    l->samples = s.samples;
    l->keep_geom = s.keep_geom;
    at = (uint64_t)s.samples * sizeof(irc__sample);
    for (i = 0; i < IRC__S_COUNT; i++) {
        /* the rays, the kind's parts, the directions, the normals */
        const int p = i == 0 ? IRC__S_RAYS : i < IRC__S_COUNT - 2 ? i + 2 : i - IRC__S_COUNT + 3;
        l->soff[p] = at;
        at += s.bytes[p];
    }
    return irc__up(at);
}

/* In 64-bit arithmetic, so that a 32-bit size_t is checked, not wrapped. */
static void irc__layout_of(const irc_config *cfg, uint32_t capacity, irc__layout *l)
{
    const irc__kind *k = irc__kind_of(cfg->features);
    uint64_t at = irc__up(sizeof(irc_cache));
    irc__record_layout(cfg, k, l);
    /* the state on lines of its own: inserts write it, lookups read the
     * cache's form beside it */
    l->state = at;
    at += irc__up(sizeof(irc__state));
    /* The slot ends with the record a lookup-or-compute builds, of the
     * cache's kind: on the stack it would sit over the whole lookup. */
    l->slot_bytes = irc__slot_layout(cfg, k, l);
    l->slot_rec = l->slot_bytes;
    l->slot_bytes += irc__up(k->record_bytes);
    l->slot_bytes += IRC__ALIGN; /* the owner's head (form.h irc__slot_owner) */
    l->node_cap = irc__node_cap(capacity);
    l->ref_cap = irc__ref_cap(capacity);
    l->lock_bytes = irc__up(cfg->port->lock_size ? cfg->port->lock_size : 1);
    l->lock = at;
    at += l->lock_bytes;
    l->scratch = at;
    at += (uint64_t)cfg->threads * l->slot_bytes;
    l->records = at;
    at += irc__up((uint64_t)capacity * l->rec_size);
    l->ix = at;
    at += irc__up((uint64_t)capacity * sizeof(irc__ixe));
    l->nodes = at;
    at += irc__up((uint64_t)l->node_cap * sizeof(irc__node));
    l->refs = at;
    at += irc__up((uint64_t)l->ref_cap * sizeof(irc__ref));
    l->ctr = at;
    at += (uint64_t)IRC__STRIPES * IRC__STRIPE_BYTES;
    l->used = at;
    if (cfg->evict == IRC_EVICT_CLOCK)
        at += irc__up(((uint64_t)capacity + 63u) / 64u * sizeof(uint64_t));
    l->gtab = at;
    at += irc__up(irc__gtab_bytes(cfg->strata_theta, cfg->strata_phi));
    l->total = at;
}

int irc_footprint(const irc_config *cfg, uint32_t max_records, size_t *bytes)
{
    irc_config r;
    irc__layout l;
    int st;
    if (!bytes)
        return IRC_ERR_NULL;
    if ((st = irc__config_resolve(cfg, &r)) < 0)
        return st;
    if (max_records == 0 || max_records > IRC_MAX_RECORDS)
        return IRC_ERR_CONFIG;
    irc__layout_of(&r, max_records, &l);
    if (l.total > (uint64_t)(SIZE_MAX - IRC__ALIGN))
        return IRC_ERR_CONFIG;
    *bytes = (size_t)(l.total + IRC__ALIGN);
    return IRC_OK;
}

/* The first 64-byte boundary after the block's byte 0. */
static size_t irc__pad(const void *buffer)
{
    return IRC__ALIGN - ((uintptr_t)buffer & (IRC__ALIGN - 1));
}

/* The pointers a block cannot carry from one address or process to
 * another: taken from the caller at init and at attach. */
static void irc__attach_pointers(irc_cache *c, const irc_config *cfg, const irc_port *port)
{
    c->cfg.trace = cfg->trace;
    c->cfg.context = cfg->context;
    c->cfg.port = c->port = port;
    c->cfg.buffer = cfg->buffer;
    c->cfg.buffer_size = cfg->buffer_size;
    c->kind = irc__kind_by_id(c->kind_id); /* irc__find checked it */
    c->home = c;
}

/* The port's name as the block keeps it, to tell whether a view's port
 * makes the same kind of lock. */
static void irc__port_name(const irc_port *port, char out[16])
{
    size_t i;
    IRC_MEMSET(out, 0, 16);
    for (i = 0; i < 15 && port->name && port->name[i]; i++)
        out[i] = port->name[i];
}

static void irc__set_parts(irc_cache *c, const irc__layout *l)
{
    const irc__kind *kind = irc__kind_of(c->cfg.features);
    int i;
    c->rec_size = l->rec_size;
    IRC_MEMCPY(c->off, l->off, sizeof c->off);
    IRC_MEMCPY(c->parts, l->parts, sizeof c->parts);
    c->n_parts = l->n_parts;
    c->slot_samples = l->samples;
    c->keep_geom = l->keep_geom;
    c->node_cap = l->node_cap;
    c->ref_cap = l->ref_cap;
    c->lock_bytes = (size_t)l->lock_bytes;
    c->slot_bytes = (size_t)l->slot_bytes;
    c->slot_rec = (size_t)l->slot_rec;
    for (i = 0; i < IRC__S_COUNT; i++)
        c->soff[i] = (size_t)l->soff[i];
    c->total_bytes = (size_t)l->total;
    c->o_state = (size_t)l->state;
    c->o_lock = (size_t)l->lock;
    c->o_scratch = (size_t)l->scratch;
    c->o_records = (size_t)l->records;
    c->o_ix = (size_t)l->ix;
    c->o_nodes = (size_t)l->nodes;
    c->o_refs = (size_t)l->refs;
    c->o_ctr = (size_t)l->ctr;
    c->o_used = c->cfg.evict == IRC_EVICT_CLOCK ? (size_t)l->used : 0;
    c->o_gtab = (size_t)l->gtab;
    /* lookups reach further than a R when the kind blends wider (the
     * kind from the config: init and attach's check call this before the
     * handle has one) */
    c->reach_a = c->cfg.accuracy;
    c->w_inner = 0.0f;
    if (kind->reach)
        kind->reach(&c->cfg, &c->reach_a, &c->w_inner);
}

int irc_init(const irc_config *cfg, uint32_t max_records, irc_cache **out)
{
    irc_config r;
    irc__layout l;
    unsigned char *base;
    irc_cache *c;
    size_t need, pad;
    int st;
    if (!out)
        return IRC_ERR_NULL;
    if ((st = irc_footprint(cfg, max_records, &need)) < 0)
        return st;
    if (!cfg->buffer)
        return IRC_ERR_NULL;
    if (cfg->buffer_size < need)
        return IRC_ERR_NOMEM;
    irc__config_resolve(cfg, &r);
    irc__layout_of(&r, max_records, &l);
    pad = irc__pad(cfg->buffer);
    base = (unsigned char *)cfg->buffer + pad;
    IRC_MEMSET(base, 0, (size_t)l.total);
    c = (irc_cache *)(void *)base;
    c->abi = IRC__ABI;
    c->capacity = max_records;
    c->cfg = r;
    c->kind_id = irc__kind_of(r.features)->id;
    irc__attach_pointers(c, cfg, r.port);
    irc__set_parts(c, &l);
    c->strata = r.strata_theta * r.strata_phi;
    irc__port_name(c->port, c->port_name);
    irc__index_reset(c);
    irc__gtab_fill(c->cfg.strata_theta, c->cfg.strata_phi, irc__part(c, c->o_gtab));
    if (c->port->lock_init(irc__lock(c)) < 0)
        return IRC_ERR_PORT;
    c->magic = IRC__MAGIC;
    *(unsigned char *)cfg->buffer = (unsigned char)pad;
    *out = c;
    return IRC_OK;
}

/* Reads the cache's header where byte 0 says it is (it may sit at any
 * alignment now) and checks it belongs to this build. */
static int irc__find(const irc_config *cfg, size_t *at, irc_cache *head)
{
    const unsigned char *b = (const unsigned char *)cfg->buffer;
    size_t pad = b[0];
    if (pad < 1 || pad > IRC__ALIGN || cfg->buffer_size < pad + sizeof *head)
        return cfg->buffer_size < IRC__ALIGN + sizeof *head ? IRC_ERR_NOMEM : IRC_ERR_CONFIG;
    IRC_MEMCPY(head, b + pad, sizeof *head);
    if (head->magic != IRC__MAGIC || head->abi != IRC__ABI || !irc__kind_by_id(head->kind_id))
        return IRC_ERR_CONFIG;
    /* Other bad features are the header check's (corrupt). */
    if (irc__kind_features(head->cfg.features) == IRC_ERR_UNSUPPORTED)
        return IRC_ERR_UNSUPPORTED;
    if (head->total_bytes + IRC__ALIGN > cfg->buffer_size)
        return IRC_ERR_NOMEM;
    *at = pad;
    return IRC_OK;
}

static int irc__finite_d(double x)
{
    return x == x && x - x == 0.0;
}

static int irc__switch_back(uint32_t v, uint32_t *out)
{
    *out = v == 1u ? IRC_ON : IRC_OFF;
    return v <= 1u;
}

static int irc__same_bytes(const unsigned char *a, const unsigned char *b, uint32_t n)
{
    uint32_t i;
    for (i = 0; i < n && a[i] == b[i]; i++)
        ;
    return i == n;
}

static int irc__tables_same(const irc_cache *a, const irc_cache *b)
{
    uint32_t i;
    for (i = 0; i < IRC__S_COUNT; i++)
        if (a->soff[i] != b->soff[i])
            return 0;
    for (i = 0; i < IRC__PARTS; i++) {
        const irc__recpart *p = &a->parts[i], *q = &b->parts[i];
        if (a->off[i] != b->off[i] || p->id != q->id || p->w1 != q->w1 || p->w2 != q->w2 ||
            p->sane != q->sane || p->lead != q->lead || p->bytes != q->bytes)
            return 0;
    }
    return a->rec_size == b->rec_size && a->n_parts == b->n_parts;
}

static int irc__parts_same(const irc_cache *a, const irc_cache *b)
{
    return irc__tables_same(a, b) && a->slot_samples == b->slot_samples &&
           a->keep_geom == b->keep_geom &&
           a->node_cap == b->node_cap && a->ref_cap == b->ref_cap && a->lock_bytes == b->lock_bytes &&
           a->slot_bytes == b->slot_bytes && a->slot_rec == b->slot_rec &&
           a->total_bytes == b->total_bytes && a->o_state == b->o_state && a->o_lock == b->o_lock &&
           a->o_scratch == b->o_scratch && a->o_records == b->o_records && a->o_ix == b->o_ix &&
           a->o_nodes == b->o_nodes && a->o_refs == b->o_refs && a->o_ctr == b->o_ctr && a->o_used == b->o_used &&
           a->o_gtab == b->o_gtab && a->reach_a == b->reach_a && a->w_inner == b->w_inner;
}

/* The state's fields in range, for the cache c. */
static int irc__state_sane(const irc_cache *c, const irc__state *h)
{
    return h->count <= c->capacity && h->nodes_used >= 1u && h->nodes_used <= c->node_cap &&
           h->refs_used <= c->ref_cap && h->refs_live <= h->refs_used &&
           (h->ref_free == IRC__NIL || h->ref_free < h->refs_used) && h->indexed <= h->count &&
           (uint64_t)h->refs_live + (c->capacity - h->indexed) <= c->ref_cap &&
           h->hand < c->capacity && h->depth <= IRC__LEVELS && h->root_set <= 1u &&
           h->pass_open <= 1u && h->pass_base <= c->capacity && h->compacted <= c->capacity &&
           h->progress <= IRC__PROGRESS_TOP + 1u && h->pending <= c->capacity - h->pass_base &&
           h->packed <= h->pending &&
           (uint32_t)h->torn <= c->capacity && (uint32_t)(h->torn >> 32) <= c->capacity &&
           h->writing <= 1u &&
           irc__finite_d(h->root_c[0]) && irc__finite_d(h->root_c[1]) &&
           irc__finite_d(h->root_c[2]) && h->root_h >= 0.0 && h->root_h <= 1e39 &&
           (!h->root_set || irc__root_ok(h->root_c, h->root_h));
}

/* Whether a block's header is one irc_init could have written: its
 * stored config resolves to itself, and every size and offset equals what
 * that config and capacity give; its state (at offset at of the buffer,
 * then o_state) is in range.  The switches are stored resolved (0 or 1) and read back as IRC_OFF / IRC_ON.
 * IRC_OK, IRC_ERR_CORRUPT, or IRC_ERR_UNSUPPORTED for a block asking for
 * what this build leaves out. */
static int irc__header_sane(const irc_config *cfg, const irc_cache *h, size_t at)
{
    irc__state state;
    irc_port lockless;
    irc_config in = h->cfg, r;
    irc_cache e;
    irc__layout l;
    const irc__kind *k = irc__kind_of(h->cfg.features);
    int st;
    if (h->capacity == 0 || h->capacity > IRC_MAX_RECORDS || h->lock_bytes > 4096u ||
        h->lock_bytes % IRC__ALIGN || h->kind_id != k->id ||
        !irc__switch_back(h->cfg.clamp_neighbours, &in.clamp_neighbours) ||
        !irc__switch_back(h->cfg.check_visibility, &in.check_visibility))
        return IRC_ERR_CORRUPT;
    if (in.features == 0) /* bare records, stored resolved */
        in.features = IRC_FEATURE_NONE;
    /* the layout with a port whose lock is the room the block has */
    lockless = irc_port_none;
    lockless.lock_size = h->lock_bytes;
    in.trace = cfg->trace;
    in.port = &lockless;
    /* A kind's fields resolve to themselves (a switch of its own to 0 or
     * 1, which is off by default or on).  What this build leaves out is
     * named as such. */
    if ((st = irc__config_resolve(&in, &r)) == IRC_ERR_UNSUPPORTED)
        return st;
    if (st < 0 || r.features != h->cfg.features ||
        r.strata_theta != h->cfg.strata_theta || r.strata_phi != h->cfg.strata_phi ||
        r.threads != h->cfg.threads || r.max_batch != h->cfg.max_batch ||
        !irc__same_bytes((const unsigned char *)&r + k->cfg_at,
                         (const unsigned char *)&h->cfg + k->cfg_at, k->cfg_bytes) ||
        r.evict != h->cfg.evict || r.accuracy != h->cfg.accuracy)
        return IRC_ERR_CORRUPT;
    irc__layout_of(&r, h->capacity, &l);
    IRC_MEMSET(&e, 0, sizeof e);
    e.cfg = r;
    irc__set_parts(&e, &l);
    if (!irc__parts_same(&e, h) || h->strata != r.strata_theta * r.strata_phi)
        return IRC_ERR_CORRUPT;
    /* o_state is the layout's, and the block holds total_bytes from at
     * (irc__find); a copy, as the state may lie unaligned until moved */
    IRC_MEMCPY(&state, (const unsigned char *)cfg->buffer + at + h->o_state, sizeof state);
    return irc__state_sane(h, &state) ? IRC_OK : IRC_ERR_CORRUPT;
}


/* Moves the cache from offset was to pad (its 64-byte boundary here) and
 * checks its records and index there, where they are aligned; a block
 * that fails is moved back, with the < 64 bytes beside it that the move
 * overwrote, so a refusal leaves every byte as it was. */
static int irc__move_checked(const irc_config *cfg, irc_cache *head, size_t was, size_t pad)
{
    unsigned char *b = (unsigned char *)cfg->buffer, keep[IRC__ALIGN];
    const size_t total = head->total_bytes;
    size_t lo = 0, span = 0;
    if (pad != was) {
        lo = pad < was ? pad : was + total;
        span = pad < was ? was - pad : pad - was;
        IRC_MEMCPY(keep, b + lo, span);
        IRC_MEMMOVE(b + pad, b + was, total);
    }
    head->home = (irc_cache *)(void *)(b + pad);
    /* A writer killed inside the lock left it mid-write: repaired, not
     * refused (lock.c, irc__repair_locked). */
    if (irc__st(head)->writing || irc__st(head)->torn) {
        irc__repair_locked(head);
        irc__st(head)->writing = 0;
    }
    if (irc__block_sane(head))
        return IRC_OK;
    if (pad != was) {
        IRC_MEMMOVE(b + was, b + pad, total);
        IRC_MEMCPY(b + lo, keep, span);
    }
    return IRC_ERR_CORRUPT;
}

int irc_attach(const irc_config *cfg, irc_cache **out)
{
    irc_cache head, *c;
    const irc_port *port;
    size_t was, pad;
    int st;
    if (!cfg || !out)
        return IRC_ERR_NULL;
    if (cfg->version != IRC_CONFIG_VERSION)
        return IRC_ERR_VERSION;
    if (!cfg->buffer || !cfg->trace)
        return IRC_ERR_NULL;
    port = cfg->port ? cfg->port : irc_port_default;
    if ((st = irc__find(cfg, &was, &head)) < 0)
        return st;
    if (!irc__port_ok(port) || port->lock_size > head.lock_bytes)
        return IRC_ERR_CONFIG;
    if ((st = irc__header_sane(cfg, &head, was)) < 0)
        return st;
    head.port = port;
    pad = irc__pad(cfg->buffer);
    if ((st = irc__move_checked(cfg, &head, was, pad)) < 0)
        return st;
    c = (irc_cache *)(void *)((unsigned char *)cfg->buffer + pad);
    *(unsigned char *)cfg->buffer = (unsigned char)pad;
    irc__attach_pointers(c, cfg, port);
    irc__port_name(port, c->port_name);
    /* What a lookup reads but no check can judge is made anew: the
     * strata's table from the config, and the scratch slots, empty and
     * owned by none. */
    irc__gtab_fill(c->cfg.strata_theta, c->cfg.strata_phi, irc__part(c, c->o_gtab));
    IRC_MEMSET(irc__part(c, c->o_scratch), 0, (size_t)c->cfg.threads * c->slot_bytes);
    /* The copied lock object is the old address's: made anew.  Nothing
     * holds it in a block at rest. */
    IRC_MEMSET(irc__lock(c), 0, c->lock_bytes);
    /* A lock that cannot be made leaves the block moved but whole:
     * irc_attach may be called again. */
    if (port->lock_init(irc__lock(c)) < 0)
        return IRC_ERR_PORT;
    *out = c;
    return IRC_OK;
}

/* A view is a copy of the cache's header: it must fit the room the header
 * promises (C99 has no static_assert: a negative array size stops the
 * build). */
typedef char irc__view_fits[sizeof(irc_cache) <= IRC_VIEW_BYTES ? 1 : -1];

int irc_join(const irc_config *cfg, void *view, size_t view_size, irc_cache **out)
{
    irc_cache head, *home, *v = (irc_cache *)view;
    const irc_port *port;
    char name[16];
    size_t at;
    int st;
    if (!cfg || !out)
        return IRC_ERR_NULL;
    if (cfg->version != IRC_CONFIG_VERSION)
        return IRC_ERR_VERSION;
    if (!cfg->buffer || !cfg->trace || !view)
        return IRC_ERR_NULL;
    /* IRC_VIEW_BYTES, not this build's sizeof: a host sized by less would
     * fail only under a later build. */
    if (view_size < IRC_VIEW_BYTES || ((uintptr_t)view & (sizeof(double) - 1u)))
        return IRC_ERR_NOMEM;
    port = cfg->port ? cfg->port : irc_port_default;
    if ((st = irc__find(cfg, &at, &head)) < 0)
        return st;
    irc__port_name(port, name);
    /* A live block cannot move: this mapping must put the cache where the
     * others do, at the same offset from a 64-byte boundary. */
    if (at != irc__pad(cfg->buffer) || !irc__port_ok(port) ||
        port->lock_size > head.lock_bytes ||
        !irc__same_bytes((const unsigned char *)name, (const unsigned char *)head.port_name, 16))
        return IRC_ERR_CONFIG;
    if ((st = irc__header_sane(cfg, &head, at)) < 0)
        return st;
    home = (irc_cache *)(void *)((unsigned char *)cfg->buffer + at);
    IRC_MEMCPY(v, home, sizeof *v);
    irc__attach_pointers(v, cfg, port);
    v->home = home;
    /* a live block: its records and index are read under the lock */
    if (irc__read_lock(v) < 0)
        return IRC_ERR_PORT;
    st = irc__block_sane(v);
    irc__read_unlock(v);
    if (!st)
        return IRC_ERR_CORRUPT;
    *out = v;
    return IRC_OK;
}

int irc_fini(irc_cache *c)
{
    int st = irc__enter(c, NULL);
    if (st < 0)
        return st;
    if (c->home == c) /* not a view: the lock is this handle's */
        c->port->lock_destroy(irc__lock(c));
    c->magic = 0;
    return IRC_OK;
}
