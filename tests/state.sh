#!/bin/sh
# tests/state.sh -- the store's mutable state (src/block/cache.h) is read
# only where docs/DESIGN.md ("Layers") says: the block, index, store and
# persistence folders, and the three public-call files that make and check
# blocks, open passes and set a progressive cache's level.  The kinds, the sampler, the estimators and the
# other public calls see the cache's form (form.h) alone; a file there
# that includes cache.h fails.  Run by make cycles (make check, make test).
set -e
cd "$(dirname "$0")/.."
bad=$(grep -lE '#include *"(\.\./block/)?cache\.h"' $(find src -name '*.[ch]') |
      grep -v -e '^src/block/' -e '^src/index/' -e '^src/store/' -e '^src/persist/' \
              -e '^src/api/life\.c$' -e '^src/api/pass\.c$' -e '^src/api/progress\.c$' || true)
if [ -n "$bad" ]; then
    echo "state: outside the layers that keep it, these include block/cache.h:"
    echo "$bad" | sed 's/^/  /'
    exit 1
fi
n=$(grep -lE '#include *"(\.\./block/)?cache\.h"' $(find src -name '*.c') | wc -l)
all=$(find src -name '*.c' | wc -l)
echo "state: block/cache.h in $n of $all files of src/, none above the store but life.c, pass.c and progress.c"
