/*
 * png.c -- the demo's PNG previews (see image.h): 8-bit RGB whose zlib
 * stream is made of stored blocks, so no compressor is needed.
 */
#include "image.h"
#include "image_int.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* ---------------------------------------------------------------- PNG */

typedef struct png {
    sink s;
    uint32_t crc;         /* of the chunk being written */
    uint32_t a, b;        /* Adler-32 of the zlib data */
    uint64_t left;        /* raw zlib bytes still to come */
    uint32_t inblk;       /* of them, left in the current stored block */
    uint32_t table[256];
} png;

static void png_out(png *p, const unsigned char *buf, size_t n)
{
    size_t i;
    for (i = 0; i < n; i++)
        p->crc = p->table[(p->crc ^ buf[i]) & 0xff] ^ (p->crc >> 8);
    img_sink_put(&p->s, buf, n);
}

static void png_begin(png *p, const char *type, uint32_t len)
{
    unsigned char b[4];
    img_be32(b, len);
    img_sink_put(&p->s, b, 4);
    p->crc = 0xffffffffu;
    png_out(p, (const unsigned char *)type, 4);
}

static void png_end(png *p)
{
    unsigned char b[4];
    img_be32(b, p->crc ^ 0xffffffffu);
    img_sink_put(&p->s, b, 4);
}

/* Raw bytes into stored deflate blocks of at most 65535 bytes; the block
 * lengths are known in advance since the total is. */
static void png_raw(png *p, const unsigned char *buf, size_t n)
{
    size_t i, k;
    while (n > 0) {
        if (p->inblk == 0) {
            uint32_t len = p->left < 65535 ? (uint32_t)p->left : 65535;
            unsigned char hd[5];
            hd[0] = len == p->left; /* BFINAL; BTYPE 00 = stored */
            img_le16(hd + 1, len);
            img_le16(hd + 3, ~len & 0xffff);
            png_out(p, hd, 5);
            p->inblk = len;
        }
        k = n < p->inblk ? n : p->inblk;
        for (i = 0; i < k; i++) {
            p->a = (p->a + buf[i]) % 65521;
            p->b = (p->b + p->a) % 65521;
        }
        png_out(p, buf, k);
        buf += k;
        n -= k;
        p->inblk -= (uint32_t)k;
        p->left -= k;
    }
}

static unsigned char tone(float x, float exposure)
{
    double v = 0.0;
    if (x > 0)
        v = 1.0 - exp(-(double)exposure * x);
    if (!(v > 0)) /* also NaN from 0 * inf */
        v = 0.0;
    if (v > 1)
        v = 1.0;
    v = v < 0.0031308 ? 12.92 * v : 1.055 * pow(v, 1 / 2.4) - 0.055;
    return (unsigned char)floor(255.0 * v + 0.5);
}

int png_write(const char *path, int w, int h, const float *rgb, float exposure,
              char *err, size_t errlen)
{
    static const unsigned char sig[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    unsigned char ihdr[13], *row;
    uint64_t raw, nblk;
    uint32_t i, k;
    png p;
    int x, y;

    if (!rgb || w <= 0 || h <= 0)
        return img_fail(err, errlen, path, "invalid image size %dx%d", w, h);
    raw = (uint64_t)h * (1 + 3 * (uint64_t)w);
    nblk = (raw + 65534) / 65535;
    if (2 + raw + 5 * nblk + 4 > 0x7fffffffu) /* PNG chunk length limit */
        return img_fail(err, errlen, path, "image too large for PNG (%dx%d)", w, h);
    row = malloc(1 + 3 * (size_t)w);
    if (!row)
        return img_fail(err, errlen, path, "out of memory");
    if (img_sink_open(&p.s, path, err, errlen) < 0) {
        free(row);
        return -1;
    }
    for (i = 0; i < 256; i++) {
        uint32_t c = i;
        for (k = 0; k < 8; k++)
            c = c & 1 ? 0xedb88320u ^ (c >> 1) : c >> 1;
        p.table[i] = c;
    }
    img_sink_put(&p.s, sig, 8);
    img_be32(ihdr, (uint32_t)w);
    img_be32(ihdr + 4, (uint32_t)h);
    memcpy(ihdr + 8, "\x08\x02\x00\x00\x00", 5); /* 8 bits, RGB, deflate, filter 0, no interlace */
    png_begin(&p, "IHDR", 13);
    png_out(&p, ihdr, 13);
    png_end(&p);

    png_begin(&p, "IDAT", (uint32_t)(2 + raw + 5 * nblk + 4));
    png_out(&p, (const unsigned char *)"\x78\x01", 2); /* deflate, 32K window, no dict */
    p.a = 1;
    p.b = 0;
    p.left = raw;
    p.inblk = 0;
    for (y = 0; y < h && !p.s.err; y++) {
        row[0] = 0; /* filter: none */
        for (x = 0; x < 3 * w; x++)
            row[1 + x] = tone(rgb[(size_t)y * w * 3 + x], exposure);
        png_raw(&p, row, 1 + 3 * (size_t)w);
    }
    img_be32(ihdr, p.b << 16 | p.a); /* Adler-32 ends the zlib stream */
    png_out(&p, ihdr, 4);
    png_end(&p);
    png_begin(&p, "IEND", 0);
    png_end(&p);
    free(row);
    return img_sink_close(&p.s, path, err, errlen);
}
