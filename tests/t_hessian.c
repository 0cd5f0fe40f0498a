/* t_hessian.c -- the occlusion-aware Hessian of irradiance against the
 * second derivatives of closed forms (central differences of the exact
 * E, step 1e-3), and the 2x2 eigen-decomposition on hand-built matrices.
 * The eigen test calls the internal irc__eigen2 on purpose (cache.h). */
#include <math.h>
#include <string.h>

#include "cache.h"
#include "scenes.h"
#include "test.h"

typedef double (*closed_fn)(const tscene *s, const double p[3]);

/* d2E/dx2, d2E/dxdy, d2E/dy2 of the closed form at p (on z = 0). */
static void closed_hessian(const tscene *s, closed_fn f, const double p[3], double h[3])
{
    const double e = 1e-3;
    double q[3];
    int i, j;
    double v[3][3];
    for (i = -1; i <= 1; i++)
        for (j = -1; j <= 1; j++) {
            q[0] = p[0] + i * e;
            q[1] = p[1] + j * e;
            q[2] = p[2];
            v[i + 1][j + 1] = f(s, q);
        }
    h[0] = (v[2][1] - 2.0 * v[1][1] + v[0][1]) / (e * e);
    h[1] = (v[2][2] - v[2][0] - v[0][2] + v[0][0]) / (4.0 * e * e);
    h[2] = (v[1][2] - 2.0 * v[1][1] + v[1][0]) / (e * e);
}

/* Relative Frobenius error of the record's tangent Hessian (channel 0). */
static double hessian_error(const irc_record *r, const double h[3])
{
    const float *g = r->hessian[0];
    double dxx = g[0] - h[0], dxy = g[1] - h[1], dyy = g[3] - h[2];
    return sqrt((dxx * dxx + 2.0 * dxy * dxy + dyy * dyy) /
                (h[0] * h[0] + 2.0 * h[1] * h[1] + h[2] * h[2]));
}

/* Angle in degrees between the major eigenvectors (largest |l|) of the
 * record's tangent Hessian and of the closed form's. */
static double axis_error(const irc_record *r, const double h[3])
{
    double l0, l1, u[2], v[2], c;
    irc__eigen2(r->hessian[0][0], r->hessian[0][1], r->hessian[0][3], &l0, &l1, u);
    irc__eigen2(h[0], h[1], h[2], &l0, &l1, v);
    c = fabs(u[0] * v[0] + u[1] * v[1]);
    return acos(c > 1.0 ? 1.0 : c) * 180.0 / 3.14159265358979;
}

static double worst_axis;

static double worst_over(tscene *s, closed_fn f, const double (*pts)[3], int npts,
                         uint32_t m, uint32_t n, const char *what)
{
    irc_config cfg = scene_config(s, IRC_FEATURE_HESSIAN, m, n);
    irc_cache *c = block_cache(&cfg, 16, 0);
    double worst = 0.0;
    int i;
    if (!c) return 1e9;
    for (i = 0; i < npts; i++) {
        const float p[3] = {(float)pts[i][0], (float)pts[i][1], 0.0f}, nn[3] = {0, 0, 1};
        irc_record r;
        double h[3], err;
        if (irc_record_compute(c, p, nn, &r, NULL) != IRC_OK)
            return 1e9;
        closed_hessian(s, f, pts[i], h);
        err = hessian_error(&r, h);
        if (axis_error(&r, h) > worst_axis)
            worst_axis = axis_error(&r, h);
        printf("  %s (%.1f, %.1f) %ux%u: H %+.4f %+.4f %+.4f, closed form %+.4f %+.4f %+.4f: "
               "%.2f%%\n", what, pts[i][0], pts[i][1], m, n, r.hessian[0][0], r.hessian[0][1],
               r.hessian[0][3], h[0], h[1], h[2], 100.0 * err);
        if (err > worst)
            worst = err;
    }
    block_free(&cfg);
    return worst;
}

/* A black unit sphere at height 2 over the plane under a uniform sky, and
 * a black disk of radius 0.8 at height 1. */
TEST(test_hessian_closed_forms)
{
    static const double sp[4][3] = {{0.5, 0, 0}, {1, 1, 0}, {-1.5, 0.5, 0}, {2, -1, 0}};
    static const double dk[3][3] = {{0.3, 0, 0}, {1.2, 0, 0}, {-0.5, 1.0, 0}};
    tscene s;
    double w;
    scene_sphere_plane(&s);
    worst_axis = 0.0;
    w = worst_over(&s, sphere_plane_e, sp, 4, 64, 256, "sphere");
    /* A curved blocker's silhouette slides over it as p moves, while the
     * triangles between hit points move as a rigid polygon: the
     * magnitudes read 22-45% high (README); the principal axes, which
     * orient a record's radii, hold. */
    printf("  sphere: worst magnitude error %.1f%%, worst major axis %.2f deg\n", 100.0 * w,
           worst_axis);
    CHECK(worst_axis < 3.0, "sphere: major axis off by %.2f deg", worst_axis);
    scene_init(&s);
    s.sky_a[0] = s.sky_a[1] = s.sky_a[2] = 1.0f;
    s.has_disk = 1;
    s.disk_c[2] = 1.0;
    s.disk_r = 0.8;
    w = worst_over(&s, disk_plane_e, dk, 3, 64, 256, "disk");
    CHECK(w < 0.05, "disk: worst %.2f%%", 100.0 * w);
}

/* Hand-built matrices: the eigenvalues and the major axis, with negative,
 * zero and equal eigenvalues, and a vanishing off-diagonal. */
