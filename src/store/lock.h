/*
 * lock.h -- the port's locks as the library takes them (lock.c), so that
 * a writer's death is repaired before anyone reads the block.
 */
#ifndef IRC_LOCK_H
#define IRC_LOCK_H

#include "../base/kind.h"

int irc__write_lock(irc_cache *c);
void irc__write_unlock(irc_cache *c);
int irc__read_lock(irc_cache *c);
void irc__read_unlock(irc_cache *c);
/* Takes the write lock for a call a fill pass forbids: IRC_OK with the
 * lock held, or IRC_ERR_PORT / IRC_ERR_STATE (a pass is open) without. */
int irc__write_lock_idle(irc_cache *c);
/* The caller holds the write lock (or the block is at rest, irc_attach):
 * drops the torn slots and every record that is not sane, and builds the
 * index anew. */
void irc__repair_locked(irc_cache *c);

#endif
