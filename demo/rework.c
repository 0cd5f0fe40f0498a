/*
 * rework.c -- experiments on the records between the fill and the final
 * sweep (render_opts.place_seed, boost, filter, gfilter): each reads every record
 * back, changes its E or gradients, and puts the records back in, their
 * points, normals and reaches as they were.
 */
#define IRC_EXPERIMENTAL /* irc_cache_lookup_gradient (irrcache.h) */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bounce.h"
#include "camera.h"
#include "render.h"

/* Every record of c, into a new array (*n of them); NULL when out of
 * memory or the cache failed. */
static irc_record *read_all(irc_cache *c, uint32_t *n)
{
    irc_stats s;
    irc_record *rec;
    uint32_t id;
    *n = 0;
    if (irc_cache_stats(c, &s) < 0 ||
        !(rec = malloc(sizeof *rec * (size_t)(s.records ? s.records : 1))))
        return NULL;
    for (id = 0; id < s.capacity && *n < s.records; id++)
        if (irc_cache_record(c, id, &rec[*n]) == IRC_OK)
            (*n)++;
    return rec;
}

/* Replaces c's records by rec's n, and frees rec. */
static int put_back(irc_cache *c, irc_record *rec, uint32_t n)
{
    uint32_t i;
    int st = irc_cache_clear(c);
    for (i = 0; i < n && st >= 0; i++)
        st = irc_cache_insert(c, &rec[i]);
    free(rec);
    return st < 0 ? st : 0;
}

/* grad_r along the surface from dE/dn: the lookup's dn = grad_r x n_i
 * (irrcache.h, irc_gradient), so n_i x dn = grad_r less its part along
 * n_i, which no rotation of n_i reads. */
static void grad_r_of(const float n[3], const float dn[3], float out[3])
{
    out[0] = n[1] * dn[2] - n[2] * dn[1];
    out[1] = n[2] * dn[0] - n[0] * dn[2];
    out[2] = n[0] * dn[1] - n[1] * dn[0];
}

/* Irradiance filtering (Kontkanen, Rasanen and Keller 2004, "Irradiance
 * filtering for Monte Carlo ray tracing"): every record's E moves by f,
 * and its gradients by g, toward the blended lookup at its own point (its
 * neighbours' extrapolations and its own value averaged with the lookup's
 * weights), so that the independent noise of overlapping records averages
 * out.  Every lookup reads the unfiltered cache. */
static int filter_records(irc_cache *c, float f, float g)
{
    uint32_t n, i;
    irc_record *rec = read_all(c, &n);
    if (!rec)
        return -1;
    for (i = 0; i < n; i++) {
        float v[3], rn[3];
        irc_gradient gr;
        int k, q;
        if (irc_cache_lookup_gradient(c, rec[i].p, rec[i].n, v, &gr, NULL) != IRC_OK)
            continue;
        for (k = 0; k < 3; k++) {
            rec[i].e[k] += f * (v[k] - rec[i].e[k]);
            grad_r_of(rec[i].n, gr.dn[k], rn);
            for (q = 0; q < 3; q++) {
                rec[i].grad_t[k][q] += g * (gr.dp[k][q] - rec[i].grad_t[k][q]);
                rec[i].grad_r[k][q] += g * (rn[q] - rec[i].grad_r[k][q]);
            }
        }
    }
    return put_back(c, rec, n);
}

/* The geometric normal of the surface under the record at p (normal n),
 * turned to n's side; n itself when no surface is found within reach. */
static void normal_under(const renderer *r, const float p[3], const float n[3], float ng[3])
{
    const float eps = 1e-4f * (1.0f + fabsf(p[0]) + fabsf(p[1]) + fabsf(p[2]));
    float q[3], d[3];
    bvh_hit bh;
    int k;
    for (k = 0; k < 3; k++) {
        q[k] = p[k] + eps * n[k];
        d[k] = -n[k];
        ng[k] = n[k];
    }
    if (bvh_intersect(&r->b, q, d, 0.0f, 4.0f * eps, &bh)) {
        surface sf;
        float sg;
        surface_at(r->s, q, d, &bh, &sf);
        sg = dot3(sf.ng, n) < 0.0f ? -1.0f : 1.0f;
        for (k = 0; k < 3; k++)
            ng[k] = sg * sf.ng[k];
    }
}

/* The pixels record rec serves alone: pi (a R / f)^2, f the pixel's
 * footprint at its point (surface normal ng) as the camera sees it. */
