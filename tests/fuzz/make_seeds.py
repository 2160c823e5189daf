#!/usr/bin/env python3
"""Writes the seed corpora of the fuzz harnesses (tests/fuzz/corpus/{obj,core,image,mtl_texture}).

The files are committed; run this again only to change them:
    python3 tests/fuzz/make_seeds.py
Each seed is small and aims at one feature, so libFuzzer starts from inputs that already
reach every statement of the OBJ/MTL grammar, every call of the core's API and every
branch of the image writer, and mutates from there.
"""
import os
import struct
import zlib

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))


def out(harness, name, data):
    d = os.path.join(HERE, "corpus", harness)
    os.makedirs(d, exist_ok=True)
    if isinstance(data, str):
        data = data.encode("latin-1")
    with open(os.path.join(d, name), "wb") as f:
        f.write(data)


# ---- OBJ / MTL ---------------------------------------------------------------------
# fuzz_obj reads OBJ text, then optionally "\n%%MTL\n" and the text of m.mtl.

MTL = """# every MTL statement the loader knows
newmtl white
Kd 0.74 0.73 0.70
Ka 0 0 0
Ks 0 0 0
Ns 10
Ni 1.5
d 1
Tr 0
Tf 1 1 1
illum 2
map_Kd white.png
bump b.png
newmtl light
Kd 0.78
Ke 18.0 12.8 4.4
newmtl red
Kd 0.62 0.07 0.05
Pr 0.5
Pm 0
aniso 0
unknown_mtl_statement 1 2 3
"""


