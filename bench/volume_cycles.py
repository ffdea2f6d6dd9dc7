# The volume benchmark scenes of bench/volumes/ (fog.yaml, cloud.yaml), built in Blender and
# rendered with Cycles on the CPU, for bench/compare_volumes.sh. Same camera (vertical fov), sun
# (irradiance and angular diameter), constant world, diffuse floor and sphere, the same medium
# coefficients and phase (Volume Scatter + Volume Absorption for the fog; a Volume object from
# the same .vdb with a Principled Volume, absorption colour black, for the cloud, whose density
# then multiplies the grid and whose colour is the albedo), box filter, no denoiser, no adaptive
# sampling, no clamping, and the same path length: Cycles' N bounces of every kind are glint's
# max_depth N + 1 (glint counts the first scattering too): 15 for the fog; for the dense cloud
# (albedo 0.98, hundreds of scatterings inside) 1023, as good as no limit, so that the image is
# the full transport and not each renderer's way of cutting it. Interface crossings are
# transparent bounces in Cycles: up to 64.
#
# glint's frame is left-handed with y up, Blender's right-handed with z up: points map by the
# rotation (x, y, z) -> (-x, z, y), which shows the image mirrored left to right:
# bench/compare_volumes.sh mirrors the written EXR back (oiiotool --flop). (Mapping by the mirror (x, z, y) instead would need a negative
# determinant on the Volume object, and Cycles then samples the grid mirrored.)
#
#   blender -b --factory-startup -P bench/volume_cycles.py -- SCENE OUT.exr SPP THREADS [SEED] [STEP_RATE] [BOUNCES]
#
# Prints "cycles render seconds: S" (the render alone, without Blender's start-up).
import math
import os
import sys

import bpy
from mathutils import Matrix, Vector

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from cycles_setup import cycles_settings, render_timed  # noqa: E402

argv = sys.argv[sys.argv.index("--") + 1:]
which, out, spp, threads = argv[0], argv[1], int(argv[2]), int(argv[3])
seed = int(argv[4]) if len(argv) > 4 else 0
step_rate = float(argv[5]) if len(argv) > 5 else 1.0
bounces = int(argv[6]) if len(argv) > 6 else None  # overrides the scene's bounce limit
here = os.path.dirname(os.path.abspath(__file__))


def P(p):
    return Vector((-p[0], p[2], p[1]))


bpy.ops.wm.read_factory_settings(use_empty=True)
scene = bpy.context.scene


def node_material(name):
    m = bpy.data.materials.new(name)
    m.use_nodes = True
    m.node_tree.nodes.clear()
    return m, m.node_tree.nodes, m.node_tree.links


def diffuse(name, color):
    m, nodes, links = node_material(name)
    out_node = nodes.new("ShaderNodeOutputMaterial")
    bsdf = nodes.new("ShaderNodeBsdfDiffuse")
    bsdf.inputs["Color"].default_value = (*color, 1)
    bsdf.inputs["Roughness"].default_value = 0
    links.new(bsdf.outputs["BSDF"], out_node.inputs["Surface"])
    return m


def mesh_object(name, verts, faces, material):
    mesh = bpy.data.meshes.new(name)
    mesh.from_pydata([P(v) for v in verts], [], faces)
    mesh.update()
    obj = bpy.data.objects.new(name, mesh)
    obj.data.materials.append(material)
    scene.collection.objects.link(obj)
    return obj


def quad(name, corner, e1, e2, material):
    c, a, b = Vector(corner), Vector(e1), Vector(e2)
    return mesh_object(name, [c, c + a, c + a + b, c + b], [(0, 1, 2, 3)], material)


def box(name, lo, hi, material):
    x0, y0, z0 = lo
    x1, y1, z1 = hi
    v = [(x0, y0, z0), (x1, y0, z0), (x1, y1, z0), (x0, y1, z0), (x0, y0, z1), (x1, y0, z1), (x1, y1, z1), (x0, y1, z1)]
    # Wound so that every face's normal points out of the box (Cycles tells a volume's inside
    # from the normals).
    f = [(3, 2, 1, 0), (5, 6, 7, 4), (1, 5, 4, 0), (7, 6, 2, 3), (4, 7, 3, 0), (2, 6, 5, 1)]
    return mesh_object(name, v, f, material)


def sun(direction, irradiance, diameter_deg):
    data = bpy.data.lights.new("sun", "SUN")
    data.energy = irradiance  # W/m^2 on a surface facing it: glint's directional intensity
    data.angle = math.radians(diameter_deg)
    obj = bpy.data.objects.new("sun", data)
    # A sun shines along its local -z.
    obj.rotation_euler = P(direction).to_track_quat("-Z", "Y").to_euler()
    scene.collection.objects.link(obj)


def world(color):
    w = bpy.data.worlds.new("sky")
    w.use_nodes = True
    w.node_tree.nodes["Background"].inputs["Color"].default_value = (*color, 1)
    w.node_tree.nodes["Background"].inputs["Strength"].default_value = 1
    scene.world = w


