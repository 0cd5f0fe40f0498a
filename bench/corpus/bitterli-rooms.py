#!/usr/bin/env python3
# bitterli-rooms.py -- three of Bitterli's Mitsuba scenes to plain OBJ + MTL, for the
# benchmark's corpus (bench/notes.md, "The corpus").
#
# Source: public GitHub repository jgarciapueyo/mitsuba2-transient-scenes,
#   commit ab67c4caa9228aa9d4115aeb90c3d3bab0aaf7b5, one folder a room (scene.xml,
#   models/Mesh*.obj, textures/, LICENSE.txt):
#   kitchen/      -> country-kitchen: "Country Kitchen" by Jay-Artist
#                    (Blend Swap, http://www.blendswap.com/blends/view/42851);
#   dining-room/  -> breakfast-room:  "The Breakfast Room" by Wig42 (Blend Swap);
#   living-room/  -> grey-white-room: "The Grey & White Room" by Wig42 (Blend Swap);
#   Mitsuba versions by Benedikt Bitterli (https://benedikt-bitterli.me/resources/).
# Licence: CC BY 3.0 (https://creativecommons.org/licenses/by/3.0/), as each folder's
#   LICENSE.txt says.  Credit: the model's author (above), Mitsuba version by Benedikt
#   Bitterli, CC BY 3.0 -- reduced to geometry and diffuse colours.
#
# Usage: python3 bench/corpus/bitterli-rooms.py ROOM SRC_DIR OUT_DIR
#   ROOM: kitchen, dining-room or living-room.
#   SRC_DIR: that folder of the repository.
#   OUT_DIR: gets NAME.obj.gz and NAME.mtl (NAME as above).
#
# What it does (deterministic: same input, same bytes out):
#   * every <shape type="obj"> of scene.xml is read, its vertices moved by its toWorld
#     matrix (row-major 4x4, Mitsuba's order), and its faces kept as they are (all
#     triangles or quads in these models), grouped by the shape's bsdf id (usemtl ID);
#   * left out: emitters (lights, not geometry: the kitchen's rectangle behind the window
#     and three strip lights under the wall cupboards); shapes whose bsdf is glass
#     (dielectric / thindielectric: the kitchen's WineGlasses, CookerGlass, MicrowaveGlass,
#     MicrowaveDigital, RadioGlass; the grey-white room's Glass); alpha-cut shapes (a "mask"
#     bsdf whose opacity is a texture: the grey-white room's Leaves); the breakfast room's
#     one "rectangle" (a Walls patch at x = -6.3, outside the room's obj walls); a "mask" of
#     constant opacity (the kitchen's rolled-up blind, 0.61) is kept, as an opaque surface;
#   * the kitchen's six meshes in ROOMS (files of 4 MiB and more that the public copies of
#     the repository lack) are skipped with a note on stderr if they are not there (used
#     when present);
#   * vertices are written with %.6g and welded where the written text is equal; a face
#     that welding leaves with a repeated corner is dropped (counted on stderr);
#   * Kd: the bsdf's diffuse colour (diffuse: reflectance; plastic/roughplastic:
#     diffuseReflectance), a texture's mean colour where textured (mean of the sRGB
#     texels converted to linear, as Mitsuba reads 8-bit bitmaps; JPEGs from their DC
#     coefficients, i.e. 8x8-block means, PNGs from every texel), 0.6 grey for metals
#     (conductor / roughconductor); every channel clamped to [0, 0.9].
# Python 3 standard library only.

import gzip
import os
import struct
import sys
import xml.etree.ElementTree as ET
import zlib

