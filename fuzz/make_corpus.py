#!/usr/bin/env python3
"""Writes the fuzzers' seed corpora, one folder per target, from glint's own scenes and test files
and from small files written here (every PLY encoding, OBJ index forms, every image format the
texture reader takes):

    fuzz/make_corpus.py OUT_DIR GLINT_CLI

OUT_DIR/<target>/ then holds the seeds of fuzz_<target>. GLINT_CLI writes the checkpoint seed
(an 8 x 8 render). Nothing here is committed: it is rebuilt from the sources whenever they change."""
import glob
import os
import shutil
import struct
import subprocess
import sys
import tempfile
import zlib

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
IMAGE_EXT = [".png", ".exr", ".hdr", ".pfm", ".jpg", ".tga", ".ppm", ".tif"]  # fuzz_image.cpp's order


def put(folder, name, data):
    os.makedirs(folder, exist_ok=True)
    with open(os.path.join(folder, name), "wb") as f:
        f.write(data if isinstance(data, bytes) else data.encode())


def copy_files(pattern, folder):
    for path in sorted(glob.glob(os.path.join(ROOT, pattern), recursive=True)):
        with open(path, "rb") as f:
            put(folder, os.path.relpath(path, ROOT).replace("/", "_"), f.read())


def ply_seeds(folder):
    verts = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (0.5, 0.5, 1)]
    faces = [(0, 1, 2, 3), (0, 1, 4), (1, 2, 4), (2, 3, 4), (3, 0, 4)]
    for fmt, order in (("ascii", None), ("binary_little_endian", "<"), ("binary_big_endian", ">")):
        for extras in ((), ("nx", "ny", "nz"), ("u", "v"), ("s", "t", "red", "green", "blue")):
            props = ["x", "y", "z", *extras]
            kind = {"red": "uchar", "green": "uchar", "blue": "uchar"}
            head = f"ply\nformat {fmt} 1.0\ncomment seed\nelement vertex {len(verts)}\n"
            head += "".join(f"property {kind.get(p, 'float')} {p}\n" for p in props)
            head += f"element face {len(faces)}\nproperty list uchar int vertex_indices\nend_header\n"
            values = lambda v: [*v, *[(0.5 if p not in kind else 200) for p in extras]]
            if order is None:
                body = "".join(" ".join(str(x) for x in values(v)) + "\n" for v in verts)
                body += "".join(f"{len(f)} " + " ".join(map(str, f)) + "\n" for f in faces)
                data = (head + body).encode()
            else:
                body = b""
                for v in verts:
                    for p, x in zip(props, values(v)):
                        body += struct.pack(order + ("B" if p in kind else "f"), int(x) if p in kind else x)
                for f in faces:
                    body += struct.pack(order + "B" + "i" * len(f), len(f), *f)
                data = head.encode() + body
            put(folder, f"{fmt}-{'-'.join(extras) or 'plain'}.ply", data)


def obj_seeds(folder):
    mtl = ("newmtl matte\nKd 0.8 0.2 0.1\nnewmtl shiny\nKd 0.1 0.1 0.7\nKs 0.5 0.5 0.5\nNs 98\nNi 1.4\n"
           "newmtl glass\nKd 1 1 1\nd 0.2\nNi 1.33\nnewmtl lamp\nKd 0 0 0\nKe 5 4 3\n"
           "newmtl bumpy\nKd 1 1 1\nmap_Bump -bm 0.5 n.png\nillum 2\n")
    cube = "".join(f"v {x} {y} {z}\n" for x in (0, 1) for y in (0, 1) for z in (0, 1))
    cube += "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvn 0 0 1\nvn 0 1 0\n"
    put(folder, "plain.obj", cube + "f 1 2 4 3\nf 5 6 8 7\nf 1 2 6 5\n")
    put(folder, "slashes.obj", cube + "o a\nf 1/1/1 2/2/1 4/3/1\ng b\nf 5//2 6//2 8//2\ns 1\nf 1/1 2/2 6/3 5/4\n")
    put(folder, "negative.obj", cube + "f -1 -2 -3\nf -4/-1/-1 -5/-2/-2 -6/-3/-1\nl 1 2\np 3\n")
    put(folder, "materials.obj", "mtllib m.mtl\n" + cube +
        "usemtl matte\nf 1 2 4 3\nusemtl shiny\nf 5 6 8\nusemtl glass\nf 1 5 6\nusemtl lamp\nf 2 6 8 4\n"
        "usemtl bumpy\nf 3 4 8 7\n" + "\n#MTL\n" + mtl)


