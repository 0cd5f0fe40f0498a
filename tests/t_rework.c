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

static render_stats last; /* render_and_read's last render */

static int by_place(const void *a, const void *b)
{
    const irc_record *x = a, *y = b;
    int k;
    for (k = 0; k < 3; k++)
        if (x->p[k] != y->p[k])
            return x->p[k] < y->p[k] ? -1 : 1;
    return 0;
}

/* Renders the box with o and returns its records sorted by place (*n of
 * them); *r stays open for lookups (renderer_free by the caller). */
static irc_record *render_and_read(const scene *s, const render_opts *o, renderer *r,
                                   uint32_t *n)
{
    static float img[W * H * 3];
    irc_stats cs;
    irc_record *rec;
    char err[256];
    uint32_t id;
    *n = 0;
    if (renderer_init(r, s, o, err, sizeof err) < 0) {
        CHECK(0, "%s", err);
        return NULL;
    }
    if (render_image(r, img, &last) != 0 || irc_cache_stats(r->cache, &cs) != IRC_OK ||
        !(rec = malloc(sizeof *rec * (size_t)(cs.records + 1)))) {
        CHECK(0, "render");
        return NULL;
    }
    for (id = 0; id < cs.capacity && *n < cs.records; id++)
        if (irc_cache_record(r->cache, id, &rec[*n]) == IRC_OK)
            (*n)++;
    qsort(rec, *n, sizeof *rec, by_place);
    return rec;
}

static void box_opts(render_opts *o)
{
    render_opts_defaults(o);
    o->mode = MODE_CACHE;
    o->show = SHOW_INDIRECT;
    o->accuracy = 0.3f;
    o->strata_m = 16;
    o->strata_n = 64;
    o->light_samples = 1;
    o->threads = 1;
    o->final_sweep = 1;
}

static int same_places(const irc_record *a, const irc_record *b, uint32_t n)
{
    uint32_t i;
    for (i = 0; i < n; i++)
        if (by_place(&a[i], &b[i]) || fabsf(a[i].radius - b[i].radius) > 1e-6f * a[i].radius)
            return 0;
    return 1;
}

/* filter = 1: each record's E is what the unfiltered cache (the same
 * seed's fill) looked up at its point, its point and reach kept (to the
 * clamp's rounding on the way back in); gfilter = 1 as well moves the
 * gradients, not E. */
TEST(test_rework_filter)
{
    scene s;
    render_opts o;
    renderer ra, rb, rc;
    irc_record *a, *b, *c;
    uint32_t na, nb, nc, i, moved = 0, grads = 0;
    double worst = 0.0;
    char err[256];
    CHECK(scene_load("demo/scenes/cornell.scene", &s, err, sizeof err) == 0, "%s", err);
    s.cam.width = W;
    s.cam.height = H;
    box_opts(&o);
    a = render_and_read(&s, &o, &ra, &na);
    o.filter = 1.0f;
    b = render_and_read(&s, &o, &rb, &nb);
    o.gfilter = 1.0f;
    c = render_and_read(&s, &o, &rc, &nc);
    CHECK(a && b && c && na > 50 && na == nb && na == nc, "records %u %u %u", na, nb, nc);
    CHECK(a && b && c && same_places(a, b, na) && same_places(a, c, na), "places kept");
    for (i = 0; a && b && c && i < na && na == nb && na == nc; i++) {
        float v[3];
        int k;
        CHECK(irc_cache_lookup(ra.cache, a[i].p, a[i].n, v, NULL) == IRC_OK, "lookup %u", i);
        for (k = 0; k < 3; k++) {
            const double d = fabs(b[i].e[k] - v[k]) / (v[k] + 1e-6);
            worst = d > worst ? d : worst;
            moved += fabsf(b[i].e[k] - a[i].e[k]) > 1e-4f * a[i].e[k];
            CHECK(memcmp(c[i].e, b[i].e, sizeof b[i].e) == 0, "record %u: E with gfilter", i);
        }
    }
    CHECK(worst < 1e-5, "filtered E off the lookup by %.2e", worst);
    CHECK(moved > na, "%u of %u channels moved", moved, 3 * na);
    for (i = 0; b && c && i < na && na == nc; i++)
        grads += memcmp(c[i].grad_t, b[i].grad_t, sizeof b[i].grad_t) != 0;
    CHECK(grads > na / 2, "gfilter moved %u of %u records' gradients", grads, na);
    free(a);
    free(b);
    free(c);
    renderer_free(&ra);
    renderer_free(&rb);
    renderer_free(&rc);
    scene_free(&s);
}

