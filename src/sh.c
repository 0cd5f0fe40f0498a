/*
 * sh.c -- the real spherical-harmonic basis, bands 0..L-1 (L <= 5), and its
 * Cartesian gradient, without trigonometric calls: from the Cartesian
 * components of s, by the associated Legendre recurrence in z on
 * Q_l^m = P_l^m / (1 - z^2)^(m/2) and by (x + i y)^m for the azimuth.
 *
 * y_l0 = K_l0 Q_l^0, y_lm = sqrt2 K_lm Q_l^m Re (x+iy)^m, y_l-m = sqrt2 K_lm
 * Q_l^m Im (x+iy)^m, K_lm = sqrt((2l+1)/(4 pi) (l-m)!/(l+m)!), with the
 * Condon-Shortley phase; coefficient index l^2 + l + m.
 *
 * Differentiating the recurrences gives the gradient of the polynomial
 * that equals y on the sphere; the gradient of y(s/|s|) is its part tangent
 * to the sphere over |s|, whichever polynomial that is.
 */
#include "cache.h"

/* K_lm = sqrt((2l+1)/(4 pi) (l-m)!/(l+m)!), times sqrt2 for m > 0, for
 * l < 5 (a wrong digit fails test_sh's orthonormality check). */
static const double irc__sh_k[IRC__SH_MAX_BANDS][IRC__SH_MAX_BANDS] = {
    {0.28209479177387814},
    {0.48860251190291992, 0.48860251190291998},
    {0.63078313050504009, 0.36418281019735976, 0.18209140509867988},
    {0.7463526651802308, 0.3046971996429772, 0.096353714754685155, 0.039336239328442907},
    {0.84628437532163447, 0.26761861742291571, 0.063078313050504001,
     0.016858388283618388, 0.0059603403376112026}};

/* Q_m^m = (-1)^m (2m-1)!! */
static const double irc__sh_qmm[IRC__SH_MAX_BANDS] = {1.0, -1.0, 3.0, -15.0, 105.0};

/* Q_l^m(z) for l, m < bands and, when dq is not NULL, dQ_l^m/dz: the
 * recurrence Q_m+1^m = (2m+1) z Q_m^m, (l-m) Q_l^m = (2l-1) z Q_l-1^m -
 * (l+m-1) Q_l-2^m, differentiated term by term. */
static void irc__sh_legendre(int bands, double z, double q[][IRC__SH_MAX_BANDS],
                             double dq[][IRC__SH_MAX_BANDS])
{
    int l, m;
    for (m = 0; m < bands; m++) {
        q[m][m] = irc__sh_qmm[m];
        if (dq)
            dq[m][m] = 0.0;
        if (m + 1 < bands) {
            q[m + 1][m] = (2.0 * m + 1.0) * z * q[m][m];
            if (dq)
                dq[m + 1][m] = (2.0 * m + 1.0) * q[m][m];
        }
        for (l = m + 2; l < bands; l++) {
            q[l][m] = ((2.0 * l - 1.0) * z * q[l - 1][m] - (l + m - 1.0) * q[l - 2][m]) /
                      (l - m);
            if (dq)
                dq[l][m] = ((2.0 * l - 1.0) * (q[l - 1][m] + z * dq[l - 1][m]) -
                            (l + m - 1.0) * dq[l - 2][m]) / (l - m);
        }
    }
}

/* The part of a polynomial's gradient g tangent to the unit sphere at u,
 * over |s|: g - (g.u) u, where g.u = p (Euler: p = the degree times the
 * polynomial's value, for a homogeneous polynomial). */
static void irc__sh_tangent(double out[3], double gx, double gy, double gz, double p,
                            const double u[3], double il)
{
    out[0] = (gx - p * u[0]) * il;
    out[1] = (gy - p * u[1]) * il;
    out[2] = (gz - p * u[2]) * il;
}

