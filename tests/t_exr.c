/*
 * t_exr.c -- cross-checks the demo's EXR writer against OpenEXR's own C
 * library (OpenEXRCore).
 *
 *   t_exr                          synthetic images, float and half
 *   t_exr IMAGE.exr RAW.f32 W H    an EXR the demo wrote against a raw dump
 *                                  (W*H*3 little-endian floats, top row
 *                                  first) of the buffer it rendered
 *
 * Each file must open with OpenEXRCore as one scanline part without
 * compression, have a data window of W x H, exactly channels B, G, R of one
 * type, and decode (in the file's own type) to exactly the reference: the
 * same float bits, or float_to_half of the reference for half files.
 * Uses the shared harness (tests/harness.c): the synthetic images are one
 * test each, the demo's file one test named after it; ends with
 * "N passed, N failed".
 */
#ifndef _POSIX_C_SOURCE
#define _POSIX_C_SOURCE 200809L
#endif
#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

/* OpenEXRCore's headers use C11 anonymous unions. */
#if defined(__GNUC__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpedantic"
#endif
#include <openexr.h>
#if defined(__GNUC__)
#pragma GCC diagnostic pop
#endif

#include "image.h"
#include "test.h"

#define TESTS(X)                                                                          \
    X(test_float_37x23) X(test_half_37x23) X(test_float_1x1) X(test_half_1x1)             \
    X(test_half_301x7) X(test_float_5x130)
TESTS(TEST_DECL)
TEST_DECL(test_demo_file)

/* What OpenEXRCore found: B, G, R planes in the file's own pixel type. */
typedef struct core_image {
    int w, h, type;
    unsigned char *plane[3];
} core_image;

/* Checks that an OpenEXRCore call succeeded; returns whether it did. */
static int rv_ok(exr_result_t rv, const char *call)
{
    CHECK(rv == EXR_ERR_SUCCESS, "%s: %s", call, exr_get_error_code_as_string(rv));
    return rv == EXR_ERR_SUCCESS;
}

/* The part's layout: scanline, uncompressed, exactly B, G, R of one type. */
static int check_layout(exr_context_t ctx, core_image *im)
{
    const exr_attr_chlist_t *cl = NULL;
    exr_attr_box2i_t dw;
    exr_storage_t st;
    exr_compression_t comp;
    int parts = 0, c;
    /* stops at the first failure */
    if (!rv_ok(exr_get_count(ctx, &parts), "exr_get_count"))
        return -1;
    CHECK(parts == 1, "%d parts", parts);
    if (parts != 1 || !rv_ok(exr_get_storage(ctx, 0, &st), "exr_get_storage"))
        return -1;
    CHECK(st == EXR_STORAGE_SCANLINE, "storage %d", (int)st);
    if (st != EXR_STORAGE_SCANLINE ||
        !rv_ok(exr_get_compression(ctx, 0, &comp), "exr_get_compression"))
        return -1;
    CHECK(comp == EXR_COMPRESSION_NONE, "compression %d", (int)comp);
    if (comp != EXR_COMPRESSION_NONE ||
        !rv_ok(exr_get_data_window(ctx, 0, &dw), "exr_get_data_window") ||
        !rv_ok(exr_get_channels(ctx, 0, &cl), "exr_get_channels"))
        return -1;
    CHECK(cl->num_channels == 3, "%d channels", (int)cl->num_channels);
    if (cl->num_channels != 3)
        return -1;
    im->w = dw.max.x - dw.min.x + 1;
    im->h = dw.max.y - dw.min.y + 1;
    im->type = cl->entries[0].pixel_type;
    for (c = 0; c < 3; c++) {
        const exr_attr_chlist_entry_t *e = &cl->entries[c];
        const char *want = c == 0 ? "B" : c == 1 ? "G" : "R";
        CHECK(strcmp(e->name.str, want) == 0, "channel %d is \"%s\", want \"%s\"", c,
              e->name.str, want);
        if (strcmp(e->name.str, want) != 0)
            return -1;
        CHECK(e->pixel_type == EXR_PIXEL_HALF || e->pixel_type == EXR_PIXEL_FLOAT,
              "channel %s: pixel type %d", want, (int)e->pixel_type);
        if (!(e->pixel_type == EXR_PIXEL_HALF || e->pixel_type == EXR_PIXEL_FLOAT))
            return -1;
        CHECK((int)e->pixel_type == im->type, "channel %s: pixel type %d, channel B's %d", want,
              (int)e->pixel_type, im->type);
        if ((int)e->pixel_type != im->type)
            return -1;
        CHECK(e->x_sampling == 1 && e->y_sampling == 1, "channel %s: sampling %d x %d", want,
              (int)e->x_sampling, (int)e->y_sampling);
        if (!(e->x_sampling == 1 && e->y_sampling == 1))
            return -1;
    }
    return 0;
}

