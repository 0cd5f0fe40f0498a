/*
 * fingerprint.c -- one 64-bit hash a config of what the library computes
 * (make fingerprint): records, lookups, snapshot bytes and counters over
 * fills of an analytic scene in several configs (defaults, bare records,
 * Hessian ellipses with the leak guard, visibility gradients with batches,
 * fill passes and a merge, SH records with gradients).  A change meant to
 * move no number (a refactor) must print the same lines before and after
 * on one compiler and machine; the hashes are not portable across
 * compilers or flags, so no test pins them.
 */
#define IRC_EXPERIMENTAL /* irc_cache_lookup_gradient (irrcache.h) */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "irrcache.h"
#include "scenes.h"

typedef struct fp {
    unsigned long long h;
} fp;

static void eat(fp *f, const void *p, size_t n)
{
    const unsigned char *b = (const unsigned char *)p;
    size_t i;
    for (i = 0; i < n; i++) {
        f->h ^= b[i];
        f->h *= 1099511628211ull; /* FNV-1a, 64 bit */
    }
}

static unsigned rnd_state = 12345u;
static float rnd(void)
{
    rnd_state = rnd_state * 1664525u + 1013904223u;
    return (float)(rnd_state >> 8) / 16777216.0f;
}

/* A point above the plane, a normal tilted up to ~4 degrees from +z. */
static void point(float p[3], float n[3])
{
    p[0] = 1.5f * rnd() - 0.75f;
    p[1] = 1.5f * rnd() - 0.75f;
    p[2] = 0.05f + 0.1f * rnd();
    n[0] = 0.1f * rnd() - 0.05f;
    n[1] = 0.1f * rnd() - 0.05f;
    n[2] = 1.0f;
}

static irc_cache *make(irc_config *cfg, uint32_t records)
{
    size_t bytes;
    irc_cache *c = NULL;
    if (irc_footprint(cfg, records, &bytes) != IRC_OK)
        return NULL;
    cfg->buffer = calloc(1, bytes);
    cfg->buffer_size = bytes;
    if (!cfg->buffer || irc_init(cfg, records, &c) != IRC_OK)
        return NULL;
    return c;
}

static void eat_snapshot(fp *f, irc_cache *c)
{
    size_t n = 0, w = 0;
    void *b;
    if (irc_snapshot_size(c, &n) != IRC_OK || !(b = malloc(n)))
        return;
    if (irc_snapshot_write(c, 7u, b, n, NULL, NULL, &w) == IRC_OK)
        eat(f, b, w);
    free(b);
}

/* The block's total bytes are printed apart, not hashed: a change of the
 * block's layout alone moves that column and no hash. */
static unsigned long long eat_stats(fp *f, irc_cache *c, unsigned long long *bytes)
{
    irc_stats s;
    memset(&s, 0, sizeof s);
    irc_cache_stats(c, &s);
    *bytes = (unsigned long long)s.bytes_total;
    s.bytes_total = 0;
    eat(f, &s, sizeof s);
    return (unsigned long long)s.records;
}

/* Fill with n lookup-or-compute calls (every third with a footprint),
 * then look up m points. */
static void drive_irr(fp *f, irc_cache *c, int n, int m, int passes)
{
    float p[3], nn[3], rgb[3], w;
    int i, st;
    uint32_t added = 0;
    for (i = 0; i < n; i++) {
        if (passes && i % 50 == 0)
            irc_pass_begin(c);
        point(p, nn);
        st = i % 3 ? irc_cache_lookup_or_compute(c, p, nn, rgb, &w, NULL)
                   : irc_cache_lookup_or_compute_px(c, p, nn, NULL, 0.004f, rgb, &w, NULL);
        eat(f, &st, sizeof st);
        eat(f, rgb, sizeof rgb);
        eat(f, &w, sizeof w);
        if (passes && i % 50 == 49) {
            irc_pass_end(c, &added);
            eat(f, &added, sizeof added);
        }
    }
    for (i = 0; i < m; i++) {
        irc_gradient g;
        point(p, nn);
        st = irc_cache_lookup(c, p, nn, rgb, &w);
        eat(f, &st, sizeof st);
        eat(f, rgb, sizeof rgb);
        eat(f, &w, sizeof w);
        st = irc_cache_lookup_gradient(c, p, nn, rgb, &g, &w);
        eat(f, &st, sizeof st);
        eat(f, &g, sizeof g);
    }
}

