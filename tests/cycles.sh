#!/bin/sh
# tests/cycles.sh OBJ... -- fails when the library's modules depend on
# each other in a cycle.  A module is one object file; it depends on
# another when it uses a symbol the other defines (nm).  Sinks (modules
# that use no other) are peeled off until none is left; what remains lies
# on a cycle, and is printed with the symbols that tie it.  Run by make
# check and make test on the objects of the library (make cycles).
# tests/cycles.sh --self-test: the check must fail on two objects that
# call each other and pass on two that do not.
set -e
[ $# -gt 0 ] || { echo "usage: tests/cycles.sh OBJ... | --self-test" >&2; exit 2; }
NM=${NM:-nm}
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
    echo "cycles: self-test passed"
    exit 0
fi
{
    for o in "$@"; do
        m=$(basename "$o" .o)
        $NM --defined-only "$o" | awk -v m="$m" 'NF == 3 && $2 ~ /[TDBRC]/ { print "D", m, $3 }'
        $NM --undefined-only "$o" | awk -v m="$m" 'NF >= 2 { print "U", m, $NF }'
    done
} | awk '
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
        if (left == 0) { printf "cycles: none among %d modules\n", length(mod); exit 0 }
        printf "cycles: %d modules depend on each other in a cycle:\n", left
        for (m in alive) for (k in alive) if ((m, k) in edge)
            printf "  %s -> %s (%s)\n", m, k, edge[m, k]
        exit 1
    }'
