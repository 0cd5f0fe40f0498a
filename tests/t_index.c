/* t_index.c -- the octree returns exactly what a scan of every record does. */
#define IRC_EXPERIMENTAL /* irc_cache_neighbours (irrcache.h) */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "block/cache.h" /* internals on purpose: records scanned without the index */
#include "index/layout.h"
#include "sample/sampler.h"
#include "block/octa.h"
#include "irr/weight.h"
#include "scenes.h"
#include "test.h"
#include "index_check.h"
#include "block/check.h"
#include "util.h"

static tscene dummy;

static int cmp_u32(const void *a, const void *b)
{
    uint32_t x = *(const uint32_t *)a, y = *(const uint32_t *)b;
    return x < y ? -1 : x > y;
}

/* A random unit normal near one of the six axes (so queries and records
 * share orientations, as surfaces do). */
static void rand_normal(unsigned long long *st, float n[3])
{
    int axis = (int)(xrand(st) * 6.0), k;
    double len;
    for (k = 0; k < 3; k++)
        n[k] = (float)((xrand(st) - 0.5) * 0.3);
    n[axis % 3] = axis < 3 ? 1.0f : -1.0f;
    len = sqrt((double)n[0] * n[0] + (double)n[1] * n[1] + (double)n[2] * n[2]);
    for (k = 0; k < 3; k++)
        n[k] = (float)(n[k] / len);
}

/* index_check.h */
void index_fill(irc_cache *c, uint32_t count, int decades, unsigned long long *st)
{
    uint32_t i;
    for (i = 0; i < count; i++) {
        irc_record r;
        double scale = pow(10.0, (xrand(st) - 0.5) * decades);
        int k;
        memset(&r, 0, sizeof r);
        for (k = 0; k < 3; k++) {
            r.p[k] = (float)(xrand(st) * scale);
            r.e[k] = (float)xrand(st);
        }
        rand_normal(st, r.n);
        r.radius = (float)(scale * 0.01 * pow(10.0, xrand(st) * 1.5));
        if (irc_cache_insert(c, &r) != IRC_OK)
            break;
    }
}

