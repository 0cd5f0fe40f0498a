/*
 * strata.c -- one surface or two between neighbouring samples, and where a
 * curved blocker's silhouette lies in depth (strata.h).
 */
#include "strata.h"

/* Both hits, normals alike and facing the same way, and a depth change no
 * larger than a surface seen at that slant makes over the angle between
 * them (twice over). */
int irc__continuous(const irc__seen *a, const irc__seen *b)
{
    float sa, sb, dw = 0.0f, big, slant;
    int k;
    if (!(a->d < HUGE_VALF) || !(b->d < HUGE_VALF))
        return 0; /* escaped, or NaN: failed */
    sa = a->n[0] * a->w[0] + a->n[1] * a->w[1] + a->n[2] * a->w[2];
    sb = b->n[0] * b->w[0] + b->n[1] * b->w[1] + b->n[2] * b->w[2];
    if ((sa < 0.0f) != (sb < 0.0f) ||
        a->n[0] * b->n[0] + a->n[1] * b->n[1] + a->n[2] * b->n[2] < 0.5f)
        return 0;
    for (k = 0; k < 3; k++)
        dw += (a->w[k] - b->w[k]) * (a->w[k] - b->w[k]);
    big = a->d > b->d ? a->d : b->d;
    slant = IRC_FABSF(sa) > IRC_FABSF(sb) ? IRC_FABSF(sa) : IRC_FABSF(sb);
    return IRC_FABSF(a->d - b->d) * slant <= 2.0f * IRC_SQRTF(dw) * big;
}

/* The last hit before a silhouette (edge) and the one before it on the
 * same grid line (inner).  At a smooth blocker the depth falls short of
 * the silhouette's as D_s - c sqrt(eps) and |n.w| goes as sqrt(eps), eps
 * the angle inside it: the depth is linear in |n.w|, and extrapolated to
 * |n.w| = 0 from the two hits.  That holds on one surface (continuous)
 * that curves (its normal turns faster than the view between the two
 * hits: a flat face seen edge-on has a small |n.w| too, but a fixed
 * normal), deepening toward the silhouette, where |n.w|^2 falls at least
 * as fast as the angle (by 1.25 over one step); the depth may grow by
 * half at most.  Returns 1 and sets *depth then, else 0 and the edge's
 * depth (a polygon's outline, or an edge of the surface itself). */
int irc__silhouette_depth(const irc__seen *edge, const irc__seen *inner, float *depth)
{
    float fe, fi, dn = 0.0f, dw = 0.0f, ds;
    int k;
    *depth = edge->d;
    if (!irc__continuous(edge, inner) || !(inner->d < edge->d))
        return 0;
    for (k = 0; k < 3; k++) {
        dn += (edge->n[k] - inner->n[k]) * (edge->n[k] - inner->n[k]);
        dw += (edge->w[k] - inner->w[k]) * (edge->w[k] - inner->w[k]);
    }
    fe = irc__facing(edge->w, edge->n);
    fi = irc__facing(inner->w, inner->n);
    if (!(dn > dw) || !(fi > fe) || !(fi * fi >= 1.25f * fe * fe))
        return 0;
    ds = edge->d + fe * (edge->d - inner->d) / (fi - fe);
    *depth = ds < 1.5f * edge->d ? ds : 1.5f * edge->d;
    return 1;
}
