/*
 * t_shrec.c -- SH records: coefficients and gradients of a spherical
 * emitter against closed forms, the clamped-cosine and Phong convolutions
 * against independent quadrature, Eq. 14-16 lookups by hand, and bad input.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "test.h"
#include "scenes.h"
#include "../src/cache.h"

#define NC 25

/* Legendre P_0..P_kmax at x. */
static void legendre(double x, int kmax, double *p)
{
    int k;
    p[0] = 1.0;
    p[1] = x;
    for (k = 1; k < kmax; k++)
        p[k + 1] = ((2.0 * k + 1.0) * x * p[k] - k * p[k - 1]) / (k + 1.0);
}

/* Coefficients of a sphere of radiance 1, centre cc, radius rho, seen from
 * p: a cap of half-angle alpha, sin alpha = rho/D, a zonal function about
 * the centre's direction u, so by Funk-Hecke c_lm = lambda_l y_lm(u),
 * lambda_l = 2 pi integral_{cos alpha}^1 P_l = 2 pi (P_l-1 - P_l+1)(cos
 * alpha)/(2l+1) (l > 0), 2 pi (1 - cos alpha) (l = 0). */
static void cap_coeffs(const double p[3], const double cc[3], double rho, int bands,
                       double *c)
{
    double u[3], d = 0.0, x, pl[8], lam[6], y[NC];
    int k, l, m;
    for (k = 0; k < 3; k++) {
        u[k] = cc[k] - p[k];
        d += u[k] * u[k];
    }
    d = sqrt(d);
    x = sqrt(1.0 - rho * rho / (d * d));
    legendre(x, 6, pl);
    lam[0] = 2.0 * TPI * (1.0 - x);
    for (l = 1; l < bands; l++)
        lam[l] = 2.0 * TPI * (pl[l - 1] - pl[l + 1]) / (2.0 * l + 1.0);
    irc__sh_eval(bands, u, y, NULL);
    for (l = 0; l < bands; l++)
        for (m = -l; m <= l; m++)
            c[l * l + l + m] = lam[l] * y[l * l + l + m];
}

/* The same cap projected by brute quadrature in the cap's own frame (a
 * check on the closed form, not on the library). */
static void cap_quadrature(const double u[3], double alpha, int bands, double *c)
{
    const int nt = 400, np = 400;
    double t1[3], t2[3], y[NC];
    int i, j, k;
    irc__frame(u, t1, t2);
    memset(c, 0, sizeof(double) * (size_t)(bands * bands));
    for (i = 0; i < nt; i++) {
        double th = alpha * (i + 0.5) / nt, dw = sin(th) * (alpha / nt) * (2.0 * TPI / np);
        for (j = 0; j < np; j++) {
            double ph = 2.0 * TPI * (j + 0.5) / np, w[3];
            for (k = 0; k < 3; k++)
                w[k] = sin(th) * (cos(ph) * t1[k] + sin(ph) * t2[k]) + cos(th) * u[k];
            irc__sh_eval(bands, w, y, NULL);
            for (k = 0; k < bands * bands; k++)
                c[k] += dw * y[k];
        }
    }
}

TEST(test_sh_cap_closed_form)
{
    double u[3] = {0.6, 0.48, 0.64}, p[3] = {0, 0, 0}, cc[3], a[NC], b[NC], worst = 0.0;
    int k;
    for (k = 0; k < 3; k++)
        cc[k] = 4.0 * u[k];
    cap_coeffs(p, cc, 1.0, 5, a);
    cap_quadrature(u, asin(0.25), 5, b);
    for (k = 0; k < 25; k++)
        worst = fmax(worst, fabs(a[k] - b[k]));
    printf("  cap at D/r = 4, bands 0-4: closed form vs 400x400 quadrature %.2e\n", worst);
    CHECK(worst < 1e-5, "closed form %.3e", worst);
}

/* Config of an SH cache on scene s. */
static irc_config sh_config(tscene *s, uint32_t features, uint32_t m, uint32_t n,
                            uint32_t bands)
{
    irc_config cfg = scene_config(s, features, m, n);
    cfg.sh_bands = bands;
    return cfg;
}

/* One free-point record (or the mean of `seeds` of them) at the origin
 * with a unit emitter at distance dr along a generic direction: the largest
 * coefficient and gradient errors relative to the largest coefficient and
 * gradient of the closed form (gradient by central differences of it). */
