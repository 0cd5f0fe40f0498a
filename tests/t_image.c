/*
 * t_image.c -- the demo's image code without any image library: half
 * conversion, EXR write/read round trips and refusals, and PNG files
 * re-parsed here by independent code (bitwise CRC, own Adler-32, stored
 * deflate blocks read back).  Uses the shared harness (tests/harness.c):
 *   t_image [TEST...]   the tests named (by prefix), or all; ends with
 *                       "N passed, N failed".
 */
#ifndef _POSIX_C_SOURCE
#define _POSIX_C_SOURCE 200809L
#endif
#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "image.h"
#include "test.h"

#define TESTS(X)                                                                          \
    X(test_half_all) X(test_half_known) X(test_exr_float) X(test_exr_half)               \
    X(test_exr_refuse) X(test_write_fail) X(test_png_small) X(test_png_blocks)
TESTS(TEST_DECL)

/* A sweep over many values stops once a test has this many failed checks:
 * the test has failed already, and the log stays short. */
enum { MAX_FAILS = 10 };

static char dir[64];

static const char *tmp(const char *name)
{
    static char buf[8][128];
    static int i;
    char *p = buf[i++ & 7];
    snprintf(p, 128, "%s/%s", dir, name);
    return p;
}

static uint32_t bits(float f)
{
    uint32_t u;
    memcpy(&u, &f, 4);
    return u;
}

static float from_bits(uint32_t u)
{
    float f;
    memcpy(&f, &u, 4);
    return f;
}

static int half_is_nan(unsigned short h) { return (h & 0x7c00) == 0x7c00 && (h & 0x3ff); }

static unsigned char *slurp(const char *path, size_t *n)
{
    FILE *f = fopen(path, "rb");
    unsigned char *b = NULL;
    long len;
    *n = 0;
    if (!f)
        return NULL;
    if (fseek(f, 0, SEEK_END) == 0 && (len = ftell(f)) >= 0 && fseek(f, 0, SEEK_SET) == 0) {
        b = malloc((size_t)len + 1);
        if (b && fread(b, 1, (size_t)len, f) == (size_t)len)
            *n = (size_t)len;
    }
    fclose(f);
    return b;
}

static int spit(const char *path, const unsigned char *b, size_t n)
{
    FILE *f = fopen(path, "wb");
    int ok = f && fwrite(b, 1, n, f) == n;
    if (f && fclose(f) != 0)
        ok = 0;
    return ok ? 0 : -1;
}

static int exists(const char *path) { return access(path, F_OK) == 0; }

/* ---------------------------------------------------------------- half */

TEST(test_half_all)
{
    unsigned h;
    int f0 = irc_t_fails;
    for (h = 0; h < 65536 && irc_t_fails - f0 < MAX_FAILS; h++) {
        float f = half_to_float((unsigned short)h);
        unsigned short back = float_to_half(f);
        if (half_is_nan((unsigned short)h)) {
            CHECK(isnan(f), "half 0x%04x gives %a, not a NaN", h, (double)f);
            CHECK(half_is_nan(back), "half NaN 0x%04x comes back as 0x%04x", h, back);
        } else {
            CHECK(back == h, "half 0x%04x -> %a -> 0x%04x", h, (double)f, back);
        }
        /* finite positive halves are strictly increasing as floats */
        if (h < 0x7c00)
            CHECK(half_to_float((unsigned short)h) < half_to_float((unsigned short)(h + 1)),
                  "half 0x%04x (%a) not below the next (%a)", h, (double)f,
                  (double)half_to_float((unsigned short)(h + 1)));
    }
    CHECK(half_to_float(0x3c00) == 1.0f, "0x3c00 -> %a", (double)half_to_float(0x3c00));
    CHECK(half_to_float(0x0001) == 0x1p-24f, "0x0001 -> %a", (double)half_to_float(0x0001));
    CHECK(half_to_float(0x03ff) == 1023 * 0x1p-24f, "0x03ff -> %a",
          (double)half_to_float(0x03ff));
    CHECK(half_to_float(0x0400) == 0x1p-14f, "0x0400 -> %a", (double)half_to_float(0x0400));
    CHECK(half_to_float(0x7bff) == 65504.0f, "0x7bff -> %a", (double)half_to_float(0x7bff));
    CHECK(half_to_float(0xfc00) == -INFINITY, "0xfc00 -> %a", (double)half_to_float(0xfc00));
    CHECK(bits(half_to_float(0x8000)) == 0x80000000u, "0x8000 -> bits 0x%08lx",
          (unsigned long)bits(half_to_float(0x8000)));
    CHECK(half_to_float(0xc000) == -2.0f, "0xc000 -> %a", (double)half_to_float(0xc000));
}

