#!/usr/bin/env python3
"""Writes glint's glTF test scene, by hand (no Blender needed), as OUT_DIR/textured.gltf (with
textured.bin and PNG textures beside it) and OUT_DIR/textured.glb (everything embedded).

    scripts/make_gltf_scene.py OUT_DIR

The scene exercises what the importer maps: a ground quad with a tiled base-colour texture
(KHR_texture_transform scale 4, mirrored-repeat sampler), a slab with a normal map, a
metallic-roughness texture on a metal ball, an emissive panel with an emissive texture and
KHR_materials_emissive_strength, a glass ball (KHR_materials_transmission, KHR_materials_ior, KHR_materials_volume), a
node hierarchy (a parent's rotation and scale carried to its children), a perspective camera and
a KHR_lights_punctual spot light. Generated files are small (about 60 KB) and not committed."""
import base64
import json
import math
import os
import struct
import sys
import zlib


def png(width, height, pixel):
    """An 8-bit RGB PNG; pixel(x, y) -> (r, g, b) in 0..255, row 0 at the top."""
    raw = b"".join(b"\x00" + bytes(c for x in range(width) for c in pixel(x, y)) for y in range(height))

    def chunk(kind, data):
        body = kind + data
        return struct.pack(">I", len(data)) + body + struct.pack(">I", zlib.crc32(body) & 0xFFFFFFFF)

    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0))
            + chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))


