/*
 * bench_core.c -- the core library's figures, as CSV on stdout:
 *   bytes per record for each feature set; index bytes per record (the
 *   pool reserved and the nodes used); lookups per second on one core at
 *   1e5 and 1e6 records, with queries in random order and in coherent
 *   (scanline-like) order, filled freely, and again inside a fill pass
 *   after one has laid the records out in the index's order; inserts per
 *   second.
 *
 * The records lie on the six inner faces of a unit box, normals inward,
 * with radii set so a query point lies within reach of about 6 records
 * (that is, a full cache at accuracy 0.2).  Queries sit on the same faces.
 * The box has a corner at the origin; the placement rows move it to be
 * centred on the origin and 1000 away, where users put their scenes.
 *
 * Records: library time per record for each feature set with a host whose
 * rays cost almost nothing, and the gradients' cost as ratios; then the
 * Cornell box rendered by the demo's tracer (cornell_rows): the cache's
 * share of the render and the gradients' share of a record's thread time
 * with a real host.  Run from the project's root (it reads
 * demo/scenes/cornell.scene).
 */
#define _POSIX_C_SOURCE 200809L
#include <float.h>
#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "irrcache.h"
#include "bench_util.h"
#include "bvh.h"
#include "camera.h"
#include "render.h"
#include "scene.h"
#include "shade.h"


static unsigned long long rng = 1;
static double urand(void)
{
    unsigned long long x = (rng += 0x9e3779b97f4a7c15ull);
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
    return (double)((x ^ (x >> 31)) >> 11) * (1.0 / 9007199254740992.0);
}

static int no_trace(const irc_trace_args *a)
{
    (void)a;
    return -1;
}

/* Microseconds of library time per record computed. */
static double record_cost(uint32_t features, uint32_t m, uint32_t n, double seconds)
{
    irc_config cfg;
    irc_cache *c;
    size_t bytes;
    double t0, t1;
    long done = 0;
    memset(&cfg, 0, sizeof cfg);
    cfg.version = IRC_CONFIG_VERSION;
    cfg.trace = bench_cheap_trace;
    cfg.features = features;
    cfg.strata_theta = m;
    cfg.strata_phi = n;
    cfg.max_batch = 256;
    irc_footprint(&cfg, 16, &bytes);
    cfg.buffer = malloc(bytes);
    cfg.buffer_size = bytes;
    cfg.sh.bands = (features & IRC_FEATURE_SH) ? 3u : 0u;
    irc_init(&cfg, 16, &c);
    t0 = bench_now();
    do {
        float p[3] = {(float)urand(), (float)urand(), 0.0f}, nn[3] = {0.0f, 0.0f, 1.0f};
        irc_record r;
        irc_sh sh;
        if ((features & IRC_FEATURE_SH) ? irc_sh_compute(c, p, nn, &sh, NULL) != IRC_OK
                                        : irc_record_compute(c, p, nn, &r, NULL) != IRC_OK)
            return -1.0;
        done++;
        t1 = bench_now();
    } while (t1 - t0 < seconds);
    free(cfg.buffer);
    return 1e6 * (t1 - t0) / done;
}

/* Library time of records with features b over records with features a:
 * five alternating runs of each, the fastest of each kept (this machine's
 * speed drifts by up to 2x; alternation puts both under the same drift). */
static double cost_ratio(uint32_t a, uint32_t b, uint32_t m, uint32_t n)
{
    double best_a = 1e30, best_b = 1e30;
    int k;
    for (k = 0; k < 5; k++) {
        double ta = record_cost(a, m, n, 0.15), tb = record_cost(b, m, n, 0.15);
        if (ta < best_a) best_a = ta;
        if (tb < best_b) best_b = tb;
    }
    return best_b / best_a;
}

/* Snapshot write, read and merge throughput of a filled cache (records/s),
 * the read and the merge into a second block of the same config. */
