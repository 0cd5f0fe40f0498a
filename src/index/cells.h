/*
 * cells.h -- the index's cells and pools (cells.c), for index.c.
 */
#ifndef IRC_CELLS_H
#define IRC_CELLS_H

#include "../base/kind.h"
#include "layout.h"

#define IRC__ONE ((int64_t)1 << 58) /* the root's edge in integer units */

typedef struct irc__cube {
    double c[3];
    double h; /* half the edge */
} irc__cube;

/* A record's box in integer units (inside: within the root), and the
 * cell point of its position. */
typedef struct irc__box {
    int64_t lo[3], hi[3], at[3];
    int inside;
} irc__box;

/* A node met on a walk at some depth: its index and low corner. */
typedef struct irc__cell {
    uint32_t node;
    int64_t lo[3];
} irc__cell;

void irc__node_empty(irc__node *n);
void irc__root_cube(const irc_cache *c, irc__cube *q);
/* The cube of the cell of depth d with low corner lo (units). */
void irc__cell_cube(const irc_cache *c, const int64_t lo[3], int d, irc__cube *q);
/* The half edge of the box a record of this reach is placed by. */
double irc__half(const float p[3], double reach);
/* The box clipped to the root (inside: it needed no clipping). */
void irc__box_of(const irc_cache *c, const float p[3], double half, irc__box *b);
/* The deepest level, at most cap, whose cells are as wide as the box. */
int irc__level(const irc_cache *c, double half, int cap);
void irc__quantize(irc__ref *e, const irc__cube *q, const float p[3], double reach);
/* The reach record id's references bound: a R now (no more than placed). */
double irc__reach_now(const irc_cache *c, uint32_t id);
/* References an insertion may take beyond the one kept for it. */
uint32_t irc__spare(const irc_cache *c);
void irc__ref_give(irc_cache *c, uint32_t r);
/* A new reference to id at the head of node's list, whose cube is q. */
void irc__ref_push(irc_cache *c, uint32_t node, const irc__cube *q, uint32_t id, int home);
/* Calls fn on the nodes a box overlaps down to depth L: every one (all
 * set) or the leaves above L and the nodes of depth L. */
typedef void (*irc__cell_fn)(irc_cache *c, const irc__cell *x, int d, void *ud);
void irc__cover(irc_cache *c, const irc__box *b, int L, int all, irc__cell_fn fn, void *ud);
/* Whether cell x of depth d holds the cell point at. */
int irc__holds(const irc__cell *x, int d, const int64_t at[3]);
uint32_t irc__list_len(const irc_cache *c, uint32_t r, uint32_t limit);
/* A block of 8 empty nodes, 0 when the pool has none. */
uint32_t irc__block_alloc(irc_cache *c);
/* The children of cell x (depth d) that box b overlaps, as bits. */
unsigned irc__overlapped(const irc__cell *x, int d, const irc__box *b);
unsigned irc__popcount(unsigned m);

#endif