TEST(test_half_known)
{
    static const struct {
        float f;
        unsigned short h;
    } k[] = {
        {0.0f, 0x0000}, {-0.0f, 0x8000}, {1.0f, 0x3c00}, {-2.0f, 0xc000}, {0.5f, 0x3800},
        {0.1f, 0x2e66}, {1.0f / 3, 0x3555}, {65504.0f, 0x7bff}, {65519.0f, 0x7bff},
        {65520.0f, 0x7c00} /* tie: 65504 is odd, inf even */, {-65520.0f, 0xfc00},
        {1e30f, 0x7c00}, {-1e30f, 0xfc00}, {1e-30f, 0x0000}, {-1e-30f, 0x8000},
        {1e-40f, 0x0000} /* float subnormal */, {0x1p-24f, 0x0001}, {-0x1p-24f, 0x8001},
        {0x1p-25f, 0x0000} /* tie to even 0 */, {0x1.000002p-25f, 0x0001},
        {0x1.fffffep-26f, 0x0000}, {3 * 0x1p-25f, 0x0002} /* 1.5 -> 2 */,
        {5 * 0x1p-25f, 0x0002} /* 2.5 -> 2 */, {7 * 0x1p-25f, 0x0004},
        {1023 * 0x1p-24f, 0x03ff}, {0x1p-14f, 0x0400},
        {0x1p-14f - 0x1p-25f, 0x0400} /* 1023.5 units: ties to the even 0x400 */,
        {0x1p-14f - 3 * 0x1p-25f, 0x03fe} /* 1022.5 units: to even */,
        {1.0009765625f, 0x3c01}, {1.00048828125f, 0x3c00} /* 1 + 2^-11: tie */,
        {1.00146484375f, 0x3c02} /* 1 + 3*2^-11: tie */, {1.00048828125f + 0x1p-23f, 0x3c01},
        {2049.0f, 0x6800}, {2051.0f, 0x6802}, {2050.0f, 0x6801}, {0x1p15f, 0x7800},
        {0x1p16f, 0x7c00}, {INFINITY, 0x7c00}, {-INFINITY, 0xfc00},
    };
    size_t i;
    for (i = 0; i < sizeof k / sizeof k[0]; i++) {
        unsigned short h = float_to_half(k[i].f);
        CHECK(h == k[i].h, "float_to_half(%a) = 0x%04x, want 0x%04x", (double)k[i].f, h, k[i].h);
    }
    CHECK(half_is_nan(float_to_half(NAN)), "NaN -> 0x%04x", float_to_half(NAN));
    CHECK(half_is_nan(float_to_half(from_bits(0x7f800001u))), /* payload only in low bits */
          "NaN 0x7f800001 -> 0x%04x", float_to_half(from_bits(0x7f800001u)));
    CHECK(half_is_nan(float_to_half(from_bits(0xffc00000u))), "NaN 0xffc00000 -> 0x%04x",
          float_to_half(from_bits(0xffc00000u)));
    CHECK(float_to_half(from_bits(0xffc00000u)) & 0x8000, "NaN 0xffc00000 -> 0x%04x: no sign",
          float_to_half(from_bits(0xffc00000u)));
}

/* ---------------------------------------------------------------- EXR */

enum { EW = 37, EH = 23 };

static float *test_image(int w, int h)
{
    static const float special[] = {0.0f, -0.0f, 1e-30f, 1e30f, 65504.0f, 1e-40f, 0x1p-20f,
                                    -0x1p-24f, 65520.0f, -3.5f, 0.1f, 1e-45f};
    float *rgb = malloc((size_t)w * h * 3 * sizeof *rgb);
    int i;
    for (i = 0; i < w * h * 3; i++)
        rgb[i] = (float)(i % 3 + 1) * (float)(i / 3 % w) / (float)w + (float)(i / 3 / w) * 0.37f;
    for (i = 0; i < (int)(sizeof special / sizeof special[0]); i++) {
        rgb[i * 7 + 1] = special[i];
        rgb[w * h * 3 - 1 - i * 5] = special[i];
    }
    rgb[100] = INFINITY;
    rgb[101] = -INFINITY;
    rgb[102] = NAN;
    return rgb;
}

