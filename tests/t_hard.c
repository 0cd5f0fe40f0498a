/*
 * t_hard.c -- hard numerical cases: each asserts a finite answer within a
 * stated tolerance of the right one, or a documented error, never a crash
 * or a silent NaN.  TESTING.md lists them.
 */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "test.h"
#include "scenes.h"

static int finite_record(const irc_record *r)
{
    int c, k;
    for (c = 0; c < 3; c++) {
        if (!isfinite(r->e[c]) || r->e[c] < 0.0f)
            return 0;
        for (k = 0; k < 3; k++)
            if (!isfinite(r->grad_t[c][k]) || !isfinite(r->grad_r[c][k]))
                return 0;
    }
    return isfinite(r->radius) && r->radius > 0.0f;
}

/* The sphere-over-plane scene scaled by s about the origin, queried at the
 * origin (so the query's random numbers do not change with s): E is the
 * same and the gradients scale as 1/s, within 1e-4 relative, from s =
 * 1e-6 to 3e5 (hit distances from 1e-6 to 1e6), with translational and
 * with visibility gradients; the Hessian's ellipse (both radii as s, the
 * same axis) and the leak guard (fractions of the reach) alike. */
static int scaled_record(uint32_t features, double scale, irc_record *r)
{
    const float p[3] = {0, 0, 0}, n[3] = {0, 0, 1};
    tscene s;
    irc_config cfg;
    irc_cache *cache;
    int st = -1;
    scene_sphere_plane(&s);
    s.centre[0] = 0.3 * scale;
    s.centre[2] = 2.0 * scale;
    s.radius = scale;
    cfg = scene_config(&s, features, 16, 64);
    cache = block_cache(&cfg, 4, 0);
    if (cache)
        st = irc_record_compute(cache, p, n, r, NULL);
    block_free(&cfg);
    return st;
}

TEST(test_hard_scale_invariance)
{
    static const uint32_t feats[] = {IRC_FEATURE_TRANSLATION | IRC_FEATURE_ROTATION,
                                     IRC_FEATURE_VISIBILITY | IRC_FEATURE_ROTATION,
                                     IRC_FEATURE_TRANSLATION | IRC_FEATURE_HESSIAN};
    static const double scales[] = {1e-6, 1e-4, 1e-2, 1e2, 1e4, 3e5};
    double worst = 0.0;
    int f, i, c, k;
    for (f = 0; f < 3; f++) {
        irc_record base, r;
        double gb = 0.0, hb = 0.0;
        CHECK(scaled_record(feats[f], 1.0, &base) == IRC_OK && finite_record(&base), "base");
        for (c = 0; c < 3; c++)
            for (k = 0; k < 3; k++)
                gb = fmax(gb, fabs(base.grad_t[c][k]));
        for (c = 0; c < 3; c++)
            for (k = 0; k < 6; k++)
                hb = fmax(hb, fabs(base.hessian[c][k]));
        for (i = 0; i < 6; i++) {
            CHECK(scaled_record(feats[f], scales[i], &r) == IRC_OK && finite_record(&r),
                  "s = %g", scales[i]);
            for (c = 0; c < 3; c++) {
                worst = fmax(worst, fabs(r.e[c] - base.e[c]) / base.e[c]);
                for (k = 0; k < 3; k++) {
                    worst = fmax(worst, fabs(r.grad_t[c][k] * scales[i] - base.grad_t[c][k]) / gb);
                    worst = fmax(worst, fabs(r.grad_r[c][k] - base.grad_r[c][k]) / base.e[c]);
                }
            }
            worst = fmax(worst, fabs(r.radius / scales[i] - base.radius) / base.radius);
            worst = fmax(worst, fabs(r.minor_radius / scales[i] - base.minor_radius) /
                                    base.minor_radius);
            for (k = 0; k < 3; k++)
                worst = fmax(worst, fabs(r.axis[k] - base.axis[k]));
            CHECK(r.leak_guard == base.leak_guard, "leak guard %llx at s = %g, %llx at 1",
                  (unsigned long long)r.leak_guard, scales[i], (unsigned long long)base.leak_guard);
            /* second derivatives go as 1/s^2 (the Hessian radius as s) */
            for (c = 0; hb > 0.0 && c < 3; c++)
                for (k = 0; k < 6; k++)
                    worst = fmax(worst, fabs(r.hessian[c][k] * scales[i] * scales[i] -
                                             base.hessian[c][k]) / hb);
        }
        if (feats[f] & IRC_FEATURE_HESSIAN)
            CHECK(hb > 0.0, "the Hessian case saw no curvature: the test proves little");
    }
    printf("  scales 1e-6 .. 3e5, trans+rot, vis+rot and trans+Hessian: worst relative "
           "difference %.2e\n", worst);
    CHECK(worst < 1e-4, "scale invariance %.3e", worst);
}

