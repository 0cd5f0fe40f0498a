/* t_index_shape.c -- the octree's shape: growth, bulk spread, roots refused, far scenes. */
#define IRC_EXPERIMENTAL /* irc_cache_neighbours, irc_join (irrcache.h) */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "block/cache.h" /* internals on purpose: the tree's nodes and root */
#include "index/index.h"
#include "index/layout.h"
#include "scenes.h"
#include "test.h"
#include "index_check.h"
#include "index/verify.h"

static tscene dummy;

/* A root that grows becomes a child of the new root, and every record of
 * its subtree must stay where removal looks for it.  A record on the face
 * the old root shares with a new sibling was not: the octant rule sends
 * such a point to the sibling, removal (an eviction) did not find it, and
 * its entry stayed linked while its slot took another record (found by
 * t_kill.c's eviction fill on a lattice with rows on y = 0).  Here: a
 * cluster on every face of its fitted root, growth on every axis both
 * ways, then every record evicted, twice over. */
TEST(test_index_grow_faces)
{
    static const float far[6][3] = {{9, .75f, .75f}, {-9, .75f, .75f}, {.75f, 9, .75f},
                                    {.75f, -9, .75f}, {.75f, .75f, 9}, {.75f, .75f, -9}};
    irc_config cfg = scene_config(&dummy, 0, 4, 4);
    irc_record r;
    irc_stats st;
    irc_cache *c;
    uint32_t i, seen, lost = 0;
    index_runs k = {0, 0, 0};
    cfg.evict = IRC_EVICT_CLOCK;
    c = block_cache(&cfg, 40, 0);
    CHECK(c != NULL, "init");
    if (!c) return;
    memset(&r, 0, sizeof r);
    r.n[2] = 1.0f;
    r.e[0] = r.e[1] = r.e[2] = 1.0f;
    r.radius = 0.01f;
    for (i = 0; i < 27 + 6 + 80; i++) {
        uint32_t ids[4], n;
        const float up[3] = {0, 0, 1};
        if (i < 27) {
            r.p[0] = 0.5f + 0.25f * (float)(i % 3);
            r.p[1] = 0.5f + 0.25f * (float)(i / 3 % 3);
            r.p[2] = 0.5f + 0.25f * (float)(i / 9);
        } else if (i < 33) {
            memcpy(r.p, far[i - 27], sizeof r.p);
        } else {
            r.p[0] = (float)(i % 7) * 3.0f - 9.0f;
            r.p[1] = (float)(i / 7 % 7) * 3.0f - 9.0f;
            r.p[2] = 0.5f * (float)(i % 2);
        }
        CHECK(irc_cache_insert(c, &r) == IRC_OK, "insert %u", i);
        lost += irc_cache_neighbours(c, r.p, up, ids, 4, &n) != IRC_OK || n != 1;
    }
    seen = index_runs_check(c, &irc__nodes(c)[0], &k);
    CHECK(irc_cache_stats(c, &st) == IRC_OK && st.records == 40 && k.home == 40 &&
              seen == irc__st(c)->refs_live && irc__block_sane(c) &&
              st.evictions == 27 + 6 + 80 - 40 && lost == 0,
          "%u homes in the index for %u records, %u not found", k.home, (unsigned)st.records,
          lost);
    block_free(&cfg);
}

/* A record on one of the unit box's faces, radius log-uniform around the
 * spacing of `count` records (bench/lookups.c's workload). */
static void box_record(unsigned long long *st, uint32_t count, irc_record *r)
{
    const int f = (int)(xrand(st) * 6.0), ax = f / 2;
    const double reach = sqrt(36.0 / (3.14159265 * count));
    memset(r, 0, sizeof *r);
    r->p[ax] = f % 2 ? 0.5f : -0.5f;
    r->p[(ax + 1) % 3] = (float)(xrand(st) - 0.5);
    r->p[(ax + 2) % 3] = (float)(xrand(st) - 0.5);
    r->n[ax] = f % 2 ? 1.0f : -1.0f;
    r->e[0] = r->e[1] = r->e[2] = 1.0f;
    r->radius = (float)(reach / 0.2 * exp((xrand(st) - 0.5) * 1.4));
}

static void count_one(void *ud, uint32_t id)
{
    (void)id;
    ++*(uint32_t *)ud;
}

