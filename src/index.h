/*
 * index.h -- the octree over record positions (index.c) and its
 * compaction into query order (compact.c).
 */
#ifndef IRC_INDEX_H
#define IRC_INDEX_H

#include "irrcache.h"
#include "util.h"
/* Octree node.  Its cube is implied by the path from the root.  12 bytes. */
typedef struct irc__node {
    uint32_t child;  /* first of 8 consecutive children, 0 = leaf */
    uint32_t head;   /* first record stored at this node (IRC__NIL = none) */
    float reach;     /* largest a*R_i of any record in this subtree */
} irc__node;

/* The deepest node below the root, growth included: a root that grows
 * makes every node one deeper, and refuses to once that would pass this
 * (records then stay in the root's list); a walk's stack holds a frame a
 * level (index.c, compact.c). */
#define IRC__LEVELS 48

/* A record's entry in the index, by id: its list link and its position and
 * reach a*R_i quantized against the cube (centre c, half edge h) of the
 * node whose list holds it, in steps of 2h/65535.  A query tests these
 * before it touches the record, and most candidates fail the test: it
 * reads 12 bytes, not a record's line.  Entries sit at their records'
 * ids, so one lookup's entries share lines only as far as their ids are
 * near: after a pass's end each list is a run of ids (compact.c).  12
 * bytes. */
#define IRC__IX_ANY 0xffffu  /* rq: no bound in this cube's steps (a root
                                record outside the cube, or a reach of
                                2h or more): always a candidate */
typedef struct irc__ixe {
    uint16_t q[3];   /* (x - (c - h)) / step, rounded to nearest */
    uint16_t rq;     /* reach / step, rounded up */
    uint32_t next;   /* next record in the same list, IRC__NIL = last */
} irc__ixe;

/* index.c */
/* Called with each candidate: a superset of the records the query asks
 * for, which the caller tests exactly. */
typedef void (*irc__visit_fn)(void *ud, uint32_t id);
void irc__index_reset(irc_cache *c);
void irc__index_insert(irc_cache *c, uint32_t id);
void irc__index_remove(irc_cache *c, uint32_t id);
void irc__index_compact(irc_cache *c); /* compact.c */
/* compact.c: the index emptied (records kept); the records [0, count)
 * inserted into an empty index in a scattered order. */
void irc__index_clear(irc_cache *c);
void irc__index_rebuild(irc_cache *c);
/* Returns the index entries it scanned (the work; tests check it). */
uint32_t irc__index_query(const irc_cache *c, const float p[3], irc__visit_fn fn,
                          void *ud);
/* 1 if a block's root cube is one the index could have made (layout.c's
 * header check of a set root), else 0. */
int irc__index_root_sane(const irc_cache *c);
void irc__index_range(const irc_cache *c, const float p[3], float range, irc__visit_fn fn,
                      void *ud);

#endif
