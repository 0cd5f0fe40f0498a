/*
 * octa.c -- the normal codec: a unit normal in 32 bits (octahedral
 * mapping, 16 bits a coordinate, worst error ~5e-5 rad), and the tangent
 * frame records keep their gradients in.
 */
#include "cache.h"

uint32_t irc__oct_encode(const double n[3])
{
    double l1 = IRC_FABS(n[0]) + IRC_FABS(n[1]) + IRC_FABS(n[2]);
    double x = n[0] / l1, y = n[1] / l1;
    uint32_t qx, qy;
    if (n[2] < 0.0) {
        double ox = (1.0 - IRC_FABS(y)) * (x >= 0.0 ? 1.0 : -1.0);
        double oy = (1.0 - IRC_FABS(x)) * (y >= 0.0 ? 1.0 : -1.0);
        x = ox;
        y = oy;
    }
    qx = (uint32_t)IRC_FLOOR((x * 0.5 + 0.5) * 65535.0 + 0.5);
    qy = (uint32_t)IRC_FLOOR((y * 0.5 + 0.5) * 65535.0 + 0.5);
    /* All ones is IRC__FREE; its neighbour is as good a normal. */
    return (qx | qy << 16) == IRC__FREE ? IRC__FREE - 1u : qx | qy << 16;
}

/* Decoded in float: lookups decode every accepted record's normal. */
void irc__oct_decode(uint32_t code, float out[3])
{
    float x = (float)(code & 0xffffu) * (2.0f / 65535.0f) - 1.0f;
    float y = (float)(code >> 16) * (2.0f / 65535.0f) - 1.0f;
    float z = 1.0f - IRC_FABSF(x) - IRC_FABSF(y), inv;
    if (z < 0.0f) {
        float ox = (1.0f - IRC_FABSF(y)) * (x >= 0.0f ? 1.0f : -1.0f);
        float oy = (1.0f - IRC_FABSF(x)) * (y >= 0.0f ? 1.0f : -1.0f);
        x = ox;
        y = oy;
    }
    inv = 1.0f / IRC_SQRTF(x * x + y * y + z * z);
    out[0] = x * inv;
    out[1] = y * inv;
    out[2] = z * inv;
}

/* The frame of the decoded normal: what packing and unpacking agree on. */
void irc__oct_frame(uint32_t code, double t1[3], double t2[3])
{
    float nf[3];
    double n[3];
    irc__oct_decode(code, nf);
    n[0] = nf[0];
    n[1] = nf[1];
    n[2] = nf[2];
    irc__frame(n, t1, t2);
}
