"""The glint render engine inside Blender, headless (docs/blender.md):

    GLINT_PYTHON=build/python/glint blender -b --factory-startup --python tests/blender/test_engine.py

A Cornell-like box built by script (coloured walls, a smooth sphere and a cube with Principled
materials, an area light, a dim world) rendered by glint and by Cycles at high spp: the channel
means must agree within 3 % and 95 % of the 16 x 16 blocks within 10 %. Then: each mapped input
changes glint's image, Esc (test_break) stops a render early, and an unmapped node gives one
report line. Exit status 0 when every check holds; the failures are printed.
"""
import math
import os
import pathlib
import sys
import tempfile
import time
import traceback

import bpy
import numpy as np

ROOT = pathlib.Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "blender"))
import glint as addon  # noqa: E402  (the add-on: blender/glint)

sys.path.insert(0, str(ROOT / "tests" / "blender"))
from scenes import SIZE, build_scene, lambert, render, volume_scene  # noqa: E402

addon.register()
failures = []
SPP = int(os.environ.get("GLINT_BLENDER_SPP", "1024"))


def check(ok, what):
    print(("ok   " if ok else "FAIL ") + what, flush=True)
    if not ok:
        failures.append(what)












def compare_with_cycles(scene, tmp, what="the box", spp=SPP):
    g = render(scene, "GLINT", tmp / "glint.exr", spp)
    c = render(scene, "CYCLES", tmp / "cycles.exr", spp)
    if os.environ.get("GLINT_BLENDER_KEEP"):  # docs/blender.md's picture
        keep = pathlib.Path(os.environ["GLINT_BLENDER_KEEP"])
        keep.mkdir(parents=True, exist_ok=True)
        for name in ("glint.exr", "cycles.exr"):
            (keep / f"{what.replace(' ', '-')}-{name}").write_bytes((tmp / name).read_bytes())
    gm, cm = g.mean(axis=(0, 1)), c.mean(axis=(0, 1))
    print(f"channel means: glint {gm}, Cycles {cm}, ratio {gm / cm}")
    check(bool(np.all(np.abs(gm / cm - 1) < 0.03)), f"{what}: channel means within 3 % of Cycles'")
    b = SIZE // 16
    gb = g[:b * 16, :b * 16].reshape(16, b, 16, b, 3).mean(axis=(1, 3))
    cb = c[:b * 16, :b * 16].reshape(16, b, 16, b, 3).mean(axis=(1, 3))
    # Blocks compared by their luminance-like sum (a dark block's single channel is mostly noise).
    ratio = gb.sum(axis=2) / np.maximum(cb.sum(axis=2), 1e-6)
    within = float(np.mean(np.abs(ratio - 1) < 0.10))
    print(f"16 x 16 blocks within 10 %: {within:.3f}")
    check(within >= 0.95, f"{what}: 95 % of 16 x 16 blocks within 10 % of Cycles'")
    return g


def glint_image(scene, tmp, name, spp=16):
    return render(scene, "GLINT", tmp / f"{name}.exr", spp)


def add_normal_map(tmp):
    """A tilted constant normal map (an image file) on the cube, through a Normal Map node."""
    image = bpy.data.images.new("tilt", 4, 4)
    image.pixels = [0.8, 0.5, 0.7, 1.0] * 16
    image.filepath_raw = str(tmp / "tilt.png")
    image.file_format = "PNG"
    image.save()
    image.colorspace_settings.name = "Non-Color"
    tree = bpy.data.materials["plastic"].node_tree
    tex = tree.nodes.new("ShaderNodeTexImage")
    tex.image = image
    nmap = tree.nodes.new("ShaderNodeNormalMap")
    tree.links.new(tex.outputs["Color"], nmap.inputs["Color"])
    tree.links.new(nmap.outputs["Normal"], tree.nodes["Principled BSDF"].inputs["Normal"])


