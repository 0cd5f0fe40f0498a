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
#include "../block/check.h"
#include "shrec.h"

#ifndef IRC_NO_SH

/* K_lm = sqrt((2l+1)/(4 pi) (l-m)!/(l+m)!), times sqrt2 for m > 0, for
 * l < 5 (a wrong digit fails test_sh's orthonormality check). */
static const float irc__sh_k[IRC__SH_MAX_BANDS][IRC__SH_MAX_BANDS] = {
    {0.28209479177387814f},
    {0.48860251190291992f, 0.48860251190291998f},
    {0.63078313050504009f, 0.36418281019735976f, 0.18209140509867988f},
    {0.7463526651802308f, 0.3046971996429772f, 0.096353714754685155f, 0.039336239328442907f},
    {0.84628437532163447f, 0.26761861742291571f, 0.063078313050504001f,
     0.016858388283618388f, 0.0059603403376112026f}};

/* Q_m^m = (-1)^m (2m-1)!! */
static const float irc__sh_qmm[IRC__SH_MAX_BANDS] = {1.0f, -1.0f, 3.0f, -15.0f, 105.0f};

/* Q_l^m(z) for l, m < bands and, when dq is not NULL, dQ_l^m/dz: the
 * recurrence Q_m+1^m = (2m+1) z Q_m^m, (l-m) Q_l^m = (2l-1) z Q_l-1^m -
 * (l+m-1) Q_l-2^m, differentiated term by term. */
static void irc__sh_legendre(int bands, float z, float q[][IRC__SH_MAX_BANDS],
                             float dq[][IRC__SH_MAX_BANDS])
{
    int l, m;
    for (m = 0; m < bands; m++) {
        q[m][m] = irc__sh_qmm[m];
        if (dq)
            dq[m][m] = 0.0f;
        if (m + 1 < bands) {
            q[m + 1][m] = (2.0f * m + 1.0f) * z * q[m][m];
            if (dq)
                dq[m + 1][m] = (2.0f * m + 1.0f) * q[m][m];
        }
        for (l = m + 2; l < bands; l++) {
            q[l][m] = ((2.0f * l - 1.0f) * z * q[l - 1][m] - (l + m - 1.0f) * q[l - 2][m]) /
                      (l - m);
            if (dq)
                dq[l][m] = ((2.0f * l - 1.0f) * (q[l - 1][m] + z * dq[l - 1][m]) -
                            (l + m - 1.0f) * dq[l - 2][m]) / (l - m);
        }
    }
}

/* The part of a polynomial's gradient g tangent to the unit sphere at u,
 * over |s|: g - (g.u) u, where g.u = p (Euler: p = the degree times the
 * polynomial's value, for a homogeneous polynomial). */
static void irc__sh_tangent(float out[3], float gx, float gy, float gz, float p,
                            const float u[3], float il)
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
static void irc__sh_eval3(int bands, const float u[3], float il, float *y,
                          float (*grad)[3])
{
    const float x = u[0], v = u[1], z = u[2];
    const float a = irc__sh_k[1][1] * irc__sh_qmm[1], b = irc__sh_k[1][0];
    const float c = irc__sh_k[2][2] * irc__sh_qmm[2], d = 3.0f * irc__sh_k[2][1] * irc__sh_qmm[1];
    const float e = irc__sh_k[2][0];
    float t[9];
    int l;
    t[0] = irc__sh_k[0][0];
    t[1] = a * v;
    t[2] = b * z;
    t[3] = a * x;
    t[4] = 2.0f * c * x * v;
    t[5] = d * v * z;
    t[6] = e * (1.5f * z * z - 0.5f);
    t[7] = d * x * z;
    t[8] = c * (x * x - v * v);
    for (l = 0; l < bands * bands; l++)
        y[l] = t[l];
    if (!grad)
        return;
    grad[0][0] = grad[0][1] = grad[0][2] = 0.0f;
    if (bands < 2)
        return;
    irc__sh_tangent(grad[1], 0.0f, a, 0.0f, t[1], u, il);
    irc__sh_tangent(grad[2], 0.0f, 0.0f, b, t[2], u, il);
    irc__sh_tangent(grad[3], a, 0.0f, 0.0f, t[3], u, il);
    if (bands < 3)
        return;
    irc__sh_tangent(grad[4], 2.0f * c * v, 2.0f * c * x, 0.0f, 2.0f * t[4], u, il);
    irc__sh_tangent(grad[5], 0.0f, d * z, d * v, 2.0f * t[5], u, il);
    irc__sh_tangent(grad[6], -e * x, -e * v, 2.0f * e * z,
                    e * (2.0f * z * z - x * x - v * v), u, il);
    irc__sh_tangent(grad[7], d * z, 0.0f, d * x, 2.0f * t[7], u, il);
    irc__sh_tangent(grad[8], 2.0f * c * x, -2.0f * c * v, 0.0f, 2.0f * t[8], u, il);
}

