#!/bin/sh
# bench_vars.sh -- bench/README.md's table of variables (its "## Variables")
# names every BENCH_* name the bench uses (bench/*.c, bench/*.h, bench/*.sh
# and the Makefile) and every BENCH_SET key bench/select.c accepts, and
# names nothing else.  Not variables: header guards (BENCH_..._H) and the
# Makefile's own (BENCH_RUN_SRC: assigned there).  Prints what is missing
# or extra; fails if anything is.
cd "$(dirname "$0")/.." || exit 1
readme=bench/README.md
files=$(echo bench/*.c bench/*.h bench/*.sh Makefile)
set -f # names, not patterns, from here on
# The table's names: every `name` in the first cell of its rows.
# shellcheck disable=SC2016 # backquotes are the table's, not the shell's
table=$(awk '/^## Variables/ { on = 1; next } on && /^#/ { exit } on && /^\| `/ { print }' $readme |
        cut -d'|' -f2 | grep -o '`[^`]*`' | tr -d '`' | sort -u | tr '\n' ' ')
# The code's: BENCH_* names, less guards and the Makefile's own ...
made=$(sed -n 's/^\(BENCH_[A-Z0-9_]*\)[[:space:]]*[:?+]*=.*/\1/p' Makefile | sort -u | tr '\n' ' ')
# shellcheck disable=SC2086 # $files: the list above
vars=$(cat $files | grep -o 'BENCH_[A-Z0-9][A-Z0-9_]*' | grep -v '_H$' | sort -u | tr '\n' ' ')
# ... and the keys experiment_opts compares BENCH_SET's names with.
keys=$(sed -n 's/.*strcmp(name, "\([a-z]*\)").*/\1/p' bench/select.c | sort -u | tr '\n' ' ')
if [ -z "$table" ]; then echo "bench_vars: no table under \"## Variables\" in $readme"; exit 1; fi
if [ -z "$vars" ] || [ -z "$keys" ]; then echo "bench_vars: no BENCH_* name or BENCH_SET key in the code"; exit 1; fi
in_list() { # NAME "LIST"
    case " $2 " in *" $1 "*) return 0 ;; esac
    return 1
}
missing=0
for v in $vars; do
    in_list "$v" "$made" && continue
    in_list "$v" "$table" && continue
    # shellcheck disable=SC2086
    echo "$readme, Variables: $v missing (used in $(grep -l "$v" $files | tr '\n' ' ' | sed 's/ $//'))"
    missing=1
done
for k in $keys; do
    in_list "$k" "$table" && continue
    echo "$readme, Variables: BENCH_SET key $k missing (bench/select.c accepts it)"
    missing=1
done
for n in $table; do
    case $n in
        BENCH_*) in_list "$n" "$vars" && ! in_list "$n" "$made" && continue
                 echo "$readme, Variables: $n is used nowhere in bench/ or the Makefile" ;;
        *) in_list "$n" "$keys" && continue
           echo "$readme, Variables: $n is no BENCH_SET key bench/select.c accepts" ;;
    esac
    missing=1
done
# shellcheck disable=SC2086 # split on purpose
count() { set -- $1; echo $#; }
[ $missing = 0 ] && echo "bench_vars: the table names the bench's $(($(count "$vars") - $(count "$made"))) BENCH_* names and $(count "$keys") BENCH_SET keys, and nothing else"
exit $missing
