#!/bin/sh
# amalgamate.sh PORT VERSION OUT SRC... -- the library as one C file (OUT), for
# hosts that copy one .c and irrcache.h into their tree: the headers of
# src/, then every source file in the order given, then the single-threaded
# port and the chosen one.  Nothing is rewritten but the
# internal includes, which the concatenation makes redundant.
set -eu
port=$1 version=$2 out=$3
shift 3
# The library's own headers, in an order where each follows what it
# includes; their includes of each other are dropped.
HEADERS="src/util.h src/index.h src/kind.h src/cache.h src/strata.h src/sampler.h src/octa.h src/estimator.h src/weight.h src/shrec.h src/snapshot.h src/cells.h"
strip() { grep -v '^#include "\(util\|index\|kind\|cache\|strata\|sampler\|octa\|weight\|estimator\|shrec\|snapshot\|cells\)\.h"' "$1"; }
{
    cat <<HEAD
/*
 * irrcache.c -- irrcache $version in one file, with the $port port.
 * Written by make amalgamation (pkg/amalgamate.sh) from src/ and port/;
 * change those, not this.  Put irrcache.h beside it and compile it like
 * any C file of the host:
 *     cc -std=$( [ "$port" = c11 ] && echo c11 || echo c99 ) -O2 -c irrcache.c
 * The library's internal functions (irc__*) are external symbols here;
 * -fvisibility=hidden keeps them out of a shared object.
 */
HEAD
    [ "$port" = posix ] && printf '#ifndef _POSIX_C_SOURCE\n#define _POSIX_C_SOURCE 200809L\n#endif\n'
    printf '#define IRC_PORT_DEFAULT irc_port_%s\n#include "irrcache.h"\n' "$port"
    for f in $HEADERS "$@" port/none/irc_port.c; do
        printf '\n/* ---- %s ---- */\n' "$f"
        strip "$f"
    done
    if [ "$port" != none ]; then
        printf '\n/* ---- port/%s/irc_port.c ---- */\n' "$port"
        strip "port/$port/irc_port.c"
    fi
    printf '\n/* ---- port/irc_port_default.c ---- */\n'
    strip port/irc_port_default.c
} > "$out"
