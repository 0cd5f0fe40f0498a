/*
 * snapshot.c -- a cache's records as a portable byte string, and back: the
 * format docs/FORMAT.md defines byte by byte (little-endian, IEEE floats, a
 * versioned header, CRC-32C over header and records).
 */
#include "../block/cache.h"
#include "../block/check.h"
#include "../bytes.h"
#include "../index/index.h"
#include "../index/verify.h"
#include "../store/lock.h"
#include "snapshot.h"


/* CRC-32C (Castagnoli, reflected polynomial 0x82F63B78), four bits at a
 * time: a 64-byte table instead of 1 KiB, for small targets. */
static const uint32_t irc__crc_nibble[16] = {
    0x00000000u, 0x105ec76fu, 0x20bd8edeu, 0x30e349b1u, 0x417b1dbcu, 0x5125dad3u,
    0x61c69362u, 0x7198540du, 0x82f63b78u, 0x92a8fc17u, 0xa24bb5a6u, 0xb21572c9u,
    0xc38d26c4u, 0xd3d3e1abu, 0xe330a81au, 0xf36e6f75u};

/* Continues a CRC: crc is the running value before the final inversion
 * (start from 0xffffffff, invert at the end). */
static uint32_t irc__crc(uint32_t crc, const unsigned char *p, size_t n)
{
    while (n--) {
        crc ^= *p++;
        crc = (crc >> 4) ^ irc__crc_nibble[crc & 15u];
        crc = (crc >> 4) ^ irc__crc_nibble[crc & 15u];
    }
    return crc;
}

/* The width of the packed record's field at byte `at`: the head's 4-byte
 * words (floats, the octahedral code), then each part's as its table says. */
unsigned irc__field_width(const irc_cache *c, uint32_t at)
{
    uint32_t i;
    for (i = 0; i < c->n_parts; i++) {
        const irc__recpart *p = &c->parts[i];
        const uint32_t o = c->off[p->id];
        if (at >= o && at < o + p->bytes)
            return at - o < p->lead ? p->w1 : p->w2;
    }
    return 4;
}

/* The fields of a packed record from byte `from` on, as many whole ones as
 * fit in max bytes, to the snapshot's bytes (to_le) or back; src and dst
 * point at byte `from`.  Returns the bytes converted. */
static uint32_t irc__convert_part(const irc_cache *c, const unsigned char *src,
                                  unsigned char *dst, uint32_t from, uint32_t max, int to_le)
{
    uint32_t at = from;
    while (at < c->rec_size) {
        unsigned w = irc__field_width(c, at);
        if (at + w - from > max)
            break;
        if (to_le)
            irc__le_put(dst + (at - from), irc__native_get(src + (at - from), w), w);
        else
            irc__native_put(dst + (at - from), irc__le_get(src + (at - from), w), w);
        at += w;
    }
    return at - from;
}

/* A whole packed record to the snapshot's bytes (to_le) or back. */
void irc__convert(const irc_cache *c, const unsigned char *src, unsigned char *dst,
                         int to_le)
{
    (void)irc__convert_part(c, src, dst, 0, c->rec_size, to_le);
}

/* The kind's config word w that the header keeps (irc__kind.snap_at). */
static uint32_t irc__cfg_word(const irc_cache *c, int w)
{
    const uint32_t at = c->kind->snap_at[w];
    uint32_t v = 0;
    if (at)
        IRC_MEMCPY(&v, (const unsigned char *)&c->cfg + at, sizeof v);
    return v;
}

static void irc__header(const irc_cache *c, uint64_t fingerprint, unsigned char *h)
{
    float a = c->cfg.accuracy;
    uint32_t abits;
    IRC_MEMCPY(&abits, &a, 4);
    IRC_MEMSET(h, 0, IRC__SNAP_HEAD);
    h[0] = 'I'; h[1] = 'R'; h[2] = 'C'; h[3] = 'S';
    irc__le_put(h + 4, IRC_SNAPSHOT_VERSION, 2);
    irc__le_put(h + 6, c->kind_id, 2);
    irc__le_put(h + 8, c->cfg.features, 4);
    irc__le_put(h + 12, irc__st(c)->count, 4);
    irc__le_put(h + 16, c->rec_size, 4);
    irc__le_put(h + 20, irc__cfg_word(c, 0), 2);
    irc__le_put(h + 22, irc__cfg_word(c, 1), 2);
    irc__le_put(h + 24, abits, 4);
    irc__le_put(h + 28, c->cfg.strata_theta, 4);
    irc__le_put(h + 32, c->cfg.strata_phi, 4);
    irc__le_put(h + 36, fingerprint, 8);
    irc__le_put(h + 44, irc__crc(0xffffffffu, h, 44) ^ 0xffffffffu, 4);
}