static void snapshot_rates(irc_cache *c, const irc_config *cfg, uint32_t cap)
{
    irc_config c2 = *cfg;
    irc_cache *d;
    size_t bytes = 0, need;
    unsigned char *buf;
    irc_stats st;
    double t0;
    if (irc_snapshot_size(c, &bytes) != IRC_OK || irc_cache_stats(c, &st) != IRC_OK ||
        !(buf = malloc(bytes)))
        return;
    t0 = bench_now();
    irc_snapshot_write(c, 1u, buf, bytes, NULL, NULL, NULL);
    printf("snapshot_write_per_s,trans+rot,%u,,,%.0f,records/s\n", cap,
           st.records / (bench_now() - t0));
    irc_footprint(&c2, cap, &need);
    c2.buffer = malloc(need);
    c2.buffer_size = need;
    if (c2.buffer && irc_init(&c2, cap, &d) == IRC_OK) {
        t0 = bench_now();
        if (irc_snapshot_read(d, 1u, buf, bytes) == IRC_OK)
            printf("snapshot_read_per_s,trans+rot,%u,,,%.0f,records/s\n", cap,
                   st.records / (bench_now() - t0));
        /* A merge into an empty cache: every check, the canonical sort,
         * the index rebuilt. */
        irc_cache_clear(d);
        t0 = bench_now();
        if (irc_merge(d, 1u, buf, bytes) == IRC_OK)
            printf("merge_per_s,trans+rot,%u,,,%.0f,records/s\n", cap,
                   st.records / (bench_now() - t0));
        irc_fini(d);
    }
    free(c2.buffer);
    free(buf);
}

static double shift; /* the box's offset along every axis */

/* A point on face f (0..5) at face coordinates (u, v) in [0,1)^2. */
static void face_point(int f, double u, double v, float p[3], float n[3])
{
    int axis = f % 3, side = f / 3, a1 = (axis + 1) % 3, a2 = (axis + 2) % 3;
    p[axis] = (float)(side + shift);
    p[a1] = (float)(u + shift);
    p[a2] = (float)(v + shift);
    n[0] = n[1] = n[2] = 0.0f;
    n[axis] = side ? -1.0f : 1.0f;
}

static irc_cache *build(irc_config *cfg, uint32_t count, double *insert_rate)
{
    size_t bytes;
    irc_cache *c;
    irc_record r;
    double reach = sqrt(6.0 * 6.0 / (3.14159265 * count)), t0;
    uint32_t i;
    irc_footprint(cfg, count, &bytes);
    cfg->buffer = malloc(bytes);
    cfg->buffer_size = bytes;
    if (!cfg->buffer || irc_init(cfg, count, &c) != IRC_OK)
        return NULL;
    memset(&r, 0, sizeof r);
    t0 = bench_now();
    for (i = 0; i < count; i++) {
        face_point((int)(urand() * 6), urand(), urand(), r.p, r.n);
        r.e[0] = r.e[1] = r.e[2] = (float)(0.5 + urand());
        r.grad_t[0][0] = 0.1f;
        r.radius = (float)(reach / cfg->accuracy * exp((urand() - 0.5) * 1.4));
        if (irc_cache_insert(c, &r) != IRC_OK)
            return NULL;
    }
    *insert_rate = count / (bench_now() - t0);
    return c;
}

enum { Q = 1 << 16 };
static float qp[Q][3], qn[Q][3];

static void make_queries(int coherent)
{
    int i;
    for (i = 0; i < Q; i++) {
        if (coherent) {
            /* 256-long scanlines, step 1/4096 of the face */
            int f = (i >> 14) % 6;
            double v = urand();
            int j, line = i;
            for (j = 0; j < 256 && i < Q; j++, i++)
                face_point(f, (double)((line + j) & 255) / 4096.0 + 0.3, v, qp[i], qn[i]);
            i--;
        } else {
            face_point((int)(urand() * 6), urand(), urand(), qp[i], qn[i]);
        }
    }
}

typedef struct looper {
    irc_cache *c;
    int first;            /* where in the queries this thread starts */
    long done, hits;
    double seconds;
} looper;

/* Lookups over the query set, from first on, for about a second. */
static void *lookup_loop(void *arg)
{
    looper *l = (looper *)arg;
    double t0 = bench_now(), t1, sink = 0.0;
    int i;
    l->done = l->hits = 0;
    do {
        for (i = 0; i < Q; i++) {
            int at = (l->first + i) & (Q - 1);
            float rgb[3], w;
            l->hits += irc_cache_lookup(l->c, qp[at], qn[at], rgb, &w) == IRC_OK;
            sink += rgb[0];
        }
        l->done += Q;
        t1 = bench_now();
    } while (t1 - t0 < 1.0);
    l->seconds = t1 - t0;
    if (sink < 0.0)
        printf("#\n");
    return NULL;
}

/* Lookups per second over the current query set with n threads (each
 * starting at another place in it), summed over threads. */
static double lookups_n(irc_cache *c, int n, double *hit_rate)
{
    pthread_t th[8];
    looper l[8];
    double rate = 0.0;
    long done = 0, hits = 0;
    int t;
    for (t = 0; t < n; t++) {
        l[t].c = c;
        l[t].first = t * (Q / n);
        if (t > 0)
            pthread_create(&th[t], NULL, lookup_loop, &l[t]);
    }
    lookup_loop(&l[0]);
    for (t = 0; t < n; t++) {
        if (t > 0)
            pthread_join(th[t], NULL);
        rate += l[t].done / l[t].seconds;
        done += l[t].done;
        hits += l[t].hits;
    }
    *hit_rate = (double)hits / done;
    return rate;
}