def obj_seeds():
    out("obj", "all_statements.obj", """# every OBJ statement form
mtllib m.mtl
o object_one
g group_a group_b
s 1
v 0 0 0
v 1.0 0 0
v 1 1 0 1.0
v 0 1 0 0.5 0.5 0.5
v +2 -0 .5
v 1e-3 2E+1 -3.5e-2
vt 0 0
vt 1 0 0
vn 0 0 1
vp 0.5
vp 0.5 0.5 1
usemtl white
f 1 2 3
f 1/1 2/2 3/2
f 1//1 2//1 3//1
f 1/1/1 2/2/1 3/2/1 4/1/1
f -4 -3 -2 -1
f -6/-2/-1 -5/-1/-1 -4//-1
usemtl light
f 1 2 3 4 5 6
l 1 2 3
p 1 2
mg 1 0.5
s off
g
o
usemtl mat#1   # a name with a hash, then a comment
f 4 3 2 1
cstype bezier
unknown_statement a b c
%%MTL
""" + MTL)
    out("obj", "crlf.obj", "mtllib m.mtl\r\nv 0 0 0\r\nv 1 0 0\r\nv 0 1 0\r\nusemtl red\r\nf 1 2 3\r\n"
        "\r\n%%MTL\n" + MTL.replace("\n", "\r\n"))
    out("obj", "continuation.obj", "v 0 0 \\\n 0\nv 1 \\\n0 0\nv 0 1 0\nf 1 \\\n 2 \\\n\t3\n"
        "# a comment \\\n that continues\nf 3 2 1 \\")
    out("obj", "concave.obj", """# concave n-gons, a polygon with a bridged hole, a spike
v 0 0 0
v 4 0 0
v 4 4 0
v 2 1 0
v 0 4 0
f 1 2 3 4 5
v 0 0 1
v 10 0 1
v 10 10 1
v 0 10 1
v 3 3 1
v 3 7 1
v 7 7 1
v 7 3 1
f 6 7 8 9 6 10 13 12 11 10 9
v 5 5 1
f 6 7 14 7 8
""")
    out("obj", "degenerate.obj", """v 0 0 0
v 1 0 0
v 2 0 0
v 0 0 0
f 1 2 3
f 1 1 1
f 1 4 2 3
f 1 2 1 2 1 2
""")
    out("obj", "numbers.obj", "v 1e30 -1e30 0\nv 1e-300 0.000000000000000000001 1\n"
        "v 123456789012345678901234567890 -0 +0\nv 0.5 .5 5.\nf 1 2 3\nf 1 2 3 4\n")
    out("obj", "whitespace.obj", "\n\n  \t v\t0 0 0  \n\v\fv 1 0 0\nv 0 1 0\f\n   f   1   2   3   \n\n#\n#end")
    out("obj", "cornell.obj", open(os.path.join(ROOT, "examples", "cornell_box.obj")).read()
        .replace("mtllib cornell_box.mtl", "mtllib m.mtl") + "\n%%MTL\n"
        + open(os.path.join(ROOT, "examples", "cornell_box.mtl")).read())
    out("obj", "spaces_in_mtllib.obj", "mtllib m.mtl other.mtl\nmtllib my mats.mtl\nmtllib m.mtl\n"
        "usemtl light\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nusemtl undefined_one\nf 3 2 1\n%%MTL\n" + MTL)
    out("obj", "mtl_redefined.obj", "mtllib m.mtl\nusemtl a\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n%%MTL\n"
        "newmtl a\nKd 0.1\nnewmtl a\nKd 0.2 0.3 0.4\nKe 1\n")
    out("obj", "no_basedir_warning.obj", "mtllib missing.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")
    errors = {
        "err_index0.obj": "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n",
        "err_index_range.obj": "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n",
        "err_index_negative.obj": "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -1 -2 -4\n",
        "err_index_huge.obj": "v 0 0 0\nf 1 99999999999999999999 2\n",
        "err_face_vertex.obj": "v 0 0 0\nf 1/2/3/4 1 1\nf 1/x 1 1\n",
        "err_face_short.obj": "v 0 0 0\nv 1 0 0\nf 1 2\n",
        "err_vertex_short.obj": "v 0 0\n",
        "err_nan.obj": "v nan 0 0\n",
        "err_inf.obj": "v inf 0 0\n",
        "err_hex.obj": "v 0x1p3 0 0\n",
        "err_big.obj": "v 1e31 0 0\n",
        "err_bad_number.obj": "v 1.2.3 0 0\n",
        "err_exp.obj": "v 1e 0 0\n",
        "err_nul.obj": "v 0 0 0\x00\n",
        "err_usemtl.obj": "usemtl   \n",
        "err_mtllib.obj": "mtllib\n",
        "err_kd_first.obj": "mtllib m.mtl\n%%MTL\nKd 1 1 1\n",
        "err_kd_negative.obj": "mtllib m.mtl\n%%MTL\nnewmtl a\nKd -1\n",
        "err_kd_two.obj": "mtllib m.mtl\n%%MTL\nnewmtl a\nKd 1 1\n",
        "err_kd_four.obj": "mtllib m.mtl\n%%MTL\nnewmtl a\nKe 1 1 1 1\n",
        "err_ke_nan.obj": "mtllib m.mtl\n%%MTL\nnewmtl a\nKe nan 0 0\n",
        "err_newmtl.obj": "mtllib m.mtl\n%%MTL\nnewmtl\n",
        "err_binary.obj": "\x89PNG\r\n\x1a\n\x00\x00\x00\rIHDR",
    }
    for name, text in errors.items():
        out("obj", name, text)


# ---- core ---------------------------------------------------------------------------
# The byte program of fuzz_core.c: see its comment. Helpers mirror its reader.

def raw(q):                      # a Q16.16 value as raw bits
    return bytes([0]) + struct.pack("<i", q)


def quarter(x):                  # x in quarter units, |x| <= 32
    return bytes([1, int(round(x * 4)) & 0xFF])


def pal(i):                      # palette entry i
    return bytes([2, i])


def special(k):                  # float core: special value k (fixed core: palette)
    return bytes([8 | 2, k])


def real(x):
    return quarter(x) if abs(x * 4 - round(x * 4)) < 1e-9 and abs(x) <= 31.75 else raw(int(round(x * 65536)))


def vert(x, y, z):
    return bytes([0]) + real(x) + real(y) + real(z)


def shared(i):                   # the i-th remembered vertex
    return bytes([7 | (i << 3)])


def colour(r, g, b):
    return real(r) + real(g) + real(b)


def setup(flags=0, surfaces=11, patches=95, elements=600, vertices=1000, max_patch=None,
          max_element=None, res_index=0, band=0, work=0, misalign=0):
    b = bytes([flags, surfaces, patches]) + struct.pack("<HH", elements, vertices)
    if flags & 1:
        b += real(max_patch)
    if flags & 2:
        b += real(max_element)
    b += bytes([res_index])
    if flags & 4:
        b += bytes([band])
    return b + bytes([work, misalign])