def image_seeds(folder):
    def seed(name, ext, data):
        put(folder, name, bytes([IMAGE_EXT.index(ext)]) + data)

    for path in ("scenes/textures/uv-grid.png", "scenes/textures/sky.exr"):
        with open(os.path.join(ROOT, path), "rb") as f:
            seed(os.path.basename(path), os.path.splitext(path)[1], f.read())
    w, h = 3, 2
    rgb = [((x * 80) % 256, (y * 120) % 256, 40) for y in range(h) for x in range(w)]
    seed("rgb.ppm", ".ppm", f"P6\n{w} {h}\n255\n".encode() + bytes(c for p in rgb for c in p))
    seed("grey.ppm", ".ppm", f"P5\n{w} {h}\n255\n".encode() + bytes(p[0] for p in rgb))
    seed("ascii.ppm", ".ppm", f"P3\n{w} {h}\n255\n".encode() + " ".join(str(c) for p in rgb for c in p).encode())
    seed("colour.pfm", ".pfm", f"PF\n{w} {h}\n-1.0\n".encode() + struct.pack(f"<{3 * w * h}f", *[c / 255 for p in rgb for c in p]))
    seed("grey-be.pfm", ".pfm", f"Pf\n{w} {h}\n1.0\n".encode() + struct.pack(f">{w * h}f", *[p[0] / 255 for p in rgb]))
    # Radiance HDR, flat (not run-length encoded) RGBE
    rgbe = b"".join(bytes([p[0], p[1], p[2], 128]) for p in rgb)
    seed("flat.hdr", ".hdr", b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n" + f"-Y {h} +X {w}\n".encode() + rgbe)
    # Uncompressed true-colour TGA, bottom-up
    tga = struct.pack("<BBBHHBHHHHBB", 0, 0, 2, 0, 0, 0, 0, 0, w, h, 24, 0)
    seed("plain.tga", ".tga", tga + bytes(c for p in rgb for c in reversed(p)))
    # An 8-bit grey-alpha PNG, written by hand
    raw = b"".join(b"\x00" + bytes(v for x in range(w) for v in (x * 100, 255 - y * 100)) for y in range(h))
    chunk = lambda k, d: struct.pack(">I", len(d)) + k + d + struct.pack(">I", zlib.crc32(k + d) & 0xFFFFFFFF)
    png = b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 4, 0, 0, 0))
    seed("grey-alpha.png", ".png", png + chunk(b"IDAT", zlib.compress(raw)) + chunk(b"IEND", b""))
    # JPEG and TIFF through oiiotool, when present
    if shutil.which("oiiotool"):
        with tempfile.TemporaryDirectory() as tmp:
            for ext in (".jpg", ".tif"):
                out = os.path.join(tmp, "x" + ext)
                src = os.path.join(ROOT, "scenes/textures/uv-grid.png")
                if subprocess.run(["oiiotool", src, "--resize", "8x8", "-o", out], capture_output=True).returncode == 0:
                    with open(out, "rb") as f:
                        seed("uv-grid" + ext, ext, f.read())


def gltf_seeds(folder):
    copy_files("tests/data/khronos/*.gltf", folder)
    with tempfile.TemporaryDirectory() as tmp:
        for script in ("make_gltf_scene.py", "make_gltf_alpha.py"):
            subprocess.run([sys.executable, os.path.join(ROOT, "scripts", script), tmp], check=True, capture_output=True)
        for name in ("textured.glb", "alpha.gltf"):
            with open(os.path.join(tmp, name), "rb") as f:
                put(folder, name, f.read())


def checkpoint_seeds(folder, cli):
    with tempfile.TemporaryDirectory() as tmp:
        scene = os.path.join(ROOT, "scenes/cornell-box.yaml")
        for name, extra in (("uniform", ["--spp", "2"]), ("adaptive", ["--noise-threshold", "0.1", "--spp", "32"])):
            ckpt = os.path.join(tmp, name + ".ckpt")
            cmd = [cli, "render", scene, "--width", "6", "--height", "4", "--threads", "1", "-q",
                   "-o", os.path.join(tmp, name + ".exr"), "--checkpoint", ckpt, *extra]
            subprocess.run(cmd, check=True, capture_output=True)
            with open(ckpt, "rb") as f:
                put(folder, name + ".ckpt", f.read())


def structure_seeds(folder):
    """Choice streams for fuzz_structure: one per kind of attack (the first byte picks it), the
    rest the choices; each reaches its class at once (a self-referencing anchor, extras 40,000
    deep, an 11000 x 11000 HDR header over 56 bytes, a 360-corner polygon)."""
    put(folder, "aliases", bytes([0, 40, 0, 5, 0, 3, 0, 0, 0, 7, 0, 11, 0, 1]))
    put(folder, "deep-extras", bytes([1, 0x40, 0x9c, 1, 3, 0, 0, 0, 36, 0, 0, 0, 1]))
    put(folder, "hdr-lie", bytes([2, 0xf8, 0x2a, 0, 0, 0xf8, 0x2a, 0, 0, 0, 16, 0]) + bytes(16))
    put(folder, "circle", bytes([3, 0x65, 0x01]) + bytes(400))


def main():
    if len(sys.argv) != 3:
        sys.exit("usage: fuzz/make_corpus.py OUT_DIR GLINT_CLI")
    out, cli = sys.argv[1], sys.argv[2]
    shutil.rmtree(out, ignore_errors=True)
    copy_files("scenes/**/*.yaml", os.path.join(out, "scene"))
    copy_files("scenes/**/*.pbrt", os.path.join(out, "pbrt"))
    obj_seeds(os.path.join(out, "obj"))
    ply_seeds(os.path.join(out, "ply"))
    gltf_seeds(os.path.join(out, "gltf"))
    image_seeds(os.path.join(out, "image"))
    checkpoint_seeds(os.path.join(out, "checkpoint"), cli)
    structure_seeds(os.path.join(out, "structure"))
    for target in sorted(os.listdir(out)):
        print(f"make_corpus: {target}: {len(os.listdir(os.path.join(out, target)))} seeds")


if __name__ == "__main__":
    main()
