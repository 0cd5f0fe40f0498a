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
 * Every quantity is carried with its derivatives along x, y and z (forward
 * differentiation of the recurrence), which gives the gradient of the
 * polynomial that equals y on the sphere; the gradient of y(s/|s|) is its
 * part tangent to the sphere over |s|, whichever polynomial that is.
 */
#include "cache.h"

typedef struct irc__dual {
    double v, d[3]; /* value and d/dx, d/dy, d/dz */
} irc__dual;

static irc__dual irc__dmul(irc__dual a, irc__dual b)
{
    irc__dual r;
    int k;
    r.v = a.v * b.v;
    for (k = 0; k < 3; k++)
        r.d[k] = a.d[k] * b.v + a.v * b.d[k];
    return r;
}

static irc__dual irc__dlin(double a, irc__dual x, double b, irc__dual y)
{
    irc__dual r;
    int k;
    r.v = a * x.v + b * y.v;
    for (k = 0; k < 3; k++)
        r.d[k] = a * x.d[k] + b * y.d[k];
    return r;
}

static irc__dual irc__dconst(double v)
{
    irc__dual r;
    r.v = v;
    r.d[0] = r.d[1] = r.d[2] = 0.0;
    return r;
}

/* K_lm for l < 5: sqrt((2l+1)/(4 pi) (l-m)!/(l+m)!). */
static double irc__sh_k(int l, int m)
{
    static const double fact[9] = {1, 1, 2, 6, 24, 120, 720, 5040, 40320};
    return IRC_SQRT((2.0 * l + 1.0) / (4.0 * IRC_PI) * fact[l - m] / fact[l + m]);
}

/* y[i] = y_i(s/|s|) for the L*L basis functions and, when grad is not
 * NULL, grad[i] = the gradient of y_i(s/|s|) with respect to s.  s must be
 * finite and nonzero; 1 <= L <= IRC__SH_MAX_BANDS. */
void irc__sh_eval(int bands, const double s[3], double *y, double (*grad)[3])
{
    irc__dual x, yy, z, q[IRC__SH_MAX_BANDS][IRC__SH_MAX_BANDS], cm, sm;
    double len = IRC_SQRT(irc__dot3d(s, s)), u[3];
    int l, m, k;
    for (k = 0; k < 3; k++)
        u[k] = s[k] / len;
    x = irc__dconst(u[0]);
    yy = irc__dconst(u[1]);
    z = irc__dconst(u[2]);
    x.d[0] = yy.d[1] = z.d[2] = 1.0;
    /* Q_m^m = (-1)^m (2m-1)!!, Q_m+1^m = (2m+1) z Q_m^m, then the
     * three-term recurrence in l. */
    for (m = 0; m < bands; m++) {
        double dfact = 1.0;
        for (k = 1; k < 2 * m; k += 2)
            dfact *= k;
        q[m][m] = irc__dconst(m & 1 ? -dfact : dfact);
        if (m + 1 < bands)
            q[m + 1][m] = irc__dmul(irc__dconst(2.0 * m + 1.0), irc__dmul(z, q[m][m]));
        for (l = m + 2; l < bands; l++)
            q[l][m] = irc__dlin((2.0 * l - 1.0) / (l - m), irc__dmul(z, q[l - 1][m]),
                                -(l + m - 1.0) / (l - m), q[l - 2][m]);
    }
    cm = irc__dconst(1.0); /* Re, Im of (x + i y)^m */
    sm = irc__dconst(0.0);
    for (m = 0; m < bands; m++) {
        for (l = m; l < bands; l++) {
            double kk = m ? IRC_SQRT(2.0) * irc__sh_k(l, m) : irc__sh_k(l, 0);
            irc__dual a = irc__dmul(q[l][m], cm), b = irc__dmul(q[l][m], sm);
            int ip = l * l + l + m, in = l * l + l - m;
            y[ip] = kk * a.v;
            if (grad)
                for (k = 0; k < 3; k++)
                    grad[ip][k] = kk * a.d[k];
            if (m) {
                y[in] = kk * b.v;
                if (grad)
                    for (k = 0; k < 3; k++)
                        grad[in][k] = kk * b.d[k];
            }
        }
        {
            irc__dual c2 = irc__dlin(1.0, irc__dmul(x, cm), -1.0, irc__dmul(yy, sm));
            sm = irc__dlin(1.0, irc__dmul(x, sm), 1.0, irc__dmul(yy, cm));
            cm = c2;
        }
    }
    if (!grad)
        return;
    for (l = 0; l < bands * bands; l++) { /* tangent part, over |s| */
        double gn = irc__dot3d(grad[l], u);
        for (k = 0; k < 3; k++)
            grad[l][k] = (grad[l][k] - gn * u[k]) / len;
    }
}