def add(verts, rho=None, em=None, null_v=False):
    f = (1 if len(verts) == 4 else 0) | (0x10 if rho else 0) | (0x20 if em else 0) | (0xC0 if null_v else 0)
    b = bytes([0, f]) + b"".join(verts)
    if rho:
        b += colour(*rho)
    if em:
        b += colour(*em)
    return b


def shoot(n=3, tol=0):
    return bytes([5, n]) + real(tol)


def render(eye, target, w=8, h=8, f=0, extra=b""):
    return bytes([11, f, w - 1, h - 1]) + extra + vert(*eye) + vert(*target)


def box(x0, y0, z0, x1, y1, z1):
    """The six faces of tests/scenes.h's box(), wound inward (a room)."""
    f = [[(x0, y0, z0), (x1, y0, z0), (x1, y0, z1), (x0, y0, z1)],
         [(x0, y1, z0), (x0, y1, z1), (x1, y1, z1), (x1, y1, z0)],
         [(x0, y0, z0), (x0, y0, z1), (x0, y1, z1), (x0, y1, z0)],
         [(x1, y0, z0), (x1, y1, z0), (x1, y1, z1), (x1, y0, z1)],
         [(x0, y0, z0), (x0, y1, z0), (x1, y1, z0), (x1, y0, z0)],
         [(x0, y0, z1), (x1, y0, z1), (x1, y1, z1), (x0, y1, z1)]]
    return [[q[0], q[3], q[2], q[1]] for q in f]


def room(emit_face=1, rho=(0.5, 0.5, 0.5), em=(10, 10, 10)):
    b = b""
    for i, q in enumerate(box(-8, -8, -8, 8, 8, 8)):
        b += add([vert(*p) for p in q], rho, em if i == emit_face else None)
    return b


