/*
 * kind_occ.c -- a third record kind, built only into the test binary:
 * records of plain openness (the cosine-weighted fraction of a hemisphere's
 * rays that escape, no gradients), with one part of their own (the counts
 * of hit and cast rays).  It shows what a kind is: this file, one line in
 * the registry (the tests compile src/kinds.c with IRC_KIND_EXTRA), one
 * line in the Makefile.  Its calls go through the store as the library's
 * kinds' do; the tests below check its records against a closed form and
 * its lookups, snapshots and re-attach against the store's contracts.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "block/cache.h"
#include "sample/sampler.h"
#include "block/octa.h"
#include "irr/weight.h"
#include "scenes.h"
#include "test.h"
#include "block/check.h"
#include "base/kind.h"
#include "sample/grid.h"
#include "store/lookup.h"
#include "store/store.h"
#include "store/walk.h"

#define OCC_FEATURE (1u << 16) /* a bit no library kind claims */
#define OCC_ID 3u
enum { OCC_P_COUNTS }; /* its one part */

/* The kind's public record. */
typedef struct occ_record {
    float p[3], n[3];
    float open;       /* escaped rays' share, cosine-weighted: E / (pi L)
                         under a uniform sky of radiance L */
    float radius;     /* Ward's split sphere: the harmonic mean hit distance */
    uint32_t hits, rays;
} occ_record;

static int occ_make(irc__call *k, void *rec)
{
    occ_record *o = (occ_record *)rec;
    const irc_cache *c = k->c;
    const irc__sample *s = (const irc__sample *)(void *)k->slot;
    float t1[3], t2[3], r;
    double inv = 0.0;
    uint32_t i, used = 0, open = 0;
    irc__grid g;
    int st;
    irc__grid_at(c, 0, &g);
    if ((st = irc__hemisphere(k, &g, t1, t2, 0)) < 0)
        return st;
    memset(o, 0, sizeof *o);
    for (i = 0; i < c->strata; i++) {
        if (s[i].d != s[i].d)
            continue; /* the host failed this ray */
        used++;
        if (s[i].d == HUGE_VALF) {
            open++;
        } else {
            o->hits++;
            inv += 1.0 / s[i].d;
        }
    }
    if (used == 0)
        return IRC_ERR_NOSAMPLES;
    r = inv > 0.0 ? (float)(used / inv) : c->cfg.max_radius;
    r = r < c->cfg.min_radius ? c->cfg.min_radius : r > c->cfg.max_radius ? c->cfg.max_radius : r;
    o->radius = r < FLT_MIN ? FLT_MIN : r;
    o->open = (float)open / (float)used;
    o->rays = used;
    for (i = 0; i < 3; i++) {
        o->p[i] = k->q.p[i];
        o->n[i] = k->q.n[i];
    }
    return IRC_OK;
}

static int occ_check(const irc_cache *c, const void *rec, float un[3])
{
    const occ_record *o = (const occ_record *)rec;
    int st;
    (void)c;
    if ((st = irc__check_vec(o->p)) < 0 || (st = irc__check_normal(o->n, un)) < 0)
        return st;
    if (!(o->open >= 0.0f && o->open <= 1.0f) || !(o->radius > 0.0f && o->radius < HUGE_VALF))
        return IRC_ERR_NONFINITE;
    return IRC_OK;
}

static void occ_pack(const irc_cache *c, const void *rec, const float un[3], void *dst)
{
    const occ_record *o = (const occ_record *)rec;
    irc__rec *h = (irc__rec *)dst;
    uint32_t counts[2];
    memcpy(h->p, o->p, sizeof h->p);
    h->r = o->radius;
    h->e[0] = h->e[1] = h->e[2] = o->open;
    h->n = irc__oct_encode(un);
    counts[0] = o->hits;
    counts[1] = o->rays;
    memcpy((unsigned char *)dst + c->off[OCC_P_COUNTS], counts, sizeof counts);
}

static void occ_unpack(const irc_cache *c, const void *src, void *rec)
{
    const irc__rec *h = (const irc__rec *)src;
    occ_record *o = (occ_record *)rec;
    uint32_t counts[2];
    memcpy(o->p, h->p, sizeof o->p);
    irc__oct_decode(h->n, o->n);
    o->radius = h->r;
    o->open = h->e[0];
    memcpy(counts, (const unsigned char *)src + c->off[OCC_P_COUNTS], sizeof counts);
    o->hits = counts[0];
    o->rays = counts[1];
}

static void occ_answer(const irc_cache *c, const void *rec, void *out)
{
    (void)c;
    *(float *)out = ((const occ_record *)rec)->open;
}

