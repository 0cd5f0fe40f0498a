/*
 * grid.c -- the strata grids and their table: every angle the sampler and
 * the gradient estimators need depends on the configuration only (the
 * strata's boundaries and centres), so the sines, cosines and row weights
 * sit in a table made once at irc_init, one per grid level, in the block
 * (form.h, irc__gtab).  The sampler takes its columns' boundary angles
 * from it, the gradients (irr/gradient.c) their weights.
 */
#include "../block/form.h"
#include "grid.h"

/* The table: four padded rows of floats, cos and sin of each column's
 * centre phi_c = 2 pi (k + 1/2)/N and of its first boundary phi_b =
 * 2 pi k/N (entry N repeats entry 0); then per row j the
 * translational weights of its lower boundary (U_j) and of its column
 * boundaries (V_j) and the rotational weight W_j, and the two constants of
 * the rotation that turns (cos phi_b, sin phi_b) into a column's integral
 * of v(phi). */
static void irc__gtab_fill_one(uint32_t m, uint32_t nphi, float *tab)
{
    const uint32_t np = irc__pad4(nphi);
    const float dphi = 2.0f * IRC_PI / nphi, half = IRC_SINF(0.5f * dphi);
    float *col = tab;
    float *row = (float *)(void *)(col + 4u * np), th0 = 0.0f, sc0 = 0.0f;
    uint32_t j, k;
    for (k = 0; k <= nphi; k++) {
        float phc = 2.0f * IRC_PI * (k + 0.5f) / nphi, phb = 2.0f * IRC_PI * (k % nphi) / nphi;
        col[k] = IRC_COSF(phc);
        col[np + k] = IRC_SINF(phc);
        col[2 * np + k] = IRC_COSF(phb);
        col[3 * np + k] = IRC_SINF(phb);
    }
    for (j = 0; j < m; j++) {
        /* Translational (Krivanek et al. 2005, stratified form): the
         * boundary between rows j-1 and j, at theta_j- = asin(sqrt(j/M)),
         * sweeps solid angle at (2 pi/N) cos^2(theta_j-) sin(theta_j-) / d;
         * a column boundary at cos(theta_j) (cos theta_j- - cos theta_j+) /
         * (sin(theta_j) d), theta_j the row's centre. */
        float s2lo = (float)j / m, s2hi = (float)(j + 1) / m, s2c = (j + 0.5f) / m;
        /* Rotational (Ward-Heckbert 1992, integrated exactly over the row):
         * W_j = integral of sin^2(theta) dtheta = [theta/2 - sin(2 theta)/4]. */
        float th1 = IRC_ASINF(IRC_SQRTF(s2hi)), sc1 = IRC_SQRTF(s2hi * (1.0f - s2hi));
        row[3 * j] = dphi * (1.0f - s2lo) * IRC_SQRTF(s2lo);
        row[3 * j + 1] = nphi > 1 ? IRC_SQRTF(1.0f - s2c) *
                                        (IRC_SQRTF(1.0f - s2lo) - IRC_SQRTF(1.0f - s2hi)) /
                                        IRC_SQRTF(s2c)
                                  : 0.0f; /* one column: no column boundary */
        row[3 * j + 2] = 0.5f * (th1 - th0) - 0.5f * (sc1 - sc0);
        th0 = th1;
        sc0 = sc1;
    }
    /* V_k = [[cos dphi - 1, -sin dphi], [sin dphi, cos dphi - 1]] (cos phi_b,
     * sin phi_b); cos dphi - 1 as -2 sin^2(dphi/2), which keeps its digits
     * when N is large. */
    row[3 * m] = -2.0f * half * half;
    row[3 * m + 1] = IRC_SINF(dphi);
}

/* Floats of one grid's table, rounded up to a multiple of 4 so that the
 * next level's table stays 16-byte aligned. */
static uint64_t irc__gtab_floats(uint32_t m, uint32_t nphi)
{
    return ((uint64_t)irc__pad4(nphi) * 4u + 3u * (uint64_t)m + 2u + 3u) / 4u * 4u;
}

/* The grids a config's M x N strata coarsen to, each halving M and N: a
 * level exists while both halve exactly and it keeps >= 2 rows, >= 8
 * columns and >= 64 strata (a coarser pilot's radius is too noisy to
 * choose by).  Level 0 is the configured grid. */
uint32_t irc__grid_levels(uint32_t m, uint32_t nphi)
{
    uint32_t l = 1;
    while (l < IRC__GRIDS && m % (2u << (l - 1)) == 0 && nphi % (2u << (l - 1)) == 0 &&
           (m >> l) >= 2u && (nphi >> l) >= 8u && (m >> l) * (nphi >> l) >= 64u)
        l++;
    return l;
}

/* Bytes of every level's table (irc__gtab_fill). */
uint64_t irc__gtab_bytes(uint32_t m, uint32_t nphi)
{
    const uint32_t levels = irc__grid_levels(m, nphi);
    uint64_t f = 0;
    uint32_t l;
    for (l = 0; l < levels; l++)
        f += irc__gtab_floats(m >> l, nphi >> l);
    return f * sizeof(float);
}

void irc__gtab_fill(uint32_t m, uint32_t nphi, void *tab)
{
    const uint32_t levels = irc__grid_levels(m, nphi);
    float *t = (float *)tab;
    uint32_t l;
    for (l = 0; l < levels; l++) {
        irc__gtab_fill_one(m >> l, nphi >> l, t);
        t += irc__gtab_floats(m >> l, nphi >> l);
    }
}

void irc__grid_at(const irc_cache *c, uint32_t level, irc__grid *g)
{
    const float *t = (const float *)irc__gtab(c);
    uint32_t l;
    for (l = 0; l < level; l++)
        t += irc__gtab_floats(c->cfg.strata_theta >> l, c->cfg.strata_phi >> l);
    g->m = c->cfg.strata_theta >> level;
    g->nphi = c->cfg.strata_phi >> level;
    g->strata = g->m * g->nphi;
    g->level = level;
    g->tab = t;
}
