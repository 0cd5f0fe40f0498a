/*
 * host.c -- the library on a microcontroller: a host with a static block
 * and a callback that answers from a tiny analytic scene, checked against
 * closed forms, with the cost of one record in instructions and the stack
 * every entry point used (board.h).  Built by `make embedded-test` for a
 * Cortex-M4F and run under QEMU (mps2-an386, semihosting); `make
 * embedded-host` builds the same program for the build machine.
 *
 * Scenes (as tests/scenes.c, in float): a sky of radiance 1, open (E = pi
 * on any upward surface, no gradient), and the same sky over a black unit
 * sphere at (0, 0, 2) above the plane z = 0, where E(p) = pi (1 - h/d^3)
 * and its gradient in the plane is 3 pi h (p - C)/d^5 (h = 2, d = |p - C|).
 * Prints one line per check and "N passed, N failed"; exits 0 when all
 * passed.
 */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "board.h"
#include "irrcache.h"

#define PI 3.14159265358979

static int sphere_on; /* the scene: 0 the open sky, 1 the sky over the sphere */
static int passed, failed;
static uint64_t in_trace; /* instructions spent in the callback: the host's */

static int trace(const irc_trace_args *a)
{
    const uint64_t t0 = board_instructions();
    uint32_t i;
    for (i = 0; i < a->count; i++) {
        const float *o = a->rays[i].org, *d = a->rays[i].dir;
        irc_hit *h = &a->hits[i];
        float oc[3], b, c, disc, t = -1.0f;
        int k;
        oc[0] = o[0];
        oc[1] = o[1];
        oc[2] = o[2] - 2.0f;
        b = oc[0] * d[0] + oc[1] * d[1] + oc[2] * d[2];
        c = oc[0] * oc[0] + oc[1] * oc[1] + oc[2] * oc[2] - 1.0f;
        disc = b * b - c;
        if (sphere_on && disc > 0.0f)
            t = -b - sqrtf(disc);
        if (t > 0.0f) {
            h->status = IRC_RAY_HIT;
            h->dist = t;
            for (k = 0; k < 3; k++) {
                h->normal[k] = oc[k] + t * d[k];
                h->radiance[k] = 0.0f;
            }
        } else {
            h->status = IRC_RAY_ESCAPED;
            h->radiance[0] = h->radiance[1] = h->radiance[2] = 1.0f;
        }
    }
    in_trace += board_instructions() - t0;
    return 0;
}

static void check(int ok, const char *what, double got, double want)
{
    printf("%s %-44s %.6f (want %.6f)\n", ok ? "ok  " : "FAIL", what, got, want);
    if (ok)
        passed++;
    else
        failed++;
}

/* The blocks: records of 72 bytes and an index of 160 bytes a record
 * (8 references and 2 nodes), a scratch slot, the strata table; SH records
 * of 464 bytes.  Sized by irc_footprint at run time against these
 * arrays. */
static unsigned char irr_block[144 * 1024], sh_block[144 * 1024];
static irc_sh sh_out;

/* 16 x 64 strata, rays in batches of 64, the single-threaded port; an
 * open sky's records get the largest radius the scene needs. */
static void settings(irc_config *cfg, uint32_t features)
{
    memset(cfg, 0, sizeof *cfg);
    cfg->version = IRC_CONFIG_VERSION;
    cfg->trace = trace;
    cfg->max_batch = 64;
    cfg->features = features;
    cfg->strata_theta = 16;
    cfg->strata_phi = 64;
    cfg->max_radius = 4.0f;
    cfg->port = &irc_port_none;
}

static irc_cache *make(irc_config *cfg, unsigned char *block, size_t size, uint32_t records)
{
    irc_cache *c = NULL;
    size_t need = 0;
    int st = irc_footprint(cfg, records, &need);
    if (st < 0 || need > size) {
        printf("FAIL footprint %s, %u bytes for %u records\n", irc_strerror(st),
               (unsigned)need, (unsigned)records);
        failed++;
        return NULL;
    }
    cfg->buffer = block;
    cfg->buffer_size = size;
    if ((st = irc_init(cfg, records, &c)) < 0) {
        printf("FAIL init: %s\n", irc_strerror(st));
        failed++;
        return NULL;
    }
    printf("     block: %u bytes for %u records\n", (unsigned)need, (unsigned)records);
    return c;
}

