/*
 * cache.c -- the cache's public calls: insert (with CLOCK eviction), lookup,
 * lookup-or-compute, and the read-only views.  Lookups hold the port's read
 * lock; anything that changes records or the index holds its write lock.
 * Counters are updated only once a call has succeeded, so a call that fails
 * leaves the block as it was.
 */
#include "cache.h"

int irc__check_cache(const irc_cache *c)
{
    if (!c)
        return IRC_ERR_NULL;
    return c->magic == IRC__MAGIC ? IRC_OK : IRC_ERR_CONFIG;
}

/* The irradiance calls serve caches without IRC_FEATURE_SH only. */
static int irc__check_irr(const irc_cache *c)
{
    int st = irc__check_cache(c);
    if (st < 0)
        return st;
    return c->sh_n ? IRC_ERR_UNSUPPORTED : IRC_OK;
}

static void irc__count(irc_cache *c, int which, uint64_t v)
{
    c->port->fetch_add(&c->ctr[which], v);
}

/* Second-chance CLOCK: the hand clears the bit of every used record it
 * passes and stops at the first unused one.  Two turns at most. */
static uint32_t irc__clock_victim(irc_cache *c)
{
    for (;;) {
        uint32_t id = c->hand;
        uint64_t *w = &c->used[id >> 6], bit = 1ull << (id & 63u);
        c->hand = id + 1 == c->capacity ? 0 : id + 1;
        if (!(c->port->load(w) & bit))
            return id;
        c->port->store(w, c->port->load(w) & ~bit);
    }
}

/* Stores a packed record (rec_size bytes, already checked) in a free slot,
 * or in CLOCK's victim. */
int irc__store(irc_cache *c, const void *packed)
{
    uint32_t id;
    c->port->write_lock(c->lock);
    if (c->count < c->capacity) {
        id = c->count++;
    } else if (c->used) {
        id = irc__clock_victim(c);
        irc__index_remove(c, id);
        irc__count(c, IRC__C_EVICTIONS, 1);
    } else {
        c->port->write_unlock(c->lock);
        return IRC_ERR_FULL;
    }
    IRC_MEMCPY(irc__rec_at(c, id), packed, c->rec_size);
    irc__index_insert(c, id);
    irc__count(c, IRC__C_INSERTS, 1);
    c->port->write_unlock(c->lock);
    return IRC_OK;
}

int irc_cache_insert(irc_cache *c, const irc_record *rec)
{
    union { irc__rec head; unsigned char b[64]; } packed;
    int st;
    if ((st = irc__check_irr(c)) < 0)
        return st;
    if (!rec)
        return IRC_ERR_NULL;
    if ((st = irc__record_check(rec)) < 0)
        return st;
    irc__record_pack(c, rec, &packed);
    return irc__store(c, &packed);
}

/* CLOCK's use bit: set by lookups, only when not yet set (no write when the
 * line is shared). */
void irc__mark_used(irc_cache *c, uint32_t id)
{
    if (c->used) {
        uint64_t *word = &c->used[id >> 6], bit = 1ull << (id & 63u);
        if (!(c->port->load(word) & bit))
            c->port->fetch_or(word, bit);
    }
}

typedef struct irc__acc {
    irc_cache *c;
    const float *p, *n;
    double sum[3], w;
    uint32_t *ids, cap, found;
} irc__acc;

static void irc__visit_lookup(void *ud, uint32_t id)
{
    irc__acc *a = (irc__acc *)ud;
    const irc_cache *c = a->c;
    for (; id != IRC__NIL; id = c->next[id]) {
        const irc__rec *r = irc__rec_at(c, id);
        double w, v[3];
        float ni[3];
        if (!irc__within_reach(c, r, a->p) || !irc__weigh(c, r, a->p, a->n, &w, ni))
            continue;
        irc__extrapolate(c, r, ni, a->p, a->n, v);
        a->sum[0] += w * v[0];
        a->sum[1] += w * v[1];
        a->sum[2] += w * v[2];
        a->w += w;
        irc__mark_used(a->c, id);
    }
}

