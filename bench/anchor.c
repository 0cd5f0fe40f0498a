/*
 * anchor.c -- the lookup anchor: bench_lookups' records and queries
 * answered by a baseline written here after pbrt-v2's irradiance cache
 * (an octree that keeps a reference to a record in every node its reach
 * box overlaps, down to nodes no larger than the box; a lookup follows the
 * one root-to-leaf path through the query and tests every reference on
 * it), with irrcache's own weight and extrapolation, so that both accept
 * the same records.  The records are the ones irrcache stored (read back
 * with irc_cache_record after the fill: the radii it kept).
 *
 *   ./build/bench_anchor ORDER L N [pass]    ORDER: scanline | random
 *
 * Prints, for irrcache and the baseline, lookups a second, hits, records
 * accepted a lookup (the baseline's) and the sums of the answers; exits 1
 * when both ran and their hits differ or their sums differ by more than
 * float rounding (then they did not do the same work).  Instructions a lookup:
 * callgrind with L = 0 and L = 100000, the difference over 100000, with
 * BENCH_ANCHOR=irrcache or baseline to run one side alone (bench/anchor.sh,
 * make bench-anchor).
 */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "bench_util.h"
#include "box.h"

#define MAX_DEPTH 16

typedef struct ref_list {
    uint32_t *id;
    uint32_t n, cap;
} ref_list;

typedef struct onode {
    int32_t child[8]; /* node index, -1 none */
    ref_list refs;
} onode;

typedef struct octree {
    onode *nodes;
    uint32_t n, cap;
    float lo[3], hi[3];
    const irc_record *rec;
    float a;
} octree;

static unsigned long long rng = 1;

static int32_t node_new(octree *t)
{
    int k;
    if (t->n == t->cap) {
        t->cap = t->cap ? 2 * t->cap : 1024;
        t->nodes = realloc(t->nodes, sizeof *t->nodes * t->cap);
        if (!t->nodes)
            exit(2);
    }
    for (k = 0; k < 8; k++)
        t->nodes[t->n].child[k] = -1;
    memset(&t->nodes[t->n].refs, 0, sizeof t->nodes[t->n].refs);
    return (int32_t)t->n++;
}

static void ref_push(ref_list *l, uint32_t id)
{
    if (l->n == l->cap) {
        l->cap = l->cap ? 2 * l->cap : 4;
        l->id = realloc(l->id, sizeof *l->id * l->cap);
        if (!l->id)
            exit(2);
    }
    l->id[l->n++] = id;
}

/* pbrt-v2's rule: a reference lives in the first nodes on the way down
 * whose diagonal is below the box's (or at the depth limit), in every
 * child the box overlaps. */
static void add(octree *t, int32_t node, const float nlo[3], const float nhi[3],
                const float blo[3], const float bhi[3], float diag2, int depth, uint32_t id)
{
    float mid[3], d2 = 0.0f;
    int k, i;
    for (i = 0; i < 3; i++) {
        d2 += (nhi[i] - nlo[i]) * (nhi[i] - nlo[i]);
        mid[i] = 0.5f * (nlo[i] + nhi[i]);
    }
    if (depth == MAX_DEPTH || d2 < diag2) {
        ref_push(&t->nodes[node].refs, id);
        return;
    }
    for (k = 0; k < 8; k++) {
        float clo[3], chi[3];
        int overlap = 1;
        for (i = 0; i < 3; i++) {
            clo[i] = (k >> i & 1) ? mid[i] : nlo[i];
            chi[i] = (k >> i & 1) ? nhi[i] : mid[i];
            overlap &= blo[i] <= chi[i] && bhi[i] >= clo[i];
        }
        if (!overlap)
            continue;
        if (t->nodes[node].child[k] < 0) {
            const int32_t c = node_new(t); /* may move t->nodes */
            t->nodes[node].child[k] = c;
        }
        add(t, t->nodes[node].child[k], clo, chi, blo, bhi, diag2, depth + 1, id);
    }
}