# ROOM: (output name, the model's title and author, meshes the public copies lack)
ROOMS = {
    "kitchen": ("country-kitchen", "'Country Kitchen' by Jay-Artist",
                {"models/Mesh054.obj", "models/Mesh090.obj", "models/Mesh145.obj",
                 "models/Mesh273.obj", "models/Mesh275.obj", "models/Mesh294.obj"}),
    "dining-room": ("breakfast-room", "'The Breakfast Room' by Wig42", set()),
    "living-room": ("grey-white-room", "'The Grey & White Room' by Wig42", set()),
}
GLASS = ("dielectric", "thindielectric", "roughdielectric")
METAL = ("conductor", "roughconductor")
KD_MAX = 0.9
METAL_GREY = 0.6


def note(msg):
    sys.stderr.write(msg + "\n")


# ---------------------------------------------------------------- colours

def srgb_to_linear(c):
    c = c / 255.0
    return c / 12.92 if c <= 0.04045 else ((c + 0.055) / 1.055) ** 2.4


LIN = [srgb_to_linear(i) for i in range(256)]


def png_mean_linear(data):
    """Mean linear RGB of an 8-bit, non-interlaced RGB/RGBA/grey PNG."""
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        raise ValueError("not a PNG")
    pos, idat, hdr = 8, [], None
    while pos < len(data):
        n, typ = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + n]
        pos += 12 + n
        if typ == b"IHDR":
            hdr = struct.unpack(">IIBBBBB", body)
        elif typ == b"IDAT":
            idat.append(body)
        elif typ == b"IEND":
            break
    w, h, depth, ctype, _, _, interlace = hdr
    if depth != 8 or interlace != 0 or ctype not in (0, 2, 4, 6):
        raise ValueError("unsupported PNG")
    bpp = {0: 1, 2: 3, 4: 2, 6: 4}[ctype]
    raw = zlib.decompress(b"".join(idat))
    stride = w * bpp
    prev = bytearray(stride)
    sums = [0.0, 0.0, 0.0]
    i = 0
    for _ in range(h):
        ft = raw[i]
        line = bytearray(raw[i + 1:i + 1 + stride])
        i += 1 + stride
        if ft == 1:
            for x in range(bpp, stride):
                line[x] = (line[x] + line[x - bpp]) & 255
        elif ft == 2:
            for x in range(stride):
                line[x] = (line[x] + prev[x]) & 255
        elif ft == 3:
            for x in range(stride):
                a = line[x - bpp] if x >= bpp else 0
                line[x] = (line[x] + ((a + prev[x]) >> 1)) & 255
        elif ft == 4:
            for x in range(stride):
                a = line[x - bpp] if x >= bpp else 0
                b = prev[x]
                c = prev[x - bpp] if x >= bpp else 0
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                pr = a if (pa <= pb and pa <= pc) else (b if pb <= pc else c)
                line[x] = (line[x] + pr) & 255
        if ctype in (2, 6):
            for k in range(3):
                sums[k] += sum(LIN[v] for v in line[k::bpp])
        else:
            s = sum(LIN[v] for v in line[0::bpp])
            for k in range(3):
                sums[k] += s
        prev = line
    return [s / (w * h) for s in sums]


def _huff_table(counts, syms):
    """Canonical Huffman codes -> {bitstring: symbol}."""
    table, code, k = {}, 0, 0
    for length in range(1, 17):
        for _ in range(counts[length - 1]):
            table[format(code, "0%db" % length)] = syms[k]
            k += 1
            code += 1
        code <<= 1
    return table


def _extend(bits, s):
    v = int(bits, 2)
    return v - (1 << s) + 1 if v < (1 << (s - 1)) else v


def _decode(bits, p, table):
    for length in range(1, 17):
        sym = table.get(bits[p:p + length])
        if sym is not None:
            return sym, p + length
    raise ValueError("bad Huffman code")


