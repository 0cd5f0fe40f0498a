/* share.h -- what the tests of a cache shared between processes have in
 * common (t_share.c, t_kill.c). */
#ifndef IRC_TEST_SHARE_H
#define IRC_TEST_SHARE_H

#include "irrcache.h"

/* The lattice the processes fill: SHARE_SIDE x SHARE_SIDE points 0.2
 * apart on the plane z = 0 of scene_sphere_plane, normals +z. */
#define SHARE_SIDE 30

void share_nap(void); /* a millisecond */
/* Lookup-or-compute over half 0 (x < 0) or half 1 (x >= 0) of the
 * lattice, a shared column at x = 0; returns failed calls. */
int share_fill_half(irc_cache *c, int half);
/* Every stored record equals a fresh record computed at its query, and a
 * lookup there finds it; returns failures. */
int share_verify_all(irc_cache *c);

#endif
