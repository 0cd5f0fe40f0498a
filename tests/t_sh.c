/* t_sh.c -- the real SH basis and its Cartesian gradient. */
#include <math.h>

#include "block/cache.h" /* internals on purpose: the SH basis (irc__sh_eval) */
#include "sample/sampler.h"
#include "sh/shrec.h"
#include "scenes.h"
#include "test.h"
#include "util.h"

void sh_eval_d(int bands, const double s[3], double *y, double (*g)[3])
{
    float sf[3] = {(float)s[0], (float)s[1], (float)s[2]}, yf[IRC__NC], gf[IRC__NC][3];
    int i, k;
    irc__sh_eval(bands, sf, yf, g ? gf : NULL);
    for (i = 0; i < bands * bands; i++) {
        y[i] = yf[i];
        for (k = 0; g && k < 3; k++)
            g[i][k] = gf[i][k];
    }
}

void frame_d(const double n[3], double t1[3], double t2[3])
{
    float nf[3] = {(float)n[0], (float)n[1], (float)n[2]}, a[3], b[3];
    int k;
    irc__frame(nf, a, b);
    for (k = 0; k < 3; k++) {
        t1[k] = a[k];
        t2[k] = b[k];
    }
}

/* Gauss-Legendre nodes and weights on [-1, 1] by Newton's method on P_n. */
static void gauss_legendre(int n, double *x, double *w)
{
    int i, k, it;
    for (i = 0; i < n; i++) {
        double z = cos(TPI * (i + 0.75) / (n + 0.5)), p0, p1, dp = 1.0;
        for (it = 0; it < 100; it++) {
            double zl;
            p0 = 1.0;
            p1 = z;
            for (k = 2; k <= n; k++) {
                double p2 = ((2.0 * k - 1.0) * z * p1 - (k - 1.0) * p0) / k;
                p0 = p1;
                p1 = p2;
            }
            dp = n * (z * p1 - p0) / (z * z - 1.0);
            zl = z;
            z -= p1 / dp;
            if (fabs(z - zl) < 1e-15)
                break;
        }
        x[i] = z;
        w[i] = 2.0 / ((1.0 - z * z) * dp * dp);
    }
}

/* Integral of y_i y_j over the sphere: 16 Gauss-Legendre nodes in z by 32
 * in phi integrate these degree-8 products exactly. */
TEST(test_sh_orthonormal)
{
    enum { NZ = 16, NP = 32, B = IRC__SH_MAX_BANDS, C = B * B };
    double gx[NZ], gw[NZ], acc[C][C], worst = 0.0;
    int a, b, i, j;
    gauss_legendre(NZ, gx, gw);
    for (i = 0; i < C; i++)
        for (j = 0; j < C; j++)
            acc[i][j] = 0.0;
    for (a = 0; a < NZ; a++)
        for (b = 0; b < NP; b++) {
            double ph = 2.0 * TPI * b / NP, r = sqrt(1.0 - gx[a] * gx[a]);
            double s[3] = {r * cos(ph), r * sin(ph), gx[a]}, y[C];
            sh_eval_d(B, s, y, NULL);
            for (i = 0; i < C; i++)
                for (j = 0; j < C; j++)
                    acc[i][j] += gw[a] * (2.0 * TPI / NP) * y[i] * y[j];
        }
    for (i = 0; i < C; i++)
        for (j = 0; j < C; j++) {
            double e = fabs(acc[i][j] - (i == j));
            if (e > worst)
                worst = e;
        }
    printf("  largest |<y_i, y_j> - delta_ij| over 25 x 25: %.2e\n", worst);
    /* The basis is float: each y within about 1e-6 of its value. */
    CHECK(worst < 3e-6, "not orthonormal: %g", worst);
}

/* Bands 0-2 against their closed forms (Condon-Shortley phase). */
TEST(test_sh_closed_forms)
{
    unsigned long long st = 5;
    int t;
    for (t = 0; t < 100; t++) {
        double s[3], y[9], x, yy, z, l, want[9];
        int i;
        for (i = 0; i < 3; i++)
            s[i] = xrand(&st) * 2.0 - 1.0;
        l = sqrt(s[0] * s[0] + s[1] * s[1] + s[2] * s[2]);
        x = s[0] / l; yy = s[1] / l; z = s[2] / l;
        sh_eval_d(3, s, y, NULL);
        want[0] = 0.5 / sqrt(TPI);
        want[1] = -sqrt(3.0 / (4.0 * TPI)) * yy;
        want[2] = sqrt(3.0 / (4.0 * TPI)) * z;
        want[3] = -sqrt(3.0 / (4.0 * TPI)) * x;
        want[4] = sqrt(15.0 / (4.0 * TPI)) * x * yy;
        want[5] = -sqrt(15.0 / (4.0 * TPI)) * yy * z;
        want[6] = sqrt(5.0 / (16.0 * TPI)) * (3.0 * z * z - 1.0);
        want[7] = -sqrt(15.0 / (4.0 * TPI)) * x * z;
        want[8] = sqrt(15.0 / (16.0 * TPI)) * (x * x - yy * yy);
        for (i = 0; i < 9; i++)
            CHECK(fabs(y[i] - want[i]) < 1e-6, "y_%d %g vs %g", i, y[i], want[i]); /* float */
    }
}

/* The gradient of y_i(s/|s|) against central differences, at s of lengths
 * 0.01 to 100. */
TEST(test_sh_gradient)
{
    enum { C = IRC__SH_MAX_BANDS * IRC__SH_MAX_BANDS };
    unsigned long long st = 9;
    double worst = 0.0;
    int t;
    /* Every L: bands up to 3 take the closed form, more the recurrence. */
    for (t = 0; t < 250; t++) {
        const int B = 1 + t % IRC__SH_MAX_BANDS;
        double s[3], y[C], g[C][3], scale = pow(10.0, xrand(&st) * 4.0 - 2.0);
        int i, k;
        double len;
        for (i = 0; i < 3; i++)
            s[i] = (xrand(&st) * 2.0 - 1.0) * scale;
        len = sqrt(s[0] * s[0] + s[1] * s[1] + s[2] * s[2]);
        sh_eval_d(B, s, y, g);
        for (k = 0; k < 3; k++) {
            double sp[3] = {s[0], s[1], s[2]}, sm[3] = {s[0], s[1], s[2]}, yp[C], ym[C];
            /* The step and the error scale with |s|.  The basis is float,
             * so a difference carries its roundings (about 1e-6 of y) over
             * 2h: 2.5e-4 at this step, the truncation (h^2) far below. */
            double h = 2e-3 * len;
            sp[k] += h;
            sm[k] -= h;
            sh_eval_d(B, sp, yp, NULL);
            sh_eval_d(B, sm, ym, NULL);
            for (i = 0; i < B * B; i++) {
                double fd = (yp[i] - ym[i]) / (2.0 * h), e = fabs(fd - g[i][k]) * len;
                if (e > worst)
                    worst = e;
            }
        }
    }
    printf("  largest |analytic - central difference| x |s|: %.2e\n", worst);
    CHECK(worst < 5e-4, "gradient off by %g", worst);
}
