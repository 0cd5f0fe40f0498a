/* t_attach.c -- a damaged block: every single-bit flip of a filled
 * block's first 512 bytes (the header and the start of what follows) and
 * 3,000 random flips elsewhere either make irc_attach refuse it with
 * IRC_ERR_CORRUPT or IRC_ERR_CONFIG, the block unchanged, or give a cache
 * whose lookups and computes answer (run under ASan + UBSan by make test:
 * nothing read out of bounds). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "irrcache.h"
#include "scenes.h"
#include "test.h"

/* Lookups over the plane and one compute: each must return a documented
 * status.  Returns the calls that did not. */
static int use(irc_cache *c)
{
    const float n[3] = {0, 0, 1};
    int i, bad = 0;
    for (i = 0; i < 12; i++) {
        float p[3] = {-3.0f + 0.5f * (float)i, 0.3f * (float)(i % 5) - 0.6f, 0.0f}, rgb[3], w;
        int st = irc_cache_lookup(c, p, n, rgb, &w);
        bad += st != IRC_OK && st != IRC_MISS && st != IRC_ERR_NONFINITE;
        if (i == 5) {
            st = irc_cache_lookup_or_compute(c, p, n, rgb, &w, NULL);
            bad += st < IRC_ERR_LAST || st > IRC_DETAIL;
        }
    }
    return bad;
}

TEST(test_attach_bit_flips)
{
    tscene s;
    irc_config cfg, ac;
    irc_cache *c;
    unsigned char *pristine, *damaged;
    size_t size, pad, total, bit, nbits;
    unsigned long long rng = 12345;
    int refused = 0, accepted = 0, changed = 0, misused = 0, k, step = irc_t_quick ? 7 : 1;
    irc_stats st;
    scene_sphere_plane(&s);
    cfg = scene_config(&s, IRC_FEATURE_TRANSLATION | IRC_FEATURE_ROTATION | IRC_FEATURE_HESSIAN, 4,
                       16);
    cfg.evict = IRC_EVICT_CLOCK;
    c = block_cache(&cfg, 256, 0);
    CHECK(c != NULL, "init");
    if (!c) return;
    for (k = 0; k < 150; k++) {
        const float n[3] = {0, 0, 1};
        float p[3] = {(float)(xrand(&rng) * 6.0 - 3.0), (float)(xrand(&rng) * 6.0 - 3.0), 0.0f},
              rgb[3], w;
        irc_cache_lookup_or_compute(c, p, n, rgb, &w, NULL);
    }
    CHECK(irc_cache_stats(c, &st) == IRC_OK && st.records > 40, "records %llu",
          (unsigned long long)st.records);
    size = cfg.buffer_size;
    pad = *(unsigned char *)cfg.buffer;
    total = (size_t)st.bytes_total;
    pristine = malloc(size);
    damaged = malloc(size);
    if (!pristine || !damaged) {
        CHECK(0, "malloc");
        free(pristine);
        free(damaged);
        block_free(&cfg);
        return;
    }
    memcpy(pristine, cfg.buffer, size);
    nbits = 512 * 8;
    for (k = 0; (size_t)k < nbits + 3000; k += step) {
        irc_cache *a;
        int rc;
        bit = (size_t)k < nbits ? (size_t)k
                                : 512 * 8 + (size_t)(xrand(&rng) * (double)((total - 512) * 8));
        memcpy(damaged, pristine, size);
        damaged[pad + bit / 8] ^= (unsigned char)(1u << (bit % 8));
        memcpy(cfg.buffer, damaged, size);
        ac = cfg;
        rc = irc_attach(&ac, &a);
        if (rc == IRC_OK) {
            accepted++;
            misused += use(a);
            irc_fini(a);
        } else {
            refused++;
            changed += memcmp(cfg.buffer, damaged, size) != 0;
            misused += rc != IRC_ERR_CORRUPT && rc != IRC_ERR_CONFIG && rc != IRC_ERR_NOMEM &&
                       rc != IRC_ERR_UNSUPPORTED;
        }
    }
    printf("  %d flips refused, %d attached\n", refused, accepted);
    CHECK(refused > 0 && accepted > 0, "refused %d, accepted %d", refused, accepted);
    CHECK(changed == 0, "%d refusals changed the block", changed);
    CHECK(misused == 0, "%d undocumented statuses", misused);
    /* the pristine block still attaches and answers */
    memcpy(cfg.buffer, pristine, size);
    ac = cfg;
    CHECK(irc_attach(&ac, &c) == IRC_OK && use(c) == 0, "pristine");
    free(pristine);
    free(damaged);
    block_free(&cfg);
}

