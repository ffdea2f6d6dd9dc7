"""The Python module against the command line, closed forms and itself (docs/python.md)."""
import ast
import gc
import inspect
import json
import os
import pathlib
import resource
import signal
import subprocess
import threading
import time

import numpy as np
import pytest

import glint
from conftest import plane_scene

SMALL = dict(width=48, height=40, spp=4, seed=7)


def run_cli(cli, *args):
    return subprocess.run([cli, *map(str, args)], capture_output=True, text=True)


# --- loading every format ------------------------------------------------------------------------


@pytest.mark.parametrize("path", [
    "scenes/cornell-box.yaml",                 # YAML
    "scenes/pbrt/cornell-box.pbrt",            # pbrt-v4
    "tests/data/khronos/BoxTextured.gltf",     # glTF, rendered directly
    "stanford-bunny.ply",                      # PLY, from the models folder
    "stanford-bunny.obj",                      # OBJ
])
def test_every_format_loads_and_renders(source, path):
    full = source / path
    if not full.exists():
        full = source.parent / "shared" / "models" / path
        if not full.exists():
            full = pathlib.Path("/work/shared/models") / path
    scene = glint.load(full)
    image = glint.render(scene, width=32, height=24, spp=2, seed=1)
    assert image.shape == (24, 32, 3) and image.dtype == np.float32
    assert np.isfinite(image).all() and image.mean() > 0
    assert image.complete and image.spp == 2


def test_json_scene_file(tmp_path):
    path = tmp_path / "plane.json"
    path.write_text(json.dumps(plane_scene()))
    a = glint.render(glint.load(path), seed=3)
    b = glint.render(glint.load_dict(plane_scene()), seed=3)
    assert np.array_equal(a, b)


def test_the_built_in_demo_renders():
    image = glint.render(None, width=40, height=30)
    assert image.shape == (30, 40, 3) and image.mean() > 0


# --- the same floats as the command line ---------------------------------------------------------


# Spectral renders may hold negative values (colours outside sRGB, per sample and sometimes per
# pixel); the file keeps them, glint.read clamps them to 0 as every texture read does.
@pytest.mark.parametrize("scene,spectral", [
    ("scenes/cornell-box.yaml", None), ("scenes/materials.yaml", None), ("scenes/pbrt/cornell-box.pbrt", False),
    ("scenes/pbrt/cornell-box.pbrt", True),
])
def test_images_equal_the_cli_bit_for_bit(source, cli, tmp_path, scene, spectral):
    out = tmp_path / "cli.exr"
    mode = [] if spectral is None else ["--spectral" if spectral else "--rgb"]
    r = run_cli(cli, "render", source / scene, "-o", out, "--width", 48, "--height", 40, "--spp", 8, "--seed", 11,
                "--threads", 2, "--quiet", *mode)
    assert r.returncode == 0, r.stderr
    from_cli = glint.read(out)
    from_python = glint.render(source / scene, width=48, height=40, spp=8, seed=11, threads=1, spectral=spectral)
    assert from_python.shape == from_cli.shape
    assert np.array_equal(np.maximum(np.asarray(from_python), 0), np.asarray(from_cli))
    assert (np.asarray(from_python) < 0).any() == bool(spectral)


def test_one_sample_images_equal_the_cli(source, cli, tmp_path):
    out = tmp_path / "cli.exr"
    r = run_cli(cli, "render", source / "scenes/seed/fig14-reflections.yaml", "-o", out, "--width", 64, "--height",
                48, "--quiet")
    assert r.returncode == 0, r.stderr
    image = glint.render(source / "scenes/seed/fig14-reflections.yaml", width=64, height=48)
    assert np.array_equal(np.asarray(image), np.asarray(glint.read(out)))


# --- scenes from dicts and numpy -----------------------------------------------------------------


def height_field(n=24):
    x, z = np.meshgrid(np.linspace(-1, 1, n), np.linspace(-1, 1, n))
    y = 0.25 * np.sin(3 * x) * np.cos(3 * z)
    positions = np.stack([x, y, z], axis=-1).reshape(-1, 3)
    idx = np.arange(n * n).reshape(n, n)
    a, b, c, d = idx[:-1, :-1].ravel(), idx[:-1, 1:].ravel(), idx[1:, 1:].ravel(), idx[1:, :-1].ravel()
    # Wound so that each triangle's normal points up (+y) in glint's left-handed frame.
    indices = np.concatenate([np.stack([a, c, b], 1), np.stack([a, d, c], 1)])
    return positions, indices


