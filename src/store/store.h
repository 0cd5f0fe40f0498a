/*
 * store.h -- records into and out of the pool (store.c).
 */
#ifndef IRC_STORE_H
#define IRC_STORE_H

#include "../base/kind.h"

/* The handle checked (want), the record checked by its kind, then stored
 * (IRC_ERR_FULL when no slot is free and CLOCK is off or a pass is
 * open). */
int irc__insert(irc_cache *c, const irc__kind *want, const void *rec);
/* The same for a caller that checked the handle. */
int irc__insert_checked(irc_cache *c, const void *rec);
/* Record id's contents replaced by rec, which keeps its position, normal
 * and radius (the index is untouched): irc_progress's refinements.  Not
 * concurrent with lookups. */
int irc__store_refresh(irc_cache *c, uint32_t id, const void *rec);
/* The caller holds the write lock: the record in slot id (below count)
 * joins the index, clamped by its neighbours if the config asks. */
void irc__commit_locked(irc_cache *c, uint32_t id);
/* Record id unpacked into out (IRC_MISS past count). */
int irc__record_get(irc_cache *c, const irc__kind *want, uint32_t id, void *out);

#endif
