#!/bin/sh
# tests/run.sh -- every test stage of `make test`; the last line is
# "N passed, N failed" over all of them.  Each suite run counts its own
# tests; every other stage counts as one.  Each stage prints its seconds
# as it ends, and the line "stages:" lists them all.
#   stage 1  library builds warning-free with gcc and clang (-Werror); the
#            port-less build (PORT=none) needs no thread library; the
#            build-time switches (tests/switches.c); the
#            shared library exports the documented irc_ API only (nm -D)
#   stage 2  the suite, optimised
#   stage 3  the suites and the fuzz corpora under ASan + UBSan (clang,
#            -fno-sanitize-recover)
#   stage 4  the thread tests under ThreadSanitizer (clang)
#   stage 2b the demo tracer: BVH, loader, images, the EXR read back by
#            OpenEXR, malformed scenes
#   stage 5  the header alone as C99 and as C++; no allocator symbol in
#            libirrcache.a; no thread or I/O header in src/; the documents
#            list every status, public call and source file (tests/docs.sh);
#            bench/README.md's variables table names every BENCH_* variable
#            and BENCH_SET key, and no other (tests/bench_vars.sh);
#            every test is in a suite's list (tests/listed.sh); no cycle
#            among the library's modules (tests/cycles.sh); the refactors'
#            fingerprint runs (make fingerprint);
#            the one-file library builds alone, and the examples built on it
#            print what the library's print (tests/amalgamation.sh)
#   stage 2c the suite built for 32 bits (-m32: size_t and pointers of a
#            microcontroller)
#   stage 2d the suite with assertions compiled out (-DIRC_NO_ASSERT: IRC_ASSERT
#            does nothing, as in a release firmware)
#   stage 6  line and branch coverage of src/ (gcov), printed; at least
#            90% of lines and 80% of branches
#   stage 7  the library built for a Cortex-M4F and its host run under
#            QEMU (make embedded-test; embedded/need.sh installs the Arm
#            compiler, newlib and QEMU when missing), and make size
#            (fails if the library can recurse)
#   stage 8  make install into a temporary DESTDIR, then the example host
#            built from the staged files with cc + pkg-config, with a CMake
#            project (find_package), and from C++; make uninstall removes
#            it all (tests/consumers.sh)
set -u
cd "$(dirname "$0")/.."
P=0
F=0
LOG=build/test-logs
mkdir -p "$LOG"
MAKE=${MAKE:-make}
SAN_CC=${SAN_CC:-clang}

