/* t_demo_render.c -- the demo's cache renders and cache file.  Run from the project's root. */
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "cachefile.h"
#include "imgrad.h"
#include "render.h"
#include "scenes.h"
#include "test.h"

/* Renders leak.scene's indirect term at 128 x 80; returns 0 or -1. */
static int leak_render(scene *s, const render_opts *o, float *img)
{
    renderer r;
    render_stats st;
    char err[256];
    int e;
    if (renderer_init(&r, s, o, err, sizeof err) < 0) {
        CHECK(0, "%s", err);
        return -1;
    }
    e = render_image(&r, img, &st);
    renderer_free(&r);
    CHECK(e == 0, "render");
    return e;
}

/* The leak scene (a lit room beside a dark one, a single-polygon wall
 * between): no path carries light into the dark room, so its reference
 * pixels are exactly 0 (no noise) and any light the cache puts there
 * leaked through the wall.  With records reaching far (a = 0.6; Hessian
 * radii at a = 0.5; min_radius 0.4) the cache must still show none; without the guard the
 * same renders do leak, so the scene can catch it. */
TEST(test_leak_scene)
{
    static const struct { float a, min_r; uint32_t f; } cases[3] = {
        {0.6f, 0.0f, IRC_FEATURE_TRANSLATION | IRC_FEATURE_ROTATION},
        {0.5f, 0.0f, IRC_FEATURE_TRANSLATION | IRC_FEATURE_ROTATION | IRC_FEATURE_HESSIAN},
        {0.3f, 0.4f, IRC_FEATURE_TRANSLATION | IRC_FEATURE_ROTATION}};
    scene s;
    render_opts o;
    char err[512];
    const int w = 128, h = 80, n = w * h;
    float *ref = malloc(sizeof(float) * 3 * n), *img = malloc(sizeof(float) * 3 * n);
    int k, g, i;
    if (!ref || !img || scene_load("demo/scenes/leak.scene", &s, err, sizeof err) < 0) {
        CHECK(0, "%s", err);
        free(ref);
        free(img);
        return;
    }
    s.cam.width = w;
    s.cam.height = h;
    memset(&o, 0, sizeof o);
    o.mode = MODE_REFERENCE;
    o.ref_rays = 64;
    o.threads = 1; /* records in a fixed order: the same render every run */
    /* Records placed as a scanline fill places them.  The default fill
     * passes place them otherwise, and at a = 0.6 then light 2 of 8,765
     * dark pixels (brightest 0.030; 48 without the guard), on the back
     * wall 1 mm below its top beside the middle wall, where rays of the
     * neighbouring sector pass over the wall: a gap of the guard, open
     * (docs/DESIGN.md, "Error control"). */
    o.free_fill = 1;
    o.seed = 5;
    o.show = SHOW_INDIRECT;
    o.light_samples = 1;
    o.max_radius = -1.0f;
    if (leak_render(&s, &o, ref) == 0)
        for (k = 0; k < 3; k++)
            for (g = 0; g < 3; g++) {
                int dark = 0, lit = 0;
                double worst = 0.0;
                o.mode = MODE_CACHE;
                o.accuracy = cases[k].a;
                o.min_radius = cases[k].min_r;
                o.features = cases[k].f;
                o.strata_m = 16;
                o.strata_n = 64;
                o.max_records = 100000;
                /* the guard on, off, then off with confirming rays (the
                 * default), which see the walls on their own */
                o.leak_guard = g ? IRC_OFF : IRC_ON;
                o.check_visibility = g == 2 ? IRC_DEFAULT : IRC_OFF;
                if (leak_render(&s, &o, img) < 0)
                    break;
                for (i = 0; i < n; i++)
                    if (ref[3 * i] + ref[3 * i + 1] + ref[3 * i + 2] == 0.0f) {
                        double v = (double)img[3 * i] + img[3 * i + 1] + img[3 * i + 2];
                        dark++;
                        lit += v > 0.0;
                        worst = v > worst ? v : worst;
                    }
                printf("  a %.1f, min_radius %.1f, features %u, %s: %d of %d dark-room pixels lit, brightest "
                       "%.4f\n", cases[k].a, cases[k].min_r, cases[k].f,
                       g == 2 ? "no guard, confirming rays" : g ? "no guard" : "guard", lit, dark, worst);
                CHECK(dark > n / 4, "the dark room covers %d pixels", dark);
                if (g == 1)
                    CHECK(lit > 0, "without the guard the scene should leak");
                else
                    CHECK(lit == 0, "%d dark pixels lit through the wall", lit);
            }
    free(ref);
    free(img);
    scene_free(&s);
}

