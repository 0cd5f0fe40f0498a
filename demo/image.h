/*
 * image.h -- the demo's image files: OpenEXR (scanline, uncompressed, RGB
 * float or half) written and read by its own code, and PNG previews
 * (8-bit RGB, zlib stored blocks, no zlib needed).
 *
 * Pixels are float RGB, row-major, first row at the top: rgb[(y*w + x)*3 + c].
 * Every function returns 0, or -1 with a message in err ("PATH: what").
 */
#ifndef DEMO_IMAGE_H
#define DEMO_IMAGE_H

#include <stddef.h>

/* half = 0: 32-bit float channels; 1: 16-bit half (rounded to nearest even). */
int exr_write(const char *path, int w, int h, const float *rgb, int half,
              char *err, size_t errlen);

/* Reads an EXR this writer can produce (scanline, NO_COMPRESSION, channels
 * B, G, R of one type, float or half; any other file is refused with a
 * message).  *rgb is malloc'd; the caller frees it. */
int exr_read(const char *path, int *w, int *h, float **rgb, char *err, size_t errlen);

/* Tone-mapped preview: v = 1 - exp(-exposure * x) per channel, then the
 * sRGB curve, 8 bits. */
int png_write(const char *path, int w, int h, const float *rgb, float exposure,
              char *err, size_t errlen);

/* Float <-> half (IEEE 754 binary16), round to nearest even; exposed for
 * tests. */
unsigned short float_to_half(float f);
float half_to_float(unsigned short h);

#endif
