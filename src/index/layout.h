/*
 * layout.h -- the index's nodes, references and entries as the block holds
 * them, and where they lie (the index's own files, verification, and the
 * sizes life.c and irc_cache_stats report).
 */
#ifndef IRC_LAYOUT_H
#define IRC_LAYOUT_H

#include "../block/form.h"

/* Octree node.  Its cube is implied by the path from the root.  12 bytes. */
typedef struct irc__node {
    uint32_t child;  /* first of 8 consecutive children, 0 = leaf */
    uint32_t head;   /* first reference in this node's list, IRC__NIL = none */
    float reach;     /* largest reach a*R_i of a record whose home lies in
                        this subtree (-1: none); range walks prune by it */
} irc__node;

/* The deepest node below the root, growth included: a root that grows
 * makes every node one deeper, and refuses to once that would pass this
 * (records then stay in the root's list); a walk's stack holds a frame a
 * level (index.c, query.c, compact.c). */
#define IRC__LEVELS 48

/* A reference to a record in the list of a node whose cube its reach's box
 * overlaps (index.c).  The record's position and reach a*R_i quantized
 * against the node's cube widened to twice its edge (centre c, half edge
 * h: [c - 2h, c + 2h] in steps of 4h/65535), which holds the position of
 * every record placed in it by its level, so that a lookup tests these 8
 * bytes and touches the record only when they pass.  16 bytes. */
#define IRC__IX_ANY 0xffffu  /* rq: no bound in the cube's steps (a root
                                reference to a record outside the frame,
                                or a reach of 4h or more): always a
                                candidate */
#define IRC__REF_HOME 0x80000000u /* id: the reference in the node whose cube
                                     holds the record's position, the one
                                     range walks take */
typedef struct irc__ref {
    uint16_t q[3];   /* (x - (c - 2h)) / step, rounded to nearest */
    uint16_t rq;     /* reach / step, rounded up */
    uint32_t id;     /* the record, | IRC__REF_HOME for its home */
    uint32_t next;   /* next reference in the list, IRC__NIL = last */
} irc__ref;

/* A record's index entry, by id: the reach its references were placed for
 * (clamping may shrink its radius since; removal finds them by this) and
 * how many it has (0: not indexed).  8 bytes. */
typedef struct irc__ixe {
    float reach;
    uint32_t refs;
} irc__ixe;

/* The index's parts of the block (form.h's offsets). */
static inline irc__ixe *irc__ix(const irc_cache *c)
{
    return (irc__ixe *)(void *)irc__part(c, c->o_ix);
}
static inline irc__node *irc__nodes(const irc_cache *c)
{
    return (irc__node *)(void *)irc__part(c, c->o_nodes);
}
static inline irc__ref *irc__refs(const irc_cache *c)
{
    return (irc__ref *)(void *)irc__part(c, c->o_refs);
}

#endif