def mesh_scene(positions, indices, **mesh):
    return {
        "camera": {"type": "look_at", "from": [0, 2.5, -2.5], "to": [0, 0, 0], "up": [0, 1, 0], "fov": 40},
        "film": {"width": 40, "height": 32},
        "integrator": {"type": "path", "max_depth": 3},
        "background": {"type": "sky"},
        "objects": [dict({"type": "mesh", "positions": positions, "indices": indices,
                          "material": {"type": "diffuse", "albedo": np.array([0.7, 0.5, 0.3])}}, **mesh)],
    }


def test_numpy_mesh_equals_the_same_mesh_as_yaml_lists(tmp_path):
    positions, indices = height_field()
    from_numpy = glint.render(mesh_scene(positions.astype(np.float32), indices.astype(np.uint32)), spp=4, seed=2)
    # The same numbers written into a scene file as plain lists, read by the file reader.
    text = json.dumps(mesh_scene(positions.astype(np.float32).tolist(), indices.tolist()),
                      default=lambda a: a.tolist())
    path = tmp_path / "field.json"
    path.write_text(text)
    from_file = glint.render(glint.load(path), spp=4, seed=2)
    assert np.array_equal(from_numpy, from_file)
    assert from_numpy.mean() > 0.05  # the field is lit and seen


def test_an_array_given_twice_is_handed_over_once():
    # Two meshes on the same position array, and one image on the same pixels twice: each array
    # crosses once, and every use refers to it (the reader makes the meshes one, instanced).
    positions, indices = height_field()
    p, i = positions.astype(np.float32), indices.astype(np.uint32)
    pixels = np.full((2, 2, 3), 0.5, np.float32)
    arrays = {}
    plain = glint._plain({"objects": [{"type": "mesh", "positions": p, "indices": i},
                                      {"type": "mesh", "positions": p, "indices": i.copy()}],
                          "textures": [{"type": "image", "pixels": pixels}, {"type": "image", "pixels": pixels}]},
                         arrays)
    assert len(arrays) == 4  # p, i, the copy of i, pixels
    assert plain["objects"][0]["positions"] == plain["objects"][1]["positions"]
    assert plain["objects"][0]["indices"] != plain["objects"][1]["indices"]
    assert plain["textures"][0]["pixels"] == plain["textures"][1]["pixels"]
    assert sorted(n for n, _, _ in arrays.values()) == [0, 1, 2, 3]


def test_numpy_dtypes_and_layouts_convert():
    positions, indices = height_field()
    reference = glint.render(mesh_scene(positions.astype(np.float32), indices.astype(np.uint32)), spp=2, seed=1)
    # float64 positions, int64 indices, a flat position array, a Fortran-ordered one: the same mesh.
    for p, i in [(positions, indices), (positions.astype(np.float32).ravel(), indices),
                 (np.asfortranarray(positions), indices.astype(np.int32))]:
        assert np.array_equal(glint.render(mesh_scene(p, i), spp=2, seed=1), reference)


def test_vertex_attributes_from_numpy():
    positions, indices = height_field(8)
    normals = np.tile([0.0, 1.0, 0.0], (len(positions), 1))
    uvs = positions[:, [0, 2]] * 0.5 + 0.5
    colors = np.tile([1.0, 0.0, 0.0], (len(positions), 1))
    scene = mesh_scene(positions, indices, normals=normals, uvs=uvs, colors=colors)
    scene["objects"][0]["material"] = {"type": "diffuse", "albedo": {"type": "vertex_color"}}
    image = glint.render(scene, spp=4, seed=1, aovs=["albedo", "depth"])
    albedo = image.aovs["albedo"]
    hit = np.isfinite(image.aovs["depth"])  # a pixel none of whose samples hit has depth inf
    # Pixels whose 3 x 3 neighbourhood is all mesh (an edge pixel mixes the mesh with the sky).
    seen = np.zeros_like(hit)
    seen[1:-1, 1:-1] = np.logical_and.reduce([hit[1 + dy:hit.shape[0] - 1 + dy, 1 + dx:hit.shape[1] - 1 + dx]
                                              for dy in (-1, 0, 1) for dx in (-1, 0, 1)])
    assert seen.mean() > 0.1
    # The vertex colour (1, 0, 0) is the albedo wherever the mesh is seen.
    assert np.allclose(albedo[seen], [1, 0, 0], atol=1e-5)