TEST(test_eigen2)
{
    static const struct { double a, b, c, l0, l1, ang; } cases[] = {
        {3, 0, 1, 3, 1, 0},          /* diagonal */
        {1, 0, 3, 3, 1, 90},         /* diagonal, the larger second */
        {1, 0, -3, -3, 1, 90},       /* the larger in size negative */
        {-3, 0, 1, -3, 1, 0},
        {2, 1, 2, 3, 1, 45},         /* off-diagonal */
        {2, -1, 2, 3, 1, -45},
        {0, 1, 0, 1, -1, 45},        /* indefinite, equal sizes */
        {0, 0, 0, 0, 0, -1},         /* zero: any axis */
        {2, 0, 2, 2, 2, -1},         /* equal: any axis */
        {1, 1e-300, 4, 4, 1, 90},    /* a vanishing off-diagonal */
        {5, 2, 5e-9, 5.70156, -0.70156, 19.3299}}; /* 2.5 +- sqrt(10.25); atan2(4, 5)/2 */
    size_t i;
    for (i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        double l0, l1, u[2], ang;
        irc__eigen2(cases[i].a, cases[i].b, cases[i].c, &l0, &l1, u);
        ang = atan2(u[1], u[0]) * 180.0 / 3.14159265358979;
        while (ang > 90.0) ang -= 180.0;
        while (ang <= -90.0) ang += 180.0;
        CHECK(fabs(l0 - cases[i].l0) < 1e-4 && fabs(l1 - cases[i].l1) < 1e-4 &&
                  fabs(u[0] * u[0] + u[1] * u[1] - 1.0) < 1e-12,
              "case %zu: l %g %g, want %g %g", i, l0, l1, cases[i].l0, cases[i].l1);
        if (cases[i].ang > -1.0 || cases[i].ang < -1.0) {
            double d = fabs(ang - cases[i].ang);
            if (d > 90.0) d = 180.0 - d;
            CHECK(d < 0.01, "case %zu: axis at %.3f deg, want %.3f", i, ang, cases[i].ang);
        }
        /* A u = l0 u, whatever the case. */
        CHECK(fabs(cases[i].a * u[0] + cases[i].b * u[1] - l0 * u[0]) < 1e-9 &&
                  fabs(cases[i].b * u[0] + cases[i].c * u[1] - l0 * u[1]) < 1e-9,
              "case %zu: not an eigenvector", i);
    }
}


/* The radius rule with gradients (irradiance.c, irc__hessian_radius):
 * R = sqrt(2 E/|l|), so that first-order extrapolation errs by a^2 E at
 * the edge of reach a R along the Hessian's major axis.  Checked against
 * the disk's closed form: the true error of the exact first-order
 * extrapolation there, where the Hessian and not the split sphere set R. */
TEST(test_hessian_radius)
{
    static const double pts[3][3] = {{0.3, 0, 0}, {1.2, 0, 0}, {-0.5, 1.0, 0}};
    tscene s;
    irc_config cfg;
    irc_cache *c;
    int i, bound = 0;
    scene_init(&s);
    s.sky_a[0] = s.sky_a[1] = s.sky_a[2] = 1.0f;
    s.has_disk = 1;
    s.disk_c[2] = 1.0;
    s.disk_r = 0.8;
    cfg = scene_config(&s, IRC_FEATURE_TRANSLATION | IRC_FEATURE_HESSIAN, 64, 256);
    c = block_cache(&cfg, 16, 0);
    CHECK(c != NULL, "init");
    if (!c) return;
    for (i = 0; i < 3; i++) {
        const float p[3] = {(float)pts[i][0], (float)pts[i][1], 0.0f}, nn[3] = {0, 0, 1};
        const double a = cfg.accuracy > 0.0f ? cfg.accuracy : 0.2, e = 1e-5;
        double h[3], l0, l1, u[2], d, q[3], g[2], e0, err;
        irc_record r;
        CHECK(irc_record_compute(c, p, nn, &r, NULL) == IRC_OK, "compute");
        irc__eigen2(r.hessian[0][0], r.hessian[0][1], r.hessian[0][3], &l0, &l1, u);
        if (fabs(r.radius - sqrt(2.0 * r.e[0] / fabs(l0))) > 1e-4 * r.radius) {
            printf("  (%.1f, %.1f): R %.4f set by the split sphere (%.4f)\n", pts[i][0],
                   pts[i][1], r.radius, r.mean_dist);
            continue;
        }
        bound++;
        /* exact value and exact gradient of the closed form at p */
        closed_hessian(&s, disk_plane_e, pts[i], h);
        e0 = disk_plane_e(&s, pts[i]);
        memcpy(q, pts[i], sizeof q);
        q[0] += e;
        g[0] = (disk_plane_e(&s, q) - e0) / e;
        q[0] -= e;
        q[1] += e;
        g[1] = (disk_plane_e(&s, q) - e0) / e;
        d = a * r.radius;
        q[0] = pts[i][0] + d * u[0];
        q[1] = pts[i][1] + d * u[1];
        q[2] = 0.0;
        err = fabs(disk_plane_e(&s, q) - e0 - d * (g[0] * u[0] + g[1] * u[1])) / e0;
        printf("  (%.1f, %.1f): R %.4f, first-order error at a R: %.5f (a^2 = %.4f)\n",
               pts[i][0], pts[i][1], r.radius, err, a * a);
        CHECK(err > 0.5 * a * a && err < 1.5 * a * a, "error %.5f at the edge, want ~%.4f", err,
              a * a);
    }
    CHECK(bound >= 1, "no point had its radius set by the Hessian");
    block_free(&cfg);
}
