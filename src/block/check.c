/*
 * check.c -- the checks every call makes of the vectors it is given.
 */
#include "form.h"
#include "check.h"

int irc__check_vec(const float v[3])
{
    if (!v)
        return IRC_ERR_NULL;
    return irc__finite3(v) ? IRC_OK : IRC_ERR_NONFINITE;
}

/* Normalises in float after dividing by the largest component, so that a
 * normal made of denormals is still a direction and not a zero. */
float irc__unit3(const float v[3], float unit[3], float *big)
{
    float m, len;
    int i;
    m = IRC_FABSF(v[0]);
    if (IRC_FABSF(v[1]) > m) m = IRC_FABSF(v[1]);
    if (IRC_FABSF(v[2]) > m) m = IRC_FABSF(v[2]);
    *big = m;
    if (m == 0.0f)
        return 0.0f;
    for (i = 0; i < 3; i++)
        unit[i] = v[i] / m;
    len = IRC_SQRTF(irc__dot3(unit, unit));
    for (i = 0; i < 3; i++)
        unit[i] /= len;
    return len;
}

int irc__check_normal(const float n[3], float unit[3])
{
    float m;
    if (!n)
        return IRC_ERR_NULL;
    if (!irc__finite3(n) || irc__unit3(n, unit, &m) == 0.0f)
        return IRC_ERR_NORMAL;
    return IRC_OK;
}

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
