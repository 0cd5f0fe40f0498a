/*
 * fuzz_api.c -- the public API driven by a byte string: a config (tiny or
 * odd strata, accuracy 0 or 1e9, tiny capacities, eviction on or off), then
 * up to 64 calls (compute, insert, lookup, lookup-or-compute, neighbours,
 * record, stats, clear) with hostile floats.  The host is an analytic sky
 * with a sphere whose parameters also come from the bytes.
 *
 * Invariants checked on every call (abort() on violation, which libFuzzer
 * and the replay driver report): the status is one the header documents;
 * a negative status left the block byte for byte as it was; lookups return
 * finite, non-negative values; guard bytes after the block are intact.
 */
#define IRC_EXPERIMENTAL /* irc_cache_lookup_gradient, irc_cache_neighbours */
#include <stdio.h>
#include <stdlib.h>

#include "fuzz_input.h"
#include "irrcache.h"

typedef struct host {
    float sky[3], sphere_l[3], c[3], r;
    int fail_every, calls;
} host;

static int trace(const irc_trace_args *a)
{
    host *h = (host *)a->context;
    uint32_t i;
    int k;
    for (i = 0; i < a->count; i++) {
        const float *o = a->rays[i].org, *d = a->rays[i].dir;
        irc_hit *hit = &a->hits[i];
        float oc[3] = {o[0] - h->c[0], o[1] - h->c[1], o[2] - h->c[2]};
        float b = oc[0] * d[0] + oc[1] * d[1] + oc[2] * d[2];
        float cc = oc[0] * oc[0] + oc[1] * oc[1] + oc[2] * oc[2] - h->r * h->r;
        float disc = b * b - cc, t = -b - sqrtf(disc > 0.0f ? disc : 0.0f);
        if (h->fail_every && ++h->calls % h->fail_every == 0) {
            hit->status = IRC_RAY_FAILED;
        } else if (disc > 0.0f && t > 0.0f) {
            hit->status = IRC_RAY_HIT;
            hit->dist = t;
            for (k = 0; k < 3; k++) {
                hit->normal[k] = oc[k] + t * d[k];
                hit->radiance[k] = h->sphere_l[k];
            }
        } else {
            hit->status = IRC_RAY_ESCAPED;
            for (k = 0; k < 3; k++)
                hit->radiance[k] = h->sky[k];
        }
    }
    return 0;
}

static void read_vec(fuzz_in *in, float v[3])
{
    v[0] = fz_float(in);
    v[1] = fz_float(in);
    v[2] = fz_float(in);
}

static int status_ok(int st)
{
    return st >= IRC_ERR_LAST && st <= IRC_DETAIL;
}

static void read_config(fuzz_in *in, irc_config *cfg, host *h, uint32_t *cap)
{
    /* Mostly small grids, so that a run gets deep: a 65,536-stratum
     * record costs a thousand small ones under the sanitizers, and the
     * defaults (0 x 0: 32 x 128) a hundred.  Byte values 252-255 take the
     * defaults, 1024 x 64 and 256 x 256, 1 in 64 of inputs in all (at 1
     * in 16 and 1 in 32, as before, the harness ran ~70 inputs a
     * second). */
    static const uint32_t strata[][2] = {{1, 1}, {1, 7}, {3, 1}, {2, 8}, {5, 13}, {2, 2},
                                         {4, 4}, {1, 2}, {3, 5}, {2, 3}, {6, 6}, {8, 16},
                                         {1, 3}, {4, 9}, {0, 0}, {0, 0}, {1024, 64}, {256, 256}};
    uint8_t s = fz_u8(in);
    int k;
    float px[2];
    memset(cfg, 0, sizeof *cfg);
    cfg->version = IRC_CONFIG_VERSION;
    cfg->trace = trace;
    cfg->context = h;
    cfg->features = fz_u8(in) & 127u;
    cfg->accuracy = fz_float(in);
    cfg->min_radius = fz_u8(in) & 1 ? fz_float(in) : 0.0f;
    cfg->max_radius = fz_u8(in) & 1 ? fz_float(in) : 0.0f;
    k = fz_u8(in);
    px[0] = k & 1 ? fz_float(in) : 0.0f;
    px[1] = k & 2 ? fz_float(in) : 0.0f;
    /* The irradiance kind's fields: set for SH records too in one input of
     * four, where they must be refused. */
    if (!(cfg->features & (IRC_FEATURE_SH | IRC_FEATURE_SH_GRADIENT)) || (k >> 6) == 3) {
        cfg->irr.min_pixels = px[0];
        cfg->irr.max_pixels = px[1];
        cfg->irr.leak_guard = (uint32_t)(k >> 2) % 4u;
    }
    cfg->clamp_neighbours = (uint32_t)(k >> 4) & 3u;
    cfg->strata_theta = strata[s < 252 ? s % 14u : s - 238u][0];
    cfg->strata_phi = strata[s < 252 ? s % 14u : s - 238u][1];
    cfg->max_batch = (uint32_t)(fz_u8(in) % 70);
    cfg->evict = fz_u8(in) & 1;
    cfg->seed = fz_u32(in);
    cfg->port = &irc_port_none;
    *cap = 1u + fz_u8(in) % 40u;
    for (k = 0; k < 3; k++) {
        h->sky[k] = fz_float(in);
        h->sphere_l[k] = fz_float(in);
        h->c[k] = fz_float(in);
    }
    h->r = fz_float(in);
    h->fail_every = fz_u8(in) % 5;
    h->calls = 0;
    if (cfg->features & (IRC_FEATURE_SH | IRC_FEATURE_SH_GRADIENT)) {
        cfg->sh.bands = fz_u8(in) % 7u;
        cfg->sh.channels = fz_u8(in) % 4u;
        cfg->sh.power = fz_u8(in) & 1 ? fz_float(in) : 0.0f;
    }
}

