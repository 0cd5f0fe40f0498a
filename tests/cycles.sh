#!/bin/sh
# tests/cycles.sh OBJ... -- fails when the library's modules depend on
# each other in a cycle, or a lower layer uses a higher one.  A module is
# one object file; it depends on another when it uses a symbol the other
# defines (nm).  Sinks (modules that use no other) are peeled off until
# none is left; what remains lies on a cycle, and is printed with the
# symbols that tie it.  A module's layer is its folder under src/ (files
# at src/'s top: "top"), ranked by LAYERS, lowest first, folders of one
# rank joined by commas (docs/DESIGN.md, "Layers"); a module may use its
# own rank and those below.  Run by make check and make test on the
# objects of the library (make cycles).
# tests/cycles.sh --self-test: the check must fail on two objects that
# call each other, or on a lower layer's object using a higher one's, and
# pass when neither happens.
set -e
[ $# -gt 0 ] || { echo "usage: tests/cycles.sh OBJ... | --self-test" >&2; exit 2; }
NM=${NM:-nm}
LAYERS=${LAYERS:-}
if [ "$1" = --self-test ]; then
    d=$(mktemp -d)
    trap 'rm -rf "$d"' EXIT
    printf 'int b(int);\nint a(int x) { return x ? b(x - 1) : 0; }\n' > "$d/a.c"
    printf 'int a(int);\nint b(int x) { return x ? a(x - 1) : 1; }\n' > "$d/b.c"
    printf 'int c(int x) { return x + 1; }\n' > "$d/c.c"
    printf 'int c(int);\nint e(int x) { return c(x); }\n' > "$d/e.c"
    for f in a b c e; do ${CC:-cc} -c "$d/$f.c" -o "$d/$f.o"; done
    if sh "$0" "$d/a.o" "$d/b.o" "$d/c.o" > "$d/out"; then
        echo "cycles: self-test: a <-> b not found"; exit 1
    fi
    grep -q 'a -> b (b)' "$d/out" || { echo "cycles: self-test: edge a -> b not named"; exit 1; }
    sh "$0" "$d/c.o" "$d/e.o" > /dev/null || { echo "cycles: self-test: e -> c called a cycle"; exit 1; }
    mkdir "$d/lo" "$d/hi"
    cp "$d/e.o" "$d/lo/e.o"
    cp "$d/c.o" "$d/hi/c.o"
    if LAYERS="lo hi" sh "$0" "$d/lo/e.o" "$d/hi/c.o" > "$d/out"; then
        echo "cycles: self-test: lo using hi not found"; exit 1
    fi
    LAYERS="hi lo" sh "$0" "$d/lo/e.o" "$d/hi/c.o" > /dev/null ||
        { echo "cycles: self-test: hi below lo refused"; exit 1; }
    echo "cycles: self-test passed"
    exit 0
fi
{
    r=0
    for l in $LAYERS; do
        for f in $(echo "$l" | tr , ' '); do echo "R $f $r"; done
        r=$((r + 1))
    done
    for o in "$@"; do
        m=$(basename "$o" .o)
        f=$(basename "$(dirname "$o")")
        [ "$f" = src ] && f=top
        echo "F $m $f"
        $NM --defined-only "$o" | awk -v m="$m" 'NF == 3 && $2 ~ /[TDBRC]/ { print "D", m, $3 }'
        $NM --undefined-only "$o" | awk -v m="$m" 'NF >= 2 { print "U", m, $NF }'
    done
} | awk '
    $1 == "R" { rank[$2] = $3; next }
    $1 == "F" { folder[$2] = $3; next }
    $1 == "D" { def[$3] = $2; mod[$2] = 1; next }
    $1 == "U" { use[++n] = $2 " " $3; mod[$2] = 1 }
    END {
        for (i = 1; i <= n; i++) {
            split(use[i], u, " ")
            d = def[u[2]]
            if (d == "" || d == u[1]) continue
            if (!((u[1], d) in edge)) { edge[u[1], d] = u[2]; out[u[1]]++ }
            else if (index(edge[u[1], d], u[2]) == 0) edge[u[1], d] = edge[u[1], d] " " u[2]
        }
        up = 0
        for (e in edge) {
            split(e, ab, SUBSEP)
            fa = folder[ab[1]]; fb = folder[ab[2]]
            if (length(rank) && (!(fa in rank) || !(fb in rank))) {
                printf "layers: %s (%s) or %s (%s) is in no layer\n", ab[1], fa, ab[2], fb; up = 1
            } else if (length(rank) && rank[fb] > rank[fa]) {
                printf "layers: %s (%s) uses %s (%s), a higher layer: %s\n", ab[1], fa, ab[2], fb, edge[e]
                up = 1
            }
        }
        for (m in mod) alive[m] = 1
        do {
            peeled = 0
            for (m in alive) {
                sink = 1
                for (k in alive) if ((m, k) in edge) { sink = 0; break }
                if (sink) { delete alive[m]; peeled = 1 }
            }
        } while (peeled)
        left = 0
        for (m in alive) left++
        if (left == 0 && !up) {
            printf "cycles: none among %d modules", length(mod)
            if (length(rank)) printf "; every use goes down the layers"
            printf "\n"
            exit 0
        }
        if (left == 0) exit 1
        printf "cycles: %d modules depend on each other in a cycle:\n", left
        for (m in alive) for (k in alive) if ((m, k) in edge)
            printf "  %s -> %s (%s)\n", m, k, edge[m, k]
        exit 1
    }'