/* place_seed: renders with seeds 1 and 2 over one fill have the same
 * records, with values of their own; the two differ by a 1,024-ray
 * estimate's noise (a few percent), not by a wrong normal or surface. */
TEST(test_rework_place)
{
    scene s;
    render_opts o;
    renderer ra, rb;
    irc_record *a, *b;
    uint32_t na, nb, i, differ = 0;
    double sum = 0.0;
    char err[256];
    CHECK(scene_load("demo/scenes/cornell.scene", &s, err, sizeof err) == 0, "%s", err);
    s.cam.width = W;
    s.cam.height = H;
    box_opts(&o);
    o.place_seed = 7;
    a = render_and_read(&s, &o, &ra, &na);
    o.seed = 2;
    b = render_and_read(&s, &o, &rb, &nb);
    CHECK(a && b && na > 50 && na == nb && same_places(a, b, na), "records %u %u", na, nb);
    for (i = 0; a && b && i < na && na == nb; i++) {
        const double ea = a[i].e[0] + a[i].e[1] + a[i].e[2], eb = b[i].e[0] + b[i].e[1] + b[i].e[2];
        differ += ea != eb;
        sum += fabs(ea - eb) / (0.5 * (ea + eb) + 1e-6);
    }
    CHECK(differ > na * 9 / 10, "%u of %u records revalued", differ, na);
    CHECK(na && sum / na < 0.08, "mean relative difference %.4f", na ? sum / na : 0.0);
    free(a);
    free(b);
    renderer_free(&ra);
    renderer_free(&rb);
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
    renderer ra, rb, rc;
    irc_record *a, *b, *c;
    uint32_t na, nb, nc, i, differ = 0;
    unsigned long long ra_rays, rb_rays;
    double sum = 0.0;
    char err[256];
    CHECK(scene_load("demo/scenes/cornell.scene", &s, err, sizeof err) == 0, "%s", err);
    s.cam.width = W;
    s.cam.height = H;
    box_opts(&o);
    a = render_and_read(&s, &o, &ra, &na);
    ra_rays = (unsigned long long)last.rays;
    o.boost = 1e9f;
    b = render_and_read(&s, &o, &rb, &nb);
    rb_rays = (unsigned long long)last.rays;
    o.boost = 1e-6f;
    c = render_and_read(&s, &o, &rc, &nc);
    CHECK(a && b && c && na > 50 && na == nb && na == nc, "records %u %u %u", na, nb, nc);
    CHECK(a && c && same_places(a, c, na), "places kept");
    for (i = 0; a && b && c && i < na && na == nb && na == nc; i++) {
        const double ea = a[i].e[0] + a[i].e[1] + a[i].e[2], ec = c[i].e[0] + c[i].e[1] + c[i].e[2];
        CHECK(memcmp(a[i].e, b[i].e, sizeof a[i].e) == 0, "record %u moved, none boosted", i);
        differ += ea != ec;
        sum += fabs(ea - ec) / (0.5 * (ea + ec) + 1e-6);
    }
    CHECK(rb_rays == ra_rays, "rays %llu against %llu with nothing boosted", rb_rays, ra_rays);
    CHECK((double)last.rays - (double)ra_rays > 0.95 * 4096.0 * na &&
              (double)last.rays - (double)ra_rays <= 2.0 * 4096.0 * na,
          "%.0f more rays for %u records", (double)last.rays - (double)ra_rays, na);
    CHECK(differ > na * 9 / 10, "%u of %u records boosted", differ, na);
    CHECK(na && sum / na < 0.08, "mean relative difference %.4f", na ? sum / na : 0.0);
    free(a);
    free(b);
    free(c);
    renderer_free(&ra);
    renderer_free(&rb);
    renderer_free(&rc);
    scene_free(&s);
}
