/*
 * probes.c -- why a view's pixels become per-pixel estimates (bench/notes.md,
 * "Rays under the surface").  For every camera hit of SCENE at WxH it casts
 * the eight detail probes the _px call casts (60 degrees from the normal,
 * 45 degrees apart; src/irr/detail.c) around the normal the demo passes,
 * and counts the points whose nearest probe hit lies within D pixels'
 * footprint (cfg.irr.detail_pixels, default 0.5): those the library answers
 * per pixel.  Of them it counts those with a probe leaving below the
 * geometric surface, those whose shading normal is more than 30 degrees off
 * the geometric one, and the nearest hits' distances in pixels.  With
 * --fail-under the probes below the geometric surface are not cast, as the
 * demo's callback now answers them (demo/bounce.h, tstate.under).
 *   probes SCENE WxH [D] [--fail-under]
 */
#define _POSIX_C_SOURCE 200809L
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bvh.h"
#include "camera.h"
#include "render.h"
#include "shade.h"

typedef struct tally {
    long pixels, detail, below, tilted, hist[8];
} tally;

/* The nearest probe hit within reach (FLT_MAX: none); *below: a probe that
 * hit within reach left below the geometric surface. */
static float probe(const bvh *b, const surface *sf, const float p[3], const float n[3],
                   float reach, int fail_under, int *below)
{
    float nearest = FLT_MAX;
    int i;
    *below = 0;
    for (i = 0; i < 8; i++) {
        float d[3];
        bvh_hit h;
        /* sin^2 theta = 3/4: 60 degrees from n; the azimuths are the
         * library's up to a rotation, which does not change what is near */
        cosine_dir(n, 0.75, i / 8.0, d);
        if (fail_under && dot3(d, sf->ng) <= 0.0f)
            continue;
        if (!bvh_intersect(b, p, d, ray_offset(p), FLT_MAX, &h) || h.t > reach)
            continue;
        *below |= dot3(d, sf->ng) < 0.0f;
        nearest = h.t < nearest ? h.t : nearest;
    }
    return nearest;
}

int main(int argc, char **argv)
{
    static const float edges[7] = {0.001f, 0.01f, 0.05f, 0.1f, 0.2f, 0.3f, 0.4f};
    scene s;
    bvh b;
    cam_frame cf;
    char err[256];
    tally t;
    float px = 0.5f;
    int w, h, x, y, k, fail_under = 0;
    if (argc < 3 || sscanf(argv[2], "%dx%d", &w, &h) != 2 || w < 1 || h < 1) {
        fprintf(stderr, "usage: probes SCENE WxH [D] [--fail-under]\n");
        return 2;
    }
    for (k = 3; k < argc; k++) {
        if (!strcmp(argv[k], "--fail-under"))
            fail_under = 1;
        else
            px = (float)atof(argv[k]);
    }
    if (scene_load(argv[1], &s, err, sizeof err) < 0 || bvh_build(&b, &s) < 0) {
        fprintf(stderr, "probes: %s\n", err);
        return 1;
    }
    s.cam.width = w;
    s.cam.height = h;
    camera_frame(&s.cam, &cf);
    memset(&t, 0, sizeof t);
    for (y = 0; y < h; y++)
        for (x = 0; x < w; x++) {
            float d[3], p[3], fp, nearest;
            const float *n;
            bvh_hit bh;
            surface sf;
            int below;
            camera_ray(&cf, &s.cam, x, y, d);
            if (!bvh_intersect(&b, cf.eye, d, 0.0f, FLT_MAX, &bh))
                continue;
            surface_at(&s, cf.eye, d, &bh, &sf);
            cache_point(&sf, p);
            fp = camera_footprint(&cf, &s.cam, d, bh.t, sf.ng);
            if (!(fp > 0.0f))
                continue;
            t.pixels++;
            /* the demo's normal (render.c, shade_pixel) */
            n = !fail_under || dot3(sf.nsm, sf.ng) >= 0.5f ? sf.nsm : sf.ng;
            nearest = probe(&b, &sf, p, n, px * fp, fail_under, &below);
            if (nearest == FLT_MAX)
                continue;
            t.detail++;
            t.below += below;
            t.tilted += dot3(sf.nsm, sf.ng) < 0.8660254f;
            for (k = 0; k < 7 && nearest / fp >= edges[k]; k++)
                ;
            t.hist[k]++;
        }
    printf("%s %dx%d, probes within %g px%s: %ld of %ld pixels answered per pixel (%.1f%%); "
           "of them %ld with a probe below the geometric surface, %ld with the shading normal "
           "more than 30 degrees off the geometric one\n",
           argv[1], w, h, (double)px, fail_under ? ", failed below the surface" : "", t.detail,
           t.pixels, 100.0 * (double)t.detail / (double)(t.pixels ? t.pixels : 1), t.below,
           t.tilted);
    printf("nearest hit in pixels:");
    for (k = 0; k < 8; k++)
        printf(" %s%g %ld%s", k < 7 ? "<" : ">=", (double)edges[k < 7 ? k : 6], t.hist[k],
               k < 7 ? "," : "\n");
    bvh_free(&b);
    scene_free(&s);
    return 0;
}
