/*
 * strata.h -- the stratum grid as a surface seen from the record's point:
 * neighbours across the azimuth's wrap, a sample's facing, whether two
 * neighbouring samples lie on one surface, and the one rule for where a
 * curved blocker's silhouette lies in depth, which the visibility, Hessian
 * and SH estimators share (strata.c).
 */
#ifndef IRC_STRATA_H
#define IRC_STRATA_H

#include "../util.h"

/* Sample (j, k) of an m x n grid, the column wrapped (the azimuth is
 * periodic); -1 past the first or last row. */
static inline int64_t irc__strata_at(uint32_t m, uint32_t n, int64_t j, int64_t k)
{
    if (j < 0 || j >= (int64_t)m)
        return -1;
    k %= (int64_t)n;
    return j * (int64_t)n + (k < 0 ? k + (int64_t)n : k);
}

/* What one ray saw: its unit direction, the unit normal and depth of its
 * hit. */
typedef struct irc__seen {
    const float *w, *n;
    float d;
} irc__seen;

/* Sample i of a slot's directions and hit normals (3 floats each), at
 * depth d. */
static inline irc__seen irc__seen_at(const float *dirs, const float *nrm, uint32_t i, float d)
{
    irc__seen v;
    v.w = dirs + 3u * i;
    v.n = nrm + 3u * i;
    v.d = d;
    return v;
}

/* |n.w| of a hit: how squarely its surface faces the record. */
static inline float irc__facing(const float w[3], const float n[3])
{
    return IRC_FABSF(w[0] * n[0] + w[1] * n[1] + w[2] * n[2]);
}

int irc__continuous(const irc__seen *a, const irc__seen *b);
int irc__silhouette_depth(const irc__seen *edge, const irc__seen *inner, float *depth);

#endif
