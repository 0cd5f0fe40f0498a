/* switches.c -- the library built with every IRC_NO_* switch (src/util.h:
 * SH, VISIBILITY, HESSIAN, SIGHT, SUPERSAMPLE, GUARD): what is left out is
 * refused with IRC_ERR_UNSUPPORTED, what is left in works, and a zeroed
 * config gets the defaults this build has.  Built and run by make test
 * (tests/run.sh, stage 1) against a library built with the switches;
 * prints "N passed, N failed". */
#define IRC_EXPERIMENTAL /* irc_occlusion_compute, irc_sh_radiance */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "irrcache.h"
#include "block/cache.h" /* a block header poked on purpose: as a full build writes it */

static int passed, failed;

static void check(int ok, const char *what)
{
    printf("%s %s\n", ok ? "ok  " : "FAIL", what);
    if (ok)
        passed++;
    else
        failed++;
}

/* An open sky of radiance 1: E = pi on any upward surface. */
static int sky(const irc_trace_args *a)
{
    uint32_t i;
    for (i = 0; i < a->count; i++) {
        a->hits[i].status = IRC_RAY_ESCAPED;
        a->hits[i].radiance[0] = a->hits[i].radiance[1] = a->hits[i].radiance[2] = 1.0f;
    }
    return 0;
}

static irc_config config(uint32_t features)
{
    irc_config cfg;
    memset(&cfg, 0, sizeof cfg);
    cfg.version = IRC_CONFIG_VERSION;
    cfg.trace = sky;
    cfg.features = features;
    cfg.strata_theta = 8;
    cfg.strata_phi = 16;
    cfg.max_radius = 1.0f;
    cfg.port = &irc_port_none;
    return cfg;
}

int main(void)
{
    static const uint32_t out[] = {IRC_FEATURE_SH, IRC_FEATURE_SH | IRC_FEATURE_SH_GRADIENT,
                                   IRC_FEATURE_VISIBILITY, IRC_FEATURE_HESSIAN};
    const float p[3] = {0, 0, 0}, n[3] = {0, 0, 1};
    irc_config cfg;
    irc_cache *c = NULL;
    irc_record r;
    irc_sh sh;
    irc_occlusion occ;
    size_t need = 0;
    float rgb[3], w;
    unsigned i;
    void *block;
    for (i = 0; i < sizeof out / sizeof out[0]; i++) {
        cfg = config(out[i]);
        check(irc_footprint(&cfg, 16, &need) == IRC_ERR_UNSUPPORTED,
              "footprint refuses a feature left out");
    }
    cfg = config(0);
    cfg.check_visibility = IRC_ON;
    check(irc_footprint(&cfg, 16, &need) == IRC_ERR_UNSUPPORTED, "confirming rays asked for");
    cfg = config(0);
    cfg.irr.supersamples = 4;
    check(irc_footprint(&cfg, 16, &need) == IRC_ERR_UNSUPPORTED, "super-samples asked for");
    cfg = config(0);
    cfg.irr.leak_guard = IRC_ON;
    check(irc_footprint(&cfg, 16, &need) == IRC_ERR_UNSUPPORTED, "a leak guard asked for");
    cfg = config(0);
    cfg.check_visibility = IRC_OFF;
    cfg.irr.leak_guard = IRC_OFF;
    check(irc_footprint(&cfg, 16, &need) == IRC_OK, "the three asked off");
    /* A zeroed config: trans + rot, neighbour clamping, no confirming rays. */
    cfg = config(0);
    check(irc_footprint(&cfg, 16, &need) == IRC_OK, "footprint: the defaults");
    block = malloc(need);
    cfg.buffer = block;
    cfg.buffer_size = need;
    check(block && irc_init(&cfg, 16, &c) == IRC_OK, "init: trans + rot");
    if (!c)
        return 1;
    check(irc_record_compute(c, p, n, &r, NULL) == IRC_OK && fabsf(r.e[0] - 3.14159265f) < 1e-5f &&
              r.features == (IRC_FEATURE_TRANSLATION | IRC_FEATURE_ROTATION) && r.leak_guard == 0,
          "a record under the open sky: E = pi, both gradients, no guard");
    check(irc_cache_insert(c, &r) == IRC_OK &&
              irc_cache_lookup(c, p, n, rgb, &w) == IRC_OK && fabsf(rgb[0] - r.e[0]) < 1e-6f,
          "insert and lookup");
    {
        irc_stats st;
        float q[3] = {0.05f, 0.0f, 0.0f};
        check(irc_cache_lookup_or_compute(c, q, n, rgb, &w, NULL) == IRC_OK &&
                  fabsf(rgb[0] - 3.14159265f) < 1e-5f && irc_cache_stats(c, &st) == IRC_OK &&
                  st.rays == 128u && st.computes == 1u,
              "lookup or compute: the record answers, no ray cast to confirm it");
    }
    check(irc_sh_compute(c, p, n, &sh, NULL) == IRC_ERR_UNSUPPORTED &&
              irc_sh_lookup(c, p, n, &sh, &w) == IRC_ERR_UNSUPPORTED &&
              irc_sh_lookup_or_compute(c, p, n, &sh, &w, NULL) == IRC_ERR_UNSUPPORTED &&
              irc_sh_insert(c, &sh) == IRC_ERR_UNSUPPORTED &&
              irc_sh_record(c, 0, &sh) == IRC_ERR_UNSUPPORTED &&
              irc_sh_irradiance(&sh, n, rgb) == IRC_ERR_UNSUPPORTED &&
              irc_sh_glossy(&sh, n, 8.0f, rgb) == IRC_ERR_UNSUPPORTED &&
              irc_sh_radiance(&sh, n, rgb) == IRC_ERR_UNSUPPORTED,
          "the SH calls: IRC_ERR_UNSUPPORTED");
    check(irc_sh_lookup(NULL, p, n, &sh, &w) == IRC_ERR_NULL, "an SH call on NULL: IRC_ERR_NULL");
    check(irc_occlusion_compute(c, p, n, &occ, NULL) == IRC_ERR_UNSUPPORTED,
          "occlusion: IRC_ERR_UNSUPPORTED");
    {
        /* The block as a full build would have made it, with confirming
         * rays or a leak guard: this build names it unsupported, and
         * leaves it as it was. */
        irc_cache *d = NULL;
        unsigned char *copy = malloc(need);
        int st1, st2;
        memcpy(copy, block, need);
        c->cfg.check_visibility = 1;
        st1 = irc_attach(&cfg, &d);
        c->cfg.check_visibility = 0;
        c->cfg.irr.leak_guard = 1;
        st2 = irc_attach(&cfg, &d);
        c->cfg.irr.leak_guard = 0;
        check(st1 == IRC_ERR_UNSUPPORTED && st2 == IRC_ERR_UNSUPPORTED && d == NULL &&
                  memcmp(copy, block, need) == 0,
              "attach: a block with what this build leaves out is unsupported, left whole");
        check(irc_attach(&cfg, &d) == IRC_OK && d != NULL, "attach: the block as it was");
        c = d ? d : c;
        free(copy);
    }
    irc_fini(c);
    free(block);
    printf("%d passed, %d failed\n", passed, failed);
    return failed != 0;
}
