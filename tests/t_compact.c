/* t_compact.c -- the index after a pass's end and after compaction:
 * records renumbered in walk order with every lookup bit for bit as
 * before, and a pass's end that costs what its records cost (inserted
 * into the live index, earlier records keeping their ids, renumbering
 * only as the cache grows by a quarter). */
#include <stdlib.h>
#include <string.h>

#include "block/cache.h" /* internals on purpose: lists, ids and the state */
#include "block/octa.h"
#include "index/index.h"
#include "index/layout.h"
#include "index_check.h"
#include "scenes.h"
#include "test.h"

static tscene dummy;

/* A record's bytes and CLOCK bit, to follow it across renumbering. */
typedef struct held {
    unsigned char b[32u + 25u * 3u * 4u * 4u]; /* the largest: SH, L = 5, RGB, gradients */
    int used;
} held;

static size_t held_size;

static int cmp_held(const void *a, const void *b)
{
    int d = memcmp(((const held *)a)->b, ((const held *)b)->b, held_size);
    return d ? d : ((const held *)a)->used - ((const held *)b)->used;
}

static held *hold_all(const irc_cache *c)
{
    held *h = calloc(irc__st(c)->count, sizeof *h);
    uint32_t i;
    for (i = 0; i < irc__st(c)->count; i++) {
        memcpy(h[i].b, irc__rec_at(c, i), c->rec_size);
        h[i].used = (int)(irc__used(c)[i >> 6] >> (i & 63u) & 1u);
    }
    held_size = c->rec_size;
    qsort(h, irc__st(c)->count, sizeof *h, cmp_held);
    return h;
}

/* An empty pass's end compacts: records renumbered in the index's walk
 * order (lists become runs of ids), each moved with its CLOCK bit, every
 * lookup bit for bit as before, and the index still exact afterwards,
 * eviction included. */
TEST(test_index_compact)
{
    irc_config cfg = scene_config(&dummy, IRC_FEATURE_TRANSLATION | IRC_FEATURE_ROTATION, 4, 4);
    unsigned long long st = 777;
    enum { N = 6000, Q = 3000 };
    static float before[Q][5], after[Q][5], qp[Q][3], qn[Q][3];
    uint32_t i, added = 1, seen;
    index_runs rk = {0, 0, 0};
    held *h0, *h1;
    irc_cache *c;
    cfg.evict = IRC_EVICT_CLOCK;
    c = block_cache(&cfg, N, 0);
    CHECK(c != NULL, "init");
    if (!c) return;
    index_fill(c, N, 2, &st);
    for (i = 0; i < Q; i++) {
        const irc__rec *r = irc__rec_at(c, (uint32_t)(xrand(&st) * N));
        int k;
        irc__oct_decode(r->n, qn[i]);
        for (k = 0; k < 3; k++)
            qp[i][k] = r->p[k] + (float)((xrand(&st) - 0.5) * 0.2 * r->r);
        before[i][4] = (float)irc_cache_lookup(c, qp[i], qn[i], before[i], &before[i][3]);
    }
    seen = index_runs_check(c, &irc__nodes(c)[0], &rk);
    CHECK(seen == irc__st(c)->refs_live && rk.home == N && rk.bad > N / 2,
          "filled freely, lists are scattered (%u of %u out of run)", rk.bad, seen);
    h0 = hold_all(c);
    CHECK(irc_pass_begin(c) == IRC_OK && irc_pass_end(c, &added) == IRC_OK && added == 0,
          "empty pass");
    memset(&rk, 0, sizeof rk);
    seen = index_runs_check(c, &irc__nodes(c)[0], &rk);
    CHECK(seen == irc__st(c)->refs_live && rk.home == N && rk.bad == 0,
          "after the pass: %u of %u references or homes out of run", rk.bad, seen);
    h1 = hold_all(c);
    CHECK(memcmp(h0, h1, sizeof *h0 * N) == 0, "records or CLOCK bits changed in the move");
    for (i = 0; i < Q; i++)
        after[i][4] = (float)irc_cache_lookup(c, qp[i], qn[i], after[i], &after[i][3]);
    CHECK(memcmp(before, after, sizeof before) == 0, "lookups changed");
    index_compare(c, 1000, 2, &st);
    index_fill(c, 2000, 2, &st); /* evicts a third */
    index_compare(c, 1000, 2, &st);
    free(h0);
    free(h1);
    block_free(&cfg);
}


/* The positions and normals of records [0, n), by id. */
static float (*places(const irc_cache *c, uint32_t n))[4]
{
    float(*at)[4] = malloc(sizeof *at * (n ? n : 1));
    uint32_t i;
    for (i = 0; at && i < n; i++) {
        const irc__rec *r = irc__rec_at(c, i);
        memcpy(at[i], r->p, sizeof r->p);
        memcpy(&at[i][3], &r->n, sizeof r->n);
    }
    return at;
}

/* A fill of many passes, clamping on as a renderer's cache has it.  A
 * pass's end inserts its records into the live index: every earlier
 * record keeps its id (it was renumbered every pass when the index was
 * rebuilt whole), records are renumbered only once the cache has grown by
 * a quarter since they last were (so about log(n) / log(1.25) times over
 * the fill, not once a pass), and the index stays exact: every lookup
 * finds what a scan of every record finds. */
TEST(test_pass_end_incremental)
{
    enum { PASSES = 60, EACH = 250 };
    irc_config cfg = scene_config(&dummy, IRC_FEATURE_TRANSLATION | IRC_FEATURE_ROTATION, 4, 4);
    unsigned long long st = 2024;
    uint32_t p, moved = 0, renumbered = 0, kept_bad = 0, added = 0, found = 0;
    irc_cache *c;
    cfg.clamp_neighbours = IRC_DEFAULT;
    c = block_cache(&cfg, PASSES * EACH, 0);
    CHECK(c != NULL, "init");
    if (!c) return;
    for (p = 0; p < PASSES; p++) {
        const uint32_t base = irc__st(c)->count, was = irc__st(c)->compacted;
        float(*before)[4] = places(c, base), (*after)[4];
        CHECK(irc_pass_begin(c) == IRC_OK, "pass %u begins", p);
        index_fill(c, EACH, 1, &st);
        CHECK(irc_pass_end(c, &added) == IRC_OK && added == EACH, "pass %u ends (%u added)", p,
              added);
        after = places(c, base);
        if (irc__st(c)->compacted != was) {
            renumbered++;
            CHECK(irc__st(c)->compacted == irc__st(c)->count, "renumbered all");
        } else {
            kept_bad += base && (!before || !after || memcmp(before, after, sizeof *after * base));
        }
        moved += base && before && after && memcmp(before, after, sizeof *after * base) != 0;
        free(before);
        free(after);
        if (p % 15 == 14)
            found += index_compare(c, irc_t_quick ? 300u : 1000u, 1, &st);
    }
    printf("  %u passes of %u records: renumbered at %u ends (ids moved at %u)\n", PASSES, EACH,
           renumbered, moved);
    CHECK(kept_bad == 0, "%u passes moved earlier records without renumbering", kept_bad);
    /* 250 records to 15,000 by quarters: 19 (1.25^19 = 69 > 60) */
    CHECK(renumbered >= 2 && renumbered <= 20, "renumbered at %u of %u pass ends", renumbered,
          PASSES);
    CHECK(4u * (uint64_t)irc__st(c)->count <= 5u * (uint64_t)irc__st(c)->compacted,
          "%u records, %u of them laid out", irc__st(c)->count, irc__st(c)->compacted);
    CHECK(found > 100, "the queries found records (%u)", found);
    block_free(&cfg);
}
