#!/usr/bin/env python3
"""Writes glint's glTF test model for alpha, texture-coordinate sets and quantized meshes, by hand,
as OUT_DIR/alpha.gltf (everything embedded as data URIs).

    scripts/make_gltf_alpha.py OUT_DIR

Five 4 x 4 quads in the plane z = 0 (glTF frame), facing +z, side by side along x:
  fence   x in [0, 4]:   alphaMode MASK (cutoff 0.5), a 4 x 4 RGBA base-colour texture whose
                         texel (i, j) is opaque when i + j is even and fully transparent otherwise
  veil    x in [10, 14]: alphaMode BLEND, baseColorFactor alpha 0.25, no texture
  fade    x in [20, 24]: alphaMode MASK (cutoff 0.5), COLOR_0 (RGBA) with alpha 0 at x = 20 and
                         1 at x = 24, so alpha = (x - 20) / 4
  second  x in [30, 34]: opaque; TEXCOORD_0 is (0, 0) everywhere, TEXCOORD_1 spans the quad, and
                         the base-colour texture (texCoord 1) is a 4 x 4 RGB image whose texel
                         (i, j) is (255 * (i % 2), 255 * (j % 2), 255) -- so the colour seen says
                         which set was read
  packed  x in [40, 44]: positions stored as unsigned shorts x 0.5 by its node's scale
                         (KHR_mesh_quantization, listed in extensionsRequired)
Texel (i, j) is column i, row j from the top; uv (glTF, v down) covers the quad with u = (x - x0)/4
and v = 1 - y/4, so texel (i, j) is centred at x = x0 + i + 0.5, y = 3.5 - j."""
import base64
import json
import os
import struct
import sys
import zlib


def png(width, height, channels, pixel):
    """An 8-bit PNG, RGB (3) or RGBA (4); pixel(x, y) -> tuple of 0..255, row 0 at the top."""
    raw = b"".join(b"\x00" + bytes(c for x in range(width) for c in pixel(x, y)) for y in range(height))

    def chunk(kind, data):
        body = kind + data
        return struct.pack(">I", len(data)) + body + struct.pack(">I", zlib.crc32(body) & 0xFFFFFFFF)

    colour_type = 6 if channels == 4 else 2
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, colour_type, 0, 0, 0))
            + chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))


def data_uri(mime, data):
    return f"data:{mime};base64," + base64.b64encode(data).decode()


def build():
    data = bytearray()
    views, accessors = [], []

    def add(fmt, values, type_, component, normalized=False):
        while len(data) % 4:
            data.append(0)
        start = len(data)
        data.extend(struct.pack("<" + fmt * len(values), *values))
        views.append({"buffer": 0, "byteOffset": start, "byteLength": len(data) - start})
        count = len(values) // {"SCALAR": 1, "VEC2": 2, "VEC3": 3, "VEC4": 4}[type_]
        a = {"bufferView": len(views) - 1, "componentType": component, "count": count, "type": type_}
        if normalized:
            a["normalized"] = True
        if type_ == "VEC3" and fmt == "f":
            a["min"] = [min(values[k::3]) for k in range(3)]
            a["max"] = [max(values[k::3]) for k in range(3)]
        accessors.append(a)
        return len(accessors) - 1

    FLOAT, USHORT = 5126, 5123

    def quad(x0, **extra):
        corners = [(0, 0), (4, 0), (4, 4), (0, 4)]
        attributes = {"POSITION": add("f", [v for cx, cy in corners for v in (x0 + cx, cy, 0.0)], "VEC3", FLOAT),
                      "NORMAL": add("f", [0.0, 0.0, 1.0] * 4, "VEC3", FLOAT),
                      "TEXCOORD_0": add("f", [v for cx, cy in corners for v in (cx / 4, 1 - cy / 4)], "VEC2", FLOAT)}
        attributes.update(extra)
        return attributes

    indices = add("H", [0, 1, 2, 0, 2, 3], "SCALAR", USHORT)
    corners = [(0, 0), (4, 0), (4, 4), (0, 4)]
    meshes = [
        {"name": "fence", "primitives": [{"attributes": quad(0), "indices": indices, "material": 0}]},
        {"name": "veil", "primitives": [{"attributes": quad(10), "indices": indices, "material": 1}]},
        {"name": "fade", "primitives": [{"attributes": quad(20, COLOR_0=add(
            "f", [v for cx, cy in corners for v in (1.0, 1.0, 1.0, cx / 4)], "VEC4", FLOAT)),
            "indices": indices, "material": 2}]},
        {"name": "second", "primitives": [{"attributes": dict(quad(30), TEXCOORD_0=add("f", [0.0] * 8, "VEC2", FLOAT),
                                                              TEXCOORD_1=add("f", [v for cx, cy in corners
                                                                                   for v in (cx / 4, 1 - cy / 4)],
                                                                             "VEC2", FLOAT)),
                                           "indices": indices, "material": 3}]},
        {"name": "packed", "primitives": [{"attributes": {"POSITION": add(
            "H", [v for cx, cy in corners for v in (80 + 2 * cx, 2 * cy, 0)], "VEC3", USHORT)},
            "indices": indices, "material": 3}]},
    ]
    # The quantized accessor's bounds, in its own units (the spec requires them for POSITION).
    accessors[meshes[4]["primitives"][0]["attributes"]["POSITION"]].update({"min": [80, 0, 0], "max": [88, 8, 0]})
    fence = png(4, 4, 4, lambda i, j: (200, 160, 90, 255 if (i + j) % 2 == 0 else 0))
    second = png(4, 4, 3, lambda i, j: (255 * (i % 2), 255 * (j % 2), 255))
    materials = [
        {"name": "fence", "alphaMode": "MASK", "alphaCutoff": 0.5,
         "pbrMetallicRoughness": {"baseColorTexture": {"index": 0}, "metallicFactor": 0}},
        {"name": "veil", "alphaMode": "BLEND",
         "pbrMetallicRoughness": {"baseColorFactor": [0.2, 0.5, 0.9, 0.25], "metallicFactor": 0}},
        {"name": "fade", "alphaMode": "MASK", "pbrMetallicRoughness": {"metallicFactor": 0}},
        {"name": "second", "pbrMetallicRoughness": {"baseColorTexture": {"index": 1, "texCoord": 1},
                                                    "metallicFactor": 0}},
    ]
    return {
        "asset": {"version": "2.0", "generator": "glint scripts/make_gltf_alpha.py"},
        "extensionsUsed": ["KHR_mesh_quantization"],
        "extensionsRequired": ["KHR_mesh_quantization"],
        "scene": 0,
        "scenes": [{"nodes": [0, 1, 2, 3, 4]}],
        "nodes": [{"mesh": 0}, {"mesh": 1}, {"mesh": 2}, {"mesh": 3}, {"mesh": 4, "scale": [0.5, 0.5, 0.5]}],
        "meshes": meshes,
        "materials": materials,
        "textures": [{"source": 0, "sampler": 0}, {"source": 1, "sampler": 0}],
        "samplers": [{"wrapS": 33071, "wrapT": 33071}],
        "images": [{"uri": data_uri("image/png", fence)}, {"uri": data_uri("image/png", second)}],
        "accessors": accessors,
        "bufferViews": views,
        "buffers": [{"byteLength": len(data), "uri": data_uri("application/octet-stream", bytes(data))}],
    }


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    out = sys.argv[1]
    os.makedirs(out, exist_ok=True)
    with open(os.path.join(out, "alpha.gltf"), "w") as f:
        json.dump(build(), f, indent=1)
    print(f"wrote {out}/alpha.gltf")


if __name__ == "__main__":
    main()
