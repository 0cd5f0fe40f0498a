/*
 * store.c -- the one record store behind every public call: the handle
 * check, scratch slots, insert with CLOCK eviction, the lookup driver
 * (index query, weighting, accumulation through the record kind's table),
 * lookup-or-compute.  Lookups hold the port's read lock
 * (none in a fill pass); anything that changes records or the index holds
 * its write lock; the host's callback runs with no lock held.  Counters
 * are updated only once a call has succeeded, so a call that fails leaves
 * the block as it was.
 */
#include "cache.h"
#include "index.h"

/* Every public call on a cache starts here: a live cache (IRC_ERR_CONFIG
 * for anything else), of the kind the call serves when want is set. */
int irc__enter(const irc_cache *c, const irc__kind *want)
{
    if (!c)
        return IRC_ERR_NULL;
    if (c->magic != IRC__MAGIC)
        return IRC_ERR_CONFIG;
    return want && c->kind != want ? IRC_ERR_UNSUPPORTED : IRC_OK;
}

/* A finite point and a usable normal; no normal is a free point, for the
 * kinds that have them. */
static int irc__query_make(const irc_cache *c, const float p[3], const float n[3],
                           irc__query *q)
{
    int st, k;
    if ((st = irc__check_vec(p)) < 0)
        return st;
    q->free = n == NULL;
    if (q->free) {
        if (!c->kind->free_points)
            return IRC_ERR_NULL;
        q->n[0] = q->n[1] = q->n[2] = 0.0f;
    } else if ((st = irc__check_normal(n, q->n)) < 0) {
        return st;
    }
    for (k = 0; k < 3; k++)
        q->p[k] = p[k];
    q->hidden = NULL;
    q->n_hidden = 0;
    q->marks = NULL;
    return IRC_OK;
}

/* What every call that takes a query checks first, in this order: the
 * cache, the output, the query. */
static int irc__open(const irc_cache *c, const irc__kind *want, const void *out,
                     const float p[3], const float n[3], irc__query *q)
{
    int st = irc__enter(c, want);
    if (st < 0)
        return st;
    return out ? irc__query_make(c, p, n, q) : IRC_ERR_NULL;
}

/* Runs fn with slot t, which stays claimed. */
static int irc__run_in(irc_cache *c, irc__call *k, uint32_t t, void *host,
                       int (*fn)(irc__call *k, void *out), void *out)
{
    k->c = c;
    k->slot = irc__slot(c, t);
    k->host = host;
    k->rays = 0;
    k->sight = 0;
    return fn(k, out);
}

/* Runs fn with slot t, then gives the slot back. */
static int irc__run(irc_cache *c, irc__call *k, uint32_t t, void *host,
                    int (*fn)(irc__call *k, void *out), void *out)
{
    int st = irc__run_in(c, k, t, host, fn, out);
    irc__slot_release(c, t);
    return st;
}

static void irc__count_compute(irc_cache *c, const irc__call *k, int record, int waited)
{
    if (record)
        irc__count(c, IRC__C_COMPUTES, 1);
    if (waited)
        irc__count(c, IRC__C_WAITS, 1);
    irc__count(c, IRC__C_RAYS, k->rays);
}

/* Runs fn in a claimed slot; its rays in *rays and whether it waited in
 * *waited, counted by the caller (nothing of a failed call is). */
int irc__compute_quiet(irc_cache *c, const irc__kind *want, const float p[3], const float n[3],
                       void *out, void *host, int (*fn)(irc__call *k, void *out),
                       uint32_t *rays, int *waited)
{
    irc__call k;
    uint32_t t;
    int st;
    k.footprint = 0.0f;
    *waited = 0;
    *rays = 0;
    if ((st = irc__open(c, want, out, p, n, &k.q)) < 0 ||
        (st = irc__slot_claim(c, &t, waited)) < 0 ||
        (st = irc__run(c, &k, t, host, fn, out)) < 0)
        return st;
    *rays = k.rays;
    return IRC_OK;
}

int irc__compute(irc_cache *c, const irc__kind *want, const float p[3], const float n[3],
                 void *out, void *host, int (*fn)(irc__call *k, void *out), int record)
{
    irc__call k;
    int st, waited;
    if ((st = irc__compute_quiet(c, want, p, n, out, host, fn, &k.rays, &waited)) < 0)
        return st;
    irc__count_compute(c, &k, record, waited);
    return IRC_OK;
}