static void drive_sh(fp *f, irc_cache *c, int n, int m)
{
    float p[3], nn[3], w, rgb[3];
    irc_sh sh;
    int i, st;
    for (i = 0; i < n + m; i++) {
        point(p, nn);
        memset(&sh, 0, sizeof sh);
        st = i < n ? irc_sh_lookup_or_compute(c, p, nn, &sh, &w, NULL)
                   : irc_sh_lookup(c, p, nn, &sh, &w);
        eat(f, &st, sizeof st);
        eat(f, &sh, sizeof sh);
        eat(f, &w, sizeof w);
        if (st >= 0 && irc_sh_irradiance(&sh, nn, rgb) == IRC_OK)
            eat(f, rgb, sizeof rgb);
    }
}

static tscene scene;

static irc_config base(uint32_t features)
{
    irc_config cfg;
    memset(&cfg, 0, sizeof cfg);
    cfg.version = IRC_CONFIG_VERSION;
    cfg.trace = scene_trace;
    cfg.context = &scene;
    cfg.features = features;
    cfg.strata_theta = 8;
    cfg.strata_phi = 24;
    return cfg;
}

static int run(const char *name, irc_config cfg, int sh, int passes)
{
    fp f = {14695981039346656037ull};
    irc_cache *c;
    void *block;
    unsigned long long records, block_bytes;
    rnd_state = 12345u;
    if (!(c = make(&cfg, 3000))) {
        printf("%-22s  could not make the cache\n", name);
        return 1;
    }
    block = cfg.buffer;
    if (sh)
        drive_sh(&f, c, 400, 400);
    else
        drive_irr(&f, c, 600, 600, passes);
    records = eat_stats(&f, c, &block_bytes);
    eat_snapshot(&f, c);
    if (passes) {
        /* the snapshot merged into a second cache that has records of its own */
        irc_config c2 = cfg;
        irc_cache *d;
        size_t bytes = 0, wrote = 0;
        void *snap;
        if ((d = make(&c2, 3000)) != NULL) {
            drive_irr(&f, d, 100, 0, 0);
            irc_snapshot_size(c, &bytes);
            if ((snap = malloc(bytes)) != NULL) {
                irc_snapshot_write(c, 7u, snap, bytes, NULL, NULL, &wrote);
                int st = irc_merge(d, 7u, snap, wrote);
                eat(&f, &st, sizeof st);
                free(snap);
            }
            drive_irr(&f, d, 0, 300, 0);
            eat_snapshot(&f, d);
            irc_fini(d);
            free(c2.buffer);
        }
    }
    irc_fini(c);
    free(block);
    printf("%-22s  %016llx  (%llu records; block %llu bytes)\n", name, f.h, records, block_bytes);
    return 0;
}

int main(void)
{
    irc_config cfg;
    int bad = 0;
    scene_sphere_plane(&scene);
    scene.has_plane = 1;
    scene.plane_l[0] = 0.3f;
    scene.plane_l[1] = 0.2f;
    scene.plane_l[2] = 0.1f;
    scene.plane_z = -0.001;
    scene.lobe_l[0] = scene.lobe_l[1] = 2.0f;
    scene.lobe_dir[0] = 0.6;
    scene.lobe_dir[2] = 0.8;
    scene.lobe_k = 8.0;

    bad |= run("defaults", base(0), 0, 0);
    bad |= run("bare", base(IRC_FEATURE_NONE), 0, 0);
    cfg = base(IRC_FEATURE_TRANSLATION | IRC_FEATURE_ROTATION | IRC_FEATURE_HESSIAN);
    cfg.irr.leak_guard = IRC_ON;
    cfg.evict = IRC_EVICT_CLOCK;
    bad |= run("hessian-guard-clock", cfg, 0, 0);
    cfg = base(IRC_FEATURE_TRANSLATION | IRC_FEATURE_ROTATION | IRC_FEATURE_VISIBILITY);
    cfg.max_batch = 16;
    bad |= run("visibility-batch", cfg, 0, 0);
    bad |= run("passes-merge", base(0), 0, 1);
    cfg = base(IRC_FEATURE_SH | IRC_FEATURE_SH_GRADIENT);
    cfg.strata_theta = 8;
    cfg.strata_phi = 16;
    bad |= run("sh-gradient", cfg, 1, 0);
    return bad;
}
