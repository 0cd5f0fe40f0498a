/*
 * torn.h -- slots being written named in the block (torn.c), for the
 * repair after a writer's death.
 */
#ifndef IRC_TORN_H
#define IRC_TORN_H

#include "../base/kind.h"

/* A word of the block set with release order: what follows is not
 * written before it. */
void irc__set(irc_cache *c, uint64_t *w, uint64_t v);
/* Slots a and b (b IRC__NIL for one slot) are about to be written. */
void irc__mark(irc_cache *c, uint32_t a, uint32_t b);
void irc__unmark(irc_cache *c);
/* Records i and j exchanged in place, both named while they move. */
void irc__rec_swap(irc_cache *c, uint32_t i, uint32_t j);

#endif
