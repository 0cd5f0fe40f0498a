/*
 * octa.h -- the normal codec (octa.c).
 */
#ifndef IRC_OCTA_H
#define IRC_OCTA_H

#include "irrcache.h"
#include "util.h"
/* octa.c: the normal codec */
uint32_t irc__oct_encode(const float n[3]);
void irc__oct_decode(uint32_t code, float n[3]);
void irc__oct_frame(uint32_t code, float t1[3], float t2[3]);

#endif
