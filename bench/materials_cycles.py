# The materials scene of scenes/materials.yaml, built in Blender and rendered with Cycles on the
# CPU, for bench/compare_cycles.sh (SCENE=materials). The same camera, spheres, ground, checker,
# sky map, disk light and path length; the materials as near as Cycles 3.4's nodes come:
#
#   clay     Diffuse BSDF (Lambert)              = glint's diffuse
#   plastic  Principled, specular 0.5 (f0 0.04 = index 1.5), roughness 0.25
#                                                ~ glint's plastic (a diffuse base under a GGX coat)
#   gold     Principled, metallic, base colour = gold's normal-incidence reflectance from the
#            eta and k glint uses, roughness 0.35 ~ glint's conductor (complex Fresnel)
#   glass    Glass BSDF, sharp, index 1.5        = glint's dielectric
#   frosted  Glass BSDF, GGX, roughness 0.3      = glint's rough dielectric (alpha = roughness^2 in both)
#
# The images therefore differ (the plastic and gold most), and bench/compare_cycles.sh measures
# each renderer's error against its own reference for this scene. The three opaque spheres are
# Cycles' analytic point-cloud spheres (Geometry Nodes' Mesh to Points); the two glass spheres
# are smooth-shaded 256 x 128 UV-sphere meshes, because Cycles 3.4 renders rough glass on a point
# sphere as another, blurrier material (add_mesh_sphere). The disk light is a 256-sided polygon
# of the disk's area, emitting on its front face only, as glint's.
#
#   blender -b --factory-startup -P bench/materials_cycles.py -- OUT.exr SPP THREADS [SEED [ONLY]]
#
# ONLY = frosted or frosted-points: the rough glass sphere alone (as a mesh, or as a point
# sphere) over the ground under a uniform sky (0.8, 0.85, 1), no lamp, only the window of pixels
# [600, 760) x [125, 295) around it (bench/rough_glass_twin.sh).
#
# Prints "cycles render seconds: S" (the render alone, without Blender's start-up).
import math
import os
import sys

import bmesh
import bpy

here = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, here)
from cycles_setup import cycles_settings, one_sided_emission, render_timed  # noqa: E402

argv = sys.argv[sys.argv.index("--") + 1:]
out, spp, threads = argv[0], int(argv[1]), int(argv[2])
seed = int(argv[3]) if len(argv) > 3 else 0
only = argv[4] if len(argv) > 4 else None
if only not in (None, "frosted", "frosted-points"):
    sys.exit(f"materials_cycles.py: ONLY={only}: frosted or frosted-points")


# glint's frame is left-handed (+y up, the camera along +z, +x to the right); Blender's is
# right-handed with +z up. Swapping y and z mirrors the world and the frame's handedness
# together, so the image is the same: (x, y, z) -> (x, z, y).
def to_blender(p):
    return (p[0], p[2], p[1])


bpy.ops.wm.read_factory_settings(use_empty=True)
scene = bpy.context.scene


def material(name, make):
    m = bpy.data.materials.new(name)
    m.use_nodes = True
    nodes, links = m.node_tree.nodes, m.node_tree.links
    nodes.clear()
    out_node = nodes.new("ShaderNodeOutputMaterial")
    links.new(make(nodes, links), out_node.inputs["Surface"])
    return m


def diffuse(color):
    def make(nodes, links):
        b = nodes.new("ShaderNodeBsdfDiffuse")
        b.inputs["Color"].default_value = (*color, 1)
        b.inputs["Roughness"].default_value = 0
        return b.outputs["BSDF"]
    return make


def principled(color, metallic, roughness):
    def make(nodes, links):
        b = nodes.new("ShaderNodeBsdfPrincipled")
        b.distribution = "GGX"
        b.inputs["Base Color"].default_value = (*color, 1)
        b.inputs["Metallic"].default_value = metallic
        b.inputs["Specular"].default_value = 0.5
        b.inputs["Roughness"].default_value = roughness
        return b.outputs["BSDF"]
    return make


def glass(roughness):
    def make(nodes, links):
        b = nodes.new("ShaderNodeBsdfGlass")
        b.distribution = "SHARP" if roughness == 0 else "GGX"
        b.inputs["Color"].default_value = (1, 1, 1, 1)
        b.inputs["Roughness"].default_value = roughness
        b.inputs["IOR"].default_value = 1.5
        return b.outputs["BSDF"]
    return make