/* y[i] = y_i(s/|s|) for the L*L basis functions and, when grad is not
 * NULL, grad[i] = the gradient of y_i(s/|s|) with respect to s.  s must be
 * finite and nonzero; 1 <= L <= IRC__SH_MAX_BANDS.  The polynomial
 * K Q_l^m(z) C_m(x, y), C_m + i S_m = (x + i y)^m, has the gradient
 * K (Q C_m-1 m, -Q S_m-1 m, Q' C_m) (and for S_m: (m S_m-1, m C_m-1)); the
 * gradient on the sphere is its tangent part over |s|. */
void irc__sh_eval(int bands, const float s[3], float *y, float (*grad)[3])
{
    float q[IRC__SH_MAX_BANDS][IRC__SH_MAX_BANDS], dq[IRC__SH_MAX_BANDS][IRC__SH_MAX_BANDS];
    /* One division: a record evaluates the basis at every sample, and a
     * division costs several multiplications. */
    const float il = 1.0f / IRC_SQRTF(irc__dot3(s, s));
    float u[3], cm = 1.0f, sm = 0.0f, cp = 0.0f, sp = 0.0f;
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
            const float kq = irc__sh_k[l][m] * q[l][m];
            const int ip = l * l + l + m, in = l * l + l - m;
            float kd;
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
        float gn = irc__dot3(grad[l], u);
        for (k = 0; k < 3; k++)
            grad[l][k] = (grad[l][k] - gn * u[k]) * il;
    }
}

/* A_l(s) = 2 pi integral_0^1 z^s P_l(z) dz from the coefficients of P_l,
 * the zonal convolution of a lobe max(0, z)^s (Ramamoorthi-Hanrahan 2001,
 * for s = 1: pi, 2 pi/3, pi/4, 0, -pi/24). */
static float irc__sh_zonal(int l, float s)
{
    static const float p[IRC__SH_MAX_BANDS][IRC__SH_MAX_BANDS] = {
        {1, 0, 0, 0, 0},
        {0, 1, 0, 0, 0},
        {-0.5f, 0, 1.5f, 0, 0},
        {0, -1.5f, 0, 2.5f, 0},
        {0.375f, 0, -3.75f, 0, 4.375f}};
    float sum = 0.0f;
    int k;
    for (k = 0; k <= l; k++)
        sum += p[l][k] / (s + k + 1.0f);
    return 2.0f * IRC_PI * sum;
}

static int irc__sh_valid(const irc_sh *sh, const float r[3], const float *rgb,
                         float u[3])
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

/* sum over l, m of A_l c_lm y_lm(r): A_l the zonal lobe's of exponent s,
 * or with radiance, A_l = 1 (the band-limited radiance itself). */
static int irc__sh_convolve(const irc_sh *sh, const float r[3], float s, int radiance,
                            float rgb[3])
{
    float u[3], y[IRC__SH_MAX_BANDS * IRC__SH_MAX_BANDS], sum[3] = {0, 0, 0};
    uint32_t ch;
    int st = irc__sh_valid(sh, r, rgb, u), l, m;
    if (st < 0)
        return st;
    if (!radiance && !(s >= 0.0f && s <= 1e4f))
        return IRC_ERR_RANGE;
    irc__sh_eval((int)sh->bands, u, y, NULL);
    for (l = 0; l < (int)sh->bands; l++) {
        float a = radiance ? 1.0f : irc__sh_zonal(l, s);
        for (m = -l; m <= l; m++)
            for (ch = 0; ch < sh->channels; ch++)
                sum[ch] += a * sh->c[ch][l * l + l + m] * y[l * l + l + m];
    }
    for (ch = 0; ch < 3; ch++)
        rgb[ch] = sum[sh->channels == 3 ? ch : 0];
    return IRC_OK;
}

int irc_sh_glossy(const irc_sh *sh, const float r[3], float s, float rgb[3])
{
    return irc__sh_convolve(sh, r, s, 0, rgb);
}

int irc_sh_irradiance(const irc_sh *sh, const float n[3], float rgb[3])
{
    return irc_sh_glossy(sh, n, 1.0f, rgb);
}

int irc_sh_radiance(const irc_sh *sh, const float w[3], float rgb[3])
{
    return irc__sh_convolve(sh, w, 0.0f, 1, rgb);
}

#else /* IRC_NO_SH: the public calls are absent.c's */

typedef int irc__sh_absent; /* ISO C wants something in a file */

#endif
