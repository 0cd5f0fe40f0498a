/*
 * pixel.c -- irc_pixel_footprint: the width of one pixel on the surface
 * at a camera ray's hit, from what a pinhole camera knows, so that every
 * host bounds records by the same rule (the _px call's footprint).
 */
#include "../util.h"
#include "irrcache.h"

/* Below this |cos| between the ray and the surface the footprint stops
 * growing: at grazing angles 1/sqrt(|cos|) is unbounded, and a record a
 * pixel's stretch wide there would reach far past what the pixel sees. */
#define IRC__GRAZE 0.05f

int irc_pixel_footprint(const float eye[3], const float forward[3], float pixel_angle,
                        const float p[3], const float n[3], float *footprint)
{
    float d[3], t = 0.0f, fl = 0.0f, nl = 0.0f, df = 0.0f, dn = 0.0f, f;
    int i;
    if (!eye || !forward || !p || !n || !footprint)
        return IRC_ERR_NULL;
    if (!irc__finite3(eye) || !irc__finite3(forward) || !irc__finite3(p) ||
        !irc__finite(pixel_angle))
        return IRC_ERR_NONFINITE;
    if (!irc__finite3(n) || (n[0] == 0.0f && n[1] == 0.0f && n[2] == 0.0f))
        return IRC_ERR_NORMAL;
    for (i = 0; i < 3; i++) {
        d[i] = p[i] - eye[i];
        t += d[i] * d[i];
        fl += forward[i] * forward[i];
        nl += n[i] * n[i];
    }
    if (!(pixel_angle > 0.0f) || !(t > 0.0f) || !(fl > 0.0f) || !(t <= FLT_MAX))
        return IRC_ERR_RANGE;
    t = IRC_SQRTF(t);
    for (i = 0; i < 3; i++) {
        df += d[i] * forward[i];
        dn += d[i] * n[i];
    }
    df /= t * IRC_SQRTF(fl);
    dn = IRC_FABSF(dn) / (t * IRC_SQRTF(nl));
    if (!(df > 0.0f))
        return IRC_ERR_RANGE; /* behind the camera */
    if (dn < IRC__GRAZE)
        dn = IRC__GRAZE;
    /* A pixel of width s on the image plane at distance 1 along forward
     * subtends s^2 (d.f)^3 of solid angle in direction d (the plane lies
     * 1/(d.f) away along d, tilted by the same angle); at distance t that
     * covers t^2 s^2 (d.f)^3 / |d.n| of the surface.  The footprint is the
     * square root. */
    f = pixel_angle * t * df * IRC_SQRTF(df / dn);
    if (!irc__finite(f))
        return IRC_ERR_NONFINITE;
    *footprint = f;
    return IRC_OK;
}
