/*
 * octa.c -- the normal codec: a unit normal in 32 bits (octahedral
 * mapping, 16 bits a coordinate, worst error ~5e-5 rad), and the tangent
 * frame records keep their gradients in.
 */
#include "../base/kind.h"
#include "octa.h"

uint32_t irc__oct_encode(const float n[3])
{
    float l1 = IRC_FABSF(n[0]) + IRC_FABSF(n[1]) + IRC_FABSF(n[2]);
    float x = n[0] / l1, y = n[1] / l1;
    uint32_t qx, qy;
    if (n[2] < 0.0f) {
        float ox = (1.0f - IRC_FABSF(y)) * (x >= 0.0f ? 1.0f : -1.0f);
        float oy = (1.0f - IRC_FABSF(x)) * (y >= 0.0f ? 1.0f : -1.0f);
        x = ox;
        y = oy;
    }
    qx = (uint32_t)IRC_FLOORF((x * 0.5f + 0.5f) * 65535.0f + 0.5f);
    qy = (uint32_t)IRC_FLOORF((y * 0.5f + 0.5f) * 65535.0f + 0.5f);
    /* All ones is IRC__FREE; its neighbour is as good a normal. */
    return (qx | qy << 16) == IRC__FREE ? IRC__FREE - 1u : qx | qy << 16;
}

/* Decoded in float (octa.h's inline decoding, out of line). */
void irc__oct_decode(uint32_t code, float out[3])
{
    irc__oct_decode_inline(code, out);
}

/* The frame of the decoded normal: what packing and unpacking agree on. */
void irc__oct_frame(uint32_t code, float t1[3], float t2[3])
{
    float nf[3];
    float n[3];
    irc__oct_decode(code, nf);
    n[0] = nf[0];
    n[1] = nf[1];
    n[2] = nf[2];
    irc__frame(n, t1, t2);
}
