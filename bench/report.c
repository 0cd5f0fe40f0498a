/*
 * report.c -- make bench's table (bench/notes.md, "Speed against error") and the
 * gnuplot data, from the runs bench.c made.
 */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "bench.h"

const char *const methods[NMETHODS] = {"brute", "none", "trans+rot", "vis", "hess", "sh",
                                      "first", "levels"};
const char *const method_names[NMETHODS] = {
    "brute force", "cache, no gradients", "cache, translational + rotational (the defaults)",
    "cache, visibility gradients", "cache, trans + rot, Hessian radii",
    "cache, SH records L = 3 + gradients",
    "cache at the first level, path-traced gathers (trans + rot)",
    "cache at every level (trans + rot)"};

/* The error a run is judged by: relative RMSE, or the 99th percentile of
 * the per-pixel relative error. */
enum { BY_RMSE, BY_P99 };

static double err_of(const run *r, int by)
{
    return by == BY_P99 ? r->p99 : r->rmse;
}

/* Time at which a method first reaches error `target` (err_of `by`):
 * along its lower envelope (runs in order of time, each kept only if more
 * accurate than every faster one), interpolated log-log between the runs
 * either side; -1 if no run does.  When the fastest run already does, its
 * time (an upper bound) with *bound = 1. */
static double time_by(const ctx *c, const char *method, double target, int by, int *bound)
{
    int idx[MAX_RUNS], n = 0, i, j, k = 0;
    for (i = 0; i < c->nruns; i++)
        if (!strcmp(c->runs[i].method, method))
            idx[n++] = i;
    for (i = 1; i < n; i++)
        for (j = i; j > 0 && c->runs[idx[j]].st.cpu < c->runs[idx[j - 1]].st.cpu; j--) {
            int t = idx[j];
            idx[j] = idx[j - 1];
            idx[j - 1] = t;
        }
    for (i = 0; i < n; i++) /* the envelope, in place */
        if (k == 0 || err_of(&c->runs[idx[i]], by) < err_of(&c->runs[idx[k - 1]], by))
            idx[k++] = idx[i];
    *bound = 0;
    if (k == 0)
        return -1.0;
    if (err_of(&c->runs[idx[0]], by) <= target) {
        *bound = 1;
        return c->runs[idx[0]].st.cpu;
    }
    for (i = 1; i < k; i++) {
        const run *a = &c->runs[idx[i - 1]], *b = &c->runs[idx[i]];
        if (err_of(b, by) <= target) {
            double u = (log(target) - log(err_of(a, by))) / (log(err_of(b, by)) - log(err_of(a, by)));
            return exp(log(a->st.cpu) + u * (log(b->st.cpu) - log(a->st.cpu)));
        }
    }
    return -1.0;
}

static double time_to(const ctx *c, const char *method, double target, int *bound)
{
    return time_by(c, method, target, BY_RMSE, bound);
}

/* The power law t = A e^b fitted by least squares in log-log over brute
 * force's runs (error err_of `by`, time t): *a = log A, *b, and the runs'
 * error range [*lo, *hi].  Returns the number of runs; a fit needs four.
 * A Monte Carlo estimate's error falls as t^-1/2, so b = -2 in theory; the
 * fits on the corpus are flatter (fixed costs a pixel, the reference's own
 * noise), which favours brute force. */
static int brute_law(const ctx *c, int by, double *a, double *b, double *lo, double *hi)
{
    double sx = 0.0, sy = 0.0, sxx = 0.0, sxy = 0.0;
    int i, n = 0;
    *lo = HUGE_VAL;
    *hi = 0.0;
    for (i = 0; i < c->nruns; i++) {
        const run *r = &c->runs[i];
        double x, y;
        if (strcmp(r->method, "brute") || !(err_of(r, by) > 0.0) || !(r->st.cpu > 0.0))
            continue;
        x = log(err_of(r, by));
        y = log(r->st.cpu);
        sx += x;
        sy += y;
        sxx += x * x;
        sxy += x * y;
        *lo = fmin(*lo, err_of(r, by));
        *hi = fmax(*hi, err_of(r, by));
        n++;
    }
    if (n < 4 || !(n * sxx - sx * sx > 0.0))
        return n < 4 ? n : 0;
    *b = (n * sxy - sx * sy) / (n * sxx - sx * sx);
    *a = (sy - *b * sx) / n;
    return n;
}

