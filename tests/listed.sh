#!/bin/sh
# tests/listed.sh -- every TEST(name) in tests/ is in a suite's list (an
# X(name) of a TESTS list) or run by a main of its own (fn = name: t_exr's
# file mode), so no test is written and never run, and the other way; and
# the Makefile's SRC and TEST_SRC against the files in src/ and tests/.
# The lists are kept by hand (SRC's order is the one-file library's);
# this check keeps them complete.
cd "$(dirname "$0")/.."
missing=0
for name in $(grep -ho '^TEST([a-z_0-9]*)' tests/*.c | sed 's/TEST(\(.*\))/\1/'); do
    grep -q -e "X($name)" -e "fn = $name;" tests/*.c || { echo "listed: $name is defined but in no TESTS list"; missing=1; }
done
# ... and every X(name) of a list is a test that exists.
for name in $(grep -ho 'X([a-z_0-9]*)' tests/*.c | sed 's/X(\(.*\))/\1/'); do
    grep -q "^TEST($name)" tests/*.c || { echo "listed: X($name) names no TEST"; missing=1; }
done
# The Makefile's lists of sources against the tree, both ways: every
# file of src/ is in SRC, every file of tests/ in TEST_SRC or built by a
# rule or script of its own, and every listed file is there.
lists=$(${MAKE:-make} -s print-lists) || { echo "listed: make print-lists failed"; exit 1; }
src=$(echo "$lists" | sed -n 's/^SRC //p')
tsrc=$(echo "$lists" | sed -n 's/^TEST_SRC //p')
[ -n "$src" ] && [ -n "$tsrc" ] || { echo "listed: no SRC or TEST_SRC from make print-lists"; exit 1; }
for f in src/*.c src/*/*.c; do
    case " $src " in *" $f "*) ;; *) echo "listed: $f is in no SRC (Makefile)"; missing=1 ;; esac
done
for f in $src $tsrc; do
    [ -f "$f" ] || { echo "listed: the Makefile lists $f, which is not there"; missing=1; }
done
for f in tests/*.c; do
    case " $tsrc " in
        *" $f "*) ;;
        *) grep -q "$f" Makefile tests/*.sh || { echo "listed: $f is built by nothing"; missing=1; } ;;
    esac
done
[ $missing = 0 ] && echo "listed: every test is in a suite's list, every list entry a test; SRC and TEST_SRC match the tree"
exit $missing
