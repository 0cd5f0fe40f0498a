/*
 * main.c -- irc_demo, the demo tracer's command line (see --help).
 */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "cachefile.h"
#include "image.h"
#include "render.h"

static const char usage[] =
    "usage: irc_demo SCENE [options]\n"
    "  --cache                 irradiance from the cache (the default); every\n"
    "                          cache setting not given is the library's default\n"
    "  --reference N           brute force: N hemisphere rays per shading point\n"
    "  --features LIST         cache gradients: none, trans, rot, trans,rot (default),\n"
    "                          any of these + \",hess\" (Hessian radii),\n"
    "                          vis, vis,rot (vis: translational from visibility),\n"
    "                          sh, sh,grad (SH records, L = 3, E by convolution)\n"
    "  --accuracy A            cache accuracy a (default 0.2)\n"
    "  --strata MxN            cache hemisphere strata (default: the library's)\n"
    "  --records N             cache capacity (default 200000; CLOCK eviction)\n"
    "  --min-radius R          cache minimum radius (scene units, default 0)\n"
    "  --leak-guard            records keep a leak guard (irc_config.irr.leak_guard)\n"
    "  --no-clamp              no neighbour clamping (irc_config.clamp_neighbours)\n"
    "  --supersamples S        S more rays a record where strata differ (irc_config.irr.supersamples)\n"
    "  --full-pixels F         records narrower than F pixels take coarser strata (irc_config.irr.full_pixels; -1 never)\n"
    "  --detail-pixels D       points within D pixels of geometry get their own estimate (irc_config.irr.detail_pixels; -1 never)\n"
    "  --blend B               lookups average the records within B a R (irc_config.irr.blend, 1..4; default 2)\n"
    "  --pixels MIN,MAX        a record's reach in pixels (default 0,15: none,15; -1: no\n"
    "                          bound on that side)\n"
    "  --no-footprint          records ignore the pixel (the plain lookup-or-compute)\n"
    "  --no-check-visibility   lookups use records out of the point's sight too\n"
    "                          (irc_config.check_visibility off)\n"
    "  --max-radius R          cache maximum radius (default 0: none; -1: 0.1 x the\n"
    "                          diagonal of what the camera sees)\n"
    "  --threads T             render threads (default: the machine's cores)\n"
    "  --tiles K --tile I      render only the I-th of K bands of rows (0-based)\n"
    "  --save-cache F          after rendering, write the cache's records to F\n"
    "                          (a snapshot carrying the scene file's fingerprint)\n"
    "  --load-cache F          before rendering, merge the snapshot F (repeatable;\n"
    "                          any order gives the same cache)\n"
    "  --no-new-records        keep the cache as loaded: a miss computes a record,\n"
    "                          uses it and drops it (counted)\n"
    "  --bounces N             bounces of indirect light, 1..8 (default 1)\n"
    "  --gather cache|path     with N > 1, what a gather ray's hit adds for the\n"
    "                          bounces beyond: the next level's cache (one cache\n"
    "                          a level, default) or a path with next-event\n"
    "                          estimation (the reference always takes paths)\n"
    "  --level-scale S         level k's accuracy is a x S^(k-1) (default 1),\n"
    "  --level-strata D        its strata M/D^(k-1) x N/D^(k-1) (default 2),\n"
    "  --level-min-radius F    its radii in [F x, 1 x] 0.1 x the visible\n"
    "                          diagonal (default 0.5; 0: no minimum)\n"
    "  --level-sight           deeper levels' lookups confirm records with rays\n"
    "                          (default: they do not)\n"
    ;
static const char usage2[] =
    "  --free-fill             threads store records as they make them (the\n"
    "                          records then depend on thread timing); default:\n"
    "                          deterministic fill passes, pixels P apart in P^2\n"
    "                          passes coarse to fine (P = 8..32 from the width)\n"
    "  --size WxH              override the scene's resolution\n"
    "  --indirect              show only the indirect terms (kd/pi E, and the\n"
    "                          glossy bounce with --glossy)\n"
    "  --light-samples N       light samples at camera-ray hits (default 16)\n"
    "  --secondary-samples N   light samples at secondary hits (default 1)\n"
    "  --glossy N              glossy surfaces reflect indirect light too: from\n"
    "                          SH records (--features sh) while the Phong\n"
    "                          exponent is at most --sh-lobe-max S (default\n"
    "                          0.4 L^2), else from N samples of the lobe\n"
    "  --sh-bands L            SH records' bands, 1..5 (default 3)\n"
    "  --seed S                random seed (default 1)\n"
    "  --out PREFIX            write PREFIX.exr, PREFIX.png (+ PREFIX-records.png and\n"
    "                          PREFIX-detail.png: red where a pixel paid its own estimate)\n"
    "  --half                  write the EXR as half floats\n"
    "  --exposure X            PNG exposure (default 1)\n"
    "  --raw FILE              also dump the image as raw little-endian floats\n"
    "  --compare REF.exr       relative RMSE and largest error against REF\n"
    "  --points FILE           irradiance \"r g b\" per line of \"px py pz nx ny nz\"\n"
    "  --quiet                 no progress bar\n";