# Tools a fresh Debian machine may lack: installed when we are root with
# apt, otherwise the run stops and says what to install.
need=""
command -v clang >/dev/null 2>&1 || need="$need clang"
command -v c++ >/dev/null 2>&1 || need="$need g++"
command -v nm >/dev/null 2>&1 || need="$need binutils"
# an installed irrcache used from a CMake project (stage 8)
command -v cmake >/dev/null 2>&1 || need="$need cmake"
# 32-bit builds (stage 2c)
[ -e /usr/lib32/crt1.o ] || [ -e /usr/lib/i386-linux-gnu/crt1.o ] || need="$need gcc-multilib"
ls /usr/lib/llvm-*/lib/clang/*/lib/linux/libclang_rt.tsan-x86_64.a >/dev/null 2>&1 ||
    need="$need libclang-rt-14-dev"
# the corpus's converter (tests/corpus.sh)
command -v python3 >/dev/null 2>&1 || need="$need python3"
# OpenEXR's C library reads the demo's images back (tests only).
command -v pkg-config >/dev/null 2>&1 || need="$need pkg-config"
pkg-config --exists OpenEXR 2>/dev/null || need="$need libopenexr-dev"
if [ -n "$need" ]; then
    if [ "$(id -u)" = 0 ] && command -v apt-get >/dev/null 2>&1; then
        echo "installing:$need"
        apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq $need >/dev/null ||
            { echo "could not install:$need"; exit 1; }
    else
        echo "make test needs:$need (sudo apt-get install$need)"
        exit 1
    fi
fi

ok() { P=$((P + 1)); echo "ok   $1"; }
bad() { F=$((F + 1)); echo "FAIL $1${2:+: $2}"; }
check() { # name command...
    name=$1; shift
    if "$@" >"$LOG/$name.log" 2>&1; then ok "$name"; else bad "$name" "see $LOG/$name.log"; tail -20 "$LOG/$name.log"; fi
}
# Each stage's seconds, printed as it ends and listed at the end.
STAGE_NAME=
STAGE_T=0
STAGES=
stage_end() {
    [ -n "$STAGE_NAME" ] || return 0
    t=$(( $(date +%s) - STAGE_T ))
    echo "   ($STAGE_NAME: $t s)"
    STAGES="$STAGES ${STAGE_NAME%%:*} ${t}s;"
}
stage() {
    stage_end
    STAGE_NAME=$1
    STAGE_T=$(date +%s)
    echo "== $1"
}

suite() { # name env-and-binary...
    name=$1; shift
    env "$@" >"$LOG/$name.log" 2>&1
    rc=$?
    line=$(grep -E '^[0-9]+ passed, [0-9]+ failed$' "$LOG/$name.log" | tail -1)
    grep -E '^(ok|FAIL) |^  ' "$LOG/$name.log" | sed "s/^/[$name] /"
    if [ -n "$line" ]; then
        p=${line%% passed*}
        f=${line#*passed, }; f=${f%% failed}
        P=$((P + p)); F=$((F + f))
        [ "$rc" -eq 0 ] || [ "$f" -ne 0 ] || bad "$name" "exit status $rc (sanitizer report?)"
    else
        bad "$name" "no result line, exit status $rc"
        tail -30 "$LOG/$name.log"
    fi
}

stage "stage 1: builds"
check build-gcc $MAKE -s CC=gcc BUILD=build all
check build-clang $MAKE -s CC=clang BUILD=build-clang all

# Without a port that needs threads: no pthread or C11-thread symbol.
WARN_TEST="-Wall -Wextra -Wpedantic -Werror"
portless() {
    $MAKE -s CC=gcc BUILD=build-none PORT=none lib || return 1
    found=$(nm build-none/libirrcache.a | grep -E ' U (pthread_|thrd_|mtx_|cnd_|sched_)')
    [ -z "$found" ] || { echo "$found"; return 1; }
    nm build-none/libirrcache.a | grep -q ' T irc_init$' || return 1
    # the ports it did not compile are defined, and refuse to make a lock
    gcc -std=c99 $WARN_TEST -Iinclude tests/unbuilt.c build-none/libirrcache.a \
        -o build-none/unbuilt -lm && ./build-none/unbuilt
}
check portless-build portless
# A user configuration header replaces single macros of src/util.h.
user_config() {
    d=build/user-config
    mkdir -p "$d"
    for f in src/*.c src/*/*.c; do
        gcc -std=c99 -O1 -Iinclude -Itests -DIRC_USER_CONFIG='"user_config.h"' -c "$f" \
            -o "$d/$(basename "$f" .c).o" || return 1
    done
    nm "$d"/*.o > "$d/nm.txt"
    grep -q ' U irc_user_sqrtf$' "$d/nm.txt" || { echo "IRC_SQRTF was not replaced"; return 1; }
    grep -q ' U irc_user_assert$' "$d/nm.txt" || { echo "IRC_ASSERT was not replaced"; return 1; }
    ! grep -qE ' U (sqrtf|__assert_fail)$' "$d/nm.txt" || { echo "a call bypasses the macros"; return 1; }
    grep -qE ' U (cosf|ldexp)$' "$d/nm.txt" || { echo "the other macros lost their defaults"; return 1; }
}
check user-config user_config
# The build-time switches: what is left out is refused, the rest works.
switches() {
    d=build-switches
    # One function of each part that can be left out; each must be in a
    # build with every part, or this check would pass for a stale name.
    parts="irc__sh_eval irc__hessian irc__grad_visibility irc__confirm_batch irc__supersample irc__leak_guard irc__guarded"
    # -fno-inline: a static function compiled in keeps its symbol for nm
    # (maybe with a suffix: irc__leak_guard.isra.0)
    $MAKE -s BUILD=$d-all PORT=none OPT="-O2 -fno-inline" $d-all/libirrcache.a || return 1
    nm "$d-all/libirrcache.a" > "$d-all/nm.txt" 2>/dev/null
    for f in $parts; do
        grep -qE " $f(\.|\$)" "$d-all/nm.txt" || { echo "no $f in a build with every part"; return 1; }
    done
    $MAKE -s BUILD=$d PORT=none OPT="-O2 -fno-inline" \
        LEAVE_OUT="SH VISIBILITY HESSIAN SIGHT SUPERSAMPLE GUARD" $d/libirrcache.a || return 1
    nm "$d/libirrcache.a" > "$d/nm.txt" 2>/dev/null
    for f in $parts; do
        ! grep -qE " $f(\.|\$)" "$d/nm.txt" || { echo "a part left out was compiled: $f"; return 1; }
    done
    cc -std=c99 -Wall -Wextra -Werror -Iinclude -Isrc tests/switches.c $d/libirrcache.a -lm \
        -o $d/switches || return 1
    $d/switches || return 1
    # the same switches as -D (or in a user config header): the files compile empty
    $MAKE -s BUILD=$d-header PORT=none \
        CFLAGS="-DIRC_NO_SH -DIRC_NO_VISIBILITY -DIRC_NO_HESSIAN -DIRC_NO_SIGHT -DIRC_NO_SUPERSAMPLE -DIRC_NO_GUARD" \
        $d-header/libirrcache.a || return 1
    cc -std=c99 -Wall -Wextra -Werror -Iinclude -Isrc tests/switches.c $d-header/libirrcache.a -lm \
        -o $d-header/switches && $d-header/switches
}
check switches switches
# Only the documented API leaves the shared library.
exports() {
    nm -D --defined-only build/libirrcache.so | awk '$2 ~ /^[TDBRV]$/ {print $3}' > "$LOG/exports.txt"
    echo "$(wc -l < "$LOG/exports.txt") symbols exported"
    bad=$(grep -vE '^irc_[a-z]' "$LOG/exports.txt")
    [ -z "$bad" ] || { echo "not documented: $bad"; return 1; }
    # each one is declared in the header
    for f in $(cat "$LOG/exports.txt"); do
        grep -qE "(^|[^a-z_])$f([^a-z_]|$)" include/irrcache.h || { echo "$f: not in irrcache.h"; return 1; }
    done
    grep -q '^irc_init$' "$LOG/exports.txt"
}
check exports-nm-D exports
sed 's/^/[exports] /' "$LOG/exports-nm-D.log" | head -2

stage "stage 2: suite"
check build-tests $MAKE -s BUILD=build build/irc_tests
suite suite ./build/irc_tests

# The benchmarks build, and the profiling driver runs (figures come from
# make bench-core, make bench-host, make bench-lookups and make bench-records, not from
# here).
check build-bench $MAKE -s BUILD=build build/bench_core build/bench_lookups build/bench_records \
    build/bench_run build/outliers build/reach build/probes build/bench_host build/bench_anchor
check bench-lookups ./build/bench_lookups scanline 1000 2000 count
check bench-anchor ./build/bench_anchor random 1000 2000 pass
check bench-host ./build/bench_host 16 12 4 16
check bench-records ./build/bench_records shgrad 3
check reach ./build/reach demo/scenes/cornell.scene 32x32 0.4 --step 4
check probes ./build/probes demo/scenes/cornell.scene 32x32 --fail-under
# the corpus's converter (bench/corpus/bitterli-rooms.py) on a room of its own
check corpus-converter sh tests/corpus.sh

stage "stage 2c: suite at 32 bits"
check build-m32 $MAKE -s CC="gcc -m32" BUILD=build-m32 build-m32/irc_tests
# A kernel built without IA-32 emulation builds i386 programs but cannot
# run them (exec fails with ENOEXEC, status 126): said, not counted.
printf 'int main(void) { return 0; }\n' > "$LOG/m32probe.c"
m32rc=0
gcc -m32 "$LOG/m32probe.c" -o "$LOG/m32probe" 2>/dev/null && { "$LOG/m32probe" 2>/dev/null; m32rc=$?; }
if [ "$m32rc" -eq 126 ]; then
    echo "skip m32: this kernel runs no i386 programs (the 32-bit suite builds; the M4F stage runs 32-bit code)"
else
    suite m32 IRC_TEST_QUICK=1 ./build-m32/irc_tests
fi

stage "stage 2d: suite with the library's assertions compiled out"
check build-ndebug $MAKE -s BUILD=build-ndebug OPT="-O2 -DIRC_NO_ASSERT" build-ndebug/irc_tests
suite ndebug IRC_TEST_QUICK=1 ./build-ndebug/irc_tests

stage "stage 2b: demo tracer"
check build-demo $MAKE -s BUILD=build real-scenes build/irc_demo build/demo_tests build/t_image build/t_loader build/t_exr \
    build/adaptive_tests
suite demo ./build/demo_tests
suite adaptive ./build/adaptive_tests
suite image ./build/t_image
suite loader ./build/t_loader
suite exr ./build/t_exr
# Images the demo rendered, float and half, read by OpenEXR against the
# buffer the demo held (dumped raw).
mkdir -p build/test-exr
for half in "" --half; do
    out=build/test-exr/cornell$half
    check "render$half" ./build/irc_demo demo/scenes/cornell.scene --size 61x47 --strata 4x16 \
        --quiet $half --out "$out" --raw "$out.f32"
    suite "exr-demo$half" ./build/t_exr "$out.exr" "$out.f32" 61 47
done
# A malformed scene: exit status 1, "FILE:LINE: ..." on stderr, no file.
bad_scene() {
    d=build/test-bad
    rm -rf "$d" && mkdir -p "$d"
    ./build/irc_demo tests/data/bad/o_face2.scene --out "$d/x" >"$d/log" 2>&1
    rc=$?
    cat "$d/log"
    [ "$rc" -eq 1 ] && grep -qE '^tests/data/bad/o_face2\.obj:[0-9]+: ' "$d/log" &&
        [ "$(ls "$d")" = log ]
}
check bad-scene bad_scene
# The long documented targets in small forms (Makefile, SMALL_TARGETS):
# make adaptive's first run at 64 x 48, fig15, glossy, sh-experiments,
# sh-animation and bench-bounces, seconds each.
for t in $($MAKE -s small-targets); do
    check "$t" $MAKE -s BUILD=build "$t"
done
# The farm (make farm-demo): 4 tile jobs of a Slurm job array and a merging
# job, on a single-node Slurm the script starts (its daemons need root).
if [ "$(id -u)" = 0 ]; then
    check farm-demo sh farm/farm-demo.sh 4
else
    echo "skip farm-demo: starting Slurm's daemons needs root"
fi

stage "stage 3: suite under ASan + UBSan"
SAN="-O1 -g -fno-omit-frame-pointer -fsanitize=address,undefined -fno-sanitize-recover=all"
check build-asan $MAKE -s CC="$SAN_CC" BUILD=build-asan OPT="$SAN" build-asan/irc_tests
suite asan IRC_TEST_QUICK=1 ASAN_OPTIONS=detect_leaks=1:abort_on_error=0 \
    UBSAN_OPTIONS=print_stacktrace=1 ./build-asan/irc_tests
check build-asan-demo $MAKE -s CC="$SAN_CC" BUILD=build-asan OPT="$SAN" build-asan/demo_tests \
    build-asan/t_loader build-asan/t_image build-asan/adaptive_tests
for t in demo_tests t_loader t_image adaptive_tests; do
    suite "asan-$t" IRC_TEST_QUICK=1 ASAN_OPTIONS=detect_leaks=1 ./build-asan/$t
done
# The fuzz corpora, replayed without libFuzzer (make fuzz grows them):
# every corpus through every harness.
check build-asan-replay $MAKE -s CC="$SAN_CC" BUILD=build-asan OPT="$SAN" \
    build-asan/replay_api build-asan/replay_attach build-asan/replay_callback \
    build-asan/replay_scene build-asan/replay_snapshot
for t in api attach callback scene snapshot; do
    suite "fuzz-replay-$t" ASAN_OPTIONS=detect_leaks=1 ./build-asan/replay_$t \
        fuzz/corpus/api fuzz/corpus/attach fuzz/corpus/callback fuzz/corpus/scene \
        fuzz/corpus/snapshot
done

stage "stage 4: threads under TSan"
check build-tsan $MAKE -s CC="$SAN_CC" BUILD=build-tsan OPT="-O1 -g -fsanitize=thread" build-tsan/irc_tests
suite tsan IRC_TEST_QUICK=1 TSAN_OPTIONS=halt_on_error=1 ./build-tsan/irc_tests test_threads test_busy_waits test_pass_order_free test_levels

stage "stage 5: header, example host and library rules"
check examples $MAKE -s BUILD=build examples
check example-minimal ./build/minimal
check example-threads ./build/threads
check example-levels ./build/levels
check example-passes ./build/passes
check example-minimal-cpp ./build/minimal_cpp
check header-c99 cc -std=c99 -pedantic -Wall -Wextra -Werror -fsyntax-only -x c include/irrcache.h
check header-cxx c++ -std=c++98 -pedantic -Wall -Wextra -Werror -Wno-long-long -Iinclude -c tests/header_cpp.cpp -o build/header_cpp.o
no_allocator() {
    found=$(nm -A build/libirrcache.a | grep -E ' U (malloc|calloc|realloc|free|aligned_alloc|posix_memalign)$')
    [ -z "$found" ] || { echo "$found"; return 1; }
    nm build/libirrcache.a | grep -q ' T irc_init$'   # the check reads the right archive
}
check no-allocator no_allocator
src_headers() {
    bad=$(grep -hoE '#[[:space:]]*include[[:space:]]*<[^>]+>' src/*.c src/*.h src/*/*.c src/*/*.h include/*.h |
        sed -E 's/.*<([^>]+)>.*/\1/' | sort -u |
        grep -vxE 'assert.h|float.h|math.h|stddef.h|stdint.h|string.h')
    [ -z "$bad" ] || { echo "src/ includes: $bad"; return 1; }
    # every libc and libm call goes through a macro of util.h
    call='(^|[^_A-Za-z0-9])(sqrtf?|sinf?|cosf?|tanf?|asin|acos|atan2?|fabsf?|floor|ceil|frexp|ldexp|pow|exp|log|memcpy|memmove|memset|assert)[[:space:]]*\('
    bare=$(grep -nE "$call" src/*.c src/*.h src/*/*.c src/*/*.h | grep -v '^src/util.h:' |
        grep -vE '^[^:]+:[0-9]+:[[:space:]]*/?\*' | sed -E 's#/\*.*##' | grep -E "$call")
    [ -z "$bare" ] || { echo "calls past util.h: $bare"; return 1; }
}
check src-headers src_headers
check docs sh tests/docs.sh
check bench-vars sh tests/bench_vars.sh
check listed sh tests/listed.sh
check cycles $MAKE -s BUILD=build cycles
check fingerprint $MAKE -s BUILD=build fingerprint
check amalgamation sh tests/amalgamation.sh

stage "stage 6: coverage of src/"
MAKE=$MAKE sh tests/coverage.sh > "$LOG/coverage-report.log" 2>&1
sed 's/^/[coverage] /' "$LOG/coverage-report.log" | tail -16
coverage_target() {
    tail -1 "$LOG/coverage-report.log" | awk '$1 == "total" { l = $2 + 0; b = $3 + 0; ok = l >= 90 && b >= 80 } END { exit !ok }'
}
check coverage coverage_target

stage "stage 7: Cortex-M4F under QEMU"
check embedded-need sh embedded/need.sh
suite m4 $MAKE -s embedded-test
check size sh embedded/size.sh

stage "stage 8: installed, and used from outside the tree"
check consumers sh tests/consumers.sh
grep -E '^(pkg-config|cmake|g\+\+|uninstall)' "$LOG/consumers.log" | sed 's/, e.g. .*//; s/^/[consumers] /'

stage_end
echo "stages: $STAGES"
echo "$P passed, $F failed"
[ "$F" -eq 0 ]