/* irrcache's weight and extrapolation (src/weight.c): within reach a R,
 * facing, not in front by more than 5% of R, Ward's error below a; E plus
 * the translational gradient along the offset, clamped at 0. */
static void visit(const octree *t, const ref_list *l, const float p[3], const float n[3],
                  double acc[4], unsigned long long *accepted)
{
    uint32_t j;
    for (j = 0; j < l->n; j++) {
        const irc_record *r = &t->rec[l->id[j]];
        const float dx = p[0] - r->p[0], dy = p[1] - r->p[1], dz = p[2] - r->p[2];
        const float d2 = dx * dx + dy * dy + dz * dz, rad = r->radius;
        float nn, ex, ey, ez, e, w;
        int ch;
        if (!(d2 < t->a * t->a * rad * rad || d2 == 0.0f))
            continue;
        nn = n[0] * r->n[0] + n[1] * r->n[1] + n[2] * r->n[2];
        if (nn <= 0.0f ||
            0.5f * (dx * (n[0] + r->n[0]) + dy * (n[1] + r->n[1]) + dz * (n[2] + r->n[2])) <
                -0.05f * rad)
            continue;
        ex = n[0] - r->n[0];
        ey = n[1] - r->n[1];
        ez = n[2] - r->n[2];
        e = sqrtf(d2) / rad + sqrtf(0.5f * (ex * ex + ey * ey + ez * ez));
        if (!(e < t->a))
            continue;
        w = e > 1e-6f ? 1.0f / e : 1e6f;
        for (ch = 0; ch < 3; ch++) {
            const float *g = r->grad_t[ch];
            const float v = r->e[ch] + dx * g[0] + dy * g[1] + dz * g[2];
            acc[ch] += w * (v > 0.0f ? v : 0.0f);
        }
        acc[3] += w;
        ++*accepted;
    }
}

/* One path from the root to the leaf that holds p. */
static int lookup(const octree *t, const float p[3], const float n[3], float rgb[3],
                  unsigned long long *accepted)
{
    float lo[3], hi[3];
    double acc[4] = {0, 0, 0, 0};
    int32_t node = 0;
    int i;
    for (i = 0; i < 3; i++) {
        if (p[i] < t->lo[i] || p[i] > t->hi[i])
            return 0;
        lo[i] = t->lo[i];
        hi[i] = t->hi[i];
    }
    while (node >= 0) {
        const onode *o = &t->nodes[node];
        int k = 0;
        visit(t, &o->refs, p, n, acc, accepted);
        for (i = 0; i < 3; i++) {
            const float mid = 0.5f * (lo[i] + hi[i]);
            if (p[i] >= mid) {
                k |= 1 << i;
                lo[i] = mid;
            } else {
                hi[i] = mid;
            }
        }
        node = o->child[k];
    }
    for (i = 0; i < 3; i++)
        rgb[i] = acc[3] > 0.0 ? (float)(acc[i] / acc[3]) : 0.0f;
    return acc[3] > 0.0;
}

static int wanted(const char *side)
{
    const char *e = getenv("BENCH_ANCHOR");
    return !e || !*e || !strcmp(e, side);
}

