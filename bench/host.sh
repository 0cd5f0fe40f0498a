#!/bin/sh
# host.sh HOST [COMMIT] -- what make bench-host runs: bench/host.c's path
# tracer against this tree's library, then (with COMMIT) the same host
# built against the library and header of that commit (git archive into
# build/before-COMMIT, make lib there), with the same arguments
# (HOST_ARGS: width height samples reference_samples).
set -e
host=$1
# shellcheck disable=SC2086
"$host" $HOST_ARGS
[ -n "$2" ] || exit 0
d=build/before-$2
rm -rf "$d"
mkdir -p "$d"
git archive "$2" | tar -x -C "$d"
make -s -C "$d" lib
cc -std=c99 -O2 -g -I"$d/include" -Ibench bench/host.c "$d/build/libirrcache.a" \
    -o "$d/bench_host" -lm -lpthread
echo "the same host against $2's library:"
# shellcheck disable=SC2086
"$d/bench_host" $HOST_ARGS