/* E at p = (1, 1, 0) under the sphere, and its translational gradient
 * against the closed form (32 x 128 strata: within 1% and 15%, as
 * tests/t_record.c's test_sphere_over_plane). */
static void sphere_checks(irc_cache *c)
{
    const float p[3] = {1.0f, 1.0f, 0.0f}, n[3] = {0.0f, 0.0f, 1.0f};
    double d = sqrt(1.0 + 1.0 + 4.0), e = PI * (1.0 - 2.0 / (d * d * d)),
           k = 3.0 * PI * 2.0 / pow(d, 5.0), gx = k * 1.0, gy = k * 1.0, err;
    irc_record r;
    int st;
    sphere_on = 1;
    st = irc_record_compute(c, p, n, &r, NULL);
    check(st == IRC_OK && fabs(r.e[0] - e) < 0.01 * e, "sphere: E within 1%", r.e[0], e);
    err = sqrt(pow(r.grad_t[0][0] - gx, 2) + pow(r.grad_t[0][1] - gy, 2)) / sqrt(gx * gx + gy * gy);
    check(st == IRC_OK && err < 0.15, "sphere: |grad E - exact|/|exact| below 0.15", err, 0.0);
}

static void irradiance(void)
{
    irc_config cfg;
    irc_cache *c;
    irc_record r;
    const float p[3] = {0.0f, 0.0f, 0.0f}, n[3] = {0.0f, 0.0f, 1.0f}, q[3] = {0.01f, 0.0f, 0.0f};
    float rgb[3], w;
    uint64_t t0, t1;
    int st;
    settings(&cfg, IRC_FEATURE_TRANSLATION | IRC_FEATURE_ROTATION);
    if (!(c = make(&cfg, irr_block, sizeof irr_block, 64)))
        return;
    sphere_on = 0;
    board_stack_paint(16384);
    in_trace = 0;
    t0 = board_instructions();
    st = irc_record_compute(c, p, n, &r, NULL);
    t1 = board_instructions();
    printf("     stack irc_record_compute: %u bytes\n", (unsigned)board_stack_used());
    check(st == IRC_OK && fabs(r.e[0] - PI) < 1e-5, "open sky: E = pi", r.e[0], PI);
    check(st == IRC_OK && fabs(r.grad_t[0][0]) + fabs(r.grad_t[0][1]) < 1e-4,
          "open sky: no translational gradient", r.grad_t[0][0], 0.0);
    printf("     one 16x64 record, trans + rot: %lu instructions, %lu in the callback;"
           " the library's %lu a ray\n", (unsigned long)(t1 - t0), (unsigned long)in_trace,
           (unsigned long)((t1 - t0 - in_trace) / (16u * 64u)));
    board_stack_paint(16384);
    st = irc_cache_lookup_or_compute(c, p, n, rgb, &w, NULL);
    printf("     stack irc_cache_lookup_or_compute: %u bytes\n", (unsigned)board_stack_used());
    board_stack_paint(16384);
    t0 = board_instructions();
    st = irc_cache_lookup(c, q, n, rgb, &w);
    t1 = board_instructions();
    printf("     stack irc_cache_lookup: %u bytes\n", (unsigned)board_stack_used());
    printf("     one lookup, one record in reach: %lu instructions\n", (unsigned long)(t1 - t0));
    check(st == IRC_OK && fabs(rgb[0] - PI) < 1e-4, "lookup beside the record", rgb[0], PI);
    irc_fini(c);
    cfg.strata_theta = 32;
    cfg.strata_phi = 128;
    if (!(c = make(&cfg, irr_block, sizeof irr_block, 16)))
        return;
    sphere_checks(c);
    irc_fini(c);
}

/* Lookups among 1,000 records of random radii on a 10 x 10 square (no
 * ray cast): the instructions a lookup takes once the octree has depth,
 * and the share the index's double arithmetic keeps (docs/PORTING.md, "Embedded").
 * Every answer is checked against the one value all records hold. */