/* Brute force's time to error `target` from brute_law's fit: between its
 * runs' errors, or extrapolated (*ext = 1) by at most a factor of two in
 * error either side; -1 beyond that.  Without a fit, time_by's
 * interpolation along the runs (-1 where that gives only a bound). */
static double brute_time(const ctx *c, double target, int by, int *ext)
{
    double a, b, lo, hi;
    *ext = 0;
    if (brute_law(c, by, &a, &b, &lo, &hi) < 4) {
        int bound;
        const double t = time_by(c, "brute", target, by, &bound);
        return bound ? -1.0 : t;
    }
    if (target < 0.5 * lo || target > 2.0 * hi)
        return -1.0;
    *ext = target < lo || target > hi;
    return exp(a + b * log(target));
}

/* Brute force's leaking pixels at relative RMSE `rmse`: interpolated
 * linearly in log RMSE between the brute-force runs either side (-1
 * outside them). */
static double brute_leaks_at(const ctx *c, double rmse)
{
    const run *lo = NULL, *hi = NULL;
    int i;
    for (i = 0; i < c->nruns; i++) {
        const run *r = &c->runs[i];
        if (strcmp(r->method, "brute"))
            continue;
        if (r->rmse >= rmse && (!lo || r->rmse < lo->rmse))
            lo = r;
        if (r->rmse <= rmse && (!hi || r->rmse > hi->rmse))
            hi = r;
    }
    if (!lo || !hi)
        return -1.0;
    if (lo == hi)
        return lo->leaks;
    return lo->leaks + (hi->leaks - lo->leaks) * (log(lo->rmse) - log(rmse)) /
                           (log(lo->rmse) - log(hi->rmse));
}

/* A method's relative RMSE at `records` records, interpolated log-log
 * along its accuracy sweep; -1 outside it. */
static double rmse_at(const ctx *c, const char *method, double records)
{
    int i, j;
    for (i = 0; i < c->nruns; i++)
        for (j = 0; j < c->nruns; j++) {
            const run *a = &c->runs[i], *b = &c->runs[j];
            double ra = (double)a->st.records, rb = (double)b->st.records, u;
            if (strcmp(a->method, method) || strcmp(b->method, method) || !(ra <= records) ||
                !(rb >= records) || ra <= 0.0 || rb <= 0.0 || a->m != DEF_M || b->m != DEF_M)
                continue;
            if (ra == rb)
                return a->rmse;
            /* the nearest bracket: no run of this method between them */
            {
                int k, inside = 0;
                for (k = 0; k < c->nruns; k++)
                    if (!strcmp(c->runs[k].method, method) && c->runs[k].m == DEF_M &&
                        c->runs[k].st.records > ra && c->runs[k].st.records < rb)
                        inside = 1;
                if (inside)
                    continue;
            }
            u = (log(records) - log(ra)) / (log(rb) - log(ra));
            return exp(log(a->rmse) + u * (log(b->rmse) - log(a->rmse)));
        }
    return -1.0;
}

const double levels[NLEVELS] = {0.08, 0.04, 0.02, 0.01};

/* Time to the target error and the speedup over brute force there
 * (brute force's time from its fit, "ext" where extrapolated); returns
 * the speedup (0: none to give). */
static double cell_time(FILE *f, const ctx *c, const char *method, double target, int is_brute)
{
    int bm, ext;
    const double t = time_to(c, method, target, &bm);
    const double tb = is_brute ? -1.0 : brute_time(c, target, BY_RMSE, &ext);
    if (t < 0.0)
        fprintf(f, " not reached |");
    else if (tb < 0.0)
        fprintf(f, " %s%.2f s |", bm ? "<= " : "", t);
    else
        fprintf(f, " %s%.2f s (%s%.1fx%s) |", bm ? "<= " : "", t, bm ? ">= " : "", tb / t,
                ext ? " ext" : "");
    return t > 0.0 && tb > 0.0 ? tb / t : 0.0;
}

