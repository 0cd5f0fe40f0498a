/*
 * fuzz_input.h -- turns a fuzzer's bytes into values: small integers, and
 * floats drawn either from a table of hostile values (NaN, infinities, -0,
 * denormals, 1e38, 1e-38, ...) or taken raw.  Past the end every read
 * returns zero, so any input is a whole program.
 */
#ifndef IRC_FUZZ_INPUT_H
#define IRC_FUZZ_INPUT_H

#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

typedef struct fuzz_in {
    const uint8_t *p;
    size_t n;
} fuzz_in;

static inline uint8_t fz_u8(fuzz_in *in)
{
    if (!in->n)
        return 0;
    in->n--;
    return *in->p++;
}

static inline uint32_t fz_u32(fuzz_in *in)
{
    uint32_t v = 0;
    int i;
    for (i = 0; i < 4; i++)
        v = v << 8 | fz_u8(in);
    return v;
}

static inline float fz_float(fuzz_in *in)
{
    static const float table[] = {0.0f, -0.0f, 1.0f, -1.0f, 0.5f, 2.0f, 1e-6f, 1e6f,
                                  1e38f, -1e38f, 1e-38f, 1e-45f, 3.4028235e38f,
                                  1.17549435e-38f, 0.1f, 0.25f};
    uint8_t k = fz_u8(in);
    if (k < 16)
        return table[k];
    if (k == 16)
        return NAN;
    if (k == 17)
        return INFINITY;
    if (k == 18)
        return -INFINITY;
    if (k < 128)
        return (float)(k - 72) / 16.0f; /* small ordinary values */
    {
        uint32_t u = fz_u32(in);
        float f;
        memcpy(&f, &u, sizeof f);
        return f;
    }
}

#endif
