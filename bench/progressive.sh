#!/bin/sh
# progressive.sh PROGRESSIVE PATHTRACER SCENE -- what make bench-progressive
# runs: the two progressive hosts (bench/progressive.c with PROG_ARGS,
# bench/pathtracer.c on SCENE with PT_ARGS), their tables, and their
# error against CPU time, log-log, as build/progressive/*.png (gnuplot,
# installed from Debian's packages when we are root, as bench.sh does;
# NO_PLOT=1: tables and CSV only).
set -e
out=build/progressive
mkdir -p "$out"
# shellcheck disable=SC2086
PROG_CSV=$out/host.csv "$1" $PROG_ARGS | tee "$out/host.txt"
# shellcheck disable=SC2086
PT_CSV=$out/pathtracer.csv "$2" "$3" $PT_ARGS | tee "$out/pathtracer.txt"
[ -z "$NO_PLOT" ] || exit 0
if ! command -v gnuplot >/dev/null 2>&1 && [ "$(id -u)" = 0 ] && command -v apt-get >/dev/null 2>&1; then
    echo "installing: gnuplot-nox"
    { apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq gnuplot-nox >/dev/null; } ||
        echo "could not install gnuplot-nox"
fi
command -v gnuplot >/dev/null 2>&1 || { echo "gnuplot not found: tables and CSV only"; exit 0; }
for t in host pathtracer; do
    modes=$(tail -n +2 "$out/$t.csv" | cut -d, -f1 | uniq)
    plot=""
    for m in $modes; do
        grep "^$m," "$out/$t.csv" | cut -d, -f3,4 | tr , ' ' > "$out/$t-$m.dat"
        plot="$plot${plot:+, }'$out/$t-$m.dat' with linespoints title '$m'"
    done
    gnuplot <<GP
set terminal png size 640,480
set output '$out/$t.png'
set logscale xy
set xlabel 'CPU seconds (one thread)'
set ylabel 'relative RMSE'
set title '$t: error against time, 4 to the last samples a pixel'
set key top right
plot $plot
GP
    echo "wrote $out/$t.png"
done
