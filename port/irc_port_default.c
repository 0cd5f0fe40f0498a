/*
 * port/irc_port_default.c -- the port that cfg.port = NULL selects: the
 * one the build compiled (make PORT=posix|c11|none passes
 * -DIRC_PORT_DEFAULT=irc_port_PORT).
 */
#include "irrcache.h"

#ifndef IRC_PORT_DEFAULT
#define IRC_PORT_DEFAULT irc_port_posix
#endif

const irc_port *const irc_port_default = &IRC_PORT_DEFAULT;