static double lookups(irc_cache *c, int coherent, double *hit_rate)
{
    make_queries(coherent);
    return lookups_n(c, 1, hit_rate);
}

/* The same 1e5 records and random queries with the box at three places:
 * an index tied to a grid through the origin degenerates to lists when
 * records straddle a coordinate plane. */
static void placement(void)
{
    static const struct { double at; const char *name; } where[] = {
        {0.0, "corner-at-origin"}, {-0.5, "centred-on-origin"}, {1000.0, "1000-away"}};
    size_t w;
    for (w = 0; w < 3; w++) {
        irc_config cfg;
        irc_cache *c;
        irc_stats st;
        double ins, hr, rate;
        memset(&cfg, 0, sizeof cfg);
        cfg.version = IRC_CONFIG_VERSION;
        cfg.trace = no_trace;
        cfg.accuracy = 0.2f;
        cfg.features = IRC_FEATURE_TRANSLATION | IRC_FEATURE_ROTATION;
        cfg.port = &irc_port_none;
        rng = 1;
        shift = where[w].at;
        if (!(c = build(&cfg, 100000, &ins)))
            break;
        irc_cache_stats(c, &st);
        rate = lookups(c, 0, &hr);
        printf("lookups_per_s,trans+rot,100000,none,random %s,%.0f,1/s\n", where[w].name, rate);
        printf("index_nodes_used,trans+rot,100000,none,%s,%llu,nodes\n", where[w].name,
               (unsigned long long)st.index_nodes);
        free(cfg.buffer);
    }
    shift = 0.0;
}

/* ------------------------------------------------------------ the Cornell box
 * The render rows: demo/scenes/cornell.scene at 256 x 256, indirect
 * light only, a = 0.2, 16x64 strata, trans + rot, fill passes, one thread
 * (as make bench renders it, smaller): the cache's share of the thread's
 * time (library time in cache calls, the host's tracing excluded, over the
 * wall time); and the gradients' share of one record's thread time there,
 * the host's tracing included: records at the camera's hits on a 16 x 16
 * pixel lattice, five alternating runs with and without gradients, the
 * fastest of each kept. */
#define CORNELL "demo/scenes/cornell.scene"

static int cornell_opts(renderer *r, const scene *s, uint32_t features)
{
    render_opts o;
    char err[256];
    memset(&o, 0, sizeof o);
    o.mode = MODE_CACHE;
    o.features = features;
    o.threads = 1;
    o.show = SHOW_INDIRECT;
    o.light_samples = 1;
    o.seed = 7;
    o.accuracy = 0.2f;
    o.strata_m = 16;
    o.strata_n = 64;
    o.max_records = 400000;
    o.max_radius = -1.0f;
    if (renderer_init(r, s, &o, err, sizeof err) < 0) {
        fprintf(stderr, "bench_core: %s\n", err);
        return -1;
    }
    return 0;
}

/* Seconds a record at each of the k points (6 floats a point). */
static double cornell_record_s(const scene *s, uint32_t features, const float *pn, int k)
{
    renderer r;
    irc_record rec;
    double t0, t;
    int i;
    if (cornell_opts(&r, s, features) < 0)
        return -1.0;
    t0 = bench_now();
    for (i = 0; i < k; i++)
        if (render_record(&r, &pn[6 * i], &pn[6 * i + 3], &rec) != IRC_OK)
            break;
    t = (bench_now() - t0) / k;
    renderer_free(&r);
    return i == k ? t : -1.0;
}