/* A host with one behaviour for every ray. */
enum { H_SAME_DIST, H_ESCAPE, H_FAIL, H_DENORMAL, H_WIDE };
typedef struct hhost {
    int mode;
    float dist;
} hhost;

static int hard_trace(const irc_trace_args *a)
{
    const hhost *h = (const hhost *)a->context;
    uint32_t i;
    int c;
    for (i = 0; i < a->count; i++) {
        irc_hit *o = &a->hits[i];
        const float *d = a->rays[i].dir;
        switch (h->mode) {
        case H_SAME_DIST:
        case H_DENORMAL:
            o->status = IRC_RAY_HIT;
            o->dist = h->mode == H_DENORMAL ? 1e-40f : h->dist;
            for (c = 0; c < 3; c++) {
                o->normal[c] = h->mode == H_DENORMAL ? -d[c] * 1e-30f : -d[c];
                o->radiance[c] = h->mode == H_DENORMAL ? 1e-40f : 1.0f;
            }
            break;
        case H_ESCAPE:
            o->status = IRC_RAY_ESCAPED;
            o->radiance[0] = o->radiance[1] = o->radiance[2] = 2.0f;
            break;
        case H_WIDE: /* 1e6 where sin^2(theta) < 1/16 (row 0 of 16 exactly), 1e-6
                        elsewhere: no stratum straddles the edge */
            o->status = IRC_RAY_ESCAPED;
            o->radiance[0] = o->radiance[1] = o->radiance[2] =
                1.0f - d[2] * d[2] < 0.0625f ? 1e6f : 1e-6f;
            break;
        default:
            o->status = IRC_RAY_FAILED;
        }
    }
    return 0;
}

static irc_config hard_config(hhost *h, uint32_t features, uint32_t m, uint32_t n)
{
    irc_config cfg;
    memset(&cfg, 0, sizeof cfg);
    cfg.version = IRC_CONFIG_VERSION;
    cfg.trace = hard_trace;
    cfg.context = h;
    cfg.features = features;
    cfg.strata_theta = m;
    cfg.strata_phi = n;
    return cfg;
}

/* Degenerate hemispheres: every hit at one distance (E = pi, gradients
 * ~0, radius = that distance), every ray escaping (E = 2 pi, radius at the
 * cap), every ray failing (IRC_ERR_NOSAMPLES, nothing counted), radiance
 * from 1e-6 to 1e6 in one hemisphere (a bright cap that fills the first
 * row of strata exactly, so E is pi (1e-6 + (1e6 - 1e-6)/16) up to
 * rounding: within 1e-5), denormal distances, normals and
 * radiance (a finite record), one stratum, and the largest grid. */
/* irc_hit.normal: "any nonzero length, either orientation".  The host's
 * hit normals turned over and made 2^60 long give the same record as the
 * scene's own, for the estimators that read them (visibility gradients,
 * the Hessian, the leak guard). */
