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
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* An invariant a harness checks; a violation aborts (which libFuzzer and
 * the replay driver report), naming the file and line. */
#define check(ok)                                                              \
    do {                                                                       \
        if (!(ok)) {                                                           \
            fprintf(stderr, "%s:%d: invariant broken: %s\n", __FILE__, __LINE__, #ok); \
            abort();                                                           \
        }                                                                      \
    } while (0)

/* A cache's block with FZ_GUARD canary bytes after it, and room for a copy
 * to compare with after a failed call. */
#define FZ_GUARD 64
typedef struct fz_block {
    unsigned char *block, *copy;
    size_t bytes;
} fz_block;

/* 0, or -1 when memory is short (the input is skipped). */
static inline int fz_block_new(fz_block *b, size_t bytes)
{
    b->bytes = bytes;
    b->block = (unsigned char *)malloc(bytes + FZ_GUARD);
    b->copy = (unsigned char *)malloc(bytes);
    if (!b->block || !b->copy) {
        free(b->block);
        free(b->copy);
        return -1;
    }
    memset(b->block + bytes, 0xA5, FZ_GUARD);
    return 0;
}

/* Checks the canary and frees both. */
static inline void fz_block_free(fz_block *b)
{
    size_t i;
    for (i = 0; i < FZ_GUARD; i++)
        check(b->block[b->bytes + i] == 0xA5);
    free(b->copy);
    free(b->block);
}

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
