/*
 * config.h -- the config rules (config.c): defaults applied, every field
 * checked, the kind's own fields resolved by its table.
 */
#ifndef IRC_CONFIG_H
#define IRC_CONFIG_H

#include "../util.h" /* first: IRC_EXPERIMENTAL */
#include "irrcache.h"

int irc__config_resolve(const irc_config *in, irc_config *out);
/* A port with every operation set and a lock size a block can hold. */
int irc__port_ok(const irc_port *p);

#endif
