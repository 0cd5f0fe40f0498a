/*
 * progressive.c -- records whose rays follow the host's samples a pixel
 * (irc_progress): made cheap while the image is noisy anyway, refined as
 * it converges, so that the cache's error keeps falling with the samples
 * as path tracing's does instead of stopping at a record's noise.
 *
 * Every point has a sequence of independent estimates (draw 0, 1, 2, ...,
 * each with random numbers of its own: sampler.c).  At level 0 a record is
 * its first estimate, on the coarsest grid (T0 = M N / 4^top rays); each
 * level doubles its rays with new estimates, never repeating a ray:
 * level l holds T0 2^l rays, the mean of its estimates weighted by their
 * rays.  The estimates of step j (level j - 1 to j) are on the finest grid
 * no larger than the step's T0 2^(j-1) rays, as many as make them up.  A
 * record made at level l and one made at level 0 and refined to l are the
 * same estimates.  The level for s samples a pixel puts the configured
 * grid (T0 4^top rays, the knob's choice) at IRC__PROGRESS_FULL samples:
 * rays a record = M N s / IRC__PROGRESS_FULL, at least T0.  The record's radius is its
 * first estimate's and never changes (the index's bounds hold), and the
 * variance of its irradiance and gradients falls as 1 / rays.
 */
#include "../block/form.h"
#include "../sample/grid.h"
#include "estimator.h"

/* The coarsest grid's level. */
static uint32_t irc__top(const irc_cache *c)
{
    return irc__grid_levels(c->cfg.strata_theta, c->cfg.strata_phi) - 1u;
}

uint32_t irc__progress_full(const irc_cache *c)
{
    return 2u * irc__top(c);
}

uint32_t irc__progress_level(const irc_cache *c, uint32_t samples)
{
    uint32_t lg = 0, l;
    while (lg < 31u && (samples >> (lg + 1u)) != 0u)
        lg++;
    /* level 2 top at IRC__PROGRESS_FULL samples, one more each doubling */
    l = 2u * irc__top(c) + lg;
    l = l > IRC__PROGRESS_FULL_LOG2 ? l - IRC__PROGRESS_FULL_LOG2 : 0u;
    return l < IRC__PROGRESS_TOP ? l : IRC__PROGRESS_TOP;
}

/* Step j's estimates: their grid level, how many, the first one's draw,
 * and the rays of one and of the levels before it, in units of T0. */
typedef struct irc__step {
    uint32_t level, count, draw;
    double rays, before;
} irc__step;

static uint32_t irc__step_count(uint32_t top, uint32_t j, uint32_t *level)
{
    const uint32_t half = (j - 1u) / 2u, g = top > half ? top - half : 0u;
    *level = g;
    return (1u << (j - 1u)) >> (2u * (top - g));
}

/* (j >= 1: the schedule's steps are numbered from 1) */
static void irc__step_of(uint32_t top, uint32_t j, irc__step *s)
{
    uint32_t i, g;
    s->draw = 1u;
    for (i = 1u; i < j; i++)
        s->draw += irc__step_count(top, i, &g);
    s->count = irc__step_count(top, j, &s->level);
    s->rays = (double)(1u << (2u * (top - s->level)));
    s->before = (double)(1u << (j - 1u));
}

/* rec's irradiance and gradients moved a fraction w toward est's. */
static void irc__mix_record(irc_record *rec, const irc_record *est, float w)
{
    int c, a;
    for (c = 0; c < 3; c++) {
        rec->e[c] += (est->e[c] - rec->e[c]) * w;
        for (a = 0; a < 3; a++) {
            rec->grad_t[c][a] += (est->grad_t[c][a] - rec->grad_t[c][a]) * w;
            rec->grad_r[c][a] += (est->grad_r[c][a] - rec->grad_r[c][a]) * w;
        }
    }
    rec->rays += est->rays;
    rec->rays_used += est->rays_used;
}

/* Steps (from, to] of the point's estimates, each record or E (by rec or
 * e) mixed into the running mean. */
static int irc__add_draws(irc__call *k, irc_record *rec, float e[3], uint32_t from, uint32_t to)
{
    const uint32_t top = irc__top(k->c);
    irc_record est;
    uint32_t j, r;
    int st = IRC_OK;
    for (j = from + 1u; j <= to && st >= 0; j++) {
        irc__step s;
        double held;
        irc__step_of(top, j, &s);
        held = s.before;
        for (r = 0; r < s.count; r++) {
            float f[3];
            k->draw = s.draw + r;
            st = rec ? irc__irr_on_grid(k, s.level, &est) : irc__irr_estimate_on(k, s.level, f);
            if (st == IRC_ERR_NOSAMPLES)
                continue;
            if (st < 0)
                break;
            held += s.rays;
            if (rec) {
                irc__mix_record(rec, &est, (float)(s.rays / held));
            } else {
                int c;
                for (c = 0; c < 3; c++)
                    e[c] += (f[c] - e[c]) * (float)(s.rays / held);
            }
        }
    }
    k->draw = 0;
    return st == IRC_ERR_NOSAMPLES ? IRC_OK : st;
}

int irc__irr_refine(irc__call *k, irc_record *rec, uint32_t from, uint32_t to)
{
    return irc__add_draws(k, rec, NULL, from, to);
}

int irc__irr_refine_e(irc__call *k, float e[3], uint32_t from, uint32_t to)
{
    return irc__add_draws(k, NULL, e, from, to);
}

/* A record whose reach a R is under a pixel serves its own point alone:
 * each level's samples, anywhere in the pixel, would miss it and make
 * another beside it (the Sponza atrium at 320 x 240: 40,000 records at 4
 * samples a pixel, 253,000 at 256).  A progressive _px record reaches a
 * pixel at least, within the host's bounds. */
static void irc__pixel_wide(const irc__call *k, irc_record *out)
{
    const irc_config *cfg = &k->c->cfg;
    float r = k->footprint / cfg->accuracy;
    if (!(k->footprint > 0.0f))
        return;
    if (cfg->irr.max_pixels > 0.0f && r > cfg->irr.max_pixels * k->footprint / cfg->accuracy)
        r = cfg->irr.max_pixels * k->footprint / cfg->accuracy;
    if (r > cfg->max_radius)
        r = cfg->max_radius;
    if (out->radius < r)
        out->radius = out->minor_radius = r;
}

int irc__irr_progressive(irc__call *k, irc_record *out)
{
    int st;
    k->draw = 0;
    if ((st = irc__irr_on_grid(k, irc__top(k->c), out)) < 0 ||
        (st = irc__add_draws(k, out, NULL, 0u, k->progress - 1u)) < 0)
        return st;
    irc__pixel_wide(k, out);
    out->rays = k->rays;
    return IRC_OK;
}

uint32_t irc__detail_level(const irc_cache *c, uint32_t level)
{
    const uint32_t top = irc__top(c);
    return level > top ? level - top : 0u;
}

/* A new per-pixel estimate is level 0's, T0 rays, whatever the cache's
 * level: a pixel whose samples land on many surfaces makes one at each
 * (the atrium's foliage at 160 x 120: 84,000 by 256 samples, most of the
 * rays at the level's T0 2^l); one that is kept gets the rest when it
 * serves again (progress.c). */
int irc__irr_progressive_e(irc__call *k, float e[3])
{
    k->draw = 0;
    return irc__irr_estimate_on(k, irc__top(k->c), e);
}
