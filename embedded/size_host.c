/*
 * size_host.c -- the smallest hosts `make size` links to see what the
 * library costs in a firmware image: irradiance records with translational
 * and rotational gradients (the default), or SH records with gradients
 * (-DSIZE_SH).  Linked with --gc-sections, only what these calls reach
 * stays.  Built for the build machine with -DSIZE_PRINT it prints the
 * block bytes a record costs for each feature set instead.
 */
#include <stdio.h>
#include <string.h>

#include "irrcache.h"

static int trace(const irc_trace_args *a)
{
    uint32_t i;
    for (i = 0; i < a->count; i++) {
        a->hits[i].status = IRC_RAY_ESCAPED;
        a->hits[i].radiance[0] = a->hits[i].radiance[1] = a->hits[i].radiance[2] = 1.0f;
    }
    return 0;
}

#ifdef SIZE_PRINT
/* The bytes one more record adds to the block (footprint at 2000 records
 * minus at 1000, over 1000): record, index entry and its share of nodes. */
static void per_record(const char *name, uint32_t features)
{
    irc_config cfg;
    size_t a = 0, b = 0;
    memset(&cfg, 0, sizeof cfg);
    cfg.version = IRC_CONFIG_VERSION;
    cfg.trace = trace;
    cfg.features = features;
    irc_footprint(&cfg, 1000, &a);
    irc_footprint(&cfg, 2000, &b);
    printf("  %-34s %7.2f\n", name, (double)(b - a) / 1000.0);
}

int main(void)
{
    printf("  block bytes a record (%u-bit size_t)\n", (unsigned)(8 * sizeof(size_t)));
    per_record("bare", IRC_FEATURE_NONE);
    per_record("trans", IRC_FEATURE_TRANSLATION);
    per_record("trans + rot", IRC_FEATURE_TRANSLATION | IRC_FEATURE_ROTATION);
    per_record("trans + rot + Hessian",
               IRC_FEATURE_TRANSLATION | IRC_FEATURE_ROTATION | IRC_FEATURE_HESSIAN);
    per_record("SH L = 3", IRC_FEATURE_SH);
    per_record("SH L = 3 + gradient", IRC_FEATURE_SH | IRC_FEATURE_SH_GRADIENT);
    return 0;
}
#else
static unsigned char block[64 * 1024];
#ifdef SIZE_SH
static irc_sh out;
#endif

int main(void)
{
    irc_config cfg;
    irc_cache *c;
    const float p[3] = {0, 0, 0}, n[3] = {0, 0, 1};
    float w = 0.0f;
    memset(&cfg, 0, sizeof cfg);
    cfg.version = IRC_CONFIG_VERSION;
    cfg.trace = trace;
    cfg.buffer = block;
    cfg.buffer_size = sizeof block;
    cfg.port = &irc_port_none;
#ifdef SIZE_SH
    cfg.features = IRC_FEATURE_SH | IRC_FEATURE_SH_GRADIENT;
    if (irc_init(&cfg, 16, &c) < 0 || irc_sh_lookup_or_compute(c, p, n, &out, &w, NULL) < 0 ||
        irc_sh_lookup(c, p, n, &out, &w) < 0 || irc_sh_irradiance(&out, n, out.e) < 0)
        return 1;
#else
    float rgb[3];
    cfg.features = IRC_FEATURE_TRANSLATION | IRC_FEATURE_ROTATION;
    if (irc_init(&cfg, 16, &c) < 0 || irc_cache_lookup_or_compute(c, p, n, rgb, &w, NULL) < 0 ||
        irc_cache_lookup(c, p, n, rgb, &w) < 0)
        return 1;
#endif
    return irc_fini(c) < 0 || w < 0.0f;
}
#endif