/* Second-chance CLOCK: the hand clears the bit of every used record it
 * passes and stops at the first unused one.  Two turns at most. */
static uint32_t irc__clock_victim(irc_cache *c)
{
    uint64_t *used = irc__used(c);
    for (;;) {
        uint32_t id = c->home->hand;
        uint64_t *w = &used[id >> 6], bit = 1ull << (id & 63u);
        c->home->hand = id + 1 == c->capacity ? 0 : id + 1;
        if (!(c->port->load(w) & bit))
            return id;
        c->port->store(w, c->port->load(w) & ~bit);
    }
}

/* Neighbour clamping (Krivanek et al. 2006): records j within the new
 * record's radius R give R = min(R, R_j + |x - x_j|), then records whose
 * radius holds x get R_j = min(R_j, R + |x - x_j|), so that radii change
 * no faster than distance (only such pairs can break that).  Done
 * under the write lock, after the insert can no longer fail; a shrunk
 * R_j keeps every index bound an upper bound, and removal finds records
 * whose home moved deeper (index.c). */
typedef struct irc__near {
    irc_cache *c;
    irc__rec *r;
    int back;
} irc__near;

static void irc__clamp_visit(void *ud, uint32_t id)
{
    irc__near *k = (irc__near *)ud;
    irc__rec *j = irc__rec_at(k->c, id);
    float dx = j->p[0] - k->r->p[0], dy = j->p[1] - k->r->p[1],
           dz = j->p[2] - k->r->p[2], d = IRC_SQRTF(dx * dx + dy * dy + dz * dz);
    if (!k->back && d < k->r->r && j->r + d < k->r->r)
        k->r->r = (float)(j->r + d);
    else if (k->back && d < j->r && k->r->r + d < j->r)
        j->r = (float)(k->r->r + d);
}

static void irc__clamp_neighbours(irc_cache *c, irc__rec *r)
{
    irc__near k;
    k.c = c;
    k.r = r;
    k.back = 0;
    irc__index_range(c, r->p, r->r, irc__clamp_visit, &k);
    k.back = 1;
    irc__index_range(c, r->p, -1.0f, irc__clamp_visit, &k);
    if (r->r < c->cfg.min_radius)
        r->r = c->cfg.min_radius;
}

void irc__commit_locked(irc_cache *c, uint32_t id)
{
    if (c->cfg.clamp_neighbours)
        irc__clamp_neighbours(c, irc__rec_at(c, id));
    irc__index_insert(c, id);
    irc__index_tidy(c);
    irc__count(c, IRC__C_INSERTS, 1);
}

/* A checked record packed straight into its slot: no packed copy of the
 * largest kind on the stack. */
static void irc__pack_at(irc_cache *c, const void *rec, const float un[3], uint32_t id)
{
    IRC_MEMSET(irc__rec_at(c, id), 0, c->rec_size);
    c->kind->pack(c, rec, un, irc__rec_at(c, id));
}

/* In an open pass a record waits, unindexed, in a slot of its own past the
 * frozen records until irc_pass_end; the slot is reserved atomically, so
 * no lock is taken and lookups, which see only indexed records, are not
 * disturbed.  A pass never evicts (that would change what its lookups
 * see): without a free slot the record is not stored. */
static int irc__defer(irc_cache *c, const void *rec, const float un[3])
{
    const uint64_t room = (uint64_t)(c->capacity - c->home->pass_base);
    uint64_t k = c->port->load(&c->home->pending);
    /* Reserved only when there is room: a refused record leaves the
     * block as it was. */
    for (;;) {
        if (k >= room)
            return IRC_ERR_FULL;
        if (c->port->cas(&c->home->pending, k, k + 1))
            break;
        k = c->port->load(&c->home->pending);
    }
    irc__pack_at(c, rec, un, c->home->pass_base + (uint32_t)k);
    c->port->fetch_add(&c->home->packed, 1);
    return IRC_OK;
}

/* Stores a checked record (un: its unit normal) in a free slot, or in
 * CLOCK's victim. */
