/*
 * image.c -- the demo's OpenEXR files (see image.h) with nothing but libc
 * and libm: scanline files without compression; and the byte and file
 * helpers png.c shares.  Every multi-byte value is written
 * and read one byte at a time in the format's own byte order, so the files
 * do not depend on the host.
 */
#include "image.h"
#include "image_int.h"

#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define EXR_MAGIC 20000630u
/* The reader's bound on w*h: a hostile header cannot ask for more. */
#define EXR_MAX_PIXELS (1LL << 28)
#define EXR_HALF 1
#define EXR_FLOAT 2


PRINTF_LIKE(4, 5) int img_fail(char *err, size_t errlen, const char *path, const char *fmt, ...)
{
    char msg[256];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    if (err && errlen)
        snprintf(err, errlen, "%s: %s", path, msg);
    return -1;
}

/* ---------------------------------------------------------------- bytes */

static uint32_t float_bits(float f) { uint32_t u; memcpy(&u, &f, 4); return u; }
static float bits_float(uint32_t u) { float f; memcpy(&f, &u, 4); return f; }

void img_le16(unsigned char *p, uint32_t v)
{
    p[0] = (unsigned char)(v & 0xff);
    p[1] = (unsigned char)(v >> 8 & 0xff);
}

static void le32(unsigned char *p, uint32_t v) { img_le16(p, v & 0xffff); img_le16(p + 2, v >> 16); }
static void le64(unsigned char *p, uint64_t v) { le32(p, (uint32_t)v); le32(p + 4, v >> 32); }
void img_be32(unsigned char *p, uint32_t v)
{
    int i;
    for (i = 0; i < 4; i++)
        p[i] = (unsigned char)(v >> (24 - 8 * i) & 0xff);
}

static uint32_t rd16(const unsigned char *p) { return (uint32_t)p[0] | (uint32_t)p[1] << 8; }
static uint32_t rd32(const unsigned char *p) { return rd16(p) | rd16(p + 2) << 16; }
static uint64_t rd64(const unsigned char *p) { return rd32(p) | (uint64_t)rd32(p + 4) << 32; }

/* Two's complement without relying on implementation-defined conversion. */
static int32_t rd32s(const unsigned char *p)
{
    uint32_t u = rd32(p);
    return u <= INT32_MAX ? (int32_t)u : -(int32_t)~u - 1;
}

/* ---------------------------------------------------------------- half */

unsigned short float_to_half(float f)
{
    uint32_t u = float_bits(f), sign = (u >> 16) & 0x8000, mant = u & 0x7fffff;
    int e = (int)((u >> 23) & 0xff) - 127;
    uint32_t h, rem, tie;
    int shift;

    if (e == 128) { /* inf, or NaN kept NaN even if its top payload bits are 0 */
        if (!mant)
            return (unsigned short)(sign | 0x7c00);
        h = mant >> 13;
        return (unsigned short)(sign | 0x7c00 | (h ? h : 0x200));
    }
    if (e > 15)
        return (unsigned short)(sign | 0x7c00);
    if (e < -25) /* below half the smallest subnormal (float subnormals too) */
        return (unsigned short)sign;
    if (e >= -14) { /* normal: a carry out of the mantissa bumps the exponent, up to inf */
        h = (uint32_t)(e + 15) << 10 | mant >> 13;
        rem = mant & 0x1fff;
        tie = 0x1000;
    } else { /* subnormal: count units of 2^-24; may round up to 0x400, the least normal */
        shift = -e - 1;
        mant |= 0x800000;
        h = mant >> shift;
        rem = mant & ((1u << shift) - 1);
        tie = 1u << (shift - 1);
    }
    if (rem > tie || (rem == tie && (h & 1)))
        h++;
    return (unsigned short)(sign | h);
}

