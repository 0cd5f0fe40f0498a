/*
 * reach.c -- how many pixels a cache render's records serve (bench/notes.md,
 * "Where the records go").  Renders SCENE's indirect term at WxH, one
 * thread, the demo's defaults at a (strata MxN, 0x0 the library's), then
 * reads every record back and prints the distribution of its reach a R in
 * pixels (R over the pinhole footprint at the record's point, from
 * irc_pixel_footprint), and for every STEP-th record the radius a record
 * made afresh at the same point would get on its own: the split sphere and
 * the gradient bound before neighbour clamping shrank it.
 *   reach SCENE WxH a [MxN] [--no-clamp] [--blend B] [--step STEP]
 */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "render.h"

#define PI 3.14159265358979323846

static int cmp_float(const void *a, const void *b)
{
    const float x = *(const float *)a, y = *(const float *)b;
    return x < y ? -1 : x > y;
}

static void print_quantiles(const char *what, float *v, size_t n)
{
    static const double q[] = {0.1, 0.25, 0.5, 0.75, 0.9};
    size_t i;
    if (!n)
        return;
    qsort(v, n, sizeof *v, cmp_float);
    printf("%-40s", what);
    for (i = 0; i < sizeof q / sizeof q[0]; i++)
        printf(" q%02d %7.2f", (int)(q[i] * 100.0 + 0.5), v[(size_t)(q[i] * (double)(n - 1))]);
    printf("\n");
}

static int parse_args(int argc, char **argv, scene *s, render_opts *o, int *step)
{
    int i, w, h;
    unsigned m = 0, n = 0;
    char err[256];
    if (argc < 4 || sscanf(argv[2], "%dx%d", &w, &h) != 2 || w < 1 || h < 1) {
        fprintf(stderr, "usage: reach SCENE WxH a [MxN] [--no-clamp] [--blend B] [--step S]\n");
        return -1;
    }
    if (scene_load(argv[1], s, err, sizeof err) < 0) {
        fprintf(stderr, "reach: %s\n", err);
        return -1;
    }
    s->cam.width = w;
    s->cam.height = h;
    render_opts_defaults(o);
    o->accuracy = (float)atof(argv[3]);
    o->threads = 1;
    o->show = SHOW_INDIRECT;
    for (i = 4; i < argc; i++) {
        if (!strcmp(argv[i], "--no-clamp"))
            o->clamp_neighbours = IRC_OFF;
        else if (!strcmp(argv[i], "--blend") && i + 1 < argc)
            o->blend = (float)atof(argv[++i]);
        else if (!strcmp(argv[i], "--step") && i + 1 < argc)
            *step = atoi(argv[++i]);
        else if (sscanf(argv[i], "%ux%u", &m, &n) == 2) {
            o->strata_m = m;
            o->strata_n = n;
        }
    }
    if (*step < 1)
        *step = 1;
    return 0;
}

int main(int argc, char **argv)
{
    scene s;
    renderer r;
    render_opts o;
    render_stats st;
    irc_stats cs;
    char err[256];
    float *img, *reach, *fresh, fwd[3], angle;
    size_t nr = 0, nf = 0, under1 = 0, clamped = 0;
    uint32_t id;
    int step = 20, i;
    if (parse_args(argc, argv, &s, &o, &step) < 0)
        return 2;
    if (renderer_init(&r, &s, &o, err, sizeof err) < 0) {
        fprintf(stderr, "reach: %s\n", err);
        return 1;
    }
    img = malloc((size_t)s.cam.width * s.cam.height * 3 * sizeof *img);
    if (!img || render_image(&r, img, &st) < 0 || irc_cache_stats(r.cache, &cs) != IRC_OK)
        return 1;
    reach = malloc((size_t)cs.records * sizeof *reach + 1);
    fresh = malloc((size_t)cs.records * sizeof *fresh + 1);
    if (!reach || !fresh)
        return 1;
    angle = (float)(2.0 * tan(s.cam.fov_deg * PI / 360.0) / s.cam.height);
    for (i = 0; i < 3; i++)
        fwd[i] = s.cam.look[i] - s.cam.eye[i];
    for (id = 0; id < cs.capacity && nr < cs.records; id++) {
        irc_record rec, own;
        float fp;
        if (irc_cache_record(r.cache, id, &rec) != IRC_OK ||
            irc_pixel_footprint(s.cam.eye, fwd, angle, rec.p, rec.n, &fp) != IRC_OK || !(fp > 0.0f))
            continue;
        reach[nr] = o.accuracy * rec.radius / fp;
        under1 += reach[nr] < 1.0f;
        if (nr++ % (size_t)step == 0 && render_record(&r, rec.p, rec.n, &own) == IRC_OK) {
            /* The _px call's pixel bounds hold a fresh record too. */
            float own_reach = o.accuracy * own.radius / fp;
            if (own_reach > 15.0f)
                own_reach = 15.0f;
            fresh[nf++] = own_reach;
            clamped += own_reach > 1.5f * reach[nr - 1];
        }
    }
    printf("%s at %dx%d, a %g: %llu records for %d pixels (%.2f a pixel), %llu detail "
           "estimates, %.1f CPU s\n",
           argv[1], s.cam.width, s.cam.height, (double)o.accuracy, (unsigned long long)cs.records,
           s.cam.width * s.cam.height, (double)cs.records / (s.cam.width * s.cam.height),
           (unsigned long long)cs.details, st.cpu);
    printf("records reaching less than one pixel: %.1f%%\n", nr ? 100.0 * under1 / nr : 0.0);
    print_quantiles("reach a R in pixels, as stored", reach, nr);
    print_quantiles("the same records made afresh (1 in step)", fresh, nf);
    printf("made afresh, more than 1.5x the stored reach (clamped by neighbours): %.1f%%\n",
           nf ? 100.0 * clamped / nf : 0.0);
    free(reach);
    free(fresh);
    free(img);
    renderer_free(&r);
    scene_free(&s);
    return 0;
}