static void irc__visit_ids(void *ud, uint32_t id)
{
    irc__acc *a = (irc__acc *)ud;
    for (; id != IRC__NIL; id = a->c->next[id]) {
        const irc__rec *r = irc__rec_at(a->c, id);
        double w;
        float ni[3];
        if (irc__within_reach(a->c, r, a->p) && irc__weigh(a->c, r, a->p, a->n, &w, ni)) {
            if (a->found < a->cap)
                a->ids[a->found] = id;
            a->found++;
        }
    }
}

/* Validates the query and turns n into a unit float normal. */
static int irc__query_init(irc_cache *c, const float p[3], const float n[3],
                           float un[3], irc__acc *a, int any)
{
    double d[3];
    int st;
    if ((st = any ? irc__check_cache(c) : irc__check_irr(c)) < 0 ||
        (st = irc__check_vec(p)) < 0 ||
        (st = irc__check_normal(n, d)) < 0)
        return st;
    un[0] = (float)d[0];
    un[1] = (float)d[1];
    un[2] = (float)d[2];
    IRC_MEMSET(a, 0, sizeof *a);
    a->c = c;
    a->p = p;
    a->n = un;
    return IRC_OK;
}

static int irc__lookup(irc_cache *c, const float p[3], const float n[3],
                       float rgb[3], float *weight)
{
    irc__acc a;
    float un[3];
    int st = irc__query_init(c, p, n, un, &a, 0), ch;
    if (st < 0)
        return st;
    if (!rgb)
        return IRC_ERR_NULL;
    c->port->read_lock(c->lock);
    irc__index_query(c, p, irc__visit_lookup, &a);
    c->port->read_unlock(c->lock);
    for (ch = 0; ch < 3; ch++)
        rgb[ch] = a.w > 0.0 ? (float)(a.sum[ch] / a.w) : 0.0f;
    if (weight)
        *weight = (float)a.w;
    /* Records with irradiance and gradients near FLT_MAX can extrapolate
     * past it. */
    if (!irc__finite3(rgb))
        return IRC_ERR_NONFINITE;
    return a.w > 0.0 ? IRC_OK : IRC_MISS;
}

/* Counts a lookup that returned st (and a hit when it answered): what the
 * irradiance and SH lookups share.  Errors count nothing. */
int irc__count_lookup(irc_cache *c, int st)
{
    if (st < 0)
        return st;
    irc__count(c, IRC__C_LOOKUPS, 1);
    if (st == IRC_OK)
        irc__count(c, IRC__C_HITS, 1);
    return st;
}

/* The end of a lookup-or-compute whose miss was computed and offered to
 * the pool with status ins: a full pool is IRC_NOT_STORED, not an error. */
int irc__count_miss(irc_cache *c, int ins)
{
    if (ins < 0 && ins != IRC_ERR_FULL)
        return ins;
    irc__count(c, IRC__C_LOOKUPS, 1);
    return ins == IRC_ERR_FULL ? IRC_NOT_STORED : IRC_OK;
}

void irc__count_compute(irc_cache *c, uint64_t rays)
{
    irc__count(c, IRC__C_COMPUTES, 1);
    irc__count(c, IRC__C_RAYS, rays);
}

int irc_cache_lookup(irc_cache *c, const float p[3], const float n[3],
                     float rgb[3], float *weight)
{
    return irc__count_lookup(c, irc__lookup(c, p, n, rgb, weight));
}