/* A block copied while a pass is open in which more records were made
 * than there was room for: a valid block, which attach refused when the
 * pass still counted every attempt past its room (found by fuzz_api; its
 * input is in the corpus as crash-pass-pending-over-capacity).  The copy
 * attaches, and its pass ends with the records that found room. */
TEST(test_attach_open_pass_overfull)
{
    tscene s;
    irc_config cfg, ac;
    irc_cache *c, *a;
    unsigned char *copy;
    uint32_t added = 0;
    int i;
    scene_sphere_plane(&s);
    cfg = scene_config(&s, IRC_FEATURE_TRANSLATION | IRC_FEATURE_ROTATION, 4, 16);
    c = block_cache(&cfg, 8, 0);
    CHECK(c != NULL && irc_pass_begin(c) == IRC_OK, "init, pass");
    if (!c) return;
    for (i = 0; i < 20; i++) {
        const float p[3] = {0.3f * (float)i - 3.0f, 0.0f, 0.0f}, n[3] = {0, 0, 1};
        float rgb[3], w;
        irc_cache_lookup_or_compute(c, p, n, rgb, &w, NULL);
    }
    copy = malloc(cfg.buffer_size + 64);
    CHECK(copy != NULL, "malloc");
    if (copy) {
        memcpy(copy + 8, cfg.buffer, cfg.buffer_size);
        ac = cfg;
        ac.buffer = copy + 8;
        CHECK(irc_attach(&ac, &a) == IRC_OK && irc_pass_end(a, &added) == IRC_OK && added == 8,
              "attach a block with an overfull pass open: %u records", (unsigned)added);
        free(copy);
    }
    block_free(&cfg);
}

/* What test_attach_damaged does with an accepted block: lookups, an
 * insert, computes, a pass with computes in it, and a snapshot written
 * and read into a healthy cache.  Each must return a documented status
 * (and nothing abort or read out of bounds: make test runs this under
 * ASan + UBSan).  Returns the calls that did not. */