/* The attributes exr_write sets that OpenEXRCore reports separately. */
static void check_attrs(exr_context_t ctx, int w, int h)
{
    exr_attr_box2i_t dw;
    exr_attr_v2f_t swc;
    exr_lineorder_t lo;
    float par = 0, sww = 0;
    if (rv_ok(exr_get_data_window(ctx, 0, &dw), "exr_get_data_window"))
        CHECK(dw.min.x == 0 && dw.min.y == 0 && dw.max.x == w - 1 && dw.max.y == h - 1,
              "data window (%d, %d)-(%d, %d), want (0, 0)-(%d, %d)", dw.min.x, dw.min.y,
              dw.max.x, dw.max.y, w - 1, h - 1);
    if (rv_ok(exr_get_display_window(ctx, 0, &dw), "exr_get_display_window"))
        CHECK(dw.min.x == 0 && dw.min.y == 0 && dw.max.x == w - 1 && dw.max.y == h - 1,
              "display window (%d, %d)-(%d, %d), want (0, 0)-(%d, %d)", dw.min.x, dw.min.y,
              dw.max.x, dw.max.y, w - 1, h - 1);
    if (rv_ok(exr_get_lineorder(ctx, 0, &lo), "exr_get_lineorder"))
        CHECK(lo == EXR_LINEORDER_INCREASING_Y, "line order %d", (int)lo);
    if (rv_ok(exr_get_pixel_aspect_ratio(ctx, 0, &par), "exr_get_pixel_aspect_ratio"))
        CHECK(par == 1.0f, "pixel aspect ratio %g", (double)par);
    if (rv_ok(exr_get_screen_window_center(ctx, 0, &swc), "exr_get_screen_window_center"))
        CHECK(swc.x == 0.0f && swc.y == 0.0f, "screen window centre (%g, %g)", (double)swc.x,
              (double)swc.y);
    if (rv_ok(exr_get_screen_window_width(ctx, 0, &sww), "exr_get_screen_window_width"))
        CHECK(sww == 1.0f, "screen window width %g", (double)sww);
}

