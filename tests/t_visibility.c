/* t_visibility.c -- visibility gradients against closed forms, and against
 * the Krivanek (Ward-Heckbert) gradient on the same points. */
#define IRC_EXPERIMENTAL /* irc_occlusion_compute (irrcache.h) */
#include <math.h>
#include <string.h>

#include "irrcache.h"
#include "scenes.h"
#include "test.h"


static double gerr(const irc_record *r, const double g[3])
{
    return hypot(r->grad_t[0][0] - g[0], r->grad_t[0][1] - g[1]);
}

/* Records with and without visibility gradients at p, both at m x n strata. */
static int both(tscene *s, const double pd[3], uint32_t m, uint32_t n, irc_record *vis,
                irc_record *wh)
{
    irc_config cv = scene_config(s, IRC_FEATURE_VISIBILITY, m, n);
    irc_config cw = scene_config(s, IRC_FEATURE_TRANSLATION, m, n);
    irc_cache *a = block_cache(&cv, 2, 0), *b = block_cache(&cw, 2, 0);
    const float p[3] = {(float)pd[0], (float)pd[1], (float)pd[2]}, up[3] = {0, 0, 1};
    int ok = a && b && irc_record_compute(a, p, up, vis, NULL) == IRC_OK &&
             irc_record_compute(b, p, up, wh, NULL) == IRC_OK;
    block_free(&cv);
    block_free(&cw);
    return ok;
}

/* The first-order paper's Fig. 14 case: a black sphere (r 1, centre height
 * 2) over the plane under a uniform sky; E = pi L (1 - r^2 cos(theta)/d^2)
 * and its analytic gradient.  Twenty points at distances 0.25 to 6.5 from
 * the sphere's foot, in two directions each, at 32 x 128 strata.  Every
 * visibility gradient must be within 1/255 of the largest analytic
 * gradient among them, with at most 1.3 x the strata's rays (the
 * bisection's budget; the silhouette's depth extrapolated). */
TEST(test_visibility_sphere)
{
    static const double rad[10] = {0.25, 0.5, 0.8, 1.2, 1.7, 2.3, 3.0, 4.0, 5.0, 6.5};
    tscene s;
    double pts[20][3], g[20][3], big = 0.0, worst = 0.0;
    irc_record v[20], w[20];
    int i;
    scene_sphere_plane(&s);
    for (i = 0; i < 20; i++) {
        double ang = (i & 1 ? 2.1 : 0.4) + 0.05 * i;
        pts[i][0] = rad[i / 2] * cos(ang);
        pts[i][1] = rad[i / 2] * sin(ang);
        pts[i][2] = 0.0;
        sphere_plane_grad(&s, pts[i], g[i]);
        if (hypot(g[i][0], g[i][1]) > big)
            big = hypot(g[i][0], g[i][1]);
    }
    for (i = 0; i < 20; i++) {
        double ev, ew;
        CHECK(both(&s, pts[i], 32, 128, &v[i], &w[i]), "compute at point %d", i);
        ev = gerr(&v[i], g[i]);
        ew = gerr(&w[i], g[i]);
        if (ev > worst)
            worst = ev;
        printf("  (%6.3f, %6.3f): |grad| %.5f; visibility error %.6f (%u rays), Krivanek %.6f\n",
               pts[i][0], pts[i][1], hypot(g[i][0], g[i][1]), ev, v[i].rays, ew);
        CHECK(ev <= big / 255.0, "point %d: error %g > %g", i, ev, big / 255.0);
        CHECK(v[i].rays <= 13u * 32u * 128u / 10u, "point %d: %u rays, over 1.3 x the strata", i,
              v[i].rays);
        CHECK(ev < ew, "point %d: visibility %g not better than Krivanek %g", i, ev, ew);
    }
    printf("  worst visibility error %.6f = 1/%.0f of the largest gradient %.5f\n", worst,
           big / worst, big);
}

/* A black box (polygonal blocker): gradients against central differences
 * of the closed form (Lambert's polygon form factor), within 2% at 64 x 256
 * strata (at 32 x 128 the two farthest points, whose gradients are 1/40 of
 * the nearest ones, read 1.6% and 2.4% off).  Twenty
 * points: under the box, around it, diagonal, far, and seven within 0.01
 * of a face's plane (that face seen nearly edge-on); from every point the
 * box's vertical edges lie in meridian planes, where the paper's
 * phi-integrand is singular (c.n -> 0). */