/* Ward-Heckbert weights, no ellipse or guard (weight.c). */
static int occ_weigh(const irc_cache *c, const irc__rec *r, const irc__query *q, float *w,
                     float ni[3])
{
    return irc__weigh(c, r, q->p, q->n, 0, w, ni);
}

static void occ_begin(const irc_cache *c, void *acc)
{
    (void)c;
    *(double *)acc = 0.0;
}

static void occ_accumulate(const irc_cache *c, const irc__rec *r, const irc__query *q, float w,
                           const float ni[3], void *acc)
{
    (void)c; (void)q; (void)ni;
    *(double *)acc += (double)w * r->e[0];
}

static int occ_finish(const irc_cache *c, const irc__query *q, const void *acc, float w,
                      void *out)
{
    (void)c; (void)q;
    if (!(w > 0.0f))
        return IRC_MISS;
    *(float *)out = (float)(*(const double *)acc / w);
    return IRC_OK;
}

static const irc__acc occ_lookup_ops;

static int occ_find(irc_cache *c, const irc__query *q, void *out, float *weight)
{
    double acc;
    return irc__lookup_once(c, &occ_lookup_ops, q, out, weight, &acc);
}

static const irc__acc occ_lookup_ops = {.weigh = occ_weigh,
    .begin = occ_begin,
    .accumulate = occ_accumulate,
    .finish = occ_finish,
    .find = occ_find};

/* Its feature alone; no neighbour clamping or confirming rays unless
 * asked. */
static int occ_resolve(irc_config *cfg)
{
    if (cfg->features != OCC_FEATURE)
        return IRC_ERR_CONFIG;
    irc__switch_defaults(cfg, IRC_OFF, IRC_OFF);
    return IRC_OK;
}

static uint32_t occ_parts(const irc_config *cfg, irc__recpart *out)
{
    static const irc__recpart counts = {OCC_P_COUNTS, 4, 4, IRC__SANE_ANY, 0, 8};
    (void)cfg;
    out[0] = counts;
    return 1;
}

static void occ_scratch(const irc_config *cfg, irc__scratch *s)
{
    s->samples = cfg->strata_theta * cfg->strata_phi;
}

const irc__kind irc__kind_occ = {
    .id = OCC_ID,
    .features = OCC_FEATURE,
    .record_bytes = (uint32_t)sizeof(occ_record),
    .resolve = occ_resolve,
    .parts = occ_parts,
    .scratch = occ_scratch,
    .compute = occ_make,
    .check = occ_check,
    .pack = occ_pack,
    .unpack = occ_unpack,
    .answer = occ_answer,
    .lookup = &occ_lookup_ops};

/* The kind's calls, as a public header would declare them. */
static int occ_compute(irc_cache *c, const float p[3], const float n[3], occ_record *out)
{
    return irc__compute(c, &irc__kind_occ, p, n, out, NULL, occ_make, 1);
}
static int occ_lookup(irc_cache *c, const float p[3], const float n[3], float *open, float *w)
{
    return irc__lookup(c, &irc__kind_occ, &occ_lookup_ops, p, n, open, w);
}
static int occ_lookup_or_compute(irc_cache *c, const float p[3], const float n[3], float *open)
{
    return irc__lookup_or_compute(c, &irc__kind_occ, p, n, open, NULL, NULL);
}
static int occ_record_get(irc_cache *c, uint32_t id, occ_record *out)
{
    return irc__record_get(c, &irc__kind_occ, id, out);
}

/* Under a uniform sky of radiance 1 with a black sphere above the plane,
 * E = pi (1 - r^2 cos(theta) / d^2) (scenes.h): openness E / pi. */
TEST(test_kind_occ_records)
{
    tscene s;
    irc_config cfg;
    irc_cache *c;
    double worst = 0.0;
    int i;
    scene_sphere_plane(&s);
    cfg = scene_config(&s, OCC_FEATURE, 16, 64);
    c = block_cache(&cfg, 64, 0);
    CHECK(c != NULL, "an occlusion cache");
    if (!c)
        return;
    for (i = 0; i < 25; i++) {
        const float p[3] = {-1.5f + 0.75f * (float)(i % 5), -1.5f + 0.75f * (float)(i / 5), 0.0f},
                    n[3] = {0.0f, 0.0f, 1.0f};
        const double pd[3] = {p[0], p[1], p[2]};
        occ_record o;
        int st = occ_compute(c, p, n, &o);
        double want = sphere_plane_e(&s, pd) / TPI;
        CHECK(st == IRC_OK, "compute: %s", irc_strerror(st));
        CHECK(o.rays == 1024u && o.hits > 0u && o.hits < 1024u, "rays %u, hits %u", o.rays, o.hits);
        CHECK(fabs(o.open - (1.0 - (double)o.hits / o.rays)) < 1e-6, "open %g, hits %u", o.open, o.hits);
        if (fabs(o.open - want) > worst)
            worst = fabs(o.open - want);
        /* Solid-angle rows (uniform sampling) would read 0.87 under the
         * sphere's centre where the closed form says 0.75. */
        CHECK(fabs(o.open - want) < 0.01, "open %g at (%g, %g), closed form %g", o.open, p[0],
              p[1], want);
        CHECK(o.radius > 0.5f && o.radius < HUGE_VALF, "radius %g", o.radius);
    }
    printf("  openness of 25 records within %.4f of the closed form\n", worst);
    block_free(&cfg);
}