static uint64_t irc__snap_bytes(const irc_cache *c, uint32_t count)
{
    return IRC__SNAP_HEAD + (uint64_t)count * c->rec_size + IRC__SNAP_TAIL;
}

int irc_snapshot_size(irc_cache *c, size_t *bytes)
{
    uint64_t n;
    int st = irc__enter(c, NULL);
    if (st < 0)
        return st;
    if (!bytes)
        return IRC_ERR_NULL;
    if (irc__read_lock(c) < 0)
        return IRC_ERR_PORT;
    n = irc__snap_bytes(c, irc__st(c)->count);
    irc__read_unlock(c);
    if (n > (uint64_t)(size_t)-1)
        return IRC_ERR_NOMEM;
    *bytes = (size_t)n;
    return IRC_OK;
}

/* Hands `n` bytes to the host's writer or copies them to out at *at. */
static int irc__emit(irc_write_fn fn, void *ctx, unsigned char *out, size_t *at,
                     const unsigned char *p, size_t n, uint32_t *crc)
{
    int st;
    *crc = irc__crc(*crc, p, n);
    if (fn) {
        st = fn(ctx, p, n);
        if (st != 0)
            return st < 0 ? st : IRC_ERR_CALLBACK;
    } else {
        IRC_MEMCPY(out + *at, p, n);
    }
    *at += n;
    return IRC_OK;
}

static int irc__write_locked(irc_cache *c, uint64_t fingerprint, unsigned char *out,
                             irc_write_fn fn, void *ctx, size_t *written)
{
    /* Records go out through 64 bytes at a time (whole fields): the stack
     * holds no record of the largest kind (1.2 KB; docs/PORTING.md, "Embedded"). */
    unsigned char buf[IRC__SNAP_HEAD > 64 ? IRC__SNAP_HEAD : 64], tail[IRC__SNAP_TAIL];
    uint32_t crc = 0xffffffffu, id, from, n;
    size_t at = 0;
    int st;
    irc__header(c, fingerprint, buf);
    if ((st = irc__emit(fn, ctx, out, &at, buf, IRC__SNAP_HEAD, &crc)) < 0)
        return st;
    for (id = 0; id < irc__st(c)->count; id++)
        for (from = 0; from < c->rec_size; from += n) {
            const unsigned char *r = (const unsigned char *)irc__rec_at(c, id) + from;
            n = irc__convert_part(c, r, buf, from, 64u, 1);
            IRC_ASSERT(n > 0);
            if ((st = irc__emit(fn, ctx, out, &at, buf, n, &crc)) < 0)
                return st;
        }
    irc__le_put(tail, crc ^ 0xffffffffu, 4);
    if ((st = irc__emit(fn, ctx, out, &at, tail, IRC__SNAP_TAIL, &crc)) < 0)
        return st;
    if (written)
        *written = at;
    return IRC_OK;
}

int irc_snapshot_write(irc_cache *c, uint64_t fingerprint, void *buffer, size_t size,
                       irc_write_fn write, void *context, size_t *written)
{
    int st = irc__enter(c, NULL);
    if (st < 0)
        return st;
    if (!write && !buffer)
        return IRC_ERR_NULL;
    if (irc__read_lock(c) < 0)
        return IRC_ERR_PORT;
    if (!write && irc__snap_bytes(c, irc__st(c)->count) > (uint64_t)size)
        st = IRC_ERR_NOMEM;
    else
        st = irc__write_locked(c, fingerprint, (unsigned char *)buffer, write, context, written);
    irc__read_unlock(c);
    return st;
}

