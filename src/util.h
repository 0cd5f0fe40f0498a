/*
 * util.h -- the one portability header of the library.  Every libc and libm
 * call, and assert, passes through a macro here so that a port can replace
 * it.  Define IRC_NO_ASSERT to compile the internal checks out.
 */
#ifndef IRC_UTIL_H
#define IRC_UTIL_H

#include <float.h>
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#ifndef IRC_MEMCPY
#define IRC_MEMCPY(d, s, n) memcpy((d), (s), (n))
#endif
#ifndef IRC_MEMSET
#define IRC_MEMSET(d, v, n) memset((d), (v), (n))
#endif
#ifndef IRC_SQRT
#define IRC_SQRT(x) sqrt(x)
#define IRC_SQRTF(x) sqrtf(x)
#define IRC_SIN(x) sin(x)
#define IRC_COS(x) cos(x)
#define IRC_ASIN(x) asin(x)
#define IRC_ACOS(x) acos(x)
#define IRC_COSF(x) cosf(x)
#define IRC_SINF(x) sinf(x)
#endif

#ifdef IRC_NO_ASSERT
#define IRC_ASSERT(x) ((void)0)
#else
#include <assert.h>
#define IRC_ASSERT(x) assert(x)
#endif

#define IRC_PI 3.14159265358979323846

/* Finite test that does not depend on the compiler honouring isfinite under
 * aggressive float options: exponent bits all ones means Inf or NaN. */
static inline int irc__finite(float x)
{
    uint32_t u;
    IRC_MEMCPY(&u, &x, sizeof u);
    return (u & 0x7f800000u) != 0x7f800000u;
}

static inline int irc__finite3(const float v[3])
{
    return irc__finite(v[0]) && irc__finite(v[1]) && irc__finite(v[2]);
}

static inline double irc__dot3d(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static inline void irc__cross3d(const double a[3], const double b[3], double out[3])
{
    out[0] = a[1] * b[2] - a[2] * b[1];
    out[1] = a[2] * b[0] - a[0] * b[2];
    out[2] = a[0] * b[1] - a[1] * b[0];
}

#endif