static void roundtrip(int half)
{
    const char *p = tmp(half ? "half.exr" : "float.exr");
    float *in = test_image(EW, EH), *out = NULL;
    char err[256] = "";
    int w = 0, h = 0, i, f0 = irc_t_fails;
    size_t n = 0;
    unsigned char *file;
    CHECK(exr_write(p, EW, EH, in, half, err, sizeof err) == 0, "exr_write: %s", err);
    CHECK(!exists(tmp(half ? "half.exr.tmp" : "float.exr.tmp")), "temporary file left");
    file = slurp(p, &n);
    CHECK(n == 313 + EH * 8 + (size_t)EH * (8 + EW * 3 * (half ? 2 : 4)), "%lu bytes",
          (unsigned long)n);
    CHECK(file && memcmp(file, "\x76\x2f\x31\x01\x02\x00\x00\x00", 8) == 0,
          "not an EXR version 2 header");
    free(file);
    CHECK(exr_read(p, &w, &h, &out, err, sizeof err) == 0, "exr_read: %s", err);
    if (!out) {
        free(in);
        return;
    }
    CHECK(w == EW && h == EH, "read %d x %d", w, h);
    for (i = 0; i < EW * EH * 3 && irc_t_fails - f0 < MAX_FAILS; i++) {
        uint32_t want = half ? bits(half_to_float(float_to_half(in[i]))) : bits(in[i]);
        CHECK(bits(out[i]) == want, "value %d: bits 0x%08lx, want 0x%08lx", i,
              (unsigned long)bits(out[i]), (unsigned long)want);
    }
    free(in);
    free(out);
}

TEST(test_exr_float) { roundtrip(0); }
TEST(test_exr_half) { roundtrip(1); }

/* Writes a corrupt copy of the good file and expects exr_read to refuse it
 * with a message containing `want`. */
static void refuse(const unsigned char *good, size_t n, size_t at, int byte, const char *want)
{
    const char *p = tmp("bad.exr");
    unsigned char *b = malloc(n);
    char err[256] = "";
    float *rgb = (float *)1;
    int w = -1, h = -1;
    memcpy(b, good, n);
    if (byte >= 0)
        b[at] = (unsigned char)byte;
    CHECK(spit(p, b, byte >= 0 ? n : at) == 0, "cannot write %s", p);
    CHECK(exr_read(p, &w, &h, &rgb, err, sizeof err) == -1, "read (want \"%s\")", want);
    CHECK(rgb == NULL, "pixels not NULL (want \"%s\")", want);
    CHECK(strstr(err, want) != NULL, "got \"%s\", want \"%s\"", err, want);
    CHECK(strncmp(err, p, strlen(p)) == 0, "\"%s\" does not start with the path", err);
    free(b);
    remove(p);
}

static size_t find(const unsigned char *b, size_t n, const char *s, size_t len)
{
    size_t i;
    for (i = 0; i + len <= n; i++)
        if (memcmp(b + i, s, len) == 0)
            return i;
    return 0;
}

