#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""gltf_validate.py FILE.glb ... -- checks binary glTF 2.0 files against the MUST rules
of the glTF 2.0 specification (Khronos, version 2.0.1) that rad's writer can break, with
the Python standard library only (Debian packages no Khronos validator). Prints one
line "FILE: what is wrong (section)" per error; exits 1 if any file has one, else 0.

Rules checked (the specification's section numbers; "5" is its JSON schema):
  4.4.2    Header: magic "glTF", version 2, length the file's size.
  4.4.3    Chunks: lengths multiples of 4, inside the file, nothing after the last; the
           first JSON, at most one BIN and only second. 4.4.3.2: the JSON padded with
           spaces (0x20); 4.4.3.3: the BIN with zeros (after buffers[0].byteLength).
  2.7      The JSON is UTF-8 without a BOM, an object.
  3.2      asset.version present, "MAJOR.MINOR", major 2.
  3.12     extensionsRequired within extensionsUsed; every extension a material uses
           in extensionsUsed.
  3.3, 5   Every index in range (scene, scenes[].nodes, nodes[].mesh and children,
           primitives' attributes, indices and material, accessors' bufferView,
           bufferViews' buffer, images' bufferView, textures' sampler and source, every
           textureInfo's index); arrays at the root not empty.
  3.6.1.1  bufferViews: byteLength >= 1, inside their buffer; byteStride 4..252, a
           multiple of 4; target 34962 or 34963.
  3.6.1.2  The BIN chunk is buffers[0], without a uri; a buffer without one needs it;
           byteLength <= the chunk's length <= byteLength + 3.
  3.6.2.1  Accessors: componentType, type, count >= 1; min/max one value a component.
  3.6.2.2  Float values finite (no NaN, no infinity).
  3.6.2.4  accessor.byteOffset and bufferView.byteOffset + accessor.byteOffset
           multiples of the component size, byteStride too; the accessor inside its
           view: byteOffset + stride x (count - 1) + element size <= byteLength.
  3.6.2.5  min and max, when given, are the data's (floats compared as float32).
  3.7.2.1  Primitives: attributes not empty, of one count, 4-byte aligned; POSITION
           VEC3 float with min and max; NORMAL VEC3 float, unit (within 5e-4, the
           Khronos validator's); TEXCOORD_n VEC2 float or normalized unsigned
           byte/short; COLOR_n VEC3/VEC4 float or normalized unsigned byte/short, and
           every COLOR_0 component in [0, 1]; TEXCOORD_n and COLOR_n numbered from 0
           without gaps; other semantics start with "_" and are not unsigned int;
           indices SCALAR unsigned, their view without byteStride, each < the vertex
           count and not the type's largest value; mode 0..6, triangles in threes.
  3.8.2    Textures' sampler and source in range.
  3.8.3    Images: a uri or a bufferView; with a bufferView a mimeType (image/png or
           image/jpeg) that the bytes match (their signature).
  3.8.4, 5 Samplers: magFilter 9728/9729, minFilter 9728/9729/9984..9987, wraps
           33071/33648/10497.
  3.9, 5   Materials: baseColorFactor 4 and emissiveFactor 3 numbers in [0, 1];
           metallicFactor, roughnessFactor in [0, 1]; alphaMode OPAQUE/MASK/BLEND; a
           textureInfo's texCoord >= 0, a TEXCOORD_n every primitive using it has;
           KHR_materials_emissive_strength's emissiveStrength >= 0.
  3.5.1    A scene's nodes are roots; 3.5.2: each node has at most one parent, no
           cycles.
"""
import json
import math
import struct
import sys

COMPONENT_SIZE = {5120: 1, 5121: 1, 5122: 2, 5123: 2, 5125: 4, 5126: 4}
COMPONENT_FMT = {5120: "b", 5121: "B", 5122: "h", 5123: "H", 5125: "I", 5126: "f"}
TYPE_COMPONENTS = {"SCALAR": 1, "VEC2": 2, "VEC3": 3, "VEC4": 4, "MAT2": 4, "MAT3": 9, "MAT4": 16}
KNOWN_ROOT_ARRAYS = ("accessors", "animations", "buffers", "bufferViews", "cameras", "images",
                     "materials", "meshes", "nodes", "samplers", "scenes", "skins", "textures")
SIGNATURES = {"image/png": b"\x89PNG\r\n\x1a\n", "image/jpeg": b"\xff\xd8\xff"}


def f32(x):
    """X rounded to float32, as a reader of min/max stores it."""
    return struct.unpack("<f", struct.pack("<f", x))[0]


class Checker:
    def __init__(self, name):
        self.name = name
        self.errors = []

    def err(self, what):
        self.errors.append("%s: %s" % (self.name, what))

    def check(self, cond, what):
        if not cond:
            self.err(what)
        return cond

    # ---- the container ------------------------------------------------------------
    def glb(self, data):
        if not self.check(len(data) >= 20, "shorter than a GLB header and a chunk header (%d bytes)" % len(data)):
            return None, None
        magic, version, length = struct.unpack_from("<III", data, 0)
        self.check(magic == 0x46546C67, "bad magic 0x%08x (4.4.2: 'glTF')" % magic)
        self.check(version == 2, "GLB version %d (4.4.2: 2)" % version)
        self.check(length == len(data), "header length %d != file size %d (4.4.2)" % (length, len(data)))
        chunks, at = [], 12
        while at + 8 <= len(data):
            clen, ctype = struct.unpack_from("<II", data, at)
            self.check(clen % 4 == 0, "chunk %d's length %d not a multiple of 4 (4.4.3)" % (len(chunks), clen))
            if not self.check(at + 8 + clen <= len(data), "chunk %d runs past the file (4.4.3)" % len(chunks)):
                return None, None
            chunks.append((ctype, data[at + 8:at + 8 + clen]))
            at += 8 + clen
        self.check(at == len(data), "%d bytes after the last chunk (4.4.3)" % (len(data) - at))
        if not self.check(chunks and chunks[0][0] == 0x4E4F534A, "the first chunk is not JSON (4.4.3)"):
            return None, None
        bins = [i for i, c in enumerate(chunks) if c[0] == 0x004E4942]
        self.check(len(bins) <= 1, "%d BIN chunks (4.4.3: at most one)" % len(bins))
        self.check(not bins or bins[0] == 1, "the BIN chunk is not the second (4.4.3)")
        text = chunks[0][1]
        self.check(not text.startswith(b"\xef\xbb\xbf"), "JSON chunk starts with a BOM (2.7)")
        end = text.rstrip(b" ")
        self.check(end.endswith(b"}") or end.endswith(b"]") or not end, "JSON chunk padded with other bytes than spaces (4.4.3.2)")
        try:
            doc = json.loads(text.decode("utf-8"))
        except (UnicodeDecodeError, ValueError) as e:
            self.err("JSON chunk is not UTF-8 JSON (2.7): %s" % e)
            return None, None
        if not self.check(isinstance(doc, dict), "JSON is not an object (2.7)"):
            return None, None
        return doc, (chunks[1][1] if len(chunks) > 1 and chunks[1][0] == 0x004E4942 else None)

    # ---- helpers ------------------------------------------------------------------
    def array(self, doc, key):
        v = doc.get(key, [])
        if key in doc:
            self.check(isinstance(v, list) and len(v) >= 1, "'%s' must be a non-empty array (5: the schema's minItems)" % key)
        return v if isinstance(v, list) else []

    def ref(self, value, arr, what):
        ok = isinstance(value, int) and not isinstance(value, bool) and 0 <= value < len(arr)
        self.check(ok, "%s = %r out of range (0..%d)" % (what, value, len(arr) - 1))
        return ok

    def numbers(self, v, n, lo, hi, what):
        if not self.check(isinstance(v, list) and len(v) == n, "%s must be %d numbers" % (what, n)):
            return
        for x in v:
            self.check(isinstance(x, (int, float)) and lo <= x <= hi, "%s value %r outside [%g, %g]" % (what, x, lo, hi))

    # ---- the document -------------------------------------------------------------
    def document(self, doc, bin_chunk):
        asset = doc.get("asset")
        if self.check(isinstance(asset, dict) and "version" in asset, "asset.version missing (3.2)"):
            v = asset["version"]
            self.check(isinstance(v, str) and len(v.split(".")) == 2 and all(p.isdigit() for p in v.split(".")),
                       "asset.version %r is not MAJOR.MINOR (3.2)" % v)
            self.check(v.split(".")[0] == "2", "asset.version %r is not glTF 2 (3.2)" % v)
        used = doc.get("extensionsUsed", [])
        for e in doc.get("extensionsRequired", []):
            self.check(e in used, "extensionsRequired %r not in extensionsUsed (3.12)" % e)
        arrays = {k: self.array(doc, k) for k in KNOWN_ROOT_ARRAYS}
        self.buffers(arrays, bin_chunk)
        self.buffer_views(arrays)
        data = self.accessors(arrays, bin_chunk)
        self.meshes(arrays, data)
        self.materials(arrays, used)
        self.textures(arrays)
        self.images(arrays, bin_chunk)
        self.nodes(doc, arrays)

    def buffers(self, a, bin_chunk):
        for i, b in enumerate(a["buffers"]):
            n = b.get("byteLength")
            self.check(isinstance(n, int) and n >= 1, "buffers[%d].byteLength %r must be >= 1" % (i, n))
            if i == 0 and "uri" not in b:
                if self.check(bin_chunk is not None, "buffers[0] has no uri and the file no BIN chunk (3.6.1.2)"):
                    if self.check(isinstance(n, int) and n <= len(bin_chunk) <= n + 3,
                                  "buffers[0].byteLength %r against the BIN chunk's %d bytes (3.6.1.2)" % (n, len(bin_chunk))):
                        self.check(not bin_chunk[n:].strip(b"\0"), "BIN chunk padded with other bytes than zeros (4.4.3.3)")
            else:
                self.check("uri" in b, "buffers[%d] has no uri (only buffer 0 may be the BIN chunk)" % i)

    def buffer_views(self, a):
        for i, v in enumerate(a["bufferViews"]):
            if not self.ref(v.get("buffer"), a["buffers"], "bufferViews[%d].buffer" % i):
                continue
            off, n = v.get("byteOffset", 0), v.get("byteLength")
            self.check(isinstance(n, int) and n >= 1, "bufferViews[%d].byteLength %r must be >= 1 (3.6.1.1)" % (i, n))
            self.check(isinstance(off, int) and off >= 0, "bufferViews[%d].byteOffset %r" % (i, off))
            if isinstance(n, int) and isinstance(off, int):
                bl = a["buffers"][v["buffer"]].get("byteLength", 0)
                self.check(off + n <= bl, "bufferViews[%d] bytes %d..%d past its buffer's %d (3.6.1.1)" % (i, off, off + n, bl))
            if "byteStride" in v:
                s = v["byteStride"]
                self.check(isinstance(s, int) and 4 <= s <= 252 and s % 4 == 0,
                           "bufferViews[%d].byteStride %r: 4..252, a multiple of 4 (3.6.1.1)" % (i, s))
            if "target" in v:
                self.check(v["target"] in (34962, 34963), "bufferViews[%d].target %r (3.6.1.1)" % (i, v["target"]))

    def accessors(self, a, bin_chunk):
        """Each accessor's values as a list of tuples (None when unreadable)."""
        out = []
        for i, acc in enumerate(a["accessors"]):
            out.append(self.accessor(a, i, acc, bin_chunk))
        return out

    def accessor(self, a, i, acc, bin_chunk):
        ct, ty, count = acc.get("componentType"), acc.get("type"), acc.get("count")
        what = "accessors[%d]" % i
        ok = self.check(ct in COMPONENT_SIZE, "%s.componentType %r (3.6.2.1)" % (what, ct))
        ok &= self.check(ty in TYPE_COMPONENTS, "%s.type %r (3.6.2.1)" % (what, ty))
        ok &= self.check(isinstance(count, int) and count >= 1, "%s.count %r must be >= 1 (3.6.2.1)" % (what, count))
        if not ok:
            return None
        ncomp, size = TYPE_COMPONENTS[ty], COMPONENT_SIZE[ct]
        self.check(not (acc.get("normalized") and ct in (5125, 5126)), "%s normalized with a float or uint type" % what)
        for k in ("min", "max"):
            if k in acc:
                self.check(isinstance(acc[k], list) and len(acc[k]) == ncomp,
                           "%s.%s must have %d values (3.6.2.1)" % (what, k, ncomp))
        if "bufferView" not in acc:
            return [tuple([0] * ncomp)] * count  # all zeros (3.6.2.1), no sparse written here
        if not self.ref(acc["bufferView"], a["bufferViews"], what + ".bufferView"):
            return None
        view = a["bufferViews"][acc["bufferView"]]
        off, voff = acc.get("byteOffset", 0), view.get("byteOffset", 0)
        elem = size * ncomp
        stride = view.get("byteStride", elem)
        self.check(off % size == 0, "%s.byteOffset %d not a multiple of %d (3.6.2.4)" % (what, off, size))
        self.check((off + voff) % size == 0, "%s starts at %d in the buffer, not a multiple of %d (3.6.2.4)" % (what, off + voff, size))
        self.check(stride % size == 0, "%s's byteStride %d not a multiple of %d (3.6.2.4)" % (what, stride, size))
        vlen = view.get("byteLength", 0)
        if not self.check(off + stride * (count - 1) + elem <= vlen,
                          "%s needs %d bytes, its bufferView has %d (3.6.2.4)" % (what, off + stride * (count - 1) + elem, vlen)):
            return None
        if bin_chunk is None or view.get("buffer") != 0 or "uri" in a["buffers"][0]:
            return None
        start = voff + off
        if start + stride * (count - 1) + elem > len(bin_chunk):
            self.err("%s runs past the BIN chunk" % what)
            return None
        fmt = "<" + COMPONENT_FMT[ct] * ncomp
        vals = [struct.unpack_from(fmt, bin_chunk, start + stride * k) for k in range(count)]
        if ct == 5126:
            bad = sum(1 for v in vals for x in v if not math.isfinite(x))
            self.check(bad == 0, "%s has %d values NaN or infinite (3.6.2.2)" % (what, bad))
        for k, pick in (("min", min), ("max", max)):
            if k in acc and isinstance(acc[k], list) and len(acc[k]) == ncomp:
                for c in range(ncomp):
                    real = pick(v[c] for v in vals)
                    given = f32(acc[k][c]) if ct == 5126 else acc[k][c]
                    self.check(given == real, "%s.%s[%d] = %r, the data's is %r (3.6.2.5)" % (what, k, c, acc[k][c], real))
        return vals

    def meshes(self, a, data):
        self.material_uses = {}
        for m, mesh in enumerate(a["meshes"]):
            prims = mesh.get("primitives", [])
            self.check(isinstance(prims, list) and len(prims) >= 1, "meshes[%d].primitives empty (3.7.2)" % m)
            for p, prim in enumerate(prims):
                self.primitive(a, data, "meshes[%d].primitives[%d]" % (m, p), prim)

    def primitive(self, a, data, what, prim):
        attrs = prim.get("attributes", {})
        if not self.check(isinstance(attrs, dict) and attrs, "%s.attributes empty (3.7.2.1)" % what):
            return
        counts, sets = set(), {"TEXCOORD": [], "COLOR": [], "JOINTS": [], "WEIGHTS": []}
        for sem, idx in attrs.items():
            w = "%s.attributes.%s" % (what, sem)
            if not self.ref(idx, a["accessors"], w):
                continue
            acc, vals = a["accessors"][idx], data[idx]
            ct, ty, norm = acc.get("componentType"), acc.get("type"), acc.get("normalized", False)
            counts.add(acc.get("count"))
            view = a["bufferViews"][acc["bufferView"]] if isinstance(acc.get("bufferView"), int) and acc["bufferView"] < len(a["bufferViews"]) else {}
            self.check((view.get("byteOffset", 0) + acc.get("byteOffset", 0)) % 4 == 0 and view.get("byteStride", 4) % 4 == 0,
                       "%s not 4-byte aligned (3.7.2.1)" % w)
            base, _, n = sem.partition("_")
            if sem == "POSITION":
                self.check(ty == "VEC3" and ct == 5126, "%s must be VEC3 float (3.7.2.1)" % w)
                self.check("min" in acc and "max" in acc, "%s must have min and max (3.7.2.1)" % w)
            elif sem == "NORMAL":
                self.check(ty == "VEC3" and ct == 5126, "%s must be VEC3 float (3.7.2.1)" % w)
                if vals and ct == 5126:
                    worst = max(abs(math.sqrt(sum(x * x for x in v)) - 1) for v in vals)
                    self.check(worst <= 5e-4, "%s not unit length (off by %g) (3.7.2.1)" % (w, worst))
            elif sem == "TANGENT":
                self.check(ty == "VEC4" and ct == 5126, "%s must be VEC4 float (3.7.2.1)" % w)
            elif base in sets and n.isdigit() and sem == base + "_" + str(int(n)):
                sets[base].append(int(n))
                if base == "TEXCOORD":
                    self.check(ty == "VEC2" and (ct == 5126 or (ct in (5121, 5123) and norm)),
                               "%s must be VEC2 float or normalized unsigned byte/short (3.7.2.1)" % w)
                elif base == "COLOR":
                    self.check(ty in ("VEC3", "VEC4") and (ct == 5126 or (ct in (5121, 5123) and norm)),
                               "%s must be VEC3/VEC4 float or normalized unsigned byte/short (3.7.2.1)" % w)
                    if vals and ct == 5126:
                        out = [x for v in vals for x in v if not 0 <= x <= 1]
                        self.check(not out, "%s has %d values outside [0, 1], e.g. %r (3.7.2.1)" % (w, len(out), out[:1]))
            else:
                self.check(sem.startswith("_"), "%s: application-specific semantics must start with '_' (3.7.2.1)" % w)
                self.check(ct != 5125, "%s: an application-specific semantic of unsigned int (3.7.2.1)" % w)
        for base, ns in sets.items():
            self.check(sorted(ns) == list(range(len(ns))), "%s: %s_n not numbered 0..%d without gaps (3.7.2.1)" % (what, base, len(ns) - 1))
        self.check(len(counts) == 1, "%s: attributes of different counts %s (3.7.2.1)" % (what, sorted(counts, key=str)))
        nverts = min(counts, key=lambda x: x if isinstance(x, int) else 0) if counts else 0
        mode = prim.get("mode", 4)
        self.check(mode in range(7), "%s.mode %r (3.7.2.1)" % (what, mode))
        if "indices" in prim and self.ref(prim["indices"], a["accessors"], what + ".indices"):
            acc, vals = a["accessors"][prim["indices"]], data[prim["indices"]]
            ct = acc.get("componentType")
            self.check(acc.get("type") == "SCALAR" and ct in (5121, 5123, 5125), "%s.indices must be SCALAR unsigned (3.7.2.1)" % what)
            if isinstance(acc.get("bufferView"), int) and acc["bufferView"] < len(a["bufferViews"]):
                self.check("byteStride" not in a["bufferViews"][acc["bufferView"]], "%s.indices' bufferView has a byteStride (3.7.2.1)" % what)
            if vals is not None and ct in COMPONENT_SIZE:
                top = (1 << (8 * COMPONENT_SIZE[ct])) - 1
                big = [v[0] for v in vals if v[0] >= nverts or v[0] == top]
                self.check(not big, "%s: %d indices >= the vertex count %s or the restart value, e.g. %r (3.7.2.1)" % (what, len(big), nverts, big[:1]))
            if mode == 4:
                self.check(acc.get("count", 0) % 3 == 0, "%s: %r indices, not triangles (3.7.2.1)" % (what, acc.get("count")))
        elif mode == 4:
            self.check(isinstance(nverts, int) and nverts % 3 == 0, "%s: %r vertices, not triangles (3.7.2.1)" % (what, nverts))
        if "material" in prim and self.ref(prim["material"], a["materials"], what + ".material"):
            self.material_uses.setdefault(prim["material"], []).append((what, set(sets["TEXCOORD"])))

    def texture_info(self, a, what, info, m):
        if not self.check(isinstance(info, dict), "%s is not an object" % what):
            return
        self.ref(info.get("index"), a["textures"], what + ".index")
        tc = info.get("texCoord", 0)
        if self.check(isinstance(tc, int) and tc >= 0, "%s.texCoord %r must be >= 0 (3.9)" % (what, tc)):
            for prim, have in self.material_uses.get(m, []):
                self.check(tc in have, "%s uses %s, which has no TEXCOORD_%d (3.9)" % (prim, what, tc))

    def materials(self, a, used):
        for m, mat in enumerate(a["materials"]):
            w = "materials[%d]" % m
            pbr = mat.get("pbrMetallicRoughness", {})
            if "baseColorFactor" in pbr:
                self.numbers(pbr["baseColorFactor"], 4, 0, 1, w + ".baseColorFactor (3.9)")
            for k in ("metallicFactor", "roughnessFactor"):
                if k in pbr:
                    self.numbers([pbr[k]], 1, 0, 1, "%s.%s (3.9)" % (w, k))
            for k in ("baseColorTexture", "metallicRoughnessTexture"):
                if k in pbr:
                    self.texture_info(a, "%s.pbrMetallicRoughness.%s" % (w, k), pbr[k], m)
            for k in ("normalTexture", "occlusionTexture", "emissiveTexture"):
                if k in mat:
                    self.texture_info(a, "%s.%s" % (w, k), mat[k], m)
            if "emissiveFactor" in mat:
                self.numbers(mat["emissiveFactor"], 3, 0, 1, w + ".emissiveFactor (3.9)")
            self.check(mat.get("alphaMode", "OPAQUE") in ("OPAQUE", "MASK", "BLEND"), "%s.alphaMode (3.9)" % w)
            for e, body in mat.get("extensions", {}).items():
                self.check(e in used, "%s uses extension %s, not in extensionsUsed (3.12)" % (w, e))
                if e == "KHR_materials_emissive_strength":
                    s = body.get("emissiveStrength", 1)
                    self.check(isinstance(s, (int, float)) and s >= 0 and math.isfinite(s), "%s emissiveStrength %r must be >= 0" % (w, s))

    def textures(self, a):
        for t, tex in enumerate(a["textures"]):
            if "sampler" in tex:
                self.ref(tex["sampler"], a["samplers"], "textures[%d].sampler" % t)
            if "source" in tex:
                self.ref(tex["source"], a["images"], "textures[%d].source" % t)
        for s, smp in enumerate(a["samplers"]):
            w = "samplers[%d]" % s
            self.check(smp.get("magFilter", 9729) in (9728, 9729), "%s.magFilter %r (3.8.4)" % (w, smp.get("magFilter")))
            self.check(smp.get("minFilter", 9729) in (9728, 9729, 9984, 9985, 9986, 9987), "%s.minFilter %r (3.8.4)" % (w, smp.get("minFilter")))
            for k in ("wrapS", "wrapT"):
                self.check(smp.get(k, 10497) in (33071, 33648, 10497), "%s.%s %r (3.8.4)" % (w, k, smp.get(k)))

    def images(self, a, bin_chunk):
        for i, img in enumerate(a["images"]):
            w = "images[%d]" % i
            if not self.check(("uri" in img) != ("bufferView" in img), "%s needs exactly one of uri and bufferView (3.8.3)" % w):
                continue
            if "bufferView" not in img:
                continue
            mime = img.get("mimeType")
            self.check(mime in SIGNATURES, "%s.mimeType %r with a bufferView: image/png or image/jpeg (3.8.3)" % (w, mime))
            if self.ref(img["bufferView"], a["bufferViews"], w + ".bufferView") and bin_chunk is not None and mime in SIGNATURES:
                v = a["bufferViews"][img["bufferView"]]
                head = bin_chunk[v.get("byteOffset", 0):v.get("byteOffset", 0) + len(SIGNATURES[mime])]
                self.check(head == SIGNATURES[mime], "%s's bytes are not %s (3.8.3)" % (w, mime))

    def nodes(self, doc, a):
        parent = {}
        for n, node in enumerate(a["nodes"]):
            if "mesh" in node:
                self.ref(node["mesh"], a["meshes"], "nodes[%d].mesh" % n)
            for c in node.get("children", []):
                if self.ref(c, a["nodes"], "nodes[%d].children" % n):
                    self.check(c not in parent, "nodes[%d] has two parents (3.5.2)" % c)
                    parent[c] = n
        for n in range(len(a["nodes"])):
            seen, x = set(), n
            while x in parent and x not in seen:
                seen.add(x)
                x = parent[x]
            self.check(x not in seen, "nodes[%d] is in a cycle (3.5.2)" % n)
        if "scene" in doc:
            self.ref(doc["scene"], a["scenes"], "scene")
        for s, scene in enumerate(a["scenes"]):
            for n in scene.get("nodes", []):
                if self.ref(n, a["nodes"], "scenes[%d].nodes" % s):
                    self.check(n not in parent, "scenes[%d] lists nodes[%d], which is not a root (3.5.1)" % (s, n))


def validate(path):
    c = Checker(path)
    try:
        with open(path, "rb") as f:
            data = f.read()
    except OSError as e:
        c.err("cannot read: %s" % e)
        return c.errors
    doc, bin_chunk = c.glb(data)
    if doc is not None:
        try:
            c.document(doc, bin_chunk)
        except (AttributeError, TypeError, KeyError) as e:  # a property of the wrong JSON type
            c.err("malformed: %s: %s" % (type(e).__name__, e))
    return c.errors


def main(argv):
    if len(argv) < 2:
        print("usage: gltf_validate.py FILE.glb ...", file=sys.stderr)
        return 2
    bad = 0
    for path in argv[1:]:
        errors = validate(path)
        for e in errors:
            print(e)
        bad += bool(errors)
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
