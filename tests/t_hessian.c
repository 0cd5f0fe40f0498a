/* t_hessian.c -- the occlusion-aware Hessian of irradiance against the
 * second derivatives of closed forms (central differences of the exact
 * E, step 1e-3), and the 2x2 eigen-decomposition on hand-built matrices.
 * The eigen test calls the internal irc__eigen2 on purpose (cache.h). */
#include <math.h>
#include <string.h>

#include "block/cache.h"
#include "irr/estimator.h"
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

/* A closed cave for test_hessian_reference: every ray hits at a depth and
 * with a radiance that vary smoothly with its direction, except a patch of
 * one radiance (whose inner edges carry nothing); the rays of the record
 * being computed are kept, in stratum order, for the reference. */
typedef struct cave {
    uint32_t rays, cap;
    float dir[64 * 256][3], dist[64 * 256], l[64 * 256][3];
} cave;

static int cave_trace(const irc_trace_args *a)
{
    cave *cv = (cave *)a->context;
    uint32_t i;
    int c;
    for (i = 0; i < a->count; i++) {
        const float *w = a->rays[i].dir;
        irc_hit *h = &a->hits[i];
        const int patch = w[0] > 0.3f && w[1] > 0.2f;
        h->status = IRC_RAY_HIT;
        h->dist = 1.0f + 0.3f * w[0] * w[0] + 0.2f * w[1] * w[2] + 0.1f * w[2];
        for (c = 0; c < 3; c++) {
            h->normal[c] = -w[c];
            h->radiance[c] = patch ? 2.0f - 0.5f * (float)c
                                   : 0.5f + 0.2f * (float)c + 0.3f * w[c] * w[(c + 1) % 3];
        }
        if (cv->rays < cv->cap) {
            for (c = 0; c < 3; c++) {
                cv->dir[cv->rays][c] = w[c];
                cv->l[cv->rays][c] = h->radiance[c];
            }
            cv->dist[cv->rays++] = h->dist;
        }
    }
    return 0;
}

/* One edge r0 -> r1's -H F_e times pi, straight from the per-edge closed
 * forms (notes/hessian.md), in double, I1 from atan2. */
static void edge_ref(const double r0[3], const double r1[3], const double n[3], const double l[3],
                     double h[3][6])
{
    static const int a[6] = {0, 0, 0, 1, 1, 2}, b[6] = {0, 1, 2, 1, 2, 2};
    double e[3], c[3], nxe[3], g[3], d00, d11, ee, cc, er0, er1, i1, i2, j2, i3, j3, k3, nc;
    int i, ch;
    for (i = 0; i < 3; i++)
        e[i] = r1[i] - r0[i];
    c[0] = r0[1] * r1[2] - r0[2] * r1[1];
    c[1] = r0[2] * r1[0] - r0[0] * r1[2];
    c[2] = r0[0] * r1[1] - r0[1] * r1[0];
    nxe[0] = n[1] * e[2] - n[2] * e[1];
    nxe[1] = n[2] * e[0] - n[0] * e[2];
    nxe[2] = n[0] * e[1] - n[1] * e[0];
    cc = c[0] * c[0] + c[1] * c[1] + c[2] * c[2];
    ee = e[0] * e[0] + e[1] * e[1] + e[2] * e[2];
    d00 = r0[0] * r0[0] + r0[1] * r0[1] + r0[2] * r0[2];
    d11 = r1[0] * r1[0] + r1[1] * r1[1] + r1[2] * r1[2];
    er0 = e[0] * r0[0] + e[1] * r0[1] + e[2] * r0[2];
    er1 = e[0] * r1[0] + e[1] * r1[1] + e[2] * r1[2];
    nc = n[0] * c[0] + n[1] * c[1] + n[2] * c[2];
    i1 = atan2(sqrt(cc), r0[0] * r1[0] + r0[1] * r1[1] + r0[2] * r1[2]) / sqrt(cc);
    i2 = (er1 / d11 - er0 / d00 + ee * i1) / (2.0 * cc);
    j2 = (0.5 * (1.0 / d00 - 1.0 / d11) - er0 * i2) / ee;
    i3 = (er1 / (d11 * d11) - er0 / (d00 * d00) + 3.0 * ee * i2) / (4.0 * cc);
    j3 = (0.25 * (1.0 / (d00 * d00) - 1.0 / (d11 * d11)) - er0 * i3) / ee;
    k3 = (i2 - d00 * i3 - 2.0 * er0 * j3) / ee;
    for (i = 0; i < 3; i++)
        g[i] = i2 * r0[i] + j2 * e[i];
    for (i = 0; i < 6; i++) {
        const double m = i3 * r0[a[i]] * r0[b[i]] + j3 * (r0[a[i]] * e[b[i]] + e[a[i]] * r0[b[i]]) +
                         k3 * e[a[i]] * e[b[i]];
        const double f = nxe[a[i]] * g[b[i]] + g[a[i]] * nxe[b[i]] +
                         nc * (4.0 * m - (a[i] == b[i] ? i2 : 0.0));
        for (ch = 0; ch < 3; ch++)
            h[ch][i] -= l[ch] * f;
    }
}

