"""glint, a physically based ray tracer, from Python: numpy in, numpy out.

    import glint
    scene = glint.load("scenes/cornell-box.yaml")      # or glint.load_dict({...})
    image = glint.render(scene, spp=64, seed=1)        # an H x W x 3 float32 array (glint.Image)
    glint.write("cornell.exr", image)

Every render goes through the same render session as the `glint render` command, so the same
scene, seed and samples give the same floats, bit for bit. The reference is docs/python.md.
"""
import inspect
import json
import os
import queue
import tempfile
import threading
from typing import NamedTuple

import numpy as np

from . import _glint

__version__ = _glint.version
__all__ = ["Diagnostic", "GlintError", "Image", "Scene", "SceneError", "load", "load_dict", "read",
           "render", "render_passes", "write", "__version__"]

# The arrays an inline mesh takes from numpy without a copy through text.
_MESH_ARRAYS = {"positions", "indices", "normals", "uvs", "colors"}
# The AOVs render() can return.
_AOVS = ("albedo", "normal", "depth", "noisy", "samples")


class GlintError(RuntimeError):
    """A render that could not be done: a file that cannot be read or written, a bad option.
    str(error) is the message the command line prints after "glint: error: "."""


class Diagnostic(NamedTuple):
    """One located error: the file (or the name given to load_dict), its 1-based line and column
    (0 when the error is about the whole file), and the message."""
    file: str
    line: int
    column: int
    message: str


class SceneError(GlintError):
    """A scene with errors. str(error) is the text the command line prints: every error as
    "file:line:col: error: message", the line of the file and a caret under the spot.
    `diagnostics` lists them; `file`, `line`, `column` and `message` are the first one's."""

    def __init__(self, text, diagnostics=()):
        super().__init__(text)
        self.diagnostics = [Diagnostic(*d) for d in diagnostics]
        first = self.diagnostics[0] if self.diagnostics else Diagnostic("", 0, 0, text)
        self.file, self.line, self.column, self.message = first


_glint.set_error_types(SceneError, GlintError)


class Scene:
    """A scene read by load() or load_dict(), not yet built: render() builds it with each
    render's options (size, samples, seed ...), so one Scene renders many ways."""

    def __init__(self, core, name):
        self._core = core
        self.name = name

    @property
    def objects(self):
        """How many objects the scene lists (a mesh file counts once)."""
        return self._core.objects

    @property
    def lights(self):
        """How many lights the scene lists (emitting objects are not counted)."""
        return self._core.lights

    @property
    def warnings(self):
        """What the reader approximated or left out (pbrt files, dropped triangles), as text."""
        return list(self._core.warnings)

    def __repr__(self):
        return f"<glint.Scene {self.name!r}: {self.objects} objects, {self.lights} lights>"


class Image(np.ndarray):
    """An image: a float32 numpy array of shape (height, width, 3), linear RGB, row 0 at the top.

    Beside the pixels: `aovs` (a dict of the arrays asked for: "albedo" and "normal" H x W x 3,
    "depth" and "samples" H x W, "noisy" H x W x 3), `spp` (samples per pixel reached), `complete`
    (False if the render was stopped or ran out of time), `interrupted` (stopped by Ctrl-C),
    `metadata` (what an image file's header would hold), `notes` (what the command line would
    print) and `display` (the scene's exposure, tone curve and encoding, used by write() for
    8-bit formats and by notebooks)."""

    def __array_finalize__(self, obj):
        self.aovs = getattr(obj, "aovs", {})
        self.spp = getattr(obj, "spp", 0)
        self.complete = getattr(obj, "complete", True)
        self.interrupted = getattr(obj, "interrupted", False)
        self.metadata = getattr(obj, "metadata", {})
        self.notes = getattr(obj, "notes", [])
        self.display = getattr(obj, "display", {})

    def _repr_png_(self):
        """PNG bytes through the image's display transform: how Jupyter shows an Image."""
        with tempfile.TemporaryDirectory() as folder:
            path = os.path.join(folder, "image.png")
            write(path, self)
            with open(path, "rb") as f:
                return f.read()

    def save(self, path):
        """write(path, self)."""
        write(path, self)


