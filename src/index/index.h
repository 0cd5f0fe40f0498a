/*
 * index.h -- what the index offers the rest of the library: the octree
 * over record reaches (index.c), its walks (query.c) and its compaction
 * into query order (compact.c).  Its layout is layout.h's.
 */
#ifndef IRC_INDEX_H
#define IRC_INDEX_H

#include "../block/form.h"
#include "../util.h"
#include "irrcache.h"
/* index.c */
/* Called with each candidate: a superset of the records the query asks
 * for, which the caller tests exactly. */
typedef void (*irc__visit_fn)(void *ud, uint32_t id);
void irc__index_reset(irc_cache *c);
void irc__index_insert(irc_cache *c, uint32_t id);
void irc__index_remove(irc_cache *c, uint32_t id);
/* After record id's radius shrank: its references' reach bounds from the
 * radius now (nodes and list order kept, so lookups are unchanged). */
void irc__index_tighten(irc_cache *c, uint32_t id);
void irc__index_compact(irc_cache *c); /* compact.c */
/* compact.c: the lists laid out as runs again when a quarter as many
 * references have been taken since they last were as they hold (records
 * not moved). */
void irc__index_tidy(irc_cache *c);
/* compact.c: the index emptied (records kept); the records [0, count)
 * inserted into an empty index in a scattered order. */
void irc__index_clear(irc_cache *c);
void irc__index_rebuild(irc_cache *c);
/* compact.c, the caller holding the write lock: forget drops the index,
 * the list links and CLOCK's bits, keeping the records; clear drops the
 * records too. */
void irc__forget_locked(irc_cache *c);
void irc__clear_locked(irc_cache *c);
/* query.c.  Returns the references it scanned (the work; tests check it). */
uint32_t irc__index_query(const irc_cache *c, const float p[3], irc__visit_fn fn,
                          void *ud);
/* 1 if a block's root cube is one the index could have made (life.c's
 * header check of a set root), else 0. */
int irc__index_root_sane(const irc_cache *c);
int irc__root_ok(const double c[3], double h); /* the same test of a centre and half edge */
void irc__index_range(const irc_cache *c, const float p[3], float range, irc__visit_fn fn,
                      void *ud);

#endif
