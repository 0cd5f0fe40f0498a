/* t_snapshot.c -- snapshots: round trips bit for bit, every truncation and
 * single-byte corruption refused with its status and the cache unchanged,
 * and a snapshot built by hand from docs/FORMAT.md's definition. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "irrcache.h"
#include "scenes.h"
#include "test.h"

/* A cache on the sphere-over-plane scene, filled by lookups over a grid. */
static irc_cache *filled(tscene *s, irc_config *cfg, uint32_t features, uint32_t cap, int n)
{
    irc_cache *c;
    int i;
    scene_sphere_plane(s);
    *cfg = scene_config(s, features, 8, 32);
    cfg->max_radius = 4.0f;
    c = block_cache(cfg, cap, 0);
    for (i = 0; c && i < n * n; i++) {
        const float p[3] = {(float)(i % n) * 6.0f / n - 3.0f, (float)(i / n) * 6.0f / n - 3.0f, 0},
                    up[3] = {0, 0, 1};
        float rgb[3], w;
        if (irc_cache_lookup_or_compute(c, p, up, rgb, &w, NULL) < 0)
            return NULL;
    }
    return c;
}

typedef struct sink {
    unsigned char *b;
    size_t n, cap;
} sink;

static int to_sink(void *ctx, const void *bytes, size_t count)
{
    sink *k = (sink *)ctx;
    if (k->n + count > k->cap)
        return -99;
    memcpy(k->b + k->n, bytes, count);
    k->n += count;
    return 0;
}

/* Write (into a buffer and streamed: the same bytes), read into a fresh
 * block at another address: the same records, and 2000 lookups equal bit
 * for bit; for irradiance records with both gradients, the Hessian ellipse
 * and the guard. */
TEST(test_snapshot_round_trip)
{
    tscene s, s2;
    irc_config cfg, cfg2;
    irc_cache *a = filled(&s, &cfg, IRC_FEATURE_TRANSLATION | IRC_FEATURE_ROTATION |
                                        IRC_FEATURE_HESSIAN, 4096, 24),
              *b;
    irc_stats sa, sb;
    size_t bytes = 0, written = 0;
    unsigned char *buf;
    sink k;
    int i, diff = 0;
    CHECK(a && irc_snapshot_size(a, &bytes) == IRC_OK && irc_cache_stats(a, &sa) == IRC_OK,
          "fill");
    if (!a) return;
    CHECK(bytes == 48u + sa.records * sa.record_bytes + 4u, "size %zu", bytes);
    buf = malloc(bytes);
    k.b = malloc(bytes);
    k.n = 0;
    k.cap = bytes;
    memset(buf, 0xa5, bytes);
    CHECK(irc_snapshot_write(a, 77u, buf, bytes - 1, NULL, NULL, &written) == IRC_ERR_NOMEM,
          "short buffer");
    {
        size_t at;
        for (at = 0; at < bytes && buf[at] == 0xa5; at++)
            ;
        CHECK(at == bytes, "a short buffer was written at byte %zu", at);
    }
    CHECK(irc_snapshot_write(a, 77u, buf, bytes, NULL, NULL, &written) == IRC_OK &&
              written == bytes, "write %zu", written);
    CHECK(irc_snapshot_write(a, 77u, NULL, 0, to_sink, &k, &written) == IRC_OK && k.n == bytes &&
              memcmp(k.b, buf, bytes) == 0, "streamed bytes differ");
    k.cap = bytes / 2;
    k.n = 0;
    CHECK(irc_snapshot_write(a, 77u, NULL, 0, to_sink, &k, NULL) == -99, "writer's code");
    scene_sphere_plane(&s2);
    cfg2 = cfg;
    cfg2.buffer = NULL;
    b = block_cache(&cfg2, 4096, 0);
    CHECK(b && irc_snapshot_read(b, 77u, buf, bytes) == IRC_OK &&
              irc_cache_stats(b, &sb) == IRC_OK && sb.records == sa.records, "read");
    for (i = 0; b && i < 2000; i++) {
        const float p[3] = {(float)(i % 50) * 0.13f - 3.2f, (float)(i / 50) * 0.16f - 3.2f, 0},
                    n[3] = {0.0f, 0.05f * (float)(i % 3), 1.0f};
        float r1[3], r2[3], w1, w2;
        int s1 = irc_cache_lookup(a, p, n, r1, &w1), s2r = irc_cache_lookup(b, p, n, r2, &w2);
        diff += s1 != s2r || memcmp(r1, r2, sizeof r1) != 0 || memcmp(&w1, &w2, sizeof w1) != 0;
    }
    printf("  %llu records, %zu bytes (%u a record); 2000 lookups, %d differ\n",
           (unsigned long long)sa.records, bytes, (unsigned)sa.record_bytes, diff);
    CHECK(diff == 0, "%d lookups differ after the round trip", diff);
    free(buf);
    free(k.b);
    block_free(&cfg);
    block_free(&cfg2);
}

