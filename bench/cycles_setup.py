# What every Cycles twin of the benchmarks shares (bench/cornell_cycles.py, materials_cycles.py,
# volume_cycles.py): Cycles on the CPU with a fixed number of threads, a 32-bit EXR, the Standard
# view, no adaptive sampling, no denoiser, a box filter, no clamping; one-sided emitters as
# glint's area lights are; and the timed render. Each script puts this folder on sys.path.
import time

import bpy


def cycles_settings(scene, out, spp, threads, seed):
    """Sets the shared render settings and returns scene.cycles for the twin's own (bounces)."""
    r = scene.render
    r.engine = "CYCLES"
    r.resolution_percentage = 100
    r.threads_mode = "FIXED"
    r.threads = threads
    r.use_persistent_data = False
    r.image_settings.file_format = "OPEN_EXR"
    r.image_settings.color_depth = "32"
    r.image_settings.exr_codec = "ZIP"
    r.filepath = out
    scene.view_settings.view_transform = "Standard"
    c = scene.cycles
    c.device = "CPU"
    c.samples = spp
    c.use_adaptive_sampling = False
    c.use_denoising = False
    c.seed = seed
    c.pixel_filter_type = "BOX"
    c.sample_clamp_direct = 0
    c.sample_clamp_indirect = 0
    return c


def one_sided_emission(nodes, links, color):
    """Emission of radiance `color` on the front face, black behind; returns the shader output."""
    emission = nodes.new("ShaderNodeEmission")
    emission.inputs["Color"].default_value = (*color, 1)
    emission.inputs["Strength"].default_value = 1
    black = nodes.new("ShaderNodeBsdfDiffuse")
    black.inputs["Color"].default_value = (0, 0, 0, 1)
    geometry = nodes.new("ShaderNodeNewGeometry")
    mix = nodes.new("ShaderNodeMixShader")
    links.new(geometry.outputs["Backfacing"], mix.inputs["Fac"])
    links.new(emission.outputs["Emission"], mix.inputs[1])
    links.new(black.outputs["BSDF"], mix.inputs[2])
    return mix.outputs["Shader"]


def render_timed():
    """Renders and writes the still; prints the render's own seconds (without Blender's start-up)."""
    start = time.time()
    bpy.ops.render.render(write_still=True)
    print(f"cycles render seconds: {time.time() - start:.3f}")
