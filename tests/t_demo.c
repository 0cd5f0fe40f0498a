/* t_demo.c -- the demo tracer: BVH against brute force, brute-force
 * irradiance against the closed form.  Run from the project's root. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "bvh.h"
#include "glossy.h"
#include "render.h"
#include "scenes.h"
#include "test.h"

static unsigned long long st_rng = 99;

/* A random ray from a point inside the scene's bounds (grown by 10%) in a
 * uniformly random direction. */
static void random_ray(const bvh *b, float o[3], float d[3])
{
    double z, phi, r;
    int i;
    for (i = 0; i < 3; i++) {
        float lo = b->nodes[0].lo[i], hi = b->nodes[0].hi[i], pad = 0.1f * (hi - lo);
        o[i] = (float)(lo - pad + xrand(&st_rng) * (hi - lo + 2 * pad));
    }
    z = 2.0 * xrand(&st_rng) - 1.0;
    phi = 2.0 * TPI * xrand(&st_rng);
    r = sqrt(1.0 - z * z);
    d[0] = (float)(r * cos(phi));
    d[1] = (float)(r * sin(phi));
    d[2] = (float)z;
}

/* Casts n random rays at b and at a brute-force loop over s's primitives;
 * returns how many disagree (nearest hit, its distance, or occlusion) and
 * adds the rays that hit to *hits.  A ray through an edge shared by two
 * triangles may name either, at exactly the same distance. */
static int compare_bvh(const scene *s, const bvh *b, int n, int *hits)
{
    int i, bad = 0;
    for (i = 0; i < n; i++) {
        float o[3], d[3];
        bvh_hit h1, h2;
        int a, c;
        random_ray(b, o, d);
        a = bvh_intersect(b, o, d, 0.0f, 1e30f, &h1);
        c = brute_intersect(s, o, d, 0.0f, 1e30f, &h2);
        *hits += a;
        if (a != c || (a && h1.t != h2.t) || !bvh_occluded(b, o, d, 0.0f, 1e30f) != !c)
            bad++;
    }
    return bad;
}

static void bvh_vs_brute(const char *path)
{
    scene s;
    bvh b;
    char err[512];
    int n = irc_t_quick ? 10000 : 100000, bad, hits = 0;
    if (scene_load(path, &s, err, sizeof err) < 0) {
        CHECK(0, "%s", err);
        return;
    }
    CHECK(bvh_build(&b, &s) == 0, "build");
    bad = compare_bvh(&s, &b, n, &hits);
    printf("  %s: %d triangles, %d spheres, %d nodes; %d of %d rays hit; %d differ\n", path,
           s.ntris, s.nspheres, b.nnodes, hits, n, bad);
    CHECK(bad == 0, "%d rays differ from brute force", bad);
    CHECK(hits > n / 10, "too few hits to prove much (%d)", hits);
    bvh_free(&b);
    scene_free(&s);
}

/* A soup of 5000 random triangles and 50 spheres: deep trees, overlapping
 * boxes, SAH splits on every axis. */
TEST(test_bvh_soup)
{
    enum { NT = 5000, NS = 50, RAYS = 20000 };
    static triangle tris[NT];
    static sphere sps[NS];
    material m;
    scene s;
    bvh b;
    int i, k, c, bad, hits = 0;
    memset(&m, 0, sizeof m);
    memset(&s, 0, sizeof s);
    for (i = 0; i < NT; i++) {
        float centre[3], size = (float)(0.1 + 1.5 * xrand(&st_rng) * xrand(&st_rng));
        for (c = 0; c < 3; c++)
            centre[c] = (float)(xrand(&st_rng) * 10.0);
        for (k = 0; k < 3; k++)
            for (c = 0; c < 3; c++)
                tris[i].v[k][c] = centre[c] + size * (float)(xrand(&st_rng) - 0.5);
    }
    for (i = 0; i < NS; i++) {
        for (c = 0; c < 3; c++)
            sps[i].c[c] = (float)(xrand(&st_rng) * 10.0);
        sps[i].r = (float)(0.05 + 0.3 * xrand(&st_rng));
    }
    s.tris = tris; s.ntris = NT; s.spheres = sps; s.nspheres = NS; s.mats = &m; s.nmats = 1;
    CHECK(bvh_build(&b, &s) == 0, "build");
    bad = compare_bvh(&s, &b, RAYS, &hits);
    printf("  soup: %d nodes; %d of %d rays hit; %d differ\n", b.nnodes, hits, RAYS, bad);
    CHECK(bad == 0, "%d rays differ", bad);
    CHECK(hits > RAYS / 10 && b.nnodes > NT / 4, "hits %d nodes %d", hits, b.nnodes);
    bvh_free(&b);
}

