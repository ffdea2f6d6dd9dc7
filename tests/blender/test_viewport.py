"""The glint engine's viewport preview, in a real Blender window (docs/blender.md). Blender's
viewport needs OpenGL, so this runs under a virtual X server (Xvfb, Mesa's llvmpipe):

    GLINT_PYTHON=build/python/glint xvfb-run -a -s "-screen 0 1280x800x24" \\
        blender --factory-startup --python tests/blender/test_viewport.py

The test's box is shown through its camera in the 3D viewport, first in Solid shading, then in
Rendered shading with glint: the viewport must change from Blender's own drawing to a picture
with the box's red wall on the left and green wall on the right, and keep refining. Then the view
moves (the camera's lens changes): the picture must follow. Screenshots of the 3D view area are
compared. Exit status 0 when every check holds.
"""
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
sys.path.insert(0, str(ROOT / "tests" / "blender"))
import glint as addon  # noqa: E402  (the add-on: blender/glint)
from scenes import build_scene  # noqa: E402

failures = []
folder = pathlib.Path(tempfile.mkdtemp())
bpy.context.preferences.view.show_splash = False  # it would cover the middle of the viewport


def check(ok, what):
    print(("ok   " if ok else "FAIL ") + what, flush=True)
    if not ok:
        failures.append(what)


def view3d():
    for window in bpy.context.window_manager.windows:
        for area in window.screen.areas:
            if area.type == "VIEW_3D":
                return window, area
    raise RuntimeError("no 3D viewport")


def screenshot(name):
    """The 3D view area's pixels as an H x W x 3 array in [0, 1]."""
    window, area = view3d()
    path = folder / f"{name}.png"
    with bpy.context.temp_override(window=window, area=area):
        bpy.ops.screen.screenshot_area(filepath=str(path))
    image = bpy.data.images.load(str(path))
    pixels = np.array(image.pixels[:], dtype=np.float32).reshape(image.size[1], image.size[0], 4)[::-1, :, :3]
    bpy.data.images.remove(image)
    return pixels


def walls(pixels):
    """Mean colour where the left and right walls are at mid-height, the camera's frame filling
    the viewport (the area's screenshot: the walls span about 10-18 % and 74-85 % of its width)."""
    h, w = pixels.shape[:2]
    band = pixels[2 * h // 5: 3 * h // 5]
    return band[:, w * 10 // 100: w * 17 // 100].mean(axis=(0, 1)), band[:, w * 76 // 100: w * 83 // 100].mean(axis=(0, 1))


def steps():
    """The test as a sequence of steps, each run by a timer once the window has drawn."""
    window, area = view3d()
    space = area.spaces.active
    addon.register()
    scene = build_scene()
    scene.render.engine = "GLINT"
    scene.glint.viewport_samples = 64
    space.region_3d.view_perspective = "CAMERA"
    space.overlay.show_overlays = False
    space.show_region_toolbar = space.show_region_header = space.show_region_tool_header = False
    space.shading.type = "SOLID"
    yield 0.5
    with bpy.context.temp_override(window=window, area=area, region=next(r for r in area.regions if r.type == "WINDOW")):
        bpy.ops.view3d.view_center_camera()  # the camera's frame fills the viewport
    yield 2.0
    solid = screenshot("solid")
    space.shading.type = "RENDERED"
    yield 4.0
    first = screenshot("rendered")
    yield 6.0
    later = screenshot("rendered-later")
    left, right = walls(later)
    print(f"rendered: left wall {left}, right wall {right}; solid-mode difference "
          f"{float(np.abs(later - solid).mean()):.4f}", flush=True)
    check(float(np.abs(later - solid).mean()) > 0.02, "Rendered shading replaces Blender's own drawing")
    # Through Blender's display transform (Filmic desaturates) and with a noisy first few passes:
    # red well above green on the left, green above red and blue on the right.
    check(left[0] > 2 * left[1] and right[1] > 1.25 * right[0] and right[1] > 2 * right[2],
          "the preview shows the red and the green wall")
    check(float(np.abs(later - first).mean()) > 1e-4, "the preview keeps refining (new passes are drawn)")
    scene.camera.data.lens = 25  # a wider view: the walls move towards the middle
    yield 6.0
    moved = screenshot("moved")
    check(float(np.abs(moved - later).mean()) > 0.01, "the preview follows a change of the view")


def run(sequence):
    try:
        return next(sequence)
    except StopIteration:
        pass
    except Exception:
        traceback.print_exc()
        failures.append("exception")
    print(f"{len(failures)} failure(s)" + (": " + "; ".join(failures) if failures else ""), flush=True)
    os._exit(1 if failures else 0)


sequence = steps()
bpy.app.timers.register(lambda: run(sequence), first_interval=1.0)
# A watchdog: whatever happens, do not hang.
started = time.monotonic()
bpy.app.timers.register(lambda: (print("timed out"), os._exit(2)) if time.monotonic() - started > 120 else 5.0,
                        first_interval=5.0, persistent=True)
