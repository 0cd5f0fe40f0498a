#!/bin/sh
# amalgamation.sh -- the one-file library (make amalgamation): it compiles
# alone as C99 without a warning (gcc and clang, posix and none ports) and
# exports the public calls only, the example hosts built on it print what
# the normal build's print, and its object is the library's size (within
# 5% of the archive's objects).
# AMALG_QUICK=1 (make check): gcc and the posix port only, the minimal
# example's output, no size.
set -eu
cd "$(dirname "$0")/.."
MAKE=${MAKE:-make}
B=build/amalg-test
W="-std=c99 -Wall -Wextra -Wpedantic -Wshadow -Wmissing-prototypes -Wdouble-promotion -Werror -fno-math-errno"
QUICK=${AMALG_QUICK:-0}
mkdir -p $B
ports="posix none"
ccs="gcc clang"
[ "$QUICK" = 1 ] && { ports=posix; ccs=gcc; }
for port in $ports; do
    $MAKE -s BUILD=$B/$port PORT=$port amalgamation
    for cc in $ccs; do
        $cc $W -O2 -I$B/$port/amalgamation -c $B/$port/amalgamation/irrcache.c -o $B/$port/irrcache-$cc.o
    done
done
A=$B/posix/amalgamation
# Only the public calls leave the object: every internal has internal
# linkage (pkg/amalgamate.sh).
leaked=$(nm -g --defined-only $B/posix/irrcache-gcc.o | awk '{ print $3 }' | grep -v '^irc_[a-z]' || true)
[ -z "$leaked" ] || { echo "amalgamation: exports more than irc_ calls:"; echo "$leaked" | head; exit 1; }
if [ "$QUICK" = 1 ]; then
    $MAKE -s BUILD=build build/minimal
    cc -std=c99 -O2 -I$A examples/minimal.c $B/posix/irrcache-gcc.o -o $B/minimal -lm -lpthread
    ./build/minimal > $B/minimal.lib.txt
    $B/minimal > $B/minimal.amalg.txt
    cmp -s $B/minimal.lib.txt $B/minimal.amalg.txt || { echo "minimal: the amalgamation's output differs"; exit 1; }
    echo "amalgamation: $(wc -l < $A/irrcache.c) lines; builds alone, minimal prints what the library's does"
    exit 0
fi
$MAKE -s BUILD=build build/minimal build/passes
cc -std=c99 -O2 -I$A examples/minimal.c $B/posix/irrcache-gcc.o -o $B/minimal -lm -lpthread
cc -std=c99 -O2 -D_POSIX_C_SOURCE=200809L -I$A examples/passes.c $B/posix/irrcache-gcc.o -o $B/passes -lm -lpthread
cc -std=c99 -O2 -D_POSIX_C_SOURCE=200809L -I$A examples/threads.c $B/posix/irrcache-gcc.o -o $B/threads -lm -lpthread
for e in minimal passes; do
    ./build/$e > $B/$e.lib.txt
    $B/$e > $B/$e.amalg.txt
    cmp -s $B/$e.lib.txt $B/$e.amalg.txt || { echo "$e: the amalgamation's output differs"; diff $B/$e.lib.txt $B/$e.amalg.txt | head; exit 1; }
done
$B/threads > $B/threads.amalg.txt
grep -q ", 0 errors" $B/threads.amalg.txt || { echo "threads: errors"; exit 1; }
# Size: the amalgamation's text against the same code built file by file.
rm -rf $B/lib
$MAKE -s BUILD=$B/lib OPT=-O2 lib
text() { size "$@" | awk 'NR > 1 { t += $1 } END { print t }'; }
one=$(text $B/posix/irrcache-gcc.o)
many=$(text $B/lib/src/*.o $B/lib/src/*/*.o $B/lib/port/*.o $B/lib/port/*/*.o)
echo "amalgamation: $(wc -l < $A/irrcache.c) lines; text $one bytes in one object, $many in the library's"
awk -v a="$one" -v b="$many" 'BEGIN { exit !(a <= 1.05 * b && a >= 0.80 * b) }' ||
    { echo "amalgamation: its size is not the library's"; exit 1; }