/* SH records (coefficients and gradients, free points and surface points)
 * survive the round trip bit for bit too. */
TEST(test_snapshot_round_trip_sh)
{
    tscene s;
    irc_config cfg, cfg2;
    irc_cache *a, *b;
    size_t bytes = 0;
    unsigned char *buf;
    int i, diff = 0;
    scene_sphere_plane(&s);
    cfg = scene_config(&s, IRC_FEATURE_SH | IRC_FEATURE_SH_GRADIENT, 8, 16);
    cfg.max_radius = 4.0f;
    a = block_cache(&cfg, 256, 0);
    CHECK(a != NULL, "init");
    if (!a) return;
    for (i = 0; i < 36; i++) {
        const float p[3] = {(float)(i % 6) - 2.5f, (float)(i / 6) - 2.5f, 0.5f * (float)(i & 1)},
                    up[3] = {0, 0, 1};
        irc_sh sh;
        float w;
        CHECK(irc_sh_lookup_or_compute(a, p, i & 1 ? NULL : up, &sh, &w, NULL) >= 0, "fill");
    }
    CHECK(irc_snapshot_size(a, &bytes) == IRC_OK, "size");
    buf = malloc(bytes);
    CHECK(irc_snapshot_write(a, 9u, buf, bytes, NULL, NULL, NULL) == IRC_OK, "write");
    cfg2 = cfg;
    cfg2.buffer = NULL;
    b = block_cache(&cfg2, 256, 0);
    CHECK(b && irc_snapshot_read(b, 9u, buf, bytes) == IRC_OK, "read");
    for (i = 0; b && i < 400; i++) {
        const float p[3] = {(float)(i % 20) * 0.27f - 2.7f, (float)(i / 20) * 0.27f - 2.7f,
                            0.25f * (float)(i & 1)},
                    up[3] = {0, 0, 1};
        irc_sh h1, h2;
        float w1, w2;
        int s1, s2;
        memset(&h1, 0, sizeof h1);
        memset(&h2, 0, sizeof h2);
        s1 = irc_sh_lookup(a, p, i & 1 ? NULL : up, &h1, &w1);
        s2 = irc_sh_lookup(b, p, i & 1 ? NULL : up, &h2, &w2);
        diff += s1 != s2 || memcmp(&h1, &h2, sizeof h1) != 0 || memcmp(&w1, &w2, sizeof w1);
    }
    printf("  SH: %zu bytes; 400 lookups, %d differ\n", bytes, diff);
    CHECK(diff == 0, "%d SH lookups differ after the round trip", diff);
    free(buf);
    block_free(&cfg);
    block_free(&cfg2);
}

/* Whether cache c still holds exactly the records of `want`. */
static int same_records(irc_cache *c, irc_cache *want)
{
    irc_stats a, b;
    uint32_t i;
    if (irc_cache_stats(c, &a) != IRC_OK || irc_cache_stats(want, &b) != IRC_OK ||
        a.records != b.records)
        return 0;
    for (i = 0; i < a.records; i++) {
        irc_record r1, r2;
        if (irc_cache_record(c, i, &r1) != IRC_OK || irc_cache_record(want, i, &r2) != IRC_OK ||
            memcmp(r1.p, r2.p, sizeof r1.p) || memcmp(r1.e, r2.e, sizeof r1.e) ||
            r1.radius != r2.radius)
            return 0;
    }
    return 1;
}

/* Every truncation and every single-byte change of a small snapshot is
 * refused with its status (magic: CORRUPT, version bytes: VERSION, any
 * other byte: CORRUPT through a checksum; any shorter length: TRUNCATED),
 * and the target, which holds records of its own, keeps them; so do a
 * wrong fingerprint, another feature set, too small a cache and a
 * trailing byte. */