def textures():
    n = 64
    checker = png(n, n, lambda x, y: (230, 200, 150) if ((x // 8) + (y // 8)) % 2 == 0 else (60, 90, 140))

    def bump(x, y):  # a grid of round bumps as tangent-space normals (+y up, OpenGL convention)
        u, v = (x % 16) / 16 - 0.5, (y % 16) / 16 - 0.5
        r2 = u * u + v * v
        nx, ny = (-u * 2, v * 2) if r2 < 0.16 else (0, 0)  # image y runs down: +v is -y
        nz = math.sqrt(max(0.0, 1 - nx * nx - ny * ny))
        return tuple(int(round((c * 0.5 + 0.5) * 255)) for c in (nx, ny, nz))

    normal = png(n, n, bump)
    # metallic (blue) 1 everywhere, roughness (green) in stripes 0.15 / 0.6
    metal_rough = png(n, n, lambda x, y: (0, 38 if (x // 8) % 2 == 0 else 153, 255))
    emissive = png(n, n, lambda x, y: (255, 220, 150) if (x // 16 + y // 16) % 2 == 0 else (40, 30, 20))
    return {"checker.png": checker, "normal.png": normal, "metal_rough.png": metal_rough, "emissive.png": emissive}


class Buffer:
    def __init__(self):
        self.data = bytearray()
        self.views, self.accessors = [], []

    def add(self, fmt, values, type_, component, target=None, minmax=False):
        while len(self.data) % 4:
            self.data.append(0)
        start = len(self.data)
        for v in values:
            self.data += struct.pack("<" + fmt, *(v if isinstance(v, (tuple, list)) else (v,)))
        view = {"buffer": 0, "byteOffset": start, "byteLength": len(self.data) - start}
        if target:
            view["target"] = target
        self.views.append(view)
        acc = {"bufferView": len(self.views) - 1, "componentType": component, "count": len(values), "type": type_}
        if minmax:
            acc["min"] = [min(v[k] for v in values) for k in range(3)]
            acc["max"] = [max(v[k] for v in values) for k in range(3)]
        self.accessors.append(acc)
        return len(self.accessors) - 1

    def mesh(self, positions, normals, uvs, indices):
        attrs = {"POSITION": self.add("fff", positions, "VEC3", 5126, 34962, True),
                 "NORMAL": self.add("fff", normals, "VEC3", 5126, 34962)}
        if uvs:
            attrs["TEXCOORD_0"] = self.add("ff", uvs, "VEC2", 5126, 34962)
        return attrs, self.add("H", indices, "SCALAR", 5123, 34963)


def box(sx, sy, sz):
    """An axis-aligned box centred at the origin; per-face normals and uvs."""
    faces = [((1, 0, 0), (0, 0, -1), (0, 1, 0)), ((-1, 0, 0), (0, 0, 1), (0, 1, 0)),
             ((0, 1, 0), (1, 0, 0), (0, 0, -1)), ((0, -1, 0), (1, 0, 0), (0, 0, 1)),
             ((0, 0, 1), (1, 0, 0), (0, 1, 0)), ((0, 0, -1), (-1, 0, 0), (0, 1, 0))]
    p, n, t, ix = [], [], [], []
    half = (sx / 2, sy / 2, sz / 2)
    for normal, u, v in faces:
        base = len(p)
        for a, b in ((-1, -1), (1, -1), (1, 1), (-1, 1)):
            p.append(tuple((normal[k] + a * u[k] + b * v[k]) * half[k] for k in range(3)))
            n.append(normal)
            t.append(((a + 1) / 2, (1 - b) / 2))
        ix += [base, base + 1, base + 2, base, base + 2, base + 3]
    return p, n, t, ix


def sphere(r, rings=24, segments=48):
    p, n, t, ix = [], [], [], []
    for i in range(rings + 1):
        th = math.pi * i / rings
        for j in range(segments + 1):
            ph = 2 * math.pi * j / segments
            d = (math.sin(th) * math.cos(ph), math.cos(th), math.sin(th) * math.sin(ph))
            p.append(tuple(r * c for c in d))
            n.append(d)
            t.append((j / segments, i / rings))
    for i in range(rings):
        for j in range(segments):
            a, b = i * (segments + 1) + j, (i + 1) * (segments + 1) + j
            ix += [a, a + 1, b, a + 1, b + 1, b]  # counter-clockwise seen from outside
    return p, n, t, ix


def build():
    buf = Buffer()
    meshes = []

    def add_mesh(name, geometry, material):
        attrs, indices = buf.mesh(*geometry)
        meshes.append({"name": name, "primitives": [{"attributes": attrs, "indices": indices, "material": material}]})
        return len(meshes) - 1

    ground = ([(-4, 0, -4), (4, 0, -4), (4, 0, 4), (-4, 0, 4)], [(0, 1, 0)] * 4,
              [(0, 1), (1, 1), (1, 0), (0, 0)], [0, 2, 1, 0, 3, 2])
    m_ground = add_mesh("ground", ground, 0)
    m_slab = add_mesh("slab", box(1.6, 0.3, 1.6), 1)
    m_metal = add_mesh("metal ball", sphere(0.5), 2)
    m_glass = add_mesh("glass ball", sphere(0.45), 3)
    m_panel = add_mesh("panel", box(1.2, 0.8, 0.05), 4)

    s = math.sin(math.radians(20)), math.cos(math.radians(20))
    doc = {
        "asset": {"version": "2.0", "generator": "glint scripts/make_gltf_scene.py"},
        "extensionsUsed": ["KHR_texture_transform", "KHR_materials_emissive_strength",
                           "KHR_materials_transmission", "KHR_materials_ior", "KHR_materials_volume",
                           "KHR_lights_punctual"],
        "scene": 0,
        "scenes": [{"nodes": [0, 1, 5, 6]}],
        "nodes": [
            {"name": "ground", "mesh": m_ground},
            {"name": "group", "rotation": [0, s[0], 0, s[1]], "scale": [1.2, 1.2, 1.2], "children": [2, 3, 4]},
            {"name": "slab", "mesh": m_slab, "translation": [-1.2, 0.15, 0.5]},
            {"name": "metal", "mesh": m_metal, "translation": [0.3, 0.5, 0.0]},
            {"name": "glass", "mesh": m_glass, "translation": [1.4, 0.45, 0.6]},
            {"name": "panel", "mesh": m_panel, "translation": [0, 0.9, 2.0]},
            {"name": "camera", "camera": 0, "translation": [0, 2.2, -6.0],
             "rotation": [0, 0.9945219, 0.1045285, 0], "children": [7]},
            {"name": "key light", "extensions": {"KHR_lights_punctual": {"light": 0}},
             "translation": [2, 2.5, 0], "rotation": [-0.2588190, 0, 0, 0.9659258]},
        ],
        "cameras": [{"name": "main", "type": "perspective", "perspective": {"yfov": 0.7, "znear": 0.1}}],
        "extensions": {"KHR_lights_punctual": {"lights": [
            {"name": "spot", "type": "spot", "color": [1, 0.95, 0.9], "intensity": 40,
             "spot": {"innerConeAngle": 0.3, "outerConeAngle": 0.6}}]}},
        "samplers": [{"wrapS": 33648, "wrapT": 33648}, {"wrapS": 33071, "wrapT": 10497}],
        "images": [{"uri": "checker.png"}, {"uri": "normal.png"}, {"uri": "metal_rough.png"}, {"uri": "emissive.png"}],
        "textures": [{"source": 0, "sampler": 0}, {"source": 1}, {"source": 2, "sampler": 1}, {"source": 3}],
        "materials": [
            {"name": "tiles", "pbrMetallicRoughness": {
                "baseColorTexture": {"index": 0, "extensions": {"KHR_texture_transform": {"scale": [4, 4]}}},
                "metallicFactor": 0, "roughnessFactor": 0.8}},
            {"name": "bumpy", "pbrMetallicRoughness": {"baseColorFactor": [0.7, 0.7, 0.72, 1],
                                                       "metallicFactor": 0, "roughnessFactor": 0.5},
             "normalTexture": {"index": 1, "scale": 1.0}},
            {"name": "brushed metal", "pbrMetallicRoughness": {
                "baseColorFactor": [0.95, 0.8, 0.55, 1], "metallicFactor": 1, "roughnessFactor": 1,
                "metallicRoughnessTexture": {"index": 2}}},
            {"name": "glass", "pbrMetallicRoughness": {"baseColorFactor": [1, 1, 1, 1], "metallicFactor": 0,
                                                        "roughnessFactor": 0},
             "extensions": {"KHR_materials_transmission": {"transmissionFactor": 1},
                            "KHR_materials_ior": {"ior": 1.45},
                            "KHR_materials_volume": {"thicknessFactor": 0.9, "attenuationDistance": 0.5,
                                                     "attenuationColor": [0.9, 0.5, 0.25]}}},
            {"name": "lamp", "pbrMetallicRoughness": {"baseColorFactor": [0.1, 0.1, 0.1, 1]},
             "emissiveFactor": [1, 1, 1], "emissiveTexture": {"index": 3},
             "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 4}}},
        ],
        "meshes": meshes,
        "accessors": buf.accessors,
        "bufferViews": buf.views,
    }
    return doc, bytes(buf.data)


def main():
    if len(sys.argv) != 2:
        sys.exit("usage: make_gltf_scene.py OUT_DIR")
    out = sys.argv[1]
    os.makedirs(out, exist_ok=True)
    doc, data = build()
    tex = textures()
    # .gltf with external files
    gltf = json.loads(json.dumps(doc))
    gltf["buffers"] = [{"uri": "textured.bin", "byteLength": len(data)}]
    with open(os.path.join(out, "textured.bin"), "wb") as f:
        f.write(data)
    for name, bytes_ in tex.items():
        with open(os.path.join(out, name), "wb") as f:
            f.write(bytes_)
    with open(os.path.join(out, "textured.gltf"), "w") as f:
        json.dump(gltf, f, indent=1)
    # .glb: the images appended to the binary chunk as buffer views
    glb = json.loads(json.dumps(doc))
    blob = bytearray(data)
    for i, name in enumerate(["checker.png", "normal.png", "metal_rough.png", "emissive.png"]):
        while len(blob) % 4:
            blob.append(0)
        glb["bufferViews"].append({"buffer": 0, "byteOffset": len(blob), "byteLength": len(tex[name])})
        blob += tex[name]
        glb["images"][i] = {"bufferView": len(glb["bufferViews"]) - 1, "mimeType": "image/png"}
    while len(blob) % 4:
        blob.append(0)
    glb["buffers"] = [{"byteLength": len(blob)}]
    js = json.dumps(glb).encode()
    js += b" " * ((4 - len(js) % 4) % 4)
    body = struct.pack("<I4s", len(js), b"JSON") + js + struct.pack("<I4s", len(blob), b"BIN\x00") + bytes(blob)
    with open(os.path.join(out, "textured.glb"), "wb") as f:
        f.write(struct.pack("<4sII", b"glTF", 2, 12 + len(body)) + body)
    print(f"wrote {out}/textured.gltf (+ .bin, 4 PNGs) and {out}/textured.glb")


if __name__ == "__main__":
    main()