static int irc__store(irc_cache *c, const void *rec, const float un[3])
{
    uint32_t id;
    if (c->home->pass_open)
        return irc__defer(c, rec, un);
    if (irc__write_lock(c) < 0)
        return IRC_ERR_PORT;
    if (c->home->count < c->capacity) {
        id = c->home->count++;
    } else if (c->o_used) {
        id = irc__clock_victim(c);
        irc__index_remove(c, id);
        irc__count(c, IRC__C_EVICTIONS, 1);
    } else {
        irc__write_unlock(c);
        return IRC_ERR_FULL;
    }
    irc__mark(c, id, IRC__NIL);
    irc__pack_at(c, rec, un, id);
    irc__unmark(c);
    irc__commit_locked(c, id);
    irc__write_unlock(c);
    return IRC_OK;
}

static int irc__insert_checked(irc_cache *c, const void *rec)
{
    float un[3];
    int st;
    if ((st = c->kind->check(c, rec, un)) < 0)
        return st;
    return irc__store(c, rec, un);
}

int irc__insert(irc_cache *c, const irc__kind *want, const void *rec)
{
    int st = irc__enter(c, want);
    if (st < 0)
        return st;
    return rec ? irc__insert_checked(c, rec) : IRC_ERR_NULL;
}

/* CLOCK's use bit: set by lookups, only when not yet set (no write when the
 * line is shared); with marks, remembered, or left unset past their room. */
static void irc__mark_used(irc_cache *c, irc__marks *m, uint32_t id)
{
    uint64_t *used = irc__used(c);
    if (used) {
        uint64_t *word = &used[id >> 6], bit = 1ull << (id & 63u);
        if (c->port->load(word) & bit)
            return;
        if (m && m->n == IRC__MARKS)
            return;
        if (!(c->port->fetch_or(word, bit) & bit) && m)
            m->id[m->n++] = id;
    }
}

/* A failed lookup-or-compute takes back the use bits its lookups set. */
static void irc__unmark_used(irc_cache *c, const irc__marks *m)
{
    uint64_t *used = irc__used(c);
    uint32_t i;
    for (i = 0; used && i < m->n; i++) {
        uint64_t *word = &used[m->id[i] >> 6], bit = 1ull << (m->id[i] & 63u), w;
        do
            w = c->port->load(word);
        while (!c->port->cas(word, w, w & ~bit));
    }
}

/* One lookup's walk: the records of every list the index hands over that
 * the kind accepts, accumulated (acc set) or collected as ids. */
typedef struct irc__walk {
    irc_cache *c;
    const irc__acc *ops;     /* the weight and accumulator: the cache's kind's,
                                or a variant of it (a gradient lookup) */
    const irc__query *q;
    void *acc;
    float w;
    uint32_t *ids, cap, found;
} irc__walk;

static int irc__is_hidden(const irc__query *q, uint32_t id)
{
    uint32_t lo = 0, hi = q->n_hidden;
    while (lo < hi) {
        uint32_t mid = lo + (hi - lo) / 2;
        if (q->hidden[mid] < id)
            lo = mid + 1;
        else
            hi = mid;
    }
    return lo < q->n_hidden && q->hidden[lo] == id;
}

static void irc__visit(void *ud, uint32_t id)
{
    irc__walk *v = (irc__walk *)ud;
    const irc_cache *c = v->c;
    const irc__rec *r = irc__rec_at(c, id);
    float w;
    float ni[3];
    if (!irc__within_reach(c, r, v->q->p) || (v->q->n_hidden && irc__is_hidden(v->q, id)) ||
        !v->ops->weigh(c, r, v->q, &w, ni))
        return;
    v->w += w;
    if (v->acc) {
        v->ops->accumulate(c, r, v->q, w, ni, v->acc);
        irc__mark_used(v->c, v->q->marks, id);
    } else {
        if (v->found < v->cap)
            v->ids[v->found] = id;
        v->found++;
    }
}

/* irc__visit for a kind that weighs and accumulates in one call, when the
 * query hides no record: the same records in the same order. */
static void irc__visit_take(void *ud, uint32_t id)
{
    irc__walk *v = (irc__walk *)ud;
    const float w = v->ops->take(v->c, irc__rec_at(v->c, id), v->q, v->acc);
    if (w > 0.0f) {
        v->w += w;
        irc__mark_used(v->c, v->q->marks, id);
    }
}