void corpus_summary(const ctx *c, FILE *md)
{
    int k;
    fprintf(md, "\n**Over the scenes run** (geometric means): the defaults (translational + "
                "rotational, a = 0.2, the library's strata) against brute force at equal relative RMSE ");
    if (c->gm_n)
        fprintf(md, "%.1fx over %d scenes", exp(c->gm_log / c->gm_n), c->gm_n);
    else
        fprintf(md, "(none)");
    for (k = 0; k < NLEVELS; k++) {
        fprintf(md, "; at %g%%: ", 100.0 * levels[k]);
        if (c->lvl_n[k])
            fprintf(md, "%.1fx over %d", exp(c->lvl_log[k] / c->lvl_n[k]), c->lvl_n[k]);
        else
            fprintf(md, "not reached");
    }
    fprintf(md, " (the translational + rotational cache's lower envelope over its runs).\n");
}


void table(ctx *c, const bscene *b, FILE *md)
{
    int m, i, k;
    fprintf(md, "\n**%s** (%dx%d; reference %d rays at every %dth pixel, noise %.4f; "
                "%d light sample%s at secondary hits",
            b->name, c->w, c->h, c->ref_rays, c->stride, c->ref_noise,
            c->secondary ? c->secondary : 1, c->secondary > 1 ? "s" : "");
    {
        double a, e, lo, hi;
        if (brute_law(c, BY_RMSE, &a, &e, &lo, &hi) >= 4)
            fprintf(md, "; brute force's time ~ RMSE^%.2f over its runs", e);
    }
    fprintf(md, ")\n\n");
    fprintf(md, "| method | runs | best rel. RMSE | its p99 / p99.9 / max, px > 10%% | "
                "time to 8%% (speedup) | to 4%% | to 2%% | to 1%% | records at a = 0.2 "
                "(their bytes) | cache share there |\n"
                "|---|---|---|---|---|---|---|---|---|---|\n");
    for (m = 0; m < NMETHODS; m++) {
        const run *best = NULL, *mid = NULL;
        int n = 0;
        for (i = 0; i < c->nruns; i++) {
            const run *r = &c->runs[i];
            if (strcmp(r->method, methods[m]))
                continue;
            n++;
            if (!best || r->rmse < best->rmse)
                best = r;
            if (m > 0 && fabs(r->param - 0.2) < 1e-6 && r->m == DEF_M)
                mid = r;
        }
        if (!n)
            continue;
        fprintf(md, "| %s | %d | %.4f | %.4f / %.4f / %.3f, %d |", method_names[m], n, best->rmse,
                best->p99, best->p999, best->maxe, best->over10);
        for (k = 0; k < NLEVELS; k++) {
            const double x = cell_time(md, c, methods[m], levels[k], m == 0);
            if (x > 0.0 && !strcmp(methods[m], "trans+rot")) {
                c->lvl_log[k] += log(x);
                c->lvl_n[k]++;
            }
        }
        if (mid)
            fprintf(md, " %llu (%.2f MB) | %.1f%% |\n", (unsigned long long)mid->st.records,
                    (double)mid->st.records * mid->st.record_bytes / 1048576.0,
                    100.0 * mid->st.cache_s / (mid->st.cpu));
        else
            fprintf(md, " | |\n");
    }
    for (i = 0; i < c->nruns; i++)
        if (!strcmp(c->runs[i].method, "trans+rot") && fabs(c->runs[i].param - 0.2) < 1e-6 &&
            c->runs[i].m == DEF_M) {
            double rec = (double)c->runs[i].st.records, e0 = rmse_at(c, "none", rec),
                   e1 = c->runs[i].rmse, e2 = rmse_at(c, "vis", rec), e3 = rmse_at(c, "hess", rec);
            fprintf(md, "\nAt %llu records (trans+rot, a = 0.2), along the sweeps of a: "
                        "relative RMSE no gradients %.4f, "
                        "translational + rotational %.4f, visibility %.4f, Hessian radii %.4f",
                    (unsigned long long)rec, e0, e1, e2, e3);
            if (e0 > 0.0 && e2 > 0.0)
                fprintf(md, " (none / trans+rot = %.2f, trans+rot / visibility = %.2f)", e0 / e1,
                        e1 / e2);
            fprintf(md, "; -1: the record count is outside that method's sweep.\n");
        }
}