/* Index entries 2,000 queries on the box scan. */
static uint64_t scanned(irc_cache *c)
{
    unsigned long long st = 99;
    uint64_t total = 0;
    uint32_t i, passed = 0;
    irc_record q;
    for (i = 0; i < 2000; i++) {
        box_record(&st, 1000, &q);
        total += irc__index_query(c, q.p, count_one, &passed);
    }
    return total;
}

/* The bulk paths (a pass's end, a merge) index records that come in space
 * order: inserted in that order they spent the node pool on the first
 * part of the scene, and a lookup scanned up to 8x the entries of a
 * random-order fill (compact.c, irc__index_rebuild).  Exactness is the
 * other tests'; here the entries scanned, a count, not a time. */
TEST(test_index_bulk_spread)
{
    const uint32_t n = 20000;
    irc_config a = scene_config(&dummy, IRC_FEATURE_TRANSLATION | IRC_FEATURE_ROTATION, 4, 4), b, d;
    a.clamp_neighbours = IRC_DEFAULT; /* on, as a renderer's cache has it */
    b = a;
    d = a;
    irc_cache *ca = block_cache(&a, n, 0), *cb = block_cache(&b, n, 0), *cd = block_cache(&d, n, 0);
    unsigned long long st = 7;
    uint64_t free_fill, pass, merged;
    size_t bytes = 0;
    unsigned char *snap;
    uint32_t i;
    CHECK(ca && cb && cd, "three caches");
    if (!ca || !cb || !cd)
        return;
    CHECK(irc_pass_begin(cb) == IRC_OK, "pass");
    for (i = 0; i < n; i++) {
        irc_record r;
        box_record(&st, n, &r);
        CHECK(irc_cache_insert(ca, &r) == IRC_OK && irc_cache_insert(cb, &r) == IRC_OK, "insert");
    }
    CHECK(irc_pass_end(cb, NULL) == IRC_OK, "pass end");
    irc_snapshot_size(cb, &bytes);
    snap = (unsigned char *)malloc(bytes);
    CHECK(snap && irc_snapshot_write(cb, 1, snap, bytes, NULL, NULL, NULL) == IRC_OK &&
              irc_merge(cd, 1, snap, bytes) == IRC_OK,
          "the pass's records, in index order, merged into an empty cache");
    free_fill = scanned(ca);
    pass = scanned(cb);
    merged = scanned(cd);
    printf("  entries scanned a query: free fill %.1f, after a pass %.1f, after a merge %.1f\n",
           free_fill / 2000.0, pass / 2000.0, merged / 2000.0);
    CHECK(pass <= free_fill * 3 / 2 && merged <= free_fill * 3 / 2,
          "a bulk index scans %llu and %llu entries where a random-order fill scans %llu",
          (unsigned long long)pass, (unsigned long long)merged, (unsigned long long)free_fill);
    free(snap);
    block_free(&a);
    block_free(&b);
    block_free(&d);
}

/* What the walk relies on of the root (query.c, irc__index_root_sane) is
 * checked when a block is attached: a root centre off its grid, or farther
 * than 33 half edges from the origin, is refused, the block unchanged. */