TEST(test_exr_refuse)
{
    char p[128];
    float *in = test_image(EW, EH), *out = NULL;
    char err[256];
    size_t n, c, d, cut[] = {0, 3, 7, 8, 40, 312, 313, 313 + 8 * EH - 1, 313 + 8 * EH + 5};
    unsigned char *good;
    int w, h, i;
    snprintf(p, sizeof p, "%s", tmp("good.exr")); /* tmp() names are reused */
    CHECK(exr_write(p, EW, EH, in, 0, err, sizeof err) == 0, "exr_write: %s", err);
    good = slurp(p, &n);
    CHECK(good && n > 1000, "%lu bytes", (unsigned long)n);
    if (!good)
        return;
    for (i = 0; i < (int)(sizeof cut / sizeof cut[0]); i++)
        refuse(good, n, cut[i], -1, "truncated");
    refuse(good, n, n - 1, -1, "truncated");
    c = find(good, n, "compression\0compression\0", 24);
    CHECK(c > 0, "no compression attribute");
    refuse(good, n, c + 24 + 4, 3, "unsupported compression 3");
    refuse(good, n, 0, 0x77, "not an OpenEXR file");
    refuse(good, n, 5, 0x02, "unsupported OpenEXR flags"); /* tiled bit */
    d = find(good, n, "dataWindow\0box2i\0", 17) + 17 + 4;
    refuse(good, n, d + 11, 0x7f, "too large"); /* xmax = 0x7f000024 */
    refuse(good, n, d + 11, 0x80, "bad data window"); /* xmax < xmin */
    refuse(good, n, find(good, n, "G\0", 2) + 2, 0, "unsupported pixel type 0");
    refuse(good, n, find(good, n, "R\0", 2), 'A', "unsupported channels");
    refuse(good, n, 313 + 8 * EH, 9, "bad chunk for line 0");
    refuse(good, n, 313 + 7, 0x40, "bad offset for line 0");
    /* the untouched file still reads */
    CHECK(exr_read(p, &w, &h, &out, err, sizeof err) == 0, "exr_read: %s", err);
    free(out);
    CHECK(exr_read(tmp("missing.exr"), &w, &h, &out, err, sizeof err) == -1, "read a missing file");
    CHECK(strstr(err, strerror(ENOENT)) != NULL, "\"%s\"", err);
    free(good);
    free(in);
}

TEST(test_write_fail)
{
    const char *p = tmp("no/such/dir.exr");
    float px[3] = {1, 2, 3};
    char err[256] = "";
    CHECK(exr_write(p, 1, 1, px, 0, err, sizeof err) == -1, "wrote into a missing directory");
    CHECK(strncmp(err, p, strlen(p)) == 0 && strstr(err, strerror(ENOENT)), "\"%s\"", err);
    CHECK(png_write(tmp("no/such/dir.png"), 1, 1, px, 1, err, sizeof err) == -1,
          "PNG written into a missing directory");
    CHECK(exr_write(tmp("zero.exr"), 0, 1, px, 0, err, sizeof err) == -1, "wrote width 0");
    CHECK(!exists(tmp("zero.exr")) && !exists(tmp("zero.exr.tmp")), "width 0 left a file");
    /* a file in the way of the temporary name: the target is not touched */
    CHECK(spit(tmp("busy.exr"), (const unsigned char *)"old", 3) == 0, "cannot write busy.exr");
    CHECK(mkdir(tmp("busy.exr.tmp"), 0700) == 0, "cannot make busy.exr.tmp");
    CHECK(exr_write(tmp("busy.exr"), 1, 1, px, 0, err, sizeof err) == -1,
          "wrote with a directory in the way of the temporary file");
    CHECK(exists(tmp("busy.exr")) && !exists(tmp("busy.exr.tmp/x")),
          "busy.exr gone or a file made in busy.exr.tmp");
    rmdir(tmp("busy.exr.tmp"));
    remove(tmp("busy.exr"));
}

/* ---------------------------------------------------------------- PNG */

/* Bitwise, unlike the table in image.c. */
static uint32_t crc32_bitwise(const unsigned char *p, size_t n)
{
    uint32_t c = 0xffffffffu;
    size_t i;
    int k;
    for (i = 0; i < n; i++) {
        c ^= p[i];
        for (k = 0; k < 8; k++)
            c = (c >> 1) ^ (0xedb88320u & (0u - (c & 1)));
    }
    return ~c;
}

static uint32_t adler32_slow(const unsigned char *p, size_t n)
{
    uint32_t a = 1, b = 0;
    size_t i;
    for (i = 0; i < n; i++) {
        a = (a + p[i]) % 65521;
        b = (b + a) % 65521;
    }
    return b << 16 | a;
}

static uint32_t be(const unsigned char *p)
{
    return (uint32_t)p[0] << 24 | (uint32_t)p[1] << 16 | (uint32_t)p[2] << 8 | p[3];
}

typedef struct decoded {
    uint32_t w, h;
    int idats, blocks;
    unsigned char *pix; /* w*h*3 */
} decoded;

