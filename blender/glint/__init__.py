"""glint as a Blender render engine (docs/blender.md).

Renders the evaluated depsgraph in memory through glint's Python module: the scene becomes a
dict with numpy meshes (export.py), glint renders it in progressive passes, and each pass is
written into Blender's render result, with progress and Esc to cancel. What does not map is
reported once per render in the Info area. In the viewport's Rendered shading the same render
runs live through the viewport's own view (view_update, view_draw).

The compiled module is found, in order, where the add-on preferences point, on sys.path under
the name glint_renderer, or in the checkout's build/python/glint beside this add-on when it is
installed as a link to blender/glint (the documented way).
"""
bl_info = {
    "name": "glint",
    "author": "the glint authors",
    "version": (0, 1, 0),
    "blender": (3, 4, 0),
    "location": "Render Properties > Render Engine > glint",
    "description": "glint, a physically based path tracer, as a render engine",
    "category": "Render",
}

import importlib.util
import os
import pathlib
import sys
import threading

import bpy
import numpy as np

from . import export

_renderer = None


def renderer(path=None):
    """glint's Python package, loaded as `glint_renderer` (this add-on is the module `glint`)."""
    global _renderer
    if _renderer is not None:
        return _renderer
    candidates = []
    if path:
        candidates.append(pathlib.Path(path))
    if os.environ.get("GLINT_PYTHON"):
        candidates.append(pathlib.Path(os.environ["GLINT_PYTHON"]))
    here = pathlib.Path(__file__).resolve().parent  # blender/glint in the checkout, through the link
    candidates.append(here.parents[1] / "build" / "python" / "glint")
    for folder in candidates:
        init = folder / "__init__.py"
        if init.exists():
            spec = importlib.util.spec_from_file_location("glint_renderer", init,
                                                          submodule_search_locations=[str(folder)])
            module = importlib.util.module_from_spec(spec)
            sys.modules["glint_renderer"] = module
            spec.loader.exec_module(module)
            _renderer = module
            return module
    raise ImportError("glint's Python module was not found: build it (make build) and install the add-on as a "
                      "link to the checkout's blender/glint, or set its folder (build/python/glint) in the "
                      "add-on's preferences or $GLINT_PYTHON")


class GlintPreferences(bpy.types.AddonPreferences):
    bl_idname = __name__
    module_path: bpy.props.StringProperty(
        name="Module folder", subtype="DIR_PATH",
        description="The folder of glint's Python package (build/python/glint in a checkout)")

    def draw(self, context):
        self.layout.prop(self, "module_path")


class GlintSettings(bpy.types.PropertyGroup):
    samples: bpy.props.IntProperty(name="Samples", default=64, min=1, max=1 << 20,
                                   description="Samples per pixel")
    max_depth: bpy.props.IntProperty(name="Max Bounces", default=12, min=1, max=10000,
                                     description="Scattering events a path may have")
    seed: bpy.props.IntProperty(name="Seed", default=0, min=0, description="The sample pattern's seed")
    denoise: bpy.props.BoolProperty(name="Denoise", default=False,
                                    description="glint's feature-guided denoiser on the final image")
    threads: bpy.props.IntProperty(name="Threads", default=0, min=0, max=1024,
                                   description="Worker threads; 0: every core")
    time_limit: bpy.props.FloatProperty(name="Time Limit", default=0, min=0, unit="TIME_ABSOLUTE",
                                        description="Stop after the last pass that fits (seconds; 0: none)")
    viewport_samples: bpy.props.IntProperty(name="Viewport Samples", default=64, min=1, max=1 << 16,
                                            description="Samples per pixel of the viewport's rendered preview")


