/*
 * lookup.c -- the calls every kind's public calls drive: a lookup (the
 * kind's find over the index walk, walk.c), a computation in a claimed
 * scratch slot (slots.c), and lookup-or-compute, which looks up (with
 * confirming rays when the config asks, confirm.c) and on a miss computes
 * the record in its slot and offers it to the pool (store.c).  The host's
 * callback runs with no lock held.  Counters are updated only once a call
 * has succeeded.
 */
#include "../block/cache.h"
#include "../block/form.h"
#include "../block/check.h"
#include "../block/slots.h"
#include "lookup.h"
#include "confirm.h"
#include "stats.h"
#include "store.h"
#include "walk.h"

/* A shading normal more than 60 degrees from the geometric one would have
 * more than a third of its hemisphere below the surface, its rays failed
 * uncast: the query gathers around the geometric normal there instead
 * (on four Sponza views the rule with the failed rays below cut the time
 * at equal error 1.5-2.3x: bench/notes.md, "Rays under the surface"). */
#define IRC__GATHER_COS 0.5f

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
    q->among = NULL;
    q->n_among = 0;
    q->marks = NULL;
    q->place = 0;
    q->under = 0;
    return IRC_OK;
}

int irc__query_ground(irc__query *q, const float ng[3])
{
    float g[3], d;
    int st, k;
    if (!ng)
        return IRC_OK;
    if ((st = irc__check_normal(ng, g)) < 0)
        return st;
    d = irc__dot3(q->n, g);
    for (k = 0; k < 3; k++) {
        q->g[k] = d < 0.0f ? -g[k] : g[k];
        if (d < IRC__GATHER_COS && d > -IRC__GATHER_COS)
            q->n[k] = q->g[k];
    }
    q->under = 1;
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
static int irc__compute_in_slot(irc_cache *c, irc__call *k, uint32_t t, void *host,
                                int (*fn)(irc__call *k, void *out), void *out)
{
    k->c = c;
    k->slot = irc__slot(c, t);
    k->host = host;
    k->rays = 0;
    k->visibility_only = 0;
    k->progress = irc__st(c)->progress;
    return fn(k, out);
}

/* Runs fn with slot t, then gives the slot back. */
static int irc__compute_and_release(irc_cache *c, irc__call *k, uint32_t t, void *host,
                                    int (*fn)(irc__call *k, void *out), void *out)
{
    int st = irc__compute_in_slot(c, k, t, host, fn, out);
    irc__slot_release(c, t);
    return st;
}

/* What a compute in a slot adds: a record when record is set, a wait, its
 * rays. */
static void irc__tally_compute(irc__counts *t, const irc__call *k, int record, int waited)
{
    t->add[IRC__C_COMPUTES] += record != 0;
    t->add[IRC__C_WAITS] += waited != 0;
    t->add[IRC__C_RAYS] += k->rays;
}

int irc__compute_at(irc_cache *c, const irc__query *q, void *out, void *host,
                    int (*fn)(irc__call *k, void *out), uint32_t *rays, int *waited)
{
    irc__call k;
    uint32_t t;
    int st;
    k.q = *q;
    k.footprint = 0.0f;
    k.draw = 0;
    *waited = 0;
    *rays = 0;
    if ((st = irc__slot_claim(c, &t, waited)) < 0 ||
        (st = irc__compute_and_release(c, &k, t, host, fn, out)) < 0)
        return st;
    *rays = k.rays;
    return IRC_OK;
}

int irc__compute(irc_cache *c, const irc__kind *want, const float p[3], const float n[3],
                 void *out, void *host, int (*fn)(irc__call *k, void *out), int record)
{
    irc__call k;
    irc__counts t;
    int st, waited;
    if ((st = irc__open(c, want, out, p, n, &k.q)) < 0 ||
        (st = irc__compute_at(c, &k.q, out, host, fn, &k.rays, &waited)) < 0)
        return st;
    IRC_MEMSET(&t, 0, sizeof t);
    irc__tally_compute(&t, &k, record, waited);
    irc__count_tally(c, &t);
    return IRC_OK;
}

/* A lookup that returned st, and a hit when it answered.  Errors add
 * nothing. */
static int irc__tally_lookup(irc__counts *t, int st)
{
    if (st < 0)
        return st;
    t->add[IRC__C_LOOKUPS]++;
    t->add[IRC__C_HITS] += st == IRC_OK;
    return st;
}

int irc__lookup(irc_cache *c, const irc__kind *want, const irc__acc *ops, const float p[3],
                const float n[3], void *out, float *weight)
{
    irc__query q;
    irc__marks marks;
    irc__counts t;
    int st = irc__open(c, want, out, p, n, &q);
    if (st < 0)
        return st;
    marks.n = 0;
    q.marks = &marks;
    /* A miss where a lookup-or-compute would compute (out keeps the mean
     * of the records within blend a R). */
    q.place = c->w_inner > 0.0f;
    /* A lookup that read records and then failed (its answer past float)
     * takes its use bits back. */
    if ((st = ops->find(c, &q, out, weight)) < 0) {
        irc__unmark_used(c, &marks);
        return st;
    }
    IRC_MEMSET(&t, 0, sizeof t);
    irc__tally_lookup(&t, st);
    irc__count_tally(c, &t);
    return st;
}

/* The end of a miss: the computed record offered to the pool.  A full
 * pool is IRC_NOT_STORED, counted, not an error.  *weight holds the
 * weight of the records the lookup found beyond a R (their mean in out),
 * which the answer blends in; it becomes 0, a computed record's. */
static int irc__offer_computed(irc_cache *c, const void *rec, void *out, float *weight,
                               irc__counts *t)
{
    int st = irc__insert_checked(c, rec);
    if (st < 0 && st != IRC_ERR_FULL)
        return st;
    t->add[IRC__C_LOOKUPS]++;
    t->add[IRC__C_NOT_STORED] += st == IRC_ERR_FULL;
    if (*weight > 0.0f && c->kind->mix_in)
        c->kind->mix_in(c, rec, out, *weight);
    else
        c->kind->answer(c, rec, out);
    *weight = 0.0f;
    return st == IRC_ERR_FULL ? IRC_NOT_STORED : IRC_OK;
}

/* Confirming rays (cfg.check_visibility, confirm.c): the records a lookup
 * would use, up to IRC__SIGHT_CAP, their positions read IRC__SIGHT_BATCH
 * at a time and handed to confirm.c, which hides those out of the query's
 * sight; the kind's find then leaves the hidden ones out. */
#ifndef IRC_NO_SIGHT
static int irc__find_confirmed(irc__call *k, void *out, float *weight)
{
    irc_cache *c = k->c;
    uint32_t ids[IRC__SIGHT_CAP], order[IRC__SIGHT_CAP], nrm[IRC__SIGHT_BATCH], found, i, n,
        batch;
    float pos[IRC__SIGHT_BATCH][3];
    int st;
    if ((st = irc__collect(c, &k->q, ids, IRC__SIGHT_CAP, &found)) < 0)
        return st;
    /* All of them collected: the second walk takes them, in the first
     * walk's order, rather than the index again (the same records weighed
     * in the same order, so the same answer at half the walking). */
    if (found <= IRC__SIGHT_CAP) {
        IRC_MEMCPY(order, ids, found * sizeof *ids);
        k->q.among = order;
        k->q.n_among = found;
    } else {
        found = IRC__SIGHT_CAP;
    }
    batch = c->cfg.max_batch < IRC__SIGHT_BATCH ? c->cfg.max_batch : IRC__SIGHT_BATCH;
    for (i = 0; i < found && st >= 0; i += batch) {
        n = found - i < batch ? found - i : batch;
        if ((st = irc__positions(c, ids + i, n, pos, nrm)) >= 0)
            st = irc__confirm_batch(k, ids, i, n, (const float(*)[3])pos, nrm);
    }
    if (st >= 0) {
        irc__confirm_hide(k, ids);
        st = c->kind->lookup->find(c, &k->q, out, weight);
    }
    k->q.hidden = NULL;
    k->q.n_hidden = 0;
    k->q.among = NULL;
    k->q.n_among = 0;
    return st;
}
#endif

/* The kind's find at k->q (k->c, k->host set), without the records out
 * of the query's sight when the config asks. */
static int irc__find_in_sight(irc__call *k, void *out, float *weight)
{
    k->q.hidden = NULL;
    k->q.n_hidden = 0;
#ifndef IRC_NO_SIGHT
    if (k->c->cfg.check_visibility && !k->q.free)
        return irc__find_confirmed(k, out, weight);
#endif
    return k->c->kind->lookup->find(k->c, &k->q, out, weight);
}

/* A lookup-or-compute's lookup: what it read, and the rays it cast to
 * confirm its records. */
static int irc__lookup_first(irc__call *k, void *out, float *weight, irc__counts *t)
{
    int st = irc__find_in_sight(k, out, weight);
    t->add[IRC__C_RAYS] += k->rays;
    return st;
}

static int irc__miss(irc_cache *c, irc__call *k, void *out, float *weight, void *host,
                     irc__counts *t)
{
    uint32_t slot;
    void *rec;
    int st, waited = 0;
    if ((st = irc__slot_claim(c, &slot, &waited)) < 0)
        return st;
    /* While this thread waited, another may have stored a record here. */
    k->rays = 0;
    if (waited && (st = irc__lookup_first(k, out, weight, t)) != IRC_MISS) {
        irc__slot_release(c, slot);
        return irc__tally_lookup(t, st);
    }
    /* The record is built in the slot's tail and kept before the slot is
     * given back. */
    rec = irc__slot_record(c, slot);
    if ((st = irc__compute_in_slot(c, k, slot, host, c->kind->compute, rec)) >= 0 &&
        (st = irc__offer_computed(c, rec, out, weight, t)) >= 0)
        irc__tally_compute(t, k, 1, waited);
    irc__slot_release(c, slot);
    return st;
}

int irc__loc_open(irc_cache *c, const irc__kind *want, const float p[3], const float n[3],
                 const float ng[3], float footprint, const void *out, irc__loc *px)
{
    int st;
    if ((st = irc__open(c, want, out, p, n, &px->q)) < 0 ||
        (st = irc__query_ground(&px->q, ng)) < 0)
        return st;
    if (!irc__finite(footprint))
        return IRC_ERR_NONFINITE;
    if (footprint < 0.0f)
        return IRC_ERR_RANGE;
    px->footprint = footprint;
    px->loose = 0;
    IRC_MEMSET(&px->tally, 0, sizeof px->tally);
    return IRC_OK;
}

int irc__loc_finish(irc_cache *c, irc__loc *px, int st, void *out, float *weight, void *host)
{
    irc__call k;
    irc__marks marks;
    float w = 0.0f;
    if (st == IRC_MISS) {
        k.q = px->q;
        marks.n = 0;
        k.q.marks = &marks;
        k.footprint = px->footprint;
        k.c = c;
        k.host = host;
        k.rays = 0;
        k.visibility_only = 0;
        k.draw = 0;
        k.q.place = c->w_inner > 0.0f && !px->loose;
        st = irc__lookup_first(&k, out, &w, &px->tally);
        st = st == IRC_MISS ? irc__miss(c, &k, out, &w, host, &px->tally)
                            : irc__tally_lookup(&px->tally, st);
        /* Nothing of a failed call stays in the block: not its use bits,
         * nor anything in the counters. */
        if (st < 0)
            irc__unmark_used(c, &marks);
    }
    if (st < 0)
        return st;
    irc__count_tally(c, &px->tally);
    if (weight)
        *weight = w;
    return st;
}

int irc__lookup_or_compute(irc_cache *c, const irc__kind *want, const float p[3],
                           const float n[3], void *out, float *weight, void *host)
{
    irc__loc px;
    const int st = irc__loc_open(c, want, p, n, NULL, 0.0f, out, &px);
    return st < 0 ? st : irc__loc_finish(c, &px, IRC_MISS, out, weight, host);
}

int irc__neighbours(irc_cache *c, const float p[3], const float n[3], uint32_t *ids,
                    uint32_t cap, uint32_t *count)
{
    irc__query q;
    int st;
    if ((st = irc__enter(c, NULL)) < 0 || (st = irc__query_make(c, p, n, &q)) < 0)
        return st;
    if (!count || (!ids && cap))
        return IRC_ERR_NULL;
    return irc__collect(c, &q, ids, cap, count);
}