/* Inflates stored blocks only; returns an error or NULL. */
static const char *inflate_stored(const unsigned char *z, size_t n, unsigned char *out,
                                  size_t cap, size_t *len, int *blocks)
{
    size_t p = 2;
    int final = 0;
    if (n < 6 || z[0] != 0x78 || (z[0] * 256 + z[1]) % 31 != 0 || (z[1] & 0x20))
        return "bad zlib header";
    *len = 0;
    while (!final) {
        uint32_t l, nl;
        if (p + 5 > n)
            return "zlib stream truncated";
        if (z[p] & ~1u)
            return "not a stored block";
        final = z[p] & 1;
        l = z[p + 1] | (uint32_t)z[p + 2] << 8;
        nl = z[p + 3] | (uint32_t)z[p + 4] << 8;
        if ((l ^ 0xffff) != nl)
            return "LEN/NLEN mismatch";
        if (p + 5 + l > n || *len + l > cap)
            return "stored block too long";
        memcpy(out + *len, z + p + 5, l);
        *len += l;
        p += 5 + l;
        (*blocks)++;
    }
    if (p + 4 != n)
        return "bad zlib trailer length";
    if (be(z + p) != adler32_slow(out, *len))
        return "adler32 mismatch";
    return NULL;
}

static const char *parse_png(const char *path, decoded *d)
{
    size_t n, p = 8, zn = 0, raw_len = 0, row, y;
    unsigned char *f = slurp(path, &n), *z, *raw;
    const char *e = NULL;
    memset(d, 0, sizeof *d);
    if (!f || n < 8 || memcmp(f, "\x89PNG\r\n\x1a\n", 8) != 0)
        return free(f), "bad signature";
    z = malloc(n);
    while (!e) {
        uint32_t len;
        if (p + 12 > n) {
            e = "chunk truncated";
            break;
        }
        len = be(f + p);
        if (len > n - p - 12) {
            e = "chunk length";
            break;
        }
        if (crc32_bitwise(f + p + 4, len + 4) != be(f + p + 8 + len))
            e = "chunk CRC mismatch";
        else if (p == 8 && (memcmp(f + p + 4, "IHDR", 4) || len != 13 ||
                            memcmp(f + p + 16, "\x08\x02\x00\x00\x00", 5)))
            e = "bad IHDR";
        else if (p == 8) {
            d->w = be(f + p + 8);
            d->h = be(f + p + 12);
        } else if (!memcmp(f + p + 4, "IDAT", 4)) {
            memcpy(z + zn, f + p + 8, len);
            zn += len;
            d->idats++;
        } else if (!memcmp(f + p + 4, "IEND", 4)) {
            if (len != 0 || p + 12 != n)
                e = "IEND not last or not empty";
            break;
        }
        p += 12 + len;
    }
    row = 1 + 3 * (size_t)d->w;
    raw = malloc(row * d->h + 1);
    if (!e)
        e = inflate_stored(z, zn, raw, row * d->h, &raw_len, &d->blocks);
    if (!e && raw_len != row * d->h)
        e = "wrong amount of image data";
    d->pix = e ? NULL : malloc(row * d->h);
    for (y = 0; !e && y < d->h; y++) {
        if (raw[y * row] != 0)
            e = "filter byte not 0";
        memcpy(d->pix + y * (row - 1), raw + y * row + 1, row - 1);
    }
    free(f);
    free(z);
    free(raw);
    return e;
}

static int tone_ref(float x, float exposure)
{
    double v = x > 0 ? 1.0 - exp(-(double)exposure * (double)x) : 0.0;
    if (isnan(v) || v < 0)
        v = 0;
    v = v > 1 ? 1 : v;
    v = v < 0.0031308 ? 12.92 * v : 1.055 * pow(v, 1.0 / 2.4) - 0.055;
    return (int)floor(255.0 * v + 0.5);
}

