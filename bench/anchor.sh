#!/bin/sh
# anchor.sh -- instructions a lookup, irrcache against the pbrt-v2-style
# baseline (bench/anchor.c), on the same records and queries: callgrind
# with L = 0 and L = 100000 lookups, the difference over 100000.
#   sh bench/anchor.sh BIN RECORDS [CSV]
bin=${1:-build/bench_anchor}
n=${2:-100000}
csv=${3:-build/bench/anchor.csv}
command -v valgrind >/dev/null || { echo "anchor: valgrind is missing"; exit 1; }
mkdir -p "$(dirname "$csv")"
echo "records,order,fill,side,instructions_per_lookup" > "$csv"
tmp=$(mktemp -d)
for order in scanline random; do
    for fill in free pass; do
        arg=; [ $fill = pass ] && arg=pass
        for side in irrcache baseline; do
            for l in 0 100000; do
                BENCH_ANCHOR=$side valgrind --tool=callgrind --callgrind-out-file="$tmp/cg.$l" \
                    "$bin" $order $l "$n" $arg > "$tmp/out.$l" 2>/dev/null || { echo "anchor: $bin failed"; exit 1; }
            done
            a=$(sed -n 's/^totals: //p' "$tmp/cg.0")
            b=$(sed -n 's/^totals: //p' "$tmp/cg.100000")
            per=$(( (b - a) / 100000 ))
            echo "$n,$order,$fill,$side,$per" >> "$csv"
            printf '%s records, %s, %s fill, %s: %d instructions a lookup; %s\n' "$n" $order $fill \
                $side $per "$(sed 's/.*M\/s, //' "$tmp/out.100000")"
        done
    done
done
rm -rf "$tmp"