static double pixels_served(const renderer *r, const cam_frame *cf, const irc_record *rec,
                            const float ng[3])
{
    const float a = r->cfg.accuracy > 0.0f ? r->cfg.accuracy : 0.2f; /* 0: the library's */
    float d[3], t = 0.0f, f;
    int k;
    for (k = 0; k < 3; k++) {
        d[k] = rec->p[k] - cf->eye[k];
        t += d[k] * d[k];
    }
    t = sqrtf(t);
    for (k = 0; k < 3; k++)
        d[k] /= t > 0.0f ? t : 1.0f;
    f = camera_footprint(cf, &r->s->cam, d, t, ng);
    return f > 0.0f ? 3.14159265 * pow(a * rec->radius / f, 2.0) : 0.0;
}

/* Every record serving at least min_pixels (0: every record) computed
 * again at its point by a cache of config cfg, its E and gradients
 * replacing the fill's; its point, normal and reach kept. */
static int recompute(renderer *r, tstate *ts, irc_config cfg, float min_pixels)
{
    irc_cache *c2 = NULL;
    irc_record *rec;
    cam_frame cf;
    size_t bytes;
    uint32_t n, i;
    int st;
    if ((st = irc_footprint(&cfg, 16, &bytes)) < 0)
        return st;
    if (!(rec = read_all(r->cache, &n)))
        return -1;
    cfg.buffer = malloc(bytes);
    cfg.buffer_size = bytes;
    if (!cfg.buffer || (st = irc_init(&cfg, 16, &c2)) < 0) {
        free(cfg.buffer);
        free(rec);
        return st < 0 ? st : -1;
    }
    camera_frame(&r->s->cam, &cf);
    for (i = 0; i < n; i++) {
        float ng[3];
        irc_record f;
        normal_under(r, rec[i].p, rec[i].n, ng);
        if (min_pixels > 0.0f && pixels_served(r, &cf, &rec[i], ng) < min_pixels)
            continue;
        ts->under[1] = ng;
        st = irc_record_compute(c2, rec[i].p, rec[i].n, &f, ts);
        ts->under[1] = NULL;
        if (st < 0)
            continue;
        memcpy(rec[i].e, f.e, sizeof f.e);
        memcpy(rec[i].grad_t, f.grad_t, sizeof f.grad_t);
        memcpy(rec[i].grad_r, f.grad_r, sizeof f.grad_r);
    }
    irc_fini(c2);
    free(cfg.buffer);
    return put_back(r->cache, rec, n);
}

/* Every record's E and gradients computed again with the value seed
 * (render_opts.place_seed), the demo's own random numbers too: the same
 * records with values independent of the fill's, so that two renders
 * with different seeds differ by the records' values alone, not by where
 * they were put. */
static int revalue_records(renderer *r, tstate *ts)
{
    irc_config cfg = r->cfg;
    int st;
    cfg.seed = r->o.seed = r->value_seed;
    st = recompute(r, ts, cfg, 0.0f);
    r->o.seed = r->cfg.seed;
    return st;
}

/* Records that serve at least o.boost pixels computed again with twice
 * the strata each way (four times the rays): rays that follow the pixels
 * a record serves once neighbour clamping has set its reach.  The strata
 * are the library's for the accuracy when the config leaves them 0
 * (irrcache.h, strata_theta). */
static int boost_records(renderer *r, tstate *ts)
{
    irc_config cfg = r->cfg;
    const float a = cfg.accuracy > 0.0f ? cfg.accuracy : 0.2f;
    const uint32_t m = cfg.strata_theta ? cfg.strata_theta : a < 0.25f ? 32u : a < 0.375f ? 16u : 8u;
    cfg.strata_theta = 2u * m;
    cfg.strata_phi = 2u * (cfg.strata_phi ? cfg.strata_phi : 4u * m);
    cfg.seed = r->cfg.seed ^ 0x626f6f7374ull;
    return recompute(r, ts, cfg, r->o.boost);
}

int rework_records(renderer *r, tstate *ts)
{
    int st = 0;
    if (r->o.place_seed)
        st = revalue_records(r, ts);
    if (st >= 0 && r->o.boost > 0.0f)
        st = boost_records(r, ts);
    if (st >= 0 && (r->o.filter > 0.0f || r->o.gfilter > 0.0f))
        st = filter_records(r->cache, r->o.filter, r->o.gfilter);
    return st;
}
