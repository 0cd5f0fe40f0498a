/* embree.c -- irrcache in an Embree 3 tracer: one-bounce indirect light
 * kd/pi E of a scene file (the demo's loader reads its OBJ, camera, sun
 * and constant sky; the first channel only: a grey scene), from the cache with the library's defaults and the recommended
 * call, against brute force through the same callback.
 *
 *   embree SCENE [W H]     (make embree-example: the Sponza atrium, 320 x 240)
 *
 * The host side is what an Embree renderer writes: each thread's
 * RTCIntersectContext reaches the callback as the call's host pointer;
 * camera hits call irc_cache_lookup_or_compute_px with the pixel's
 * footprint, in deterministic fill passes.  Brute force and a 16384-ray
 * reference run on a lattice of every 4th pixel (their cost per pixel does
 * not depend on the neighbours; the cache's image is whole), and the
 * speedup at equal relative RMSE is brute force's time interpolated
 * (log-log) to the cache's error over the cache's time, both the
 * process's CPU seconds.  It also prints the library's own share of the
 * cache's render, outside the callback: lookups (calls that sampled no
 * hemisphere), record and detail sampling, and pass ends. */
#define _POSIX_C_SOURCE 200809L
#include <embree3/rtcore.h>
#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "irrcache.h"
#include "scene.h"

#define THREADS 2
#define STRIDE 4     /* the error lattice: every 4th pixel from 1 */
#define PI 3.14159265358979323846f

typedef struct host { /* one a thread */
    struct RTCIntersectContext ctx;
    double in_calls, in_trace, in_passes; /* seconds: inside the _px calls,
                                             inside the callback within
                                             them, in pass ends */
    double in_lookups;   /* of in_calls less in_trace: the calls that
                            sampled no hemisphere (lookups) */
    unsigned long gathers; /* callbacks of hemisphere rays (records and
                              per-pixel estimates), not probes or
                              confirming rays */
} host;

typedef struct world {
    const scene *s;
    RTCScene rtc;
    float eye[3], f[3], r[3], u[3], tx, ty;
    int w, h, rays;   /* rays: brute force's a point, 0 for the cache */
    unsigned salt;    /* the reference's own random numbers: not brute force's */
    irc_cache *cache;
    pthread_barrier_t wall;
    float *img;
    int failed;
    double lib_s, pass_s, lookup_s; /* the cache's render: the library's
                                       own seconds (outside the callback),
                                       its pass ends and its lookups */
} world;

/* The process's CPU time over every thread: what one thread would take,
 * so the comparison holds on a shared machine. */
static double now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* A thread's time on a monotonic clock, for the split of the cache's
 * render (cheap enough to read at every callback). */