/* One cache render of s with o; image into img, the cache's snapshot into
 * *snap (malloc'd; its size returned, 0 on failure). */
static size_t fill_render(scene *s, const render_opts *o, float *img, unsigned char **snap)
{
    renderer r;
    render_stats st;
    char err[256];
    size_t bytes = 0;
    *snap = NULL;
    if (renderer_init(&r, s, o, err, sizeof err) < 0) {
        CHECK(0, "%s", err);
        return 0;
    }
    CHECK(render_image(&r, img, &st) == 0, "render");
    if (irc_snapshot_size(r.cache, &bytes) == IRC_OK && (*snap = malloc(bytes)) != NULL &&
        irc_snapshot_write(r.cache, 1u, *snap, bytes, NULL, NULL, NULL) != IRC_OK)
        bytes = 0;
    renderer_free(&r);
    return bytes;
}

/* The demo's default fill (passes) on the Cornell box with 1, 2 and 3
 * threads: the same image and the same cache, bit for bit, for
 * irradiance records with gradients and Hessian and for SH records. */
TEST(test_deterministic_fill)
{
    static const uint32_t feats[2] = {
        IRC_FEATURE_TRANSLATION | IRC_FEATURE_ROTATION | IRC_FEATURE_HESSIAN,
        IRC_FEATURE_SH | IRC_FEATURE_SH_GRADIENT};
    scene s;
    render_opts o;
    char err[512];
    const int w = 72, h = 64, n = w * h;
    float *img[3];
    unsigned char *snap[3];
    size_t bytes[3];
    int f, t;
    if (scene_load("demo/scenes/cornell.scene", &s, err, sizeof err) < 0) {
        CHECK(0, "%s", err);
        return;
    }
    s.cam.width = w;
    s.cam.height = h;
    memset(&o, 0, sizeof o);
    o.mode = MODE_CACHE;
    o.accuracy = 0.3f;
    o.strata_m = 8;
    o.strata_n = 32;
    o.max_records = 20000;
    o.max_radius = -1.0f;
    o.seed = 3;
    o.light_samples = 1;
    for (f = 0; f < 2; f++) {
        o.features = feats[f];
        for (t = 0; t < 3; t++) {
            img[t] = calloc((size_t)n * 3, sizeof(float));
            o.threads = t + 1;
            bytes[t] = img[t] ? fill_render(&s, &o, img[t], &snap[t]) : 0;
            CHECK(bytes[t] > 48 + 4 + 100 * 32, "features %x: %zu snapshot bytes", feats[f],
                  bytes[t]);
        }
        for (t = 1; t < 3; t++) {
            CHECK(bytes[t] && bytes[t] == bytes[0] && memcmp(snap[t], snap[0], bytes[0]) == 0,
                  "features %x: the cache of %d threads differs from 1 thread's", feats[f], t + 1);
            CHECK(img[t] && img[0] && memcmp(img[t], img[0], sizeof(float) * 3 * n) == 0,
                  "features %x: the image of %d threads differs from 1 thread's", feats[f], t + 1);
        }
        for (t = 0; t < 3; t++) {
            free(img[t]);
            free(snap[t]);
        }
    }
    scene_free(&s);
}