def each_mapped_input_changes_the_image(scene, tmp):
    base = glint_image(scene, tmp, "base")
    changes = {
        "base colour": lambda: bpy.data.materials["plastic"].node_tree.nodes["Principled BSDF"].inputs[
            "Base Color"].__setattr__("default_value", (0.9, 0.1, 0.1, 1)),
        "metallic": lambda: bpy.data.materials["metal"].node_tree.nodes["Principled BSDF"].inputs[
            "Metallic"].__setattr__("default_value", 0.0),
        "roughness": lambda: bpy.data.materials["metal"].node_tree.nodes["Principled BSDF"].inputs[
            "Roughness"].__setattr__("default_value", 0.9),
        "emission": lambda: bpy.data.materials["plastic"].node_tree.nodes["Principled BSDF"].inputs[
            "Emission Strength"].__setattr__("default_value", 2.0) or bpy.data.materials["plastic"].node_tree.nodes[
            "Principled BSDF"].inputs["Emission"].__setattr__("default_value", (1, 1, 1, 1)),
        "transmission": lambda: bpy.data.materials["plastic"].node_tree.nodes["Principled BSDF"].inputs[
            "Transmission"].__setattr__("default_value", 1.0),
        "light power": lambda: setattr(bpy.data.lights[0], "energy", 60),
        "world colour": lambda: scene.world.node_tree.nodes["Background"].inputs["Color"].__setattr__(
            "default_value", (0.5, 0.5, 0.5, 1)),
        "camera lens": lambda: setattr(scene.camera.data, "lens", 35),
        "normal map": lambda: add_normal_map(tmp),
        "depth of field": lambda: (setattr(scene.camera.data.dof, "use_dof", True),
                                   setattr(scene.camera.data.dof, "aperture_fstop", 0.5),
                                   setattr(scene.camera.data.dof, "focus_distance", 1.0)),
    }
    for name, change in changes.items():
        change()
        image = glint_image(scene, tmp, name.replace(" ", "-"))
        check(float(np.abs(image - base).mean()) > 1e-3, f"{name} changes the image")
        scene = build_scene()  # the next change starts from the base scene
    return scene


def cancel_stops_the_render(scene):
    glint = addon.renderer()
    ex = addon.export.Export(bpy.context.evaluated_depsgraph_get(), 64, 64)
    loaded = glint.load_dict(ex.scene_dict(4096, 8))

    class Pass:
        rect = None

    class Result:
        layers = [type("L", (), {"passes": {"Combined": Pass()}})()]

    class Engine:
        breaks = 0
        updates = []

        def test_break(self):
            self.breaks += 1
            return True

        def update_result(self, result):
            pass

        def update_progress(self, p):
            self.updates.append(p)

        def update_stats(self, a, b):
            pass

    settings = type("S", (), dict(samples=4096, seed=0, denoise=False, threads=0, time_limit=0))()
    engine, result = Engine(), Result()
    addon.GlintRenderEngine.render_passes(engine, glint, loaded, settings, result, 64, 64)
    rect = result.layers[0].passes["Combined"].rect
    check(engine.breaks == 1 and len(engine.updates) == 1 and engine.updates[0] < 1,
          "Esc (test_break) stops the render after the pass in hand")
    check(rect is not None and len(rect) == 64 * 64, "the pass was written into the render result")


def a_viewport_render_stops_at_once(scene):
    """The viewport preview's render (addon.Preview) stops at its next tile, not at the end of
    the pass in flight: a 1024 x 1024 render whose passes have grown to seconds each is stopped
    within a second."""
    glint = addon.renderer()
    ex = addon.export.Export(bpy.context.evaluated_depsgraph_get(), 1024, 1024)
    loaded = glint.load_dict(ex.scene_dict(1 << 16, 8))

    class Engine:
        def tag_redraw(self):
            pass

    preview = addon.Preview(Engine(), glint, loaded, None, dict(spp=1 << 16, seed=0, threads=2))
    started = time.monotonic()
    while (preview.image is None or preview.image.spp < 4) and time.monotonic() - started < 120:
        time.sleep(0.05)
    before = preview.image.spp if preview.image is not None else 0
    start = time.monotonic()
    preview.stop()
    took = time.monotonic() - start
    print(f"viewport render: stopped after a {before}-spp pass in {took:.2f} s")
    check(before >= 4 and took < 1.0, "a viewport render stops within a second, mid-pass")