@pytest.mark.parametrize("change, message", [
    (dict(indices=np.array([[0, 1, 900]])), "uses vertex 900, but there are 16 vertices"),
    (dict(normals=np.zeros((3, 3))), "rows for"),
    (dict(positions=np.zeros((5, 2))), "3 columns"),
    (dict(indices=np.array([[0.5, 1, 2]])), "integers"),
    (dict(indices=np.array([[-1, 1, 2]])), "[0, 2**32)"),
])
def test_bad_arrays_are_errors(change, message):
    positions, indices = height_field(4)
    scene = mesh_scene(positions, indices)
    scene["objects"][0].update(change)
    with pytest.raises((glint.SceneError, ValueError, TypeError)) as e:
        glint.load_dict(scene)
    assert message in str(e.value)


def pixels_scene(pixels, **texture):
    return {
        "camera": {"type": "look_at", "from": [0, 0, -3], "to": [0, 0, 0], "fov": 30},
        "film": {"width": 24, "height": 16},
        "integrator": {"type": "flat"},
        "objects": [{"type": "quad", "corner": [-1.5, -1, 0], "edge1": [3, 0, 0], "edge2": [0, 2, 0],
                     "material": {"color": dict({"type": "image", "pixels": pixels}, **texture)}}],
    }


def test_numpy_pixels_equal_the_same_pixels_as_lists():
    rng = np.random.default_rng(3)
    pixels = rng.random((4, 6, 3), dtype=np.float32)
    from_numpy = glint.render(pixels_scene(pixels), spp=4, seed=1)
    from_lists = glint.render(glint.load_dict(pixels_scene(pixels.tolist())), spp=4, seed=1)
    assert np.array_equal(from_numpy, from_lists)
    # Row 0 is the top of the image: in the flat view of a 2 x 2 image clamped at its edges, each
    # corner of the picture shows that corner's pixel exactly (the quad fills the frame).
    corners = np.array([[[1, 0, 0], [0, 1, 0]], [[0, 0, 1], [1, 1, 1]]], dtype=np.float32)
    seen = glint.render(pixels_scene(corners, wrap="clamp"), spp=1)
    for (y, x), (row, col) in {(0, 0): (0, 0), (0, -1): (0, 1), (-1, 0): (1, 0), (-1, -1): (1, 1)}.items():
        assert np.array_equal(seen[y, x], corners[row, col]), (y, x, seen[y, x])
    # A grey array is its channel in all three; an RGBA array's colour is its RGB (the alpha channel
    # is alpha, not colour).
    grey = np.ascontiguousarray(pixels[:, :, 0])
    assert np.array_equal(glint.render(pixels_scene(grey), spp=1),
                          glint.render(pixels_scene(np.repeat(grey[:, :, None], 3, axis=2)), spp=1))
    rgba = np.dstack([pixels, np.full((4, 6, 1), 0.5, np.float32)])
    assert np.array_equal(glint.render(pixels_scene(rgba), spp=1), glint.render(pixels_scene(pixels), spp=1))


def test_8_bit_pixels_read_as_srgb_like_8_bit_files():
    codes = np.array([[[0, 128, 255]]], dtype=np.uint8)
    image = glint.render(pixels_scene(codes), spp=1, width=4, height=4)
    srgb = np.where(codes / 255 <= 0.04045, codes / 255 / 12.92, ((codes / 255 + 0.055) / 1.055) ** 2.4)
    assert np.allclose(image[2, 2], srgb[0, 0], atol=1e-5)
    linear = glint.render(pixels_scene(codes, encoding="linear"), spp=1, width=4, height=4)
    assert np.allclose(linear[2, 2], codes[0, 0] / 255, atol=1e-5)


