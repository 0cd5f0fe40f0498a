#!/bin/sh
# amalgamate.sh PORT VERSION OUT SRC... -- the library as one C file (OUT), for
# hosts that copy one .c and irrcache.h into their tree: the headers of
# src/, then every source file in the order given (the Makefile's SRC),
# then the single-threaded port and the chosen one.
#
# Two rewrites, nothing else: the internal includes go (the concatenation
# makes them redundant), and the library's internals (irc__*) get internal
# linkage, as Lua's onelua.c gives its LUAI_FUNC functions: a header's
# declaration of an internal function becomes static (its definition then
# has internal linkage too, C99 6.2.2), and an internal object is static at
# its declaration and its definition.  tests/amalgamation.sh checks that the
# object exports irc_ names only.
set -eu
port=$1 version=$2 out=$3
shift 3

# The headers in an order where each follows the library headers it
# includes (src/*.h and src/*/*.h, includes relative to the includer).
inc_of() { # HEADER: the library headers it includes, as paths from the root
    d=$(dirname "$1")
    sed -n 's/^#include "\(.*\)"$/\1/p' "$1" | while read -r i; do
        p=$(cd "$d/$(dirname "$i")" 2>/dev/null && pwd)/$(basename "$i")
        p=${p#"$ROOT"/}
        [ -f "$p" ] && case $p in src/*) echo "$p" ;; esac
    done
    return 0
}
ROOT=$(pwd)
left=$(ls src/*.h src/*/*.h)
HEADERS=
while [ -n "$left" ]; do
    rest= moved=0
    for h in $left; do
        ready=1
        for i in $(inc_of "$h"); do
            case " $HEADERS " in *" $i "*) ;; *) ready=0 ;; esac
        done
        if [ $ready = 1 ]; then HEADERS="$HEADERS $h"; moved=1; else rest="$rest $h"; fi
    done
    [ $moved = 1 ] || { echo "amalgamate.sh: headers include each other:$rest" >&2; exit 1; }
    left=$rest
done

strip() { grep -v '^#include "' "$1" | grep -v '^#include "irrcache.h"' || true; }
# Internal functions declared in a header (a line that starts with a type
# and names irc__something followed by a parenthesis), and extern objects.
internal_decls() {
    sed -E -e 's/^((const )?[a-z_0-9]+( \*| )+irc__[a-z_0-9]+\()/static \1/' \
           -e 's/^extern (const [a-z_0-9]+ irc__[a-z_0-9]+)/static \1/'
}
# An internal object's definition.
internal_defs() {
    sed -E 's/^(const [a-z_0-9]+ irc__[a-z_0-9]+ = )/static \1/'
}
{
    cat <<HEAD
/*
 * irrcache.c -- irrcache $version in one file, with the $port port.
 * Written by make amalgamation (pkg/amalgamate.sh) from src/ and port/;
 * change those, not this.  Put irrcache.h beside it and compile it like
 * any C file of the host:
 *     cc -std=$( [ "$port" = c11 ] && echo c11 || echo c99 ) -O2 -c irrcache.c
 * Only the irc_ calls of irrcache.h leave the object: the library's
 * internals (irc__*) are static here.
 */
HEAD
    [ "$port" = posix ] && printf '#ifndef _POSIX_C_SOURCE\n#define _POSIX_C_SOURCE 200809L\n#endif\n'
    # the library defines the experimental calls: it sees their declarations
    printf '#define IRC_EXPERIMENTAL\n#define IRC_PORT_DEFAULT irc_port_%s\n#include "irrcache.h"\n' "$port"
    for f in $HEADERS; do
        printf '\n/* ---- %s ---- */\n' "$f"
        strip "$f" | internal_decls
    done
    for f in "$@" port/none/irc_port.c; do
        printf '\n/* ---- %s ---- */\n' "$f"
        strip "$f" | internal_defs
    done
    if [ "$port" != none ]; then
        printf '\n/* ---- port/%s/irc_port.c ---- */\n' "$port"
        strip "port/$port/irc_port.c"
    fi
    printf '\n/* ---- port/irc_port_default.c ---- */\n'
    strip port/irc_port_default.c
    printf '\n/* ---- port/unbuilt.c ---- */\n'
    case $port in posix) printf '#define IRC_BUILT_POSIX\n' ;; c11) printf '#define IRC_BUILT_C11\n' ;; esac
    strip port/unbuilt.c
} > "$out"