/* The radiance of triangle (a, b, c) of the cave's strata, its farthest
 * vertex's, plus the floor. */
static const float *cave_shine(const cave *cv, uint32_t a, uint32_t b, uint32_t c)
{
    const float *d = cv->dist;
    return cv->l[d[a] >= d[b] && d[a] >= d[c] ? a : d[b] >= d[c] ? b : c];
}

/* The occlusion-aware Hessian of the cave's record with normal nrm, vertex
 * by vertex as hessian.c first walked the grid: the three edges vertex
 * (j, k) starts, each with the radiances of the two triangles that share
 * it. */
static void cave_hessian(const cave *cv, uint32_t m, uint32_t n, const double nrm[3],
                         double h[3][6])
{
    double fl = 0.0;
    uint32_t j, k, i;
    int ch;
    memset(h, 0, 18 * sizeof(double));
    for (i = 0; i < m * n; i++)
        fl += ((double)cv->l[i][0] + cv->l[i][1] + cv->l[i][2]) / 3.0;
    fl *= 0.01 / (m * n);
    for (j = 0; j < m; j++)
        for (k = 0; k < n; k++) {
            const uint32_t a = j * n + k, b = j * n + (k + 1) % n, c = a + n, d = b + n;
            const uint32_t lft = j * n + (k + n - 1) % n;
            const float *t1 = j + 1 < m ? cave_shine(cv, a, b, c) : NULL;
            const float *t2 = j + 1 < m ? cave_shine(cv, d, c, b) : NULL;
            const float *up = j > 0 ? cave_shine(cv, b, a, b - n) : NULL;
            const float *left = j + 1 < m ? cave_shine(cv, a + n, lft + n, a) : NULL;
            const uint32_t e0[3] = {a, b, c}, e1[3] = {b, c, a};
            const float *la[3] = {t1, t1, t1}, *lb[3] = {up, t2, left};
            int q;
            for (q = 0; q < (j + 1 < m ? 3 : 1); q++) {
                double r0[3], r1[3], l[3];
                for (ch = 0; ch < 3; ch++) {
                    r0[ch] = (double)cv->dist[e0[q]] * cv->dir[e0[q]][ch];
                    r1[ch] = (double)cv->dist[e1[q]] * cv->dir[e1[q]][ch];
                    l[ch] = (la[q] ? la[q][ch] + fl : 0.0) - (lb[q] ? lb[q][ch] + fl : 0.0);
                }
                if (l[0] != 0.0 || l[1] != 0.0 || l[2] != 0.0)
                    edge_ref(r0, r1, nrm, l, h);
            }
        }
}

/* The record's Hessian against a straight double evaluation of the same
 * closed forms over the same triangles (cave_hessian), on grids whose rows
 * do and do not fill blocks of four, with edges wide enough for atan2 (2 x
 * 3), a patch of one radiance and a tilted normal: within 1e-4 of the
 * largest entry, where an edge taken twice, dropped or with the wrong
 * triangle is off by far more.  The cave's Hessian is well conditioned:
 * its terms cancel little. */
TEST(test_hessian_reference)
{
    static const uint32_t grids[7][2] = {{2, 3}, {3, 5}, {4, 8}, {5, 7}, {16, 64}, {16, 64},
                                         {11, 30}};
    static cave cv;
    double worst = 0.0;
    int gi;
    for (gi = 0; gi < 7; gi++) {
        const uint32_t m = grids[gi][0], n = grids[gi][1];
        const double tilt[3] = {0.3 / 0.9695, -0.2 / 0.9695, 0.9 / 0.9695};
        irc_config cfg;
        irc_cache *c;
        irc_record r;
        const float p[3] = {0.1f, -0.2f, 0.0f};
        float nn[3] = {0.0f, 0.0f, 1.0f};
        double h[3][6], nd[3], big = 0.0, err = 0.0;
        int ch, i;
        for (i = 0; gi % 2 && i < 3; i++)
            nn[i] = (float)tilt[i];
        memset(&cfg, 0, sizeof cfg);
        cfg.version = IRC_CONFIG_VERSION;
        cfg.trace = cave_trace;
        cfg.context = &cv;
        cfg.features = IRC_FEATURE_TRANSLATION | IRC_FEATURE_HESSIAN;
        cfg.clamp_neighbours = IRC_OFF;
        cfg.check_visibility = IRC_OFF;
        cfg.strata_theta = m;
        cfg.strata_phi = n;
        c = block_cache(&cfg, 4, 0);
        CHECK(c != NULL, "init %ux%u", m, n);
        if (!c)
            continue;
        cv.rays = 0;
        cv.cap = m * n;
        CHECK(irc_record_compute(c, p, nn, &r, NULL) == IRC_OK, "compute %ux%u", m, n);
        for (i = 0; i < 3; i++)
            nd[i] = r.n[i];
        cave_hessian(&cv, m, n, nd, h);
        for (ch = 0; ch < 3; ch++)
            for (i = 0; i < 6; i++)
                big = fmax(big, fabs(h[ch][i]));
        for (ch = 0; ch < 3; ch++)
            for (i = 0; i < 6; i++)
                err = fmax(err, fabs(r.hessian[ch][i] - h[ch][i]) / big);
        printf("  %ux%u, n (%.2f, %.2f, %.2f): largest entry %.4g, worst difference %.2e of it\n",
               m, n, nd[0], nd[1], nd[2], big, err);
        CHECK(big > 0.0 && err < 1e-4, "%ux%u: %.3e", m, n, err);
        worst = fmax(worst, err);
        block_free(&cfg);
    }
    printf("  worst %.2e\n", worst);
}