def jpeg_mean_linear(data):
    """Mean linear RGB of a baseline or progressive JPEG from its DC coefficients
    (the first DC scan of a progressive file; the full scan of a baseline one)."""
    if data[:2] != b"\xff\xd8":
        raise ValueError("not a JPEG")
    pos, qt, huff, comps = 2, {}, {}, []
    restart, adobe_transform, jfif = 0, None, False
    X = Y = 0
    dc = {}          # component id -> {(bx, by): DC value}
    while pos < len(data):
        if data[pos] != 0xFF:
            raise ValueError("marker expected")
        while data[pos] == 0xFF:
            pos += 1
        marker = data[pos]
        pos += 1
        if marker == 0xD8 or 0xD0 <= marker <= 0xD7 or marker == 0x01:
            continue
        if marker == 0xD9:
            break
        seglen = struct.unpack(">H", data[pos:pos + 2])[0]
        seg = data[pos + 2:pos + seglen]
        pos += seglen
        if marker == 0xE0 and seg[:5] == b"JFIF\0":
            jfif = True
        elif marker == 0xEE and seg[:5] == b"Adobe" and len(seg) >= 12:
            adobe_transform = seg[11]
        elif marker == 0xDB:
            i = 0
            while i < len(seg):
                pq, tq = seg[i] >> 4, seg[i] & 15
                i += 1
                if pq == 0:
                    qt[tq] = seg[i]
                    i += 64
                else:
                    qt[tq] = struct.unpack(">H", seg[i:i + 2])[0]
                    i += 128
        elif marker in (0xC0, 0xC1, 0xC2):
            Y, X, nf = struct.unpack(">HHB", seg[1:6])
            comps = []
            for k in range(nf):
                cid, hv, tq = seg[6 + 3 * k:9 + 3 * k]
                comps.append({"id": cid, "h": hv >> 4, "v": hv & 15, "tq": tq})
                dc.setdefault(cid, {})
        elif marker in (0xC3, 0xC5, 0xC6, 0xC7, 0xC9, 0xCA, 0xCB, 0xCD, 0xCE, 0xCF):
            raise ValueError("unsupported JPEG process")
        elif marker == 0xC4:
            i = 0
            while i < len(seg):
                tc, th = seg[i] >> 4, seg[i] & 15
                counts = list(seg[i + 1:i + 17])
                n = sum(counts)
                huff[(tc, th)] = _huff_table(counts, list(seg[i + 17:i + 17 + n]))
                i += 17 + n
        elif marker == 0xDD:
            restart = struct.unpack(">H", seg[:2])[0]
        elif marker == 0xDA:
            ns = seg[0]
            sc = []
            for k in range(ns):
                cid, t = seg[1 + 2 * k], seg[2 + 2 * k]
                sc.append((cid, t >> 4, t & 15))
            ss, se, ahal = seg[1 + 2 * ns], seg[2 + 2 * ns], seg[3 + 2 * ns]
            ah, al = ahal >> 4, ahal & 15
            # the entropy-coded data runs to the next marker other than RSTn
            end = pos
            while True:
                end = data.index(b"\xff", end)
                nxt = data[end + 1]
                if nxt == 0 or 0xD0 <= nxt <= 0xD7:
                    end += 2
                    continue
                break
            ecs = data[pos:end]
            pos = end
            if ss != 0 or ah != 0:
                continue    # AC or refinement scan: nothing for the mean
            _scan_dc(ecs, sc, comps, huff, restart, X, Y, al, ss == 0 and se == 0, dc)
    hmax = max(c["h"] for c in comps)
    vmax = max(c["v"] for c in comps)
    vals = []
    for c in comps:
        q = qt[c["tq"]]
        vals.append({k: v * q / 8.0 + 128.0 for k, v in dc[c["id"]].items()})
    c0 = comps[0]
    bw = -(-(-(-X * c0["h"] // hmax)) // 8)  # ceil(ceil(X h / hmax) / 8)
    bh = -(-(-(-Y * c0["v"] // vmax)) // 8)
    if len(comps) == 3:
        ycc = adobe_transform != 0 if adobe_transform is not None else True
    else:
        ycc = False
    sums, n = [0.0, 0.0, 0.0], 0
    for by in range(bh):
        for bx in range(bw):
            px, py = bx * 8 * hmax // c0["h"], by * 8 * vmax // c0["v"]
            cs = []
            for ci, c in enumerate(comps):
                key = ((px * c["h"] // hmax) // 8, (py * c["v"] // vmax) // 8)
                cs.append(vals[ci].get(key, 128.0))
            if len(comps) == 1:
                rgb = [cs[0]] * 3
            elif ycc:
                yv, cb, cr = cs[0], cs[1] - 128.0, cs[2] - 128.0
                rgb = [yv + 1.402 * cr, yv - 0.344136 * cb - 0.714136 * cr, yv + 1.772 * cb]
            else:
                rgb = cs[:3]
            for k in range(3):
                v = min(255.0, max(0.0, rgb[k]))
                sums[k] += srgb_to_linear(v)
            n += 1
    return [s / n for s in sums]


def _scan_dc(ecs, sc, comps, huff, restart, X, Y, al, dc_only, dc):
    byid = {c["id"]: c for c in comps}
    hmax = max(c["h"] for c in comps)
    vmax = max(c["v"] for c in comps)
    # split at restart markers, unstuff, turn into a bit string per interval
    parts, cur, i = [], bytearray(), 0
    while i < len(ecs):
        b = ecs[i]
        if b == 0xFF and i + 1 < len(ecs):
            nb = ecs[i + 1]
            if nb == 0:
                cur.append(0xFF)
                i += 2
                continue
            if 0xD0 <= nb <= 0xD7:
                parts.append(cur)
                cur = bytearray()
                i += 2
                continue
        cur.append(b)
        i += 1
    parts.append(cur)
    if len(sc) == 1:
        c = byid[sc[0][0]]
        cw = -(-X * c["h"] // hmax)
        ch = -(-Y * c["v"] // vmax)
        units = [[(sc[0], bx, by)] for by in range(-(-ch // 8)) for bx in range(-(-cw // 8))]
    else:
        mx = -(-X // (8 * hmax))
        my = -(-Y // (8 * vmax))
        units = []
        for m in range(mx * my):
            ux, uy = m % mx, m // mx
            u = []
            for s in sc:
                c = byid[s[0]]
                for v in range(c["v"]):
                    for h in range(c["h"]):
                        u.append((s, ux * c["h"] + h, uy * c["v"] + v))
            units.append(u)
    per = restart if restart else len(units)
    for pi, part in enumerate(parts):
        chunk = units[pi * per:(pi + 1) * per]
        if not chunk:
            break
        bits = "".join(format(b, "08b") for b in part)
        p = 0
        pred = {s[0]: 0 for s in sc}
        for u in chunk:
            for (cid, td, ta), bx, by in u:
                s, p = _decode(bits, p, huff[(0, td)])
                diff = 0
                if s:
                    diff = _extend(bits[p:p + s], s)
                    p += s
                pred[cid] += diff
                dc[cid][(bx, by)] = pred[cid] << al
                if dc_only:
                    continue
                k = 1
                tab = huff[(1, ta)]
                while k < 64:
                    rs, p = _decode(bits, p, tab)
                    r, s = rs >> 4, rs & 15
                    if s == 0:
                        if r == 15:
                            k += 16
                            continue
                        break
                    k += r
                    p += s
                    k += 1


def texture_mean(path):
    with open(path, "rb") as f:
        data = f.read()
    if data[:8] == b"\x89PNG\r\n\x1a\n":
        return png_mean_linear(data)
    return jpeg_mean_linear(data)


# ---------------------------------------------------------------- scene.xml

def rgb_of(el):
    """An <rgb>/<spectrum>/<float> value as three floats."""
    v = el.get("value").replace(",", " ").split()
    v = [float(x) for x in v]
    return v * 3 if len(v) == 1 else v[:3]


def leaf_bsdf(b):
    """Follow twosided/mask wrappers to the bsdf that has the colour."""
    while b.get("type") in ("twosided", "mask", "bumpmap"):
        inner = b.find("bsdf")
        if inner is None:
            break
        b = inner
    return b


def material_kd(b, src, cache):
    """(kind, Kd, how) for a top-level bsdf element."""
    t = b.get("type")
    if t in GLASS:
        return "glass", None, t
    if t == "mask":
        op = b.find("*[@name='opacity']")
        if op.tag == "texture":     # alpha-cut leaves: left out
            return "alpha", None, "mask of opacity %s" % op.find("string").get("value")
        # the kitchen's roller blind: kept, opaque, with the colour under the mask
        kind, kd, how = material_kd(b.find("bsdf"), src, cache)
        return kind, kd, "mask of opacity %s, kept opaque: %s" % (
            b.find("*[@name='opacity']").get("value"), how)
    leaf = leaf_bsdf(b)
    lt = leaf.get("type")
    if lt in GLASS:
        return "glass", None, lt
    if lt in METAL:
        return "ok", [METAL_GREY] * 3, "metal (%s): %.1f grey" % (lt, METAL_GREY)
    name = "reflectance" if lt == "diffuse" else "diffuseReflectance"
    for child in leaf:
        if child.get("name") != name:
            continue
        if child.tag == "texture":
            fn = child.find("string[@name='filename']").get("value")
            if fn not in cache:
                cache[fn] = texture_mean(os.path.join(src, fn))
            return "ok", list(cache[fn]), "%s: mean of %s" % (lt, fn)
        return "ok", rgb_of(child), "%s %s" % (lt, name)
    return "ok", [0.5] * 3, "%s: no colour given, 0.5 grey (Mitsuba's default)" % lt


def matrix_of(shape):
    tr = shape.find("transform[@name='toWorld']")
    if tr is None:
        return None
    kids = list(tr)
    if len(kids) != 1 or kids[0].tag != "matrix":
        raise ValueError("only a single <matrix> toWorld is handled")
    m = [float(x) for x in kids[0].get("value").replace(",", " ").split()]
    if m == [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]:
        return None
    return m


def read_obj(path):
    """Positions and faces (lists of 0-based position indices) of an OBJ file."""
    vs, fs = [], []
    with open(path, "r") as f:
        for line in f:
            if line.startswith("v "):
                p = line.split()
                vs.append((float(p[1]), float(p[2]), float(p[3])))
            elif line.startswith("f "):
                idx = []
                for tok in line.split()[1:]:
                    i = int(tok.split("/")[0])
                    idx.append(i - 1 if i > 0 else len(vs) + i)
                fs.append(idx)
    return vs, fs


def main():
    if len(sys.argv) != 4 or sys.argv[1] not in ROOMS:
        sys.exit("usage: python3 bitterli-rooms.py kitchen|dining-room|living-room SRC_DIR OUT_DIR")
    name, title, absent = ROOMS[sys.argv[1]]
    src, out = sys.argv[2], sys.argv[3]
    os.makedirs(out, exist_ok=True)
    root = ET.parse(os.path.join(src, "scene.xml")).getroot()
    cache = {}
    mats = {}
    for b in root.iter("bsdf"):     # ids sit on top-level bsdfs, or inside a bumpmap
        if b.get("id") is not None:
            mats[b.get("id")] = material_kd(b, src, cache)

    vindex = {}          # written text -> 1-based index
    vtext = []
    groups = {}          # material -> list of face strings
    order = []           # materials in first-use order
    stats = {"shapes": 0, "skipped_absent": [], "left_out": {}, "dropped": 0, "tris": 0}
    for shape in root.findall("shape"):
        if shape.find("emitter") is not None:
            stats["left_out"].setdefault("emitter rectangles", 0)
            stats["left_out"]["emitter rectangles"] += 1
            continue
        if shape.get("type") == "rectangle":
            stats["left_out"].setdefault("rectangles", 0)
            stats["left_out"]["rectangles"] += 1
            continue
        if shape.get("type") != "obj":
            raise ValueError("unexpected shape type %s" % shape.get("type"))
        fn = shape.find("string[@name='filename']").get("value")
        ref = shape.find("ref")
        if ref is None:
            raise ValueError("shape %s has no bsdf ref" % fn)
        mid = ref.get("id")
        kind = mats[mid][0]
        if kind != "ok":
            stats["left_out"].setdefault(mid, 0)
            stats["left_out"][mid] += 1
            continue
        path = os.path.join(src, fn)
        if not os.path.exists(path):
            if fn in absent:
                stats["skipped_absent"].append((fn, mid))
                note("absent, skipped: %s (%s)" % (fn, mid))
                continue
            raise FileNotFoundError(path)
        stats["shapes"] += 1
        vs, fs = read_obj(path)
        m = matrix_of(shape)
        local = []
        for (x, y, z) in vs:
            if m is not None:
                x, y, z = (m[0] * x + m[1] * y + m[2] * z + m[3],
                           m[4] * x + m[5] * y + m[6] * z + m[7],
                           m[8] * x + m[9] * y + m[10] * z + m[11])
            t = "%.6g %.6g %.6g" % (x, y, z)
            k = vindex.get(t)
            if k is None:
                vtext.append(t)
                k = vindex[t] = len(vtext)
            local.append(k)
        if mid not in groups:
            groups[mid] = []
            order.append(mid)
        g = groups[mid]
        for f in fs:
            idx = [local[i] for i in f]
            if len(set(idx)) != len(idx):
                stats["dropped"] += 1
                continue
            g.append("f " + " ".join(str(i) for i in idx))
            stats["tris"] += len(idx) - 2

    # materials: only those used, in first-use order
    with open(os.path.join(out, name + ".mtl"), "w", newline="\n") as f:
        f.write("# %s.mtl -- diffuse albedo per Mitsuba bsdf of Bitterli's version of\n" % name)
        f.write("# %s (CC BY 3.0); made by bitterli-rooms.py\n" % title)
        for mid in order:
            kd = [min(KD_MAX, max(0.0, c)) for c in mats[mid][1]]
            f.write("\n# %s\nnewmtl %s\nKd %.4f %.4f %.4f\n" % (mats[mid][2], mid, kd[0], kd[1], kd[2]))
    objpath = os.path.join(out, name + ".obj.gz")
    with open(objpath, "wb") as raw:
        with gzip.GzipFile(filename="", mode="wb", fileobj=raw, compresslevel=9, mtime=0) as gz:
            w = []
            w.append("# %s.obj -- %s (Blend Swap), Mitsuba version by\n" % (name, title))
            w.append("# Benedikt Bitterli; CC BY 3.0 https://creativecommons.org/licenses/by/3.0/\n")
            w.append("# geometry only (materials: %s.mtl), made by bitterli-rooms.py; +y up\n" % name)
            gz.write("".join(w).encode())
            buf = []
            for t in vtext:
                buf.append("v " + t + "\n")
                if len(buf) >= 65536:
                    gz.write("".join(buf).encode())
                    buf = []
            for mid in order:
                buf.append("usemtl %s\n" % mid)
                for fl in groups[mid]:
                    buf.append(fl + "\n")
                    if len(buf) >= 65536:
                        gz.write("".join(buf).encode())
                        buf = []
            gz.write("".join(buf).encode())
    note("shapes: %d, vertices: %d, triangles: %d, faces dropped (degenerate after welding): %d"
         % (stats["shapes"], len(vtext), stats["tris"], stats["dropped"]))
    note("left out: %s" % ", ".join("%s x%d" % kv for kv in sorted(stats["left_out"].items())))
    note("absent meshes skipped: %s" % ", ".join("%s (%s)" % a for a in stats["skipped_absent"]))
    for mid in order:
        note("  %-20s %-60s %s" % (mid, mats[mid][2], " ".join("%.3f" % c for c in mats[mid][1])))


if __name__ == "__main__":
    main()