static int use_more(irc_cache *c, irc_cache *healthy, unsigned char *snap, size_t cap, int sh)
{
    const float n[3] = {0, 0, 1};
    size_t bytes = 0, written = 0;
    int i, st, bad = 0;
    for (i = 0; i < 8; i++) {
        float p[3] = {-3.0f + 0.8f * (float)i, 0.4f * (float)(i % 5) - 0.8f, 0.0f}, rgb[3], w;
        irc_sh out;
        if (sh) {
            st = i % 3 ? irc_sh_lookup(c, p, n, &out, &w) : irc_sh_lookup_or_compute(c, p, n, &out, &w, NULL);
        } else {
            st = i % 3 ? irc_cache_lookup(c, p, n, rgb, &w)
                       : irc_cache_lookup_or_compute(c, p, n, rgb, &w, NULL);
        }
        bad += st < IRC_ERR_LAST || st > IRC_DETAIL;
    }
    if (!sh) {
        irc_record r;
        memset(&r, 0, sizeof r);
        r.p[0] = 0.25f;
        r.n[2] = 1.0f;
        r.e[0] = r.e[1] = r.e[2] = 1.0f;
        r.radius = 0.5f;
        st = irc_cache_insert(c, &r);
        bad += st < IRC_ERR_LAST || st > IRC_DETAIL;
    }
    st = irc_pass_begin(c);
    bad += st < IRC_ERR_LAST || st > 0;
    if (st == IRC_OK) {
        for (i = 0; i < 3; i++) {
            float p[3] = {1.1f * (float)i - 1.7f, 0.9f, 0.0f}, rgb[3], w;
            irc_sh out;
            int s2 = sh ? irc_sh_lookup_or_compute(c, p, n, &out, &w, NULL)
                        : irc_cache_lookup_or_compute(c, p, n, rgb, &w, NULL);
            bad += s2 < IRC_ERR_LAST || s2 > IRC_DETAIL;
        }
        st = irc_pass_end(c, NULL);
        bad += st < IRC_ERR_LAST || st > 0;
    }
    st = irc_snapshot_size(c, &bytes);
    bad += st < IRC_ERR_LAST || st > 0;
    if (st == IRC_OK && bytes <= cap) {
        st = irc_snapshot_write(c, 7, snap, cap, NULL, NULL, &written);
        bad += st < IRC_ERR_LAST || st > 0;
        if (st == IRC_OK) {
            st = irc_snapshot_read(healthy, 7, snap, written);
            bad += st < IRC_ERR_LAST || st > 0;
        }
    }
    return bad;
}

/* Damaged blocks where users' blocks lie: every fourth bit of the first
 * 4 KiB flipped (every 17th in quick runs: make test's ASan stage; every
 * 61st in make check's) and one random bit in every 64 bytes of the rest
 * (every 256 in make check's), one at a time,
 * for each record kind and feature set (the Hessian's with clock
 * eviction, leak guards and clamping: the set that once passed irc_attach
 * and aborted the next insert), both locking ports, and blocks at several
 * offsets from a 64-byte boundary (the block pads itself to one, so the
 * bytes a flip meets differ).  Every flip is refused with a documented
 * status and the block left as it was, or the cache it gives answers
 * every call with a documented status (use_more). */
