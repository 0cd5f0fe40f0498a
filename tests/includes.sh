#!/bin/sh
# tests/includes.sh DIR -- fails when a file of the library includes a
# header of a higher layer: the layer rule of tests/cycles.sh (a file's
# layer is its folder under DIR, "top" at DIR's top, ranked by LAYERS,
# lowest first, folders of one rank joined by commas; docs/DESIGN.md,
# "Layers"), held for #include "..." lines as cycles.sh holds it for
# symbols.  A folder missing from LAYERS fails too, so a new folder must
# be placed.  Run by make cycles.
# tests/includes.sh --self-test: must fail on a lower folder's file that
# includes a higher one's header and on an unranked folder, and pass on
# the same tree ranked the other way.
set -e
[ $# -eq 1 ] || { echo "usage: tests/includes.sh DIR | --self-test" >&2; exit 2; }
if [ "$1" = --self-test ]; then
    d=$(mktemp -d)
    trap 'rm -rf "$d"' EXIT
    mkdir "$d/lo" "$d/hi"
    printf '#include "../hi/h.h"\n' > "$d/lo/a.c"
    printf '#include "../util.h"\nint h;\n' > "$d/hi/h.h"
    : > "$d/util.h"
    if LAYERS="top lo hi" sh "$0" "$d" > "$d/out"; then
        echo "includes: self-test: lo including hi not found"; exit 1
    fi
    grep -q 'lo/a.c includes hi/h.h' "$d/out" || { echo "includes: self-test: not named"; exit 1; }
    LAYERS="top hi lo" sh "$0" "$d" > /dev/null ||
        { echo "includes: self-test: hi below lo refused"; exit 1; }
    if LAYERS="top hi" sh "$0" "$d" > /dev/null; then
        echo "includes: self-test: an unranked folder passed"; exit 1
    fi
    echo "includes: self-test passed"
    exit 0
fi
dir=$1
find "$dir" -name '*.[ch]' | sort | while read -r f; do
    rel=${f#"$dir"/}
    case $rel in */*) from=${rel%%/*} ;; *) from=top ;; esac
    sed -n 's/^[[:space:]]*#[[:space:]]*include[[:space:]]*"\([^"]*\)".*/\1/p' "$f" |
        while read -r inc; do
            # resolve the path against the including file's folder
            p=$(dirname "$rel")/$inc
            p=$(echo "$p" | sed 's|^\./||; :a; s|[^/][^/]*/\.\./||; ta')
            # outside DIR, or not in it: the public header (-Iinclude)
            [ -e "$dir/$p" ] || continue
            case $p in
                */*) to=${p%%/*} ;;
                *) to=top ;;
            esac
            echo "$rel $from $to $p"
        done
done | awk -v layers="$LAYERS" '
    BEGIN {
        n = split(layers, l, " ")
        for (i = 1; i <= n; i++) {
            m = split(l[i], f, ",")
            for (j = 1; j <= m; j++) rank[f[j]] = i
        }
    }
    {
        if (!($2 in rank)) { print "includes: folder " $2 " is in no layer (LAYERS)"; bad = 1; next }
        if (!($3 in rank)) { print "includes: folder " $3 " is in no layer (LAYERS)"; bad = 1; next }
        if (rank[$3] > rank[$2]) { print "includes: " $1 " includes " $4 " (" $3 " is above " $2 ")"; bad = 1 }
        count++
    }
    END {
        if (bad) exit 1
        print "includes: " count " includes, none up a layer"
    }'
