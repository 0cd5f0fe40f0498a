/*
 * slots.h -- the threads' scratch slots (slots.c).
 */
#ifndef IRC_SLOTS_H
#define IRC_SLOTS_H

#include "../base/kind.h"

/* Claims a scratch slot (waiting unless cfg.no_wait; IRC_OK or
 * IRC_ERR_BUSY; *waited set when it waited). */
int irc__slot_claim(irc_cache *c, uint32_t *t, int *waited);
/* Gives slot t back zeroed. */
void irc__slot_release(irc_cache *c, uint32_t t);

#endif