/* index_check.h */
uint32_t index_compare(irc_cache *c, uint32_t queries, int decades, unsigned long long *st)
{
    uint32_t *ids = malloc(sizeof(uint32_t) * 4096), *scan = malloc(sizeof(uint32_t) * 4096);
    uint32_t q, found = 0, bad = 0, m = irc__st(c)->count, i0;
    /* Every record's position and squared reach, scanned whole per query:
     * the prefilter only skips the weight call where d >= a R already. */
    float *px = malloc(sizeof(float) * m * 4), *py = px + m, *pz = py + m, *r2 = pz + m;
    for (i0 = 0; i0 < m; i0++) {
        const irc__rec *r = irc__rec_at(c, i0);
        double reach = (double)c->reach_a * r->r; /* a R, or blend a R */
        px[i0] = r->p[0];
        py[i0] = r->p[1];
        pz[i0] = r->p[2];
        r2[i0] = (float)(reach * reach * 1.001);
    }
    for (q = 0; q < queries; q++) {
        float p[3], n[3], rgb[3], wt;
        double scale = pow(10.0, (xrand(st) - 0.5) * decades), sum[3] = {0, 0, 0}, wsum = 0;
        /* The lookup's running mean in float (m += (w / W)(v - m)) errs
         * by a few ulps of the largest value it took in, not of its
         * result: a light record of large E read before a heavy one of
         * small E (weights near a blended reach's edge fall toward 0)
         * leaves that much. */
        double vmax = 0.0;
        uint32_t cnt = 0, ns = 0, near = 0, i;
        int k, stt;
        if (q % 3 == 1) {
            for (k = 0; k < 3; k++)
                p[k] = (float)(xrand(st) * scale);
            rand_normal(st, n);
        } else if (q % 3 == 2) {
            /* At the edge of a record's reach, in its tangent plane and
             * with its normal: accepted, and only just, which is where a
             * too-tight pruning bound would lose it. */
            const irc__rec *r = irc__rec_at(c, (uint32_t)(xrand(st) * irc__st(c)->count));
            float t1[3], t2[3], nd[3];
            double ang = xrand(st) * 6.283185307179586;
            double d = (0.95 + 0.049 * xrand(st)) * c->reach_a * r->r;
            float ni[3];
            irc__oct_decode(r->n, ni);
            for (k = 0; k < 3; k++)
                nd[k] = ni[k];
            irc__frame(nd, t1, t2);
            for (k = 0; k < 3; k++) {
                p[k] = (float)(r->p[k] + d * (cos(ang) * t1[k] + sin(ang) * t2[k]));
                n[k] = ni[k];
            }
        } else {
            /* Near a record, where weights are rarely zero. */
            const irc__rec *r = irc__rec_at(c, (uint32_t)(xrand(st) * irc__st(c)->count));
            float ni[3];
            irc__oct_decode(r->n, ni);
            for (k = 0; k < 3; k++) {
                p[k] = r->p[k] + (float)((xrand(st) - 0.5) * 0.3 * r->r);
                n[k] = ni[k] + (float)((xrand(st) - 0.5) * 0.1);
            }
        }
        {   /* the scan below takes the unit normal a lookup makes of n */
            float un[3];
            irc__check_normal(n, un);
            for (k = 0; k < 3; k++)
                n[k] = (float)un[k];
        }
        irc_cache_neighbours(c, p, n, ids, 4096, &cnt);
        for (i = 0; i < m; i++) {
            float w, v[3];
            float ni[3], dx = p[0] - px[i], dy = p[1] - py[i], dz = p[2] - pz[i];
            if (dx * dx + dy * dy + dz * dz > r2[i])
                continue;
            if (irc__weigh(c, irc__rec_at(c, i), p, n, 1, &w, ni)) {
                if (ns < 4096)
                    scan[ns] = i;
                ns++;
                irc__extrapolate(c, irc__rec_at(c, i), ni, p, n, v);
                vmax = fmax(vmax, v[0]);
                near += w > c->w_inner; /* within a R (irrcache.h) */
                for (k = 0; k < 3; k++)
                    sum[k] += w * v[k];
                wsum += w;
            }
        }
        stt = irc_cache_lookup(c, p, n, rgb, &wt);
        if (cnt > 4096 || ns > 4096) {
            bad++;
            continue;
        }
        qsort(ids, cnt, sizeof *ids, cmp_u32);
        qsort(scan, ns, sizeof *scan, cmp_u32);
        if (cnt != ns || memcmp(ids, scan, cnt * sizeof *ids) != 0)
            bad++;
        else if (ns && (stt != (near ? IRC_OK : IRC_MISS) || fabs(rgb[0] - sum[0] / wsum) >
                                             1e-5 * fmax(sum[0] / wsum, vmax) + 1e-30))
            bad++;
        else if (!ns && stt != IRC_MISS)
            bad++;
        found += ns > 0;
    }
    CHECK(bad == 0, "%u of %u queries differ from the scan", bad, queries);
    free(ids);
    free(scan);
    free(px);
    return found;
}

/* 1e5 random queries over 1e5 random records (1e4 queries in sanitizer
 * builds, where the scan is slow). */
TEST(test_index_exact)
{
    irc_config cfg = scene_config(&dummy, IRC_FEATURE_TRANSLATION | IRC_FEATURE_ROTATION, 4, 4);
    unsigned long long st = 12345;
    uint32_t queries = irc_t_quick ? 10000u : 100000u, found;
    irc_cache *c = block_cache(&cfg, 100000, 0);
    irc_stats s;
    CHECK(c != NULL, "init");
    if (!c) return;
    index_fill(c, 100000, 0, &st);
    irc_cache_stats(c, &s);
    CHECK(s.records == 100000, "records %llu", (unsigned long long)s.records);
    found = index_compare(c, queries, 0, &st);
    printf("  %u queries, %u found records; %llu of %llu index nodes used\n", queries, found,
           (unsigned long long)s.index_nodes, (unsigned long long)s.index_nodes_max);
    CHECK(found > queries / 10, "too few queries find anything (%u): the test would prove little", found);
    block_free(&cfg);
}