static unsigned char many_block[256 * 1024];
#ifndef HOST_LOOKUPS
#define HOST_LOOKUPS 1000 /* embedded/profile.sh: LOOKUPS=0 for the inserts alone */
#endif

static float unit_rand(uint32_t *st)
{
    *st = *st * 1664525u + 1013904223u;
    return (float)(*st >> 8) * (1.0f / 16777216.0f);
}

static void many(void)
{
    enum { RECORDS = 1000, LOOKUPS = HOST_LOOKUPS };
    irc_config cfg;
    irc_cache *c;
    irc_record r;
    uint32_t st = 12345u;
    uint64_t t0, t1;
    float rgb[3], w;
    int i, bad = 0, hits = 0;
    settings(&cfg, IRC_FEATURE_TRANSLATION | IRC_FEATURE_ROTATION);
    /* random overlapping disks keep the radii given (clamping would
     * shrink them until most lookups miss): the lookup cost as before */
    cfg.clamp_neighbours = IRC_OFF;
    if (!(c = make(&cfg, many_block, sizeof many_block, RECORDS)))
        return;
    for (i = 0; i < RECORDS; i++) {
        memset(&r, 0, sizeof r);
        r.p[0] = 10.0f * unit_rand(&st);
        r.p[1] = 10.0f * unit_rand(&st);
        r.n[2] = 1.0f;
        r.e[0] = r.e[1] = r.e[2] = 2.0f;
        r.radius = 0.3f + unit_rand(&st);
        r.features = cfg.features;
        bad += irc_cache_insert(c, &r) != IRC_OK;
    }
    t0 = board_instructions();
    for (i = 0; i < LOOKUPS; i++) {
        const float p[3] = {10.0f * unit_rand(&st), 10.0f * unit_rand(&st), 0.0f},
                    n[3] = {0.0f, 0.0f, 1.0f};
        const int got = irc_cache_lookup(c, p, n, rgb, &w);
        hits += got == IRC_OK;
        bad += got == IRC_OK ? fabs(rgb[0] - 2.0) > 1e-5 : got != IRC_MISS;
    }
    t1 = board_instructions();
    printf("     %d lookups among %d records, %d answered: %lu instructions a lookup\n", LOOKUPS,
           RECORDS, hits, (unsigned long)((t1 - t0) / (LOOKUPS ? LOOKUPS : 1)));
    check(bad == 0 && (hits > LOOKUPS / 2 || LOOKUPS == 0), "lookups among 1000 records: every answer 2", 0.0, 0.0);
    irc_fini(c);
}

/* An L = 3 SH record with gradients under the open sky: its irradiance
 * about n is pi. */
static void sh(void)
{
    irc_config cfg;
    irc_cache *c;
    const float p[3] = {0.0f, 0.0f, 0.0f}, n[3] = {0.0f, 0.0f, 1.0f};
    float rgb[3], w;
    int st;
    settings(&cfg, IRC_FEATURE_SH | IRC_FEATURE_SH_GRADIENT);
    if (!(c = make(&cfg, sh_block, sizeof sh_block, 64)))
        return;
    sphere_on = 0;
    board_stack_paint(16384);
    st = irc_sh_lookup_or_compute(c, p, n, &sh_out, &w, NULL);
    printf("     stack irc_sh_lookup_or_compute: %u bytes\n", (unsigned)board_stack_used());
    board_stack_paint(16384);
    if (st >= 0)
        st = irc_sh_irradiance(&sh_out, n, rgb);
    printf("     stack irc_sh_irradiance: %u bytes\n", (unsigned)board_stack_used());
    check(st == IRC_OK && fabs(rgb[0] - PI) < 0.01 * PI, "SH L = 3, open sky: E within 1%",
          rgb[0], PI);
    irc_fini(c);
}

int main(void)
{
#ifdef HOST_PART /* embedded/profile.sh runs one part */
    if (HOST_PART == 1) irradiance();
    if (HOST_PART == 2) many();
    if (HOST_PART == 3) sh();
#else
    irradiance();
    many();
    sh();
#endif
    printf("%d passed, %d failed\n", passed, failed);
    return failed != 0;
}