/* Each cache method at a = 0.2 and the library's strata (its defaults for
 * trans+rot) against brute force at the same error: by relative RMSE and
 * by p99, the worst 1% of pixels' share of the squared error, the pixels
 * that leak (and brute force's at the same RMSE), the bias. */
void defaults_table(ctx *c, const bscene *b, FILE *md)
{
    int m, i, bt, bp;
    fprintf(md, "\n**%s at a = 0.2** (the defaults for trans + rot; brute force's time "
                "from its power-law fit at the same error, ext: extrapolated; leaks: pixels above the reference by more than "
                "25%% of its mean)\n\n"
                "| method | rel. RMSE | speedup at equal RMSE | p99 | speedup at equal p99 | "
                "worst 1%% of pixels: share of squared error | record noise: rel. RMSE, share "
                "of squared error | leaks (brute force at equal RMSE) | "
                "bias | records |\n|---|---|---|---|---|---|---|---|---|---|\n",
            b->name);
    for (m = 1; m < NMETHODS; m++)
        for (i = 0; i < c->nruns; i++) {
            const run *r = &c->runs[i];
            double tr, tp, bl;
            if (strcmp(r->method, methods[m]) || fabs(r->param - 0.2) > 1e-6 || r->m != DEF_M)
                continue;
            tr = brute_time(c, r->rmse, BY_RMSE, &bt);
            tp = brute_time(c, r->p99, BY_P99, &bp);
            bl = brute_leaks_at(c, r->rmse);
            fprintf(md, "| %s | %.4f |", method_names[m], r->rmse);
            if (tr > 0.0)
                fprintf(md, " %.1fx%s |", tr / r->st.cpu, bt ? " ext" : "");
            else
                fprintf(md, " beyond brute force's runs |");
            if (tr > 0.0 && !strcmp(r->method, "trans+rot")) {
                c->gm_log += log(tr / r->st.cpu);
                c->gm_n++;
            }
            fprintf(md, " %.3f |", r->p99);
            if (tp > 0.0)
                fprintf(md, " %.1fx%s |", tp / r->st.cpu, bp ? " ext" : "");
            else
                fprintf(md, " beyond brute force's runs |");
            fprintf(md, " %.0f%% |", 100.0 * r->worst1);
            if (r->noise >= 0.0 && r->rmse > 0.0)
                fprintf(md, " %.4f, %.0f%% |", r->noise, 100.0 * r->noise * r->noise / (r->rmse * r->rmse));
            else
                fprintf(md, " - |");
            fprintf(md, " %d (", r->leaks);
            if (bl >= 0.0)
                fprintf(md, "%.0f) |", bl);
            else
                fprintf(md, "-) |");
            fprintf(md, " %+.2f%% | %llu |\n", 100.0 * r->bias, (unsigned long long)r->st.records);
        }
}

/* One data file per method for gnuplot: time, RMSE. */
void data_files(const ctx *c, const bscene *b, FILE *gp)
{
    int m, i, first = 1;
    fprintf(gp, "set output '" OUT "/%s.png'\nset title '%s (reference noise %.4f); cache: "
                "a = 0.4 .. 0.1, strata by a'\nplot ", b->name, b->name, c->ref_noise);
    for (m = 0; m < NMETHODS; m++) {
        char path[256];
        FILE *f = NULL;
        for (i = 0; i < c->nruns; i++)
            if (!strcmp(c->runs[i].method, methods[m])) {
                if (!f) {
                    snprintf(path, sizeof path, OUT "/%s-%s.dat", b->name, methods[m]);
                    f = fopen(path, "w");
                    if (!f)
                        return;
                }
                /* a blank line between strata grids: separate lines */
                if (i > 0 && !strcmp(c->runs[i - 1].method, methods[m]) &&
                    c->runs[i - 1].m != c->runs[i].m)
                    fprintf(f, "\n");
                fprintf(f, "%g %g\n", c->runs[i].st.cpu, c->runs[i].rmse);
            }
        if (f) {
            fclose(f);
            fprintf(gp, "%s'%s' using 1:2 with linespoints title '%s'", first ? "" : ", ", path,
                    method_names[m]);
            first = 0;
        }
    }
    fprintf(gp, "\n");
}