/* Bands 0-2 (L <= 3, SH records' default) as the Cartesian polynomials the
 * recurrence below makes for them, with the same constants: y_1m = (a y,
 * b z, a x) with a = K_11 Q_1^1, b = K_10; y_2m = (2 c x y, d y z,
 * e (3z^2 - 1)/2, d x z, c (x^2 - y^2)) with c = K_22 Q_2^2, d = 3 K_21
 * Q_1^1 (Q_2^1 = 3 z Q_1^1), e = K_20.  For the gradient y_20 is taken as
 * e (z^2 - (x^2 + y^2)/2), equal on the sphere and homogeneous like the
 * others, so every g.u is the degree times the value.  Straight-line
 * code: no branch and no recurrence, for SH records' inner loop.  Writes
 * L*L values. */
static void irc__sh_eval3(int bands, const double u[3], double il, double *y,
                          double (*grad)[3])
{
    const double x = u[0], v = u[1], z = u[2];
    const double a = irc__sh_k[1][1] * irc__sh_qmm[1], b = irc__sh_k[1][0];
    const double c = irc__sh_k[2][2] * irc__sh_qmm[2], d = 3.0 * irc__sh_k[2][1] * irc__sh_qmm[1];
    const double e = irc__sh_k[2][0];
    double t[9];
    int l;
    t[0] = irc__sh_k[0][0];
    t[1] = a * v;
    t[2] = b * z;
    t[3] = a * x;
    t[4] = 2.0 * c * x * v;
    t[5] = d * v * z;
    t[6] = e * (1.5 * z * z - 0.5);
    t[7] = d * x * z;
    t[8] = c * (x * x - v * v);
    for (l = 0; l < bands * bands; l++)
        y[l] = t[l];
    if (!grad)
        return;
    grad[0][0] = grad[0][1] = grad[0][2] = 0.0;
    if (bands < 2)
        return;
    irc__sh_tangent(grad[1], 0.0, a, 0.0, t[1], u, il);
    irc__sh_tangent(grad[2], 0.0, 0.0, b, t[2], u, il);
    irc__sh_tangent(grad[3], a, 0.0, 0.0, t[3], u, il);
    if (bands < 3)
        return;
    irc__sh_tangent(grad[4], 2.0 * c * v, 2.0 * c * x, 0.0, 2.0 * t[4], u, il);
    irc__sh_tangent(grad[5], 0.0, d * z, d * v, 2.0 * t[5], u, il);
    irc__sh_tangent(grad[6], -e * x, -e * v, 2.0 * e * z,
                    e * (2.0 * z * z - x * x - v * v), u, il);
    irc__sh_tangent(grad[7], d * z, 0.0, d * x, 2.0 * t[7], u, il);
    irc__sh_tangent(grad[8], 2.0 * c * x, -2.0 * c * v, 0.0, 2.0 * t[8], u, il);
}

/* y[i] = y_i(s/|s|) for the L*L basis functions and, when grad is not
 * NULL, grad[i] = the gradient of y_i(s/|s|) with respect to s.  s must be
 * finite and nonzero; 1 <= L <= IRC__SH_MAX_BANDS.  The polynomial
 * K Q_l^m(z) C_m(x, y), C_m + i S_m = (x + i y)^m, has the gradient
 * K (Q C_m-1 m, -Q S_m-1 m, Q' C_m) (and for S_m: (m S_m-1, m C_m-1)); the
 * gradient on the sphere is its tangent part over |s|. */
