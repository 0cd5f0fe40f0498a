/*
 * select.c -- what a make bench run takes from its environment: which
 * scenes and methods (BENCH_SCENES, BENCH_METHODS) and the settings laid
 * over every cache run (BENCH_SET).
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench.h"

/* Whether NAME is in the comma-separated list in environment variable VAR
 * (unset: everything is). */
int wanted(const char *var, const char *name)
{
    const char *l = getenv(var), *p;
    size_t n = strlen(name);
    if (!l || !*l)
        return 1;
    for (p = l; (p = strstr(p, name)) != NULL; p += n)
        if ((p == l || p[-1] == ',') && (p[n] == ',' || p[n] == 0))
            return 1;
    return 0;
}

int wanted_method(const char *name)
{
    return wanted("BENCH_METHODS", name);
}

/* BENCH_SCENES=sponza names both Sponza views: a scene's name up to its
 * first '-'. */
int wanted_family(const char *name)
{
    char fam[32];
    const char *dash = strchr(name, '-');
    size_t n = dash ? (size_t)(dash - name) : 0;
    if (!n || n >= sizeof fam || !getenv("BENCH_SCENES") || !*getenv("BENCH_SCENES"))
        return 0;
    memcpy(fam, name, n);
    fam[n] = '\0';
    return wanted("BENCH_SCENES", fam);
}

/* BENCH_SET="name=value,...": settings laid over every cache run, for
 * experiments (minpx, maxpx: the pixel bounds, -1 none; guard: 0 or 1;
 * maxr: max_radius, -1 the demo's view rule, 0 the library's; clamp: 0 or
 * 1; free: 1 free fill; blend: cfg.irr.blend; seed: the cache's seed; sm, sn: strata; ss:
 * super-samples; vis: 1 a lookup answered by a record out of sight makes a
 * record instead; fullpx, detail: cfg.irr.full_pixels, detail_pixels; final:
 * render_opts's final_sweep). */
void experiment_opts(render_opts *o)
{
    const char *l = getenv("BENCH_SET");
    while (l && *l) {
        char name[16];
        double v;
        int n = 0;
        if (sscanf(l, "%15[a-z]=%lf%n", name, &v, &n) != 2)
            break;
        if (!strcmp(name, "minpx")) o->min_pixels = (float)v;
        else if (!strcmp(name, "maxpx")) o->max_pixels = (float)v;
        else if (!strcmp(name, "guard")) o->leak_guard = v != 0.0 ? IRC_ON : IRC_OFF;
        else if (!strcmp(name, "maxr")) o->max_radius = (float)v;
        else if (!strcmp(name, "clamp")) o->clamp_neighbours = v != 0.0 ? IRC_ON : IRC_OFF;
        else if (!strcmp(name, "nofp")) o->no_footprint = v != 0.0;
        else if (!strcmp(name, "free")) o->free_fill = v != 0.0;
        else if (!strcmp(name, "ss")) o->supersamples = (uint32_t)v;
        else if (!strcmp(name, "fullpx")) o->full_pixels = (float)v;
        else if (!strcmp(name, "detail")) o->detail_pixels = (float)v;
        else if (!strcmp(name, "blend")) o->blend = (float)v;
        else if (!strcmp(name, "seed")) o->seed = (uint64_t)v;
        else if (!strcmp(name, "final")) o->final_sweep = v != 0.0;
        else if (!strcmp(name, "vis")) o->check_visibility = v != 0.0 ? IRC_ON : IRC_OFF;
        else if (!strcmp(name, "sm")) o->strata_m = (uint32_t)v;
        else if (!strcmp(name, "sn")) o->strata_n = (uint32_t)v;
        else fprintf(stderr, "BENCH_SET: unknown %s\n", name);
        l += n;
        l += *l == ',';
    }
}

int bench_a_list(double *out, int max)
{
    const char *al = getenv("BENCH_A");
    int n;
    if (!al || !*al)
        return 0;
    for (n = 0; n < max && al && sscanf(al, "%lf", &out[n]) == 1; n++)
        if ((al = strchr(al, ',')))
            al++;
    return n;
}