float half_to_float(unsigned short hv)
{
    uint32_t h = hv, sign = (h & 0x8000) << 16, mant = h & 0x3ff;
    int e = (int)((h >> 10) & 0x1f);

    if (e == 31)
        return bits_float(sign | 0x7f800000 | mant << 13);
    if (e == 0) {
        if (!mant)
            return bits_float(sign);
        e = 1;
        while (!(mant & 0x400)) { /* normalise: every half subnormal is a float normal */
            mant <<= 1;
            e--;
        }
        mant &= 0x3ff;
    }
    return bits_float(sign | (uint32_t)(e - 15 + 127) << 23 | mant << 13);
}

/* ---------------------------------------------------------------- output */


int img_sink_open(sink *s, const char *path, char *err, size_t errlen)
{
    size_t n = strlen(path);
    s->err = 0;
    s->f = NULL;
    s->tmp = malloc(n + 5);
    if (!s->tmp)
        return img_fail(err, errlen, path, "out of memory");
    memcpy(s->tmp, path, n);
    memcpy(s->tmp + n, ".tmp", 5);
    errno = 0;
    s->f = fopen(s->tmp, "wb");
    if (!s->f) {
        int e = errno;
        free(s->tmp);
        return img_fail(err, errlen, path, "%s", e ? strerror(e) : "cannot create file");
    }
    return 0;
}

void img_sink_put(sink *s, const void *buf, size_t n)
{
    if (s->err || n == 0)
        return;
    errno = 0;
    if (fwrite(buf, 1, n, s->f) != n)
        s->err = errno ? errno : -1;
}

int img_sink_close(sink *s, const char *path, char *err, size_t errlen)
{
    errno = 0;
    if (fclose(s->f) != 0 && !s->err) /* also reports a failed flush */
        s->err = errno ? errno : -1;
    errno = 0;
    if (!s->err && rename(s->tmp, path) != 0)
        s->err = errno ? errno : -1;
    if (s->err)
        remove(s->tmp);
    free(s->tmp);
    if (s->err)
        return img_fail(err, errlen, path, "%s", s->err > 0 ? strerror(s->err) : "write failed");
    return 0;
}

/* ---------------------------------------------------------------- EXR write */

static size_t exr_attr(unsigned char *b, size_t n, const char *name, const char *type,
                       uint32_t size)
{
    size_t ln = strlen(name) + 1, lt = strlen(type) + 1;
    memcpy(b + n, name, ln);
    memcpy(b + n + ln, type, lt);
    le32(b + n + ln + lt, size);
    return n + ln + lt + 4;
}

static size_t exr_box(unsigned char *b, size_t n, int w, int h)
{
    le32(b + n, 0);
    le32(b + n + 4, 0);
    le32(b + n + 8, (uint32_t)(w - 1));
    le32(b + n + 12, (uint32_t)(h - 1));
    return n + 16;
}

/* The header (313 bytes), attributes in the alphabetical order OpenEXR
 * itself writes them. */
static size_t exr_header(unsigned char *b, int w, int h, uint32_t type)
{
    size_t n;
    int c;
    le32(b, EXR_MAGIC);
    le32(b + 4, 2); /* version 2, no flags: single-part scanline */
    n = exr_attr(b, 8, "channels", "chlist", 3 * 18 + 1);
    for (c = 0; c < 3; c++) {
        b[n] = (unsigned char)"BGR"[c];
        b[n + 1] = 0;
        le32(b + n + 2, type);
        le32(b + n + 6, 0); /* pLinear and reserved */
        le32(b + n + 10, 1);
        le32(b + n + 14, 1);
        n += 18;
    }
    b[n++] = 0;
    n = exr_attr(b, n, "compression", "compression", 1);
    b[n++] = 0;
    n = exr_box(b, exr_attr(b, n, "dataWindow", "box2i", 16), w, h);
    n = exr_box(b, exr_attr(b, n, "displayWindow", "box2i", 16), w, h);
    n = exr_attr(b, n, "lineOrder", "lineOrder", 1);
    b[n++] = 0;
    n = exr_attr(b, n, "pixelAspectRatio", "float", 4);
    le32(b + n, float_bits(1.0f));
    n = exr_attr(b, n + 4, "screenWindowCenter", "v2f", 8);
    le64(b + n, 0);
    n = exr_attr(b, n + 8, "screenWindowWidth", "float", 4);
    le32(b + n, float_bits(1.0f));
    b[n + 4] = 0;
    return n + 5;
}