def core_seeds():
    all_ops = (shoot(3) + bytes([7]) + bytes([8, 0]) + bytes([9, 0, 3, 1]) + bytes([10, 0, 1])
               + render((0, 0, 6), (0, 0, 0)) + bytes([12, 0, 2]) + bytes([3, 0x20, 1]) + colour(4, 0, 0)
               + bytes([4]) + shoot(2, 0.01) + bytes([10, 0, 0]))
    out("core", "room_res8.bin", setup(res_index=0) + room() + all_ops)
    out("core", "room_res16_max.bin", setup(flags=3, max_patch=8, max_element=4, res_index=2) + room() + all_ops)
    out("core", "room_bands.bin", setup(flags=4, res_index=3, band=1) + room() + shoot(2))
    out("core", "room_short_work.bin", setup(res_index=2, work=1 | (2 << 2)) + room() + shoot(2))
    out("core", "room_no_pixels.bin", setup(res_index=0, work=2))
    out("core", "room_misaligned.bin", setup(res_index=0, misalign=5) + room() + shoot(1))
    out("core", "room_pool_full.bin", setup(surfaces=3, patches=6, elements=20, vertices=40) + room())
    out("core", "init_bad_res.bin", setup(res_index=8))
    out("core", "init_huge_pool.bin", setup(flags=0x30))
    out("core", "init_null_pool.bin", setup(flags=0xC0))
    out("core", "init_bad_sizes.bin", setup(flags=3, max_patch=1, max_element=2))
    out("core", "init_defaults.bin", setup(flags=8, res_index=7) + room() + shoot(1))
    # Triangles, a quad through the shooter's eye, coincident and shared corners.
    tri = add([vert(-4, -4, 0), vert(4, -4, 0), vert(0, 4, 0)], (0.7, 0.2, 0.1), (5, 5, 5))
    straddle = add([vert(-4, 0, -4), vert(4, 0, -4), vert(4, 0, 4), vert(-4, 0, 4)], (0.5, 0.5, 0.5))
    through = add([vert(0, -2, -2), vert(0, 2, -2), vert(0, 2, 2), vert(0, -2, 2)], (0.5, 0.5, 0.5))
    out("core", "straddle.bin", setup(res_index=2) + tri + straddle + through + shoot(3)
        + render((0, 0, 20), (0, 0, 0)) + bytes([12, 0, 0]))
    out("core", "coincident.bin", setup(res_index=0) + tri + tri + add([shared(0), shared(1), shared(2)], (0.5, 0.5, 0.5))
        + add([shared(0), shared(0), shared(1)]) + shoot(3))
    out("core", "degenerate.bin", setup(res_index=0)
        + add([vert(0, 0, 0), vert(1, 0, 0), vert(2, 0, 0)])
        + add([vert(0, 0, 0), raw(1) + raw(0) + raw(0), raw(0) + raw(1) + raw(0)])
        + add([vert(0, 0, 0), vert(1, 0, 0), vert(1, 1, 1), vert(0, 1, 0)])
        + add([vert(0, 0, 0), vert(2, 0, 0), vert(0.5, 0.5, 0), vert(0, 2, 0)])
        + add([vert(0, 0, 0), vert(1, 0, 0), vert(0, 1, 0)], null_v=True)
        + bytes([0, 6]) + bytes([0, 7]) + vert(0, 0, 0) + bytes([0, 9]) + b"".join(vert(i, i * i, 0) for i in range(5)))
    edge = 64.0
    out("core", "huge_and_range.bin", setup(flags=3, max_patch=64, max_element=16, res_index=0)
        + add([vert(-edge, -edge, 0), vert(edge, -edge, 0), vert(edge, edge, 0), vert(-edge, edge, 0)], (0.99, 0.5, 0), (4096, 0, 1))
        + add([bytes([0]) + pal(7) + real(0) + real(0), vert(0, 1, 0), vert(0, 0, 1)])
        + add([vert(0, 0, 0), vert(1, 0, 0), vert(0, 1, 0)], (1.0, 0, 0))
        + add([vert(0, 0, 0), vert(1, 0, 0), vert(0, 1, 0)], None, (4096.1, 0, 0))
        + add([vert(0, 0, 0), vert(1, 0, 0), vert(0, 1, 0)], (-0.1, 0, 0))
        + shoot(3) + render((0, 0, 200), (0, 0, 0), 24, 24))
    out("core", "tiny.bin", setup(flags=3, max_patch=0.0625, max_element=0.0625, res_index=0)
        + add([vert(0, 0, 0), raw(4096) + raw(0) + raw(0), raw(0) + raw(4096) + raw(0)], (0.5, 0.5, 0.5), (1, 1, 1))
        + add([vert(0, 0, 0), raw(64) + raw(0) + raw(0), raw(0) + raw(64) + raw(0)])
        + shoot(3))
    cam_extra = b""
    out("core", "render_edges.bin", setup(res_index=0) + room()
        + render((0, 0, 0), (0, 0, 0))                                   # eye == target
        + render((0, 0, 6), (0, 6, 6))                                   # looking along up
        + bytes([11, 0x30, 0, 0, 0]) + vert(0, 0, 200) + vert(0, 0, 0)        # 2048 x 1
        + bytes([11, 0x08, 3, 3]) + vert(0, 0, 250) + vert(0, 0, 0) + raw(16 << 16)   # widest fov
        + bytes([11, 0x38, 0, 0, 1]) + vert(250, 250, 250) + vert(-250, -250, -250) + raw(16 << 16)
        + bytes([11, 0x04, 7, 7]) + vert(0, 0, 6) + vert(0, 0, 0) + raw(0) + raw(0) + raw(0)
        + bytes([11, 0x01, 0, 7, 0]) + vert(0, 0, 6) + vert(0, 0, 0)
        + bytes([11, 0x40, 7, 7]) + vert(0, 0, 6) + vert(0, 0, 0) + cam_extra)
    out("core", "float_specials.bin", setup(res_index=0)
        + add([bytes([0]) + special(16) + real(0) + real(0), vert(1, 0, 0), vert(0, 1, 0)])
        + add([vert(0, 0, 0), vert(1, 0, 0), vert(0, 1, 0)], None, None)
        + bytes([0, 0x30]) + vert(0, 0, 0) + vert(1, 0, 0) + vert(0, 1, 0) + special(17) + real(0) + real(0) + special(16) + real(0) + real(0)
        + bytes([3, 0x31]) + struct.pack("<I", 0) + special(5) + special(6) + special(7) + special(19) + struct.pack("<I", 0x7fc00001) + real(0) + real(0)
        + bytes([5, 3]) + special(16)
        + bytes([11, 0x0C, 3, 3]) + vert(0, 0, 6) + vert(0, 0, 0) + special(2) + special(3) + special(4) + special(16))
    out("core", "set_restart.bin", setup(res_index=0) + room() + shoot(3) + add([vert(0, 0, 0), vert(1, 0, 0), vert(0, 1, 0)])
        + bytes([3, 0x31]) + struct.pack("<I", 99) + colour(0.5, 0.5, 0.5) + colour(1, 1, 1)
        + bytes([3, 0x30, 2]) + colour(0.9, 0.9, 0.9) + colour(100, 0, 0) + bytes([4]) + shoot(3) + bytes([7])
        + bytes([9, 1]) + struct.pack("<I", 0xFFFFFFFF) + bytes([1]) + bytes([12, 1]) + struct.pack("<I", 0xFFFFFFFF)
        + bytes([10, 1, 0]) + bytes([10, 2, 3, 1]) + bytes([10, 4, 0]) + bytes([8, 1]))
    # The threaded shot, stored rows, light groups, form factor codes, the vertex memo.
    par = (bytes([13, 0]) + real(0) + bytes([3])              # 4 parts, then end
           + bytes([13, 0x10]) + real(0) + bytes([1, 0])      # 2 parts, end with 1
           + bytes([13, 0x02]) + real(0) + bytes([0, 1])      # parts of the next patch
           + bytes([13, 0x01]) + real(0) + bytes([0])         # one byte short
           + bytes([13, 0x08]) + real(0) + bytes([0])         # misaligned
           + bytes([13, 0x40]) + real(0) + bytes([0])         # no patch pointer
           + bytes([13, 0x20]) + real(0) + bytes([2])         # 3 parts, each with a vertex memo
           + bytes([13, 0xA1]) + real(0) + bytes([1]))        # a memo one byte short
    out("core", "room_parallel.bin", setup(res_index=2) + room() + par + bytes([7]))
    out("core", "bands_parallel.bin", setup(flags=4, res_index=2, band=2) + room() + par)
    rows = (bytes([14, 0x00, 1]) + struct.pack("<H", 5000) + bytes([3])   # 3 rows
            + bytes([14, 0x04, 7])                                          # the rest
            + bytes([14, 0x08, 3]) + real(0)                                # shoot through them
            + bytes([4]) + bytes([14, 0x0C, 5]) + real(0.001)               # Gauss-Seidel
            + bytes([14, 0x1C, 5]) + real(0)                                # matrix one short
            + bytes([14, 0x03, 2]) + struct.pack("<H", 5000) + bytes([7])   # a row too many
            + bytes([14, 0x03, 1]) + struct.pack("<H", 10) + bytes([7])     # entries run out
            + bytes([14, 0x08, 1]) + real(0))                               # rows missing
    out("core", "room_rows.bin", setup(res_index=0) + room() + rows)
    mix = (bytes([15, 0x12]) + colour(1, 1, 1) + colour(0.5, 0.25, 2) + colour(1, 1, 1) + colour(3, 0, 1)
           + bytes([15, 0x03]) + colour(30000, 30000, 30000) + colour(2, 2, 2) + colour(1, 1, 1) + colour(1, 1, 1)
           + colour(1, 1, 1) + colour(1, 1, 1)
           + bytes([15, 0x22]) + colour(1, 1, 1) + colour(1, 1, 1) + colour(1, 1, 1) + colour(1, 1, 1)
           + bytes([15, 0x40]) + bytes([15, 0x00]))
    out("core", "room_mix.bin", setup(res_index=0) + room() + shoot(3) + mix)
    codes = b"".join(bytes([16]) + struct.pack("<H", c) for c in (0, 1, 1023, 1024, 2047, 2048, 3072, 19 << 11 | 2047,
                                                                     20 << 11, 21 << 11 | 2047, 22 << 11 | 1024, 0xFFFF))
    out("core", "codes.bin", setup(res_index=0) + codes)
    out("core", "room_cache.bin", setup(res_index=2, misalign=8 | 3) + room() + shoot(3) + par + rows)
    out("core", "room_cache_short.bin", setup(res_index=2, misalign=16) + room() + shoot(2))
    out("core", "res1024_bands.bin", setup(flags=4, surfaces=2, patches=4, elements=8, vertices=16, res_index=14, band=1, work=1)
        + add([vert(-8, -8, 0), vert(8, -8, 0), vert(8, 8, 0), vert(-8, 8, 0)], (0.5, 0.5, 0.5), (1, 1, 1)) + render((0, 0, 6), (0, 0, 0)))


