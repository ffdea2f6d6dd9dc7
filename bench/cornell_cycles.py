# The Cornell box of scenes/cornell-box.yaml, built in Blender and rendered with Cycles on the
# CPU, for bench/compare_cycles.sh. Same measured geometry, camera (vertical fov 39.3077 deg),
# reflectances, one-sided quad light of radiance (17, 12, 4), box filter, no denoiser, no
# adaptive sampling (unless asked for), no clamping, and the same path length: Cycles' max_bounces = 15 traces the
# same paths as glint's max_depth = 16 (Cycles counts bounces after the first hit, glint counts
# scattering events including it).
#
#   blender -b --factory-startup -P bench/cornell_cycles.py -- OUT.exr SPP THREADS [SEED [SIZE [THRESHOLD]]]
#
# SIZE: the square film's side (default 512); THRESHOLD > 0: adaptive sampling with that noise
# threshold (Cycles' automatic minimum samples), SPP the maximum (bench/compare_adaptive.sh).
# Prints "cycles render seconds: S" (the render alone, without Blender's start-up).
#
# CYCLES_SCENE=bunny builds scenes/bunny.yaml instead: the same room without the two blocks, and
# the Stanford bunny (stanford-bunny.ply, from BUNNY_PLY or the models folder beside the checkout)
# placed as that file places it, white and diffuse.
import math
import os
import struct
import sys

import bpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from cycles_setup import cycles_settings, one_sided_emission, render_timed  # noqa: E402

argv = sys.argv[sys.argv.index("--") + 1:]
out, spp, threads = argv[0], int(argv[1]), int(argv[2])
seed = int(argv[3]) if len(argv) > 3 else 0
size = int(argv[4]) if len(argv) > 4 else 512
threshold = float(argv[5]) if len(argv) > 5 else 0.0

# Cornell data (right-handed, y up) to Blender (right-handed, z up): a rotation of +90 degrees
# about x, (x, y, z) -> (x, -z, y). Handedness is kept, so the red wall stays on the left.
def to_blender(p):
    return (p[0], -p[2], p[1])

WHITE = (0.725, 0.71, 0.68)
RED = (0.63, 0.065, 0.05)
GREEN = (0.14, 0.45, 0.091)
QUADS = [
    (WHITE, [(552.8, 0, 0), (0, 0, 0), (0, 0, 559.2), (549.6, 0, 559.2)]),  # floor
    (WHITE, [(556, 548.8, 0), (556, 548.8, 559.2), (0, 548.8, 559.2), (0, 548.8, 0)]),  # ceiling
    (WHITE, [(549.6, 0, 559.2), (0, 0, 559.2), (0, 548.8, 559.2), (556, 548.8, 559.2)]),  # back
    (GREEN, [(0, 0, 559.2), (0, 0, 0), (0, 548.8, 0), (0, 548.8, 559.2)]),  # right wall
    (RED, [(552.8, 0, 0), (549.6, 0, 559.2), (556, 548.8, 559.2), (556, 548.8, 0)]),  # left wall
    (WHITE, [(130, 165, 65), (82, 165, 225), (240, 165, 272), (290, 165, 114)]),
    (WHITE, [(290, 0, 114), (290, 165, 114), (240, 165, 272), (240, 0, 272)]),
    (WHITE, [(130, 0, 65), (130, 165, 65), (290, 165, 114), (290, 0, 114)]),
    (WHITE, [(82, 0, 225), (82, 165, 225), (130, 165, 65), (130, 0, 65)]),
    (WHITE, [(240, 0, 272), (240, 165, 272), (82, 165, 225), (82, 0, 225)]),
    (WHITE, [(423, 330, 247), (265, 330, 296), (314, 330, 456), (472, 330, 406)]),
    (WHITE, [(423, 0, 247), (423, 330, 247), (472, 330, 406), (472, 0, 406)]),
    (WHITE, [(472, 0, 406), (472, 330, 406), (314, 330, 456), (314, 0, 456)]),
    (WHITE, [(314, 0, 456), (314, 330, 456), (265, 330, 296), (265, 0, 296)]),
    (WHITE, [(265, 0, 296), (265, 330, 296), (423, 330, 247), (423, 0, 247)]),
]
LIGHT = [(343, 548.7, 227), (343, 548.7, 332), (213, 548.7, 332), (213, 548.7, 227)]

bpy.ops.wm.read_factory_settings(use_empty=True)
scene = bpy.context.scene


def diffuse_material(name, color):
    m = bpy.data.materials.new(name)
    m.use_nodes = True
    nodes = m.node_tree.nodes
    nodes.clear()
    out_node = nodes.new("ShaderNodeOutputMaterial")
    bsdf = nodes.new("ShaderNodeBsdfDiffuse")
    bsdf.inputs["Color"].default_value = (*color, 1)
    bsdf.inputs["Roughness"].default_value = 0  # Lambert
    m.node_tree.links.new(bsdf.outputs["BSDF"], out_node.inputs["Surface"])
    return m


