/*
 * pixel.c -- irc_pixel_footprint: the width of one pixel on the surface
 * at a camera ray's hit, from what a pinhole camera knows, so that every
 * host bounds records by the same rule (the _px call's footprint).
 */
#include "../block/check.h"
#include "../util.h"
#include "irrcache.h"

/* Below this |cos| between the ray and the surface the footprint stops
 * growing: at grazing angles 1/sqrt(|cos|) is unbounded, and a record a
 * pixel's stretch wide there would reach far past what the pixel sees. */
#define IRC__GRAZE 0.05f

int irc_pixel_footprint(const float eye[3], const float forward[3], float pixel_angle,
                        const float p[3], const float n[3], float *footprint)
{
    float half[3], d[3], f[3], un[3], t, m, fm, nm, df, dn, out;
    int i;
    if (!eye || !forward || !p || !n || !footprint)
        return IRC_ERR_NULL;
    if (!irc__finite3(eye) || !irc__finite3(forward) || !irc__finite3(p) ||
        !irc__finite(pixel_angle))
        return IRC_ERR_NONFINITE;
    if (!irc__finite3(n) || (n[0] == 0.0f && n[1] == 0.0f && n[2] == 0.0f))
        return IRC_ERR_NORMAL;
    /* Half the offset: p - eye of two finite floats can overflow, half of
     * it cannot. */
    for (i = 0; i < 3; i++)
        half[i] = 0.5f * p[i] - 0.5f * eye[i];
    t = irc__unit3(half, d, &m);
    if (!(pixel_angle > 0.0f) || !(t > 0.0f) || !(irc__unit3(forward, f, &fm) > 0.0f))
        return IRC_ERR_RANGE;
    (void)irc__unit3(n, un, &nm);
    df = d[0] * f[0] + d[1] * f[1] + d[2] * f[2];
    dn = IRC_FABSF(d[0] * un[0] + d[1] * un[1] + d[2] * un[2]);
    if (!(df > 0.0f))
        return IRC_ERR_RANGE; /* behind the camera */
    if (dn < IRC__GRAZE)
        dn = IRC__GRAZE;
    /* A pixel of width s on the image plane at distance 1 along forward
     * subtends s^2 (d.f)^3 of solid angle in direction d (the plane lies
     * 1/(d.f) away along d, tilted by the same angle); at distance t that
     * covers t^2 s^2 (d.f)^3 / |d.n| of the surface.  The footprint is the
     * square root.  |p - eye| = 2 m t, multiplied in last: the product
     * passes FLT_MAX only when the footprint does. */
    out = 2.0f * (pixel_angle * df * IRC_SQRTF(df / dn) * m) * t;
    if (!irc__finite(out))
        return IRC_ERR_NONFINITE;
    *footprint = out;
    return IRC_OK;
}