/* A lookup is the Ward-Heckbert mean of the records within reach, which
 * the test recomputes in double from the records themselves: w = 1 /
 * (|p - p_i|/R_i + sqrt(1 - n.n_i)), the record's normal as stored (its
 * octahedral code is within 2e-5 of +z). */
TEST(test_kind_occ_lookups)
{
    tscene s;
    irc_config cfg;
    irc_cache *c;
    irc_stats st;
    uint32_t id;
    int i, misses = 0;
    scene_sphere_plane(&s);
    cfg = scene_config(&s, OCC_FEATURE, 8, 32);
    cfg.accuracy = 0.3f;
    cfg.max_radius = 1.0f; /* the open sky's rays make R large */
    c = block_cache(&cfg, 2000, 0);
    CHECK(c != NULL, "an occlusion cache");
    if (!c)
        return;
    for (i = 0; i < 400; i++) {
        const float p[3] = {-2.0f + 0.2f * (float)(i % 20), -2.0f + 0.2f * (float)(i / 20), 0.0f},
                    n[3] = {0.0f, 0.0f, 1.0f};
        float open;
        CHECK(occ_lookup_or_compute(c, p, n, &open) == IRC_OK, "lookup or compute");
    }
    CHECK(irc_cache_stats(c, &st) == IRC_OK && st.records > 20u && st.records < 400u,
          "records %llu", (unsigned long long)st.records);
    for (i = 0; i < 300; i++) {
        const float p[3] = {-1.9f + 0.0123f * (float)i, 1.7f - 0.011f * (float)i, 0.0f},
                    n[3] = {0.0f, 0.0f, 1.0f};
        double sw = 0.0, sv = 0.0;
        float open = -1.0f, w = 0.0f;
        int got = occ_lookup(c, p, n, &open, &w);
        for (id = 0; id < (uint32_t)st.records; id++) {
            occ_record o;
            double d;
            if (occ_record_get(c, id, &o) != IRC_OK)
                continue;
            d = sqrt(((double)p[0] - o.p[0]) * (p[0] - o.p[0]) + ((double)p[1] - o.p[1]) * (p[1] - o.p[1]));
            if (d < 0.3 * o.radius && d > 0.0) {
                const double nd = sqrt((double)o.n[0] * o.n[0] + (double)o.n[1] * o.n[1] +
                                       (1.0 - o.n[2]) * (1.0 - o.n[2])) / sqrt(2.0),
                             wi = 1.0 / (d / o.radius + nd);
                sw += wi;
                sv += wi * o.open;
            }
        }
        if (sw == 0.0) {
            misses++;
            CHECK(got == IRC_MISS, "a lookup with no record in reach: %d", got);
            continue;
        }
        CHECK(got == IRC_OK && fabs(open - sv / sw) < 1e-5 && fabs(w - sw) < 1e-4 * sw,
              "lookup %g (weight %g), the records' mean %g (weight %g)", open, w, sv / sw, sw);
    }
    CHECK(misses < 30, "%d of 300 lookups found no record", misses);
    block_free(&cfg);
}

/* A snapshot names the kind and carries its part; it reads back into a
 * cache of the kind (records equal) and is refused by an irradiance
 * cache; a block moved elsewhere re-attaches as the same kind. */
