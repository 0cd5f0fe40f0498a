#!/bin/sh
# bench.sh DRIVER -- what make bench runs: the driver (build/bench_run), then
# the plots with gnuplot (installed from Debian's packages when we are root
# with apt, as make test installs its tools; without it, CSV and table
# only), then the table into bench/notes.md between its two marker lines
# (full runs only: quick figures are not for the documents; bench/README.md
# is the manual, "Speed against error" in bench/notes.md the dated record).
# BENCH_SCENES, BENCH_METHODS (see select.c): partial runs leave it alone.
set -e
driver=$1
if [ "${BENCH_QUICK:-0}" = 1 ]; then "$driver" quick; else "$driver"; fi
if ! command -v gnuplot >/dev/null 2>&1 && [ "$(id -u)" = 0 ] && command -v apt-get >/dev/null 2>&1; then
    echo "installing: gnuplot-nox"
    { apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq gnuplot-nox >/dev/null; } ||
        echo "could not install gnuplot-nox"
fi
if command -v gnuplot >/dev/null 2>&1; then
    gnuplot build/bench/plot.gp && echo "wrote build/bench/*.png"
else
    echo "gnuplot not found (apt-get install gnuplot-nox): CSV and table only"
fi
# Glossy indirect light on the glossy scenes (full runs, or BENCH_METHODS
# naming glossy): SH records against lobe rays, warm and cold times.
if [ "${BENCH_QUICK:-0}" != 1 ] && { [ -z "${BENCH_SCENES}${BENCH_METHODS}" ] ||
    echo ",${BENCH_METHODS}," | grep -q ",glossy,"; }; then
    g=build/bench/glossy.md
    {
        printf '\n**Glossy indirect light** (build/glossy: the glossy material'"'"'s bounce alone, kd 0, exponent s; '
        printf 'relative RMSE on its pixels against 4096 lobe rays, 16 light samples at secondary hits; '
        printf 'warm times: a render after the one that made the records, one thread)\n\n'
        printf '| scene | s | SH L = 5 (warm; cold) | lobe 1 ray | 16 rays | 64 rays | SH / lobe at equal warm time |\n|---|---|---|---|---|---|---|\n'
    } > $g
    build/glossy demo/scenes/fig5.scene glossy 256 192 --exponents 2,10,40 --table $g
    build/glossy demo/scenes/cornell-glossy.scene glossy 128 128 --exponents 2,10,40 --table $g
    cat $g >> build/bench/table.md
fi
cat build/bench/table.md
if [ "${BENCH_QUICK:-0}" != 1 ] && [ -z "${BENCH_SCENES}${BENCH_METHODS}" ]; then
    awk -v table=build/bench/table.md '
        /<!-- bench:begin -->/ { print; while ((getline l < table) > 0) print l; skip = 1; next }
        /<!-- bench:end -->/ { skip = 0 }
        !skip { print }' bench/notes.md > build/bench/notes.md.new
    if grep -q "<!-- bench:end -->" build/bench/notes.md.new; then
        mv build/bench/notes.md.new bench/notes.md && echo "bench/notes.md: table updated"
    fi
fi