TEST(test_snapshot_rejects)
{
    tscene s, s2, s3;
    irc_config cfg, cfg2, cfg3;
    irc_cache *a = filled(&s, &cfg, IRC_FEATURE_TRANSLATION, 64, 3), *t, *other;
    size_t bytes = 0, i;
    unsigned char *buf, *bad;
    int wrong = 0, bit;
    CHECK(a && irc_snapshot_size(a, &bytes) == IRC_OK, "fill");
    if (!a) return;
    buf = malloc(bytes + 1);
    bad = malloc(bytes + 1);
    CHECK(irc_snapshot_write(a, 5u, buf, bytes, NULL, NULL, NULL) == IRC_OK, "write");
    t = filled(&s2, &cfg2, IRC_FEATURE_TRANSLATION, 64, 2); /* other records */
    other = filled(&s3, &cfg3, IRC_FEATURE_TRANSLATION, 64, 2);
    CHECK(t && other, "targets");
    if (!t || !other) return;
    for (i = 0; i < bytes; i++)
        wrong += irc_snapshot_read(t, 5u, buf, i) != IRC_ERR_TRUNCATED;
    CHECK(wrong == 0, "%d truncations not reported as such", wrong);
    for (i = 0; i < bytes; i++)
        for (bit = 0; bit < 8; bit += 7) {
            int want = i < 4 ? IRC_ERR_CORRUPT : i < 6 ? IRC_ERR_VERSION : IRC_ERR_CORRUPT, got;
            memcpy(bad, buf, bytes);
            bad[i] ^= (unsigned char)(1u << bit);
            got = irc_snapshot_read(t, 5u, bad, bytes);
            if (got != want && wrong++ < 5)
                printf("  byte %zu bit %d: %s, want %s\n", i, bit, irc_strerror(got),
                       irc_strerror(want));
        }
    CHECK(wrong == 0, "%d corruptions not reported as such", wrong);
    memcpy(bad, buf, bytes);
    bad[bytes] = 0;
    CHECK(irc_snapshot_read(t, 5u, bad, bytes + 1) == IRC_ERR_CORRUPT, "trailing byte");
    CHECK(irc_snapshot_read(t, 6u, buf, bytes) == IRC_ERR_FINGERPRINT, "fingerprint");
    CHECK(same_records(t, other), "a refused read changed the cache");
    block_free(&cfg2);
    {
        irc_config c4 = scene_config(&s2, IRC_FEATURE_ROTATION, 8, 32), c5;
        irc_cache *x = block_cache(&c4, 64, 0), *y;
        CHECK(x && irc_snapshot_read(x, 5u, buf, bytes) == IRC_ERR_MISMATCH, "features");
        block_free(&c4);
        c5 = cfg;
        c5.buffer = NULL;
        y = block_cache(&c5, 3, 0);
        CHECK(y && irc_snapshot_read(y, 5u, buf, bytes) == IRC_ERR_FULL, "capacity");
        block_free(&c5);
    }
    free(buf);
    free(bad);
    block_free(&cfg);
    block_free(&cfg3);
}

/* Records carry what lookups read, whatever rays made them: a snapshot
 * of 8 x 32 records reads into caches of 16 x 64 and of the default
 * strata (32 x 128 at a = 0.2), and merges, answering every lookup as the
 * writer did; another accuracy is still refused (lookups reach a R). */
TEST(test_snapshot_other_strata)
{
    tscene s, s2;
    irc_config cfg, to;
    irc_cache *a = filled(&s, &cfg, IRC_FEATURE_TRANSLATION, 64, 3), *t;
    size_t bytes = 0;
    unsigned char *buf;
    static const uint32_t strata[][2] = {{16, 64}, {0, 0}};
    int i, k, differ = 0;
    CHECK(a && irc_snapshot_size(a, &bytes) == IRC_OK && (buf = malloc(bytes)) != NULL, "fill");
    if (!a || !buf)
        return;
    CHECK(irc_snapshot_write(a, 5u, buf, bytes, NULL, NULL, NULL) == IRC_OK, "write");
    scene_sphere_plane(&s2);
    for (i = 0; i < 2; i++) {
        to = scene_config(&s2, IRC_FEATURE_TRANSLATION, strata[i][0], strata[i][1]);
        t = block_cache(&to, 64, 0);
        CHECK(t && irc_snapshot_read(t, 5u, buf, bytes) == IRC_OK, "read into %u x %u",
              strata[i][0], strata[i][1]);
        for (k = 0; t && k < 400; k++) {
            const float p[3] = {-1.5f + 0.15f * (float)(k % 20), -1.5f + 0.15f * (float)(k / 20), 0},
                        n[3] = {0, 0, 1};
            float ra[3], rt[3], wa, wt;
            const int sa = irc_cache_lookup(a, p, n, ra, &wa), st = irc_cache_lookup(t, p, n, rt, &wt);
            differ += sa != st || memcmp(ra, rt, sizeof ra) != 0 || wa != wt;
        }
        CHECK(t && irc_cache_clear(t) == IRC_OK && irc_merge(t, 5u, buf, bytes) == IRC_OK,
              "merge into %u x %u", strata[i][0], strata[i][1]);
        block_free(&to);
    }
    CHECK(differ == 0, "%d lookups differ from the writer's", differ);
    to = scene_config(&s2, IRC_FEATURE_TRANSLATION, 8, 32);
    to.accuracy = 0.3f;
    t = block_cache(&to, 64, 0);
    CHECK(t && irc_snapshot_read(t, 5u, buf, bytes) == IRC_ERR_MISMATCH, "another accuracy");
    block_free(&to);
    free(buf);
    block_free(&cfg);
}