static void cornell_rows(void)
{
    const uint32_t both = IRC_FEATURE_TRANSLATION | IRC_FEATURE_ROTATION;
    enum { LATTICE = 16 };
    scene s;
    renderer r;
    render_stats st;
    cam_frame cf;
    char err[256];
    float *img, pn[6 * LATTICE * LATTICE];
    double best[2] = {1e30, 1e30};
    int i, j, k = 0;
    if (scene_load(CORNELL, &s, err, sizeof err) < 0) {
        fprintf(stderr, "bench_core: %s\n", err);
        return;
    }
    s.cam.width = s.cam.height = 256;
    img = malloc(sizeof(float) * 3 * 256 * 256);
    if (img && cornell_opts(&r, &s, both) == 0) {
        if (render_image(&r, img, &st) == 0)
            printf("cornell_cache_share,trans+rot,%llu,,256x256 a=0.2 16x64,%.4f,of thread time\n",
                   (unsigned long long)st.records, st.cache_s / st.wall);
        camera_frame(&s.cam, &cf);
        for (j = 0; j < LATTICE; j++)
            for (i = 0; i < LATTICE; i++) {
                float d[3];
                bvh_hit h;
                surface sf;
                camera_ray(&cf, &s.cam, 8 + 16 * i, 8 + 16 * j, d);
                if (!bvh_intersect(&r.b, cf.eye, d, 0.0f, FLT_MAX, &h))
                    continue;
                surface_at(&s, cf.eye, d, &h, &sf);
                cache_point(&sf, &pn[6 * k]);
                memcpy(&pn[6 * k + 3], sf.nsm, sizeof sf.nsm);
                k++;
            }
        renderer_free(&r);
    }
    free(img);
    for (i = 0; i < 5 && k > 0; i++) {
        double a = cornell_record_s(&s, 0u, pn, k), b = cornell_record_s(&s, both, pn, k);
        if (a < 0.0 || b < 0.0)
            break;
        best[0] = a < best[0] ? a : best[0];
        best[1] = b < best[1] ? b : best[1];
    }
    if (i == 5) {
        printf("record_us_thread,bare,%d,,cornell 16x64,%.2f,us\n", k, 1e6 * best[0]);
        printf("record_us_thread,trans+rot,%d,,cornell 16x64,%.2f,us\n", k, 1e6 * best[1]);
        printf("gradient_share_of_record,trans+rot,%d,,cornell 16x64,%.4f,of thread time\n", k,
               (best[1] - best[0]) / best[1]);
    }
    scene_free(&s);
}

