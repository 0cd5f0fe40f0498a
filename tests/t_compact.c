/* t_compact.c -- the index after a pass's end and after compaction:
 * records renumbered in walk order with every lookup bit for bit as
 * before, and a pass's end that costs what its records cost (inserted
 * into the live index, earlier records keeping their ids, renumbering
 * only as the cache grows by a quarter). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "block/cache.h" /* internals on purpose: lists, ids and the state */
#include "block/octa.h"
#include "index/cells.h"
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

/* References whose reach bound passes what their record's radius now
 * needs: rq above ceil(a R / step) + 1, step = h / 16383.75 of the node's
 * cube (layout.h), counted over the subtree of node n (depth d, low corner
 * lo in the root's units). */
static uint32_t loose_refs(const irc_cache *c, uint32_t n, int d, const int64_t lo[3],
                           uint32_t *seen)
{
    const irc__node *nd = &irc__nodes(c)[n];
    irc__cube q;
    uint32_t r, loose = 0, o;
    irc__cell_cube(c, lo, d, &q);
    for (r = nd->head; r != IRC__NIL; r = irc__refs(c)[r].next) {
        const irc__ref *e = &irc__refs(c)[r];
        const irc__rec *rec = irc__rec_at(c, e->id & ~IRC__REF_HOME);
        const double need = ceil((double)c->reach_a * rec->r * 16383.75 / q.h) + 1.0;
        if (e->rq == IRC__IX_ANY)
            continue;
        (*seen)++;
        loose += (double)e->rq > need;
    }
    for (o = 0; nd->child && o < 8; o++) {
        int64_t at[3];
        int i;
        for (i = 0; i < 3; i++)
            at[i] = lo[i] + ((o >> i & 1) ? IRC__ONE >> (d + 1) : 0);
        loose += loose_refs(c, nd->child + o, d + 1, at, seen);
    }
    return loose;
}

/* Neighbour clamping shrinks the radii of records already indexed (its
 * back pass).  Their references keep their nodes but must bound the
 * radius they have now, not the one they were placed with: else every
 * lookup near them fetches records that no longer reach it (36% of the
 * records fetched on the atrium at a = 0.4 once passes stopped rebuilding
 * the index).  Filled in passes and freely, clamping on: no reference's
 * bound exceeds its record's reach now by more than a step, and the
 * index is still exact. */
TEST(test_index_reach_tight)
{
    irc_config cfg = scene_config(&dummy, IRC_FEATURE_TRANSLATION | IRC_FEATURE_ROTATION, 4, 4);
    unsigned long long st = 31337;
    const int64_t lo[3] = {0, 0, 0};
    int mode;
    cfg.clamp_neighbours = IRC_DEFAULT;
    for (mode = 0; mode < 2; mode++) {
        irc_cache *c = block_cache(&cfg, 12000, 0);
        uint32_t p, seen = 0, loose;
        CHECK(c != NULL, "init");
        if (!c) return;
        for (p = 0; p < 40; p++) {
            if (mode)
                CHECK(irc_pass_begin(c) == IRC_OK, "pass");
            index_fill(c, 300, 1, &st);
            if (mode)
                CHECK(irc_pass_end(c, NULL) == IRC_OK, "pass end");
        }
        loose = loose_refs(c, 0, 0, lo, &seen);
        printf("  %s: %u of %u references bound more than their record's reach now\n",
               mode ? "in passes" : "filled freely", loose, seen);
        CHECK(seen > 12000 && loose == 0, "%s: %u of %u references loose",
              mode ? "passes" : "free fill", loose, seen);
        CHECK(index_compare(c, irc_t_quick ? 300u : 2000u, 1, &st) > 50, "lookups found records");
        block_free(&cfg);
    }
}
