// The Python module's compiled half (`glint._glint`): a thin layer over the render session
// (session/session.h), the scene readers and glint's image I/O. Everything a user calls is in
// __init__.py, which wraps these in the documented API (docs/python.md).
//
// Threads: a render runs on a thread of its own with the GIL released; the calling thread waits
// in slices of 50 ms, taking the GIL only to check for Ctrl-C (PyErr_CheckSignals), which cancels
// the render at the next tile. Pass callbacks take the GIL on the render's thread.
#include <fmt/core.h>
#include <pybind11/functional.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstring>
#include <exception>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "glint/base/diagnostics.h"
#include "glint/base/errors.h"
#include "glint/formats/scene_yaml.h"
#include "glint/image/image_io.h"
#include "glint/session/session.h"

namespace py = pybind11;
using namespace glint;

namespace {

// A flag a Python thread sets to stop a render (glint.render_passes closes its generator with it).
struct CancelToken {
    std::atomic<bool> flag{false};
};

py::array_t<float> plane(const float* data, int height, int width, int channels) {
    std::vector<py::ssize_t> shape{height, width};
    if (channels > 1) shape.push_back(channels);
    py::array_t<float> a(shape);
    std::memcpy(a.mutable_data(), data, sizeof(float) * static_cast<std::size_t>(height) * width * channels);
    return a;
}

static_assert(sizeof(Color) == 3 * sizeof(float) && sizeof(Normal3) == 3 * sizeof(float));

// The film as arrays: "beauty" and whichever of the AOVs it holds. Call with the GIL.
py::dict film_arrays(const Film& film) {
    const int w = film.width(), h = film.height();
    py::dict out;
    out["beauty"] = plane(&film.pixels().data()->r, h, w, 3);
    if (film.has_aovs()) {
        out["albedo"] = plane(&film.albedo().data()->r, h, w, 3);
        out["normal"] = plane(&film.normal().data()->x, h, w, 3);
        out["depth"] = plane(film.depth().data(), h, w, 1);
    }
    if (film.has_noisy()) out["noisy"] = plane(&film.noisy().data()->r, h, w, 3);
    if (film.has_sample_counts()) out["samples"] = plane(film.sample_counts().data(), h, w, 1);
    return out;
}

py::dict display_dict(const DisplaySettings& d) {
    py::dict out;
    out["srgb"] = d.encoding == Encoding::kSrgb;
    out["curve"] = static_cast<int>(d.curve);
    out["exposure"] = d.exposure;
    return out;
}

DisplaySettings display_of(const py::dict& d) {
    DisplaySettings s;
    if (d.contains("srgb")) s.encoding = d["srgb"].cast<bool>() ? Encoding::kSrgb : Encoding::kRaw;
    if (d.contains("curve")) s.curve = static_cast<ToneCurve>(d["curve"].cast<int>());
    if (d.contains("exposure")) s.exposure = d["exposure"].cast<float>();
    return s;
}

// Runs `work` on a thread of its own with the GIL released; the calling thread checks for Ctrl-C
// every 50 ms (only the main thread sees signals) and sets `cancel` when it comes. Returns whether
// a KeyboardInterrupt arrived (it is then pending in Python). Rethrows what `work` threw.
bool run_released(const std::function<void()>& work, std::atomic<bool>& cancel) {
    std::mutex m;
    std::condition_variable cv;
    bool done = false;
    std::exception_ptr error;
    bool interrupted = false;
    std::thread worker([&] {
        try {
            work();
        } catch (...) {
            error = std::current_exception();
        }
        std::lock_guard lock(m);
        done = true;
        cv.notify_all();
    });
    for (;;) {
        {
            py::gil_scoped_release release;
            std::unique_lock lock(m);
            if (cv.wait_for(lock, std::chrono::milliseconds(50), [&] { return done; })) break;
        }
        if (!interrupted && PyErr_CheckSignals() != 0) {  // the exception stays set until we decide
            interrupted = true;
            cancel = true;
        }
    }
    {
        py::gil_scoped_release release;
        worker.join();
    }
    if (error) {
        if (interrupted) PyErr_Clear();
        std::rethrow_exception(error);
    }
    return interrupted;
}

SessionOptions options_of(const py::dict& o) {
    SessionOptions s;
    const auto get = [&](const char* key) -> std::optional<py::object> {
        if (!o.contains(key) || o[key].is_none()) return std::nullopt;
        return py::reinterpret_borrow<py::object>(o[key]);
    };
    if (auto v = get("width")) s.width = v->cast<long long>();
    if (auto v = get("height")) s.height = v->cast<long long>();
    if (auto v = get("spp")) s.spp = v->cast<long long>();
    if (auto v = get("threads")) s.threads = v->cast<long long>();
    if (auto v = get("max_depth")) s.max_depth = v->cast<long long>();
    if (auto v = get("seed")) {
        const auto seed = v->cast<long long>();
        if (seed < 0) throw IoError(fmt::format("seed {}: must be at least 0", seed));
        s.seed = static_cast<std::uint64_t>(seed);
    }
    if (auto v = get("aovs")) s.aovs = v->cast<bool>();
    if (auto v = get("denoise")) s.denoise = v->cast<bool>();
    if (auto v = get("accel")) s.accel = v->cast<std::string>();
    if (auto v = get("light_sampler")) s.light_sampler = v->cast<std::string>();
    if (auto v = get("texture_filter")) s.texture_filter = v->cast<std::string>();
    if (auto v = get("spectral")) s.spectral = v->cast<bool>();
    if (auto v = get("time")) s.time = v->cast<std::string>();
    if (auto v = get("checkpoint")) s.checkpoint = v->cast<std::string>();
    if (auto v = get("checkpoint_every")) s.checkpoint_every = v->cast<std::string>();
    if (auto v = get("resume")) s.resume = v->cast<std::string>();
    if (auto v = get("noise_threshold")) s.noise_threshold = v->cast<double>();
    if (auto v = get("min_spp")) s.min_spp = v->cast<long long>();
    if (auto v = get("progress")) s.quiet = !v->cast<bool>();
    else s.quiet = true;
    return s;
}

// The result of one render: the arrays, what the header would say, the notes, how it ended.
py::dict render_scene(std::shared_ptr<LoadedScene> scene, const std::string& name, const py::dict& options,
                const py::object& on_pass, CancelToken* token) {
    SessionOptions o = options_of(options);
    o.loaded = std::move(scene);
    o.scene_label = name;
    std::atomic<bool> own_cancel{false};
    std::atomic<bool>& cancel = token ? token->flag : own_cancel;
    std::vector<std::string> notes;
    std::optional<Film> result;
    DisplaySettings display;
    ImageMetadata metadata;
    std::exception_ptr callback_error;

    SessionHooks hooks;
    hooks.print = [&notes](const std::string& text) { notes.push_back(text); };
    hooks.cancel = &cancel;
    hooks.cancel_reason = [] { return std::string("KeyboardInterrupt"); };
    hooks.image = [&](const Film& film, const DisplaySettings& d, const ImageMetadata& m) {
        result.emplace(film);
        display = d;
        metadata = m;
    };
    if (!on_pass.is_none()) {
        hooks.pass_done = [&](const ProgressiveRender& r, double seconds) {
            if (callback_error) return;
            Film film(r.state().width, r.state().height);
            if (r.state().aovs) film.enable_aovs();
            r.resolve(film);
            py::gil_scoped_acquire gil;
            try {
                py::dict pass = film_arrays(film);
                pass["spp"] = r.spp_done();
                pass["passes"] = r.passes();
                pass["seconds"] = seconds;
                on_pass(pass);
            } catch (py::error_already_set&) {
                callback_error = std::current_exception();
                cancel = true;
            }
        };
    }
    SessionResult status = SessionResult::kComplete;
    const bool interrupted = run_released(
        [&] {
            RenderSession session(o, hooks);
            status = session.run();
        },
        cancel);
    if (callback_error) {
        if (interrupted) PyErr_Clear();
        std::rethrow_exception(callback_error);
    }
    if (interrupted && !result) throw py::error_already_set();  // nothing rendered: the KeyboardInterrupt
    if (interrupted) PyErr_Clear();                              // returned with what was done
    py::dict out;
    if (result) {
        out = film_arrays(*result);
        out["display"] = display_dict(display);
    }
    py::dict meta;
    for (const auto& [k, v] : metadata) meta[py::str(k)] = v;
    out["metadata"] = meta;
    out["notes"] = notes;
    out["complete"] = status == SessionResult::kComplete;
    out["interrupted"] = interrupted;
    return out;
}

// Numpy arrays beside a dict's JSON text: float32 or uint32, C-contiguous, 1 to 3 dimensions
// (__init__.py converts them). Kept alive by the caller for the parse.
InlineArrays views_of(const std::vector<py::array>& arrays) {
    InlineArrays views;
    for (const py::array& a : arrays) {
        ArrayView v;
        if (a.ndim() < 1 || a.ndim() > 3 || !(a.flags() & py::array::c_style))
            throw std::invalid_argument("arrays must be C-contiguous, of 1 to 3 dimensions");
        v.dims = static_cast<int>(a.ndim());
        for (int i = 0; i < v.dims; ++i) v.shape[static_cast<std::size_t>(i)] = static_cast<std::size_t>(a.shape(i));
        v.rows = v.shape[0];
        v.columns = v.dims == 1 ? 1 : v.shape[1] * (v.dims == 3 ? v.shape[2] : 1);
        if (a.dtype().is(py::dtype::of<float>())) v.floats = static_cast<const float*>(a.data());
        else if (a.dtype().is(py::dtype::of<std::uint32_t>())) v.ints = static_cast<const std::uint32_t*>(a.data());
        else throw std::invalid_argument("arrays must be float32 or uint32");
        views.push_back(v);
    }
    return views;
}

}  // namespace