static double tick(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static float dot(const float a[3], const float b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static void normalize(float v[3])
{
    float l = sqrtf(dot(v, v));
    v[0] /= l, v[1] /= l, v[2] /= l;
}

/* The nearest hit along (o, d): distance, or -1; its unit normal facing o
 * and its diffuse reflectance. */
static float cast(const world *w, host *hs, const float o[3], const float d[3], float n[3],
                  float *kd)
{
    struct RTCRayHit rh;
    memset(&rh, 0, sizeof rh);
    rh.ray.org_x = o[0], rh.ray.org_y = o[1], rh.ray.org_z = o[2];
    rh.ray.dir_x = d[0], rh.ray.dir_y = d[1], rh.ray.dir_z = d[2];
    rh.ray.tnear = 1e-4f;
    rh.ray.tfar = INFINITY;
    rh.ray.mask = ~0u;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(w->rtc, &hs->ctx, &rh);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID)
        return -1.0f;
    n[0] = rh.hit.Ng_x, n[1] = rh.hit.Ng_y, n[2] = rh.hit.Ng_z;
    *kd = w->s->mats[w->s->tris[rh.hit.primID].mat].kd[0];
    normalize(n);
    if (dot(n, d) > 0.0f)
        n[0] = -n[0], n[1] = -n[1], n[2] = -n[2];
    return rh.ray.tfar;
}

/* Light leaving a diffuse surface at p (normal n) from the sun: kd/pi E
 * cos, one shadow ray. */
static float sunlit(const world *w, host *hs, const float p[3], const float n[3], float kd)
{
    const sun *su = &w->s->sun;
    float c = dot(n, su->dir);
    struct RTCRay ray;
    if (!su->on || c <= 0.0f)
        return 0.0f;
    memset(&ray, 0, sizeof ray);
    ray.org_x = p[0] + 1e-3f * n[0], ray.org_y = p[1] + 1e-3f * n[1], ray.org_z = p[2] + 1e-3f * n[2];
    ray.dir_x = su->dir[0], ray.dir_y = su->dir[1], ray.dir_z = su->dir[2];
    ray.tfar = INFINITY;
    ray.mask = ~0u;
    rtcOccluded1(w->rtc, &hs->ctx, &ray);
    return ray.tfar < 0.0f ? 0.0f : kd / PI * su->e[0] * c; /* tfar -inf: blocked */
}

/* The cache's rays: the sunlit surfaces they meet, or the sky. */
static int trace(const irc_trace_args *a)
{
    const world *w = (const world *)a->context;
    host *hs = (host *)a->host;
    const double t0 = w->rays ? 0.0 : tick();
    uint32_t i;
    hs->gathers += !a->visibility_only;
    for (i = 0; i < a->count; i++) {
        irc_hit *h = &a->hits[i];
        float kd = 0.0f, t = cast(w, hs, a->rays[i].org, a->rays[i].dir, h->normal, &kd), q[3];
        int k;
        h->status = t > 0.0f ? IRC_RAY_HIT : IRC_RAY_ESCAPED;
        h->dist = t;
        if (a->visibility_only) /* a confirming ray: the distance is all */
            continue;
        for (k = 0; k < 3; k++)
            q[k] = a->rays[i].org[k] + t * a->rays[i].dir[k];
        h->radiance[0] = t > 0.0f ? sunlit(w, hs, q, h->normal, kd)
                                  : w->s->env.kind == ENV_CONSTANT ? w->s->env.base[0] : 0.0f;
        h->radiance[1] = h->radiance[2] = h->radiance[0];
    }
    if (!w->rays)
        hs->in_trace += tick() - t0;
    return 0;
}

/* Brute force: N cosine-weighted rays on a stratified m x (N/m) grid. */
static float brute(world *w, host *hs, const float p[3], const float n[3], unsigned key)
{
    irc_trace_args a;
    irc_ray ray;
    irc_hit hit;
    float t1[3], t2[3], s = n[2] >= 0.0f ? 1.0f : -1.0f, b = -1.0f / (s + n[2]), sum = 0.0f;
    int m = (int)sqrtf((float)w->rays), k = w->rays / m, i, c;
    t1[0] = 1.0f + s * n[0] * n[0] * b, t1[1] = s * n[0] * n[1] * b, t1[2] = -s * n[0];
    t2[0] = n[0] * n[1] * b, t2[1] = s + n[1] * n[1] * b, t2[2] = -n[1];
    memset(&a, 0, sizeof a);
    a.context = w, a.host = hs, a.rays = &ray, a.hits = &hit, a.count = 1;
    for (i = 0; i < m * k; i++) {
        float u1, u2, st, ph;
        key = key * 1664525u + 1013904223u;
        u1 = ((float)(i / k) + (float)(key >> 8) / 16777216.0f) / (float)m;
        key = key * 1664525u + 1013904223u;
        u2 = ((float)(i % k) + (float)(key >> 8) / 16777216.0f) / (float)k;
        st = sqrtf(u1), ph = 2.0f * PI * u2;
        for (c = 0; c < 3; c++) {
            ray.org[c] = p[c];
            ray.dir[c] = st * (cosf(ph) * t1[c] + sinf(ph) * t2[c]) + sqrtf(1.0f - u1) * n[c];
        }
        trace(&a);
        sum += hit.radiance[0];
    }
    return PI * sum / (float)(m * k);
}

/* kd/pi E at pixel (x, y): 0 where the camera ray escapes. */
static void pixel(world *w, host *hs, int x, int y)
{
    float d[3], n[3], p[3], e[3] = {0, 0, 0}, sx = (2.0f * (x + 0.5f) / w->w - 1.0f) * w->tx,
                                           sy = (1.0f - 2.0f * (y + 0.5f) / w->h) * w->ty, t, kd;
    int k;
    for (k = 0; k < 3; k++)
        d[k] = w->f[k] + sx * w->r[k] + sy * w->u[k];
    normalize(d);
    if ((t = cast(w, hs, w->eye, d, n, &kd)) < 0.0f)
        return;
    for (k = 0; k < 3; k++)
        p[k] = w->eye[k] + t * d[k] + 1e-3f * n[k];
    if (w->rays) {
        e[0] = brute(w, hs, p, n, ((unsigned)(y * w->w + x) ^ w->salt) * 2654435761u);
    } else {
        /* the footprint: sqrt of the area the pixel covers there */
        float fp = 0.0f;
        const double t0 = tick(), traced = hs->in_trace;
        const unsigned long gathers = hs->gathers;
        double t1;
        if (irc_pixel_footprint(w->eye, w->f, 2.0f * w->ty / w->h, p, n, &fp) < 0 ||
            irc_cache_lookup_or_compute_px(w->cache, p, n, NULL, fp, e, NULL, hs) < 0)
            w->failed = 1;
        t1 = tick() - t0;
        hs->in_calls += t1;
        if (hs->gathers == gathers)
            hs->in_lookups += t1 - (hs->in_trace - traced);
    }
    w->img[y * w->w + x] = kd / PI * e[0];
}

typedef struct job {
    world *w;
    int id;
} job;

/* Fill passes take pixels P = 2^bits apart in P^2 passes, P the power of
 * two nearest width / 24 in [8, 32] (irrcache.h, irc_pass_begin): 16 at
 * 320 pixels. */
static int pass_bits(int width)
{
    int b = 3;
    while (b < 5 && width > 24 * (3 << b) / 2)
        b++;
    return b;
}

/* Brute force: this thread's rows of the lattice.  The cache: every pass,
 * coarse to fine (pixel offsets as an ordered-dither matrix), thread 0
 * closing one and opening the next between two barriers. */
static void *work(void *arg)
{
    world *w = ((job *)arg)->w;
    const int id = ((job *)arg)->id, bits = pass_bits(w->w), P = 1 << bits;
    host hs;
    int x, y, k, i, ox, oy, at = 0;
    memset(&hs, 0, sizeof hs);
    rtcInitIntersectContext(&hs.ctx);
    if (w->rays) {
        for (y = 1 + STRIDE * id; y < w->h; y += STRIDE * THREADS)
            for (x = 1; x < w->w; x += STRIDE)
                pixel(w, &hs, x, y);
        return NULL;
    }
    for (k = 0; k < P * P; k++) {
        for (ox = oy = 0, i = 0; i < bits; i++) {
            ox |= ((k >> (2 * i)) & 1) << (bits - 1 - i);
            oy |= ((k >> (2 * i + 1)) & 1) << (bits - 1 - i);
        }
        for (y = oy; y < w->h; y += P)
            for (x = ox; x < w->w; x += P)
                if (at++ % THREADS == id)
                    pixel(w, &hs, x, y);
        pthread_barrier_wait(&w->wall);
        if (id == 0) {
            const double t0 = tick();
            if (irc_pass_end(w->cache, NULL) < 0 ||
                (k + 1 < P * P && irc_pass_begin(w->cache) < 0))
                w->failed = 1;
            hs.in_passes += tick() - t0;
        }
        pthread_barrier_wait(&w->wall);
    }
    /* each thread adds its share, between the barriers of the last pass */
    for (i = 0; i < THREADS; i++) {
        if (i == id) {
            w->lib_s += hs.in_calls - hs.in_trace + hs.in_passes;
            w->pass_s += hs.in_passes;
            w->lookup_s += hs.in_lookups;
        }
        pthread_barrier_wait(&w->wall);
    }
    return NULL;
}

/* Renders with `rays` brute-force rays a point (0: the cache); seconds. */
static double render(world *w, int rays, float *img)
{
    pthread_t t[THREADS];
    job j[THREADS];
    double t0 = now();
    int i;
    w->rays = rays;
    w->img = img;
    memset(img, 0, sizeof(float) * (size_t)(w->w * w->h));
    if (!rays && (irc_cache_clear(w->cache) < 0 || irc_pass_begin(w->cache) < 0))
        w->failed = 1;
    for (i = 0; i < THREADS; i++) {
        j[i].w = w, j[i].id = i;
        pthread_create(&t[i], NULL, work, &j[i]);
    }
    for (i = 0; i < THREADS; i++)
        pthread_join(t[i], NULL);
    return now() - t0;
}

static double rel_rmse(const world *w, const float *img, const float *ref)
{
    double se = 0.0, sr = 0.0;
    int x, y;
    for (y = 1; y < w->h; y += STRIDE)
        for (x = 1; x < w->w; x += STRIDE) {
            double a = img[y * w->w + x], b = ref[y * w->w + x];
            se += (a - b) * (a - b);
            sr += b * b;
        }
    return sqrt(se / sr);
}

/* Embree's scene: one triangle mesh, three vertices a triangle. */
static RTCScene build(RTCDevice dev, const scene *s)
{
    RTCScene rtc = rtcNewScene(dev);
    RTCGeometry g = rtcNewGeometry(dev, RTC_GEOMETRY_TYPE_TRIANGLE);
    float *v = rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                       3 * sizeof(float), 3 * (size_t)s->ntris);
    unsigned *ix = rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                           3 * sizeof(unsigned), (size_t)s->ntris);
    int i;
    for (i = 0; i < 3 * s->ntris; i++) {
        memcpy(v + 3 * i, s->tris[i / 3].v[i % 3], 3 * sizeof(float));
        ix[i] = (unsigned)i;
    }
    rtcCommitGeometry(g);
    rtcAttachGeometry(rtc, g);
    rtcReleaseGeometry(g);
    rtcCommitScene(rtc);
    return rtc;
}