/* Positions over eight decades of scale (the root grows many times), and
 * an index whose node pool runs out (lists grow instead). */
TEST(test_index_scales)
{
    irc_config cfg = scene_config(&dummy, 0, 4, 4);
    unsigned long long st = 999;
    irc_cache *c = block_cache(&cfg, 20000, 0);
    uint32_t found;
    CHECK(c != NULL, "init");
    if (!c) return;
    index_fill(c, 20000, 8, &st);
    found = index_compare(c, irc_t_quick ? 2000u : 20000u, 8, &st);
    CHECK(found > 100, "found %u", found);
    /* Exhaust the node pool: many records at one point split to the
     * depth limit, then lists grow. */
    irc_cache_clear(c);
    {
        irc_record r;
        uint32_t i;
        memset(&r, 0, sizeof r);
        r.n[2] = 1.0f;
        for (i = 0; i < 20000; i++) {
            r.p[0] = (float)(xrand(&st) * 1e-6);
            r.radius = 1e-7f;
            CHECK(irc_cache_insert(c, &r) == IRC_OK, "insert");
        }
    }
    found = index_compare(c, 200, 0, &st);
    CHECK(found > 50, "found %u", found);
    block_free(&cfg);
}

/* Neighbour clamping (cfg.clamp_neighbours): radii by hand, then a random
 * fill whose lookups still equal a scan of every record, and CLOCK
 * eviction of records whose radius (so whose home in the tree) changed
 * after they were placed. */
TEST(test_index_clamped)
{
    irc_config cfg = scene_config(&dummy, 0, 4, 4);
    unsigned long long st = 4242;
    irc_cache *c;
    irc_record r, back;
    uint32_t found, i;
    cfg.clamp_neighbours = 1;
    c = block_cache(&cfg, 20000, 0);
    CHECK(c != NULL, "init");
    if (!c) return;
    disk_record(&r, 1.0f, 1.0f); /* A at the origin */
    CHECK(irc_cache_insert(c, &r) == IRC_OK, "A");
    r.p[0] = 0.5f;
    r.radius = 5.0f; /* B: at most R_A + 0.5 */
    CHECK(irc_cache_insert(c, &r) == IRC_OK, "B");
    r.p[0] = 0.3f;
    r.radius = 0.1f; /* C: clamps A to 0.4 and B to 0.3 */
    CHECK(irc_cache_insert(c, &r) == IRC_OK, "C");
    r.p[0] = 9.0f;
    r.radius = 0.2f; /* D: far from all, changes nothing */
    CHECK(irc_cache_insert(c, &r) == IRC_OK, "D");
    {
        static const float want[4] = {0.4f, 0.3f, 0.1f, 0.2f};
        for (i = 0; i < 4; i++) {
            CHECK(irc_cache_record(c, i, &back) == IRC_OK &&
                      fabsf(back.radius - want[i]) < 1e-6f,
                  "record %u: radius %g, want %g", i, back.radius, want[i]);
        }
    }
    irc_cache_clear(c);
    index_fill(c, 20000, 2, &st);
    found = index_compare(c, irc_t_quick ? 2000u : 20000u, 2, &st);
    CHECK(found > 100, "found %u", found);
    block_free(&cfg);
    /* eviction after clamping: every victim is found in the tree */
    cfg = scene_config(&dummy, 0, 4, 4);
    cfg.clamp_neighbours = 1;
    cfg.evict = IRC_EVICT_CLOCK;
    c = block_cache(&cfg, 300, 0);
    CHECK(c != NULL, "init");
    if (!c) return;
    index_fill(c, 5000, 1, &st);
    found = index_compare(c, 500, 1, &st);
    CHECK(found > 20, "found %u", found);
    block_free(&cfg);
}

/* Depth first, as queries visit: each list must be the run of references
 * that follows the previous list's, and each record's id the order of its
 * home reference.  Returns the references seen; *bad counts references
 * and homes out of order. */
