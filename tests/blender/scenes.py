"""The scenes the Blender tests and benchmarks build by script (tests/blender/test_engine.py,
bench/blender_equal_time.py): a Cornell-like box with Principled materials and an area light, its
volume variants, and a render through either engine at fixed settings."""
import math
import os
import pathlib

import bpy
import numpy as np

ROOT = pathlib.Path(__file__).resolve().parents[2]
SIZE = int(os.environ.get("GLINT_BLENDER_SIZE", "128"))


def principled(name, **inputs):
    m = bpy.data.materials.new(name)
    m.use_nodes = True
    p = m.node_tree.nodes["Principled BSDF"]
    for k, v in inputs.items():
        p.inputs[k].default_value = v
    return m


def lambert(name, color):
    """A Diffuse BSDF of roughness 0: Lambertian in both renderers (Cycles' Principled diffuse is
    Burley's, which glint does not have)."""
    m = bpy.data.materials.new(name)
    m.use_nodes = True
    nodes = m.node_tree.nodes
    nodes.remove(nodes["Principled BSDF"])
    d = nodes.new("ShaderNodeBsdfDiffuse")
    d.inputs["Color"].default_value = color
    d.inputs["Roughness"].default_value = 0
    m.node_tree.links.new(d.outputs["BSDF"], nodes["Material Output"].inputs["Surface"])
    return m


def plane(name, location, rotation, size, material):
    bpy.ops.mesh.primitive_plane_add(size=size, location=location, rotation=rotation)
    o = bpy.context.object
    o.name = name
    o.data.materials.append(material)
    return o


def build_scene():
    scene = bpy.context.scene
    for collection in (bpy.data.objects, bpy.data.meshes, bpy.data.materials, bpy.data.lights, bpy.data.cameras,
                       bpy.data.worlds):
        for item in list(collection):
            collection.remove(item)
    white = lambert("white", (0.73, 0.71, 0.68, 1))
    red = lambert("red", (0.63, 0.065, 0.05, 1))
    green = lambert("green", (0.14, 0.45, 0.09, 1))
    plane("floor", (0, 0, 0), (0, 0, 0), 2, white)
    plane("ceiling", (0, 0, 2), (math.pi, 0, 0), 2, white)
    plane("back", (0, 1, 1), (math.pi / 2, 0, 0), 2, white)
    plane("left", (-1, 0, 1), (0, math.pi / 2, 0), 2, red)
    plane("right", (1, 0, 1), (0, -math.pi / 2, 0), 2, green)
    bpy.ops.mesh.primitive_uv_sphere_add(radius=0.35, location=(-0.35, 0.2, 0.35), segments=48, ring_count=24)
    sphere = bpy.context.object
    bpy.ops.object.shade_smooth()
    sphere.data.materials.append(principled("metal", **{"Base Color": (0.9, 0.7, 0.4, 1), "Metallic": 1.0,
                                                        "Roughness": 0.3}))
    bpy.ops.mesh.primitive_cube_add(size=0.5, location=(0.4, -0.1, 0.25), rotation=(0, 0, 0.4))
    cube = bpy.context.object
    cube.data.materials.append(principled("plastic", **{"Base Color": (0.2, 0.3, 0.8, 1), "Roughness": 0.4,
                                                        "Clearcoat": 0.5, "Clearcoat Roughness": 0.25}))
    bpy.ops.object.light_add(type="AREA", location=(0, 0, 1.98))
    light = bpy.context.object
    light.data.size = 0.5
    light.data.energy = 30
    light.data.color = (1.0, 0.85, 0.6)
    # The light just out of view: Cycles hides light objects from camera rays, glint's area lights
    # are emitting shapes the camera sees (docs/blender.md).
    bpy.ops.object.camera_add(location=(0, -3.2, 1.0), rotation=(math.pi / 2 - 0.08, 0, 0))
    scene.camera = bpy.context.object
    scene.camera.data.lens = 50
    world = bpy.data.worlds.new("world")
    world.use_nodes = True
    world.node_tree.nodes["Background"].inputs["Color"].default_value = (0.05, 0.05, 0.06, 1)
    scene.world = world
    scene.render.resolution_x = scene.render.resolution_y = SIZE
    scene.render.resolution_percentage = 100
    scene.render.image_settings.file_format = "OPEN_EXR"
    scene.render.image_settings.color_depth = "32"
    scene.render.threads_mode = "FIXED"
    scene.render.threads = 2
    return scene


def render(scene, engine, path, spp, seed=1):
    scene.render.engine = engine
    if engine == "CYCLES":
        c = scene.cycles
        c.samples = spp
        c.use_adaptive_sampling = False
        c.use_denoising = False
        c.max_bounces = c.diffuse_bounces = c.glossy_bounces = c.transmission_bounces = c.volume_bounces = 12
        c.sample_clamp_direct = c.sample_clamp_indirect = 0
        c.filter_glossy = 0
        c.light_sampling_threshold = 0
        c.pixel_filter_type = "BOX"
        c.filter_width = 1.0
        c.seed = seed
    else:
        scene.glint.samples = spp
        scene.glint.max_depth = 12
        scene.glint.seed = seed
    scene.render.filepath = str(path)
    bpy.ops.render.render(write_still=True)
    image = bpy.data.images.load(str(path))
    pixels = np.array(image.pixels[:], dtype=np.float32).reshape(image.size[1], image.size[0], 4)[..., :3]
    bpy.data.images.remove(image)
    return pixels


def volume_material(name, **inputs):
    """A material with a Principled Volume on the volume output and no surface shader."""
    m = bpy.data.materials.new(name)
    m.use_nodes = True
    nodes = m.node_tree.nodes
    nodes.remove(nodes["Principled BSDF"])
    v = nodes.new("ShaderNodeVolumePrincipled")
    for k, value in inputs.items():
        v.inputs[k].default_value = value
    m.node_tree.links.new(v.outputs["Volume"], nodes["Material Output"].inputs["Volume"])
    return m


def volume_scene(kind):
    """The box without its sphere and cube, and in their place a cube of Principled Volume (a
    mesh's volume output) or glint's procedural cloud as an OpenVDB Volume object."""
    scene = build_scene()
    for o in [o for o in bpy.data.objects if o.name.startswith(("Sphere", "Cube"))]:
        bpy.data.objects.remove(o)
    if kind == "mesh":
        bpy.ops.mesh.primitive_cube_add(size=0.9, location=(0, 0.1, 0.6), rotation=(0.3, 0, 0.5))
        bpy.context.object.data.materials.append(volume_material(
            "smoke", **{"Color": (0.8, 0.5, 0.3, 1), "Density": 3.0, "Absorption Color": (0.2, 0.3, 0.6, 1),
                        "Anisotropy": 0.3}))
    else:
        volume = bpy.data.volumes.new("cloud")
        volume.filepath = str(ROOT / "scenes" / "volumes" / "cloud.vdb")
        obj = bpy.data.objects.new("cloud", volume)
        bpy.context.collection.objects.link(obj)
        obj.location, obj.scale = (-0.6, -0.6, 0.2), (0.6, 0.6, 0.6)
        obj.data.materials.append(volume_material("cloud", **{"Color": (0.9, 0.85, 0.8, 1), "Density": 4.0}))
        scene.cycles.volume_step_rate = 0.25  # Cycles ray-marches grids: small steps, little bias
        scene.cycles.volume_max_steps = 4096
    return scene