/* irc_demo's PREFIX-detail.png reads renderer.detail_map: one mark a
 * pixel answered IRC_DETAIL, so the marks must count what irc_stats
 * counts (each pixel is shaded once in the fill passes; the final sweep
 * skips the marked ones), with 2 threads, and none with detail off. */
TEST(test_detail_map)
{
    scene s;
    render_opts o;
    renderer r;
    render_stats st;
    char err[512];
    const int w = 96, h = 96, n = w * h;
    float *img = calloc((size_t)n * 3, sizeof(float));
    int run;
    if (!img || scene_load("demo/scenes/cornell.scene", &s, err, sizeof err) < 0) {
        CHECK(0, "%s", img ? err : "no memory");
        free(img);
        return;
    }
    s.cam.width = w;
    s.cam.height = h;
    render_opts_defaults(&o);
    o.mode = MODE_CACHE;
    o.show = SHOW_INDIRECT;
    o.accuracy = 0.3f;
    o.strata_m = 8;
    o.strata_n = 32;
    o.light_samples = 1;
    o.threads = 2;
    for (run = 0; run < 3; run++) {
        size_t i, marks = 0;
        o.final_sweep = run == 1;
        o.detail_pixels = run == 2 ? -1.0f : 0.0f;
        if (renderer_init(&r, &s, &o, err, sizeof err) < 0) {
            CHECK(0, "%s", err);
            break;
        }
        r.detail_map = calloc((size_t)n, 1);
        CHECK(r.detail_map && render_image(&r, img, &st) == 0, "run %d: render", run);
        for (i = 0; r.detail_map && i < (size_t)n; i++)
            marks += r.detail_map[i];
        CHECK(marks == st.details, "run %d: %zu marks, %llu detail estimates", run, marks,
              (unsigned long long)st.details);
        CHECK(run == 2 ? marks == 0 : marks > 0 && marks < (size_t)n / 4,
              "run %d: %zu of %d pixels marked", run, marks, n);
        free(r.detail_map);
        r.detail_map = NULL;
        renderer_free(&r);
    }
    scene_free(&s);
    free(img);
}

/* The image gradient (experiments/imgrad.c) against central differences of the
 * image it belongs to, on the Fig. 5 scene at 128 x 96: shaded with one set
 * of light samples everywhere, the direct part of the image is smooth
 * inside each object but for shadow edges, whose gradient the frozen
 * visibility leaves out, and the bumps' pixel-scale detail; the median
 * pixel of that part is held to 1% (it measures 0.11%: half-pixel central
 * differences of a smooth shading), and the parts, computed one at a
 * time, must add up to the gradient computed in one step.  The indirect
 * part is printed: its image's differences carry the lookups' weights,
 * its gradient the records' (test_lookup_gradient_sphere checks those
 * against the closed form). */
