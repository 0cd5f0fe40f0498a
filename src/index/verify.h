/*
 * verify.h -- whether a block's records and index are ones a cache could
 * have made (verify.c), before irc_attach or irc_join trusts them.
 */
#ifndef IRC_VERIFY_H
#define IRC_VERIFY_H

#include "../base/kind.h"

/* Every link in bounds and every walk finite. */
int irc__block_sane(const irc_cache *c);
/* A record's head as a cache could have made it (finite p and E, E >= 0,
 * R > 0, a free point only in a kind that has them); the snapshot reader
 * checks decoded heads with it too. */
int irc__rec_head_sane(const irc_cache *c, const irc__rec *r);
/* Record id whole: its head and its parts. */
int irc__rec_sane(const irc_cache *c, uint32_t id);
/* The parts after a record's head as the part table says a cache makes
 * them; rec in the block's byte order, or (le) a snapshot's. */
int irc__parts_sane(const irc_cache *c, const unsigned char *rec, int le);

#endif