static int turned_trace(const irc_trace_args *a)
{
    const int st = scene_trace(a);
    uint32_t i;
    int k;
    for (i = 0; i < a->count; i++)
        if (a->hits[i].status == IRC_RAY_HIT)
            for (k = 0; k < 3; k++)
                a->hits[i].normal[k] *= -0x1p60f;
    return st;
}

TEST(test_hit_normal_any_length)
{
    static const uint32_t feats[2] = {IRC_FEATURE_VISIBILITY | IRC_FEATURE_ROTATION,
                                      IRC_FEATURE_TRANSLATION | IRC_FEATURE_ROTATION |
                                          IRC_FEATURE_HESSIAN};
    const float p[3] = {0.5f, 0.25f, 0.0f}, n[3] = {0, 0, 1};
    tscene s;
    int f, k, ch;
    scene_sphere_plane(&s); /* the sphere fills much of the hemisphere */
    for (f = 0; f < 2; f++) {
        irc_record r[2];
        int t, same = 1;
        for (t = 0; t < 2; t++) {
            irc_config cfg = scene_config(&s, feats[f], 8, 32);
            irc_cache *c;
            cfg.irr.leak_guard = IRC_ON;
            if (t)
                cfg.trace = turned_trace;
            c = block_cache(&cfg, 4, 0);
            CHECK(c && irc_record_compute(c, p, n, &r[t], NULL) == IRC_OK, "features %u, %s", feats[f],
                  t ? "turned" : "as given");
            block_free(&cfg);
        }
        same = r[0].radius == r[1].radius && r[0].minor_radius == r[1].minor_radius &&
               r[0].leak_guard == r[1].leak_guard;
        for (k = 0; k < 3; k++) {
            same &= r[0].e[k] == r[1].e[k];
            for (ch = 0; ch < 3; ch++)
                same &= r[0].grad_t[ch][k] == r[1].grad_t[ch][k];
        }
        CHECK(same, "features %u: turned normals changed the record (R %g against %g, "
                    "grad_t %g against %g)",
              feats[f], (double)r[1].radius, (double)r[0].radius, (double)r[1].grad_t[0][0],
              (double)r[0].grad_t[0][0]);
    }
}

TEST(test_hard_hemispheres)
{
    static const uint32_t feats[] = {IRC_FEATURE_TRANSLATION | IRC_FEATURE_ROTATION,
                                     IRC_FEATURE_VISIBILITY | IRC_FEATURE_ROTATION, 0};
    const float p[3] = {0.25f, -1.5f, 3.0f}, n[3] = {0, 0, 1};
    int f;
    for (f = 0; f < 3; f++) {
        hhost h = {H_SAME_DIST, 0.5f};
        irc_config cfg = hard_config(&h, feats[f], 16, 64);
        irc_cache *c = block_cache(&cfg, 4, 0);
        irc_record r;
        irc_stats st;
        double want = TPI * (1e-6 + (1e6 - 1e-6) / 16.0);
        CHECK(c && irc_record_compute(c, p, n, &r, NULL) == IRC_OK && finite_record(&r), "same distance");
        CHECK(fabs(r.e[0] - TPI) < 1e-5 && fabs(r.radius - 0.5f) < 1e-5f &&
                  fabs(r.grad_t[0][0]) < 1e-4 && fabs(r.grad_r[0][1]) < 1e-4,
              "same distance: E %g R %g", r.e[0], r.radius);
        h.mode = H_ESCAPE;
        CHECK(irc_record_compute(c, p, n, &r, NULL) == IRC_OK && finite_record(&r) &&
                  fabs(r.e[1] - 2.0 * TPI) < 1e-5 && r.radius == FLT_MIN,
              "escape: E %g R %g", r.e[1], r.radius);
        h.mode = H_FAIL;
        irc_cache_stats(c, &st);
        CHECK(irc_record_compute(c, p, n, &r, NULL) == IRC_ERR_NOSAMPLES, "all fail");
        {
            irc_stats st2;
            irc_cache_stats(c, &st2);
            CHECK(st2.computes == st.computes && st2.rays == st.rays, "nothing counted");
        }
        h.mode = H_WIDE;
        CHECK(irc_record_compute(c, p, n, &r, NULL) == IRC_OK && finite_record(&r), "wide range");
        CHECK(fabs(r.e[2] - want) < 1e-5 * want, "wide: E %g, closed form %g", r.e[2], want);
        h.mode = H_DENORMAL;
        CHECK(irc_record_compute(c, p, n, &r, NULL) == IRC_OK && finite_record(&r), "denormals");
        block_free(&cfg);
    }
    {
        hhost h = {H_ESCAPE, 1.0f};
        irc_config cfg = hard_config(&h, IRC_FEATURE_TRANSLATION | IRC_FEATURE_ROTATION, 1, 1);
        irc_cache *c = block_cache(&cfg, 4, 0);
        irc_record r;
        CHECK(c && irc_record_compute(c, p, n, &r, NULL) == IRC_OK && fabs(r.e[0] - 2.0 * TPI) < 1e-5,
              "one stratum");
        block_free(&cfg);
        cfg = hard_config(&h, IRC_FEATURE_TRANSLATION | IRC_FEATURE_ROTATION, 1024, 4096);
        c = block_cache(&cfg, 4, 0);
        CHECK(c && irc_record_compute(c, p, n, &r, NULL) == IRC_OK && fabs(r.e[0] - 2.0 * TPI) < 1e-4 &&
                  r.rays == 1024u * 4096u && fabs(r.grad_r[0][0]) < 1e-4,
              "largest grid: E %g", r.e[0]);
        block_free(&cfg);
    }
}