#define MAX_LOADS 256

typedef struct cli {
    const char *scene, *out, *compare, *points, *raw, *save;
    const char *load[MAX_LOADS];
    int loads;
    int width, height, half;
    float exposure;
    render_opts o;
} cli;

static int parse_uint(const char *s, long lo, long hi, long *v)
{
    char *end;
    errno = 0;
    *v = strtol(s, &end, 10);
    return !errno && end != s && !*end && *v >= lo && *v <= hi;
}

static int parse_float(const char *s, float *v)
{
    char *end;
    *v = strtof(s, &end);
    return end != s && !*end && isfinite(*v);
}

static int parse_features(const char *s, uint32_t *f)
{
    char base[64];
    size_t len = strlen(s);
    /* ",hess" after any irradiance set adds Hessian radii */
    if (len > 5 && len < sizeof base && !strcmp(s + len - 5, ",hess")) {
        memcpy(base, s, len - 5);
        base[len - 5] = '\0';
        if (!strcmp(base, "hess") || !parse_features(base, f) || (*f & IRC_FEATURE_SH))
            return 0;
        *f = (*f & ~(uint32_t)IRC_FEATURE_NONE) | IRC_FEATURE_HESSIAN;
        return 1;
    }
    if (!strcmp(s, "hess")) { *f = IRC_FEATURE_HESSIAN; return 1; }
    if (!strcmp(s, "none")) *f = IRC_FEATURE_NONE;
    else if (!strcmp(s, "trans")) *f = IRC_FEATURE_TRANSLATION;
    else if (!strcmp(s, "rot")) *f = IRC_FEATURE_ROTATION;
    else if (!strcmp(s, "trans,rot") || !strcmp(s, "rot,trans"))
        *f = IRC_FEATURE_TRANSLATION | IRC_FEATURE_ROTATION;
    else if (!strcmp(s, "vis")) *f = IRC_FEATURE_VISIBILITY | IRC_FEATURE_TRANSLATION;
    else if (!strcmp(s, "vis,rot") || !strcmp(s, "rot,vis"))
        *f = IRC_FEATURE_VISIBILITY | IRC_FEATURE_TRANSLATION | IRC_FEATURE_ROTATION;
    else if (!strcmp(s, "sh")) *f = IRC_FEATURE_SH;
    else if (!strcmp(s, "sh,grad")) *f = IRC_FEATURE_SH | IRC_FEATURE_SH_GRADIENT;
    else return 0;
    return 1;
}

