#!/bin/sh
# embedded/size.sh -- make size: what the library costs in code, data,
# stack and block bytes, for the build machine (x86-64, -O2) and for a
# Cortex-M4F (-Os, the none port).  Prints
#   1. .text/.data/.bss of every object, both targets;
#   2. the library's bytes linked into the two smallest hosts
#      (embedded/size_host.c: irradiance with trans + rot gradients, and SH
#      with gradients) on the M4F with --gc-sections;
#   3. block bytes per record for each feature set, and per index node;
#   4. the worst-case stack of every public entry point on the M4F (and of
#      the irradiance calls of the build with every IRC_NO_* switch)
#      (embedded/stack.awk), and fails if any library function can reach
#      itself (no recursion);
#   5. double precision on the M4F (single-precision FPU): -Wdouble-promotion
#      warnings per file of src/, and calls to libgcc's double routines in
#      the irradiance host.
set -eu
cd "$(dirname "$0")/.."
CROSS=${CROSS:-arm-none-eabi-}
CC=${CC:-cc}
B=build-size
M4="-mcpu=cortex-m4 -mfpu=fpv4-sp-d16 -mfloat-abi=hard -mthumb"
FLAGS="-std=c99 -Iinclude -fno-math-errno -fstack-usage -fcallgraph-info=su"
sh embedded/need.sh
rm -rf $B
mkdir -p $B/x86 $B/m4
for f in src/*.c src/*/*.c port/none/irc_port.c port/irc_port_default.c port/unbuilt.c; do
    o=$(basename "$f" .c)
    $CC $FLAGS -O2 -DIRC_PORT_DEFAULT=irc_port_none -c "$f" -o $B/x86/$o.o
    ${CROSS}gcc $FLAGS $M4 -Os -ffunction-sections -fdata-sections \
        -DIRC_PORT_DEFAULT=irc_port_none -c "$f" -o $B/m4/$o.o
done
${CROSS}ar rcs $B/m4/libirrcache.a $B/m4/*.o
# The same with what an irradiance-only firmware leaves out (util.h).
mkdir -p $B/m4-irr
for f in src/*.c src/*/*.c port/none/irc_port.c port/irc_port_default.c port/unbuilt.c; do
    ${CROSS}gcc $FLAGS $M4 -Os -ffunction-sections -fdata-sections \
        -DIRC_NO_SH -DIRC_NO_VISIBILITY -DIRC_NO_HESSIAN -DIRC_NO_SIGHT -DIRC_NO_SUPERSAMPLE \
        -DIRC_NO_GUARD -DIRC_PORT_DEFAULT=irc_port_none \
        -c "$f" -o $B/m4-irr/$(basename "$f" .c).o
done
${CROSS}ar rcs $B/m4-irr/libirrcache.a $B/m4-irr/*.o

echo "1. bytes per object: x86-64 -O2 | Cortex-M4F -Os"
printf '  %-18s %7s %5s %5s | %7s %5s %5s\n' object text data bss text data bss
size $B/x86/*.o | awk 'NR > 1 { n = $6; sub(/.*\//, "", n); print n, $1, $2, $3 }' | sort > $B/x86.txt
${CROSS}size $B/m4/*.o | awk 'NR > 1 { n = $6; sub(/.*\//, "", n); print n, $1, $2, $3 }' | sort > $B/m4.txt
join $B/x86.txt $B/m4.txt | awk '
    { printf "  %-18s %7d %5d %5d | %7d %5d %5d\n", $1, $2, $3, $4, $5, $6, $7
      for (i = 2; i <= 7; i++) t[i] += $i }
    END { printf "  %-18s %7d %5d %5d | %7d %5d %5d\n", "total", t[2], t[3], t[4], t[5], t[6], t[7] }'

echo "2. library bytes linked into a host (Cortex-M4F, --gc-sections): text+rodata, data, bss"
for v in irr sh irr-switched; do
    def=""
    lib=$B/m4/libirrcache.a
    [ $v = sh ] && def="-DSIZE_SH"
    [ $v = irr-switched ] && lib=$B/m4-irr/libirrcache.a
    ${CROSS}gcc -std=c99 $M4 -Os -ffunction-sections -fdata-sections $def -Iinclude -Iembedded \
        embedded/size_host.c embedded/board.c $lib --specs=rdimon.specs \
        -nostartfiles -T embedded/mps2.ld -Wl,--gc-sections -Wl,-Map=$B/$v.map -lm -o $B/$v.elf
    # Input sections from the library's archive, after the map's list of
    # discarded ones; a long section name puts its address and size on
    # the next line.
    awk -v v=$v '
        function hex(s,   i, n) {
            n = 0
            s = tolower(substr(s, 3))
            for (i = 1; i <= length(s); i++) n = n * 16 + index("0123456789abcdef", substr(s, i, 1)) - 1
            return n
        }
        /^Linker script and memory map/ { on = 1 }
        !on { next }
        /^ \.[a-zA-Z_.]+ *$/ { sec = $1; next }
        /libirrcache\.a\(/ {
            if ($1 ~ /^\./) { s = $1; sz = $3 } else { s = sec; sz = $2 }
            n = hex(sz)
            if (s ~ /^\.(text|rodata)/) code += n; else if (s ~ /^\.data/) data += n
            else if (s ~ /^\.bss/) bss += n
        }
        END { printf "  %-34s %7d %5d %5d\n", v == "irr" ? "irradiance, trans + rot gradients" : v == "sh" ? "SH L = 3 with gradients" : "the first, with the IRC_NO_* switches", code, data, bss }' $B/$v.map
done

echo "3. block bytes"
$CC -std=c99 -O2 -Iinclude -DSIZE_PRINT embedded/size_host.c $B/x86/*.o -o $B/per_record -lm
$B/per_record
if $CC -m32 -std=c99 -O2 -Iinclude -DSIZE_PRINT embedded/size_host.c src/*.c src/*/*.c port/none/irc_port.c \
        port/irc_port_default.c -DIRC_PORT_DEFAULT=irc_port_none -o $B/per_record32 -lm 2>/dev/null; then
    # a kernel without IA-32 emulation cannot run it (status 126): said
    $B/per_record32 2>/dev/null || { [ $? -eq 126 ] && echo "  (32-bit figures: this kernel runs no i386 programs)"; } ||
        exit 1
