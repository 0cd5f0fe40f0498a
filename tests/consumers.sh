#!/bin/sh
# tests/consumers.sh -- an installed irrcache used from outside the tree
# (make test, stage 8): make install into a temporary DESTDIR, then the
# example host built and run three ways, each from the staged files only:
#   pkg-config   cc with `pkg-config --cflags --libs irrcache` (shared) and
#                `--static` (PKG_CONFIG_PATH and PKG_CONFIG_SYSROOT_DIR at
#                the stage)
#   cmake        tests/consumer/CMakeLists.txt: find_package(irrcache),
#                irrcache::irrcache and irrcache::irrcache_static, the C++
#                host too; a request for a newer version must fail
#   c++          g++ on examples/minimal.cpp, the header in a .cpp
# Each run's irradiance must match the closed form it prints (3%); the
# shared builds must need libirrcache.so.MAJOR (the soname; MAJOR.MINOR
# while the major is 0); make
# uninstall must leave no file behind; and the same with LIBDIR and
# INCLUDEDIR where a distribution puts them.
set -eu
cd "$(dirname "$0")/.."
MAKE=${MAKE:-make}
T=$(mktemp -d /tmp/irc-consumers.XXXXXX)
trap 'rm -rf "$T"' EXIT
S=$T/stage
P=/usr/local
$MAKE -s BUILD=build install DESTDIR="$S" PREFIX=$P
part() { sed -n "s/^#define IRC_VERSION_$1 \([0-9]*\)\$/\1/p" include/irrcache.h; }
major=$(part MAJOR)
minor=$(part MINOR)
version=$major.$minor.$(part PATCH)
soname=$major
[ "$major" = 0 ] && soname=$major.$minor
for f in include/irrcache.h lib/libirrcache.a lib/libirrcache.so.$version lib/libirrcache.so.$soname \
         lib/libirrcache.so lib/pkgconfig/irrcache.pc lib/cmake/irrcache/irrcacheConfig.cmake \
         lib/cmake/irrcache/irrcacheConfigVersion.cmake; do
    [ -e "$S$P/$f" ] || { echo "not installed: $f"; exit 1; }
done
readelf -d "$S$P/lib/libirrcache.so.$version" | grep -q "SONAME.*\[libirrcache.so.$soname\]" ||
    { echo "soname is not libirrcache.so.$soname"; exit 1; }

# E against the closed form on every line of a host's output.
checked() { # name binary
    out=$("$2") || { echo "$1: exit status $?"; return 1; }
    echo "$out" | awk -v name="$1" '
        { n++; e = $6; x = $8; if (e < 0.97 * x || e > 1.03 * x) { bad = 1; print name ": " $0 } }
        END { if (n != 9 || bad) { print name ": " n " lines, " (bad ? "off" : "short"); exit 1 }
              print name ": 9 points within 3% of the closed form, e.g. " $0 }'
}
needs_soname() { # binary
    readelf -d "$1" | grep -q "NEEDED.*\[libirrcache.so.$soname\]" ||
        { echo "$1 does not need libirrcache.so.$soname"; return 1; }
}
export LD_LIBRARY_PATH="$S$P/lib"

# 1. pkg-config
export PKG_CONFIG_PATH="$S$P/lib/pkgconfig" PKG_CONFIG_SYSROOT_DIR="$S"
[ "$(pkg-config --modversion irrcache)" = "$version" ] || { echo "pkg-config: version"; exit 1; }
pkg-config --static --libs irrcache | grep -q -- -lm || { echo "pkg-config: no Libs.private"; exit 1; }
cc -std=c99 -Wall -Werror examples/minimal.c $(pkg-config --cflags --libs irrcache) -lm -o "$T/pc"
needs_soname "$T/pc"
checked "pkg-config, shared" "$T/pc"
cc -std=c99 -Wall -Werror examples/minimal.c $(pkg-config --cflags irrcache) \
    "$S$P/lib/libirrcache.a" $(pkg-config --static --libs-only-l irrcache | sed 's/-lirrcache//') \
    -o "$T/pc-static"
checked "pkg-config, static" "$T/pc-static"
unset PKG_CONFIG_PATH PKG_CONFIG_SYSROOT_DIR

# 2. CMake
cmake -S tests/consumer -B "$T/cm" -DCMAKE_PREFIX_PATH="$S$P" -DIRC_EXAMPLES="$PWD/examples" \
    >"$T/cmake.log" 2>&1 || { cat "$T/cmake.log"; exit 1; }
cmake --build "$T/cm" >>"$T/cmake.log" 2>&1 || { cat "$T/cmake.log"; exit 1; }
needs_soname "$T/cm/minimal"
checked "cmake, irrcache::irrcache" "$T/cm/minimal"
checked "cmake, irrcache::irrcache_static" "$T/cm/minimal_static"
checked "cmake, C++" "$T/cm/minimal_cpp"
if cmake -S tests/consumer -B "$T/cm-new" -DCMAKE_PREFIX_PATH="$S$P" -DIRC_EXAMPLES="$PWD/examples" \
    -DIRC_WANT=$major.$((minor + 1)) \
    >"$T/cmake-new.log" 2>&1; then
    echo "cmake: a newer version was accepted"; exit 1
fi
grep -q 'compatible with requested version' "$T/cmake-new.log" ||
    { cat "$T/cmake-new.log"; echo "cmake: failed, but not on the version"; exit 1; }
echo "cmake: a request for a newer minor version is refused"

# 3. C++
g++ -std=c++11 -Wall -Wextra -Werror -pedantic -I"$S$P/include" examples/minimal.cpp \
    -L"$S$P/lib" -lirrcache -o "$T/cpp"
needs_soname "$T/cpp"
checked "g++" "$T/cpp"

$MAKE -s BUILD=build uninstall DESTDIR="$S" PREFIX=$P
left=$(find "$S" ! -type d)
[ -z "$left" ] || { echo "left behind by uninstall: $left"; exit 1; }
echo "uninstall: nothing left"

# 4. A distribution's layout: LIBDIR and INCLUDEDIR away from PREFIX's.
D="LIBDIR=/usr/lib/x86_64-linux-gnu INCLUDEDIR=/usr/include/irrcache PREFIX=/usr"
$MAKE -s BUILD=build install DESTDIR="$T/distro" $D
PKG_CONFIG_PATH="$T/distro/usr/lib/x86_64-linux-gnu/pkgconfig" PKG_CONFIG_SYSROOT_DIR="$T/distro" \
    pkg-config --cflags irrcache | grep -q -- "-I$T/distro/usr/include/irrcache" ||
    { echo "pkg-config: INCLUDEDIR not followed"; exit 1; }
cmake -S tests/consumer -B "$T/cm-distro" -DCMAKE_PREFIX_PATH="$T/distro/usr" \
    -DIRC_EXAMPLES="$PWD/examples" >"$T/cmake-distro.log" 2>&1 &&
    cmake --build "$T/cm-distro" --target minimal >>"$T/cmake-distro.log" 2>&1 ||
    { cat "$T/cmake-distro.log"; exit 1; }
LD_LIBRARY_PATH="$T/distro/usr/lib/x86_64-linux-gnu" checked "cmake, LIBDIR and INCLUDEDIR moved" \
    "$T/cm-distro/minimal"
$MAKE -s BUILD=build uninstall DESTDIR="$T/distro" $D
left=$(find "$T/distro" ! -type d)
[ -z "$left" ] || { echo "left behind by uninstall: $left"; exit 1; }
echo "uninstall (moved LIBDIR and INCLUDEDIR): nothing left"