static int parse_args(int argc, char **argv, cli *c)
{
    int i;
    long v;
    memset(c, 0, sizeof *c);
    render_opts_defaults(&c->o);
    c->o.progress = 1;
    c->o.threads = (int)sysconf(_SC_NPROCESSORS_ONLN);
    c->exposure = 1.0f;
    for (i = 1; i < argc; i++) {
        const char *a = argv[i], *n = i + 1 < argc ? argv[i + 1] : NULL;
#define NEED(cond) do { if (!n || !(cond)) { fprintf(stderr, "irc_demo: bad value for %s\n", a); return -1; } i++; } while (0)
        if (!strcmp(a, "--cache")) c->o.mode = MODE_CACHE;
        else if (!strcmp(a, "--reference")) { NEED(parse_uint(n, 1, 1 << 20, &v)); c->o.mode = MODE_REFERENCE; c->o.ref_rays = (int)v; }
        else if (!strcmp(a, "--features")) NEED(parse_features(n, &c->o.features));
        else if (!strcmp(a, "--accuracy")) NEED(parse_float(n, &c->o.accuracy));
        else if (!strcmp(a, "--strata")) NEED(sscanf(n, "%ux%u", &c->o.strata_m, &c->o.strata_n) == 2);
        else if (!strcmp(a, "--records")) { NEED(parse_uint(n, 1, IRC_MAX_RECORDS, &v)); c->o.max_records = (uint32_t)v; }
        else if (!strcmp(a, "--min-radius")) NEED(parse_float(n, &c->o.min_radius));
        else if (!strcmp(a, "--max-radius")) NEED(parse_float(n, &c->o.max_radius));
        else if (!strcmp(a, "--threads")) { NEED(parse_uint(n, 1, 64, &v)); c->o.threads = (int)v; }
        else if (!strcmp(a, "--size")) NEED(sscanf(n, "%dx%d", &c->width, &c->height) == 2 && c->width > 0 && c->height > 0 && c->width <= 16384 && c->height <= 16384);
        else if (!strcmp(a, "--indirect")) c->o.show = SHOW_INDIRECT;
        else if (!strcmp(a, "--leak-guard")) c->o.leak_guard = IRC_ON;
        else if (!strcmp(a, "--no-clamp")) c->o.clamp_neighbours = IRC_OFF;
        else if (!strcmp(a, "--full-pixels")) NEED(parse_float(n, &c->o.full_pixels));
        else if (!strcmp(a, "--detail-pixels")) NEED(parse_float(n, &c->o.detail_pixels));
        else if (!strcmp(a, "--blend")) NEED(parse_float(n, &c->o.blend));
        else if (!strcmp(a, "--supersamples")) { NEED(parse_uint(n, 0, IRC_MAX_STRATA, &v)); c->o.supersamples = (uint32_t)v; }
        else if (!strcmp(a, "--no-footprint")) c->o.no_footprint = 1;
        else if (!strcmp(a, "--no-check-visibility")) c->o.check_visibility = IRC_OFF;
        else if (!strcmp(a, "--pixels")) NEED(sscanf(n, "%f,%f", &c->o.min_pixels, &c->o.max_pixels) == 2);
        else if (!strcmp(a, "--free-fill")) c->o.free_fill = 1;
        else if (!strcmp(a, "--bounces")) { NEED(parse_uint(n, 1, MAX_BOUNCES, &v)); c->o.bounces = (int)v; }
        else if (!strcmp(a, "--gather")) { NEED(!strcmp(n, "cache") || !strcmp(n, "path")); c->o.gather = strcmp(n, "cache") ? GATHER_PATH : GATHER_CACHE; }
        else if (!strcmp(a, "--level-strata")) { NEED(parse_uint(n, 1, 64, &v)); c->o.level_strata = (int)v; }
        else if (!strcmp(a, "--level-min-radius")) NEED(parse_float(n, &c->o.level_min_radius) && c->o.level_min_radius >= 0.0f && c->o.level_min_radius < 1.0f);
        else if (!strcmp(a, "--level-sight")) c->o.level_check_visibility = 1;
        else if (!strcmp(a, "--level-scale")) NEED(parse_float(n, &c->o.level_scale) && c->o.level_scale > 0.0f);
        else if (!strcmp(a, "--tiles")) { NEED(parse_uint(n, 1, 65536, &v)); c->o.tiles = (int)v; }
        else if (!strcmp(a, "--tile")) { NEED(parse_uint(n, 0, 65535, &v)); c->o.tile = (int)v; }
        else if (!strcmp(a, "--save-cache")) { NEED(1); c->save = n; }
        else if (!strcmp(a, "--load-cache")) { NEED(c->loads < MAX_LOADS); c->load[c->loads++] = n; }
        else if (!strcmp(a, "--no-new-records")) c->o.frozen = 1;
        else if (!strcmp(a, "--light-samples")) { NEED(parse_uint(n, 0, 4096, &v)); c->o.light_samples = (int)v; }
        else if (!strcmp(a, "--secondary-samples")) { NEED(parse_uint(n, 1, 4096, &v)); c->o.secondary_samples = (int)v; }
        else if (!strcmp(a, "--glossy")) { NEED(parse_uint(n, 1, 1 << 20, &v)); c->o.lobe_rays = (int)v; }
        else if (!strcmp(a, "--sh-lobe-max")) NEED(parse_float(n, &c->o.sh_lobe_max));
        else if (!strcmp(a, "--sh-bands")) { NEED(parse_uint(n, 1, IRC_SH_MAX_BANDS, &v)); c->o.sh_bands = (uint32_t)v; }
        else if (!strcmp(a, "--seed")) { NEED(parse_uint(n, 0, 0x7fffffff, &v)); c->o.seed = (uint64_t)v; }
        else if (!strcmp(a, "--out")) { NEED(1); c->out = n; }
        else if (!strcmp(a, "--half")) c->half = 1;
        else if (!strcmp(a, "--exposure")) NEED(parse_float(n, &c->exposure));
        else if (!strcmp(a, "--raw")) { NEED(1); c->raw = n; }
        else if (!strcmp(a, "--compare")) { NEED(1); c->compare = n; }
        else if (!strcmp(a, "--points")) { NEED(1); c->points = n; }
        else if (!strcmp(a, "--quiet")) c->o.progress = 0;
        else if (!strcmp(a, "--help")) { fputs(usage, stdout); fputs(usage2, stdout); exit(0); }
        else if (a[0] == '-' || c->scene) { fprintf(stderr, "irc_demo: unknown argument %s\n%s%s", a, usage, usage2); return -1; }
        else c->scene = a;
#undef NEED
    }
    if (!c->scene) {
        fputs(usage, stderr);
        fputs(usage2, stderr);
        return -1;
    }
    return 0;
}