/* irc__eigen2 works in float; the tests hold double. */
static void eigen2_d(double a, double b, double c, double *l0, double *l1, double u[2])
{
    float f0, f1, uf[2];
    irc__eigen2((float)a, (float)b, (float)c, &f0, &f1, uf);
    *l0 = f0;
    *l1 = f1;
    u[0] = uf[0];
    u[1] = uf[1];
}

/* Angle in degrees between the major eigenvectors (largest |l|) of the
 * record's tangent Hessian and of the closed form's. */
static double axis_error(const irc_record *r, const double h[3])
{
    double l0, l1, u[2], v[2], c;
    eigen2_d(r->hessian[0][0], r->hessian[0][1], r->hessian[0][3], &l0, &l1, u);
    eigen2_d(h[0], h[1], h[2], &l0, &l1, v);
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
     * magnitudes read 22-45% high (docs/DESIGN.md); the principal axes, which
     * orient a record's radii, hold. */
    printf("  sphere: worst magnitude error %.1f%%, worst major axis %.2f deg\n", 100.0 * w,
           worst_axis);
    CHECK(worst_axis < 3.0, "sphere: major axis off by %.2f deg", worst_axis);
    scene_disk_plane(&s);
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
        {1, 1e-30, 4, 4, 1, 90},     /* a vanishing off-diagonal */
        {5, 2, 5e-9, 5.70156, -0.70156, 19.3299}}; /* 2.5 +- sqrt(10.25); atan2(4, 5)/2 */
    size_t i;
    for (i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        double l0, l1, u[2], ang;
        eigen2_d(cases[i].a, cases[i].b, cases[i].c, &l0, &l1, u);
        ang = atan2(u[1], u[0]) * 180.0 / 3.14159265358979;
        while (ang > 90.0) ang -= 180.0;
        while (ang <= -90.0) ang += 180.0;
        CHECK(fabs(l0 - cases[i].l0) < 1e-4 && fabs(l1 - cases[i].l1) < 1e-4 &&
                  fabs(u[0] * u[0] + u[1] * u[1] - 1.0) < 1e-6, /* float: a few roundings of 6e-8 */
              "case %zu: l %g %g, want %g %g", i, l0, l1, cases[i].l0, cases[i].l1);
        if (cases[i].ang > -1.0 || cases[i].ang < -1.0) {
            double d = fabs(ang - cases[i].ang);
            if (d > 90.0) d = 180.0 - d;
            CHECK(d < 0.01, "case %zu: axis at %.3f deg, want %.3f", i, ang, cases[i].ang);
        }
        /* A u = l0 u, whatever the case, to float rounding: u's entries
         * within about 1e-7 (cos(pi/2) is 4e-8 in float), the matrix's
         * entries at most 5. */
        CHECK(fabs(cases[i].a * u[0] + cases[i].b * u[1] - l0 * u[0]) < 2e-6 &&
                  fabs(cases[i].b * u[0] + cases[i].c * u[1] - l0 * u[1]) < 2e-6,
              "case %zu: not an eigenvector", i);
    }
}


/* E on z = 0 under an emitting sphere of radiance 1 and radius 1 centred
 * at (0, 0, 2), nothing else: pi r^2 cos(theta)/d^2 = 2 pi/d^3. */
static double lamp_e(const double p[3])
{
    double d = sqrt(p[0] * p[0] + p[1] * p[1] + 4.0);
    return 2.0 * TPI / (d * d * d);
}