static void emitter_errors(double dr, uint32_t m, uint32_t n, int seeds, double *ec,
                           double *eg)
{
    const double dir[3] = {0.6, 0.48, 0.64};
    double cc[3], c0[NC], g[NC][3], mc[NC] = {0}, mg[NC][3] = {{0}}, cbig = 0, gbig = 0;
    float p[3] = {0, 0, 0};
    tscene s;
    irc_config cfg;
    irc_cache *c;
    irc_sh rec;
    int i, k, sd;
    scene_init(&s);
    s.sky_a[0] = s.sky_a[1] = s.sky_a[2] = 0.0f;
    s.has_sphere = 1;
    s.radius = 1.0;
    s.sphere_l[0] = s.sphere_l[1] = s.sphere_l[2] = 1.0f;
    for (k = 0; k < 3; k++)
        s.centre[k] = cc[k] = dr * dir[k];
    cfg = sh_config(&s, IRC_FEATURE_SH_GRADIENT, m, n, 3);
    c = block_cache(&cfg, 4, 0);
    CHECK(c != NULL, "init");
    if (!c)
        return;
    for (sd = 0; sd < seeds; sd++) {
        c->cfg.seed = (uint64_t)sd + 1;
        CHECK(irc_sh_compute(c, p, NULL, &rec) == IRC_OK, "compute");
        for (i = 0; i < 9; i++) {
            mc[i] += rec.c[1][i] / seeds;
            for (k = 0; k < 3; k++)
                mg[i][k] += rec.grad[1][i][k] / seeds;
        }
    }
    block_free(&cfg);
    {
        double o[3] = {0, 0, 0};
        cap_coeffs(o, cc, 1.0, 3, c0);
    }
    for (k = 0; k < 3; k++) {
        double a[NC], b[NC], q[3] = {0, 0, 0}, h = 1e-4 * dr;
        q[k] = h;
        cap_coeffs(q, cc, 1.0, 3, a);
        q[k] = -h;
        cap_coeffs(q, cc, 1.0, 3, b);
        for (i = 0; i < 9; i++)
            g[i][k] = (a[i] - b[i]) / (2.0 * h);
    }
    *ec = *eg = 0.0;
    for (i = 0; i < 9; i++) {
        double e2 = 0.0;
        cbig = fmax(cbig, fabs(c0[i]));
        gbig = fmax(gbig, sqrt(g[i][0] * g[i][0] + g[i][1] * g[i][1] + g[i][2] * g[i][2]));
        *ec = fmax(*ec, fabs(mc[i] - c0[i]));
        for (k = 0; k < 3; k++)
            e2 += (mg[i][k] - g[i][k]) * (mg[i][k] - g[i][k]);
        *eg = fmax(*eg, sqrt(e2));
    }
    *ec /= cbig;
    *eg /= gbig;
}

/* The test: L = 3, D/r from 3 to 50, coefficients and gradient
 * within 1% of their largest magnitude.  Sample counts: 512 x 2048 strata
 * a hemisphere (2.1 M rays) up to D/r = 10; at 20 and 50 the emitter covers
 * ~1700 and ~270 strata of 1024 x 4096, and one record's own sampling noise
 * is about 1% there, so the mean of 4 records (33.6 M rays) is checked. */
TEST(test_sh_emitter_gradient)
{
    static const struct { double dr; uint32_t m, n; int seeds; } cases[] = {
        {3, 512, 2048, 1}, {5, 512, 2048, 1}, {10, 512, 2048, 1},
        {20, 1024, 4096, 4}, {50, 1024, 4096, 4}};
    int i, count = getenv("IRC_TEST_QUICK") ? 2 : 5;
    for (i = 0; i < count; i++) {
        double ec, eg;
        emitter_errors(cases[i].dr, cases[i].m, cases[i].n, cases[i].seeds, &ec, &eg);
        printf("  D/r %4.0f, %ux%u x %d: coefficients %.3f%%, gradient %.3f%% of largest\n",
               cases[i].dr, cases[i].m, cases[i].n, cases[i].seeds, 100 * ec, 100 * eg);
        CHECK(ec < 0.01, "D/r %g coefficients %.4f", cases[i].dr, ec);
        CHECK(eg < 0.01, "D/r %g gradient %.4f", cases[i].dr, eg);
    }
}
