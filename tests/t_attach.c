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
            bad += st < IRC_ERR_LAST || st > IRC_NOT_STORED;
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
