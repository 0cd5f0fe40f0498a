/*
 * fuzz_snapshot.c -- the snapshot reader on the fuzzer's bytes.  Byte 0
 * picks a cache config (bare irradiance without the guard; trans + rot;
 * trans + rot + Hessian; SH L = 2, one channel, gradients) and, in bit 7,
 * whether the harness first rewrites both CRC-32C fields to match the
 * bytes (so that mutations reach the header's fields and the records'
 * values instead of dying at the checksum), in bit 6 whether it merges
 * (irc_merge) instead of reading; the rest is the snapshot.
 * The target cache holds two records of its own beforehand.
 *
 * Invariants (abort() on violation): the status is a documented one; a
 * refused read leaves the block byte for byte as it was (irc_port_none has
 * no lock object); after a read every record reads back with finite
 * fields, R > 0, E >= 0, and lookups return documented statuses with
 * finite values; guard bytes intact.
 */
#include "fuzz_input.h"
#include "irrcache.h"

static int no_trace(const irc_trace_args *a)
{
    (void)a;
    return -1;
}

static uint32_t crc32c(const uint8_t *p, size_t n)
{
    uint32_t c = 0xffffffffu;
    int k;
    while (n--)
        for (c ^= *p++, k = 0; k < 8; k++)
            c = c & 1u ? (c >> 1) ^ 0x82f63b78u : c >> 1;
    return c ^ 0xffffffffu;
}

static void put32(uint8_t *d, uint32_t v)
{
    int i;
    for (i = 0; i < 4; i++)
        d[i] = (uint8_t)(v >> (8 * i));
}

static void config(uint8_t pick, irc_config *cfg)
{
    static const uint32_t feats[4] = {
        0, IRC_FEATURE_TRANSLATION | IRC_FEATURE_ROTATION,
        IRC_FEATURE_TRANSLATION | IRC_FEATURE_ROTATION | IRC_FEATURE_HESSIAN,
        IRC_FEATURE_SH | IRC_FEATURE_SH_GRADIENT};
    memset(cfg, 0, sizeof *cfg);
    cfg->version = IRC_CONFIG_VERSION;
    cfg->trace = no_trace;
    cfg->port = &irc_port_none;
    cfg->features = feats[pick & 3];
    /* the irradiance kind's field; zero for SH records */
    cfg->irr.leak_guard = (pick & 3) == 1 || (pick & 3) == 2 ? IRC_ON : 0u;
    cfg->strata_theta = 4;
    cfg->strata_phi = 8;
    if (cfg->features & IRC_FEATURE_SH) {
        cfg->sh.bands = 2;
        cfg->sh.channels = 1;
    }
}

static void check_after(irc_cache *c, int sh)
{
    irc_stats st;
    uint32_t i;
    check(irc_cache_stats(c, &st) == IRC_OK && st.records <= 16);
    for (i = 0; i < st.records; i++) {
        float rgb[3], w;
        const float p[3] = {0.1f * (float)i, 0.0f, 0.0f}, n[3] = {0, 0, 1};
        if (sh) {
            irc_sh r;
            check(irc_sh_record(c, i, &r) == IRC_OK);
            check(isfinite(r.radius) && r.radius > 0.0f);
            check(irc_sh_lookup(c, p, n, &r, &w) >= IRC_ERR_LAST);
        } else {
            irc_record r;
            int s;
            check(irc_cache_record(c, i, &r) == IRC_OK);
            check(isfinite(r.radius) && r.radius > 0.0f && r.e[0] >= 0.0f && r.e[1] >= 0.0f &&
                  r.e[2] >= 0.0f && isfinite(r.e[0]) && isfinite(r.e[1]) && isfinite(r.e[2]));
            s = irc_cache_lookup(c, p, n, rgb, &w);
            check(s >= IRC_ERR_LAST && s <= IRC_DETAIL);
            if (s >= 0)
                check(isfinite(rgb[0]) && isfinite(rgb[1]) && isfinite(rgb[2]) && w >= 0.0f);
        }
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    irc_config cfg;
    irc_cache *c;
    fz_block b;
    uint8_t *snap;
    size_t bytes, n = size ? size - 1 : 0;
    int st, sh;
    if (!size)
        return 0;
    config(data[0], &cfg);
    sh = (cfg.features & IRC_FEATURE_SH) != 0;
    if (irc_footprint(&cfg, 16, &bytes) != IRC_OK || fz_block_new(&b, bytes) < 0)
        return 0;
    cfg.buffer = b.block;
    cfg.buffer_size = bytes;
    check(irc_init(&cfg, 16, &c) == IRC_OK);
    {   /* two records of its own */
        const float p[3] = {5, 5, 5}, n3[3] = {0, 0, 1};
        if (sh) {
            irc_sh r;
            memset(&r, 0, sizeof r);
            memcpy(r.p, p, sizeof p);
            r.radius = 1.0f;
            r.bands = 2;
            r.channels = 1;
            check(irc_sh_insert(c, &r) == IRC_OK && irc_sh_insert(c, &r) == IRC_OK);
        } else {
            irc_record r;
            memset(&r, 0, sizeof r);
            memcpy(r.p, p, sizeof p);
            memcpy(r.n, n3, sizeof n3);
            r.radius = 1.0f;
            check(irc_cache_insert(c, &r) == IRC_OK && irc_cache_insert(c, &r) == IRC_OK);
        }
    }
    snap = (uint8_t *)malloc(n ? n : 1);
    if (!snap) {
        fz_block_free(&b);
        return 0;
    }
    memcpy(snap, data + 1, n);
    if ((data[0] & 0x80) && n >= 52) {
        put32(snap + 44, crc32c(snap, 44));
        put32(snap + n - 4, crc32c(snap, n - 4));
    }
    memcpy(b.copy, b.block, bytes);
    st = data[0] & 0x40 ? irc_merge(c, 0x5eedull, snap, n)
                        : irc_snapshot_read(c, 0x5eedull, snap, n);
    check(st == IRC_OK || (st >= IRC_ERR_LAST && st < 0));
    if (st < 0)
        check(memcmp(b.copy, b.block, bytes) == 0);
    else
        check_after(c, sh);
    free(snap);
    irc_fini(c);
    fz_block_free(&b);
    return 0;
}