def camera(frm, to, fov, width, height):
    data = bpy.data.cameras.new("camera")
    data.sensor_fit = "VERTICAL"
    data.angle_y = math.radians(fov)
    data.clip_start = 0.01
    data.clip_end = 1000
    obj = bpy.data.objects.new("camera", data)
    obj.location = P(frm)
    obj.rotation_euler = (P(to) - P(frm)).to_track_quat("-Z", "Y").to_euler()
    scene.collection.objects.link(obj)
    scene.camera = obj
    scene.render.resolution_x, scene.render.resolution_y = width, height


if which == "fog":
    camera((0, 1.5, -6), (0, 0.8, 0), 40, 320, 240)
    world((0.1, 0.12, 0.15))
    sun((-0.4, -0.7, 0.6), 2.5, 0.53)
    quad("floor", (-5, 0, -5), (0, 0, 10), (10, 0, 0), diffuse("floor", (0.6, 0.6, 0.6)))
    bpy.ops.mesh.primitive_uv_sphere_add(segments=256, ring_count=128, radius=0.8, location=P((0, 0.8, 0)))
    ball = bpy.context.active_object
    bpy.ops.object.shade_smooth()
    ball.data.materials.append(diffuse("ball", (0.8, 0.3, 0.2)))
    m, nodes, links = node_material("fog")
    out_node = nodes.new("ShaderNodeOutputMaterial")
    scatter = nodes.new("ShaderNodeVolumeScatter")
    scatter.inputs["Color"].default_value = (1, 1, 1, 1)
    scatter.inputs["Density"].default_value = 0.3
    scatter.inputs["Anisotropy"].default_value = 0.5
    absorb = nodes.new("ShaderNodeVolumeAbsorption")
    absorb.inputs["Color"].default_value = (0, 0, 0, 1)  # sigma_a = density (1 - colour)
    absorb.inputs["Density"].default_value = 0.05
    add = nodes.new("ShaderNodeAddShader")
    links.new(scatter.outputs["Volume"], add.inputs[0])
    links.new(absorb.outputs["Volume"], add.inputs[1])
    links.new(add.outputs["Shader"], out_node.inputs["Volume"])
    box("fog", (-2.5, 0.001, -2.5), (2.5, 2.5, 2.5), m)
elif which in ("cloud", "cloud-absorb"):
    # cloud-absorb (a diagnostic, docs/benchmarks.md): the cloud alone, albedo 0, in a world of
    # radiance 1, no floor and no sun: each pixel is the cloud's transmittance along it.
    alone = which != "cloud"
    camera((0, 1.2, -9), (0, 1.3, 0), 45, 320, 180)
    world((1, 1, 1) if alone else (0.3, 0.4, 0.6))
    if not alone:
        sun((-0.5, -0.6, 0.6), 3, 0.53)  # colour below
        bpy.data.lights["sun"].color = (1, 2.8 / 3, 2.5 / 3)
        quad("floor", (-8, 0, -8), (0, 0, 16), (16, 0, 0), diffuse("floor", (0.5, 0.5, 0.5)))
    vdb = os.path.join(here, "..", "scenes", "volumes", "cloud.vdb")
    volume = bpy.data.volumes.new("cloud")
    volume.filepath = vdb
    # Blender drops densities below 0.001 by default ("clipping") and keeps grids in half
    # precision: glint does neither, so neither does the comparison.
    volume.render.clipping = 0
    volume.render.precision = "FULL"
    obj = bpy.data.objects.new("cloud", volume)
    scene.collection.objects.link(obj)
    # glint: world = translate(-3, -0.75, -3) scale(3) (VDB world); Blender adds the axis swap.
    swap = Matrix(((-1, 0, 0, 0), (0, 0, 1, 0), (0, 1, 0, 0), (0, 0, 0, 1)))
    obj.matrix_world = swap @ Matrix.Translation((-3, -0.75, -3)) @ Matrix.Scale(3, 4)
    m, nodes, links = node_material("cloud")
    out_node = nodes.new("ShaderNodeOutputMaterial")
    pv = nodes.new("ShaderNodeVolumePrincipled")
    pv.inputs["Color"].default_value = (0.98, 0.98, 0.98, 1) if which == "cloud" else (0, 0, 0, 1)
    pv.inputs["Density"].default_value = 6
    pv.inputs["Anisotropy"].default_value = 0.7
    pv.inputs["Absorption Color"].default_value = (0, 0, 0, 1)
    links.new(pv.outputs["Volume"], out_node.inputs["Volume"])
    volume.materials.append(m)
else:
    sys.exit(f"unknown scene {which}")

c = cycles_settings(scene, out, spp, threads, seed)
c.max_bounces = c.diffuse_bounces = c.glossy_bounces = c.transmission_bounces = c.volume_bounces = \
    {"fog": 15, "cloud": 1023, "cloud-absorb": 0}[which] if bounces is None else bounces
c.transparent_max_bounces = {"fog": 64, "cloud": 1023, "cloud-absorb": 1023}[which]
c.volume_step_rate = step_rate
c.volume_max_steps = 4096
render_timed()