/* One chunk: y, size, then the row's B values, G values, R values. */
static void exr_chunk(unsigned char *b, int y, const float *row, int w, int half,
                      uint32_t size)
{
    int c, x;
    le32(b, (uint32_t)y);
    le32(b + 4, size);
    b += 8;
    for (c = 2; c >= 0; c--)
        for (x = 0; x < w; x++, b += half ? 2 : 4) {
            if (half)
                img_le16(b, float_to_half(row[x * 3 + c]));
            else
                le32(b, float_bits(row[x * 3 + c]));
        }
}

int exr_write(const char *path, int w, int h, const float *rgb, int half,
              char *err, size_t errlen)
{
    unsigned char hdr[512], o[8], *chunk;
    size_t n, lbytes;
    sink s;
    int y;

    half = half != 0;
    if (!rgb || w <= 0 || h <= 0 || (long long)w * h > EXR_MAX_PIXELS ||
        (long long)w * 12 > INT32_MAX)
        return img_fail(err, errlen, path, "invalid image size %dx%d", w, h);
    lbytes = (size_t)w * 3 * (half ? 2 : 4);
    n = exr_header(hdr, w, h, half ? EXR_HALF : EXR_FLOAT);
    chunk = malloc(8 + lbytes);
    if (!chunk)
        return img_fail(err, errlen, path, "out of memory");
    if (img_sink_open(&s, path, err, errlen) < 0) {
        free(chunk);
        return -1;
    }
    img_sink_put(&s, hdr, n);
    for (y = 0; y < h; y++) { /* uncompressed: one line per chunk, in order */
        le64(o, (uint64_t)n + 8u * (uint64_t)h + (uint64_t)y * (8 + lbytes));
        img_sink_put(&s, o, 8);
    }
    for (y = 0; y < h && !s.err; y++) {
        exr_chunk(chunk, y, rgb + (size_t)y * w * 3, w, half, (uint32_t)lbytes);
        img_sink_put(&s, chunk, 8 + lbytes);
    }
    free(chunk);
    return img_sink_close(&s, path, err, errlen);
}

/* ---------------------------------------------------------------- EXR read */

typedef struct src {
    FILE *f;
    const char *path;
    char *err;
    size_t errlen;
    long end; /* the file's size, once known */
} src;

#define BAD(s, ...) img_fail((s)->err, (s)->errlen, (s)->path, __VA_ARGS__)

/* What the header said; `seen` has one bit per entry of exr_known. */
typedef struct exr_info {
    unsigned seen;
    uint32_t type;
    int32_t x0, y0, x1, y1;
} exr_info;

static int get(src *s, void *buf, size_t n)
{
    errno = 0;
    if (fread(buf, 1, n, s->f) == n)
        return 0;
    if (ferror(s->f))
        return BAD(s, "%s", errno ? strerror(errno) : "read error");
    return BAD(s, "truncated");
}

/* A NUL-terminated name; without the long-names flag at most 31 bytes. */
static int get_name(src *s, char *buf, size_t cap)
{
    size_t i;
    for (i = 0; i < cap; i++) {
        if (get(s, buf + i, 1) < 0)
            return -1;
        if (!buf[i])
            return 0;
    }
    return BAD(s, "bad header (name too long)");
}

/* Reading rather than seeking notices a skip past the end. */
static int skip(src *s, uint32_t n)
{
    unsigned char buf[4096];
    while (n > 0) {
        uint32_t k = n < sizeof buf ? n : (uint32_t)sizeof buf;
        if (get(s, buf, k) < 0)
            return -1;
        n -= k;
    }
    return 0;
}

/* Only channels B, G, R (the alphabetical order the format requires), one
 * pixel type, half or float, no subsampling. */
