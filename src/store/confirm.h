/*
 * confirm.h -- confirming rays (confirm.c, cfg.check_visibility): which of a
 * lookup's records are out of the query's sight.
 */
#ifndef IRC_CONFIRM_H
#define IRC_CONFIRM_H

#include "../base/kind.h"

#define IRC__SIGHT_CAP 32u   /* records checked per lookup; more: unchecked */
#define IRC__SIGHT_BATCH 8u  /* rays per callback call, at most */

/* Rays from k->q.p toward records ids[first .. first + n - 1], at pos
 * with coded normals nrm (n <= IRC__SIGHT_BATCH); the hidden ones' ids
 * move to the front of ids, k->q.n_hidden counting them. */
int irc__confirm_batch(irc__call *k, uint32_t *ids, uint32_t first, uint32_t n,
                     const float (*pos)[3], const uint32_t *nrm);
/* After the batches: the hidden ids sorted and handed to the query
 * (k->q.hidden), for the find to leave out. */
void irc__confirm_hide(irc__call *k, uint32_t *ids);

#endif