/* Points file: one "px py pz nx ny nz" a line; blank lines and # comments
 * skipped.  Errors name the file and line. */
static float *read_points(const char *path, int *count)
{
    FILE *f = fopen(path, "r");
    char line[1024];
    float *pts = NULL;
    int n = 0, cap = 0, ln = 0;
    if (!f) {
        fprintf(stderr, "%s: %s\n", path, strerror(errno));
        return NULL;
    }
    while (fgets(line, sizeof line, f)) {
        float v[6];
        char extra;
        ln++;
        if (line[strspn(line, " \t\r\n")] == 0 || line[strspn(line, " \t")] == '#')
            continue;
        if (sscanf(line, "%f %f %f %f %f %f %c", &v[0], &v[1], &v[2], &v[3], &v[4], &v[5], &extra) != 6) {
            fprintf(stderr, "%s:%d: expected \"px py pz nx ny nz\"\n", path, ln);
            free(pts);
            fclose(f);
            return NULL;
        }
        if (n == cap) {
            float *np = realloc(pts, sizeof(float) * 6 * (size_t)(cap = cap ? 2 * cap : 256));
            if (!np) { free(pts); fclose(f); return NULL; }
            pts = np;
        }
        memcpy(&pts[6 * n++], v, sizeof v);
    }
    fclose(f);
    *count = n;
    return pts ? pts : calloc(1, sizeof(float));
}

/* What the cache's records carry, as --features names it. */
static const char *features_name(uint32_t f)
{
    static const char *const irr[8] = {"no gradients", "trans", "rot", "trans+rot",
                                       "hess",         "trans+hess", "rot+hess", "trans+rot+hess"};
    if (f == 0)
        return "trans+rot (the library's default)";
    if (f & IRC_FEATURE_SH)
        return f & IRC_FEATURE_SH_GRADIENT ? "SH+gradient" : "SH";
    if (f & IRC_FEATURE_VISIBILITY)
        return f & IRC_FEATURE_HESSIAN ? (f & IRC_FEATURE_ROTATION ? "vis+rot+hess" : "vis+hess")
                                       : (f & IRC_FEATURE_ROTATION ? "vis+rot" : "vis");
    return irr[(f & 3u) | ((f & IRC_FEATURE_HESSIAN) ? 4u : 0u)];
}