def _image(result, aovs):
    image = np.asarray(result["beauty"]).view(Image)
    image.aovs = {name: result[name] for name in aovs if name in result}
    image.metadata = dict(result.get("metadata", {}))
    image.spp = int(image.metadata.get("glint:spp", result.get("spp", 0)))
    # Complete: every sample taken (not stopped, not cut short by the time budget).
    image.complete = bool(result.get("complete", False)) and image.metadata.get("glint:complete", "yes") == "yes"
    image.interrupted = bool(result.get("interrupted", False))
    image.notes = list(result.get("notes", []))
    image.display = dict(result.get("display", {}))
    return image


def load(path, *, strict=False, frame=0.0, camera=""):
    """Reads a scene or mesh file, as `glint render` does: glint's YAML or JSON, a pbrt-v4 file,
    glTF (.gltf, .glb), OBJ, PLY (a mesh file becomes the scene that renders it, under a sky).

    strict: a pbrt file's features glint cannot render are errors, not warnings. frame: the
    animation frame whose keyframes are read. camera: a glTF file's camera by name.
    Raises SceneError (located errors) or GlintError."""
    path = os.fspath(path)
    return Scene(_glint.load(path, strict, float(frame), camera), path)


def _plain(value, arrays):
    """The dict as JSON-able values; numpy arrays under an inline mesh's keys, an image texture's
    `pixels` and a grid medium's `voxels` into `arrays`."""
    if isinstance(value, dict):
        kind = value.get("type")
        if kind == "mesh":
            return {k: (_mesh_array(v, k, arrays) if k in _MESH_ARRAYS and isinstance(v, np.ndarray)
                        else _plain(v, arrays)) for k, v in value.items()}
        if kind == "image" and isinstance(value.get("pixels"), np.ndarray):
            return _image_dict(value, arrays)
        if kind == "grid" and isinstance(value.get("voxels"), np.ndarray):
            out = {str(k): _plain(v, arrays) for k, v in value.items() if k != "voxels"}
            out["voxels"] = _block_array(value["voxels"], arrays)
            return out
        return {str(k): _plain(v, arrays) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_plain(v, arrays) for v in value]
    if isinstance(value, np.ndarray):
        return value.tolist()
    if isinstance(value, np.generic):
        return value.item()
    if isinstance(value, os.PathLike):
        return os.fspath(value)
    return value


def _mesh_array(a, key, arrays):
    # The same array object given to several meshes is handed over once: the reader then makes
    # them one mesh, placed as instances (one BVH). `arrays` maps id(original) to (its number,
    # the original, kept alive so that its id stays its own, the array handed over).
    return _hand_over(a, lambda: _mesh_rows(a, key), arrays)


def _mesh_rows(a, key):
    # A mesh array as the reader takes it: uint32 indices or float32 values, one row per entry.
    if key == "indices":
        if a.dtype.kind not in "iu":
            raise TypeError(f"mesh indices must be integers, not {a.dtype}")
        if a.size and (a.min() < 0 or a.max() > 0xFFFFFFFF):
            raise ValueError(f"mesh indices must lie in [0, 2**32): found {a.min()} to {a.max()}")
        c = np.ascontiguousarray(a, dtype=np.uint32)
    else:
        c = np.ascontiguousarray(a, dtype=np.float32)
    if c.ndim == 0:
        raise ValueError(f"mesh {key}: expected an array of rows, got a scalar")
    return c.reshape(c.shape[0], -1) if c.ndim > 1 else c


def _hand_over(original, convert, arrays):
    # The reference to `original` beside the text: an array given before is handed over once;
    # otherwise convert() becomes the next array, and `original` is kept alive in the table so
    # that its id stays its own.
    if id(original) not in arrays:
        arrays[id(original)] = (len(arrays), original, convert())
    return f"<array {arrays[id(original)][0]}>"


def _block_array(a, arrays):
    # An image's pixels or a grid's voxels, handed over with their shape (float32, C order).
    return _hand_over(a, lambda: np.ascontiguousarray(a, dtype=np.float32), arrays)


def _image_dict(value, arrays):
    # Integer pixels (uint8, uint16) are read as files of those types are: scaled to [0, 1] and,
    # unless `encoding` says otherwise, sRGB-encoded. Floats are linear unless it says srgb.
    out = {str(k): _plain(v, arrays) for k, v in value.items() if k != "pixels"}
    pixels = value["pixels"]
    if pixels.dtype.kind in "iu":
        if pixels.dtype.kind == "i" and pixels.size and pixels.min() < 0:
            raise ValueError("image pixels: integer pixels must not be negative")
        top = np.iinfo(pixels.dtype).max if pixels.dtype.itemsize <= 2 else None
        if top is None:
            raise TypeError(f"image pixels: integers of {pixels.dtype} have no standard scale; give uint8, "
                            "uint16 or floats")
        if out.get("encoding", "auto") == "auto":
            out["encoding"] = "srgb"
        pixels = pixels.astype(np.float32) / np.float32(top)
    out["pixels"] = _block_array(pixels, arrays)
    return out