/* Lookups at grazing and opposed normals, on coincident and nearly
 * coincident records, and with denormal inputs: finite or IRC_MISS. */
TEST(test_hard_lookups)
{
    hhost h = {H_ESCAPE, 1.0f};
    irc_config cfg = hard_config(&h, IRC_FEATURE_TRANSLATION | IRC_FEATURE_ROTATION, 4, 8);
    irc_cache *c;
    irc_record r;
    float rgb[3], w;
    const float p[3] = {0, 0, 0};
    int i, st;
    c = block_cache(&cfg, 256, 0);
    CHECK(c != NULL, "init");
    memset(&r, 0, sizeof r);
    r.n[2] = 1.0f;
    r.radius = 1.0f;
    r.e[0] = r.e[1] = r.e[2] = 1.0f;
    r.grad_t[0][0] = 0.5f;
    r.grad_r[1][1] = 0.5f;
    for (i = 0; i < 100; i++) /* coincident */
        CHECK(irc_cache_insert(c, &r) == IRC_OK, "insert %d", i);
    for (i = 0; i < 100; i++) { /* nearly coincident: offsets down to denormal */
        r.p[0] = (float)ldexp(1.0, -i - 30);
        CHECK(irc_cache_insert(c, &r) == IRC_OK, "near %d", i);
    }
    st = irc_cache_lookup(c, p, r.n, rgb, &w);
    CHECK(st == IRC_OK && isfinite(rgb[0]) && fabs(rgb[0] - 1.0f) < 1e-3 && isfinite(w),
          "on the records: %g (weight %g)", rgb[0], w);
    { /* a record of denormals everywhere: stored, and lookups stay finite */
        irc_record d;
        const float q[3] = {3.0f, 3.0f, 0.0f};
        memset(&d, 0, sizeof d);
        d.p[0] = 3.0f;
        d.p[1] = 3.0f;
        d.p[2] = 1e-42f;
        d.n[0] = 1e-42f;
        d.n[2] = 1e-40f;
        d.radius = 1e-40f;
        d.e[0] = d.e[1] = d.e[2] = 1e-41f;
        d.grad_t[0][0] = 1e-44f;
        d.grad_r[2][1] = -1e-43f;
        CHECK(irc_cache_insert(c, &d) == IRC_OK, "denormal record");
        st = irc_cache_lookup(c, q, r.n, rgb, &w);
        CHECK((st == IRC_OK || st == IRC_MISS) && isfinite(rgb[0]) && rgb[0] >= 0.0f && isfinite(w),
              "near the denormal record: %d %g %g", st, rgb[0], w);
    }
    {
        const float graze[3] = {1.0f, 0.0f, 1e-7f}, opposed[3] = {1e-7f, 0.0f, -1.0f};
        const float near_graze[3] = {1.0f, 0.0f, 0.02f};
        const float dn[3] = {1e-40f, -1e-40f, 1e-40f}, dp[3] = {1e-40f, 1e-45f, -1e-40f};
        CHECK(irc_cache_lookup(c, p, opposed, rgb, &w) == IRC_MISS && w == 0.0f, "opposed");
        CHECK(irc_cache_lookup(c, p, graze, rgb, &w) == IRC_MISS, "grazing (sqrt(1 - n.n_i) ~ 1 > a)");
        CHECK(irc_cache_lookup(c, p, near_graze, rgb, &w) == IRC_MISS, "near grazing");
        st = irc_cache_lookup(c, dp, dn, rgb, &w);
        CHECK((st == IRC_OK || st == IRC_MISS) && isfinite(rgb[0]) && isfinite(w), "denormal query");
    }
    block_free(&cfg);
    cfg.accuracy = 10.0f; /* a = 10: a grazing query counts, with a finite weight */
    c = block_cache(&cfg, 4, 0);
    r.p[0] = 0.0f;
    CHECK(c && irc_cache_insert(c, &r) == IRC_OK, "insert");
    {
        const float graze[3] = {1.0f, 0.0f, 1e-7f};
        st = irc_cache_lookup(c, p, graze, rgb, &w);
        CHECK(st == IRC_OK && isfinite(rgb[0]) && rgb[0] >= 0.0f && w > 0.0f && isfinite(w),
              "grazing with a = 10: %d %g %g", st, rgb[0], w);
    }
    block_free(&cfg);
}

