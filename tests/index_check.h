/* index_check.h -- the index held against a scan of every record
 * (t_index.c), for the tests of other files that build an index. */
#ifndef IRC_TEST_INDEX_CHECK_H
#define IRC_TEST_INDEX_CHECK_H

#include "irrcache.h"

/* Inserts `count` random records: positions in clusters whose scales
 * range over `decades` decades, radii log-uniform. */
void index_fill(irc_cache *c, uint32_t count, int decades, unsigned long long *st);
/* Queries the index and a scan of all records, comparing ids exactly and
 * values to float rounding (one failed CHECK for all).  Returns the
 * number of queries that found any record. */
uint32_t index_compare(irc_cache *c, uint32_t queries, int decades, unsigned long long *st);

/* Depth first, as queries visit: each list must be the run of references
 * that follows the previous list's, and each record's id the order of its
 * home reference.  index_runs_check returns the references seen; bad
 * counts references and homes out of order. */
typedef struct index_runs {
    uint32_t ref, home, bad;
} index_runs;
struct irc__node;
uint32_t index_runs_check(const irc_cache *c, const struct irc__node *n, index_runs *k);

#endif