/* In an open pass nothing a lookup reads can change until irc_pass_end,
 * which no other call may overlap (irrcache.h), and the pass's own records
 * go to slots no lookup reads: lookups then take no lock, so threads on
 * other cores write no shared line but the counters' stripes and CLOCK
 * bits not yet set.  pass_open itself changes only in irc_pass_begin and
 * irc_pass_end, outside any lookup. */
static int irc__walk_index(irc_cache *c, irc__walk *v)
{
    int lock = !c->home->pass_open;
    if (lock && irc__read_lock(c) < 0)
        return IRC_ERR_PORT;
    irc__index_query(c, v->q->p,
                     v->acc && v->ops->take && !v->q->n_hidden ? irc__visit_take : irc__visit, v);
    if (lock)
        irc__read_unlock(c);
    return IRC_OK;
}

int irc__lookup_once(irc_cache *c, const irc__acc *ops, const irc__query *q, void *out,
                     float *weight, void *acc)
{
    irc__walk v;
    int st;
    IRC_MEMSET(&v, 0, sizeof v);
    v.c = c;
    v.ops = ops;
    v.q = q;
    v.acc = acc;
    ops->begin(c, acc);
    if ((st = irc__walk_index(c, &v)) < 0)
        return st;
    if (weight)
        *weight = v.w;
    return ops->finish(c, q, acc, v.w, out);
}

/* Counts a lookup that returned st (and a hit when it answered).  Errors
 * count nothing. */
static int irc__count_lookup(irc_cache *c, int st)
{
    if (st < 0)
        return st;
    irc__count(c, IRC__C_LOOKUPS, 1);
    if (st == IRC_OK)
        irc__count(c, IRC__C_HITS, 1);
    return st;
}

int irc__lookup(irc_cache *c, const irc__kind *want, const irc__acc *ops, const float p[3],
                const float n[3], void *out, float *weight)
{
    irc__query q;
    irc__marks marks;
    int st = irc__open(c, want, out, p, n, &q);
    if (st < 0)
        return st;
    marks.n = 0;
    q.marks = &marks;
    /* A lookup that read records and then failed (its answer past float)
     * takes its use bits back. */
    if ((st = ops->find(c, &q, out, weight)) < 0)
        irc__unmark_used(c, &marks);
    return irc__count_lookup(c, st);
}

/* The end of a miss: the computed record offered to the pool.  A full
 * pool is IRC_NOT_STORED, counted, not an error. */
static int irc__keep(irc_cache *c, const void *rec, void *out, float *weight)
{
    int st = irc__insert_checked(c, rec);
    if (st < 0 && st != IRC_ERR_FULL)
        return st;
    irc__count(c, IRC__C_LOOKUPS, 1);
    if (st == IRC_ERR_FULL)
        irc__count(c, IRC__C_NOT_STORED, 1);
    c->kind->answer(c, rec, out);
    if (weight)
        *weight = 0.0f;
    return st == IRC_ERR_FULL ? IRC_NOT_STORED : IRC_OK;
}

/* A lookup-or-compute's lookup: what it read, and the rays it cast to
 * confirm its records, counted only if the call succeeds. */
static int irc__lookup_first(irc__call *k, void *out, float *weight, uint32_t *rays)
{
    int st = irc__find_in_sight(k, out, weight);
    *rays += k->rays;
    return st;
}

static int irc__miss(irc_cache *c, irc__call *k, void *out, float *weight, void *host,
                     uint32_t *rays)
{
    uint32_t t;
    void *rec;
    int st, waited = 0;
    if ((st = irc__slot_claim(c, &t, &waited)) < 0)
        return st;
    /* While this thread waited, another may have stored a record here. */
    k->rays = 0;
    if (waited && (st = irc__lookup_first(k, out, weight, rays)) != IRC_MISS) {
        irc__slot_release(c, t);
        return irc__count_lookup(c, st);
    }
    /* The record is built in the slot's tail and kept before the slot is
     * given back; its rays are counted with it, the lookups' by the
     * caller. */
    rec = irc__slot_record(c, t);
    if ((st = irc__run_in(c, k, t, host, c->kind->compute, rec)) >= 0 &&
        (st = irc__keep(c, rec, out, weight)) >= 0)
        irc__count_compute(c, k, 1, waited);
    irc__slot_release(c, t);
    return st;
}

