/*
 * fuzz_attach.c -- irc_attach on a damaged block.  The harness fills a
 * block with records by insert (byte 0 picks the config: bare, trans +
 * rot, trans + rot + Hessian with CLOCK eviction, SH), then XORs the rest
 * of the input into it from the offset in bytes 1-2 (modulo the cache's
 * size, from the cache's header on), and attaches.
 *
 * Invariants (abort() on violation): the status is a documented one; a
 * refused attach leaves the block byte for byte as it was; an attached
 * cache answers lookups, record reads and a lookup_or_compute with
 * documented statuses; guard bytes intact.
 */
#include "fuzz_input.h"
#include "irrcache.h"

static int flat_trace(const irc_trace_args *a)
{
    uint32_t i;
    for (i = 0; i < a->count; i++) {
        a->hits[i].status = IRC_RAY_ESCAPED;
        a->hits[i].radiance[0] = a->hits[i].radiance[1] = a->hits[i].radiance[2] = 1.0f;
    }
    return 0;
}

static void config(uint8_t pick, irc_config *cfg)
{
    static const uint32_t feats[4] = {
        IRC_FEATURE_NONE, 0, IRC_FEATURE_TRANSLATION | IRC_FEATURE_ROTATION | IRC_FEATURE_HESSIAN,
        IRC_FEATURE_SH | IRC_FEATURE_SH_GRADIENT};
    memset(cfg, 0, sizeof *cfg);
    cfg->version = IRC_CONFIG_VERSION;
    cfg->trace = flat_trace;
    cfg->port = &irc_port_none;
    cfg->features = feats[pick & 3];
    cfg->evict = (pick & 3) == 2 ? IRC_EVICT_CLOCK : IRC_EVICT_NONE;
    cfg->strata_theta = 2;
    cfg->strata_phi = 8;
    if (cfg->features & IRC_FEATURE_SH) {
        cfg->sh.bands = 2;
        cfg->sh.channels = 1;
    }
}

static void fill(irc_cache *c, int sh)
{
    int i;
    for (i = 0; i < 40; i++) {
        const float p[3] = {0.25f * (float)(i % 7), 0.5f * (float)(i / 7), 0.0f}, n[3] = {0, 0, 1};
        if (sh) {
            irc_sh r;
            memset(&r, 0, sizeof r);
            memcpy(r.p, p, sizeof p);
            memcpy(r.n, n, sizeof n);
            r.radius = 0.5f + 0.1f * (float)(i % 3);
            r.bands = 2;
            r.channels = 1;
            r.c[0][0] = 1.0f;
            check(irc_sh_insert(c, &r) == IRC_OK);
        } else {
            irc_record r;
            memset(&r, 0, sizeof r);
            memcpy(r.p, p, sizeof p);
            memcpy(r.n, n, sizeof n);
            r.e[0] = r.e[1] = r.e[2] = 1.0f + 0.1f * (float)i;
            r.radius = 0.5f + 0.1f * (float)(i % 3);
            check(irc_cache_insert(c, &r) == IRC_OK);
        }
    }
}

static void use(irc_cache *c, int sh)
{
    irc_stats st;
    uint32_t i;
    check(irc_cache_stats(c, &st) == IRC_OK);
    for (i = 0; i < 24; i++) {
        const float p[3] = {0.2f * (float)(i % 8), 0.4f * (float)(i / 8), 0.0f}, n[3] = {0, 0, 1};
        float rgb[3], w;
        int s;
        if (sh) {
            irc_sh r;
            s = irc_sh_lookup(c, p, n, &r, &w);
            check(s >= IRC_ERR_LAST && s <= IRC_DETAIL);
            if (i < st.records)
                check(irc_sh_record(c, i, &r) == IRC_OK);
            if (i == 3)
                check((s = irc_sh_lookup_or_compute(c, p, n, &r, &w, NULL)) >= IRC_ERR_LAST &&
                      s <= IRC_DETAIL);
            continue;
        }
        s = irc_cache_lookup(c, p, n, rgb, &w);
        check(s >= IRC_ERR_LAST && s <= IRC_DETAIL);
        if (s >= 0)
            check(isfinite(w) && w >= 0.0f);
        if (i < st.records) {
            irc_record r;
            check(irc_cache_record(c, i, &r) == IRC_OK && r.radius > 0.0f);
        }
        if (i == 3)
            check((s = irc_cache_lookup_or_compute(c, p, n, rgb, &w, NULL)) >= IRC_ERR_LAST &&
                  s <= IRC_DETAIL);
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    irc_config cfg;
    irc_cache *c;
    irc_stats st;
    fz_block b;
    size_t bytes, pad, at, i;
    int s, sh;
    if (size < 3)
        return 0;
    config(data[0], &cfg);
    sh = (cfg.features & IRC_FEATURE_SH) != 0;
    if (irc_footprint(&cfg, 64, &bytes) != IRC_OK || fz_block_new(&b, bytes) < 0)
        return 0;
    cfg.buffer = b.block;
    cfg.buffer_size = bytes;
    check(irc_init(&cfg, 64, &c) == IRC_OK);
    fill(c, sh);
    check(irc_cache_stats(c, &st) == IRC_OK);
    pad = b.block[0];
    at = ((size_t)data[1] | (size_t)data[2] << 8) % (size_t)st.bytes_total;
    for (i = 3; i < size && at + (i - 3) < (size_t)st.bytes_total; i++)
        b.block[pad + at + (i - 3)] ^= data[i];
    memcpy(b.copy, b.block, bytes);
    s = irc_attach(&cfg, &c);
    check(s == IRC_OK || s == IRC_ERR_CORRUPT || s == IRC_ERR_CONFIG || s == IRC_ERR_NOMEM ||
          s == IRC_ERR_UNSUPPORTED);
    if (s == IRC_OK)
        use(c, sh);
    else
        check(memcmp(b.copy, b.block, bytes) == 0);
    fz_block_free(&b);
    return 0;
}
