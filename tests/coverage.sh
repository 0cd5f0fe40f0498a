#!/bin/sh
# coverage.sh -- make coverage: line and branch coverage of src/ by the core
# suite (quick mode) and the replayed fuzz corpora (gcc --coverage, gcov).
# Prints one line per file and the total; make test holds the total to 90%
# of lines and 80% of branches (taken at least once).
set -e
MAKE=${MAKE:-make}
B=build-cov
rm -rf $B
$MAKE -s BUILD=$B OPT="-O0 -g --coverage" $B/irc_tests $B/replay_api $B/replay_attach $B/replay_callback $B/replay_scene $B/replay_snapshot
IRC_TEST_QUICK=1 ./$B/irc_tests >/dev/null
for t in api attach callback scene snapshot; do
    ./$B/replay_$t fuzz/corpus/api fuzz/corpus/attach fuzz/corpus/callback fuzz/corpus/scene fuzz/corpus/snapshot >/dev/null
done
cd $B
printf '%-22s %8s %8s\n' file lines branches
for f in $(cd .. && ls src/*.c src/*/*.c); do
    name=${f#src/}
    gcov -b -c -o "$(dirname "$f")" "../$f" 2>/dev/null | sed -n "\#File '$f'#,/^\$/p" |
        awk -v f="$name" '
            /^Lines executed:/ { split($0, a, /[:% ]+/); lp = a[3]; ln = a[5] }
            /^Taken at least once:/ { split($0, a, /[:% ]+/); bp = a[5]; bn = a[7] }
            END { printf "%-22s %7.2f%% %7.2f%% %d %d\n", f, lp, bp, ln, bn }'
done | awk '
    { printf "%-22s %8s %8s\n", $1, $2, $3; l += $4; b += $5; hl += $2 * $4 / 100; hb += $3 * $5 / 100 }
    END { printf "%-22s %7.2f%% %7.2f%%  (%d lines, %d branches)\n", "total", 100 * hl / l, 100 * hb / b, l, b }'