int main(int argc, char **argv)
{
    irc_config cfg;
    irc_cache *c;
    irc_record r, *kept;
    octree t;
    uint32_t count, i, nk = 0;
    long nl, hit[2] = {-1, -1};
    int scanline, pass, k;
    double sums[2] = {0.0, 0.0};
    if (argc < 4 || argc > 5 || (strcmp(argv[1], "scanline") && strcmp(argv[1], "random")) ||
        (argc == 5 && strcmp(argv[4], "pass"))) {
        fprintf(stderr, "usage: %s scanline|random LOOKUPS RECORDS [pass]\n", argv[0]);
        return 2;
    }
    scanline = !strcmp(argv[1], "scanline");
    nl = atol(argv[2]);
    count = (uint32_t)atol(argv[3]);
    pass = argc == 5;
    if (!(c = box_cache(count, &cfg)) || !(kept = malloc(sizeof *kept * count))) {
        fprintf(stderr, "bad record count\n");
        return 2;
    }
    if (pass && irc_pass_begin(c) != IRC_OK)
        return 1;
    /* bench/lookups.c's fill, record for record */
    for (i = 0; i < count; i++) {
        box_record(&rng, count, &r);
        if (irc_cache_insert(c, &r) != IRC_OK)
            return 1;
    }
    if (pass && irc_pass_end(c, NULL) != IRC_OK)
        return 1;
    for (i = 0; i < count; i++)
        if (irc_cache_record(c, i, &kept[nk]) == IRC_OK)
            nk++;

    memset(&t, 0, sizeof t);
    t.rec = kept;
    t.a = cfg.accuracy;
    for (k = 0; k < 3; k++) {
        t.lo[k] = -0.01f;
        t.hi[k] = 1.01f;
    }
    node_new(&t);
    for (i = 0; i < nk; i++) {
        const float e = t.a * kept[i].radius;
        float blo[3], bhi[3];
        for (k = 0; k < 3; k++) {
            blo[k] = kept[i].p[k] - e;
            bhi[k] = kept[i].p[k] + e;
        }
        add(&t, 0, t.lo, t.hi, blo, bhi, 12.0f * e * e, 0, i);
    }

    for (k = 0; k < 2; k++) {
        const char *side = k ? "baseline" : "irrcache";
        unsigned long long accepted = 0, refs = 0;
        long hits = 0;
        double sum = 0.0, t0, t1;
        if (!wanted(side))
            continue;
        rng = 99; /* the same random queries on both sides */
        t0 = bench_now();
        for (i = 0; i < (uint32_t)nl; i++) {
            float p[3], n[3], rgb[3] = {0, 0, 0}, w;
            box_query(scanline, i, &rng, p, n);
            if (k)
                hits += lookup(&t, p, n, rgb, &accepted);
            else
                hits += irc_cache_lookup(c, p, n, rgb, &w) == IRC_OK;
            sum += rgb[0];
        }
        t1 = bench_now();
        for (i = 0; k && i < t.n; i++)
            refs += t.nodes[i].refs.n;
        printf("%s order, %u records (%s), %s: %ld lookups, %ld hits, %.3f M/s", argv[1], nk,
               pass ? "one pass" : "free fill", side, nl, hits,
               nl > 0 && t1 > t0 ? nl / (t1 - t0) / 1e6 : 0.0);
        if (k) {
            printf(", %.2f records accepted a lookup, %u nodes, %.2f references a record",
                   nl > 0 ? (double)accepted / nl : 0.0, t.n, (double)refs / nk);
        } else {
            irc_stats st;
            if (irc_cache_stats(c, &st) == IRC_OK)
                printf(", %llu of %llu nodes, %.2f references a record (of %.2f)",
                       (unsigned long long)st.index_nodes, (unsigned long long)st.index_nodes_max,
                       (double)st.index_refs / nk, (double)st.index_refs_max / nk);
        }
        printf(", sum %.9g\n", sum);
        sums[k] = sum;
        hit[k] = hits;
    }
    for (i = 0; i < t.n; i++)
        free(t.nodes[i].refs.id);
    free(t.nodes);
    free(kept);
    free(cfg.buffer);
    /* Both sides ran: the same hits, and sums equal to float rounding, or
     * the comparison is not of the same work. */
    if (hit[0] >= 0 && hit[1] >= 0 &&
        (hit[0] != hit[1] || fabs(sums[0] - sums[1]) > 1e-6 * (fabs(sums[0]) + 1.0))) {
        fprintf(stderr, "anchor: the two sides answered differently\n");
        return 1;
    }
    return 0;
}