void irc__sh_eval(int bands, const double s[3], double *y, double (*grad)[3])
{
    double q[IRC__SH_MAX_BANDS][IRC__SH_MAX_BANDS], dq[IRC__SH_MAX_BANDS][IRC__SH_MAX_BANDS];
    /* One division: a record evaluates the basis at every sample, and a
     * division costs several multiplications. */
    const double il = 1.0 / IRC_SQRT(irc__dot3d(s, s));
    double u[3], cm = 1.0, sm = 0.0, cp = 0.0, sp = 0.0;
    int l, m, k;
    for (k = 0; k < 3; k++)
        u[k] = s[k] * il;
    if (bands <= 3) {
        irc__sh_eval3(bands, u, il, y, grad);
        return;
    }
    irc__sh_legendre(bands, u[2], q, grad ? dq : NULL);
    for (m = 0; m < bands; m++) {
        for (l = m; l < bands; l++) {
            const double kq = irc__sh_k[l][m] * q[l][m];
            const int ip = l * l + l + m, in = l * l + l - m;
            double kd;
            y[ip] = kq * cm;
            if (m)
                y[in] = kq * sm;
            if (!grad)
                continue;
            kd = irc__sh_k[l][m] * dq[l][m];
            grad[ip][0] = kq * m * cp;
            grad[ip][1] = -kq * m * sp;
            grad[ip][2] = kd * cm;
            if (m) {
                grad[in][0] = kq * m * sp;
                grad[in][1] = kq * m * cp;
                grad[in][2] = kd * sm;
            }
        }
        cp = cm; /* C_m-1, S_m-1 for the next m */
        sp = sm;
        cm = u[0] * cp - u[1] * sp;
        sm = u[0] * sp + u[1] * cp;
    }
    if (!grad)
        return;
    for (l = 0; l < bands * bands; l++) { /* tangent part, over |s| */
        double gn = irc__dot3d(grad[l], u);
        for (k = 0; k < 3; k++)
            grad[l][k] = (grad[l][k] - gn * u[k]) * il;
    }
}

/* A_l(s) = 2 pi integral_0^1 z^s P_l(z) dz from the coefficients of P_l,
 * the zonal convolution of a lobe max(0, z)^s (Ramamoorthi-Hanrahan 2001,
 * for s = 1: pi, 2 pi/3, pi/4, 0, -pi/24). */
static double irc__sh_zonal(int l, double s)
{
    static const double p[IRC__SH_MAX_BANDS][IRC__SH_MAX_BANDS] = {
        {1, 0, 0, 0, 0},
        {0, 1, 0, 0, 0},
        {-0.5, 0, 1.5, 0, 0},
        {0, -1.5, 0, 2.5, 0},
        {0.375, 0, -3.75, 0, 4.375}};
    double sum = 0.0;
    int k;
    for (k = 0; k <= l; k++)
        sum += p[l][k] / (s + k + 1.0);
    return 2.0 * IRC_PI * sum;
}

static int irc__sh_valid(const irc_sh *sh, const float r[3], const float *rgb,
                         double u[3])
{
    uint32_t ch, i;
    if (!sh || !r || !rgb)
        return IRC_ERR_NULL;
    if (sh->bands < 1 || sh->bands > IRC__SH_MAX_BANDS ||
        (sh->channels != 1 && sh->channels != 3))
        return IRC_ERR_RANGE;
    for (ch = 0; ch < sh->channels; ch++)
        for (i = 0; i < sh->bands * sh->bands; i++)
            if (!irc__finite(sh->c[ch][i]))
                return IRC_ERR_NONFINITE;
    return irc__check_normal(r, u);
}

int irc_sh_glossy(const irc_sh *sh, const float r[3], float s, float rgb[3])
{
    double u[3], y[IRC__SH_MAX_BANDS * IRC__SH_MAX_BANDS], sum[3] = {0, 0, 0};
    uint32_t ch;
    int st = irc__sh_valid(sh, r, rgb, u), l, m;
    if (st < 0)
        return st;
    if (!(s >= 0.0f && s <= 1e4f))
        return IRC_ERR_RANGE;
    irc__sh_eval((int)sh->bands, u, y, NULL);
    for (l = 0; l < (int)sh->bands; l++) {
        double a = irc__sh_zonal(l, s);
        for (m = -l; m <= l; m++)
            for (ch = 0; ch < sh->channels; ch++)
                sum[ch] += a * sh->c[ch][l * l + l + m] * y[l * l + l + m];
    }
    for (ch = 0; ch < 3; ch++)
        rgb[ch] = (float)sum[sh->channels == 3 ? ch : 0];
    return IRC_OK;
}

int irc_sh_irradiance(const irc_sh *sh, const float n[3], float rgb[3])
{
    return irc_sh_glossy(sh, n, 1.0f, rgb);
}