static void report(FILE *f, const cli *c, const renderer *r, const render_stats *st)
{
    double busy = st->trace_s + st->cache_s;
    fprintf(f, "%s: %s", c->scene, c->o.mode == MODE_CACHE ? "cache" : "reference");
    if (c->o.mode == MODE_CACHE) { /* as the library resolved every 0 */
        irc_config got;
        if (irc_cache_config(r->cache, &got) == IRC_OK) {
            fprintf(f, " (%s, a %g, strata %ux%u", features_name(c->o.features), got.accuracy,
                    got.strata_theta, got.strata_phi);
            if (got.irr.blend > 0.0f) /* irradiance records */
                fprintf(f, ", blend %g", got.irr.blend);
            fprintf(f, ", max radius %g)", r->o.max_radius);
        }
    }
    else
        fprintf(f, " (%d rays per shading point)", c->o.ref_rays);
    fprintf(f, "\n  wall %.2f s; host ray casting %.2f thread-s, cache %.3f thread-s (%.2f%% of both)\n",
           st->wall, st->trace_s, st->cache_s, busy > 0 ? 100.0 * st->cache_s / busy : 0.0);
    fprintf(f, "  rays %llu; records %llu; lookups %llu (%llu answered from records); cache memory %.1f MB\n",
           (unsigned long long)st->rays, (unsigned long long)st->records,
           (unsigned long long)st->lookups, (unsigned long long)st->hits, st->cache_bytes / 1048576.0);
    if (r->o.bounces > 1) {
        int k;
        fprintf(f, "  %d bounces, %s beyond the first", r->o.bounces,
                r->o.gather == GATHER_CACHE ? "a cache a level" : "paths");
        for (k = 2; k <= r->o.bounces && r->o.gather == GATHER_CACHE; k++)
            fprintf(f, "%s level %d %llu records", k == 2 ? ":" : ",", k,
                    (unsigned long long)st->level_records[k - 2]);
        fputc('\n', f);
    }
    if (c->o.frozen)
        fprintf(f, "  no new records: %llu misses computed and dropped\n",
                (unsigned long long)st->dropped);
}

/* Relative RMSE = sqrt(sum (a-b)^2 / sum b^2) over pixels and channels;
 * largest error = max |a - b|, also relative to the reference's largest value. */
static int compare(const cli *c, const float *img, int w, int h)
{
    char err[512];
    float *ref;
    int rw, rh;
    size_t i, at = 0;
    double se = 0, sr = 0, big = 0, rmax = 0;
    if (exr_read(c->compare, &rw, &rh, &ref, err, sizeof err) < 0) {
        fprintf(stderr, "%s\n", err);
        return -1;
    }
    if (rw != w || rh != h) {
        fprintf(stderr, "%s: %dx%d, the render is %dx%d\n", c->compare, rw, rh, w, h);
        free(ref);
        return -1;
    }
    for (i = 0; i < (size_t)w * h * 3; i++) {
        double d = (double)img[i] - ref[i];
        se += d * d;
        sr += (double)ref[i] * ref[i];
        if (fabs(d) > big) { big = fabs(d); at = i / 3; }
        if (ref[i] > rmax) rmax = ref[i];
    }
    printf("  against %s: relative RMSE %.4f; largest error %.4g at pixel (%d, %d) (%.2f%% of the reference's largest value)\n",
           c->compare, sr > 0 ? sqrt(se / sr) : 0.0, big, (int)(at % (size_t)w), (int)(at / (size_t)w),
           rmax > 0 ? 100.0 * big / rmax : 0.0);
    free(ref);
    return 0;
}

static int write_outputs(const cli *c, renderer *r, const float *img, int w, int h)
{
    char path[4096], err[512];
    float *rec;
    if (c->raw) {
        FILE *f = fopen(c->raw, "wb");
        if (!f || fwrite(img, sizeof(float), (size_t)w * h * 3, f) != (size_t)w * h * 3 || fclose(f)) {
            fprintf(stderr, "%s: %s\n", c->raw, strerror(errno));
            return -1;
        }
    }
    if (!c->out)
        return 0;
    snprintf(path, sizeof path, "%s.exr", c->out);
    if (exr_write(path, w, h, img, c->half, err, sizeof err) < 0)
        return fprintf(stderr, "%s\n", err), -1;
    snprintf(path, sizeof path, "%s.png", c->out);
    if (png_write(path, w, h, img, c->exposure, err, sizeof err) < 0)
        return fprintf(stderr, "%s\n", err), -1;
    printf("  wrote %s.exr and %s.png\n", c->out, c->out);
    if (!r->cache || !(rec = malloc(sizeof(float) * (size_t)w * h * 3)))
        return 0;
    render_records(r, rec);
    snprintf(path, sizeof path, "%s-records.png", c->out);
    if (png_write(path, w, h, rec, 4.0f, err, sizeof err) < 0) {
        free(rec);
        return fprintf(stderr, "%s\n", err), -1;
    }
    printf("  wrote %s (records: colour = the record of largest weight, white = centres)\n", path);
    if (r->detail_map) { /* the image in grey, red where a pixel paid its own estimate */
        size_t i, n = 0;
        for (i = 0; i < (size_t)w * h; i++) {
            const float y = 0.25f * (img[3 * i] + img[3 * i + 1] + img[3 * i + 2]) / 3.0f;
            n += r->detail_map[i];
            rec[3 * i] = r->detail_map[i] ? 1.0f : y;
            rec[3 * i + 1] = rec[3 * i + 2] = r->detail_map[i] ? 0.0f : y;
        }
        snprintf(path, sizeof path, "%s-detail.png", c->out);
        if (png_write(path, w, h, rec, c->exposure, err, sizeof err) < 0) {
            free(rec);
            return fprintf(stderr, "%s\n", err), -1;
        }
        printf("  wrote %s (red: the %zu pixels answered by a per-pixel estimate, IRC_DETAIL)\n",
               path, n);
    }
    free(rec);
    return 0;
}