int irc__lookup_or_compute(irc_cache *c, const irc__kind *want, float footprint,
                           const float p[3], const float n[3], void *out, float *weight,
                           void *host, uint32_t rays0)
{
    irc__call k;
    irc__marks marks;
    uint32_t rays = rays0;
    int st;
    if ((st = irc__open(c, want, out, p, n, &k.q)) < 0)
        return st;
    if (!irc__finite(footprint))
        return IRC_ERR_NONFINITE;
    if (footprint < 0.0f)
        return IRC_ERR_RANGE;
    marks.n = 0;
    k.q.marks = &marks;
    k.footprint = footprint;
    k.c = c;
    k.host = host;
    k.rays = 0;
    k.sight = 0;
    st = irc__lookup_first(&k, out, weight, &rays);
    st = st == IRC_MISS ? irc__miss(c, &k, out, weight, host, &rays) : irc__count_lookup(c, st);
    /* Nothing of a failed call stays in the block: not its use bits, nor
     * its rays in the counters. */
    if (st < 0)
        irc__unmark_used(c, &marks);
    else
        irc__count(c, IRC__C_RAYS, rays);
    return st;
}

int irc__record_get(irc_cache *c, const irc__kind *want, uint32_t id, void *out)
{
    int st = irc__enter(c, want);
    if (st < 0)
        return st;
    if (!out)
        return IRC_ERR_NULL;
    if (id >= c->capacity)
        return IRC_ERR_RANGE;
    if (irc__read_lock(c) < 0)
        return IRC_ERR_PORT;
    st = id < c->home->count ? IRC_OK : IRC_MISS;
    if (st == IRC_OK)
        c->kind->unpack(c, irc__rec_at(c, id), out);
    irc__read_unlock(c);
    return st;
}

int irc__collect(irc_cache *c, const irc__query *q, uint32_t *ids, uint32_t cap,
                 uint32_t *found)
{
    irc__walk v;
    int st;
    IRC_MEMSET(&v, 0, sizeof v);
    v.c = c;
    v.ops = c->kind->lookup;
    v.q = q;
    v.ids = ids;
    v.cap = cap;
    if ((st = irc__walk_index(c, &v)) < 0)
        return st;
    *found = v.found;
    return IRC_OK;
}

int irc__positions(irc_cache *c, const uint32_t *ids, uint32_t n, float (*pos)[3],
                   uint32_t *nrm)
{
    int lock = !c->home->pass_open;
    uint32_t i;
    if (lock && irc__read_lock(c) < 0)
        return IRC_ERR_PORT;
    for (i = 0; i < n; i++) {
        const irc__rec *r = irc__rec_at(c, ids[i]);
        IRC_MEMCPY(pos[i], r->p, sizeof pos[i]);
        nrm[i] = r->n;
    }
    if (lock)
        irc__read_unlock(c);
    return IRC_OK;
}

int irc_cache_neighbours(irc_cache *c, const float p[3], const float n[3],
                         uint32_t *ids, uint32_t cap, uint32_t *count)
{
    irc__query q;
    int st;
    if ((st = irc__enter(c, NULL)) < 0 || (st = irc__query_make(c, p, n, &q)) < 0)
        return st;
    if (!count || (!ids && cap))
        return IRC_ERR_NULL;
    return irc__collect(c, &q, ids, cap, count);
}

int irc__write_lock_idle(irc_cache *c)
{
    if (irc__write_lock(c) < 0)
        return IRC_ERR_PORT;
    if (!c->home->pass_open)
        return IRC_OK;
    irc__write_unlock(c);
    return IRC_ERR_STATE;
}

void irc__forget_locked(irc_cache *c)
{
    c->home->hand = 0;
    if (c->o_used)
        IRC_MEMSET(irc__used(c), 0, ((size_t)c->capacity + 63u) / 64u * sizeof(uint64_t));
    irc__index_clear(c);
}

void irc__clear_locked(irc_cache *c)
{
    c->home->count = 0;
    IRC_MEMSET(irc__rec_at(c, 0), 0, (size_t)c->capacity * c->rec_size);
    irc__forget_locked(c);
}

int irc_cache_clear(irc_cache *c)
{
    int st = irc__enter(c, NULL);
    if (st < 0)
        return st;
    if ((st = irc__write_lock_idle(c)) < 0)
        return st;
    irc__clear_locked(c);
    irc__write_unlock(c);
    return IRC_OK;
}
