/*
 * render.c -- the integrator (see render.h), its threads, and the host side
 * of the cache: the trace callback the library calls.
 */
#define _POSIX_C_SOURCE 200809L
#include "render.h"
#include "bounce.h"
#include "glossy.h"
#include "camera.h"

#include <float.h>
#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#define PI 3.14159265358979323846

static double seconds_of(clockid_t id)
{
    struct timespec t;
    clock_gettime(id, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

double render_clock(void)
{
    return seconds_of(CLOCK_MONOTONIC);
}

double render_cpu_clock(void)
{
    return seconds_of(CLOCK_PROCESS_CPUTIME_ID);
}

/* The default maximum radius: 0.1 x the diagonal of what the camera sees
 * (the box around the first hits of a 32 x 32 grid of camera rays), as
 * Radiance bounds radii by the scene's size; open scenes otherwise get
 * records as wide as the sky's harmonic mean distance.  The visible part,
 * not the whole scene: a huge ground object must not widen every record. */
static float visible_size(const renderer *r)
{
    const camera *c = &r->s->cam;
    camera sub = *c;
    cam_frame cf;
    float lo[3] = {FLT_MAX, FLT_MAX, FLT_MAX}, hi[3] = {-FLT_MAX, -FLT_MAX, -FLT_MAX}, d2 = 0.0f;
    int x, y, k, hits = 0;
    sub.width = sub.height = 32;
    camera_frame(&sub, &cf);
    for (y = 0; y < 32; y++)
        for (x = 0; x < 32; x++) {
            float d[3];
            bvh_hit bh;
            camera_ray(&cf, &sub, x, y, d);
            if (!bvh_intersect(&r->b, cf.eye, d, 0.0f, FLT_MAX, &bh))
                continue;
            for (k = 0; k < 3; k++) {
                float p = cf.eye[k] + bh.t * d[k];
                lo[k] = p < lo[k] ? p : lo[k];
                hi[k] = p > hi[k] ? p : hi[k];
            }
            hits++;
        }
    for (k = 0; k < 3; k++) {
        float e = hits ? hi[k] - lo[k] : (r->b.nprims ? r->b.nodes[0].hi[k] - r->b.nodes[0].lo[k] : 0.0f);
        d2 += e * e;
    }
    return 0.1f * sqrtf(d2);
}

void render_opts_defaults(render_opts *o)
{
    memset(o, 0, sizeof *o);
    o->mode = MODE_CACHE;
    o->max_records = 200000;
    o->light_samples = 16;
    o->seed = 1;
    o->threads = 1;
    o->bounces = 1;
    o->level_scale = 1.0f;
    o->level_strata = 2;
    o->level_min_radius = 0.5f;
}

int renderer_init(renderer *r, const scene *s, const render_opts *o, char *err, size_t n)
{
    memset(r, 0, sizeof *r);
    r->s = s;
    r->o = *o;
    if (r->o.bounces < 1)
        r->o.bounces = 1;
    if (r->o.bounces > MAX_BOUNCES)
        r->o.bounces = MAX_BOUNCES;
    if (o->mode != MODE_CACHE)
        r->o.gather = GATHER_PATH; /* the reference: path tracing with NEE */
    if (bvh_build(&r->b, s) < 0 || lights_build(&r->l, s) < 0) {
        snprintf(err, n, "out of memory");
        return -1;
    }
    if (o->mode == MODE_CACHE) {
        irc_config cfg;
        size_t bytes;
        int st;
        memset(&cfg, 0, sizeof cfg);
        cfg.version = IRC_CONFIG_VERSION;
        cfg.trace = host_trace;
        r->ctx[0].r = r;
        r->ctx[0].level = 1;
        cfg.context = &r->ctx[0];
        cfg.max_batch = 64;
        cfg.features = o->features;
        cfg.sh.bands = (o->features & IRC_FEATURE_SH) ? o->sh_bands : 0;
        cfg.accuracy = o->accuracy;
        cfg.strata_theta = o->strata_m;
        cfg.strata_phi = o->strata_n;
        cfg.irr.supersamples = o->supersamples;
        cfg.irr.full_pixels = o->full_pixels;
        cfg.irr.detail_pixels = o->detail_pixels;
        cfg.irr.blend = (o->features & IRC_FEATURE_SH) ? 0.0f : o->blend;
        cfg.min_radius = o->min_radius;
        cfg.irr.min_pixels = o->min_pixels;
        cfg.irr.max_pixels = o->max_pixels;
        cfg.irr.leak_guard = (uint32_t)o->leak_guard;
        cfg.check_visibility = (uint32_t)o->check_visibility;
        cfg.clamp_neighbours = (uint32_t)o->clamp_neighbours;
        cfg.max_radius = o->max_radius;
        if (o->max_radius < 0.0f)
            cfg.max_radius = r->o.max_radius = visible_size(r);
        cfg.threads = (uint32_t)o->threads;
        cfg.seed = o->seed;
        cfg.evict = IRC_EVICT_CLOCK;
        if ((st = irc_footprint(&cfg, o->max_records, &bytes)) < 0 ||
            !(r->block = malloc(bytes))) {
            snprintf(err, n, "cache: %s", st < 0 ? irc_strerror(st) : "out of memory");
            renderer_free(r);
            return -1;
        }
        cfg.buffer = r->block;
        cfg.buffer_size = bytes;
        r->cfg = cfg;
        if ((st = irc_init(&cfg, o->max_records, &r->cache)) < 0) {
            snprintf(err, n, "cache: %s", irc_strerror(st));
            renderer_free(r);
            return -1;
        }
        if (levels_init(r, &cfg, r->o.bounces > 1 ? visible_size(r) : 0.0f, err, n) < 0) {
            renderer_free(r);
            return -1;
        }
    }
    return 0;
}

void renderer_free(renderer *r)
{
    levels_free(r);
    if (r->cache)
        irc_fini(r->cache);
    free(r->block);
    bvh_free(&r->b);
    lights_free(&r->l);
    memset(r, 0, sizeof *r);
}

/* Brute force: ref_rays cosine-weighted rays, stratified on an m x k grid
 * (m = floor(sqrt(N)), k = N/m, the rest unstratified). */
static void reference_e(const renderer *r, const float p[3], const float n[3], uint64_t key,
                        float e[3], tstate *ts)
{
    irc_ray rays[64];
    irc_hit hits[64];
    int total = r->o.ref_rays, m = (int)sqrt((double)total), k = total / (m > 0 ? m : 1);
    int i, c, nb = 0;
    double sum[3] = {0, 0, 0};
    int used = 0;
    for (i = 0; i < total; i++) {
        double u1 = rnd(key, 2u * i), u2 = rnd(key, 2u * i + 1);
        if (i < m * k) {
            u1 = ((i / k) + u1) / m;
            u2 = ((i % k) + u2) / k;
        }
        memcpy(rays[nb].org, p, sizeof rays[nb].org);
        cosine_dir(n, u1, u2, rays[nb].dir);
        if (++nb == 64 || i == total - 1) {
            int j;
            cast(r, rays, hits, (uint32_t)nb, 1, 1, ts);
            for (j = 0; j < nb; j++) {
                if (hits[j].status == IRC_RAY_FAILED)
                    continue; /* below the surface: left out, as the cache does */
                used++;
                for (c = 0; c < 3; c++)
                    sum[c] += hits[j].radiance[c];
            }
            nb = 0;
        }
    }
    for (c = 0; c < 3; c++)
        e[c] = used ? (float)(PI * sum[c] / used) : 0.0f;
}

int render_hidden(const renderer *r, const float p[3], const float q[3])
{
    float d[3], len;
    int k;
    for (k = 0; k < 3; k++)
        d[k] = q[k] - p[k];
    len = sqrtf(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    if (len <= 2.0f * ray_offset(p))
        return 0;
    for (k = 0; k < 3; k++)
        d[k] /= len;
    return bvh_occluded(&r->b, p, d, ray_offset(p), len - ray_offset(q));
}

/* Indirect irradiance at a surface, from the cache or by brute force;
 * sh gets the SH record it came from (sh->bands 0: none).  n: the normal
 * gathered around (gather_normal); the _px call takes the shading normal
 * ns and the geometric one ng (NULL: none) instead and leaves out the
 * rays below the surface itself, so its callback casts them all.  fp: the
 * pixel's footprint there (0: no pixel), which bounds new records' reach
 * in pixels (irc_cache_lookup_or_compute_px). */
static int irradiance(renderer *r, const float p[3], const float n[3], const float ns[3],
                      const float *ng, float fp, uint64_t key, float e[3], irc_sh *sh,
                      tstate *ts)
{
    sh->bands = 0;
    if (r->o.mode == MODE_CACHE) {
        const double c0 = ts->cache_s;
        const uint64_t gathers0 = ts->gathers;
        int st, was = clock_enter(ts, CLOCK_CACHE);
        if (r->o.features & IRC_FEATURE_SH) {
            st = irc_sh_lookup_or_compute(r->cache, p, n, sh, NULL, ts);
            if (st >= 0)
                st = irc_sh_irradiance(sh, n, e);
            else
                sh->bands = 0;
        } else if (r->o.frozen) {
            irc_record rec;
            if ((st = irc_cache_lookup(r->cache, p, n, e, NULL)) == IRC_MISS &&
                (st = irc_record_compute(r->cache, p, n, &rec, ts)) >= 0) {
                memcpy(e, rec.e, sizeof rec.e);
                ts->dropped++;
            }
        } else if (ts->final) {
            /* every record within blend a R answers, as the fill's
             * lookups did (a miss only beyond: irrcache.h) */
            float w = 0.0f;
            if ((st = irc_cache_lookup(r->cache, p, n, e, &w)) == IRC_MISS && w > 0.0f)
                st = IRC_OK;
        } else {
            const float *under = ts->under[1];
            ts->under[1] = NULL;
            st = irc_cache_lookup_or_compute_px(r->cache, p, ng ? ns : n, ng,
                                                r->o.no_footprint ? 0.0f : fp, e, NULL, ts);
            ts->under[1] = under;
            ts->detail = st == IRC_DETAIL;
        }
        clock_enter(ts, was);
        if (ts->gathers != gathers0)
            ts->gather_s += ts->cache_s - c0;
        else
            ts->lookup_s += ts->cache_s - c0;
        return st < 0 ? st : ts->final && st == IRC_MISS ? IRC_MISS : 0;
    }
    reference_e(r, p, n, key, e, ts);
    return 0;
}

/* Glossy indirect light (glossy.h) added to out: from the SH record when
 * there is one and its bands carry the lobe (s <= sh_lobe_max), else by
 * lobe_rays samples of the lobe from p. */
static void glossy_indirect(const renderer *r, const surface *sf, const float p[3],
                            const float d[3], const irc_sh *sh, uint64_t key, float out[3],
                            tstate *ts)
{
    irc_ray rays[64];
    irc_hit hits[64];
    float wt[64][3], axis[3], g[3];
    double sum[3] = {0.0, 0.0, 0.0};
    const int n = r->o.lobe_rays;
    int i, j, c, nb = 0;
    /* 0.4 L^2: where make glossy measured SH losing to 16 lobe rays (between
     * s = 2 and 5 at L = 3, 5 and 10 at L = 4, 10 and 20 at L = 5). */
    const float most = r->o.sh_lobe_max > 0.0f ? r->o.sh_lobe_max
                                               : 0.4f * (float)(sh->bands * sh->bands);
    if (sh->bands && sf->m->ns <= most && glossy_from_sh(sh, sf, d, g) == IRC_OK) {
        for (c = 0; c < 3; c++)
            out[c] += g[c];
        return;
    }
    glossy_axis(sf, d, axis);
    for (i = 0; i < n; i++) {
        glossy_sample(sf, axis, key, i, n, rays[nb].dir, wt[nb]);
        memcpy(rays[nb].org, p, sizeof rays[nb].org);
        if (wt[nb][0] + wt[nb][1] + wt[nb][2] > 0.0f)
            nb++; /* below the surface: counted, not cast */
        if (nb > 0 && (nb == 64 || i == n - 1)) {
            cast(r, rays, hits, (uint32_t)nb, 1, 1, ts);
            for (j = 0; j < nb; j++)
                for (c = 0; c < 3; c++)
                    sum[c] += (double)wt[j][c] * hits[j].radiance[c];
            nb = 0;
        }
    }
    for (c = 0; c < 3 && n > 0; c++)
        out[c] += (float)(sum[c] / n);
}

static int shade_pixel(renderer *r, const cam_frame *cf, int x, int y, float out[3],
                       tstate *ts)
{
    const camera *c = &r->s->cam;
    float d[3], e[3], ld[3], p[3];
    /* Direct light's random numbers ignore the seed: two renders with other
     * seeds then differ only in their indirect light, which is what the
     * comparisons measure. */
    uint64_t pix = (uint64_t)y << 32 | (uint32_t)x, key = hash64(r->o.seed ^ pix);
    bvh_hit bh;
    surface sf;
    irc_sh sh;
    int i, st;
    camera_ray(cf, c, x, y, d);
    ts->rays++;
    if (!bvh_intersect(&r->b, cf->eye, d, 0.0f, FLT_MAX, &bh)) {
        if (r->o.show == SHOW_FULL)
            env_radiance(&r->s->env, d, out);
        else
            out[0] = out[1] = out[2] = 0.0f;
        return 0;
    }
    surface_at(r->s, cf->eye, d, &bh, &sf);
    cache_point(&sf, p);
    {
        /* E over the directions above the surface (ts->under, bounce.h). */
        ts->under[1] = sf.ng;
        st = irradiance(r, p, gather_normal(&sf), sf.nsm, sf.ng,
                        camera_footprint(cf, c, d, bh.t, sf.ng), key,
                        e, &sh, ts);
        ts->under[1] = NULL;
    }
    if (st != 0)
        return st;
    for (i = 0; i < 3; i++)
        out[i] = sf.m->kd[i] / (float)PI * e[i];
    if (r->o.lobe_rays > 0 && glossy_has(&sf))
        glossy_indirect(r, &sf, p, d, &sh, hash64(key ^ 0x6c6f6265ull), out, ts);
    if (r->o.show == SHOW_FULL) {
        emitted(&sf, ld);
        for (i = 0; i < 3; i++)
            out[i] += ld[i];
        direct_light(&r->b, &r->l, &sf, d, r->o.light_samples, hash64(pix), ld, &ts->rays);
        for (i = 0; i < 3; i++)
            out[i] += ld[i];
    }
    return 0;
}

typedef struct job {
    renderer *r;
    cam_frame cf;
    float *rgb;
    int next, done, error;  /* the pass's next pixel; pixels done in all */
    int level, levels;      /* this pass, of levels = 4^bits */
    int bits;               /* passes take pixels (1 << bits) apart */
    int open;               /* a pass of the cache is open */
    pthread_barrier_t wall;
    double start, shown;
    unsigned char *detail;  /* final_sweep: pixels answered per pixel */
    tstate ts[64];
} job;

static void progress(job *j, int done)
{
    double el = render_clock() - j->start;
    int all = j->r->s->cam.width * j->r->s->cam.height, bar = 40, k, n = (int)((double)done * bar / all);
    char line[64];
    if (!j->r->o.progress || el < 1.0 || (done < all && el - j->shown < 0.25))
        return;
    j->shown = el;
    for (k = 0; k < bar; k++)
        line[k] = k < n ? '#' : '.';
    line[bar] = 0;
    fprintf(stderr, "\r[%s] %3d%% %5.1fs", line, (int)(done * 100.0 / all), el);
    if (done == all)
        fputc('\n', stderr);
}

typedef struct warg {
    job *j;
    int id;
} warg;

/* The pixel offset, in a period of 1 << bits, of pass k of (1 << bits)^2:
 * each pair of k's bits, lowest first, sets the next lower bit of x and y,
 * so that passes 0..4^j - 1 together cover the lattice of stride
 * period / 2^j: coarse to fine, as an ordered-dither matrix. */
static void pass_offset(int k, int bits, int *ox, int *oy)
{
    int i;
    *ox = *oy = 0;
    for (i = 0; i < bits; i++) {
        int pair = (k >> (2 * i)) & 3;
        *ox |= (pair & 1) << (bits - 1 - i);
        *oy |= (pair >> 1) << (bits - 1 - i);
    }
}

/* Shades this thread's share of the pass's pixels, taken 8 at a time in
 * scanline order of the pass's lattice. */
static int shade_pass(job *j, tstate *ts, int id)
{
    const camera *c = &j->r->s->cam;
    const int step = j->r->o.stride > 1 ? j->r->o.stride : 1, period = 1 << j->bits;
    const int off = step > 1 ? j->r->o.stride_offset : 0;
    const int k = j->r->o.tiles > 1 ? j->r->o.tiles : 1, t = j->r->o.tile;
    const int y0 = (int)((long)c->height * t / k), y1 = (int)((long)c->height * (t + 1) / k);
    int ox, oy, nx, ny, m, st;
    pass_offset(j->level, j->bits, &ox, &oy);
    nx = (c->width - ox + period - 1) / period;
    ny = (c->height - oy + period - 1) / period;
    while ((m = __atomic_fetch_add(&j->next, 8, __ATOMIC_RELAXED)) < nx * ny) {
        int e = m + 8 < nx * ny ? m + 8 : nx * ny, done;
        for (; m < e; m++) {
            int x = ox + period * (m % nx), y = oy + period * (m / nx);
            if (__atomic_load_n(&j->error, __ATOMIC_RELAXED))
                return 0;
            if ((x - off) % step || (y - off) % step || x < off || y < off || y < y0 || y >= y1)
                continue;
            {
                const size_t at = (size_t)y * c->width + x;
                float v[3];
                if (ts->final && j->detail[at])
                    continue;
                ts->detail = 0;
                st = shade_pixel(j->r, &j->cf, x, y, v, ts);
                if (st < 0)
                    return st;
                if (st == IRC_MISS && ts->final)
                    continue; /* no record reaches: the fill's value stays */
                memcpy(&j->rgb[at * 3], v, sizeof v);
                if (j->detail)
                    j->detail[at] = (unsigned char)ts->detail;
                if (j->r->detail_map && !ts->final)
                    j->r->detail_map[at] = (unsigned char)ts->detail;
            }
        }
        done = __atomic_add_fetch(&j->done, 8, __ATOMIC_RELAXED);
        if (id == 0)
            progress(j, done);
    }
    return 0;
}

/* Every thread runs every pass; between two, all wait while thread 0
 * closes one pass and opens the next (a cache with passes). */
static void *worker(void *arg)
{
    job *j = ((warg *)arg)->j;
    int id = ((warg *)arg)->id, level, st;
    for (level = 0; level < j->levels; level++) {
        if ((st = shade_pass(j, &j->ts[id], id)) < 0)
            __atomic_store_n(&j->error, st, __ATOMIC_RELAXED);
        pthread_barrier_wait(&j->wall);
        if (id == 0) {
            tstate *ts = &j->ts[0];
            const double c0 = ts->cache_s;
            const int was = clock_enter(ts, CLOCK_CACHE);
            if (j->open && (st = irc_pass_end(j->r->cache, NULL)) < 0 && !j->error)
                j->error = st;
            j->open = 0;
            if (j->bits && level + 1 < j->levels && !j->error) {
                if ((st = irc_pass_begin(j->r->cache)) < 0)
                    j->error = st;
                j->open = st == IRC_OK;
            }
            clock_enter(ts, was);
            ts->pass_s += ts->cache_s - c0;
            j->next = 0;
            j->level = level + 1;
        }
        pthread_barrier_wait(&j->wall);
    }
    if (j->detail) { /* the final sweep: every pixel once more, all records in */
        j->ts[id].final = 1;
        if (id == 0)
            j->bits = 0;
        pthread_barrier_wait(&j->wall);
        if ((st = shade_pass(j, &j->ts[id], id)) < 0)
            __atomic_store_n(&j->error, st, __ATOMIC_RELAXED);
    }
    return NULL;
}

static void collect(renderer *r, const tstate *ts, int n, double wall, double cpu,
                    render_stats *st)
{
    irc_stats cs;
    int i;
    memset(st, 0, sizeof *st);
    st->wall = wall;
    st->cpu = cpu;
    for (i = 0; i < n; i++) {
        st->trace_s += ts[i].trace_s;
        st->cache_s += ts[i].cache_s;
        st->lookup_s += ts[i].lookup_s;
        st->gather_s += ts[i].gather_s;
        st->pass_s += ts[i].pass_s;
        st->rays += ts[i].rays;
        st->dropped += ts[i].dropped;
    }
    if (r->cache) {
        irc_cache_stats(r->cache, &cs);
        st->records = cs.records;
        st->lookups = cs.lookups;
        st->hits = cs.hits;
        st->evictions = cs.evictions;
        st->not_stored = cs.not_stored;
        st->details = cs.details;
        st->cache_bytes = cs.bytes_total;
        st->record_bytes = cs.record_bytes;
    }
    for (i = 0; i < MAX_BOUNCES; i++)
        if (r->deeper[i] && irc_cache_stats(r->deeper[i], &cs) == IRC_OK)
            st->level_records[i] = cs.records;
}

int render_image(renderer *r, float *rgb, render_stats *st)
{
    job *j = calloc(1, sizeof *j);
    pthread_t th[64];
    warg args[64];
    int n = r->o.threads < 1 ? 1 : r->o.threads > 64 ? 64 : r->o.threads, e = 0, t;
    const int passes = r->cache && !r->o.free_fill && !r->o.frozen;
    double cpu0;
    if (!j)
        return -1;
    j->r = r;
    j->rgb = rgb;
    if (passes && r->o.final_sweep &&
        !(j->detail = calloc((size_t)r->s->cam.width * r->s->cam.height, 1))) {
        free(j);
        return -1;
    }
    j->start = render_clock();
    cpu0 = render_cpu_clock();
    /* Passes of pixels P apart, coarse to fine, P^2 of them: the first
     * passes place records far apart, later ones find most pixels served.
     * Two misses of one pass both make records where one might have
     * served, so P should exceed a record's reach in pixels, which grows
     * with the image: P is the power of two nearest width / 24, in [8,
     * 32].  It must not depend on the thread count.  (fig5 at 384 x 288:
     * 19,798 records with P = 2, 6,331 with 4, 3,147 with 8, 2,550 with
     * 16, 2,474 with 32; 3,002 filled freely.) */
    j->bits = 3;
    while (passes && j->bits < 5 && r->s->cam.width > 24 * (3 << j->bits) / 2)
        j->bits++;
    if (!passes)
        j->bits = 0;
    j->levels = 1 << (2 * j->bits);
    camera_frame(&r->s->cam, &j->cf);
    if (pthread_barrier_init(&j->wall, NULL, (unsigned)n) != 0) {
        free(j);
        return -1;
    }
    if (passes && (e = irc_pass_begin(r->cache)) < 0) {
        pthread_barrier_destroy(&j->wall);
        free(j);
        return e;
    }
    j->open = passes;
    for (t = 0; t < n; t++) {
        args[t].j = j;
        args[t].id = t;
        if (t > 0)
            pthread_create(&th[t], NULL, worker, &args[t]);
    }
    worker(&args[0]);
    for (t = 1; t < n; t++)
        pthread_join(th[t], NULL);
    pthread_barrier_destroy(&j->wall);
    collect(r, j->ts, n, render_clock() - j->start, render_cpu_clock() - cpu0, st);
    e = j->error;
    free(j->detail);
    free(j);
    return e;
}

int render_points(renderer *r, const float *pn, int n, float *rgb, render_stats *st)
{
    tstate ts;
    double t0 = render_clock(), c0 = render_cpu_clock();
    int i, e;
    memset(&ts, 0, sizeof ts);
    for (i = 0; i < n; i++) {
        const float *p = &pn[6 * i], *nn = &pn[6 * i + 3];
        uint64_t key = hash64(r->o.seed ^ (uint64_t)i);
        irc_sh sh;
        if ((e = irradiance(r, p, nn, nn, NULL, 0.0f, key, &rgb[3 * i], &sh, &ts)) < 0)
            return e;
    }
    collect(r, &ts, 1, render_clock() - t0, render_cpu_clock() - c0, st);
    return 0;
}

int render_record(renderer *r, const float p[3], const float n[3], irc_record *out)
{
    tstate ts;
    memset(&ts, 0, sizeof ts);
    if (!r->cache)
        return IRC_ERR_CONFIG;
    int st;
    st = irc_record_compute(r->cache, p, n, out, &ts);
    return st;
}
