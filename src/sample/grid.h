/*
 * grid.h -- a grid of strata and its table (grid.c).
 */
#ifndef IRC_GRID_H
#define IRC_GRID_H

#include "../base/kind.h"

/* A grid of strata: M rows in theta, N columns in phi, and its table of
 * angles and weights.  Level 0 is the configured grid; level l halves M
 * and N l times, for records that serve few pixels (irradiance.c,
 * "Records that cost what they serve"). */
#define IRC__GRIDS 3u
typedef struct irc__grid {
    uint32_t m, nphi, strata, level;
    const float *tab;
} irc__grid;

/* The gradients' rows of per-column values are padded to a multiple of 4
 * plus 4, so that their loops run in blocks of four (which compilers turn
 * into vector operations) and column N can stand for column 0. */
static inline uint32_t irc__pad4(uint32_t nphi)
{
    return (nphi + 3u) / 4u * 4u + 4u;
}

/* The grids a config's M x N strata coarsen to (level 0 the configured
 * one). */
uint32_t irc__grid_levels(uint32_t m, uint32_t nphi);
/* Bytes of every level's table, and the tables made in tab: at init, from
 * the config alone. */
uint64_t irc__gtab_bytes(uint32_t m, uint32_t nphi);
void irc__gtab_fill(uint32_t m, uint32_t nphi, void *tab);
/* Grid `level` of the cache's config, its table in the block. */
void irc__grid_at(const irc_cache *c, uint32_t level, irc__grid *g);

#endif