/* SH calls: a record built, inserted, looked up, read back, shaded. */
static int call_sh(fuzz_in *in, irc_cache *c, uint32_t cap, uint8_t op, const float p[3],
                   const float n[3])
{
    irc_sh sh;
    float rgb[3], w = 0.0f;
    int s, ch, i, k;
    const float *nn = fz_u8(in) & 1 ? n : NULL;
    switch (op) {
    case 8:
        s = irc_sh_compute(c, p, nn, &sh, NULL);
        break;
    case 9:
        memset(&sh, 0, sizeof sh);
        memcpy(sh.p, p, sizeof sh.p);
        if (nn)
            memcpy(sh.n, n, sizeof sh.n);
        sh.radius = fz_float(in);
        sh.bands = fz_u8(in) % 7u;
        sh.channels = fz_u8(in) % 4u;
        for (k = fz_u8(in) % 8; k > 0; k--) {
            i = fz_u8(in) % IRC_SH_MAX_COEFFS;
            sh.c[fz_u8(in) % 3][i] = fz_float(in);
            read_vec(in, sh.grad[fz_u8(in) % 3][i]);
        }
        return irc_sh_insert(c, &sh);
    case 10:
        s = fz_u8(in) & 1 ? irc_sh_lookup(c, p, nn, &sh, &w)
                          : irc_sh_lookup_or_compute(c, p, nn, &sh, &w, NULL);
        if (s >= 0)
            check(w >= 0.0f && w == w);
        break;
    default:
        s = irc_sh_record(c, fz_u8(in) % (cap + 2u), &sh);
        break;
    }
    if (s == IRC_OK) {
        for (ch = 0; ch < (int)sh.channels; ch++)
            for (i = 0; i < (int)(sh.bands * sh.bands); i++)
                check(sh.c[ch][i] == sh.c[ch][i] && sh.c[ch][i] - sh.c[ch][i] == 0.0f);
        k = irc_sh_glossy(&sh, n, fz_float(in), rgb);
        check(k == IRC_OK || k == IRC_ERR_RANGE || k == IRC_ERR_NORMAL || k == IRC_ERR_NONFINITE);
    }
    return s;
}

/* One call; returns its status. */
static int call(fuzz_in *in, irc_cache *c, uint32_t cap)
{
    float p[3], n[3], rgb[3] = {0, 0, 0}, w = 0.0f;
    irc_record rec;
    irc_stats st;
    uint32_t ids[8], cnt;
    int s, k;
    uint8_t op = fz_u8(in) % 12;
    read_vec(in, p);
    read_vec(in, n);
    if (op >= 8)
        return call_sh(in, c, cap, op, p, n);
    switch (op) {
    case 0:
        return irc_record_compute(c, p, n, &rec, NULL);
    case 1:
        memset(&rec, 0, sizeof rec);
        memcpy(rec.p, p, sizeof p);
        memcpy(rec.n, n, sizeof n);
        read_vec(in, rec.e);
        rec.radius = fz_float(in);
        if (fz_u8(in) & 1) {
            rec.minor_radius = fz_float(in);
            read_vec(in, rec.axis);
            rec.leak_guard = (uint64_t)fz_u32(in) << 32 | fz_u32(in);
        }
        read_vec(in, rec.grad_t[fz_u8(in) % 3]);
        read_vec(in, rec.grad_r[fz_u8(in) % 3]);
        return irc_cache_insert(c, &rec);
    case 2:
        if (fz_u8(in) & 1) { /* the gradient lookup answers as the lookup does */
            irc_gradient g;
            float r2[3], w2;
            const int s2 = irc_cache_lookup(c, p, n, r2, &w2);
            s = irc_cache_lookup_gradient(c, p, n, rgb, &g, &w);
            check(s == s2 && (s < 0 || (memcmp(rgb, r2, sizeof r2) == 0 && w == w2)));
            for (k = 0; k < 9 && s == IRC_OK; k++)
                check(g.dp[k / 3][k % 3] - g.dp[k / 3][k % 3] == 0.0f &&
                      g.dn[k / 3][k % 3] - g.dn[k / 3][k % 3] == 0.0f);
            return s;
        }
        /* fall through */
    case 3:
        if (op == 2)
            s = irc_cache_lookup(c, p, n, rgb, &w);
        else if (fz_u8(in) & 1)
            s = irc_cache_lookup_or_compute(c, p, n, rgb, &w, NULL);
        else { /* with a geometric normal of any value, or none */
            float ng[3];
            const int with_ng = fz_u8(in) & 1;
            if (with_ng)
                read_vec(in, ng);
            s = irc_cache_lookup_or_compute_px(c, p, n, with_ng ? ng : NULL, fz_float(in), rgb,
                                               &w, NULL);
        }
        if (s >= 0)
            for (k = 0; k < 3; k++)
                check(rgb[k] >= 0.0f && rgb[k] <= 3.4028235e38f);
        if (s >= 0)
            check(w >= 0.0f && w == w);
        return s;
    case 4:
        s = irc_cache_neighbours(c, p, n, ids, 8, &cnt);
        return s;
    case 5:
        return irc_cache_record(c, fz_u8(in) % (cap + 2u), &rec);
    case 6:
        s = irc_cache_stats(c, &st);
        check(s == IRC_OK && st.records <= cap);
        return s;
    default:
        k = fz_u8(in);
        if (k < 16)
            return irc_cache_clear(c);
        if (k < 32)
            return irc_pass_begin(c);
        if (k < 48) {
            s = irc_pass_end(c, &cnt);
            check(s != IRC_OK || cnt <= cap);
            return s;
        }
        return IRC_OK;
    }
}

