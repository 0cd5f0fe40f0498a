/*
 * bytes.h -- values of 1, 2, 4 or 8 bytes read and written in the
 * snapshot format's order (little-endian) or the machine's, whatever the
 * alignment: the format (snapshot.c), the merge's order (merge.c) and the
 * checks of snapshot records (verify.c) share them.
 */
#ifndef IRC_BYTES_H
#define IRC_BYTES_H

#include "util.h"

static inline void irc__le_put(unsigned char *dst, uint64_t v, unsigned width)
{
    unsigned i;
    for (i = 0; i < width; i++)
        dst[i] = (unsigned char)(v >> (8 * i));
}

/* The little-endian value of `width` bytes at src (the format's order). */
static inline uint64_t irc__le_get(const unsigned char *src, unsigned width)
{
    uint64_t v = 0;
    unsigned i;
    for (i = 0; i < width; i++)
        v |= (uint64_t)src[i] << (8 * i);
    return v;
}

/* A native value of `width` bytes at p, as an integer (and back). */
static inline uint64_t irc__native_get(const unsigned char *p, unsigned width)
{
    uint8_t b;
    uint16_t h;
    uint32_t w;
    uint64_t d;
    switch (width) {
    case 1: IRC_MEMCPY(&b, p, 1); return b;
    case 2: IRC_MEMCPY(&h, p, 2); return h;
    case 4: IRC_MEMCPY(&w, p, 4); return w;
    default: IRC_MEMCPY(&d, p, 8); return d;
    }
}

static inline void irc__native_put(unsigned char *p, uint64_t v, unsigned width)
{
    uint8_t b = (uint8_t)v;
    uint16_t h = (uint16_t)v;
    uint32_t w = (uint32_t)v;
    switch (width) {
    case 1: IRC_MEMCPY(p, &b, 1); break;
    case 2: IRC_MEMCPY(p, &h, 2); break;
    case 4: IRC_MEMCPY(p, &w, 4); break;
    default: IRC_MEMCPY(p, &v, 8); break;
    }
}

#endif