/* Before the render (after = 0): merge every --load-cache file; after it:
 * write --save-cache.  Prints what it did. */
static int cache_files(const cli *c, renderer *r, int after)
{
    char err[512];
    uint64_t fp;
    irc_stats st;
    int i;
    if ((!c->loads && !c->save) || (after && !c->save) || (!after && !c->loads))
        return 0;
    if (!r->cache || scene_fingerprint(c->scene, &fp) < 0) {
        fprintf(stderr, "irc_demo: cache files need --cache and a readable scene file\n");
        return -1;
    }
    for (i = 0; !after && i < c->loads; i++)
        if (cache_merge(r->cache, fp, c->load[i], err, sizeof err) < 0) {
            fprintf(stderr, "irc_demo: %s\n", err);
            return -1;
        }
    if (after && cache_save(r->cache, fp, c->save, err, sizeof err) < 0) {
        fprintf(stderr, "irc_demo: %s\n", err);
        return -1;
    }
    irc_cache_stats(r->cache, &st);
    if (after)
        printf("  saved %llu records to %s\n", (unsigned long long)st.records, c->save);
    else
        printf("  merged %d cache file%s: %llu records\n", c->loads, c->loads > 1 ? "s" : "",
               (unsigned long long)st.records);
    return 0;
}

int main(int argc, char **argv)
{
    cli c;
    scene s;
    renderer r;
    render_stats st;
    char err[1024];
    float *img;
    int w, h, rc = 1;
    if (parse_args(argc, argv, &c) < 0)
        return 2;
    if (scene_load(c.scene, &s, err, sizeof err) < 0) {
        fprintf(stderr, "%s\n", err);
        return 1;
    }
    if (c.width) {
        s.cam.width = c.width;
        s.cam.height = c.height;
    }
    w = s.cam.width;
    h = s.cam.height;
    if (renderer_init(&r, &s, &c.o, err, sizeof err) < 0) {
        fprintf(stderr, "irc_demo: %s\n", err);
        scene_free(&s);
        return 1;
    }
    if (cache_files(&c, &r, 0) < 0) {
        renderer_free(&r);
        scene_free(&s);
        return 1;
    }
    if (c.points) {
        int n = 0, i;
        float *pts = read_points(c.points, &n), *out;
        if (pts && (out = malloc(sizeof(float) * 3 * (size_t)(n + 1)))) {
            if (render_points(&r, pts, n, out, &st) == 0) {
                for (i = 0; i < n; i++)
                    printf("%.9g %.9g %.9g\n", out[3 * i], out[3 * i + 1], out[3 * i + 2]);
                report(stderr, &c, &r, &st);
                rc = 0;
            }
            free(out);
        }
        free(pts);
    } else if ((img = malloc(sizeof(float) * 3 * (size_t)w * h))) {
        int e;
        if (c.out && r.cache)
            r.detail_map = calloc((size_t)w * h, 1); /* optional: no map without it */
        e = render_image(&r, img, &st);
        if (e < 0) {
            fprintf(stderr, "irc_demo: render failed: %s\n", irc_strerror(e));
        } else {
            report(stdout, &c, &r, &st);
            rc = (c.compare && compare(&c, img, w, h) < 0) || write_outputs(&c, &r, img, w, h) < 0 ||
                 cache_files(&c, &r, 1) < 0;
        }
        free(img);
        free(r.detail_map);
        r.detail_map = NULL;
    }
    renderer_free(&r);
    scene_free(&s);
    return rc;
}