/* Whether a record, still in the snapshot's bytes, holds values a cache
 * could have made: its head decoded into 32 bytes, the rest read where it
 * lies (no record-sized buffer on the stack). */
static int irc__record_sane(const irc_cache *c, const unsigned char *le)
{
    union { irc__rec r; unsigned char b[sizeof(irc__rec)]; } h;
    const irc__rec *r = &h.r;
    const uint32_t got = irc__convert_part(c, le, h.b, 0, sizeof h.b, 0);
    IRC_ASSERT(got == sizeof h.b);
    (void)got;
    return irc__rec_head_sane(c, r) && irc__parts_sane(c, le, 1);
}

/* Everything a read checks before it touches the cache; the record count
 * in *count, which must fit in `room` slots.  Version before the header's
 * CRC, so that another version's snapshot is named as such. */
int irc__snap_check(const irc_cache *c, uint64_t fingerprint, const unsigned char *d,
                    size_t size, uint32_t room, uint32_t *count)
{
    unsigned char want[IRC__SNAP_HEAD];
    uint64_t total;
    uint32_t i;
    if (size < 8)
        return IRC_ERR_TRUNCATED;
    if (d[0] != 'I' || d[1] != 'R' || d[2] != 'C' || d[3] != 'S')
        return IRC_ERR_CORRUPT;
    if (irc__le_get(d + 4, 2) != IRC_SNAPSHOT_VERSION)
        return IRC_ERR_VERSION;
    if (size < IRC__SNAP_HEAD)
        return IRC_ERR_TRUNCATED;
    if ((irc__crc(0xffffffffu, d, 44) ^ 0xffffffffu) != irc__le_get(d + 44, 4))
        return IRC_ERR_CORRUPT;
    *count = (uint32_t)irc__le_get(d + 12, 4);
    if (irc__le_get(d + 16, 4) == 0)
        return IRC_ERR_CORRUPT;
    total = IRC__SNAP_HEAD + (uint64_t)*count * irc__le_get(d + 16, 4) + IRC__SNAP_TAIL;
    if ((uint64_t)size < total)
        return IRC_ERR_TRUNCATED;
    if ((uint64_t)size > total ||
        (irc__crc(0xffffffffu, d, size - IRC__SNAP_TAIL) ^ 0xffffffffu) !=
            irc__le_get(d + size - IRC__SNAP_TAIL, 4))
        return IRC_ERR_CORRUPT;
    if (irc__le_get(d + 36, 8) != fingerprint)
        return IRC_ERR_FINGERPRINT;
    /* Kind, features, record bytes, the kind's words and a must agree;
     * not the count, nor the strata (bytes 28-35): a record holds what
     * lookups read, whatever rays made it. */
    irc__header(c, fingerprint, want);
    for (i = 6; i < 28; i++)
        if ((i < 12 || i >= 16) && d[i] != want[i])
            return IRC_ERR_MISMATCH;
    if (*count > room)
        return IRC_ERR_FULL;
    for (i = 0; i < *count; i++)
        if (!irc__record_sane(c, d + IRC__SNAP_HEAD + (size_t)i * c->rec_size))
            return IRC_ERR_CORRUPT;
    return IRC_OK;
}

int irc_snapshot_read(irc_cache *c, uint64_t fingerprint, const void *data, size_t size)
{
    const unsigned char *d = (const unsigned char *)data;
    uint32_t count = 0, i;
    int st = irc__enter(c, NULL);
    if (st < 0)
        return st;
    if (!data)
        return IRC_ERR_NULL;
    if ((st = irc__snap_check(c, fingerprint, d, size, c->capacity, &count)) < 0)
        return st;
    if ((st = irc__write_lock_idle(c)) < 0)
        return st;
    irc__clear_locked(c);
    for (i = 0; i < count; i++) {
        irc__convert(c, d + IRC__SNAP_HEAD + (size_t)i * c->rec_size,
                     (unsigned char *)irc__rec_at(c, i), 0);
        irc__st(c)->count = i + 1;
        irc__index_insert(c, i);
    }
    irc__write_unlock(c);
    return IRC_OK;
}
