/*
 * lookups.c -- one lookup workload, small enough to profile: N trans+rot
 * records on the six faces of a unit box (as bench_core.c builds them),
 * then L lookups in scanline or random order.  The records are inserted
 * in random order, freely (ids scattered in space), with "pass" in one
 * fill pass, whose end lays them out in the index's order (compact.c),
 * or with "morton" freely in Morton order of their positions (ids
 * following a space-filling curve).
 * Prints the lookup rate, the
 * index nodes used per record, the index entries a lookup scans and those
 * that pass the entry test (with "count": a second pass over queries of
 * the same kind, not timed), and the
 * sum of the returned values with 9 digits, so that two builds can be
 * checked for the same answers.
 *
 *   ./build/bench_lookups ORDER L N [pass|morton] [count]   ORDER: scanline | random
 *
 * Instructions per lookup: run it under callgrind with L = 0 and L = 10000
 * and divide the difference by 10000 (bench/notes.md, "Speed and memory").
 */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include "bench_util.h"
#include "box.h"
#include "block/cache.h" /* irc__index_query: entries scanned and passed */
#include "index/index.h"

static unsigned long long rng = 1;




/* A record's position as a 63-bit Morton key: 21 bits an axis of
 * coordinates in [0, 1]. */
static unsigned long long morton(const float p[3])
{
    unsigned long long k = 0;
    uint32_t q[3];
    int b, i;
    for (i = 0; i < 3; i++)
        q[i] = (uint32_t)(p[i] * 2097151.0f);
    for (b = 20; b >= 0; b--)
        for (i = 0; i < 3; i++)
            k = k << 1 | (q[i] >> b & 1u);
    return k;
}

static int by_morton(const void *a, const void *b)
{
    unsigned long long x = morton(((const irc_record *)a)->p), y = morton(((const irc_record *)b)->p);
    return x < y ? -1 : x > y;
}

static void count_passed(void *ud, uint32_t id)
{
    (void)id;
    ++*(unsigned long long *)ud;
}

int main(int argc, char **argv)
{
    irc_config cfg;
    irc_cache *c;
    irc_record r;
    irc_stats st;
    uint32_t count, i;
    long nl, hits = 0;
    unsigned long long scanned = 0, passed = 0;
    double sum = 0.0, t0, t1;
    int scanline, pass = 0, curve = 0, counting = 0, a;
    irc_record *all;
    for (a = 4; a < argc; a++) {
        if (!strcmp(argv[a], "pass"))
            pass = 1;
        else if (!strcmp(argv[a], "morton"))
            curve = 1;
        else if (!strcmp(argv[a], "count"))
            counting = 1;
        else
            break;
    }
    if (argc < 4 || a < argc || (strcmp(argv[1], "scanline") && strcmp(argv[1], "random"))) {
        fprintf(stderr, "usage: %s scanline|random LOOKUPS RECORDS [pass|morton] [count]\n", argv[0]);
        return 2;
    }
    scanline = !strcmp(argv[1], "scanline");
    nl = atol(argv[2]);
    count = (uint32_t)atol(argv[3]);
    if (!(c = box_cache(count, &cfg)) || !(all = malloc(sizeof *all * count))) {
        fprintf(stderr, "bad record count\n");
        return 2;
    }
    if (pass && irc_pass_begin(c) != IRC_OK)
        return 1;
    for (i = 0; i < count; i++) {
        box_record(&rng, count, &r);
        all[i] = r;
    }
    if (curve)
        qsort(all, count, sizeof *all, by_morton);
    for (i = 0; i < count; i++)
        if (irc_cache_insert(c, &all[i]) != IRC_OK)
            return 1;
    free(all);
    if (pass && irc_pass_end(c, NULL) != IRC_OK)
        return 1;
    t0 = bench_now();
    for (i = 0; i < (uint32_t)nl; i++) {
        float p[3], n[3], rgb[3], w;
        box_query(scanline, i, &rng, p, n);
        hits += irc_cache_lookup(c, p, n, rgb, &w) == IRC_OK;
        sum += rgb[0];
    }
    t1 = bench_now();
    for (i = 0; counting && i < (uint32_t)nl; i++) {
        float p[3], n[3];
        box_query(scanline, i, &rng, p, n);
        scanned += irc__index_query(c, p, count_passed, &passed);
    }
    irc_cache_stats(c, &st);
    printf("%s order, %u records (%s): %ld lookups, %ld hits, %.3f M/s, %.3f index nodes a record, "
           "%.1f entries scanned and %.1f passed a lookup, sum %.9g\n", argv[1], count, pass ? "one pass" : curve ? "Morton order" : "free fill", nl, hits,
           nl > 0 ? nl / (t1 - t0) / 1e6 : 0.0, (double)st.index_nodes / count,
           nl > 0 ? (double)scanned / nl : 0.0, nl > 0 ? (double)passed / nl : 0.0, sum);
    free(cfg.buffer);
    return 0;
}
