#!/bin/sh
# tests/corpus.sh -- bench/corpus/bitterli-rooms.py on a room of its own: a
# quad under each kind of bsdf the script sorts (diffuse, rough plastic,
# metal, glass, alpha-cut and constant masks), a rectangle and an emitter;
# the output checked against the rules its header states.  Exit 0 if all
# hold.
set -u
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
mkdir -p "$T/room/models" "$T/out"
printf 'v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n' > "$T/room/models/a.obj"
shape() { # bsdf-id [matrix]
    printf '<shape type="obj"><string name="filename" value="models/a.obj"/>'
    [ -n "${2:-}" ] && printf '<transform name="toWorld"><matrix value="%s"/></transform>' "$2"
    printf '<ref id="%s"/></shape>\n' "$1"
}
{
    echo '<scene version="0.5.0">'
    echo '<bsdf type="twosided" id="Red"><bsdf type="diffuse"><rgb name="reflectance" value="0.5, 0.25, 0.125"/></bsdf></bsdf>'
    echo '<bsdf type="twosided" id="Shiny"><bsdf type="roughplastic"><rgb name="diffuseReflectance" value="1.5"/></bsdf></bsdf>'
    echo '<bsdf type="roughconductor" id="Metal"/>'
    echo '<bsdf type="dielectric" id="Glass"/>'
    echo '<bsdf type="mask" id="Leaves"><texture name="opacity" type="bitmap"><string name="filename" value="textures/leaf.png"/></texture><bsdf type="diffuse"/></bsdf>'
    echo '<bsdf type="mask" id="Blind"><float name="opacity" value="0.5"/><bsdf type="diffuse"><rgb name="reflectance" value="0.3"/></bsdf></bsdf>'
    shape Red "1 0 0 10 0 1 0 0 0 0 1 0 0 0 0 1"
    shape Shiny
    shape Metal
    shape Glass
    shape Leaves
    shape Blind
    echo '<shape type="rectangle"><ref id="Red"/></shape>'
    echo '<shape type="obj"><string name="filename" value="models/a.obj"/><emitter type="area"/></shape>'
    echo '</scene>'
} > "$T/room/scene.xml"
fail=0
no() { echo "corpus.sh: $*"; fail=1; }
python3 bench/corpus/bitterli-rooms.py living-room "$T/room" "$T/out" 2>"$T/log" || no "the script failed: $(cat "$T/log")"
O="$T/out/grey-white-room"
gzip -dc "$O.obj.gz" > "$T/a.obj" 2>/dev/null || no "no $O.obj.gz"
# four corners moved by +10 in x, four shared by the three untranslated copies (welded)
[ "$(grep -c '^v ' "$T/a.obj")" = 8 ] || no "$(grep -c '^v ' "$T/a.obj") vertices, 8 expected"
grep -qx 'v 11 1 0' "$T/a.obj" || no "the toWorld translation is not applied"
[ "$(grep -c '^f ' "$T/a.obj")" = 4 ] || no "$(grep -c '^f ' "$T/a.obj") faces, 4 expected"
[ "$(grep '^usemtl' "$T/a.obj" | tr '\n' ' ')" = "usemtl Red usemtl Shiny usemtl Metal usemtl Blind " ] ||
    no "groups: $(grep '^usemtl' "$T/a.obj" | tr '\n' ' ') (glass, alpha-cut, emitter and rectangle kept?)"
kd() { awk -v m="$1" '$1 == "newmtl" { cur = $2 } $1 == "Kd" && cur == m { print $2, $3, $4 }' "$O.mtl"; }
[ "$(kd Red)" = "0.5000 0.2500 0.1250" ] || no "Red's Kd $(kd Red)"
[ "$(kd Shiny)" = "0.9000 0.9000 0.9000" ] || no "Shiny's Kd $(kd Shiny): 1.5 clamped to 0.9 expected"
[ "$(kd Metal)" = "0.6000 0.6000 0.6000" ] || no "Metal's Kd $(kd Metal)"
[ "$(kd Blind)" = "0.3000 0.3000 0.3000" ] || no "Blind's Kd $(kd Blind): the colour under the mask expected"
grep -q 'Glass\|Leaves' "$O.mtl" && no "glass or alpha-cut material written"
# deterministic: the same bytes again
cp "$O.obj.gz" "$T/first.gz"
python3 bench/corpus/bitterli-rooms.py living-room "$T/room" "$T/out" 2>/dev/null
cmp -s "$O.obj.gz" "$T/first.gz" || no "a second run wrote other bytes"
exit $fail
