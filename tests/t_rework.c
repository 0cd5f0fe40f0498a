/* t_rework.c -- the experiments on records between the fill and the final
 * sweep (demo/rework.c), on the Cornell box: a filtered record's E is the
 * unfiltered cache's lookup at its point, its points and reaches stay;
 * revalued records keep the fill's places and take values of their own
 * seed, each within a record's noise of the fill's. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "render.h"
#include "test.h"

#define W 64
#define H 64

/* One render of the box: its renderer (open for lookups), its records
 * sorted by place, and the rays it cast. */
typedef struct box_run {
    renderer r;
    int open;
    irc_record *rec;
    uint32_t n;
    double rays;
} box_run;

static int by_place(const void *a, const void *b)
{
    const irc_record *x = a, *y = b;
    int k;
    for (k = 0; k < 3; k++)
        if (x->p[k] != y->p[k])
            return x->p[k] < y->p[k] ? -1 : 1;
    return 0;
}

/* Renders the box with o into *b; 0, or -1 (checked) when it failed. */
static int render_and_read(const scene *s, const render_opts *o, box_run *b)
{
    static float img[W * H * 3];
    render_stats st;
    irc_stats cs;
    char err[256];
    uint32_t id;
    memset(b, 0, sizeof *b);
    if (renderer_init(&b->r, s, o, err, sizeof err) < 0) {
        CHECK(0, "%s", err);
        return -1;
    }
    b->open = 1;
    if (render_image(&b->r, img, &st) != 0 || irc_cache_stats(b->r.cache, &cs) != IRC_OK ||
        !(b->rec = malloc(sizeof *b->rec * (size_t)(cs.records + 1)))) {
        CHECK(0, "render");
        return -1;
    }
    b->rays = (double)st.rays;
    for (id = 0; id < cs.capacity && b->n < cs.records; id++)
        if (irc_cache_record(b->r.cache, id, &b->rec[b->n]) == IRC_OK)
            b->n++;
    qsort(b->rec, b->n, sizeof *b->rec, by_place);
    return 0;
}

static void box_run_free(box_run *b)
{
    free(b->rec);
    if (b->open)
        renderer_free(&b->r);
    memset(b, 0, sizeof *b);
}

/* The Cornell box at W x H and the options every test starts from. */
static int load_box(scene *s, render_opts *o)
{
    char err[256];
    if (scene_load("demo/scenes/cornell.scene", s, err, sizeof err) != 0) {
        CHECK(0, "%s", err);
        return -1;
    }
    s->cam.width = W;
    s->cam.height = H;
    render_opts_defaults(o);
    o->mode = MODE_CACHE;
    o->show = SHOW_INDIRECT;
    o->accuracy = 0.3f;
    o->strata_m = 16;
    o->strata_n = 64;
    o->light_samples = 1;
    o->threads = 1;
    o->final_sweep = 1;
    return 0;
}

/* Whether a's and b's records (as many) have the same points and reaches
 * (to the clamp's rounding on the way back in). */
static int same_places(const box_run *a, const box_run *b)
{
    uint32_t i;
    if (a->n != b->n || a->n <= 50)
        return 0;
    for (i = 0; i < a->n; i++)
        if (by_place(&a->rec[i], &b->rec[i]) ||
            fabsf(a->rec[i].radius - b->rec[i].radius) > 1e-6f * a->rec[i].radius)
            return 0;
    return 1;
}

/* Over records of the same places: how many have another E (summed over
 * the channels), in *differ, and the mean relative difference. */
static double values_apart(const box_run *a, const box_run *b, uint32_t *differ)
{
    double sum = 0.0;
    uint32_t i;
    *differ = 0;
    for (i = 0; i < a->n; i++) {
        const irc_record *x = &a->rec[i], *y = &b->rec[i];
        const double ex = x->e[0] + x->e[1] + x->e[2], ey = y->e[0] + y->e[1] + y->e[2];
        *differ += ex != ey;
        sum += fabs(ex - ey) / (0.5 * (ex + ey) + 1e-6);
    }
    return a->n ? sum / a->n : 0.0;
}

/* filter = 1: each record's E is what the unfiltered cache (the same
 * seed's fill) looked up at its point, its point and reach kept (to the
 * clamp's rounding on the way back in); gfilter = 1 as well moves the
 * gradients, not E. */