def voxels_scene(voxels):
    return {
        "integrator": {"type": "path", "max_depth": 4},
        "film": {"width": 8, "height": 8},
        "camera": {"type": "look_at", "from": [0.5, 0.5, -3], "to": [0.5, 0.5, 0], "fov": 10},
        "background": {"type": "constant", "color": [1, 1, 1]},
        "media": {"smoke": {"type": "grid", "voxels": voxels, "sigma_a": [2, 2, 2], "sigma_s": [0, 0, 0]}},
        "objects": [{"type": "box", "min": [-1, -1, -1], "max": [2, 2, 2], "material": "interface",
                     "interior": "smoke"}],
    }


def test_numpy_voxels_equal_the_same_voxels_as_lists():
    voxels = np.zeros((4, 5, 6), dtype=np.float32)  # (nz, ny, nx)
    voxels[:, :, 3:] = 1.0  # the right half (x >= 0.5) dense
    from_numpy = glint.render(voxels_scene(voxels), spp=64, seed=1)
    from_lists = glint.render(voxels_scene(voxels.tolist()), spp=64, seed=1)
    assert np.array_equal(from_numpy, from_lists)
    # x fastest: the dense half is on the right of the picture (+x is to the right, looking +z).
    left, right = from_numpy[:, :3].mean(), from_numpy[:, 5:].mean()
    assert left > 0.9 and right < 0.5, (left, right)


@pytest.mark.parametrize("scene, message", [
    (lambda: pixels_scene(np.zeros((4, 6, 2), np.float32)), "must have 1, 3 or 4 channels"),
    (lambda: pixels_scene(np.full((2, 2), np.nan, np.float32)), "number 0 (counting from 0) is nan"),
    (lambda: voxels_scene(np.ones((4, 4), np.float32)), "'voxels' must have 3 dimensions"),
    (lambda: voxels_scene(-np.ones((2, 2, 2))), "is -1"),
])
def test_bad_pixels_and_voxels_are_errors(scene, message):
    with pytest.raises(glint.SceneError) as e:
        glint.load_dict(scene())
    assert message in str(e.value)


# --- AOVs against what the scene says ------------------------------------------------------------