def light_material():
    # Emission on the front face only (glint's area lights are one-sided), black behind.
    m = bpy.data.materials.new("light")
    m.use_nodes = True
    nodes, links = m.node_tree.nodes, m.node_tree.links
    nodes.clear()
    out_node = nodes.new("ShaderNodeOutputMaterial")
    links.new(one_sided_emission(nodes, links, (17, 12, 4)), out_node.inputs["Surface"])
    return m


def add_mesh(name, quads, material, face_down=False):
    verts, faces = [], []
    for q in quads:
        base = len(verts)
        verts += [to_blender(p) for p in q]
        faces.append(tuple(range(base, base + len(q))))
    mesh = bpy.data.meshes.new(name)
    mesh.from_pydata(verts, [], faces)
    mesh.update()
    if face_down and mesh.polygons[0].normal.z > 0:
        mesh.flip_normals()
    obj = bpy.data.objects.new(name, mesh)
    obj.data.materials.append(material)
    scene.collection.objects.link(obj)
    return obj


variant = os.environ.get("CYCLES_SCENE", "cornell")
if variant not in ("cornell", "bunny"):
    sys.exit(f"cornell_cycles.py: CYCLES_SCENE={variant}: cornell or bunny")
if variant == "bunny":
    QUADS = QUADS[:5]  # the room; the bunny takes the blocks' place


def read_ply(path):
    # The binary little-endian PLY of ../shared/models: float x, y, z per vertex, then faces as a
    # uchar count and that many int32 indices.
    with open(path, "rb") as f:
        data = f.read()
    end = data.index(b"end_header\n") + len(b"end_header\n")
    header = data[:end].decode("ascii").split("\n")
    if "format binary_little_endian 1.0" not in header:
        sys.exit(f"{path}: not a binary little-endian PLY")
    nv = int(next(l for l in header if l.startswith("element vertex")).split()[2])
    nf = int(next(l for l in header if l.startswith("element face")).split()[2])
    verts = [struct.unpack_from("<3f", data, end + 12 * i) for i in range(nv)]
    faces, at = [], end + 12 * nv
    for _ in range(nf):
        n = data[at]
        faces.append(struct.unpack_from(f"<{n}i", data, at + 1))
        at += 1 + 4 * n
    return verts, faces


def add_bunny(material):
    here = os.path.dirname(os.path.abspath(__file__))
    candidates = [os.environ.get("BUNNY_PLY", ""), os.path.join(here, "..", "..", "shared", "models", "stanford-bunny.ply"),
                  "/work/shared/models/stanford-bunny.ply"]
    path = next((c for c in candidates if c and os.path.exists(c)), None)
    if path is None:
        sys.exit("cornell_cycles.py: stanford-bunny.ply not found (set BUNNY_PLY)")
    verts, faces = read_ply(path)
    # scenes/bunny.yaml's transform, first step first: translate, scale 2000, rotate 180 degrees
    # about y ((x, y, z) -> (-x, y, -z)), translate to (278, 0, 280).
    t = (0.0168405, -0.032987, 0.001537)
    placed = [to_blender((278 - 2000 * (v[0] + t[0]), 2000 * (v[1] + t[1]), 280 - 2000 * (v[2] + t[2]))) for v in verts]
    mesh = bpy.data.meshes.new("bunny")
    mesh.from_pydata(placed, [], faces)
    mesh.update()
    obj = bpy.data.objects.new("bunny", mesh)
    obj.data.materials.append(material)
    scene.collection.objects.link(obj)


materials = {}
for color, q in QUADS:
    if color not in materials:
        materials[color] = diffuse_material(f"m{len(materials)}", color)
    add_mesh("quad", [q], materials[color])
add_mesh("light", [LIGHT], light_material(), face_down=True)
if variant == "bunny":
    add_bunny(materials[WHITE])

world = bpy.data.worlds.new("black")
world.use_nodes = True
world.node_tree.nodes["Background"].inputs["Color"].default_value = (0, 0, 0, 1)
scene.world = world

cam_data = bpy.data.cameras.new("camera")
cam_data.sensor_fit = "VERTICAL"
cam_data.angle_y = math.radians(39.3077)
cam_data.clip_start = 1
cam_data.clip_end = 10000
cam = bpy.data.objects.new("camera", cam_data)
cam.location = to_blender((278, 273, -800))
cam.rotation_euler = (math.pi / 2, 0, math.pi)  # looks along Cornell +z (Blender -y), z up
scene.collection.objects.link(cam)
scene.camera = cam

r = scene.render
r.resolution_x = r.resolution_y = size
c = cycles_settings(scene, out, spp, threads, seed)
c.use_adaptive_sampling = threshold > 0
if threshold > 0:
    c.adaptive_threshold = threshold
    c.adaptive_min_samples = 0  # Cycles' automatic minimum
c.max_bounces = 15
c.diffuse_bounces = 15
c.glossy_bounces = 15
c.transmission_bounces = 15
c.caustics_reflective = True
c.caustics_refractive = True
c.blur_glossy = 0
render_timed()