TEST(test_bvh_shipped_scenes)
{
    bvh_vs_brute("demo/scenes/cornell.scene");
    bvh_vs_brute("demo/scenes/fig5.scene");
    bvh_vs_brute("demo/scenes/fig15.scene");
    bvh_vs_brute("demo/scenes/sh.scene");
    bvh_vs_brute("demo/scenes/leak.scene");
    bvh_vs_brute("demo/scenes/cornell-glossy.scene");
}

/* A floor z = 0 (two triangles 2000 wide, albedo 0.5) under a black ball
 * of radius 1 centred at (0, 0, 2): the tests' closed-form scene. */
static void ball_over_plane(scene *s, material mats[2], triangle tris[2], sphere *sp)
{
    static const float q[4][3] = {{-1e3f, -1e3f, 0}, {1e3f, -1e3f, 0}, {1e3f, 1e3f, 0}, {-1e3f, 1e3f, 0}};
    static const int corner[2][3] = {{0, 1, 2}, {0, 2, 3}};
    int t, k;
    memset(mats, 0, 2 * sizeof *mats);
    memset(tris, 0, 2 * sizeof *tris);
    memset(s, 0, sizeof *s);
    memset(sp, 0, sizeof *sp);
    mats[0].kd[0] = mats[0].kd[1] = mats[0].kd[2] = 0.5f;
    for (t = 0; t < 2; t++)
        for (k = 0; k < 3; k++)
            memcpy(tris[t].v[k], q[corner[t][k]], sizeof tris[t].v[k]);
    sp->c[2] = 2.0f;
    sp->r = 1.0f;
    sp->mat = 1; /* black */
    s->tris = tris; s->ntris = 2; s->spheres = sp; s->nspheres = 1; s->mats = mats; s->nmats = 2;
}

/* The demo's brute-force irradiance (--reference N) on the core tests'
 * sphere-over-plane case: a black sphere of radius 1 at (0, 0, 2) over the
 * plane z = 0 under a uniform sky 1, E = pi (1 - r^2 cos(theta)/d^2).
 * Built in code: two huge triangles for the plane, the analytic sphere. */
TEST(test_reference_sphere_plane)
{
    static const float pts[5][6] = {{0.5f, 0, 0, 0, 0, 1}, {1, 1, 0, 0, 0, 1}, {-1.5f, 0.5f, 0, 0, 0, 1},
                                    {2, -1, 0, 0, 0, 1}, {0, 3, 0, 0, 0, 1}};
    material mats[2];
    triangle tris[2];
    sphere sp;
    scene s;
    renderer r;
    render_opts o;
    render_stats st;
    tscene ref;
    char err[256];
    float e[15];
    int i;
    memset(&o, 0, sizeof o);
    ball_over_plane(&s, mats, tris, &sp);
    s.env.kind = ENV_CONSTANT;
    s.env.base[0] = s.env.base[1] = s.env.base[2] = 1.0f;
    s.cam.width = s.cam.height = 1;
    o.mode = MODE_REFERENCE;
    o.ref_rays = 32 * 128;
    o.threads = 1;
    o.seed = 3;
    CHECK(renderer_init(&r, &s, &o, err, sizeof err) == 0, "%s", err);
    CHECK(render_points(&r, &pts[0][0], 5, e, &st) == 0, "points");
    scene_init(&ref);
    ref.sky_a[0] = 1.0f;
    ref.has_sphere = 1;
    ref.centre[2] = 2.0;
    ref.radius = 1.0;
    for (i = 0; i < 5; i++) {
        double p[3] = {pts[i][0], pts[i][1], 0.0}, want = sphere_plane_e(&ref, p);
        printf("  point %d: E %.5f, closed form %.5f (%+.3f%%)\n", i, e[3 * i], want,
               100.0 * (e[3 * i] - want) / want);
        CHECK(fabs(e[3 * i] - want) <= 0.01 * want, "E %g vs %g", e[3 * i], want);
    }
    CHECK(st.rays == 5u * 32u * 128u, "rays %llu", (unsigned long long)st.rays);
    renderer_free(&r);
}

/* Glossy indirect light (demo/glossy.c) under radiance L(w) = a + b w_z
 * about the normal z, Phong exponent s = 20, ks = 0.5: the lobe's samples
 * average to the closed form ks (s + 2)/(2 pi) int (n.w)^s (n.w) L dw =
 * ks (a + b (s + 2)/(s + 3)) at normal incidence, and so does the SH path
 * (the lobe against L's exact two-band coefficients over 64 stratified
 * directions: quadrature error only); 30 degrees off the normal the SH
 * path agrees with 16384 lobe samples. */
static double lin_radiance(const float w[3])
{
    return 1.0 + 0.5 * w[2];
}