int main(void)
{
    static const struct { uint32_t f; const char *name; } sets[] = {
        {IRC_FEATURE_NONE, "none"}, {IRC_FEATURE_TRANSLATION, "trans"}, {IRC_FEATURE_ROTATION, "rot"},
        {IRC_FEATURE_TRANSLATION | IRC_FEATURE_ROTATION, "trans+rot"},
        {IRC_FEATURE_TRANSLATION | IRC_FEATURE_ROTATION | IRC_FEATURE_HESSIAN, "trans+rot+hess"}};
    const size_t nsets = sizeof sets / sizeof sets[0];
    static const uint32_t sizes[] = {100000, 1000000};
    const irc_port *ports[] = {&irc_port_posix, &irc_port_none};
    /* BENCH_ORDER=random|coherent measures one query order only;
     * BENCH_ONLY=placement the placement rows alone. */
    const char *only = getenv("BENCH_ORDER"), *part = getenv("BENCH_ONLY");
    size_t i, k, pi;
    printf("metric,features,records,port,order,value,unit\n");
    if (part && strcmp(part, "placement") == 0) {
        placement();
        return 0;
    }
    for (i = 0; i < nsets; i++) {
        irc_config cfg;
        irc_cache *c;
        irc_stats st;
        double ins;
        memset(&cfg, 0, sizeof cfg);
        cfg.version = IRC_CONFIG_VERSION;
        cfg.trace = no_trace;
        cfg.accuracy = 0.2f;
        cfg.features = sets[i].f;
        c = build(&cfg, 1000, &ins);
        irc_cache_stats(c, &st);
        printf("record_bytes,%s,,,,%zu,bytes\n", sets[i].name, st.record_bytes);
        free(cfg.buffer);
    }
    for (k = 0; k < 2; k++) {
        static const uint32_t strata[2][2] = {{16, 64}, {32, 128}};
        for (i = 0; i < nsets; i++)
            printf("record_us_library,%s,,,%ux%u,%.2f,us\n", sets[i].name, strata[k][0],
                   strata[k][1], record_cost(sets[i].f, strata[k][0], strata[k][1], 0.5));
        printf("record_us_library,sh L=3,,,%ux%u,%.2f,us\n", strata[k][0], strata[k][1],
               record_cost(IRC_FEATURE_SH, strata[k][0], strata[k][1], 0.5));
        printf("record_us_library,sh L=3 + gradient,,,%ux%u,%.2f,us\n", strata[k][0],
               strata[k][1],
               record_cost(IRC_FEATURE_SH | IRC_FEATURE_SH_GRADIENT, strata[k][0], strata[k][1],
                           0.5));
        /* The ratios asked of it: trans + rot gradients over a bare record; an
         * L = 3 SH record with gradients over one without. */
        printf("gradient_cost_over_bare,trans+rot,,,%ux%u,%.3f,x\n", strata[k][0],
               strata[k][1],
               cost_ratio(IRC_FEATURE_NONE, IRC_FEATURE_TRANSLATION | IRC_FEATURE_ROTATION, strata[k][0],
                          strata[k][1]));
        printf("gradient_cost_over_bare,sh L=3,,,%ux%u,%.3f,x\n", strata[k][0], strata[k][1],
               cost_ratio(IRC_FEATURE_SH, IRC_FEATURE_SH | IRC_FEATURE_SH_GRADIENT,
                          strata[k][0], strata[k][1]));
    }
    cornell_rows();
    fflush(stdout);
    for (k = 0; k < 2; k++) {
        for (pi = 0; pi < 2; pi++) {
            irc_config cfg;
            irc_cache *c;
            irc_stats st;
            double ins, hr, rate;
            int coh;
            memset(&cfg, 0, sizeof cfg);
            cfg.version = IRC_CONFIG_VERSION;
            cfg.trace = no_trace;
            cfg.accuracy = 0.2f;
            cfg.features = IRC_FEATURE_TRANSLATION | IRC_FEATURE_ROTATION;
            cfg.port = ports[pi];
            rng = 1;
            c = build(&cfg, sizes[k], &ins);
            if (!c) {
                fprintf(stderr, "build failed\n");
                return 1;
            }
            irc_cache_stats(c, &st);
            if (pi == 0) {
                printf("index_bytes_reserved,trans+rot,%u,,,%.2f,bytes/record\n", sizes[k],
                       (double)st.bytes_index / sizes[k]);
                /* The pool's unused nodes (12 bytes each) taken off. */
                printf("index_bytes_used,trans+rot,%u,,,%.2f,bytes/record\n", sizes[k],
                       ((double)st.bytes_index -
                        (double)(st.index_nodes_max - st.index_nodes) * 12.0) / sizes[k]);
                printf("block_bytes,trans+rot,%u,,,%.2f,bytes/record\n", sizes[k],
                       (double)st.bytes_total / sizes[k]);
                snapshot_rates(c, &cfg, sizes[k]);
            }
            printf("inserts_per_s,trans+rot,%u,%s,,%.0f,1/s\n", sizes[k], ports[pi]->name, ins);
            for (coh = 0; coh < 2; coh++) {
                if (only && strcmp(only, coh ? "coherent" : "random") != 0)
                    continue;
                rate = lookups(c, coh, &hr);
                printf("lookups_per_s,trans+rot,%u,%s,%s,%.0f,1/s\n", sizes[k], ports[pi]->name,
                       coh ? "coherent" : "random", rate);
                printf("lookup_hit_rate,trans+rot,%u,%s,%s,%.3f,\n", sizes[k], ports[pi]->name,
                       coh ? "coherent" : "random", hr);
                if (pi == 0) {
                    /* The same queries from 2 threads at once: the read
                     * path's scaling (target 1.9x on 2 cores). */
                    double two = lookups_n(c, 2, &hr);
                    printf("lookups_2threads_over_1,trans+rot,%u,%s,%s,%.2f,x\n", sizes[k],
                           ports[pi]->name, coh ? "coherent" : "random", two / rate);
                }
            }
            /* An empty fill pass's end lays the records out in the index's
             * order (compact.c); the same lookups again inside a pass,
             * where they take no lock, as a renderer's fill passes do. */
            if (pi == 0) {
                double t0 = bench_now();
                if (irc_pass_begin(c) != IRC_OK || irc_pass_end(c, NULL) != IRC_OK)
                    return 1;
                printf("compact_s,trans+rot,%u,,,%.3f,s\n", sizes[k], bench_now() - t0);
            }
            if (pi == 0 && irc_pass_begin(c) == IRC_OK) {
                for (coh = 0; coh < 2; coh++) {
                    if (only && strcmp(only, coh ? "coherent" : "random") != 0)
                        continue;
                    rate = lookups(c, coh, &hr);
                    printf("lookups_per_s_in_pass,trans+rot,%u,%s,%s,%.0f,1/s\n", sizes[k],
                           ports[pi]->name, coh ? "coherent" : "random", rate);
                    printf("lookups_2threads_over_1_in_pass,trans+rot,%u,%s,%s,%.2f,x\n",
                           sizes[k], ports[pi]->name, coh ? "coherent" : "random",
                           lookups_n(c, 2, &hr) / rate);
                }
                irc_pass_end(c, NULL);
            }
            fflush(stdout);
            free(cfg.buffer);
        }
    }
    placement();
    return 0;
}
