/*
 * util.h -- the one portability header of the library.  Every libc and libm
 * call, and assert, passes through a macro here, and each macro can be
 * replaced on its own: define it (with -D, or in a header of yours named by
 * IRC_USER_CONFIG, e.g. -DIRC_USER_CONFIG='"my_irc.h"', included first)
 * and the default below steps aside for that one macro only.
 * IRC_NO_ASSERT compiles the internal checks out.
 *
 * Build-time switches, defined the same way, leave what a firmware does
 * not use out of the build (irrcache.h, IRC_ERR_UNSUPPORTED); the files
 * named then compile empty, or make LEAVE_OUT=... does not compile them,
 * and absent.c answers their public calls:
 *   IRC_NO_SH          SH records (kind_sh.c, sh.c, shgrad.c)
 *   IRC_NO_VISIBILITY  visibility gradients (visibility.c, occlusion.c)
 *   IRC_NO_HESSIAN     the Hessian and its ellipses (hessian.c)
 *   IRC_NO_SIGHT       confirming rays, cfg.check_visibility (confirm.c;
 *                      the default is then off)
 *   IRC_NO_SUPERSAMPLE cfg.irr.supersamples (sampler.c's part)
 *   IRC_NO_GUARD       the leak guard, cfg.irr.leak_guard (irradiance.c's
 *                      and weight.c's parts)
 */
#ifndef IRC_UTIL_H
#define IRC_UTIL_H

#ifdef IRC_USER_CONFIG
#include IRC_USER_CONFIG
#endif

/* The library defines the experimental calls (irrcache.h, "Experimental
 * calls"), so it sees their declarations: every header of src/ that
 * includes irrcache.h includes this one first. */
#ifndef IRC_EXPERIMENTAL
#define IRC_EXPERIMENTAL
#endif

#include <float.h>
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

/* A helper a lookup runs per record, shared with a general path: inlined
 * where the compiler optimises for speed, called where it optimises for
 * size (-Os, firmware), so it is written once and built once there. */
#if (defined(__GNUC__) || defined(__clang__)) && !defined(__OPTIMIZE_SIZE__)
#define IRC__PER_RECORD static inline __attribute__((always_inline))
#else
#define IRC__PER_RECORD static
#endif

#ifndef IRC_MEMCPY
#define IRC_MEMCPY(d, s, n) memcpy((d), (s), (n))
#endif
#ifndef IRC_MEMMOVE
#define IRC_MEMMOVE(d, s, n) memmove((d), (s), (n))
#endif
#ifndef IRC_MEMSET
#define IRC_MEMSET(d, v, n) memset((d), (v), (n))
#endif
#ifndef IRC_SQRTF
#define IRC_SQRTF(x) sqrtf(x)
#endif
#ifndef IRC_SINF
#define IRC_SINF(x) sinf(x)
#endif
#ifndef IRC_COSF
#define IRC_COSF(x) cosf(x)
#endif
#ifndef IRC_ASINF
#define IRC_ASINF(x) asinf(x)
#endif
#ifndef IRC_ACOSF
#define IRC_ACOSF(x) acosf(x)
#endif
#ifndef IRC_ATAN2F
#define IRC_ATAN2F(y, x) atan2f((y), (x))
#endif
#ifndef IRC_FABSF
#define IRC_FABSF(x) fabsf(x)
#endif
#ifndef IRC_FLOORF
#define IRC_FLOORF(x) floorf(x)
#endif
#ifndef IRC_FREXPF
#define IRC_FREXPF(x, e) frexpf((x), (e))
#endif
#ifndef IRC_LDEXPF
#define IRC_LDEXPF(x, e) ldexpf((x), (e))
#endif
#ifndef IRC_POWF
#define IRC_POWF(x, y) powf((x), (y))
#endif
/* Double, for the index's exact cube arithmetic only (index.c). */
#ifndef IRC_FLOOR
#define IRC_FLOOR(x) floor(x)
#endif
#ifndef IRC_FABS
#define IRC_FABS(x) fabs(x)
#endif
#ifndef IRC_FREXP
#define IRC_FREXP(x, e) frexp((x), (e))
#endif
#ifndef IRC_LDEXP
#define IRC_LDEXP(x, e) ldexp((x), (e))
#endif

#ifndef IRC_ASSERT
#ifdef IRC_NO_ASSERT
#define IRC_ASSERT(x) ((void)0)
#else
#include <assert.h>
#define IRC_ASSERT(x) assert(x)
#endif
#endif

#define IRC_PI 3.14159265358979323846f

/* Keeps a function's locals out of its caller's frame, where they would
 * sit under every other call the caller makes (the stack bounds of make
 * size). */
#if defined(__GNUC__)
#define IRC__NOINLINE __attribute__((noinline))
#else
#define IRC__NOINLINE
#endif

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

static inline float irc__dot3(const float a[3], const float b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static inline void irc__cross3(const float a[3], const float b[3], float out[3])
{
    out[0] = a[1] * b[2] - a[2] * b[1];
    out[1] = a[2] * b[0] - a[0] * b[2];
    out[2] = a[0] * b[1] - a[1] * b[0];
}

/* Branchless orthonormal basis (Duff et al. 2017), right-handed:
 * t1 x t2 = n.  Continuous everywhere but across n.z = 0's sign flip. */
static inline void irc__frame(const float n[3], float t1[3], float t2[3])
{
    float s = n[2] >= 0.0f ? 1.0f : -1.0f;
    float a = -1.0f / (s + n[2]);
    float b = n[0] * n[1] * a;
    t1[0] = 1.0f + s * n[0] * n[0] * a;
    t1[1] = s * b;
    t1[2] = -s * n[0];
    t2[0] = b;
    t2[1] = s + n[1] * n[1] * a;
    t2[2] = -n[1];
}

#endif
