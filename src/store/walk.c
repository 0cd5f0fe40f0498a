/*
 * walk.c -- one lookup's pass over the index: the records of every list
 * the index hands over that the kind accepts, weighed and accumulated
 * through an accumulator's table (kind.h), or collected as ids (confirming
 * rays, irc_cache_neighbours); CLOCK's use bits set on the way.  Lookups
 * hold the port's read lock (none in an open fill pass).
 */
#include "../block/cache.h"
#include "../index/index.h"
#include "lock.h"
#include "walk.h"

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
void irc__unmark_used(irc_cache *c, const irc__marks *m)
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
    float w, wmax;
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
    if (w > v->wmax)
        v->wmax = w;
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
        if (w > v->wmax)
            v->wmax = w;
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
    int lock = !irc__st(c)->pass_open;
    const irc__visit_fn fn =
        v->acc && v->ops->take && !v->q->n_hidden ? irc__visit_take : irc__visit;
    uint32_t i;
    if (lock && irc__read_lock(c) < 0)
        return IRC_ERR_PORT;
    if (v->q->among)
        for (i = 0; i < v->q->n_among; i++)
            fn(v, v->q->among[i]);
    else
        irc__index_query(c, v->q->p, fn, v);
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
    st = ops->finish(c, q, acc, v.w, out);
    /* Records in reach but none within a R: out has their mean, *weight
     * their weight, and the lookup-or-compute computes (lookup.c). */
    if (st == IRC_OK && q->place && v.wmax <= c->w_inner)
        st = IRC_MISS;
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
    int lock = !irc__st(c)->pass_open;
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

