/*
 * fuzz_callback.c -- the host's answers come from the fuzzer: every ray's
 * status (hit, escaped, failed, or a value no status has), distance,
 * normal and radiance, and the callback's return code, are read from the
 * bytes (a pattern of up to 64 answers, repeated).  A config (irradiance
 * or SH features, small strata, batches of 1 to 64 rays) and up to 16
 * record computations and lookups-or-computes at fuzzed points follow.
 *
 * Invariants (abort() on violation): the status is a documented one or the
 * host's own negative code; a negative status left the block byte for byte
 * as it was (the lock object excepted: irc_port_none has none); a record
 * that comes back has finite fields, E >= 0, R > 0, finite SH
 * coefficients; guard bytes intact.
 */
#include <stdio.h>
#include <stdlib.h>

#include "fuzz_input.h"
#include "irrcache.h"

#define ANSWERS 64
#define HOST_CODE (-7777)

typedef struct answer {
    int status;
    float dist, normal[3], radiance[3];
} answer;

typedef struct host {
    answer a[ANSWERS];
    int n, next, code_every, calls;
} host;

static int trace(const irc_trace_args *args)
{
    host *h = (host *)args->context;
    uint32_t i;
    if (h->code_every && ++h->calls % h->code_every == 0)
        return h->code_every & 1 ? HOST_CODE : 1; /* a host code, or nonsense */
    for (i = 0; i < args->count; i++) {
        const answer *a = &h->a[h->next++ % h->n];
        irc_hit *hit = &args->hits[i];
        int k;
        if (a->status == 9)
            continue; /* left untouched */
        hit->status = a->status;
        hit->dist = a->dist;
        for (k = 0; k < 3; k++) {
            hit->normal[k] = a->normal[k];
            hit->radiance[k] = a->radiance[k];
        }
    }
    return 0;
}

static int fin(float x)
{
    return x == x && x - x == 0.0f;
}

static void read_host(fuzz_in *in, host *h)
{
    int i, k;
    h->n = 1 + fz_u8(in) % ANSWERS;
    h->next = h->calls = 0;
    h->code_every = fz_u8(in) % 8 == 0 ? 1 + fz_u8(in) % 40 : 0;
    for (i = 0; i < h->n; i++) {
        answer *a = &h->a[i];
        uint8_t s = fz_u8(in);
        a->status = s < 150 ? IRC_RAY_HIT : s < 220 ? IRC_RAY_ESCAPED : s < 245 ? IRC_RAY_FAILED
                                                                              : s % 2 ? 9 : 7;
        a->dist = fz_float(in);
        for (k = 0; k < 3; k++) {
            a->normal[k] = fz_float(in);
            a->radiance[k] = fz_float(in);
        }
    }
}

static void check_record(const irc_record *r)
{
    int c, k;
    for (c = 0; c < 3; c++) {
        check(fin(r->e[c]) && r->e[c] >= 0.0f);
        for (k = 0; k < 3; k++)
            check(fin(r->grad_t[c][k]) && fin(r->grad_r[c][k]));
    }
    check(fin(r->radius) && r->radius > 0.0f);
}

static void check_sh(const irc_sh *s)
{
    uint32_t c, i;
    for (c = 0; c < s->channels; c++)
        for (i = 0; i < s->bands * s->bands; i++)
            check(fin(s->c[c][i]) && fin(s->grad[c][i][0]) && fin(s->grad[c][i][1]) &&
                  fin(s->grad[c][i][2]));
    check(fin(s->radius) && s->radius >= 0.0f);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static const uint32_t strata[][2] = {{1, 1}, {2, 3}, {4, 8}, {3, 17}, {8, 16}, {16, 4}, {1, 64}, {6, 6}};
    static const uint32_t feats[] = {0, 1, 2, 3, 5, 7, 8, 24};
    fuzz_in in = {data, size};
    irc_config cfg;
    irc_cache *c;
    host h;
    size_t bytes;
    fz_block b;
    uint8_t s;
    int ops, st;
    memset(&cfg, 0, sizeof cfg);
    cfg.version = IRC_CONFIG_VERSION;
    s = fz_u8(&in);
    cfg.trace = trace;
    cfg.context = &h;
    cfg.features = feats[s & 7];
    cfg.strata_theta = strata[(s >> 3) & 7][0];
    cfg.strata_phi = strata[(s >> 3) & 7][1];
    cfg.max_batch = 1 + fz_u8(&in) % 64;
    cfg.sh.bands = (cfg.features & 8) ? 1 + fz_u8(&in) % 5 : 0;
    cfg.port = &irc_port_none;
    cfg.seed = fz_u8(&in);
    read_host(&in, &h);
    if (irc_footprint(&cfg, 8, &bytes) < 0 || fz_block_new(&b, bytes) < 0)
        return 0;
    cfg.buffer = b.block;
    cfg.buffer_size = bytes;
    check(irc_init(&cfg, 8, &c) == IRC_OK);
    for (ops = 0; ops < 16 && in.n > 0; ops++) {
        float p[3], n[3], rgb[3], w;
        irc_record r;
        irc_sh sh;
        uint8_t op = fz_u8(&in);
        p[0] = fz_float(&in);
        p[1] = fz_float(&in);
        p[2] = fz_float(&in);
        n[0] = fz_float(&in);
        n[1] = fz_float(&in);
        n[2] = 1.0f;
        memcpy(b.copy, b.block, bytes);
        if (cfg.features & 8) {
            const float *nn = op & 2 ? n : NULL;
            st = op & 1 ? irc_sh_compute(c, p, nn, &sh, NULL) : irc_sh_lookup_or_compute(c, p, nn, &sh, &w, NULL);
            if (st >= 0)
                check_sh(&sh);
        } else if (op & 1) {
            st = irc_record_compute(c, p, n, &r, NULL);
            if (st >= 0)
                check_record(&r);
        } else {
            st = irc_cache_lookup_or_compute(c, p, n, rgb, &w, NULL);
            if (st >= 0)
                check(fin(rgb[0]) && fin(rgb[1]) && fin(rgb[2]) && rgb[0] >= 0.0f);
        }
        check(st == HOST_CODE || (st >= IRC_ERR_LAST && st <= IRC_DETAIL));
        if (st < 0)
            check(memcmp(b.copy, b.block, bytes) == 0);
    }
    irc_fini(c);
    fz_block_free(&b);
    return 0;
}
