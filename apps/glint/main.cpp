// glint: the command line. The only place that prints diagnostics and chooses an exit status.
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <fmt/core.h>

#include <cstdio>
#include <filesystem>
#include <memory>
#include <new>
#include <optional>
#include <string>

#include "glint/demo_scene.h"
#include "glint/film/film.h"
#include "glint/io/build.h"
#include "glint/io/image_io.h"
#include "glint/io/scene_yaml.h"
#include "glint/render/render.h"

namespace {

struct RenderArgs {
    std::string scene;
    std::string output;
    std::optional<long long> width, height, spp, threads, max_depth;
    std::optional<std::uint64_t> seed;
    bool quiet = false;
    bool aovs = false;
};

// Where the image goes: -o, else the scene's film.filename, else <scene stem>.png in the current
// folder (glint.png for the built-in demo).
std::filesystem::path output_path(const RenderArgs& args, const glint::RenderJob& job) {
    if (!args.output.empty()) return args.output;
    if (!job.filename.empty()) return job.filename;
    if (args.scene.empty()) return "glint.png";
    return std::filesystem::path(args.scene).stem().string() + ".png";
}

int run_render(const RenderArgs& args) {
    auto sources = std::make_shared<glint::SourceFiles>();
    const glint::SceneDescription description =
        args.scene.empty() ? glint::parse_scene(glint::kDemoScene, glint::kDemoSceneName, sources)
                           : glint::load_scene_file(args.scene, sources);
    glint::Overrides overrides{args.width,  args.height, args.spp, args.max_depth,
                               args.threads, args.seed,   args.aovs};
    glint::RenderJob job = glint::build(description, overrides, sources);
    const std::filesystem::path out = output_path(args, job);
    glint::check_writable(out);  // fail before rendering, not after
    if (job.aovs && glint::image_format_for(out) != glint::ImageFormat::kExr) {
        throw glint::IoError(fmt::format(
            "{}: AOVs (albedo, normal, depth) are written as EXR channels; use an .exr output",
            out.string()));
    }

    const auto mode = args.quiet                 ? glint::ProgressMode::kQuiet
                      : ::isatty(::fileno(stderr)) ? glint::ProgressMode::kBar
                                                   : glint::ProgressMode::kSummary;
    glint::Film film(job.width, job.height);
    if (job.aovs) film.enable_aovs();
    glint::Progress progress(mode, stderr,
                             static_cast<std::uint64_t>(job.width) * static_cast<std::uint64_t>(job.height));
    const glint::RenderStats stats =
        glint::render(job.scene, job.camera, *job.integrator, job.options, film, &progress);
    glint::write_image(out, film, job.display);
    progress.finish(stats, job.width, job.height, job.options.spp);
    if (!args.quiet) fmt::print(stderr, "wrote {}\n", out.string());
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"glint: a ray tracer. Renders YAML or JSON scene files (the article's camera and "
                 "Whitted shading with shadows and reflections, or physically based path "
                 "tracing with area lights, metals, glass and HDR environments; spheres, planes, "
                 "quads, disks, triangles, polygons and boxes; image textures; depth of field) "
                 "to PNG, EXR or PPM.",
                 "glint"};
    app.set_version_flag("--version", std::string("glint ") + GLINT_VERSION);
    app.require_subcommand(1);

    RenderArgs args;
    CLI::App* render = app.add_subcommand(
        "render", "Render a scene file (YAML or JSON); with no SCENE, the built-in demo "
                  "(the article's Figure 14) to glint.png");
    render->add_option("SCENE", args.scene, "Scene file (.yaml, .yml or .json)");
    render->add_option("-o,--output", args.output,
                       "Output image; the format comes from the extension: .png (8-bit), "
                       ".exr (linear float), .ppm (8-bit)");
    render->add_option("--width", args.width, "Film width in pixels (overrides the scene)");
    render->add_option("--height", args.height, "Film height in pixels (overrides the scene)");
    render->add_option("--spp", args.spp,
                       "Samples per pixel: 1 samples the pixel centre, more are low-discrepancy "
                       "samples averaged over the pixel (anti-aliasing, and the path tracer's "
                       "noise falls as 1/sqrt(spp))");
    render->add_option("--threads", args.threads, "Worker threads (0 or absent: all cores)");
    render->add_option("--seed", args.seed, "Sampler seed (overrides the scene)");
    render->add_option("--max-depth", args.max_depth,
                       "Path length: whitted's reflection depth (the camera ray is depth 0), "
                       "path's scattering events (1 = direct light only)");
    render->add_flag("--aovs", args.aovs,
                     "Also write albedo, normal and depth (for denoisers) as EXR channels "
                     "albedo.R/G/B, N.X/Y/Z and Z; needs an .exr output");
    render->add_flag("-q,--quiet", args.quiet, "Print nothing but errors");

    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        return app.exit(e);
    }

    try {
        return run_render(args);
    } catch (const glint::SceneError& e) {
        std::fputs(e.what(), stderr);
        const std::size_t n = e.diagnostics().size();
        fmt::print(stderr, "glint: {} error{}; no image written\n", n, n == 1 ? "" : "s");
    } catch (const glint::IoError& e) {
        fmt::print(stderr, "glint: error: {}\n", e.what());
    } catch (const std::bad_alloc&) {
        fmt::print(stderr, "glint: error: out of memory\n");
    } catch (const std::exception& e) {
        fmt::print(stderr, "glint: error: {}\n", e.what());
    }
    return 1;
}