uint32_t index_runs_check(const irc_cache *c, const irc__node *n, index_runs *k)
{
    uint32_t r, o;
    for (r = n->head; r != IRC__NIL; r = irc__refs(c)[r].next) {
        k->bad += r != k->ref++;
        if (irc__refs(c)[r].id & IRC__REF_HOME)
            k->bad += (irc__refs(c)[r].id & ~IRC__REF_HOME) != k->home++;
    }
    for (o = 0; n->child && o < 8; o++)
        index_runs_check(c, &irc__nodes(c)[n->child + o], k);
    return k->ref;
}

/* The walk's integer point (query.c) where it is least exact: records of
 * radius 1 near the origin with one at 1e33 (the root at its widest,
 * 2^99, the far record in its list, the rest in lists at the depth
 * limit), and
 * records of radius 1e-11 within 1e-9 of the origin with one at 1 (cubes
 * 2^-40 of the root's, where the integer point is off by the most half
 * edges), each answered as a scan of every record answers. */
TEST(test_index_far_scales)
{
    static const double far[2] = {1e33, 1.0}, size[2] = {1.0, 1e-9};
    int k;
    for (k = 0; k < 2; k++) {
        irc_config cfg = scene_config(&dummy, IRC_FEATURE_TRANSLATION | IRC_FEATURE_ROTATION, 4, 4);
        irc_cache *c = block_cache(&cfg, 4000, 0);
        unsigned long long st = 31 + (unsigned long long)k;
        uint32_t i, found;
        int e;
        CHECK(c != NULL, "init");
        if (!c) return;
        for (i = 0; i < 4000; i++) {
            irc_record r;
            int j;
            memset(&r, 0, sizeof r);
            for (j = 0; j < 3; j++) {
                r.p[j] = (float)(i == 0 ? far[k] : size[k] * xrand(&st));
                r.e[j] = (float)xrand(&st);
            }
            rand_normal(&st, r.n);
            r.radius = (float)(size[k] * (0.01 + 0.02 * xrand(&st)));
            CHECK(irc_cache_insert(c, &r) == IRC_OK, "insert");
        }
        frexp(irc__st(c)->root_h, &e);
        CHECK((e - 1 == 99) == (k == 0), "scene %d: root half edge 2^%d", k, e - 1);
        CHECK(k == 0 || irc__st(c)->depth >= 30, "scene %d: depth %u", k, (unsigned)irc__st(c)->depth);
        found = index_compare(c, irc_t_quick ? 1000u : 4000u, 0, &st);
        CHECK(found > 100, "scene %d: found %u", k, found);
        block_free(&cfg);
    }
}

/* A record with gradients for test_weigh_fused: |grad_t| R up to twice E
 * and |grad_r| up to 17 E a radian, so extrapolations run below 0 and
 * are clamped. */
static void fused_record(unsigned long long *st, irc_record *r)
{
    int k, ch;
    memset(r, 0, sizeof *r);
    rand_normal(st, r->n);
    r->radius = (float)(0.05 * pow(10.0, xrand(st)));
    for (k = 0; k < 3; k++)
        r->p[k] = (float)(xrand(st) - 0.5);
    for (ch = 0; ch < 3; ch++) {
        r->e[ch] = (float)(0.01 + xrand(st));
        for (k = 0; k < 3; k++) {
            r->grad_t[ch][k] = (float)((xrand(st) - 0.5) * 2.0 * r->e[ch] / r->radius);
            r->grad_r[ch][k] = (float)((xrand(st) - 0.5) * 20.0 * r->e[ch]);
        }
    }
}

/* The lookups' fused weight and value (irc__weigh_extrapolate) against
 * the general path's three calls, bit for bit, for every record near
 * each query and every gradient set a cache without ellipse or guard
 * stores; and the value against E + grad_t.(p - p_i) + (n_i x n).grad_r
 * in double from the record as read back (world coordinates): within
 * 1e-6 of the terms' magnitudes (float roundings of the frame, the
 * products and the sums: a few 1e-7). */
