#!/bin/sh
# coverage.sh -- make coverage: line and branch coverage of src/ by the core
# suite and the replayed fuzz corpora (gcc --coverage, gcov).  Prints one
# line per file and the total; the targets are 90% of lines and 80% of
# branches (taken at least once).
set -e
MAKE=${MAKE:-make}
B=build-cov
rm -rf $B
$MAKE -s BUILD=$B OPT="-O0 -g --coverage" $B/irc_tests $B/replay_api $B/replay_callback $B/replay_scene
IRC_TEST_QUICK=1 ./$B/irc_tests >/dev/null
for t in api callback scene; do
    ./$B/replay_$t fuzz/corpus/api fuzz/corpus/callback fuzz/corpus/scene >/dev/null
done
cd $B/src
total_l=0; hit_l=0; total_b=0; hit_b=0
printf '%-16s %8s %8s\n' file lines branches
for f in ../../src/*.c; do
    base=$(basename "$f" .c)
    out=$(gcov -b -c -o . "$f" 2>/dev/null | sed -n "/File 'src\/$base.c'/,/^\$/p")
    l=$(echo "$out" | sed -n 's/Lines executed:\([0-9.]*\)% of \([0-9]*\)/\1 \2/p')
    b=$(echo "$out" | sed -n 's/Taken at least once:\([0-9.]*\)% of \([0-9]*\)/\1 \2/p')
    set -- $l; lp=$1; ln=$2
    set -- ${b:-0 0}; bp=$1; bn=$2
    printf '%-16s %7s%% %7s%%\n' "$base.c" "$lp" "$bp"
    total_l=$(echo "$total_l + $ln" | bc); hit_l=$(echo "$hit_l + $lp * $ln / 100" | bc -l)
    total_b=$(echo "$total_b + $bn" | bc); hit_b=$(echo "$hit_b + $bp * $bn / 100" | bc -l)
done
printf '%-16s %7.2f%% %7.2f%%  (%d lines, %d branches)\n' total \
    "$(echo "100 * $hit_l / $total_l" | bc -l)" "$(echo "100 * $hit_b / $total_b" | bc -l)" \
    "$total_l" "$total_b"