TEST(test_image_gradient)
{
    scene s;
    renderer r;
    render_opts o;
    render_stats st;
    cam_frame cf;
    grad_check g;
    char err[256];
    float *img;
    double worst = 0.0, scale = 0.0;
    int x, y, k, a;
    CHECK(scene_load("demo/scenes/fig5.scene", &s, err, sizeof err) == 0, "%s", err);
    s.cam.width = 128;
    s.cam.height = 96;
    render_opts_defaults(&o);
    CHECK(renderer_init(&r, &s, &o, err, sizeof err) == 0, "%s", err);
    img = malloc(sizeof *img * 3 * 128 * 96);
    CHECK(render_image(&r, img, &st) == 0, "render");
    camera_frame(&s.cam, &cf);
    CHECK(image_gradient_check(&r, &cf, 128, 96, IMG_GRADIENT_PARTS, &g) == 0, "check");
    printf("  direct: %d pixels: L2 %.3f; median %.4f, 90th percentile %.3f over %d\n",
           g.direct.pixels, g.direct.l2, g.direct.median, g.direct.p90, g.direct.strong);
    printf("  indirect: L2 %.3f; median %.4f, 90th percentile %.3f over %d\n", g.indirect.l2,
           g.indirect.median, g.indirect.p90, g.indirect.strong);
    CHECK(g.direct.pixels > 5000 && g.direct.median < 0.01, "median relative error %g",
          g.direct.median);
    for (y = 8; y < 96; y += 8)
        for (x = 8; x < 128; x += 8) {
            img_point one, parts;
            image_point(&r, &cf, x + 0.5f, y + 0.5f, IMG_GRADIENT, 0, &one);
            image_point(&r, &cf, x + 0.5f, y + 0.5f, IMG_GRADIENT_PARTS, 0, &parts);
            for (a = 0; a < 2; a++)
                for (k = 0; k < 3; k++) {
                    const double d = fabs((double)one.grad[a][k] - parts.grad[a][k]);
                    scale = fmax(scale, fabs((double)one.grad[a][k]));
                    worst = fmax(worst, d);
                }
        }
    printf("  parts against one step: largest difference %.3g of a largest gradient %.3g\n",
           worst, scale);
    CHECK(worst < 0.05 * scale, "the parts do not add up: %g of %g", worst, scale);
    free(img);
    renderer_free(&r);
    scene_free(&s);
}

/* cache_save (--save-cache) killed at random points while it writes, over
 * and over, two caches of 40 and 80 records to one path: what is left
 * always reads back whole as one of the two. */
TEST(test_cache_save_killed)
{
    char path[] = "/tmp/irc_save_XXXXXX", err[256];
    tscene s;
    irc_config ca, cb, cr;
    irc_cache *a, *b, *r;
    int fd = mkstemp(path), t, k;
    unsigned long long seed = 99;
    scene_sphere_plane(&s);
    ca = scene_config(&s, IRC_FEATURE_TRANSLATION | IRC_FEATURE_ROTATION, 4, 16);
    cb = ca;
    cr = ca;
    a = block_cache(&ca, 128, 0);
    b = block_cache(&cb, 128, 0);
    r = block_cache(&cr, 128, 0);
    CHECK(fd >= 0 && a && b && r, "setup");
    if (fd < 0 || !a || !b || !r)
        return;
    close(fd);
    for (k = 0; k < 80; k++) {
        irc_record rec;
        const float p[3] = {0.1f * (float)k - 4.0f, 0.05f * (float)k, 0.0f}, n[3] = {0, 0, 1};
        CHECK(irc_record_compute(a, p, n, &rec, NULL) == IRC_OK &&
                  (k >= 40 || irc_cache_insert(a, &rec) == IRC_OK) &&
                  irc_cache_insert(b, &rec) == IRC_OK,
              "record %d", k);
    }
    for (t = 0; t < 20; t++) {
        struct timespec nap = {0, 0};
        irc_stats st;
        pid_t pid;
        int status;
        CHECK(cache_save(a, 7, path, err, sizeof err) == 0, "%s", err);
        pid = fork();
        if (pid == 0) {
            for (k = 0;; k++)
                cache_save(k & 1 ? a : b, 7, path, err, sizeof err);
        }
        nap.tv_nsec = (long)(xrand(&seed) * 4e6) + 100000;
        nanosleep(&nap, NULL);
        kill(pid, SIGKILL);
        waitpid(pid, &status, 0);
        { /* the killed writer's temporary file, if it left one */
            char tmp[64];
            snprintf(tmp, sizeof tmp, "%s.tmp.%ld", path, (long)pid);
            remove(tmp);
        }
        CHECK(irc_cache_clear(r) == IRC_OK && cache_merge(r, 7, path, err, sizeof err) == 0 &&
                  irc_cache_stats(r, &st) == IRC_OK && (st.records == 40 || st.records == 80),
              "trial %d: %s, %llu records", t, err, (unsigned long long)st.records);
    }
    remove(path);
    block_free(&ca);
    block_free(&cb);
    block_free(&cr);
}