TEST(test_attach_damaged)
{
    static const struct {
        uint32_t features;
        int extras; /* clock eviction, leak guard, neighbour clamping */
    } sets[] = {
        {IRC_FEATURE_TRANSLATION | IRC_FEATURE_ROTATION | IRC_FEATURE_HESSIAN, 1},
        {IRC_FEATURE_TRANSLATION | IRC_FEATURE_ROTATION, 0},
        {IRC_FEATURE_NONE, 1},
        {IRC_FEATURE_SH | IRC_FEATURE_SH_GRADIENT, 0},
    };
    static const size_t offsets[] = {0, 8, 40};
    const irc_port *ports[] = {&irc_port_posix, &irc_port_c11};
    const size_t cap = 1u << 20;
    unsigned char *snap = malloc(cap);
    unsigned long long rng = 4242, blocks = 0, accepted = 0;
    unsigned f, o, pt;
    int misused = 0, changed = 0, step = irc_t_quick > 1 ? 61 : irc_t_quick ? 17 : 4;
    const size_t rest = irc_t_quick > 1 ? 4 : 1; /* every rest-th 64 bytes past 4 KiB */
    tscene s;
    CHECK(snap != NULL, "malloc");
    if (!snap) return;
    scene_sphere_plane(&s);
    for (f = 0; f < sizeof sets / sizeof sets[0]; f++)
        for (pt = 0; pt < 2; pt++)
            for (o = 0; o < 3; o++) {
                irc_config cfg = scene_config(&s, sets[f].features, 4, 16), ac, hc;
                const int sh = (sets[f].features & IRC_FEATURE_SH) != 0;
                unsigned char *mem, *pristine, *damaged;
                size_t bytes = 0, k, nflips;
                irc_cache *c, *healthy = NULL;
                int i;
                cfg.port = ports[pt];
                if (sets[f].extras) {
                    cfg.evict = IRC_EVICT_CLOCK;
                    cfg.irr.leak_guard = IRC_ON;
                    cfg.clamp_neighbours = IRC_ON;
                }
                if (irc_footprint(&cfg, 128, &bytes) != IRC_OK ||
                    !(mem = malloc(bytes + 128))) {
                    CHECK(0, "footprint or malloc");
                    continue;
                }
                cfg.buffer = mem + (64 - (uintptr_t)mem % 64) % 64 + offsets[o];
                cfg.buffer_size = bytes;
                hc = cfg;
                hc.buffer = NULL;
                if (irc_init(&cfg, 128, &c) != IRC_OK ||
                    !(healthy = block_cache(&hc, 128, 0))) {
                    CHECK(0, "init set %u port %u offset %u", f, pt, o);
                    free(mem);
                    continue;
                }
                for (i = 0; i < 100; i++) {
                    const float n[3] = {0, 0, 1};
                    float p[3] = {(float)(xrand(&rng) * 6.0 - 3.0),
                                  (float)(xrand(&rng) * 6.0 - 3.0), 0.0f},
                          rgb[3], w;
                    irc_sh out;
                    if (sh)
                        irc_sh_lookup_or_compute(c, p, n, &out, &w, NULL);
                    else
                        irc_cache_lookup_or_compute(c, p, n, rgb, &w, NULL);
                }
                pristine = malloc(bytes);
                damaged = malloc(bytes);
                if (!pristine || !damaged) {
                    CHECK(0, "malloc");
                    free(pristine);
                    free(damaged);
                    free(mem);
                    block_free(&hc);
                    continue;
                }
                memcpy(pristine, cfg.buffer, bytes);
                irc_fini(c); /* (which marks the block closed: the copy is open) */
                {
                    irc_cache *a;
                    int rc;
                    memcpy(cfg.buffer, pristine, bytes);
                    ac = cfg;
                    rc = irc_attach(&ac, &a);
                    CHECK(rc == IRC_OK, "set %u port %u offset %u: the pristine block: %d", f, pt, o,
                          rc);
                    if (rc == IRC_OK)
                        irc_fini(a);
                }
                nflips = (bytes < 4096 ? bytes : 4096) * 8;
                for (k = 0; k < nflips + bytes / 64; k += k < nflips ? (size_t)step : rest) {
                    const size_t bit =
                        k < nflips ? k : ((k - nflips) * 64 + (size_t)(xrand(&rng) * 64.0)) * 8 +
                                             (size_t)(xrand(&rng) * 8.0);
                    irc_cache *a;
                    int rc;
                    if (bit / 8 >= bytes)
                        continue;
                    memcpy(damaged, pristine, bytes);
                    damaged[bit / 8] ^= (unsigned char)(1u << (bit % 8));
                    memcpy(cfg.buffer, damaged, bytes);
                    ac = cfg;
                    blocks++;
                    rc = irc_attach(&ac, &a);
                    if (rc == IRC_OK) {
                        accepted++;
                        misused += use_more(a, healthy, snap, cap, sh);
                        irc_fini(a);
                    } else {
                        changed += memcmp(cfg.buffer, damaged, bytes) != 0;
                        misused += rc != IRC_ERR_CORRUPT && rc != IRC_ERR_CONFIG &&
                                   rc != IRC_ERR_NOMEM && rc != IRC_ERR_UNSUPPORTED;
                    }
                }
                free(pristine);
                free(damaged);
                free(mem);
                block_free(&hc);
            }
    printf("  %llu damaged blocks, %llu attached\n", blocks, accepted);
    CHECK(accepted > 0 && accepted < blocks, "accepted %llu of %llu", accepted, blocks);
    CHECK(changed == 0, "%d refusals changed the block", changed);
    CHECK(misused == 0, "%d undocumented statuses", misused);
    free(snap);
}