/* Decodes every chunk straight into the planes, without type conversion. */
static int decode_all(exr_context_t ctx, core_image *im)
{
    exr_decode_pipeline_t dec = EXR_DECODE_PIPELINE_INITIALIZER;
    exr_attr_box2i_t dw;
    int32_t spc = 0, y;
    int bpe = im->type == EXR_PIXEL_HALF ? 2 : 4, c, first = 1, ok = 1;
    if (!rv_ok(exr_get_data_window(ctx, 0, &dw), "exr_get_data_window") ||
        !rv_ok(exr_get_scanlines_per_chunk(ctx, 0, &spc), "exr_get_scanlines_per_chunk"))
        return -1;
    CHECK(spc == 1, "%d scanlines per chunk", (int)spc);
    if (spc != 1)
        return -1;
    for (y = dw.min.y; ok && y <= dw.max.y; y += spc) {
        exr_chunk_info_t ci;
        ok = rv_ok(exr_read_scanline_chunk_info(ctx, 0, y, &ci), "exr_read_scanline_chunk_info");
        if (ok && first)
            ok = rv_ok(exr_decoding_initialize(ctx, 0, &ci, &dec), "exr_decoding_initialize");
        else if (ok)
            ok = rv_ok(exr_decoding_update(ctx, 0, &ci, &dec), "exr_decoding_update");
        for (c = 0; ok && c < dec.channel_count; c++) {
            exr_coding_channel_info_t *ch = &dec.channels[c];
            int k = ch->channel_name[0] == 'B' ? 0 : ch->channel_name[0] == 'G' ? 1 : 2;
            ch->decode_to_ptr = im->plane[k] + (size_t)(ci.start_y - dw.min.y) * im->w * bpe;
            ch->user_pixel_stride = bpe;
            ch->user_line_stride = im->w * bpe;
            ch->user_bytes_per_element = (int16_t)bpe;
            ch->user_data_type = ch->data_type;
        }
        if (ok && first)
            ok = rv_ok(exr_decoding_choose_default_routines(ctx, 0, &dec),
                       "exr_decoding_choose_default_routines");
        if (ok)
            ok = rv_ok(exr_decoding_run(ctx, 0, &dec), "exr_decoding_run");
        first = 0;
    }
    if (!first)
        exr_decoding_destroy(ctx, &dec);
    return ok ? 0 : -1;
}

static int core_read(const char *path, core_image *im, int want_w, int want_h)
{
    exr_context_t ctx = NULL;
    int c, r = -1;
    memset(im, 0, sizeof *im);
    if (!rv_ok(exr_start_read(&ctx, path, NULL), "exr_start_read"))
        return -1;
    if (check_layout(ctx, im) == 0) {
        CHECK(im->w == want_w && im->h == want_h, "%d x %d, want %d x %d", im->w, im->h, want_w,
              want_h);
        if (im->w == want_w && im->h == want_h) {
            check_attrs(ctx, want_w, want_h);
            for (c = 0; c < 3; c++)
                im->plane[c] = calloc((size_t)im->w * im->h, im->type == EXR_PIXEL_HALF ? 2 : 4);
            CHECK(im->plane[0] && im->plane[1] && im->plane[2], "out of memory");
            if (im->plane[0] && im->plane[1] && im->plane[2])
                r = decode_all(ctx, im);
        }
    }
    exr_finish(&ctx);
    return r;
}

/* Every pixel: float bits equal, or the half equal to float_to_half. */
static void compare(const core_image *im, const float *ref)
{
    long bad = 0;
    size_t i, n = (size_t)im->w * im->h;
    int c;
    for (c = 0; c < 3; c++)
        for (i = 0; i < n; i++) {
            float want = ref[i * 3 + (size_t)(2 - c)];
            uint32_t got, exp;
            if (im->type == EXR_PIXEL_HALF) {
                uint16_t g16;
                memcpy(&g16, im->plane[c] + i * 2, 2);
                got = g16;
                exp = float_to_half(want);
            } else {
                memcpy(&got, im->plane[c] + i * 4, 4);
                memcpy(&exp, &want, 4);
            }
            if (got != exp && bad++ < 5)
                printf("  pixel (%d, %d) channel %c: file 0x%08lx, want 0x%08lx\n",
                       (int)(i % (size_t)im->w), (int)(i / (size_t)im->w), "BGR"[c],
                       (unsigned long)got, (unsigned long)exp);
        }
    CHECK(bad == 0, "%ld pixel values differ", bad);
}

static void check_file(const char *path, const float *ref, int w, int h, int want_type)
{
    core_image im;
    if (core_read(path, &im, w, h) == 0) {
        if (want_type >= 0)
            CHECK(im.type == want_type, "pixel type %d, want %d", im.type, want_type);
        compare(&im, ref);
    }
    free(im.plane[0]);
    free(im.plane[1]);
    free(im.plane[2]);
}