static int parse_chlist(src *s, exr_info *in, const unsigned char *b, size_t size)
{
    size_t p = 0;
    int n = 0;
    while (p < size && b[p]) {
        const unsigned char *nul = memchr(b + p, 0, size - p);
        uint32_t type;
        if (!nul || (size_t)(nul - b) + 1 + 16 > size)
            return BAD(s, "bad channel list");
        if (n == 3 || nul != b + p + 1 || b[p] != (unsigned char)"BGR"[n])
            return BAD(s, "unsupported channels (need exactly B, G, R)");
        p += 2;
        type = rd32(b + p);
        if (type != EXR_HALF && type != EXR_FLOAT)
            return BAD(s, "unsupported pixel type %lu", (unsigned long)type);
        if (n > 0 && type != in->type)
            return BAD(s, "channels of different pixel types");
        if (rd32(b + p + 8) != 1 || rd32(b + p + 12) != 1)
            return BAD(s, "unsupported channel subsampling");
        in->type = type;
        p += 16;
        n++;
    }
    if (n != 3)
        return BAD(s, "unsupported channels (need exactly B, G, R)");
    return p + 1 == size ? 0 : BAD(s, "bad channel list");
}

static const struct {
    const char *name, *type;
    uint32_t size; /* 0: variable */
} exr_known[] = {
    {"channels", "chlist", 0},        {"compression", "compression", 1},
    {"dataWindow", "box2i", 16},      {"displayWindow", "box2i", 16},
    {"lineOrder", "lineOrder", 1},    {"pixelAspectRatio", "float", 4},
    {"screenWindowCenter", "v2f", 8}, {"screenWindowWidth", "float", 4},
    {"type", "string", 0},
};
#define EXR_REQUIRED 0xffu /* all of exr_known but "type" */

/* Returns 1 if the attribute was known and consumed, 0 if unknown (still to
 * be skipped), -1 on error. */
static int parse_attr(src *s, exr_info *in, const char *name, const char *type, uint32_t size)
{
    unsigned char v[256];
    size_t i, n = sizeof exr_known / sizeof exr_known[0];
    for (i = 0; i < n && strcmp(name, exr_known[i].name) != 0; i++)
        ;
    if (i == n)
        return 0;
    if (strcmp(type, exr_known[i].type) != 0)
        return BAD(s, "attribute %s has type %s", name, type);
    if (exr_known[i].size ? size != exr_known[i].size : size >= sizeof v)
        return BAD(s, "bad size %lu for attribute %s", (unsigned long)size, name);
    if (get(s, v, size) < 0)
        return -1;
    in->seen |= 1u << i;
    if (i == 0)
        return parse_chlist(s, in, v, size) < 0 ? -1 : 1;
    if (i == 1 && v[0] != 0)
        return BAD(s, "unsupported compression %d", v[0]);
    if (i == 2) {
        in->x0 = rd32s(v);
        in->y0 = rd32s(v + 4);
        in->x1 = rd32s(v + 8);
        in->y1 = rd32s(v + 12);
    }
    if (i == 4 && v[0] > 1) /* either y order is fine: chunks come from the offset table */
        return BAD(s, "unsupported line order %d", v[0]);
    if (i == 8 && (size != 13 || memcmp(v, "scanlineimage", 13) != 0))
        return BAD(s, "not a scanline image");
    return 1;
}

static int parse_header(src *s, exr_info *in)
{
    unsigned char b[8];
    char name[32], type[32];
    uint32_t version;
    if (get(s, b, 8) < 0)
        return -1;
    if (rd32(b) != EXR_MAGIC)
        return BAD(s, "not an OpenEXR file");
    version = rd32(b + 4);
    if ((version & 0xff) != 2)
        return BAD(s, "unsupported OpenEXR version %lu", (unsigned long)(version & 0xff));
    if (version != 2) /* tiled, long names, deep or multi-part */
        return BAD(s, "unsupported OpenEXR flags 0x%lx", (unsigned long)(version & ~0xffu));
    for (;;) {
        int r;
        if (get_name(s, name, sizeof name) < 0)
            return -1;
        if (!name[0])
            break;
        if (get_name(s, type, sizeof type) < 0 || get(s, b, 4) < 0)
            return -1;
        if (rd32(b) > INT32_MAX)
            return BAD(s, "bad attribute size");
        r = parse_attr(s, in, name, type, rd32(b));
        if (r < 0 || (r == 0 && skip(s, rd32(b)) < 0))
            return -1;
    }
    if ((in->seen & EXR_REQUIRED) != EXR_REQUIRED)
        return BAD(s, "missing required attribute");
    return 0;
}