TEST(test_visibility_box)
{
    static const double pts[20][2] = {
        {0.7, 0.3},   {0.9, 0.5},    {-0.3, -0.1}, {2.0, 0.2},   {-1.5, 0.1},
        {0.3, 1.8},   {0.4, -1.4},   {2.2, 1.9},   {-1.6, -1.5}, {3.5, -2.0},
        {-0.49, 0.4}, {-0.51, -1.0}, {1.09, 0.3},  {1.11, 1.5},  {0.2, -0.29},
        {0.6, -0.31}, {0.0, 0.71},   {5.0, 0.5},   {0.3, -4.0},  {-3.0, 3.0}};
    tscene s;
    int i, k;
    scene_box_plane(&s);
    for (i = 0; i < 20; i++) {
        double p[3] = {pts[i][0], pts[i][1], 0.0}, g[3] = {0, 0, 0}, gm, ev, ew;
        const double h = 1e-4;
        irc_record v, w;
        for (k = 0; k < 2; k++) {
            double q[3], e1, e0;
            memcpy(q, p, sizeof q);
            q[k] += h;
            e1 = box_plane_e(&s, q);
            q[k] -= 2.0 * h;
            e0 = box_plane_e(&s, q);
            g[k] = (e1 - e0) / (2.0 * h);
        }
        gm = hypot(g[0], g[1]);
        CHECK(both(&s, p, 64, 256, &v, &w), "compute at point %d", i);
        ev = gerr(&v, g);
        ew = gerr(&w, g);
        printf("  (%5.2f, %5.2f): |grad| %.5f; visibility error %.2f%% (%u rays), Krivanek %.2f%%\n",
               p[0], p[1], gm, 100.0 * ev / gm, v.rays, 100.0 * ew / gm);
        CHECK(ev <= 0.02 * gm, "point %d: %.2f%% off", i, 100.0 * ev / gm);
        CHECK(v.rays <= 13u * 64u * 256u / 10u, "point %d: %u rays, over 1.3 x the strata", i,
              v.rays);
        CHECK(ev < ew, "point %d: visibility %g not better than Krivanek %g", i, ev, ew);
    }
}

/* No blocker: no crossing, no extra ray, the same zero gradient. */
TEST(test_visibility_open_sky)
{
    tscene s;
    irc_config cfg;
    irc_cache *c;
    irc_record r;
    const float p[3] = {0, 0, 0}, n[3] = {0.3f, 0.0f, 1.0f};
    scene_init(&s);
    s.sky_a[0] = s.sky_a[1] = s.sky_a[2] = 2.0f;
    cfg = scene_config(&s, IRC_FEATURE_VISIBILITY, 16, 64);
    c = block_cache(&cfg, 2, 0);
    CHECK(c && irc_record_compute(c, p, n, &r, NULL) == IRC_OK, "compute");
    CHECK(r.rays == 16u * 64u, "rays %u", r.rays);
    CHECK(hypot(r.grad_t[0][0], r.grad_t[0][1]) == 0.0 && r.grad_t[0][2] == 0.0, "gradient");
    CHECK(r.features & IRC_FEATURE_TRANSLATION, "visibility implies the translational gradient");
    block_free(&cfg);
}

/* Net visibility (Eq. 47/48) of the black sphere: the visible fraction is
 * sqrt(1 - r^2/d^2) (the sphere subtends 2 pi (1 - cos asin(r/d))), whose
 * gradient along the plane is r^2 / (d^4 sqrt(1 - r^2/d^2)) (p - C).  Ten
 * points at 32 x 128 strata: the fraction within 0.5%, the gradient within
 * 1/255 of the largest. */
TEST(test_occlusion_sphere)
{
    static const double rad[10] = {0.2, 0.5, 0.8, 1.1, 1.5, 2.0, 2.6, 3.3, 4.2, 5.5};
    tscene s;
    irc_config cfg;
    irc_cache *c;
    double big = 0.0, g[10][2], fr[10];
    float pts[10][3];
    int i;
    scene_sphere_plane(&s);
    for (i = 0; i < 10; i++) {
        double a = 0.3 + 0.7 * i, x = rad[i] * cos(a), y = rad[i] * sin(a);
        double d2 = x * x + y * y + 4.0, q = sqrt(1.0 - 1.0 / d2);
        pts[i][0] = (float)x;
        pts[i][1] = (float)y;
        pts[i][2] = 0.0f;
        fr[i] = q;
        g[i][0] = x / (d2 * d2 * q);
        g[i][1] = y / (d2 * d2 * q);
        if (hypot(g[i][0], g[i][1]) > big)
            big = hypot(g[i][0], g[i][1]);
    }
    cfg = scene_config(&s, IRC_FEATURE_VISIBILITY, 32, 128);
    c = block_cache(&cfg, 2, 0);
    CHECK(c != NULL, "init");
    if (!c) return;
    for (i = 0; i < 10; i++) {
        const float up[3] = {0, 0, 1};
        irc_occlusion o;
        double e;
        CHECK(irc_occlusion_compute(c, pts[i], up, &o, NULL) == IRC_OK, "compute");
        e = hypot(o.grad[0] - g[i][0], o.grad[1] - g[i][1]);
        printf("  (%6.3f, %6.3f): visible %.5f (exact %.5f); |grad| %.5f, error %.6f; %u rays\n",
               pts[i][0], pts[i][1], o.visible, fr[i], hypot(g[i][0], g[i][1]), e, o.rays);
        CHECK(fabs(o.visible - fr[i]) <= 0.005 * fr[i], "visible %g vs %g", o.visible, fr[i]);
        CHECK(e <= big / 255.0, "point %d: gradient error %g > %g", i, e, big / 255.0);
    }
    {
        irc_config plain = scene_config(&s, IRC_FEATURE_TRANSLATION, 8, 16);
        irc_cache *pc = block_cache(&plain, 2, 0);
        irc_occlusion o;
        const float up[3] = {0, 0, 1};
        CHECK(irc_occlusion_compute(pc, pts[0], up, &o, NULL) == IRC_ERR_UNSUPPORTED, "needs the flag");
        block_free(&plain);
    }
    block_free(&cfg);
}