int main(int argc, char **argv)
{
    static const int counts[4] = {64, 256, 1024, 4096};
    scene s;
    world w;
    char err[512];
    irc_config cfg = IRC_CONFIG_INIT; /* the library's defaults */
    size_t bytes;
    float *ref, *img;
    double tb[4], eb[4], tc, ec, tbrute = -1.0, full;
    const char *ext = "";
    RTCDevice dev;
    int i, k;
    if (argc < 2 || scene_load(argv[1], &s, err, sizeof err) < 0)
        return fprintf(stderr, "usage: embree SCENE [W H]%s%s\n", argc > 1 ? ": " : "",
                       argc > 1 ? err : ""), 2;
    memset(&w, 0, sizeof w);
    w.s = &s;
    w.w = argc > 3 ? atoi(argv[2]) : 320;
    w.h = argc > 3 ? atoi(argv[3]) : 240;
    dev = rtcNewDevice(NULL);
    w.rtc = build(dev, &s);
    for (k = 0; k < 3; k++) {
        w.eye[k] = s.cam.eye[k];
        w.f[k] = s.cam.look[k] - s.cam.eye[k];
    }
    normalize(w.f);
    w.r[0] = w.f[1] * s.cam.up[2] - w.f[2] * s.cam.up[1];
    w.r[1] = w.f[2] * s.cam.up[0] - w.f[0] * s.cam.up[2];
    w.r[2] = w.f[0] * s.cam.up[1] - w.f[1] * s.cam.up[0];
    normalize(w.r);
    w.u[0] = w.r[1] * w.f[2] - w.r[2] * w.f[1];
    w.u[1] = w.r[2] * w.f[0] - w.r[0] * w.f[2];
    w.u[2] = w.r[0] * w.f[1] - w.r[1] * w.f[0];
    w.ty = tanf(s.cam.fov_deg * PI / 360.0f);
    w.tx = w.ty * (float)w.w / (float)w.h;
    cfg.trace = trace;
    cfg.context = &w;
    cfg.threads = THREADS;
    /* a lookup-or-compute makes at most one record: pixels bound them */
    if (irc_footprint(&cfg, (uint32_t)(w.w * w.h), &bytes) < 0 || !(cfg.buffer = malloc(bytes)))
        return 1;
    cfg.buffer_size = bytes;
    ref = malloc(sizeof(float) * (size_t)(w.w * w.h));
    img = malloc(sizeof(float) * (size_t)(w.w * w.h));
    if (!ref || !img || irc_init(&cfg, (uint32_t)(w.w * w.h), &w.cache) < 0 ||
        pthread_barrier_init(&w.wall, NULL, THREADS) != 0)
        return 1;
    /* lattice pixels stand for the frame: brute force's times scaled */
    full = (double)(w.w * w.h) / (double)(((w.w - 1 + STRIDE - 1) / STRIDE) *
                                          ((w.h - 1 + STRIDE - 1) / STRIDE));
    printf("%s: %d triangles, %dx%d, %d threads\n", argv[1], s.ntris, w.w, w.h, THREADS);
    /* the reference: 16384 rays of numbers brute force's runs do not use */
    w.salt = 0x5bd1e995u;
    render(&w, 16384, ref);
    w.salt = 0;
    for (i = 0; i < 4; i++) {
        tb[i] = full * render(&w, counts[i], img);
        eb[i] = rel_rmse(&w, img, ref);
        printf("  brute force, %4d rays: relative RMSE %.4f in %6.2f s (the frame's)\n", counts[i],
               eb[i], tb[i]);
    }
    {
        const double wall0 = tick();
        tc = render(&w, 0, img);
        /* the library's share of the threads' time: its calls less the
         * callback inside them, pass ends with them */
        const double all = THREADS * (tick() - wall0);
        printf("  the library's own time (outside the callback): %.1f%% of the threads': "
               "lookups %.1f%%, record and detail sampling %.1f%%, pass ends %.1f%%\n",
               100.0 * w.lib_s / all, 100.0 * w.lookup_s / all,
               100.0 * (w.lib_s - w.lookup_s - w.pass_s) / all, 100.0 * w.pass_s / all);
    }
    ec = rel_rmse(&w, img, ref);
    {
        irc_stats st;
        irc_cache_stats(w.cache, &st);
        printf("  cache (defaults, _px, passes): relative RMSE %.4f in %6.2f s, %llu records, "
               "%llu per-pixel answers, %llu not stored\n",
               ec, tc, (unsigned long long)st.records, (unsigned long long)st.details,
               (unsigned long long)st.not_stored);
    }
    /* brute force's time at the cache's error, log-log between its runs,
     * or past its last along the last two (marked) */
    for (i = 1; i < 4 && !(eb[i] <= ec && eb[i - 1] >= ec); i++)
        ;
    if (i == 4 && ec < eb[3]) {
        i = 3;
        ext = " (extrapolated)";
    }
    if (i < 4)
        tbrute = exp(log(tb[i - 1]) + (log(ec) - log(eb[i - 1])) / (log(eb[i]) - log(eb[i - 1])) *
                                          (log(tb[i]) - log(tb[i - 1])));
    if (tbrute > 0.0)
        printf("  speedup at equal error: %.1fx%s\n", tbrute / tc, ext);
    else
        printf("  the cache's error is outside brute force's runs\n");
    irc_fini(w.cache);
    rtcReleaseScene(w.rtc);
    rtcReleaseDevice(dev);
    free(cfg.buffer);
    free(ref);
    free(img);
    scene_free(&s);
    return w.failed || !(ec < 0.2) ? 1 : 0;
}