fi
printf '  %-34s %7d\n' "an index node (8 per 4 records)" 12
printf '  %-34s %7d\n' "an index reference (8 a record)" 16

echo "4. worst-case stack of each entry point, Cortex-M4F (bytes; the host's callbacks not counted)"
entries=$(sed -n 's/^IRC_API [^(]*[ *]\(irc_[a-z0-9_]*\)(.*/\1/p' include/irrcache.h | tr '\n' ' ')
irr=$(echo "$entries" | tr ' ' '\n' | grep -v '^irc_sh_' | grep -v '^irc_cache_lookup_gradient$' |
    tr '\n' ' ')
shs=$(echo "$entries" | tr ' ' '\n' | grep '^irc_sh_' | tr '\n' ' ')
# The check can fail: a made-up graph where a reaches b and b reaches a.
printf '%s\n' 'node: { title: "a" label: "a\nx.c:1:1\n8 bytes (static)" }' \
    'node: { title: "b" label: "b\nx.c:2:1\n8 bytes (static)" }' \
    'edge: { sourcename: "a" targetname: "b" }' 'edge: { sourcename: "b" targetname: "a" }' > $B/cycle.ci
if awk -v kind=irr -v map=embedded/indirect.txt -v entries=a -f embedded/stack.awk $B/cycle.ci >/dev/null; then
    echo "stack.awk missed a cycle"
    exit 1
fi
st=0
echo "  irradiance caches (target 1024):"
awk -v kind=irr -v map=embedded/indirect.txt -v entries="$irr" -f embedded/stack.awk \
    $B/m4/*.ci > $B/stack-irr.txt || st=1
# The gradient lookup's own accumulator (irrg: in indirect.txt).
awk -v kind=irrg -v map=embedded/indirect.txt -v entries=irc_cache_lookup_gradient \
    -f embedded/stack.awk $B/m4/*.ci >> $B/stack-irr.txt || st=1
sed 's/^/    /' $B/stack-irr.txt
echo "  SH caches (target 4096):"
awk -v kind=sh -v map=embedded/indirect.txt -v entries="$shs $irr" -f embedded/stack.awk \
    $B/m4/*.ci > $B/stack-sh.txt || st=1
sed 's/^/    /' $B/stack-sh.txt
echo "  the irradiance calls of the library built with the six IRC_NO_* switches:"
awk -v kind=irr -v map=embedded/indirect.txt \
    -v entries="irc_cache_lookup_or_compute irc_cache_lookup irc_cache_insert irc_record_compute" \
    -f embedded/stack.awk $B/m4-irr/*.ci > $B/stack-switched.txt || st=1
# (the calls this build leaves out are named in indirect.txt: not an error here)
grep -v 'is not a library function' $B/stack-switched.txt | sed 's/^/    /' 
[ $st -eq 0 ] && echo "  no recursion" || echo "  FAIL: recursion (above)"

echo "5. double precision on the Cortex-M4F"
for f in src/*.c src/*/*.c; do
    ${CROSS}gcc -std=c99 $M4 -Os -Iinclude -Wdouble-promotion -c "$f" -o /dev/null 2>&1
done | grep 'warning:' | cut -d: -f1 | sort | uniq -c | sort -rn |
    awk '{ printf "  %-22s %4d -Wdouble-promotion warnings\n", $2, $1; t += $1 }
         END { printf "  %-22s %4d\n", "total", t }'
printf '  %-22s %4d calls to __aeabi_d* (software double)\n' "irradiance host" \
    "$(${CROSS}objdump -d $B/irr.elf | grep -c 'bl.*<__aeabi_d')"
exit $st
