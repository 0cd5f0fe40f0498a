/*
 * image_int.h -- helpers image.c (OpenEXR) and png.c share: error messages,
 * byte order, and files that appear only once complete.
 */
#ifndef DEMO_IMAGE_INT_H
#define DEMO_IMAGE_INT_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#if defined(__GNUC__)
#define PRINTF_LIKE(a, b) __attribute__((format(printf, a, b)))
#else
#define PRINTF_LIKE(a, b)
#endif

/* Formats "PATH: message" into err; returns -1. */
PRINTF_LIKE(4, 5) int img_fail(char *err, size_t errlen, const char *path, const char *fmt, ...);
void img_le16(unsigned char *p, uint32_t v);
void img_be32(unsigned char *p, uint32_t v);

/* A file written as PATH.tmp and renamed over PATH only once complete, so a
 * failed write never leaves a partial PATH.  The first error sticks and
 * later writes are skipped. */
typedef struct sink {
    FILE *f;
    char *tmp;
    int err; /* errno of the first failure, -1 if unknown, 0 if none */
} sink;

int img_sink_open(sink *s, const char *path, char *err, size_t errlen);
void img_sink_put(sink *s, const void *buf, size_t n);
int img_sink_close(sink *s, const char *path, char *err, size_t errlen);

#endif