/* A trans + rot cache filled by lookups on a 0.25 grid over [x0, x1] x
 * [-1, 1], and its snapshot. */
static unsigned char *tile(irc_config *cfg, double x0, double x1, size_t *bytes)
{
    static tscene s;
    irc_cache *c;
    unsigned char *buf = NULL;
    double x, y;
    scene_sphere_plane(&s);
    *cfg = scene_config(&s, IRC_FEATURE_TRANSLATION | IRC_FEATURE_ROTATION, 8, 32);
    cfg->max_radius = 4.0f;
    c = block_cache(cfg, 2048, 0);
    for (x = x0; c && x <= x1; x += 0.25)
        for (y = -1.0; y <= 1.0; y += 0.25) {
            const float p[3] = {(float)x, (float)y, 0}, up[3] = {0, 0, 1};
            float rgb[3], w;
            irc_cache_lookup_or_compute(c, p, up, rgb, &w, NULL);
        }
    if (c && irc_snapshot_size(c, bytes) == IRC_OK && (buf = malloc(*bytes)) != NULL &&
        irc_snapshot_write(c, 3u, buf, *bytes, NULL, NULL, NULL) != IRC_OK) {
        free(buf);
        buf = NULL;
    }
    block_free(cfg);
    return buf;
}

/* Merges of three tiles (two overlapping) in all six orders give caches
 * whose snapshots are byte-identical; merging a tile twice adds nothing;
 * a merge that would overflow the cache, or of a corrupt snapshot, is
 * refused with the cache unchanged. */