def checker(nodes, links):
    # glint's checker: `even` where floor(x) + floor(y) + floor(z) is even. Cycles' Checker
    # Texture of scale 1 on object coordinates (the object sits at the origin, unrotated) picks
    # Color1 where floor(x) + floor(y) is odd on the plane z = 0 (svm_checker: 1, Color1, where
    # the parities of x and y differ and z's is even), Color2 where it is even.
    coords = nodes.new("ShaderNodeTexCoord")
    tex = nodes.new("ShaderNodeTexChecker")
    tex.inputs["Scale"].default_value = 1
    tex.inputs["Color1"].default_value = (0.3, 0.3, 0.3, 1)
    tex.inputs["Color2"].default_value = (0.75, 0.75, 0.75, 1)
    links.new(coords.outputs["Object"], tex.inputs["Vector"])
    b = nodes.new("ShaderNodeBsdfDiffuse")
    b.inputs["Roughness"].default_value = 0
    links.new(tex.outputs["Color"], b.inputs["Color"])
    return b.outputs["BSDF"]


def lamp(nodes, links):
    return one_sided_emission(nodes, links, (12, 10, 8))


# Gold's normal-incidence reflectance from glint's RGB eta and k (src/glint/materials/metals.h).
GOLD_ETA, GOLD_K = (0.18299, 0.42108, 1.3734), (3.4242, 2.3459, 1.7704)
GOLD = tuple(((n - 1) ** 2 + k * k) / ((n + 1) ** 2 + k * k) for n, k in zip(GOLD_ETA, GOLD_K))


def add_object(name, data, mat):
    obj = bpy.data.objects.new(name, data)
    if mat is not None:
        obj.data.materials.append(mat)
    scene.collection.objects.link(obj)
    return obj


def add_sphere(name, center, radius, mat):
    # One vertex turned into a point of the radius by Geometry Nodes: Cycles renders a point
    # cloud's points as spheres (an exact ray-sphere test, as glint's).
    mesh = bpy.data.meshes.new(name)
    mesh.from_pydata([to_blender(center)], [], [])
    obj = add_object(name, mesh, None)
    group = bpy.data.node_groups.new(name, "GeometryNodeTree")
    group.inputs.new("NodeSocketGeometry", "Geometry")
    group.outputs.new("NodeSocketGeometry", "Geometry")
    n_in = group.nodes.new("NodeGroupInput")
    n_out = group.nodes.new("NodeGroupOutput")
    to_points = group.nodes.new("GeometryNodeMeshToPoints")
    to_points.inputs["Radius"].default_value = radius
    set_mat = group.nodes.new("GeometryNodeSetMaterial")
    set_mat.inputs["Material"].default_value = mat
    group.links.new(n_in.outputs["Geometry"], to_points.inputs["Mesh"])
    group.links.new(to_points.outputs["Points"], set_mat.inputs["Geometry"])
    group.links.new(set_mat.outputs["Geometry"], n_out.inputs["Geometry"])
    obj.modifiers.new("points", "NODES").node_group = group


def add_mesh_sphere(name, center, radius, mat):
    # A smooth-shaded UV sphere of 256 x 128 segments, for the glass spheres: Cycles 3.4 renders
    # a rough glass point sphere as a different, blurrier and brighter material than pbrt-v4 and
    # glint render (and than its own mesh sphere, which matches both), so a point is not a
    # closed glass body there. Its interpolated normals are the sphere's to within the facets.
    mesh = bpy.data.meshes.new(name)
    bm = bmesh.new()
    bmesh.ops.create_uvsphere(bm, u_segments=256, v_segments=128, radius=radius)
    bm.to_mesh(mesh)
    bm.free()
    for polygon in mesh.polygons:
        polygon.use_smooth = True
    obj = add_object(name, mesh, mat)
    obj.location = to_blender(center)
    return obj


def add_polygon(name, points, mat):
    mesh = bpy.data.meshes.new(name)
    mesh.from_pydata([to_blender(p) for p in points], [], [tuple(range(len(points)))])
    mesh.update()
    return add_object(name, mesh, mat)


def normalize(v):
    n = math.sqrt(sum(x * x for x in v))
    return tuple(x / n for x in v)


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def add_disk(name, center, normal, radius, mat, sides=256):
    # A regular polygon of the disk's area, wound so that its face normal is the disk's normal
    # in Blender's frame (the mirror to Blender's frame reverses windings, so it is set there).
    n = normalize(to_blender(normal))
    c = to_blender(center)
    helper = (1, 0, 0) if abs(n[0]) < 0.9 else (0, 1, 0)
    u = normalize(cross(helper, n))
    v = cross(n, u)
    r = radius * math.sqrt(2 * math.pi / (sides * math.sin(2 * math.pi / sides)))
    verts = []
    for i in range(sides):
        a = 2 * math.pi * i / sides
        verts.append(tuple(c[k] + r * (math.cos(a) * u[k] + math.sin(a) * v[k]) for k in range(3)))
    mesh = bpy.data.meshes.new(name)
    mesh.from_pydata(verts, [], [tuple(range(sides))])  # counter-clockwise about n: faces along n
    mesh.update()
    return add_object(name, mesh, mat)