class GlintRenderEngine(bpy.types.RenderEngine):
    bl_idname = "GLINT"
    bl_label = "glint"
    bl_use_preview = False
    bl_use_shading_nodes_custom = False

    def render(self, depsgraph):
        scene = depsgraph.scene
        settings = scene.glint
        scale = scene.render.resolution_percentage / 100
        width = max(1, int(scene.render.resolution_x * scale))
        height = max(1, int(scene.render.resolution_y * scale))
        if scene.render.pixel_aspect_x != scene.render.pixel_aspect_y:
            self.report({"WARNING"}, "glint: non-square pixels are not mapped")
        try:
            glint = renderer(_module_path())
            self.update_stats("", "glint: exporting the scene")
            ex = export.Export(depsgraph, width, height)
            data = ex.scene_dict(settings.samples, settings.max_depth)
            for line in ex.unmapped:  # once per render
                self.report({"WARNING"}, f"glint: {line}")
            loaded = glint.load_dict(data, name=f"blender:{scene.name}")
        except Exception as e:  # a scene glint refuses: its located text, in the Info area
            self.report({"ERROR"}, f"glint: {e}")
            return
        result = self.begin_result(0, 0, width, height)
        try:
            self.render_passes(glint, loaded, settings, result, width, height)
        except Exception as e:
            self.report({"ERROR"}, f"glint: {e}")
        finally:
            self.end_result(result)

    def render_passes(self, glint, loaded, settings, result, width, height):
        combined = result.layers[0].passes["Combined"]
        rgba = np.ones((height, width, 4), np.float32)
        options = dict(spp=settings.samples, seed=settings.seed, denoise=settings.denoise,
                       threads=settings.threads or None, time=settings.time_limit or None)
        for image in glint.render_passes(loaded, **options):
            rgba[..., :3] = image[::-1]  # Blender's rows run bottom to top
            combined.rect = rgba.reshape(-1, 4)
            self.update_result(result)
            self.update_progress(min(1.0, image.spp / settings.samples))
            self.update_stats("", f"glint: {image.spp} of {settings.samples} samples")
            if self.test_break():  # Esc: leaving the loop stops the render at its next tile
                break

    # --- the viewport's rendered preview ---------------------------------------------------------
    # view_update (the scene changed) and view_draw (any redraw; the view may have moved) both
    # export the depsgraph through the viewport's own camera and restart a progressive render in a
    # thread when what it would show changed. Each finished pass is kept and the viewport redrawn;
    # view_draw shows the latest pass through Blender's display transform.

    def view_update(self, context, depsgraph):
        self._preview_restart(context, depsgraph, force=True)

    def view_draw(self, context, depsgraph):
        self._preview_restart(context, depsgraph, force=False)
        preview = getattr(self, "_preview", None)
        if preview is None or preview.image is None:
            return
        import gpu
        from gpu_extras.presets import draw_texture_2d
        if preview.texture is None or preview.texture_spp != preview.image.spp:
            preview.texture = _texture(preview.image)
            preview.texture_spp = preview.image.spp
        gpu.state.blend_set("ALPHA_PREMULT")
        self.bind_display_space_shader(depsgraph.scene)
        draw_texture_2d(preview.texture, (0, 0), context.region.width, context.region.height)
        self.unbind_display_space_shader()
        gpu.state.blend_set("NONE")

    def _preview_restart(self, context, depsgraph, force):
        region, rv3d = context.region, context.region_data
        clip_end = getattr(context.space_data, "clip_end", 1000.0)
        key = (region.width, region.height, tuple(tuple(r) for r in rv3d.view_matrix),
               tuple(tuple(r) for r in rv3d.window_matrix))
        preview = getattr(self, "_preview", None)
        if preview is not None and preview.key == key and not force:
            return
        if preview is not None:
            preview.stop()
        settings = depsgraph.scene.glint
        try:
            glint = renderer(_module_path())
            ex = export.Export(depsgraph, region.width, region.height, view=export.viewport_view(rv3d, clip_end))
            loaded = glint.load_dict(ex.scene_dict(settings.viewport_samples, settings.max_depth), name="blender:viewport")
        except Exception as e:
            self.report({"ERROR"}, f"glint: {e}")
            self._preview = None
            return
        self._preview = Preview(self, glint, loaded, key, dict(spp=settings.viewport_samples, seed=settings.seed,
                                                               threads=settings.threads or None))

    def __del__(self):
        preview = getattr(self, "_preview", None)
        if preview is not None:
            preview.stop()


class Preview:
    """A progressive render in a thread: `image` is its latest pass; stop() ends it at its next
    tile (render_passes' stop event) and waits for the thread."""

    def __init__(self, engine, glint, loaded, key, options):
        self.key, self.image, self.texture, self.texture_spp = key, None, None, -1
        self._stopping = threading.Event()
        self._thread = threading.Thread(target=self._run, args=(engine, glint, loaded, options), daemon=True)
        self._thread.start()

    def _run(self, engine, glint, loaded, options):
        try:
            for image in glint.render_passes(loaded, stop=self._stopping, **options):
                self.image = image
                engine.tag_redraw()
        except Exception as e:  # shown in the terminal; the viewport keeps its last pass
            print(f"glint viewport: {e}", file=sys.stderr)

    def stop(self):
        self._stopping.set()
        self._thread.join()


def _texture(image):
    """A GPU texture of a glint image (rows from the top) for draw_texture_2d (rows from the bottom)."""
    import gpu
    h, w = image.shape[:2]
    rgba = np.ones((h, w, 4), np.float32)
    rgba[..., :3] = image[::-1]
    return gpu.types.GPUTexture((w, h), format="RGBA16F", data=gpu.types.Buffer("FLOAT", w * h * 4, rgba.ravel()))


def _module_path():
    try:
        prefs = bpy.context.preferences.addons[__name__].preferences
        return (prefs.module_path if prefs else "") or None
    except KeyError:
        return None


class GLINT_PT_sampling(bpy.types.Panel):
    bl_label = "glint"
    bl_space_type = "PROPERTIES"
    bl_region_type = "WINDOW"
    bl_context = "render"
    COMPAT_ENGINES = {"GLINT"}

    @classmethod
    def poll(cls, context):
        return context.engine in cls.COMPAT_ENGINES

    def draw(self, context):
        s = context.scene.glint
        col = self.layout.column()
        for name in ("samples", "viewport_samples", "max_depth", "seed", "denoise", "threads", "time_limit"):
            col.prop(s, name)


def _panels():
    # Blender's own panels that apply to any engine: output, dimensions, colour management.
    from bl_ui import properties_output, properties_render
    out = []
    for module in (properties_render, properties_output):
        for name in dir(module):
            panel = getattr(module, name)
            if hasattr(panel, "COMPAT_ENGINES") and "BLENDER_RENDER" in panel.COMPAT_ENGINES:
                out.append(panel)
    return out


_classes = (GlintPreferences, GlintSettings, GlintRenderEngine, GLINT_PT_sampling)


def register():
    for c in _classes:
        bpy.utils.register_class(c)
    bpy.types.Scene.glint = bpy.props.PointerProperty(type=GlintSettings)
    for p in _panels():
        p.COMPAT_ENGINES.add("GLINT")


def unregister():
    for p in _panels():
        p.COMPAT_ENGINES.discard("GLINT")
    del bpy.types.Scene.glint
    for c in reversed(_classes):
        bpy.utils.unregister_class(c)
