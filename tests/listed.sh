#!/bin/sh
# tests/listed.sh -- every TEST(name) in tests/ is in a suite's list (an
# X(name) of a TESTS list) or run by a main of its own (fn = name: t_exr's
# file mode), so no test is written and never run.  The lists are kept by
# hand in each suite's main; this check keeps them complete.
cd "$(dirname "$0")/.."
missing=0
for name in $(grep -ho '^TEST([a-z_0-9]*)' tests/*.c | sed 's/TEST(\(.*\))/\1/'); do
    grep -q -e "X($name)" -e "fn = $name;" tests/*.c || { echo "listed: $name is defined but in no TESTS list"; missing=1; }
done
[ $missing = 0 ] && echo "listed: every test is in a suite's list"
exit $missing