static float *synthetic(int w, int h)
{
    static const float special[] = {0.0f, -0.0f, 1e-30f, 1e30f, 65504.0f, 65520.0f,
                                    1e-40f, 0x1p-24f, 0x1p-25f, -7.25f, 1.0009765625f};
    float *rgb = malloc(sizeof *rgb * (size_t)w * h * 3);
    int i, n = w * h * 3, k = (int)(sizeof special / sizeof special[0]);
    for (i = 0; i < n; i++)
        rgb[i] = (float)(i / 3 % w) / (float)w * (float)(1 + i % 3) +
                 (float)(i / 3 / w) / (float)h * 100.0f;
    for (i = 0; i < k && i * 5 + 2 < n; i++)
        rgb[i * 5 + 2] = special[i];
    if (n > 40) {
        rgb[n - 1] = INFINITY;
        rgb[n - 2] = -INFINITY;
        rgb[n - 3] = NAN;
    }
    return rgb;
}

static void synthetic_test(int w, int h, int half)
{
    char path[64], err[256];
    float *rgb = synthetic(w, h);
    int fd, made, rc;
    snprintf(path, sizeof path, "/tmp/t_exr_XXXXXX");
    fd = mkstemp(path);
    made = fd >= 0 && close(fd) == 0;
    CHECK(made, "mkstemp: %s", strerror(errno));
    if (made) {
        rc = exr_write(path, w, h, rgb, half, err, sizeof err);
        CHECK(rc == 0, "exr_write: %s", err);
        if (rc == 0)
            check_file(path, rgb, w, h, half ? EXR_PIXEL_HALF : EXR_PIXEL_FLOAT);
    }
    if (fd >= 0)
        remove(path);
    free(rgb);
}

TEST(test_float_37x23) { synthetic_test(37, 23, 0); }
TEST(test_half_37x23) { synthetic_test(37, 23, 1); }
TEST(test_float_1x1) { synthetic_test(1, 1, 0); }
TEST(test_half_1x1) { synthetic_test(1, 1, 1); }
TEST(test_half_301x7) { synthetic_test(301, 7, 1); }
TEST(test_float_5x130) { synthetic_test(5, 130, 0); }

static float *read_raw(const char *path, int w, int h)
{
    size_t i, n = (size_t)w * h * 3;
    unsigned char b[4];
    float *rgb = malloc(n * sizeof *rgb);
    FILE *f = fopen(path, "rb");
    if (!f || !rgb) {
        perror(path);
        free(rgb);
        if (f)
            fclose(f);
        return NULL;
    }
    for (i = 0; i < n && fread(b, 1, 4, f) == 4; i++) {
        uint32_t u = b[0] | (uint32_t)b[1] << 8 | (uint32_t)b[2] << 16 | (uint32_t)b[3] << 24;
        memcpy(&rgb[i], &u, 4);
    }
    if (i != n || fgetc(f) != EOF) {
        printf("  %s: not %d x %d x 3 floats\n", path, w, h);
        free(rgb);
        rgb = NULL;
    }
    fclose(f);
    return rgb;
}

/* The file mode's arguments: IMAGE.exr RAW.f32 W H. */
static char **file_args;

TEST(test_demo_file)
{
    int w = atoi(file_args[2]), h = atoi(file_args[3]);
    float *ref = w > 0 && h > 0 ? read_raw(file_args[1], w, h) : NULL;
    CHECK(ref != NULL, "no %s x %s reference in %s", file_args[2], file_args[3], file_args[1]);
    if (ref)
        check_file(file_args[0], ref, w, h, -1);
    free(ref);
}

int main(int argc, char **argv)
{
    static const test_case all[] = {TESTS(TEST_ROW)};
    if (argc == 5) {
        /* one test, named after the file */
        test_case one;
        one.name = argv[1];
        one.fn = test_demo_file;
        file_args = argv + 1;
        return test_run(&one, 1, 1, argv);
    }
    if (argc != 1) {
        fprintf(stderr, "usage: %s [IMAGE.exr RAW.f32 W H]\n", argv[0]);
        return 2;
    }
    return test_run(all, sizeof all / sizeof all[0], argc, argv);
}