TEST(test_merge_order_free)
{
    static const int perm[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
    irc_config cfg;
    unsigned char *t[3], *first = NULL;
    size_t tb[3], firstb = 0;
    int k, i, same = 1;
    uint64_t records = 0;
    t[0] = tile(&cfg, -3.0, 0.0, &tb[0]);
    t[1] = tile(&cfg, 0.0, 3.0, &tb[1]);
    t[2] = tile(&cfg, -1.0, 1.5, &tb[2]);
    CHECK(t[0] && t[1] && t[2], "tiles");
    if (!t[0] || !t[1] || !t[2]) return;
    for (k = 0; k < 6; k++) {
        tscene s;
        irc_config c2;
        irc_cache *m;
        irc_stats st;
        size_t n = 0;
        unsigned char *out;
        scene_sphere_plane(&s);
        c2 = scene_config(&s, IRC_FEATURE_TRANSLATION | IRC_FEATURE_ROTATION, 8, 32);
        c2.max_radius = 4.0f;
        m = block_cache(&c2, 2048, 0);
        for (i = 0; m && i < 3; i++)
            CHECK(irc_merge(m, 3u, t[perm[k][i]], tb[perm[k][i]]) == IRC_OK, "merge");
        if (!m) continue;
        if (k == 0) { /* the first tile again: nothing added */
            irc_stats before;
            irc_cache_stats(m, &before);
            CHECK(irc_merge(m, 3u, t[0], tb[0]) == IRC_OK && irc_cache_stats(m, &st) == IRC_OK &&
                      st.records == before.records, "merging twice added records");
        }
        irc_cache_stats(m, &st);
        records = st.records;
        irc_snapshot_size(m, &n);
        out = malloc(n);
        CHECK(irc_snapshot_write(m, 3u, out, n, NULL, NULL, NULL) == IRC_OK, "write");
        if (!first) {
            first = out;
            firstb = n;
        } else {
            same &= n == firstb && memcmp(out, first, n) == 0;
            free(out);
        }
        block_free(&c2);
    }
    printf("  tiles of %zu, %zu, %zu bytes merged: %llu records; six orders %s\n", tb[0], tb[1],
           tb[2], (unsigned long long)records, same ? "byte-identical" : "DIFFER");
    CHECK(same, "merge order changed the cache");
    {   /* full, and corrupt: refused, unchanged */
        tscene s;
        irc_config c3;
        irc_cache *m, *ref;
        unsigned char *bad = malloc(tb[1]);
        scene_sphere_plane(&s);
        c3 = scene_config(&s, IRC_FEATURE_TRANSLATION | IRC_FEATURE_ROTATION, 8, 32);
        c3.max_radius = 4.0f;
        m = block_cache(&c3, (uint32_t)((tb[0] - 52) / 64 + 3), 0); /* 64-byte records */
        CHECK(m && irc_merge(m, 3u, t[0], tb[0]) == IRC_OK, "first merge");
        CHECK(m && irc_merge(m, 3u, t[1], tb[1]) == IRC_ERR_FULL, "overflow refused");
        memcpy(bad, t[1], tb[1]);
        bad[60] ^= 1u;
        CHECK(m && irc_merge(m, 3u, bad, tb[1]) == IRC_ERR_CORRUPT, "corrupt refused");
        {
            irc_config c4 = c3;
            c4.buffer = NULL;
            ref = block_cache(&c4, 64, 0);
            CHECK(ref && irc_merge(ref, 3u, t[0], tb[0]) == IRC_OK && same_records(m, ref),
                  "a refused merge changed the cache");
            block_free(&c4);
        }
        free(bad);
        block_free(&c3);
    }
    free(first);
    for (i = 0; i < 3; i++)
        free(t[i]);
}

/* CRC-32C bit by bit (the library uses a table): the test's own. */
static uint32_t crc32c(const unsigned char *p, size_t n)
{
    uint32_t c = 0xffffffffu;
    int k;
    while (n--)
        for (c ^= *p++, k = 0; k < 8; k++)
            c = c & 1u ? (c >> 1) ^ 0x82f63b78u : c >> 1;
    return c ^ 0xffffffffu;
}

static void le(unsigned char *d, uint64_t v, int w)
{
    int i;
    for (i = 0; i < w; i++)
        d[i] = (unsigned char)(v >> (8 * i));
}

static void lef(unsigned char *d, float f)
{
    uint32_t u;
    memcpy(&u, &f, 4);
    le(d, u, 4);
}

/* A snapshot written byte by byte from docs/FORMAT.md (a bare irradiance
 * cache without the guard: 32-byte records) holds the records it says,
 * and the cache writes it back byte for byte. */
TEST(test_snapshot_by_hand)
{
    unsigned char b[48 + 2 * 32 + 4], out[sizeof b];
    tscene s;
    irc_config cfg;
    irc_cache *c;
    irc_record r;
    size_t n = 0;
    int i;
    scene_init(&s);
    cfg = scene_config(&s, 0, 4, 4);
    cfg.accuracy = 0.25f;
    c = block_cache(&cfg, 4, 0);
    CHECK(c != NULL, "init");
    if (!c) return;
    memset(b, 0, sizeof b);
    memcpy(b, "IRCS", 4);
    le(b + 4, 1, 2);          /* version */
    le(b + 6, 1, 2);          /* kind: irradiance */
    le(b + 8, 0, 4);          /* features */
    le(b + 12, 2, 4);         /* records */
    le(b + 16, 32, 4);        /* bytes a record */
    lef(b + 24, 0.25f);       /* accuracy */
    le(b + 28, 4, 4);         /* strata */
    le(b + 32, 4, 4);
    le(b + 36, 0x0123456789abcdefull, 8);
    le(b + 44, crc32c(b, 44), 4);
    for (i = 0; i < 2; i++) {
        unsigned char *q = b + 48 + 32 * i;
        lef(q, 1.0f + i);     /* p */
        lef(q + 4, 2.0f);
        lef(q + 8, -3.0f);
        lef(q + 12, 0.5f);    /* R */
        lef(q + 16, 0.25f);   /* E */
        lef(q + 20, 0.5f);
        lef(q + 24, 1.0f * (i + 1));
        le(q + 28, 0x80008000u, 4); /* +z, octahedral */
    }
    le(b + sizeof b - 4, crc32c(b, sizeof b - 4), 4);
    CHECK(irc_snapshot_read(c, 0x0123456789abcdefull, b, sizeof b) == IRC_OK, "read");
    CHECK(irc_cache_record(c, 1, &r) == IRC_OK && r.p[0] == 2.0f && r.p[2] == -3.0f &&
              r.radius == 0.5f && r.e[2] == 2.0f && fabs(r.n[2] - 1.0) < 1e-6,
          "record 1: p %g %g %g R %g E %g n %g", r.p[0], r.p[1], r.p[2], r.radius, r.e[2], r.n[2]);
    CHECK(irc_snapshot_write(c, 0x0123456789abcdefull, out, sizeof out, NULL, NULL, &n) ==
                  IRC_OK && n == sizeof b && memcmp(out, b, sizeof b) == 0,
          "written back differently");
    block_free(&cfg);
}