def load_dict(scene, *, name="<dict>", frame=0.0):
    """A scene given as Python dicts and lists, with the keys of the YAML scene format
    (docs/scene-format.md). numpy arrays may stand wherever a list of numbers does; an inline
    mesh's `positions`, `indices`, `normals`, `uvs` and `colors`, an image texture's `pixels`
    (height x width [x 1, 3 or 4 channels], row 0 at the top; uint8 and uint16 read as sRGB) and a
    grid medium's `voxels` (nz x ny x nx, x fastest) are read straight from the arrays' memory
    (float32 and uint32 ones without any copy but the mesh's, image's or grid's own):

        glint.load_dict({"camera": {...}, "objects": [
            {"type": "mesh", "positions": P, "indices": F, "material": {"type": "diffuse"}}]})

    Errors are located in the dict written as indented JSON, under `name`. Mesh and texture files
    named by a relative path are looked for from the current folder."""
    arrays = {}
    plain = _plain(scene, arrays)
    text = json.dumps(plain, indent=1, allow_nan=True)
    return Scene(_glint.load_text(text, name, [a for _, _, a in arrays.values()], float(frame)), name)


def _scene_of(scene):
    if scene is None:
        return load("")
    if isinstance(scene, Scene):
        return scene
    if isinstance(scene, dict):
        return load_dict(scene)
    if isinstance(scene, (str, os.PathLike)):
        return load(scene)
    raise TypeError(f"scene: expected a glint.Scene, a path or a dict, not {type(scene).__name__}")


def _options(spp, width, height, threads, seed, max_depth, aovs, time, denoise, noise_threshold, min_spp,
             checkpoint, checkpoint_every, resume, accel, light_sampler, texture_filter, progress, spectral=None):
    aovs = list(aovs or ())
    for name in aovs:
        if name not in _AOVS:
            raise ValueError(f"unknown AOV {name!r} (known: {', '.join(_AOVS)})")
    if "noisy" in aovs and not denoise:
        raise ValueError("the 'noisy' AOV is the image before denoising: it needs denoise=True")
    if "samples" in aovs and noise_threshold is None:
        raise ValueError("the 'samples' AOV counts adaptive sampling's samples: it needs noise_threshold")
    if isinstance(time, (int, float)) and not isinstance(time, bool):
        time = f"{float(time)!r}s"
    fspath = (lambda p: None if p is None else os.fspath(p))
    return aovs, {
        "spp": spp, "width": width, "height": height, "threads": threads, "seed": seed, "max_depth": max_depth,
        "aovs": any(a in aovs for a in ("albedo", "normal", "depth")), "denoise": bool(denoise), "time": time,
        "noise_threshold": noise_threshold, "min_spp": min_spp, "checkpoint": fspath(checkpoint),
        "checkpoint_every": checkpoint_every, "resume": fspath(resume), "accel": accel,
        "light_sampler": light_sampler, "texture_filter": texture_filter, "progress": progress,
        "spectral": spectral}


