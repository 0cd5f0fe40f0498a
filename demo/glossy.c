/*
 * glossy.c -- glossy indirect light from SH records or the sampled lobe
 * (glossy.h).
 */
#define IRC_EXPERIMENTAL /* irc_sh_radiance (irrcache.h) */
#include "glossy.h"

#include <math.h>

#define PI 3.14159265358979323846

int glossy_has(const surface *sf)
{
    return sf->m->ks[0] + sf->m->ks[1] + sf->m->ks[2] > 0.0f;
}

float glossy_axis(const surface *sf, const float d[3], float r[3])
{
    const float dn = d[0] * sf->ns[0] + d[1] * sf->ns[1] + d[2] * sf->ns[2];
    int i;
    for (i = 0; i < 3; i++)
        r[i] = d[i] - 2.0f * dn * sf->ns[i];
    return -dn > 0.0f ? -dn : 0.0f;
}

int glossy_from_sh(const irc_sh *sh, const surface *sf, const float d[3], float out[3])
{
    float r[3], w[3], wt[3], l[3];
    double sum[3] = {0.0, 0.0, 0.0};
    int i, c, st = IRC_OK;
    glossy_axis(sf, d, r);
    /* The same stratified pattern about r at every pixel: its quadrature
     * error varies smoothly over the image, as the record's radiance does. */
    for (i = 0; i < GLOSSY_SH_DIRS && st == IRC_OK; i++) {
        glossy_sample(sf, r, 0x9e3779b97f4a7c15ull, i, GLOSSY_SH_DIRS, w, wt);
        if (wt[0] + wt[1] + wt[2] > 0.0f && (st = irc_sh_radiance(sh, w, l)) == IRC_OK)
            for (c = 0; c < 3; c++)
                sum[c] += (double)wt[c] * l[c];
    }
    for (c = 0; c < 3; c++)
        out[c] = st == IRC_OK ? (float)(sum[c] / GLOSSY_SH_DIRS) : 0.0f;
    return st;
}

void glossy_sample(const surface *sf, const float r[3], uint64_t key, int i, int n, float w[3],
                   float weight[3])
{
    const float s = sf->m->ns;
    const int m = (int)sqrt((double)n), k = n / (m > 0 ? m : 1);
    double u1 = rnd(key, 2u * (uint32_t)i), u2 = rnd(key, 2u * (uint32_t)i + 1), ca, sa, ph;
    float t1[3], t2[3], cn;
    const float sgn = r[2] >= 0.0f ? 1.0f : -1.0f, a = -1.0f / (sgn + r[2]),
                b = r[0] * r[1] * a;
    int c;
    if (i < m * k) {
        u1 = ((i / k) + u1) / m;
        u2 = ((i % k) + u2) / k;
    }
    /* A frame about r (Duff et al. 2017), then cos a = u1^(1/(s+1)). */
    t1[0] = 1.0f + sgn * r[0] * r[0] * a; t1[1] = sgn * b; t1[2] = -sgn * r[0];
    t2[0] = b; t2[1] = sgn + r[1] * r[1] * a; t2[2] = -r[1];
    ca = pow(u1, 1.0 / (s + 1.0));
    sa = sqrt(fmax(0.0, 1.0 - ca * ca));
    ph = 2.0 * PI * u2;
    for (c = 0; c < 3; c++)
        w[c] = (float)(sa * (cos(ph) * t1[c] + sin(ph) * t2[c]) + ca * r[c]);
    cn = w[0] * sf->ns[0] + w[1] * sf->ns[1] + w[2] * sf->ns[2];
    for (c = 0; c < 3; c++)
        weight[c] = cn > 0.0f ? sf->m->ks[c] * (s + 2.0f) / (s + 1.0f) * cn : 0.0f;
}