def test_aovs_are_the_first_hit_features():
    image = glint.render(plane_scene(albedo=(0.2, 0.4, 0.6), distance=5), aovs=["albedo", "normal", "depth"],
                         spp=4, seed=1)
    a, n, z = image.aovs["albedo"], image.aovs["normal"], image.aovs["depth"]
    assert a.shape == image.shape and n.shape == image.shape and z.shape == image.shape[:2]
    assert np.allclose(a, [0.2, 0.4, 0.6], atol=1e-5)
    assert np.allclose(n, [0, 0, -1], atol=1e-5)  # the square faces the camera (-z)
    h, w = z.shape
    # The distance along the centre pixel's rays: 5 / cos(angle off the axis), at most 5.0015 there.
    assert abs(z[h // 2, w // 2] - 5) < 5e-3
    # Under a white sky of radiance 1 with nothing else to hit, a diffuse plane's radiance is its albedo.
    assert np.allclose(image.mean(axis=(0, 1)), [0.2, 0.4, 0.6], rtol=0.03)


def test_unknown_and_unavailable_aovs_are_refused():
    with pytest.raises(ValueError, match="unknown AOV"):
        glint.render(plane_scene(), aovs=["albedoo"])
    with pytest.raises(ValueError, match="denoise=True"):
        glint.render(plane_scene(), aovs=["noisy"])


def test_denoise_keeps_the_noisy_image(source):
    image = glint.render(source / "scenes/cornell-box.yaml", width=48, height=48, spp=16, seed=1, denoise=True,
                         aovs=["noisy"])
    noisy = image.aovs["noisy"]
    plain = glint.render(source / "scenes/cornell-box.yaml", width=48, height=48, spp=16, seed=1)
    assert np.array_equal(noisy, plain)          # the image before the filter is the render
    assert not np.array_equal(image, plain)      # and the filter changed it
    # The filter smooths: less difference between neighbouring pixels.
    def roughness(x):
        return np.abs(np.diff(x, axis=1)).mean()
    assert roughness(image) < roughness(plain)


def test_adaptive_sampling_counts_samples(source):
    image = glint.render(source / "scenes/cornell-box.yaml", width=32, height=32, spp=64, seed=1,
                         noise_threshold=0.05, aovs=["samples"])
    counts = image.aovs["samples"]
    assert counts.shape == (32, 32)
    assert counts.min() >= 1 and counts.max() <= 64 and counts.min() < counts.max()


# --- progressive rendering, budgets, checkpoints -------------------------------------------------


def test_passes_end_in_the_one_pass_image(source):
    scene = glint.load(source / "scenes/cornell-box.yaml")
    whole = glint.render(scene, width=40, height=40, spp=32, seed=5)
    passes = list(glint.render_passes(scene, width=40, height=40, spp=32, seed=5))
    assert len(passes) >= 3
    spp = [p.spp for p in passes]
    assert spp == sorted(spp) and spp[-1] == 32 and spp[0] < 32
    assert [p.complete for p in passes] == [False] * (len(passes) - 1) + [True]
    assert np.array_equal(passes[-1], whole)


def test_leaving_the_passes_early_stops_the_render(source):
    started = time.monotonic()
    for image in glint.render_passes(source / "scenes/cornell-box.yaml", width=256, height=256, spp=100000):
        break
    assert image.spp < 100000
    assert time.monotonic() - started < 60  # the render of 6.5 G samples was not finished


def test_a_stop_event_from_another_thread_ends_the_passes(source):
    stop = threading.Event()
    seen = []

    def consume():
        for image in glint.render_passes(source / "scenes/cornell-box.yaml", width=256, height=256,
                                         spp=100000, stop=stop):
            seen.append(image.spp)

    worker = threading.Thread(target=consume)
    started = time.monotonic()
    worker.start()
    while not seen and time.monotonic() - started < 60:
        time.sleep(0.01)
    stop.set()
    worker.join(60)
    assert not worker.is_alive() and seen and max(seen) < 100000
    assert time.monotonic() - started < 60


def test_time_budget_and_checkpoint_resume(source, tmp_path):
    scene = glint.load(source / "scenes/cornell-box.yaml")
    cut = glint.render(scene, width=32, height=32, spp=1 << 20, seed=1, time=0.5)
    assert not cut.complete and 0 < cut.spp < 1 << 20
    ckpt = tmp_path / "c.ckpt"
    first = glint.render(scene, width=32, height=32, spp=16, seed=1, checkpoint=ckpt)
    assert ckpt.exists() and first.complete
    again = glint.render(scene, width=32, height=32, spp=16, seed=1, resume=ckpt)
    assert np.array_equal(first, again)


# --- Ctrl-C --------------------------------------------------------------------------------------


def sigint_after(seconds):
    timer = threading.Timer(seconds, lambda: os.kill(os.getpid(), signal.SIGINT))
    timer.start()
    return timer


def test_ctrl_c_returns_the_completed_passes(source):
    timer = sigint_after(1.0)
    started = time.monotonic()
    image = glint.render(source / "scenes/cornell-box.yaml", width=128, height=128, spp=1 << 20, seed=1)
    timer.join()
    assert time.monotonic() - started < 30
    assert image.interrupted and not image.complete
    assert 0 < image.spp < 1 << 20 and image.mean() > 0


def test_ctrl_c_before_any_pass_raises_keyboard_interrupt(source):
    timer = sigint_after(0.3)
    with pytest.raises(KeyboardInterrupt):
        # One sample per pixel is one sweep: nothing is complete before it ends (~10 s).
        glint.render(source / "scenes/cornell-box.yaml", width=3000, height=3000, spp=1)
    timer.join()


# --- errors --------------------------------------------------------------------------------------


def test_scene_errors_carry_the_cli_text_and_location(cli, tmp_path):
    path = tmp_path / "bad.yaml"
    bad_line = "  - {type: sphere, center: [0, 0, 0], radius: -1}"
    path.write_text("camera: {type: look_at, from: [0, 0, -5], to: [0, 0, 0], up: [0, 1, 0], fov: 40}\n"
                    f"objects:\n{bad_line}\n")
    with pytest.raises(glint.SceneError) as e:
        glint.load(path)
    assert (e.value.file, e.value.line, e.value.column) == (str(path), 3, bad_line.index("-1") + 1)
    assert "radius" in e.value.message
    r = run_cli(cli, "render", path, "-o", tmp_path / "x.png")
    assert r.returncode == 1
    assert r.stderr == str(e.value) + "glint: 1 error; no image written\n"


def test_dict_errors_point_into_the_dict_as_json():
    scene = plane_scene()
    scene["film"]["width"] = "wide"
    with pytest.raises(glint.SceneError) as e:
        glint.load_dict(scene, name="my-scene")
    text = json.dumps(scene, indent=1).splitlines()
    assert e.value.file == "my-scene"
    assert '"width": "wide"' in text[e.value.line - 1]


def test_other_errors_are_glint_errors(tmp_path):
    with pytest.raises(glint.SceneError, match="cannot open scene file"):
        glint.load(tmp_path / "missing.yaml")
    with pytest.raises(glint.GlintError, match="accel"):
        glint.render(plane_scene(), accel="kd-tree")
    with pytest.raises(glint.GlintError, match="folder"):
        glint.write(tmp_path / "no" / "such" / "x.png", np.zeros((4, 4, 3), np.float32))
    assert not (tmp_path / "no").exists()


# --- memory and threads --------------------------------------------------------------------------


def rss_kib():
    with open("/proc/self/statm") as f:
        return int(f.read().split()[1]) * (resource.getpagesize() // 1024)


def test_no_leaks_over_100_renders():
    scene = glint.load_dict(plane_scene(width=16, height=16, spp=2))
    for _ in range(20):
        glint.render(scene, aovs=["albedo"])
    gc.collect()
    objects, rss = len(gc.get_objects()), rss_kib()
    for _ in range(100):
        glint.render(scene, aovs=["albedo"])
    gc.collect()
    assert len(gc.get_objects()) - objects < 100
    assert rss_kib() - rss < 8 * 1024  # under 8 MiB over 100 renders (each holds ~10 KiB of arrays)


def test_renders_release_the_gil_and_run_in_two_threads(source):
    scene = glint.load(source / "scenes/cornell-box.yaml")
    expected = [glint.render(scene, width=64, height=64, spp=8, seed=s, threads=1) for s in (1, 2)]
    results, ticks = {}, [0]
    stop = threading.Event()

    def ticker():  # runs only if the renders let go of the GIL
        while not stop.is_set():
            ticks[0] += 1
            time.sleep(0.001)

    def work(seed):
        results[seed] = glint.render(scene, width=64, height=64, spp=8, seed=seed, threads=1)

    t = threading.Thread(target=ticker)
    t.start()
    workers = [threading.Thread(target=work, args=(s,)) for s in (1, 2)]
    for w in workers:
        w.start()
    for w in workers:
        w.join()
    stop.set()
    t.join()
    assert np.array_equal(results[1], expected[0]) and np.array_equal(results[2], expected[1])
    assert ticks[0] > 5


# --- images --------------------------------------------------------------------------------------


def test_write_and_read_round_trip(tmp_path):
    rng = np.random.default_rng(1)
    image = rng.random((20, 30, 3), dtype=np.float32) * 4
    glint.write(tmp_path / "a.exr", image)
    assert np.array_equal(glint.read(tmp_path / "a.exr"), image)
    glint.write(tmp_path / "a.pfm", image)
    assert np.array_equal(glint.read(tmp_path / "a.pfm"), image)
    low = np.clip(image / 4, 0, 1)
    glint.write(tmp_path / "a.png", low)
    back = glint.read(tmp_path / "a.png")
    # 8-bit sRGB codes decoded: within half a code step of the curve's slope at worst.
    assert np.abs(back - low).max() < 0.01


def test_notebooks_show_images_as_png():
    image = glint.render(plane_scene(width=16, height=8), spp=1)
    png = image._repr_png_()
    assert png[:8] == b"\x89PNG\r\n\x1a\n"


# --- the API as documented -----------------------------------------------------------------------


def stub_functions():
    tree = ast.parse((pathlib.Path(glint.__file__).with_suffix(".pyi")).read_text())
    return {f.name: f for f in tree.body if isinstance(f, ast.FunctionDef)}


def test_stubs_match_the_module():
    stubs = stub_functions()
    for name in ("load", "load_dict", "render", "write", "read"):
        real = inspect.signature(getattr(glint, name))
        stub = stubs[name].args
        names = [a.arg for a in stub.args + stub.kwonlyargs]
        assert names == list(real.parameters), name
    rp = stubs["render_passes"].args
    assert [a.arg for a in rp.args + rp.kwonlyargs] == (["scene", "stop"] +
                                                        list(inspect.signature(glint.render).parameters)[1:])
    for name in glint.__all__:
        assert hasattr(glint, name)


def test_help_is_useful():
    doc = glint.render.__doc__
    for word in ("spp", "aovs", "denoise", "time", "KeyboardInterrupt", "GIL"):
        assert word in doc
    assert glint.__version__.count(".") == 2


# --- the examples run ----------------------------------------------------------------------------


@pytest.mark.parametrize("example", sorted(p.name for p in (pathlib.Path(__file__).resolve().parents[2] / "examples"
                                                             / "python").glob("*.py")))
def test_examples_run(source, tmp_path, example):
    env = dict(os.environ, PYTHONPATH=str(pathlib.Path(glint.__file__).resolve().parents[1]))
    r = subprocess.run(["/usr/bin/python3" if os.path.exists("/usr/bin/python3") else "python3",
                        source / "examples" / "python" / example, tmp_path / "out.png", "--quick"],
                       capture_output=True, text=True, env=env, cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    assert glint.read(tmp_path / "out.png").mean() > 0


def test_the_reference_documents_every_argument(source):
    doc = (source / "docs" / "python.md").read_text()
    for name in glint.__all__:
        assert f"glint.{name}" in doc or name.startswith("__"), name
    for name in inspect.signature(glint.render).parameters:
        assert f"`{name}`" in doc, name


def test_a_normal_map_tilts_the_shading_normal():
    """A flat square lit from straight above, its normal map tilting the normal by a (cos a = 0.8)
    towards +u: the reflected radiance falls to 0.8 of the untilted one (Lambert's cosine)."""
    def scene(normal_color):
        return {
            "camera": {"type": "look_at", "from": [0, 3, 0.001], "to": [0, 0, 0], "up": [0, 0, 1], "fov": 20},
            "film": {"width": 16, "height": 16},
            "integrator": {"type": "path", "max_depth": 1},
            "background": {"type": "constant", "color": [0, 0, 0]},
            "lights": [{"type": "directional", "direction": [0, -1, 0], "intensity": [1, 1, 1]}],
            "objects": [{"type": "mesh", "positions": np.array([[-2, 0, -2], [2, 0, -2], [2, 0, 2], [-2, 0, 2]], float),
                         "indices": np.array([[0, 2, 1], [0, 3, 2]]),
                         "uvs": np.array([[0, 0], [1, 0], [1, 1], [0, 1]], float),
                         "material": {"type": "diffuse", "albedo": [1, 1, 1],
                                      "normal_map": {"type": "constant", "color": normal_color}}}],
        }
    flat = glint.render(scene([0.5, 0.5, 1.0]), spp=4)
    tilted = glint.render(scene([0.5 + 0.5 * 0.6, 0.5, 0.5 + 0.5 * 0.8]), spp=4)
    assert abs(flat.mean() - 1 / np.pi) < 1e-3  # E / pi with E = 1
    assert abs(tilted.mean() / flat.mean() - 0.8) < 1e-3


# --- spectral mode (docs/spectral.md) ------------------------------------------------------------


def test_spectral_mode_keeps_white_white_and_disperses_glass():
    furnace = {
        "camera": {"type": "look_at", "from": [0, 0, -3], "to": [0, 0, 0], "fov": 45},
        "film": {"width": 16, "height": 16},
        "integrator": {"type": "path", "max_depth": 32},
        "background": {"type": "constant", "color": [1, 1, 1]},
        "objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 1,
                     "material": {"type": "dielectric", "ior": "glass-F11"}}],
    }
    scene = glint.load_dict(furnace)
    spectral = glint.render(scene, spp=64, spectral=True)
    assert abs(float(spectral.mean()) - 1) < 0.01          # lossless glass in a white sky
    rgb = glint.render(scene, spp=4, spectral=False)
    assert not np.array_equal(np.asarray(spectral), np.asarray(rgb))
    with pytest.raises(glint.SceneError, match="unknown glass 'glass-F12'"):
        glint.load_dict({**furnace, "objects": [{**furnace["objects"][0],
                                                 "material": {"type": "dielectric", "ior": "glass-F12"}}]})
