/*
 * port/irc_port_default.c -- the port that cfg.port = NULL selects.  Pick
 * another at build time with -DIRC_PORT_DEFAULT=irc_port_c11 (or
 * irc_port_none for a build without threads).
 */
#include "irrcache.h"

#ifndef IRC_PORT_DEFAULT
#define IRC_PORT_DEFAULT irc_port_posix
#endif

const irc_port *const irc_port_default = &IRC_PORT_DEFAULT;