/* Hessian radii with a translational gradient: along each eigen-axis of
 * the tangent Hessian (eigenvalue l) the radius is sqrt(2 E/|l|), where
 * first-order extrapolation errs by a^2 E at a R; the minor radius on the
 * axis of the larger |l|, the major at most IRC_ANISOTROPY times it, both
 * at most the farthest hit (here an emitting sphere's silhouette,
 * sqrt(d^2 - 1) at distance d from its centre, sampled by 64 x 256 rays:
 * within 5% of it).  Checked against the closed form (lamp_e): the true
 * error of the exact first-order extrapolation at a R along each axis. */
TEST(test_hessian_radius)
{
    static const double pts[4][3] = {{0.3, 0, 0}, {1.2, 0, 0}, {-0.5, 1.0, 0}, {2.0, 0.5, 0}};
    tscene s;
    irc_config cfg;
    irc_cache *c;
    int i, k, uncapped = 0;
    scene_sphere_plane(&s);
    s.sky_a[0] = s.sky_a[1] = s.sky_a[2] = 0.0f;
    s.sphere_l[0] = s.sphere_l[1] = s.sphere_l[2] = 1.0f;
    cfg = scene_config(&s, IRC_FEATURE_TRANSLATION | IRC_FEATURE_HESSIAN, 64, 256);
    c = block_cache(&cfg, 16, 0);
    CHECK(c != NULL, "init");
    if (!c) return;
    for (i = 0; i < 4; i++) {
        const float p[3] = {(float)pts[i][0], (float)pts[i][1], 0.0f}, nn[3] = {0, 0, 1};
        const double a = cfg.accuracy > 0.0f ? cfg.accuracy : 0.2, e = 1e-5;
        const double far = sqrt(pts[i][0] * pts[i][0] + pts[i][1] * pts[i][1] + 4.0 - 1.0);
        double l[2], u[2][2], want[2], got[2], q[3], g[2], e0;
        irc_record r;
        CHECK(irc_record_compute(c, p, nn, &r, NULL) == IRC_OK, "compute");
        eigen2_d(r.hessian[0][0], r.hessian[0][1], r.hessian[0][3], &l[0], &l[1], u[0]);
        u[1][0] = -u[0][1];
        u[1][1] = u[0][0];
        want[0] = sqrt(2.0 * r.e[0] / fabs(l[0]));
        want[1] = l[1] != 0.0 ? sqrt(2.0 * r.e[0] / fabs(l[1])) : HUGE_VAL;
        if (want[1] > IRC_ANISOTROPY * want[0])
            want[1] = IRC_ANISOTROPY * want[0];
        got[0] = r.minor_radius;
        got[1] = r.radius;
        /* exact value and exact gradient of the closed form at p */
        e0 = lamp_e( pts[i]);
        memcpy(q, pts[i], sizeof q);
        q[0] += e;
        g[0] = (lamp_e( q) - e0) / e;
        q[0] -= e;
        q[1] += e;
        g[1] = (lamp_e( q) - e0) / e;
        for (k = 0; k < 2; k++) {
            double d = a * got[k], err;
            q[0] = pts[i][0] + d * u[k][0];
            q[1] = pts[i][1] + d * u[k][1];
            q[2] = 0.0;
            err = fabs(lamp_e( q) - e0 - d * (g[0] * u[k][0] + g[1] * u[k][1])) / e0;
            printf("  (%.2f, %.2f) %s: R %.4f (Hessian %.4f, farthest hit <= %.4f), first-order "
                   "error at a R %.5f (a^2 = %.4f)\n", pts[i][0], pts[i][1], k ? "major" : "minor",
                   got[k], want[k], far, err, a * a);
            if (want[k] < 0.95 * far) {
                uncapped++;
                CHECK(fabs(got[k] - want[k]) < 1e-4 * want[k], "R %g, want %g", got[k], want[k]);
                if (want[k] < IRC_ANISOTROPY * want[0] * (1.0 - 1e-6))
                    CHECK(err > 0.5 * a * a && err < 1.5 * a * a,
                          "error %.5f at the edge, want ~%.4f", err, a * a);
                else
                    CHECK(err < 1.5 * a * a, "error %.5f inside the capped edge", err);
            } else {
                CHECK(got[k] <= far * (1 + 1e-6) && got[k] >= 0.95 * far,
                      "R %g, want the farthest hit, within 5%% of %g", got[k], far);
                CHECK(err < 1.5 * a * a, "error %.5f inside the capped edge", err);
            }
        }
        if (got[0] < got[1])
            CHECK(fabs(r.axis[0] * u[0][0] + r.axis[1] * u[0][1]) < 1e-3 &&
                      fabs(r.axis[0] * u[1][0] + r.axis[1] * u[1][1]) > 0.999,
                  "axis (%g, %g) not along the smaller eigenvalue's (%g, %g)", r.axis[0],
                  r.axis[1], u[1][0], u[1][1]);
    }
    CHECK(uncapped >= 3, "only %d radii set by the Hessian: the test sees too little", uncapped);
    block_free(&cfg);
}