def unmapped_node_is_reported_once(scene):
    mat = bpy.data.materials["plastic"]
    nodes, links = mat.node_tree.nodes, mat.node_tree.links
    noise = nodes.new("ShaderNodeTexNoise")
    links.new(noise.outputs["Fac"], nodes["Principled BSDF"].inputs["Roughness"])
    nodes["Principled BSDF"].inputs["Subsurface"].default_value = 0.5
    ex = addon.export.Export(bpy.context.evaluated_depsgraph_get(), 32, 32)
    ex.scene_dict(4, 4)
    ex.scene_dict(4, 4)  # a second pass over the scene adds nothing
    print("reported:", ex.unmapped)
    check(sum("Roughness" in line and "ShaderNodeTexNoise" in line for line in ex.unmapped) == 1,
          "a node into Roughness gives one report line")
    check(sum("Subsurface" in line for line in ex.unmapped) == 1, "an unmapped Principled input gives one line")


def light_units_match_closed_forms(tmp):
    """A 100 W light 2 m above a white diffuse plane, seen straight down by an orthographic camera,
    direct light only: the pixel is rho/pi E with E = L A / d^2 (area light, L = P / (4 A), small
    enough for the point-source limit) or I / d^2 (point light, I = P / (4 pi)). Both renderers
    against the closed form."""
    scene = build_scene()
    for o in list(bpy.data.objects):
        bpy.data.objects.remove(o)
    bpy.ops.mesh.primitive_plane_add(size=20)
    bpy.context.object.data.materials.append(lambert("one", (1, 1, 1, 1)))
    bpy.ops.object.camera_add(location=(0, 0, 1), rotation=(0, 0, 0))
    scene.camera = bpy.context.object
    scene.camera.data.type = "ORTHO"
    scene.camera.data.ortho_scale = 0.02
    scene.world.node_tree.nodes["Background"].inputs["Color"].default_value = (0, 0, 0, 1)
    scene.render.resolution_x = scene.render.resolution_y = 8
    d2 = 4.0  # the light's height, squared
    for kind in ("AREA", "POINT"):
        for o in [o for o in bpy.data.objects if o.type == "LIGHT"]:
            bpy.data.objects.remove(o)
        bpy.ops.object.light_add(type=kind, location=(0, 0, 2))
        light = bpy.context.object.data
        light.energy = 100
        if kind == "AREA":
            light.size = 0.05
            expected_kind = (100 / 4) / d2 / math.pi  # L A / d^2 / pi with L A = P / 4
        else:
            light.shadow_soft_size = 0
            expected_kind = 100 / (4 * math.pi) / d2 / math.pi  # I / d^2 / pi with I = P / (4 pi)
        scene.cycles.max_bounces = 0
        scene.glint.max_depth = 1
        for engine in ("CYCLES", "GLINT"):
            scene.render.engine = engine
            if engine == "CYCLES":
                scene.cycles.samples, scene.cycles.use_denoising = 64, False
            else:
                scene.glint.samples = 64
            scene.render.filepath = str(tmp / f"units-{kind}-{engine}.exr")
            bpy.ops.render.render(write_still=True)
            image = bpy.data.images.load(scene.render.filepath)
            value = float(np.array(image.pixels[:]).reshape(-1, 4)[:, 0].mean())
            bpy.data.images.remove(image)
            print(f"{kind} light, {engine}: {value:.5f}, closed form {expected_kind:.5f}")
            check(abs(value / expected_kind - 1) < 0.01, f"{kind.lower()} light units: {engine} within 1 % of the closed form")






