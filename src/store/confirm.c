/*
 * confirm.c -- confirming rays (cfg.check_visibility): before a
 * lookup-or-compute averages its records, one ray from the query toward
 * each of them; a record out of the query's sight is left out, so the
 * light of a wall's open side does not reach a crevice, a soffit or the
 * foot of a column through a record placed outside it.  This is V-Ray's "check sample
 * visibility"; Ward's weight and the leak guard look at the record's own
 * hemisphere only, and a record's reach can span geometry smaller than
 * itself (Krivanek and Gautron 2009, Sec. 2.3.3).  The lookup collects
 * the candidates and their positions (lookup.c, walk.c); this file only
 * casts the rays and says which records are hidden.
 */
#include "../block/octa.h"
#include "trace.h"
#include "confirm.h"

#ifndef IRC_NO_SIGHT

/* A hit this far along the way to the record, or nearer, hides it.  The
 * rest is the record's own surface and what lies just before it, which
 * the record's hemisphere has seen (a host's ray offsets move the hit by
 * a few epsilons). */
#define IRC__SIGHT_SHORT 0.9f

/* The direction from the query toward a record at distance l along d.  A
 * record on the same convex surface as the query lies below the query's
 * tangent plane: on a circle the chord leaves the tangent at half the
 * angle between n and n_i, and the surface bulges above the chord by l^2
 * / 8r, far more than the epsilons a host offsets its rays by, so a ray
 * along the chord meets the query's own surface at once and every record
 * on a ball or a column would be hidden.  The chord is raised toward the
 * tangent plane by as much of its dip as the normals' turn explains, up to
 * 2 sin(theta / 2) = sqrt(2 (1 - n.n_i)): twice a circle's, since on a
 * tessellated surface a chord from a face's edge dips by the whole angle
 * between the faces.  A dip the normals do not explain (a record past a
 * ledge's edge, below the query, the normals alike) keeps its ray. */
static void irc__confirm_dir(const float n[3], uint32_t code, const float d[3], float l,
                           float dir[3])
{
    float ni[3], dip = -(d[0] * n[0] + d[1] * n[1] + d[2] * n[2]) / l, turn, m;
    int j;
    for (j = 0; j < 3; j++)
        dir[j] = d[j] / l;
    if (!(dip > 0.0f) || code == IRC__FREE)
        return;
    irc__oct_decode(code, ni);
    turn = 2.0f * (1.0f - (n[0] * ni[0] + n[1] * ni[1] + n[2] * ni[2]));
    turn = turn > 0.0f ? IRC_SQRTF(turn) : 0.0f;
    if (turn <= 0.0f)
        return;
    for (j = 0; j < 3; j++)
        dir[j] += (dip < turn ? dip : turn) * n[j];
    m = IRC_SQRTF(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);
    for (j = 0; j < 3; j++)
        dir[j] /= m;
}

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
 * (at pos, coded normals nrm) and moves the ids of the hidden ones to the
 * front of ids, in place (k->q.n_hidden counts them; none is written past
 * the one being read).  Only status and dist of the hits are read. */
int irc__confirm_batch(irc__call *k, uint32_t *ids, uint32_t first, uint32_t n,
                     const float (*pos)[3], const uint32_t *nrm)
{
    irc_ray rays[IRC__SIGHT_BATCH];
    irc_hit hits[IRC__SIGHT_BATCH];
    float len[IRC__SIGHT_BATCH];
    uint32_t i, m = 0, at[IRC__SIGHT_BATCH];
    int j, st;
    for (i = 0; i < n; i++) {
        float d[3], l;
        for (j = 0; j < 3; j++)
            d[j] = pos[i][j] - k->q.p[j];
        l = IRC_SQRTF(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
        if (!(l > 0.0f && l <= FLT_MAX))
            continue; /* at the query's own point, or beyond float */
        IRC_MEMCPY(rays[m].org, k->q.p, sizeof rays[m].org);
        irc__confirm_dir(k->q.n, nrm[i], d, l, rays[m].dir);
        len[m] = l;
        at[m++] = first + i;
    }
    if (m == 0)
        return IRC_OK;
    if ((st = irc__cast_visibility(k, rays, hits, m, IRC_VISIBILITY_CONFIRM)) < 0)
        return st;
    for (i = 0; i < m; i++) {
        if ((st = irc__visibility_hit(&hits[i])) < 0)
            return st;
        if (st && hits[i].dist < IRC__SIGHT_SHORT * len[i])
            ids[k->q.n_hidden++] = ids[at[i]];
    }
    return IRC_OK;
}

void irc__confirm_hide(irc__call *k, uint32_t *ids)
{
    irc__sort_ids(ids, k->q.n_hidden);
    k->q.hidden = ids;
}

#else /* IRC_NO_SIGHT: lookup.c asks for no confirming rays */

typedef int irc__confirm_absent; /* ISO C wants something in a file */

#endif