TEST(test_index_root_refused)
{
    irc_config cfg = scene_config(&dummy, IRC_FEATURE_TRANSLATION | IRC_FEATURE_ROTATION, 4, 4), ac;
    irc_cache *c = block_cache(&cfg, 1000, 0), *a;
    unsigned long long st = 5;
    int k;
    CHECK(c != NULL, "init");
    if (!c) return;
    index_fill(c, 1000, 0, &st);
    CHECK(irc__index_root_sane(c), "the root a fill makes");
    for (k = 0; k < 3; k++) {
        const double was = irc__st(c)->root_c[0];
        unsigned char *copy = malloc(cfg.buffer_size);
        irc__st(c)->root_c[0] = k == 0 ? 40.0 * irc__st(c)->root_h : k == 1 ? was + irc__st(c)->root_h * 0x1p-40 : 1e300;
        memcpy(copy, cfg.buffer, cfg.buffer_size);
        ac = cfg;
        CHECK(irc_attach(&ac, &a) == IRC_ERR_CORRUPT, "root %d attached", k);
        CHECK(memcmp(copy, cfg.buffer, cfg.buffer_size) == 0, "root %d: block changed", k);
        {
            /* irc_join checks a block as irc_attach does (irrcache.h) */
            static double view[IRC_VIEW_BYTES / sizeof(double)];
            irc_cache *v;
            ac = cfg;
            CHECK(irc_join(&ac, view, sizeof view, &v) == IRC_ERR_CORRUPT, "root %d joined", k);
        }
        irc__st(c)->root_c[0] = was;
        free(copy);
    }
    {
        /* irrcache.h: irc_attach refuses an older layout's block (0.3's,
         * layout 19) and another ABI's (pointer width), block unchanged */
        const uint32_t abi = c->abi;
        unsigned char *copy = malloc(cfg.buffer_size);
        for (k = 0; k < 2; k++) {
            /* layout 19; pointers of 4 bytes where they were 8 (or 8 where 4) */
            c->abi = k == 0 ? abi - 1u : abi ^ (12u << 8);
            memcpy(copy, cfg.buffer, cfg.buffer_size);
            ac = cfg;
            CHECK(irc_attach(&ac, &a) == IRC_ERR_CONFIG, "%s attached",
                  k == 0 ? "an older layout" : "another ABI");
            CHECK(memcmp(copy, cfg.buffer, cfg.buffer_size) == 0, "abi %d: block changed", k);
        }
        c->abi = abi;
        free(copy);
    }
    ac = cfg;
    CHECK(irc_attach(&ac, &a) == IRC_OK, "the block as it was");
    block_free(&cfg);
}

/* A scene away from the origin, where users put theirs: 4,000 records on
 * a unit square at 1000 (and at -100, -5000, and the origin for
 * comparison), radii so that about six reach a point.  The index must
 * split there as at the origin: a root at |centre| near 32 half edges
 * once clamped every box's far end and placed every record in the root's
 * one list (a lookup scanned all 4,000: bench-core's "1000-away" row ran
 * 4,214 lookups a second against 734,104 at the origin).  (Farther out,
 * boxes widen by the 1e-6 |p| that float positions need, index.c: at
 * 1e5 the reach here is 3 ulps and a lookup scans 17x the references.) */
TEST(test_index_far_from_origin)
{
    static const double at[] = {0.0, 1000.0, -100.0, -5000.0};
    irc_config cfg = scene_config(&dummy, IRC_FEATURE_TRANSLATION | IRC_FEATURE_ROTATION, 4, 4);
    unsigned w;
    uint64_t at_origin = 0;
    cfg.accuracy = 0.2f;
    for (w = 0; w < sizeof at / sizeof at[0]; w++) {
        irc_cache *c = block_cache(&cfg, 4000, 0);
        unsigned long long st = 5;
        uint64_t total = 0;
        uint32_t i, passed = 0;
        int ins;
        irc_stats s;
        irc_record r;
        CHECK(c != NULL, "init");
        if (!c) return;
        memset(&r, 0, sizeof r);
        r.n[2] = 1.0f;
        r.e[0] = r.e[1] = r.e[2] = 1.0f;
        for (i = 0, ins = IRC_OK; i < 4000 && ins == IRC_OK; i++) {
            r.p[0] = (float)(at[w] + xrand(&st));
            r.p[1] = (float)(at[w] + xrand(&st));
            r.p[2] = (float)at[w];
            r.radius = (float)(sqrt(6.0 / (3.14159265 * 4000.0)) / 0.2); /* a = 0.2 */
            ins = irc_cache_insert(c, &r);
        }
        CHECK(ins == IRC_OK, "at %g: insert %u: %s", at[w], i, irc_strerror(ins));
        for (i = 0; i < 2000; i++) {
            const float p[3] = {(float)(at[w] + xrand(&st)), (float)(at[w] + xrand(&st)),
                                (float)at[w]};
            total += irc__index_query(c, p, count_one, &passed);
        }
        irc_cache_stats(c, &s);
        printf("  at %g: %llu nodes, %.1f references scanned a lookup\n", at[w],
               (unsigned long long)s.index_nodes, (double)total / 2000.0);
        if (w == 0)
            at_origin = total;
        CHECK(s.index_nodes > 1, "at %g: the index never split", at[w]);
        CHECK(total <= 2 * at_origin + 2000, "at %g: %.1f references a lookup, %.1f at the origin",
              at[w], (double)total / 2000.0, (double)at_origin / 2000.0);
        block_free(&cfg);
    }
}