TEST(test_weigh_fused)
{
    static const uint32_t sets[] = {IRC_FEATURE_NONE, IRC_FEATURE_TRANSLATION,
                                    IRC_FEATURE_ROTATION,
                                    IRC_FEATURE_TRANSLATION | IRC_FEATURE_ROTATION};
    const uint32_t records = 1500, queries = irc_t_quick ? 300u : 1500u;
    unsigned long long st = 777;
    unsigned f;
    for (f = 0; f < sizeof sets / sizeof sets[0]; f++) {
        irc_config cfg = scene_config(&dummy, sets[f], 4, 4);
        irc_cache *c;
        uint32_t q, i, accepted = 0, bad_bits = 0, bad_ref = 0, clamped = 0;
        double worst = 0.0;
        cfg.accuracy = 0.4f;
        c = block_cache(&cfg, records, 0);
        CHECK(c != NULL, "init");
        if (!c) return;
        for (i = 0; i < records; i++) {
            irc_record r;
            fused_record(&st, &r);
            CHECK(irc_cache_insert(c, &r) == IRC_OK, "insert");
        }
        for (q = 0; q < queries; q++) {
            irc_record rq;
            float p[3], n[3], un[3];
            int k;
            CHECK(irc_cache_record(c, (uint32_t)(xrand(&st) * records), &rq) == IRC_OK, "read");
            for (k = 0; k < 3; k++) {
                /* at the record itself one query in eight */
                p[k] = q % 8 ? rq.p[k] + (float)((xrand(&st) - 0.5) * 0.4 * rq.radius) : rq.p[k];
                n[k] = rq.n[k] + (float)((xrand(&st) - 0.5) * (q % 3 ? 0.3 : 2.5));
            }
            if (irc__check_normal(n, un) != IRC_OK)
                continue;
            for (i = 0; i < records; i++) {
                const irc__rec *r = irc__rec_at(c, i);
                float w0 = 0.0f, w1, v0[3], v1[3], ni[3];
                int ok = irc__within_reach(c, r, p) && irc__weigh(c, r, p, un, 1, &w0, ni);
                w1 = irc__weigh_extrapolate(c, r, p, un, v1);
                if (!ok) {
                    bad_bits += w1 != 0.0f;
                    continue;
                }
                irc__extrapolate(c, r, ni, p, un, v0);
                accepted++;
                bad_bits += memcmp(&w0, &w1, sizeof w0) != 0 || memcmp(v0, v1, sizeof v0) != 0;
                {
                    irc_record rr;
                    CHECK(irc_cache_record(c, i, &rr) == IRC_OK, "read");
                    for (k = 0; k < 3; k++) {
                        const double d[3] = {(double)p[0] - rr.p[0], (double)p[1] - rr.p[1],
                                             (double)p[2] - rr.p[2]};
                        const double x[3] = {(double)rr.n[1] * un[2] - (double)rr.n[2] * un[1],
                                             (double)rr.n[2] * un[0] - (double)rr.n[0] * un[2],
                                             (double)rr.n[0] * un[1] - (double)rr.n[1] * un[0]};
                        double t = 0.0, r0 = 0.0, ref, mag, err;
                        int j;
                        for (j = 0; j < 3; j++) {
                            t += d[j] * rr.grad_t[k][j];
                            r0 += x[j] * rr.grad_r[k][j];
                        }
                        ref = rr.e[k] + t + r0;
                        clamped += ref < 0.0;
                        ref = ref > 0.0 ? ref : 0.0;
                        mag = rr.e[k] + fabs(t) + fabs(r0);
                        err = fabs(v1[k] - ref) / mag;
                        worst = err > worst ? err : worst;
                        bad_ref += err > 1e-6;
                    }
                }
            }
        }
        printf("  features %#x: %u accepted, %u clamped channels, worst |v - ref| %.2g of the "
               "terms\n",
               (unsigned)sets[f], accepted, clamped, worst);
        CHECK(accepted > queries / 2, "too few accepted (%u): the test would prove little", accepted);
        /* (a stored grad_t keeps its extrapolation within E (1 +- a): only
         * rotation reaches 0) */
        CHECK(!(sets[f] & IRC_FEATURE_ROTATION) || clamped > 0, "no extrapolation clamped");
        CHECK(bad_bits == 0, "%u records weighed or extrapolated differently", bad_bits);
        CHECK(bad_ref == 0, "%u channels off the closed form by more than 1e-6 (worst %g)",
              bad_ref, worst);
        block_free(&cfg);
    }
}