PYBIND11_MODULE(_glint, m) {
    m.doc() = "glint's compiled core; use the glint package (docs/python.md).";
    m.attr("version") = GLINT_VERSION;

    // SceneError and IoError become the package's SceneError and GlintError, classes of
    // __init__.py handed over by set_error_types (not looked up by the package's name: Blender's
    // add-on is a module named glint too, and loads this package under another name).
    static py::object scene_error, glint_error;
    m.def("set_error_types", [](py::object scene, py::object other) {
        scene_error = std::move(scene);
        glint_error = std::move(other);
    });
    // Dropped before the interpreter ends (static objects outlive it).
    py::module_::import("atexit").attr("register")(py::cpp_function([] {
        scene_error = py::object();
        glint_error = py::object();
    }));
    py::register_exception_translator([](std::exception_ptr p) {
        try {
            if (p) std::rethrow_exception(p);
        } catch (const SceneError& e) {
            if (!scene_error) throw;
            py::list diagnostics;
            for (const Diagnostic& d : e.diagnostics())
                diagnostics.append(py::make_tuple(d.loc.file, d.loc.line, d.loc.column, d.message));
            const py::object value = scene_error(e.what(), diagnostics);
            PyErr_SetObject(scene_error.ptr(), value.ptr());
        } catch (const IoError& e) {
            if (!glint_error) throw;
            PyErr_SetObject(glint_error.ptr(), glint_error(e.what()).ptr());
        } catch (const std::bad_alloc&) {
            PyErr_SetString(PyExc_MemoryError, "glint: out of memory");
        }
    });

    py::class_<LoadedScene, std::shared_ptr<LoadedScene>>(m, "LoadedScene")
        .def_property_readonly("objects", [](const LoadedScene& s) { return s.description.objects.size(); })
        .def_property_readonly("lights", [](const LoadedScene& s) { return s.description.lights.size(); })
        .def_property_readonly("mesh", [](const LoadedScene& s) { return s.mesh; })
        .def_property_readonly("warnings", [](const LoadedScene& s) {
            std::vector<std::string> out;
            for (const Diagnostic& w : s.description.warnings) out.push_back(format_warning(w, *s.sources));
            return out;
        });

    py::class_<CancelToken>(m, "CancelToken")
        .def(py::init<>())
        .def("cancel", [](CancelToken& t) { t.flag = true; })
        .def_property_readonly("cancelled", [](const CancelToken& t) { return t.flag.load(); });

    m.def("load", [](const std::string& path, bool strict, double frame, const std::string& camera) {
        SessionOptions o;
        o.scene = path;
        o.strict = strict;
        o.frame = frame;
        o.camera = camera;
        std::shared_ptr<LoadedScene> s;
        {
            py::gil_scoped_release release;
            s = std::make_shared<LoadedScene>(read_scene(o));
        }
        return s;
    });

    m.def("load_text", [](const std::string& text, const std::string& name, const std::vector<py::array>& arrays,
                          double frame) {
        const InlineArrays views = views_of(arrays);
        auto s = std::make_shared<LoadedScene>();
        s->sources = std::make_shared<SourceFiles>();
        py::gil_scoped_release release;  // the arrays are kept alive by the caller's list
        s->description = parse_scene_over_shutter(text, name, s->sources, frame, &views);
        s->description.frame = frame;
        return s;
    });

    m.def("render", &render_scene, py::arg("scene"), py::arg("name"), py::arg("options"), py::arg("on_pass") = py::none(),
          py::arg("cancel") = nullptr);

    m.def("write", [](const std::string& path, py::array_t<float, py::array::c_style | py::array::forcecast> rgb,
                      const py::dict& display, const std::vector<std::pair<std::string, std::string>>& metadata) {
        if (rgb.ndim() != 3 || rgb.shape(2) != 3) throw std::invalid_argument("write: the image must be H x W x 3");
        const int h = static_cast<int>(rgb.shape(0)), w = static_cast<int>(rgb.shape(1));
        if (h < 1 || w < 1) throw std::invalid_argument("write: the image is empty");
        Film film(w, h);
        std::memcpy(&film.pixels().data()->r, rgb.data(), sizeof(float) * 3 * static_cast<std::size_t>(w) * h);
        const DisplaySettings d = display_of(display);
        py::gil_scoped_release release;
        check_writable(path, w, h);
        write_image(path, film, d, metadata);
    });

    m.def("read", [](const std::string& path, bool linear) {
        Image image;
        {
            py::gil_scoped_release release;
            image = read_image(path, linear ? ImageEncoding::kLinear : ImageEncoding::kAuto);
        }
        return plane(&image.texels.data()->r, image.height, image.width, 3);
    });
}
