/*
 * records.c -- one record workload, small enough to profile: K records at
 * random points of the plane z = 0, facing +z, under bench_core.c's cheap
 * host (a sky brightening toward +z, every tenth ray hitting a wall at
 * distance 1), so the library's own work is what a profiler sees.  Prints
 * microseconds a record and the sum of every returned value (%.9g), so
 * that two builds can be checked for the same records.
 *
 *   ./build/bench_records FEATURES K [M N]    FEATURES: bare | trans | rot |
 *                                             both | hess | sh | shgrad
 *
 * Instructions per record: run it under callgrind with K = 0 and K = 1000
 * and divide the difference by 1000 (bench/notes.md, "Speed and memory").  Built
 * with -DBENCH_PRINT_GRADIENTS it prints each irradiance record's
 * gradients, one line a channel, so that two builds can be compared record
 * by record.
 */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "bench_util.h"

static unsigned long long rng = 1;

static double sum_of(const float *v, size_t n)
{
    double s = 0.0;
    size_t i;
    for (i = 0; i < n; i++)
        s += v[i];
    return s;
}

int main(int argc, char **argv)
{
    static const struct { const char *name; uint32_t f; } kinds[] = {
        {"bare", IRC_FEATURE_NONE},
        {"trans", IRC_FEATURE_TRANSLATION},
        {"rot", IRC_FEATURE_ROTATION},
        {"both", IRC_FEATURE_TRANSLATION | IRC_FEATURE_ROTATION},
        {"hess", IRC_FEATURE_TRANSLATION | IRC_FEATURE_ROTATION | IRC_FEATURE_HESSIAN},
        {"sh", IRC_FEATURE_SH},
        {"shgrad", IRC_FEATURE_SH | IRC_FEATURE_SH_GRADIENT},
    };
    irc_config cfg;
    irc_cache *c;
    size_t bytes, k;
    long i, count;
    double t0, t1, sum = 0.0;
    int kind = -1;
    if (argc != 3 && argc != 5) {
        fprintf(stderr, "usage: %s bare|trans|rot|both|hess|sh|shgrad K [M N]\n", argv[0]);
        return 2;
    }
    for (k = 0; k < sizeof kinds / sizeof kinds[0]; k++)
        if (!strcmp(argv[1], kinds[k].name))
            kind = (int)k;
    count = atol(argv[2]);
    if (kind < 0 || count < 0)
        return 2;
    memset(&cfg, 0, sizeof cfg);
    cfg.version = IRC_CONFIG_VERSION;
    cfg.trace = bench_cheap_trace;
    cfg.features = kinds[kind].f;
    cfg.strata_theta = argc == 5 ? (uint32_t)atol(argv[3]) : 16u;
    cfg.strata_phi = argc == 5 ? (uint32_t)atol(argv[4]) : 64u;
    cfg.max_batch = 256;
    cfg.sh.bands = (cfg.features & IRC_FEATURE_SH) ? 3u : 0u;
    if (irc_footprint(&cfg, 16, &bytes) != IRC_OK)
        return 1;
    cfg.buffer = malloc(bytes);
    cfg.buffer_size = bytes;
    if (!cfg.buffer || irc_init(&cfg, 16, &c) != IRC_OK)
        return 1;
    t0 = bench_now();
    for (i = 0; i < count; i++) {
        float p[3] = {(float)bench_xorshift(&rng), (float)bench_xorshift(&rng), 0.0f}, n[3] = {0.0f, 0.0f, 1.0f};
        irc_record r;
        irc_sh sh;
        if (cfg.features & IRC_FEATURE_SH) {
            if (irc_sh_compute(c, p, n, &sh, NULL) != IRC_OK)
                return 1;
            sum += sum_of(&sh.c[0][0], sizeof sh.c / sizeof(float));
            sum += sum_of(&sh.grad[0][0][0], sizeof sh.grad / sizeof(float));
        } else {
            if (irc_record_compute(c, p, n, &r, NULL) != IRC_OK)
                return 1;
#ifdef BENCH_PRINT_GRADIENTS /* to compare two builds record by record */
            {
                int ch;
                for (ch = 0; ch < 3; ch++)
                    printf("t %.9g %.9g %.9g r %.9g %.9g %.9g\n", r.grad_t[ch][0], r.grad_t[ch][1],
                           r.grad_t[ch][2], r.grad_r[ch][0], r.grad_r[ch][1], r.grad_r[ch][2]);
            }
#endif
            sum += sum_of(r.e, 3) + sum_of(&r.grad_t[0][0], 9) +
                   sum_of(&r.grad_r[0][0], 9) + r.radius;
        }
    }
    t1 = bench_now();
    printf("%s %ldx (%ux%u): %.1f us a record, sum %.9g\n", argv[1], count, cfg.strata_theta,
           cfg.strata_phi, count ? 1e6 * (t1 - t0) / (double)count : 0.0, sum);
    free(cfg.buffer);
    return 0;
}