TEST(test_rework_filter)
{
    scene s;
    render_opts o;
    box_run a, b, c;
    uint32_t i, moved = 0, grads = 0;
    double worst = 0.0;
    if (load_box(&s, &o) < 0)
        return;
    render_and_read(&s, &o, &a);
    o.filter = 1.0f;
    render_and_read(&s, &o, &b);
    o.gfilter = 1.0f;
    render_and_read(&s, &o, &c);
    CHECK(same_places(&a, &b) && same_places(&a, &c), "records %u %u %u, places kept", a.n, b.n,
          c.n);
    for (i = 0; same_places(&a, &b) && same_places(&a, &c) && i < a.n; i++) {
        float v[3];
        int k;
        CHECK(irc_cache_lookup(a.r.cache, a.rec[i].p, a.rec[i].n, v, NULL) == IRC_OK, "lookup %u",
              i);
        for (k = 0; k < 3; k++) {
            const double d = fabs(b.rec[i].e[k] - v[k]) / (v[k] + 1e-6);
            worst = d > worst ? d : worst;
            moved += fabsf(b.rec[i].e[k] - a.rec[i].e[k]) > 1e-4f * a.rec[i].e[k];
        }
        CHECK(memcmp(c.rec[i].e, b.rec[i].e, sizeof b.rec[i].e) == 0, "record %u: E with gfilter",
              i);
        grads += memcmp(c.rec[i].grad_t, b.rec[i].grad_t, sizeof b.rec[i].grad_t) != 0;
    }
    CHECK(worst < 1e-5, "filtered E off the lookup by %.2e", worst);
    CHECK(moved > a.n, "%u of %u channels moved", moved, 3 * a.n);
    CHECK(grads > a.n / 2, "gfilter moved %u of %u records' gradients", grads, a.n);
    box_run_free(&a);
    box_run_free(&b);
    box_run_free(&c);
    scene_free(&s);
}

/* place_seed: renders with seeds 1 and 2 over one fill have the same
 * records, with values of their own; the two differ by a 1,024-ray
 * estimate's noise (a few percent), not by a wrong normal or surface. */
TEST(test_rework_place)
{
    scene s;
    render_opts o;
    box_run a, b;
    uint32_t differ = 0;
    double apart = 0.0;
    if (load_box(&s, &o) < 0)
        return;
    o.place_seed = 7;
    render_and_read(&s, &o, &a);
    o.seed = 2;
    render_and_read(&s, &o, &b);
    CHECK(same_places(&a, &b), "records %u %u, places kept", a.n, b.n);
    if (same_places(&a, &b))
        apart = values_apart(&a, &b, &differ);
    CHECK(differ > a.n * 9 / 10, "%u of %u records revalued", differ, a.n);
    CHECK(a.n && apart < 0.08, "mean relative difference %.4f", apart);
    box_run_free(&a);
    box_run_free(&b);
    scene_free(&s);
}

/* boost: records serving at least that many pixels computed again with
 * twice the strata each way (16 x 64 -> 32 x 128, 4,096 rays each), so a
 * threshold no record meets changes nothing and one every record meets
 * casts 4,096 more hemisphere rays a record, each with at most one shadow
 * ray where it hits (the demo counts both), and moves every E by about a
 * record's noise. */
TEST(test_rework_boost)
{
    scene s;
    render_opts o;
    box_run a, b, c;
    uint32_t i, differ = 0;
    double apart = 0.0, more;
    if (load_box(&s, &o) < 0)
        return;
    render_and_read(&s, &o, &a);
    o.boost = 1e9f;
    render_and_read(&s, &o, &b);
    o.boost = 1e-6f;
    render_and_read(&s, &o, &c);
    CHECK(same_places(&a, &b) && same_places(&a, &c), "records %u %u %u, places kept", a.n, b.n,
          c.n);
    for (i = 0; same_places(&a, &b) && i < a.n; i++)
        CHECK(memcmp(a.rec[i].e, b.rec[i].e, sizeof a.rec[i].e) == 0,
              "record %u moved, none boosted", i);
    if (same_places(&a, &c))
        apart = values_apart(&a, &c, &differ);
    more = c.rays - a.rays;
    CHECK(b.rays == a.rays, "rays %.0f against %.0f with nothing boosted", b.rays, a.rays);
    CHECK(more > 0.95 * 4096.0 * a.n && more <= 2.0 * 4096.0 * a.n,
          "%.0f more rays for %u records", more, a.n);
    CHECK(differ > a.n * 9 / 10, "%u of %u records boosted", differ, a.n);
    CHECK(a.n && apart < 0.08, "mean relative difference %.4f", apart);
    box_run_free(&a);
    box_run_free(&b);
    box_run_free(&c);
    scene_free(&s);
}