TEST(test_png_small)
{
    /* 3 x 2; values chosen with their 8-bit results worked out separately */
    float px[18] = {0.5f, 1.0f, 0.001f, 10.0f, 0.0f, -1.0f, NAN, INFINITY, 1e30f,
                    0.0001f, 2.0f, 0.25f, 1.0f, 1.0f, 1.0f, -INFINITY, 1e-6f, 3.0f};
    static const int want1[9] = {168, 208, 3, 255, 0, 0, 0, 255, 255};
    decoded d;
    const char *e;
    char err[256] = "";
    int i;
    CHECK(png_write(tmp("small.png"), 3, 2, px, 1.0f, err, sizeof err) == 0, "png_write: %s",
          err);
    CHECK(!exists(tmp("small.png.tmp")), "temporary file left");
    e = parse_png(tmp("small.png"), &d);
    CHECK(e == NULL, "%s", e);
    if (e)
        return;
    CHECK(d.w == 3 && d.h == 2 && d.idats == 1 && d.blocks == 1,
          "%lu x %lu, %d IDAT, %d blocks", (unsigned long)d.w, (unsigned long)d.h, d.idats,
          d.blocks);
    for (i = 0; i < 9; i++)
        CHECK(d.pix[i] == want1[i], "byte %d: %d, want %d", i, d.pix[i], want1[i]);
    for (i = 0; i < 18; i++)
        CHECK(d.pix[i] == tone_ref(px[i], 1.0f), "byte %d: %d, tone_ref %d", i, d.pix[i],
              tone_ref(px[i], 1.0f));
    free(d.pix);
    /* exposure: 1 - exp(-2 * 0.25) = 1 - exp(-0.5), same as x = 0.5 at 1 */
    CHECK(png_write(tmp("small.png"), 3, 2, px, 2.0f, err, sizeof err) == 0, "png_write: %s",
          err);
    e = parse_png(tmp("small.png"), &d);
    CHECK(e == NULL, "%s", e);
    if (!e) {
        CHECK(d.pix[11] == 168 && d.pix[0] == tone_ref(0.5f, 2.0f),
              "exposure 2: bytes 11, 0: %d, %d, want 168, %d", d.pix[11], d.pix[0],
              tone_ref(0.5f, 2.0f));
        free(d.pix);
    }
}

TEST(test_png_blocks)
{
    enum { W = 300, H = 200 }; /* 200 * 901 = 180200 raw bytes: 3 blocks */
    float *px = malloc(sizeof(float) * W * H * 3);
    decoded d;
    const char *e;
    char err[256] = "";
    int i, f0 = irc_t_fails;
    for (i = 0; i < W * H * 3; i++)
        px[i] = (float)((i * 7919) % 1000) / 250.0f;
    CHECK(png_write(tmp("big.png"), W, H, px, 0.7f, err, sizeof err) == 0, "png_write: %s", err);
    e = parse_png(tmp("big.png"), &d);
    CHECK(e == NULL, "%s", e);
    if (!e) {
        CHECK(d.w == W && d.h == H && d.idats == 1 && d.blocks == 3,
              "%lu x %lu, %d IDAT, %d blocks", (unsigned long)d.w, (unsigned long)d.h, d.idats,
              d.blocks);
        for (i = 0; i < W * H * 3 && irc_t_fails - f0 < MAX_FAILS; i++)
            CHECK(d.pix[i] == tone_ref(px[i], 0.7f), "byte %d: %d, tone_ref %d", i, d.pix[i],
                  tone_ref(px[i], 0.7f));
        free(d.pix);
    }
    /* exactly 65535 raw bytes: one full block, marked final */
    CHECK(png_write(tmp("big.png"), 21844, 1, px, 1.0f, err, sizeof err) == 0, "png_write: %s",
          err);
    e = parse_png(tmp("big.png"), &d);
    CHECK(e == NULL && d.blocks == 1, "65535 bytes: %s, %d blocks", e ? e : "parsed", d.blocks);
    free(d.pix);
    CHECK(png_write(tmp("big.png"), 21845, 1, px, 1.0f, err, sizeof err) == 0, "png_write: %s",
          err);
    e = parse_png(tmp("big.png"), &d);
    CHECK(e == NULL && d.blocks == 2, "65538 bytes: %s, %d blocks", e ? e : "parsed", d.blocks);
    free(d.pix);
    free(px);
}

int main(int argc, char **argv)
{
    static const test_case all[] = {TESTS(TEST_ROW)};
    static const char *files[] = {"half.exr", "float.exr", "good.exr", "small.png", "big.png"};
    size_t i;
    int rc;
    snprintf(dir, sizeof dir, "/tmp/t_image.XXXXXX");
    if (!mkdtemp(dir)) {
        perror("mkdtemp");
        return 1;
    }
    rc = test_run(all, sizeof all / sizeof all[0], argc, argv);
    for (i = 0; i < sizeof files / sizeof files[0]; i++)
        remove(tmp(files[i]));
    if (rmdir(dir) != 0)
        printf("  could not remove %s\n", dir);
    return rc;
}
