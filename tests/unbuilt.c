/*
 * unbuilt.c -- linked with a PORT=none library (make test, stage 1): the
 * ports that build did not compile are defined (port/unbuilt.c), and a
 * cache configured with one is refused with IRC_ERR_PORT (no handle
 * written), while irc_port_none works.  Prints "unbuilt: ok" and exits 0.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "irrcache.h"

static int trace(const irc_trace_args *a)
{
    uint32_t i;
    for (i = 0; i < a->count; i++)
        a->hits[i].status = IRC_RAY_ESCAPED;
    return 0;
}

static int try_port(const irc_port *port, int want)
{
    irc_config cfg;
    irc_cache *c = NULL;
    size_t bytes;
    unsigned char *block;
    int st;
    memset(&cfg, 0, sizeof cfg);
    cfg.version = IRC_CONFIG_VERSION;
    cfg.trace = trace;
    cfg.port = port;
    if (irc_footprint(&cfg, 16, &bytes) != IRC_OK || !(block = calloc(1, bytes)))
        return 1;
    cfg.buffer = block;
    cfg.buffer_size = bytes;
    st = irc_init(&cfg, 16, &c);
    if (st == IRC_OK)
        irc_fini(c);
    free(block);
    if (st != want || (st != IRC_OK && c != NULL)) {
        printf("unbuilt: port %s: irc_init %d (%s), want %d\n", port->name, st,
               irc_strerror(st), want);
        return 1;
    }
    return 0;
}

int main(void)
{
    int bad = try_port(&irc_port_posix, IRC_ERR_PORT) + try_port(&irc_port_c11, IRC_ERR_PORT) +
              try_port(&irc_port_none, IRC_OK);
    if (!bad)
        printf("unbuilt: ok\n");
    return bad != 0;
}