/* The file must hold what the header promises before anything the size of
 * the image is allocated. */
static int check_size(src *s, long long need)
{
    long here = ftell(s->f);
    if (here < 0 || fseek(s->f, 0, SEEK_END) != 0 || (s->end = ftell(s->f)) < 0 ||
        fseek(s->f, here, SEEK_SET) != 0)
        return BAD(s, "%s", strerror(errno));
    return (long long)s->end - here < need ? BAD(s, "truncated") : 0;
}

static void decode_line(float *dst, const unsigned char *b, int w, uint32_t type)
{
    int c, x;
    for (c = 2; c >= 0; c--)
        for (x = 0; x < w; x++, b += type == EXR_HALF ? 2 : 4)
            dst[x * 3 + c] = type == EXR_HALF ? half_to_float((unsigned short)rd16(b))
                                              : bits_float(rd32(b));
}

/* Line i must be the chunk the i-th offset points to, so every line is
 * filled exactly once. */
static int read_chunks(src *s, const exr_info *in, int w, int h, float *rgb)
{
    size_t lbytes = (size_t)w * 3 * (in->type == EXR_HALF ? 2 : 4);
    unsigned char *off = malloc((size_t)h * 8), *chunk = malloc(8 + lbytes);
    uint64_t first = (uint64_t)ftell(s->f) + 8u * (uint64_t)h;
    int y, r = off && chunk ? get(s, off, (size_t)h * 8) : BAD(s, "out of memory");
    for (y = 0; r == 0 && y < h; y++) {
        uint64_t o = rd64(off + (size_t)y * 8);
        if (o < first || o > (uint64_t)s->end - 8 - lbytes)
            r = BAD(s, "bad offset for line %d", y);
        else if (fseek(s->f, (long)o, SEEK_SET) != 0)
            r = BAD(s, "%s", strerror(errno));
        else if (get(s, chunk, 8 + lbytes) < 0)
            r = -1;
        else if ((long long)rd32s(chunk) != (long long)in->y0 + y || rd32(chunk + 4) != lbytes)
            r = BAD(s, "bad chunk for line %d", y);
        else
            decode_line(rgb + (size_t)y * w * 3, chunk + 8, w, in->type);
    }
    free(off);
    free(chunk);
    return r;
}

int exr_read(const char *path, int *w, int *h, float **rgb, char *err, size_t errlen)
{
    src s = {NULL, path, err, errlen, 0};
    exr_info in = {0, 0, 0, 0, 0, 0};
    long long ww, hh;
    float *img = NULL;
    int r;

    *w = *h = 0;
    *rgb = NULL;
    errno = 0;
    s.f = fopen(path, "rb");
    if (!s.f)
        return img_fail(err, errlen, path, "%s", errno ? strerror(errno) : "cannot open");
    r = parse_header(&s, &in);
    ww = (long long)in.x1 - in.x0 + 1;
    hh = (long long)in.y1 - in.y0 + 1;
    if (r == 0 && (ww < 1 || hh < 1))
        r = BAD(&s, "bad data window");
    if (r == 0 && (ww * hh > EXR_MAX_PIXELS || ww * 12 > INT32_MAX))
        r = BAD(&s, "image too large (%lldx%lld)", ww, hh);
    if (r == 0)
        r = check_size(&s, hh * 8 + hh * (8 + ww * 3 * (in.type == EXR_HALF ? 2 : 4)));
    if (r == 0 && !(img = malloc((size_t)(ww * hh) * 3 * sizeof *img)))
        r = BAD(&s, "out of memory");
    if (r == 0)
        r = read_chunks(&s, &in, (int)ww, (int)hh, img);
    fclose(s.f);
    if (r < 0) {
        free(img);
        return -1;
    }
    *w = (int)ww;
    *h = (int)hh;
    *rgb = img;
    return 0;
}

