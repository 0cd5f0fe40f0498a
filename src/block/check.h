/*
 * check.h -- what every public call checks first (check.c): the handle,
 * and the points and normals it is given.
 */
#ifndef IRC_CHECK_H
#define IRC_CHECK_H

#include "../base/kind.h"

/* A live cache (IRC_ERR_NULL, IRC_ERR_CONFIG for anything else), of the
 * kind the call serves when want is set (IRC_ERR_UNSUPPORTED). */
int irc__enter(const irc_cache *c, const irc__kind *want);
/* IRC_ERR_NULL or IRC_ERR_NONFINITE for a point no call takes. */
int irc__check_vec(const float v[3]);
/* A usable normal, made unit in float; IRC_ERR_NULL or IRC_ERR_NORMAL. */
int irc__check_normal(const float n[3], float unit[3]);
/* v over its length for any finite v not zero, scaled by its largest
 * component first so that no square underflows or overflows (lengths from
 * denormals to FLT_MAX): writes that component's magnitude to *big and
 * returns the length over it, in [1, sqrt 3]; 0 (unit not written) for a
 * zero vector. */
float irc__unit3(const float v[3], float unit[3], float *big);

#endif