# ---- image --------------------------------------------------------------------------

def png(w, h, ct=2, depth=8, rows=None, interlace=0, extra_chunks=b"", cut=None):
    def chunk(t, d):
        return struct.pack(">I", len(d)) + t + d + struct.pack(">I", zlib.crc32(t + d) & 0xffffffff)
    ch = {0: 1, 2: 3, 3: 1, 4: 2, 6: 4}[ct]
    bpr = (w * ch * depth + 7) // 8
    raw_rows = rows if rows is not None else b"".join(b"\x00" + bytes((x * 37 + y * 11) & 0xff for x in range(bpr)) for y in range(h))
    b = b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, depth, ct, 0, 0, interlace))
    if ct == 3:
        b += chunk(b"PLTE", bytes(range(48))) + chunk(b"tRNS", b"\x00\x80")
    b += extra_chunks + chunk(b"IDAT", zlib.compress(raw_rows)) + chunk(b"IEND", b"")
    return b[:cut] if cut else b


def img(flags, w, h, name, exposure=1.0, payload=b""):
    n = name.encode()
    return bytes([flags]) + struct.pack("<iiB", w, h, len(n)) + n + struct.pack("<d", exposure) + payload


def floats(*v):
    return struct.pack("<%df" % len(v), *v)


def image_seeds():
    full = 0xF0
    px = bytes(range(36))
    out("image", "png_write.bin", img(full, 4, 3, "a.png", 1.0, px))
    out("image", "ppm_write.bin", img(full, 4, 3, "b.PPM", 0.5, px))
    out("image", "replace_existing.bin", img(full | 4, 2, 2, "c.png", 2.0, px))
    out("image", "keep_existing.bin", img(full | 4, 0, 2, "c.png", 2.0, px))
    out("image", "missing_dir.bin", img(full | 1, 2, 2, "d.png", 1.0, px))
    out("image", "null_path.bin", img(full | 2, 2, 2, "e.png"))
    out("image", "null_pixels.bin", img(full | 3, 2, 2, "e.png"))
    out("image", "bad_ext.bin", img(full, 2, 2, "f.jpg"))
    out("image", "no_ext.bin", img(full, 2, 2, "png"))
    out("image", "dot_dir.bin", img(full, 2, 2, "x.png/"))
    out("image", "sizes_negative.bin", img(full, -1, 5, "g.png"))
    out("image", "sizes_huge.bin", img(full, 32769, 1, "g.png"))
    out("image", "sizes_max.bin", img(full, 32768, 32768, "g.png"))
    out("image", "sizes_int_min.bin", img(full, -2**31, -2**31, "g.png"))
    out("image", "small_err.bin", img(0x00, 0, 0, "h.png"))
    out("image", "err_len3.bin", img(0x20, 0, 0, "h.png"))
    out("image", "no_err.bin", img(0x88, 0, 0, "h.png"))
    out("image", "tonemap_specials.bin", img(full, 1, 1, "t.ppm", 1.0,
        floats(0.0, -0.0, 1.0, float("nan"), float("inf"), -float("inf"), 1e-40, 3.4e38, 0.0031308, 0.5, -1.0, 1e-45)))
    out("image", "tonemap_nan_exposure.bin", img(full, 1, 1, "t.ppm", float("nan"), floats(1, 2, 3, 0.1, 0.2, 0.3)))
    out("image", "tonemap_inf_exposure.bin", img(full, 1, 1, "t.ppm", float("inf"), floats(0, 2, 3, 0.1, -0.2, 0.3)))
    out("image", "tonemap_neg_exposure.bin", img(full, 1, 1, "t.ppm", -3.0, floats(0, 2, 3, 0.1, -0.2, 0.3)))
    out("image", "read_png_rgb.bin", img(full, 1, 1, "r.png", 1.0, png(3, 2)))
    out("image", "read_png_grey16.bin", img(full, 1, 1, "r.png", 1.0, png(2, 2, ct=0, depth=16)))
    out("image", "read_png_grey1.bin", img(full, 1, 1, "r.png", 1.0, png(9, 2, ct=0, depth=1)))
    out("image", "read_png_palette.bin", img(full, 1, 1, "r.png", 1.0, png(4, 2, ct=3, depth=4)))
    out("image", "read_png_rgba.bin", img(full, 1, 1, "r.png", 1.0, png(2, 2, ct=6)))
    out("image", "read_png_ga_interlaced.bin", img(full, 1, 1, "r.png", 1.0, png(5, 5, ct=4, interlace=1)))
    out("image", "read_png_cut.bin", img(full, 1, 1, "r.png", 1.0, png(8, 8, cut=60)))
    out("image", "read_png_huge_header.bin", img(full, 1, 1, "r.png", 1.0, png(40000, 1, rows=b"\x00" * 10)))
    out("image", "read_ppm.bin", img(full, 1, 1, "r.ppm", 1.0, b"P6\n# comment\n3 2\n255\n" + bytes(range(18))))
    out("image", "read_ppm_cut.bin", img(full, 1, 1, "r.ppm", 1.0, b"P6 3 2 255\n" + bytes(5)))
    out("image", "read_ppm_maxval.bin", img(full, 1, 1, "r.ppm", 1.0, b"P6 3 2 65535\n" + bytes(36)))
    out("image", "read_ppm_bad.bin", img(full, 1, 1, "r.ppm", 1.0, b"P6 3x 2 255\n"))
    out("image", "read_ppm_p3.bin", img(full, 1, 1, "r.ppm", 1.0, b"P3 1 1 255\n1 2 3\n"))