int irc_cache_lookup_or_compute(irc_cache *c, const float p[3],
                                const float n[3], float rgb[3], float *weight)
{
    irc_record rec;
    int st = irc__lookup(c, p, n, rgb, weight);
    if (st != IRC_MISS)
        return irc__count_lookup(c, st);
    if ((st = irc_record_compute(c, p, n, &rec)) < 0)
        return st;
    if ((st = irc__count_miss(c, irc_cache_insert(c, &rec))) < 0)
        return st;
    rgb[0] = rec.e[0];
    rgb[1] = rec.e[1];
    rgb[2] = rec.e[2];
    if (weight)
        *weight = 0.0f;
    return st;
}

int irc_cache_neighbours(irc_cache *c, const float p[3], const float n[3],
                         uint32_t *ids, uint32_t cap, uint32_t *count)
{
    irc__acc a;
    float un[3];
    int st = irc__query_init(c, p, n, un, &a, 1);
    if (st < 0)
        return st;
    if (!count || (!ids && cap))
        return IRC_ERR_NULL;
    a.ids = ids;
    a.cap = cap;
    c->port->read_lock(c->lock);
    irc__index_query(c, p, irc__visit_ids, &a);
    c->port->read_unlock(c->lock);
    *count = a.found;
    return IRC_OK;
}

int irc_cache_record(irc_cache *c, uint32_t id, irc_record *out)
{
    int st = irc__check_irr(c);
    if (st < 0)
        return st;
    if (!out)
        return IRC_ERR_NULL;
    if (id >= c->capacity)
        return IRC_ERR_RANGE;
    c->port->read_lock(c->lock);
    st = id < c->count ? IRC_OK : IRC_MISS;
    if (st == IRC_OK)
        irc__record_unpack(c, irc__rec_at(c, id), out);
    c->port->read_unlock(c->lock);
    return st;
}

int irc_cache_clear(irc_cache *c)
{
    int st = irc__check_cache(c);
    if (st < 0)
        return st;
    c->port->write_lock(c->lock);
    c->count = 0;
    c->hand = 0;
    IRC_MEMSET(c->records, 0, (size_t)c->capacity * c->rec_size);
    IRC_MEMSET(c->next, 0, (size_t)c->capacity * sizeof *c->next);
    IRC_MEMSET(c->nodes, 0, (size_t)c->nodes_used * sizeof *c->nodes);
    if (c->used)
        IRC_MEMSET(c->used, 0, ((size_t)c->capacity + 63u) / 64u * sizeof *c->used);
    irc__index_reset(c);
    c->port->write_unlock(c->lock);
    return IRC_OK;
}

int irc_cache_stats(irc_cache *c, irc_stats *out)
{
    int st = irc__check_cache(c);
    if (st < 0)
        return st;
    if (!out)
        return IRC_ERR_NULL;
    IRC_MEMSET(out, 0, sizeof *out);
    c->port->read_lock(c->lock);
    out->records = c->count;
    out->index_nodes = c->nodes_used;
    c->port->read_unlock(c->lock);
    out->capacity = c->capacity;
    out->inserts = c->port->load(&c->ctr[IRC__C_INSERTS]);
    out->evictions = c->port->load(&c->ctr[IRC__C_EVICTIONS]);
    out->lookups = c->port->load(&c->ctr[IRC__C_LOOKUPS]);
    out->hits = c->port->load(&c->ctr[IRC__C_HITS]);
    out->computes = c->port->load(&c->ctr[IRC__C_COMPUTES]);
    out->rays = c->port->load(&c->ctr[IRC__C_RAYS]);
    out->index_nodes_max = c->node_cap;
    out->record_bytes = c->rec_size;
    out->bytes_records = (size_t)c->capacity * c->rec_size;
    out->bytes_index = (size_t)c->capacity * sizeof(uint32_t) +
                       (size_t)c->node_cap * sizeof(irc__node) +
                       (c->used ? ((size_t)c->capacity + 63u) / 64u * 8u : 0u);
    out->bytes_scratch = (size_t)c->cfg.threads * c->slot_bytes;
    out->bytes_total = c->total_bytes;
    return IRC_OK;
}