def render(scene=None, *, spp=None, width=None, height=None, threads=None, seed=None, max_depth=None, aovs=(),
           time=None, denoise=False, noise_threshold=None, min_spp=None, checkpoint=None, checkpoint_every="5m",
           resume=None, accel=None, light_sampler=None, texture_filter=None, progress=False, spectral=None):
    """Renders a scene and returns the image (glint.Image: float32, height x width x 3, linear).

    scene: a glint.Scene, a file path, a dict (load_dict) or None (the built-in demo).
    spp, width, height, threads, seed, max_depth: override the scene's values (as the command
    line's flags do); threads=None uses every core. The image does not depend on `threads`.
    aovs: names among "albedo", "normal", "depth" (first-hit features), "noisy" (the image before
    denoising) and "samples" (adaptive sampling's per-pixel counts), returned in image.aovs.
    time: a time budget, in seconds or as text ("90s", "5m"): the render stops at the last pass
    that fits. denoise: the image is denoised with glint's feature-guided filter.
    noise_threshold, min_spp: adaptive sampling. checkpoint, checkpoint_every, resume: long
    renders saved and continued, as the command line's flags. accel ("bvh", "sbvh", "embree"),
    light_sampler ("bvh", "power"), texture_filter ("ewa", "trilinear", "none").
    progress: the progress bar on stderr. spectral: True traces wavelengths (the path tracer),
    False RGB, None the scene's choice (docs/spectral.md).

    The GIL is released while rendering. Ctrl-C stops the render at the next tile and returns the
    completed passes (image.interrupted is then True); with none completed, KeyboardInterrupt is
    raised. Raises SceneError or GlintError."""
    names, options = _options(spp, width, height, threads, seed, max_depth, aovs, time, denoise, noise_threshold,
                              min_spp, checkpoint, checkpoint_every, resume, accel, light_sampler, texture_filter,
                              progress, spectral)
    s = _scene_of(scene)
    return _image(_glint.render(s._core, s.name, options), names)


def render_passes(scene=None, *, stop=None, **options):
    """Renders as render() does (the same keyword arguments), yielding the image after each
    pass of the progressive render: passes double in samples while they are short, so a
    notebook can show the image sharpening. The last image yielded is render()'s result, bit for
    bit (denoised if asked; the passes before it are not). Leaving the loop early stops the render.
    A render of one sample per pixel is one pass. stop: a threading.Event; setting it, from any
    thread, stops the render at its next tile and ends the loop without another image (a live
    view that must restart when its scene changes)."""
    s = _scene_of(options.pop("scene", scene))
    names, opts = _options(**{k: options.pop(k, d) for k, d in _DEFAULTS.items()})
    if options:
        raise TypeError(f"render_passes: unknown argument {next(iter(options))!r}")
    events = queue.Queue()
    token = _glint.CancelToken()
    outcome = {}

    def work():
        try:
            outcome["result"] = _glint.render(s._core, s.name, opts, lambda p: events.put(p), token)
        except BaseException as e:  # handed to the consumer
            outcome["error"] = e
        finally:
            events.put(None)

    thread = threading.Thread(target=work, name="glint render", daemon=True)
    thread.start()
    try:
        pending = None
        while True:
            try:
                p = events.get(timeout=None if stop is None else 0.02)
            except queue.Empty:  # only with `stop`: look at it every 20 ms
                if stop.is_set():
                    return
                continue
            if p is None:
                break
            if stop is not None and stop.is_set():
                return
            if pending is not None:
                yield _image(dict(pending, complete=False), names)
            pending = p
        if stop is not None and stop.is_set():
            return
        if "error" in outcome:
            raise outcome["error"]
        result = outcome["result"]
        if "beauty" in result:
            yield _image(result, names)
        elif pending is not None:
            yield _image(dict(pending, complete=False), names)
    finally:
        token.cancel()
        thread.join()


# render_passes takes render's keyword arguments, with render's defaults.
_DEFAULTS = {k: p.default for k, p in inspect.signature(render).parameters.items() if k != "scene"}


def write(path, image, *, metadata=None):
    """Writes an H x W x 3 image through glint's image I/O, by the path's extension: EXR, HDR and
    PFM hold the linear floats; PNG, JPEG and PPM 8-bit codes through the image's display
    transform (a rendered Image's scene exposure and tone curve; sRGB otherwise). The write is
    atomic: a failed one leaves no file and never clobbers one. Raises GlintError."""
    a = np.asarray(image, dtype=np.float32)
    if a.ndim != 3 or a.shape[2] != 3:
        raise ValueError(f"write: expected an image of shape (height, width, 3), got {a.shape}")
    display = getattr(image, "display", None) or {}
    meta = dict(getattr(image, "metadata", {}) or {})
    meta.update(metadata or {})
    _glint.write(os.fspath(path), np.ascontiguousarray(a), display, [(str(k), str(v)) for k, v in meta.items()])


def read(path, *, linear=False):
    """Reads an image file as linear RGB (glint.Image, float32, H x W x 3): PNG, EXR, JPEG, HDR,
    PFM, PPM, and through OpenImageIO the other formats it knows. 8-bit files are taken as sRGB
    and decoded, unless `linear`. Raises GlintError."""
    return np.asarray(_glint.read(os.fspath(path), bool(linear))).view(Image)
