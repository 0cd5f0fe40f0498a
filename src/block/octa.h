/*
 * octa.h -- the normal codec (octa.c).
 */
#ifndef IRC_OCTA_H
#define IRC_OCTA_H

#include "../util.h"
#include "irrcache.h"
/* Decoded in float: inline where lookups decode every accepted record's
 * normal. */
static inline void irc__oct_decode_inline(uint32_t code, float out[3])
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

/* octa.c: the normal codec */
uint32_t irc__oct_encode(const float n[3]);
void irc__oct_decode(uint32_t code, float n[3]);
void irc__oct_frame(uint32_t code, float t1[3], float t2[3]);

#endif