add_polygon("ground", [(-20, 0, -20), (-20, 0, 20), (20, 0, 20), (20, 0, -20)], material("ground", checker))
if only is None:
    add_sphere("clay", (-3.6, 0.8, 0), 0.8, material("clay", diffuse((0.8, 0.3, 0.2))))
    add_sphere("plastic", (-1.8, 0.8, 0.6), 0.8, material("plastic", principled((0.1, 0.35, 0.8), 0, 0.25)))
    add_sphere("gold", (0, 0.8, 0), 0.8, material("gold", principled(GOLD, 1, 0.35)))
    add_mesh_sphere("glass", (1.8, 0.8, 0.6), 0.8, material("glass", glass(0)))
(add_sphere if only == "frosted-points" else add_mesh_sphere)("frosted", (3.6, 0.8, 0), 0.8, material("frosted", glass(0.3)))
if only is None:
    add_disk("lamp", (3, 5, -3), (-0.4, -1, 0.4), 1, material("lamp", lamp))

# The sky: glint's map has its centre column along +z (Blender +y) and its right half towards +x;
# Cycles' equirectangular lookup, u = 1/2 - atan2(y, x) / 2 pi, has its centre along +x and its
# right half towards -y, so the direction is turned by -90 degrees about z before the lookup
# (the sun then lights the spheres from the front left in both, and their shadows and caustics
# fall behind them to the right).
world = bpy.data.worlds.new("sky")
world.use_nodes = True
wn, wl = world.node_tree.nodes, world.node_tree.links
env = wn.new("ShaderNodeTexEnvironment")
env.image = bpy.data.images.load(os.path.join(here, "..", "scenes", "textures", "sky.exr"))
env.interpolation = "Linear"
coords = wn.new("ShaderNodeTexCoord")
mapping = wn.new("ShaderNodeMapping")
mapping.vector_type = "VECTOR"
mapping.inputs["Rotation"].default_value = (0, 0, math.radians(-90))
wl.new(coords.outputs["Generated"], mapping.inputs["Vector"])
wl.new(mapping.outputs["Vector"], env.inputs["Vector"])
if only is None:
    wl.new(env.outputs["Color"], wn["Background"].inputs["Color"])
else:
    wn["Background"].inputs["Color"].default_value = (0.8, 0.85, 1, 1)
wn["Background"].inputs["Strength"].default_value = 1
scene.world = world

# The camera: from (0, 2.2, -7.5) towards (0, 0.8, 0), vertical field of view 38 degrees.
cam_data = bpy.data.cameras.new("camera")
cam_data.sensor_fit = "VERTICAL"
cam_data.angle_y = math.radians(38)
cam_data.clip_start = 1e-3
cam_data.clip_end = 1e4
cam = bpy.data.objects.new("camera", cam_data)
eye, target = to_blender((0, 2.2, -7.5)), to_blender((0, 0.8, 0))
cam.location = eye
d = tuple(t - e for t, e in zip(target, eye))
# Blender's camera looks along its local -z with +y up: pitch it from looking down (rotation 0)
# up to the view direction, about x; the view has no sideways part.
cam.rotation_euler = (math.atan2(math.hypot(d[0], d[1]), -d[2]), 0, 0)
scene.collection.objects.link(cam)
scene.camera = cam

r = scene.render
r.resolution_x, r.resolution_y = 800, 400
if only is not None:  # Blender's border counts rows from the bottom
    r.use_border = r.use_crop_to_border = True
    r.border_min_x, r.border_max_x = 600 / 800, 760 / 800
    r.border_min_y, r.border_max_y = (400 - 295) / 400, (400 - 125) / 400
c = cycles_settings(scene, out, spp, threads, seed)
# glint's max_depth 12 counts scattering events including the first hit; Cycles counts bounces
# after it.
for k in ("max_bounces", "diffuse_bounces", "glossy_bounces", "transmission_bounces", "transparent_max_bounces"):
    setattr(c, k, 11)
c.caustics_reflective = True
c.caustics_refractive = True
c.blur_glossy = 0
render_timed()
