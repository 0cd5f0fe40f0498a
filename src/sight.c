/*
 * Confirming rays (cfg.check_visibility): before a lookup-or-compute
 * averages its records, one ray from the query toward each of them; a
 * record out of the query's sight is left out, so the light of a wall's
 * open side does not reach a crevice, a soffit or the foot of a column
 * through a record placed outside it.  This is V-Ray's "check sample
 * visibility"; Ward's weight and the leak guard look at the record's own
 * hemisphere only, and a record's reach can span geometry smaller than
 * itself (Krivanek and Gautron 2009, Sec. 2.3.3).
 */
#include "cache.h"
#include "sampler.h"

#ifndef IRC_NO_SIGHT

#define IRC__SIGHT_CAP 32u   /* records checked per lookup; more: unchecked */
#define IRC__SIGHT_BATCH 8u  /* rays per callback call, at most */

/* A hit this far along the way to the record, or nearer, hides it.  The
 * rest is the record's own surface and what lies just before it, which
 * the record's hemisphere has seen (a host's ray offsets move the hit by
 * a few epsilons). */
#define IRC__SIGHT_SHORT 0.9f

static void irc__sort_ids(uint32_t *ids, uint32_t n)
{
    uint32_t i, j;
    for (i = 1; i < n; i++) {
        uint32_t x = ids[i];
        for (j = i; j > 0 && ids[j - 1] > x; j--)
            ids[j] = ids[j - 1];
        ids[j] = x;
    }
}

/* Casts rays from k->q.p toward the records ids[first .. first + n - 1]
 * and moves the ids of the hidden ones to the front of ids, in place (k->
 * q.n_hidden counts them; none is written past the one being read).  Only
 * status and dist of the hits are read. */
static int irc__sight_batch(irc__call *k, uint32_t *ids, uint32_t first, uint32_t n)
{
    irc_ray rays[IRC__SIGHT_BATCH];
    irc_hit hits[IRC__SIGHT_BATCH];
    float len[IRC__SIGHT_BATCH], pos[IRC__SIGHT_BATCH][3];
    uint32_t i, m = 0, at[IRC__SIGHT_BATCH];
    int j, st;
    if ((st = irc__positions(k->c, ids + first, n, pos)) < 0)
        return st;
    for (i = 0; i < n; i++) {
        float d[3], l;
        for (j = 0; j < 3; j++)
            d[j] = pos[i][j] - k->q.p[j];
        l = IRC_SQRTF(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
        if (!(l > 0.0f && l <= FLT_MAX))
            continue; /* at the query's own point, or beyond float */
        for (j = 0; j < 3; j++) {
            rays[m].org[j] = k->q.p[j];
            rays[m].dir[j] = d[j] / l;
        }
        len[m] = l;
        at[m++] = first + i;
    }
    if (m == 0)
        return IRC_OK;
    k->sight = 1;
    st = irc__cast(k, rays, hits, m);
    k->sight = 0;
    if (st < 0)
        return st;
    for (i = 0; i < m; i++) {
        const irc_hit *h = &hits[i];
        if (h->status == IRC_RAY_HIT && !(h->dist > 0.0f && h->dist <= FLT_MAX))
            return IRC_ERR_CALLBACK;
        if (h->status < IRC_RAY_HIT || h->status > IRC_RAY_FAILED)
            return IRC_ERR_CALLBACK;
        if (h->status == IRC_RAY_HIT && h->dist < IRC__SIGHT_SHORT * len[i])
            ids[k->q.n_hidden++] = ids[at[i]];
    }
    return IRC_OK;
}

int irc__find_in_sight(irc__call *k, void *out, float *weight)
{
    irc_cache *c = k->c;
    uint32_t ids[IRC__SIGHT_CAP], found, i, batch;
    int st;
    k->q.hidden = NULL;
    k->q.n_hidden = 0;
    if (!c->cfg.check_visibility || k->q.free)
        return c->kind->lookup->find(c, &k->q, out, weight);
    if ((st = irc__collect(c, &k->q, ids, IRC__SIGHT_CAP, &found)) < 0)
        return st;
    if (found > IRC__SIGHT_CAP)
        found = IRC__SIGHT_CAP;
    batch = c->cfg.max_batch < IRC__SIGHT_BATCH ? c->cfg.max_batch : IRC__SIGHT_BATCH;
    for (i = 0; i < found && st >= 0; i += batch)
        st = irc__sight_batch(k, ids, i, found - i < batch ? found - i : batch);
    if (st < 0)
        return st;
    irc__sort_ids(ids, k->q.n_hidden);
    k->q.hidden = ids;
    st = c->kind->lookup->find(c, &k->q, out, weight);
    k->q.hidden = NULL;
    k->q.n_hidden = 0;
    return st;
}

#else /* IRC_NO_SIGHT: absent.c's plain find */

typedef int irc__sight_absent; /* ISO C wants something in a file */

#endif