/* A full cache under continued inserts: with CLOCK every insert succeeds
 * and lookups keep answering; without, IRC_ERR_FULL from the first insert
 * past capacity, lookups still answering. */
TEST(test_hard_full_cache)
{
    hhost h = {H_SAME_DIST, 0.5f};
    int ev;
    for (ev = 0; ev < 2; ev++) {
        irc_config cfg = hard_config(&h, IRC_FEATURE_TRANSLATION, 4, 8);
        irc_cache *c;
        irc_stats st;
        int i, ok = 0, full = 0;
        unsigned long long rs = 5;
        cfg.evict = ev ? IRC_EVICT_CLOCK : IRC_EVICT_NONE;
        c = block_cache(&cfg, 64, 0);
        for (i = 0; i < 2000 && c; i++) {
            float p[3], n[3] = {0, 0, 1}, rgb[3], w;
            int s;
            p[0] = (float)(10.0 * xrand(&rs));
            p[1] = (float)(10.0 * xrand(&rs));
            p[2] = 0.0f;
            s = irc_cache_lookup_or_compute(c, p, n, rgb, &w, NULL);
            ok += s == IRC_OK;
            full += s == IRC_NOT_STORED;
            CHECK(s >= 0 && isfinite(rgb[0]), "call %d: %d", i, s);
        }
        irc_cache_stats(c, &st);
        printf("  eviction %s: %d stored or answered, %d not stored, %llu records, %llu evictions\n",
               ev ? "CLOCK" : "off", ok, full, (unsigned long long)st.records,
               (unsigned long long)st.evictions);
        CHECK(st.records == 64, "pool full");
        CHECK(ev ? (full == 0 && st.evictions > 0) : (full > 0 && st.evictions == 0), "policy");
        block_free(&cfg);
    }
}