TEST(test_kind_occ_snapshot_attach)
{
    tscene s;
    irc_config cfg, other, at;
    irc_cache *c, *d, *e, *irr;
    unsigned char *snap, *moved;
    size_t bytes, size;
    uint32_t id, n;
    irc_stats st;
    scene_sphere_plane(&s);
    cfg = scene_config(&s, OCC_FEATURE, 8, 32);
    c = block_cache(&cfg, 100, 0);
    CHECK(c != NULL, "an occlusion cache");
    if (!c)
        return;
    for (id = 0; id < 30; id++) {
        const float p[3] = {-1.5f + 0.1f * (float)id, 0.3f, 0.0f}, nz[3] = {0.0f, 0.0f, 1.0f};
        float open;
        CHECK(occ_lookup_or_compute(c, p, nz, &open) == IRC_OK, "fill");
    }
    irc_cache_stats(c, &st);
    n = (uint32_t)st.records;
    CHECK(irc_snapshot_size(c, &bytes) == IRC_OK && bytes == 48u + n * (32u + 8u) + 4u,
          "snapshot of %u records: %zu bytes", n, bytes);
    snap = (unsigned char *)malloc(bytes);
    CHECK(irc_snapshot_write(c, 9, snap, bytes, NULL, NULL, NULL) == IRC_OK, "write");
    CHECK(snap[6] == OCC_ID && snap[7] == 0, "the header names kind %u", snap[6]);
    other = cfg;
    d = block_cache(&other, 100, 0);
    CHECK(d && irc_snapshot_read(d, 9, snap, bytes) == IRC_OK, "read back");
    for (id = 0; d && id < n; id++) {
        occ_record a, b;
        CHECK(occ_record_get(c, id, &a) == IRC_OK && occ_record_get(d, id, &b) == IRC_OK &&
                  memcmp(&a, &b, sizeof a) == 0 && a.rays == 256u && a.hits > 0u,
              "record %u differs after the snapshot", id);
    }
    {
        irc_config ic = scene_config(&s, 0, 8, 32);
        irr = block_cache(&ic, 100, 0);
        CHECK(irr && irc_snapshot_read(irr, 9, snap, bytes) == IRC_ERR_MISMATCH,
              "an irradiance cache takes an occlusion snapshot");
        block_free(&ic);
    }
    /* The whole block one byte further on. */
    irc_footprint(&cfg, 100, &size);
    moved = (unsigned char *)malloc(size + 64);
    memcpy(moved + 1, cfg.buffer, size);
    at = cfg;
    at.buffer = moved + 1;
    at.buffer_size = size;
    e = NULL;
    CHECK(irc_attach(&at, &e) == IRC_OK && e != NULL, "attach the moved block");
    for (id = 0; e && id < 20; id++) {
        const float p[3] = {-1.2f + 0.11f * (float)id, 0.35f, 0.0f}, nz[3] = {0.0f, 0.0f, 1.0f};
        float a = -1.0f, b = -2.0f;
        int sa = occ_lookup(c, p, nz, &a, NULL), sb = occ_lookup(e, p, nz, &b, NULL);
        CHECK(sa == IRC_OK && sb == IRC_OK && a == b, "lookup %u: %d %g vs %d %g after attach", id,
              sa, a, sb, b);
    }
    if (e)
        irc_fini(e);
    free(moved);
    free(snap);
    block_free(&other);
    block_free(&cfg);
}

/* The kind's config: its feature alone, no other kind's fields; the other
 * kinds' calls refuse its cache. */
TEST(test_kind_occ_config)
{
    tscene s;
    irc_config cfg, bad;
    irc_cache *c;
    size_t bytes;
    float rgb[3], w;
    irc_sh sh;
    const float p[3] = {0.0f, 0.0f, 0.0f}, n[3] = {0.0f, 0.0f, 1.0f};
    scene_sphere_plane(&s);
    cfg = scene_config(&s, OCC_FEATURE, 8, 32);
    bad = cfg;
    bad.sh.bands = 3;
    CHECK(irc_footprint(&bad, 10, &bytes) == IRC_ERR_CONFIG, "SH fields in an occlusion config");
    bad = cfg;
    bad.irr.supersamples = 4;
    CHECK(irc_footprint(&bad, 10, &bytes) == IRC_ERR_CONFIG, "irradiance fields in it");
    bad = cfg;
    bad.features |= IRC_FEATURE_SH;
    CHECK(irc_footprint(&bad, 10, &bytes) == IRC_ERR_CONFIG, "two kinds' features");
    bad.features = OCC_FEATURE | IRC_FEATURE_TRANSLATION;
    CHECK(irc_footprint(&bad, 10, &bytes) == IRC_ERR_CONFIG, "two kinds' features");
    c = block_cache(&cfg, 10, 0);
    CHECK(c != NULL, "an occlusion cache");
    if (!c)
        return;
    CHECK(irc_cache_lookup(c, p, n, rgb, &w) == IRC_ERR_UNSUPPORTED, "irradiance lookup");
    CHECK(irc_sh_lookup(c, p, n, &sh, &w) == IRC_ERR_UNSUPPORTED, "SH lookup");
    block_free(&cfg);
}
