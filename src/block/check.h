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

#endif