def image_base_colour_matches_the_value(tmp):
    """The cube's base colour as a value and as an Image Texture holding that colour (an 8-bit
    sRGB image, read from Blender's memory): the same picture. glint remaps a Principled base
    colour for its coat (docs/blender.md); before images were read from memory only values were."""
    scene = build_scene()
    code = (0.3, 0.45, 0.85)
    linear = [c / 12.92 if c <= 0.04045 else ((c + 0.055) / 1.055) ** 2.4 for c in code]
    node = bpy.data.materials["plastic"].node_tree.nodes["Principled BSDF"]
    node.inputs["Base Color"].default_value = (*linear, 1)
    value = glint_image(scene, tmp, "base-value")
    image = bpy.data.images.new("flat", 4, 4)  # 8-bit, sRGB
    image.pixels = [*code, 1.0] * 16
    tex = bpy.data.materials["plastic"].node_tree.nodes.new("ShaderNodeTexImage")
    tex.image = image
    bpy.data.materials["plastic"].node_tree.links.new(tex.outputs["Color"], node.inputs["Base Color"])
    node.inputs["Base Color"].default_value = (1, 1, 1, 1)  # what an unmapped image would fall back to
    textured = glint_image(scene, tmp, "base-image")
    diff = float(np.abs(textured.mean(axis=(0, 1)) / value.mean(axis=(0, 1)) - 1).max())
    print(f"image-textured / valued base colour: channel means differ by {diff:.2e}")
    check(diff < 2e-3, "an image-textured base colour renders as the same colour given as a value")


def volumes_match_cycles(tmp):
    for kind in ("mesh", "vdb"):
        scene = volume_scene(kind)
        print(f"volume: {kind}")
        compare_with_cycles(scene, tmp, f"{kind} volume", min(SPP, 512))  # 512 spp: the bars hold, at half the time
        base = glint_image(scene, tmp, f"{kind}-volume-base")
        node = bpy.data.materials["smoke" if kind == "mesh" else "cloud"].node_tree.nodes["Principled Volume"]
        changes = {"density": ("Density", 1.0), "colour": ("Color", (0.2, 0.9, 0.2, 1))}
        if kind == "mesh":
            changes["emission"] = ("Emission Strength", 2.0)
        for what, (name, value) in changes.items():
            old = node.inputs[name].default_value
            old = tuple(old) if hasattr(old, "__len__") else old
            node.inputs[name].default_value = value
            image = glint_image(scene, tmp, f"{kind}-volume-{what}")
            check(float(np.abs(image - base).mean()) > 1e-3, f"{kind} volume: {what} changes the image")
            node.inputs[name].default_value = old
        ex = addon.export.Export(bpy.context.evaluated_depsgraph_get(), 16, 16)
        ex.scene_dict(4, 4)
        check(not any("volume" in line.lower() for line in ex.unmapped), f"{kind} volume: nothing reported unmapped")


def main():
    with tempfile.TemporaryDirectory() as folder:
        tmp = pathlib.Path(folder)
        only = os.environ.get("GLINT_BLENDER_ONLY")  # a quicker run of one part
        if only == "volumes":
            volumes_match_cycles(tmp)
            return
        if only == "images":
            image_base_colour_matches_the_value(tmp)
            return
        if only == "viewport":
            a_viewport_render_stops_at_once(build_scene())
            return
        scene = build_scene()
        compare_with_cycles(scene, tmp)
        scene = each_mapped_input_changes_the_image(scene, tmp)
        cancel_stops_the_render(scene)
        a_viewport_render_stops_at_once(scene)
        unmapped_node_is_reported_once(scene)
        light_units_match_closed_forms(tmp)
        image_base_colour_matches_the_value(tmp)
        volumes_match_cycles(tmp)


try:
    main()
except Exception:
    traceback.print_exc()
    failures.append("exception")
print(f"{len(failures)} failure(s)" + (": " + "; ".join(failures) if failures else ""))
sys.stdout.flush()
os._exit(1 if failures else 0)