TEST(test_glossy_lobe)
{
    const double s = 20.0, ks = 0.5, a = 1.0, b = 0.5, PI_ = 3.14159265358979323846;
    material m;
    surface sf;
    irc_sh sh;
    float r[3], w[3], wt[3], out[3];
    int i, k, n = 16384;
    memset(&m, 0, sizeof m);
    memset(&sf, 0, sizeof sf);
    memset(&sh, 0, sizeof sh);
    m.ks[0] = m.ks[1] = m.ks[2] = (float)ks;
    m.ns = (float)s;
    sf.m = &m;
    sf.ns[2] = sf.nsm[2] = sf.ng[2] = 1.0f;
    sh.bands = 2;
    sh.channels = 3;
    for (k = 0; k < 3; k++) {
        sh.c[k][0] = (float)(2.0 * sqrt(PI_) * a);      /* y00 = 1/(2 sqrt(pi)) */
        sh.c[k][2] = (float)(2.0 * sqrt(PI_ / 3.0) * b); /* y10 = sqrt(3/(4 pi)) z */
    }
    for (k = 0; k < 2; k++) {
        const double th = k ? 30.0 * PI_ / 180.0 : 0.0;
        const float d[3] = {(float)sin(th), 0.0f, (float)-cos(th)};
        glossy_axis(&sf, d, r);
        double mc = 0.0;
        for (i = 0; i < n; i++) {
            glossy_sample(&sf, r, 0x1234ull, i, n, w, wt);
            mc += wt[0] * lin_radiance(w) / n;
        }
        CHECK(glossy_from_sh(&sh, &sf, d, out) == IRC_OK, "SH path");
        printf("  %2.0f degrees: lobe samples %.5f, SH path %.5f\n", th * 180.0 / PI_, mc,
               out[0]);
        if (k == 0) {
            const double want = ks * (a + b * (s + 2.0) / (s + 3.0));
            CHECK(fabs(mc - want) < 0.002 * want, "lobe samples %g vs %g", mc, want);
            CHECK(fabs(out[0] - want) < 0.005 * want, "SH path %g vs %g", out[0], want);
        } else {
            CHECK(fabs(out[0] - mc) < 0.005 * mc, "off the normal: SH %g vs lobe %g", out[0], mc);
        }
    }
}

/* The sun (scene statement sun): a Lambertian plane z = 0 of albedo 0.5
 * under a sun of irradiance 2 from (0.6, 0, 0.8), a black sphere of radius
 * 1 at (0, 0, 2) above it.  Lit points reflect kd/pi E cos = 0.5/pi 2 0.8
 * exactly; the point whose ray toward the sun passes through the
 * sphere's centre, and points in its shadow, get nothing; one shadow ray
 * each. */
TEST(test_sun)
{
    static const float lit[3][2] = {{3, 3}, {2, -1}, {-1.5f, 1.2f}}, dark[2][2] = {{-1.5f, 0},
                                                                                   {-1.2f, 0.3f}};
    material mats[2];
    triangle tris[2];
    sphere sp;
    scene s;
    bvh b;
    lights l;
    const float want = 0.5f / (float)TPI * 2.0f * 0.8f, down[3] = {0, 0, -1};
    int i, k;
    ball_over_plane(&s, mats, tris, &sp);
    s.sun.on = 1;
    s.sun.dir[0] = 0.6f;
    s.sun.dir[2] = 0.8f;
    s.sun.e[0] = s.sun.e[1] = s.sun.e[2] = 2.0f;
    CHECK(bvh_build(&b, &s) == 0 && lights_build(&l, &s) == 0, "build");
    for (i = 0; i < 5; i++) {
        const float *xy = i < 3 ? lit[i] : dark[i - 3];
        float o[3] = {xy[0], xy[1], 5.0f}, out[3];
        uint64_t rays = 0;
        bvh_hit h;
        surface sf;
        CHECK(bvh_intersect(&b, o, down, 0.0f, 1e30f, &h) && h.prim >= 0, "the plane at point %d", i);
        surface_at(&s, o, down, &h, &sf);
        direct_light(&b, &l, &sf, down, 4, 1, out, &rays);
        for (k = 0; k < 3; k++)
            CHECK(i < 3 ? fabsf(out[k] - want) <= 1e-6f * want : out[k] == 0.0f,
                  "point %d: %g, want %g", i, (double)out[k], i < 3 ? (double)want : 0.0);
        CHECK(rays == 1, "point %d: %llu shadow rays", i, (unsigned long long)rays);
    }
    bvh_free(&b);
    lights_free(&l);
}

#define TESTS(X) X(test_cache_save_killed) X(test_sun) X(test_bvh_soup) X(test_bvh_shipped_scenes) X(test_reference_sphere_plane) X(test_leak_scene) X(test_deterministic_fill) X(test_detail_map) \
    X(test_image_gradient) X(test_glossy_lobe) X(test_bounces_furnace) X(test_bounces_tilted_normals)
TESTS(TEST_DECL)

int main(int argc, char **argv)
{
    static const test_case all[] = {TESTS(TEST_ROW)};
    return test_run(all, sizeof all / sizeof all[0], argc, argv);
}