def mtl_texture_seeds():
    """fuzz_mtl_texture: MTL text, then \n%%TEX\n and the bytes of t.png."""
    def seed(name, mtl, tex=b""):
        out("mtl_texture", name, mtl + b"\n%%TEX\n" + tex)
    seed("plain.bin", b"newmtl a\nKd 0 0 0\nmap_Kd t.png\n", png(3, 2))
    seed("options.bin", b"newmtl a\nKd 0.5 0.2 1\nmap_Kd -s 2 3 -o 0.5 0.25 -clamp on -bm 1 -blendu off t.png\n"
         b"newmtl b\nmap_Kd -mm 0 1 -imfchan l -type sphere -texres 64 t.png\n", png(4, 4, ct=6))
    seed("huge_scale.bin", b"newmtl a\nmap_Kd -s 1e30 -1e30 -o 1e30 t.png\n", png(2, 2, ct=0, depth=16))
    seed("grey1.bin", b"newmtl a\nKd 0 0 0\nmap_Kd t.png\n", png(9, 2, ct=0, depth=1))
    seed("palette_interlaced.bin", b"newmtl a\nmap_Kd t.png\n", png(5, 5, ct=3, depth=4, interlace=1))
    seed("cut.bin", b"newmtl a\nKd 0 0 0\nmap_Kd t.png\n", png(8, 8, cut=60))
    seed("bomb.bin", b"newmtl a\nKd 0 0 0\nmap_Kd t.png\n", png(10000, 10000, rows=b"\x00" * 10))
    seed("ppm.bin", b"newmtl a\nmap_Kd t.png\n", b"P6\n3 2\n255\n" + bytes(range(18)))
    seed("empty.bin", b"newmtl a\nKd 0 0 0\nmap_Kd t.png\n")
    seed("shared.bin", b"newmtl a\nKd 0 0 0\nmap_Kd t.png\nnewmtl b\nKd 0.5 0.5 0.5\nmap_Kd -clamp on t.png\n", png(3, 3))
    seed("missing_and_bad.bin", b"newmtl a\nKd 0 0 0\nmap_Kd no such.png\nnewmtl b\nmap_Kd -s\n"
         b"newmtl c\nmap_Kd -clamp maybe t.png\nnewmtl d\nmap_Kd\n", png(1, 1))


if __name__ == "__main__":
    obj_seeds()
    core_seeds()
    image_seeds()
    mtl_texture_seeds()