/* The filled block copied to a shifted address and re-attached answers
 * as the original does: stats, and lookups at points from the input. */
static void relocated(fuzz_in *in, irc_config cfg, irc_cache *c, size_t bytes)
{
    size_t shift = 1u + fz_u8(in) % 127u;
    unsigned char *mem = (unsigned char *)malloc(bytes + 128u);
    irc_cache *copy;
    irc_stats a, b;
    int k;
    if (!mem)
        return;
    memcpy(mem + shift, cfg.buffer, bytes);
    cfg.buffer = mem + shift;
    check(irc_attach(&cfg, &copy) == IRC_OK);
    check(irc_cache_stats(c, &a) == IRC_OK && irc_cache_stats(copy, &b) == IRC_OK);
    check(a.records == b.records && a.index_nodes == b.index_nodes);
    for (k = 0; k < 4 && in->n > 0; k++) {
        float p[3], n[3], ra[3] = {0, 0, 0}, rb[3] = {0, 0, 0}, wa = 0.0f, wb = 0.0f;
        int sa, sb;
        read_vec(in, p);
        read_vec(in, n);
        if (cfg.features & (IRC_FEATURE_SH | IRC_FEATURE_SH_GRADIENT)) {
            irc_sh ha, hb;
            const float *nn = fz_u8(in) & 1 ? n : NULL;
            sa = irc_sh_lookup(c, p, nn, &ha, &wa);
            sb = irc_sh_lookup(copy, p, nn, &hb, &wb);
            check(sa != IRC_OK || memcmp(ha.c, hb.c, sizeof ha.c) == 0);
        } else {
            sa = irc_cache_lookup(c, p, n, ra, &wa);
            sb = irc_cache_lookup(copy, p, n, rb, &wb);
            check(memcmp(ra, rb, sizeof ra) == 0);
        }
        check(sa == sb && (wa == wb || wa != wa));
    }
    irc_fini(copy);
    free(mem);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fuzz_in in = {data, size};
    irc_config cfg;
    irc_cache *c;
    host h;
    uint32_t cap;
    size_t bytes;
    fz_block b;
    int ops, st, max_ops;
    read_config(&in, &cfg, &h, &cap);
    st = irc_footprint(&cfg, cap, &bytes);
    check(status_ok(st));
    if (st < 0 || bytes > (64u << 20) || fz_block_new(&b, bytes) < 0)
        return 0;
    cfg.buffer = b.block;
    cfg.buffer_size = bytes;
    check(irc_init(&cfg, cap, &c) == IRC_OK);
    /* A 65,536-stratum record takes about a second under the sanitizers,
     * and the mutations keep such inputs once they add coverage: three
     * calls on those (every call copies the 5-20 MB block too). */
    max_ops = (uint64_t)cfg.strata_theta * cfg.strata_phi > 4096u ? 3 : 64;
    for (ops = 0; ops < max_ops && in.n > 0; ops++) {
        memcpy(b.copy, b.block, bytes);
        st = call(&in, c, cap);
        if (getenv("FUZZ_TRACE"))
            fprintf(stderr, "call %d: status %d (%s)\n", ops, st, irc_strerror(st));
        check(status_ok(st));
        if (st < 0)
            check(memcmp(b.copy, b.block, bytes) == 0);
    }
    if (bytes <= (4u << 20))
        relocated(&in, cfg, c, bytes);
    irc_fini(c);
    fz_block_free(&b);
    return 0;
}
