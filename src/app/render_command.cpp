// `luxtrace render`: pictures of a result. Thin: check the options, load, call the render
// library, say what was written.
#include "commands.hpp"

#include "luxtrace/core/error.hpp"
#include "luxtrace/render/camera.hpp"
#include "luxtrace/render/image_io.hpp"
#include "luxtrace/render/renderer.hpp"
#include "luxtrace/render/tone_map.hpp"
#include "luxtrace/tracer/embree_scene.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <optional>
#include <tuple>

namespace luxtrace {

namespace fs = std::filesystem;

namespace {

struct ViewJob {
    Camera camera;
    fs::path png, exr;
};

void check_options(const RenderArgs& a) {
    if (a.tonemap != "auto" && a.tonemap != "exposure" && a.tonemap != "falsecolour" && a.tonemap != "falsecolor")
        throw InputError("--tonemap: '" + a.tonemap + "' is not one of auto, exposure, falsecolour");
    if (a.samples < 1) throw InputError("--samples: must be at least 1");
    if (a.threads < 0) throw InputError("--threads: must not be negative");
    if (!(a.gamma > 0.0 && std::isfinite(a.gamma))) throw InputError("--gamma: must be positive");
    if (a.exposure && !(*a.exposure > 0.0 && std::isfinite(*a.exposure)))
        throw InputError("--exposure: the luminance shown as white must be positive");
    if (a.falsecolour_max && !(*a.falsecolour_max > 0.0 && std::isfinite(*a.falsecolour_max)))
        throw InputError("--falsecolour-max: must be positive");
    if (a.fov_deg && !(*a.fov_deg > 0.0 && *a.fov_deg < 180.0))
        throw InputError("--fov: " + std::to_string(*a.fov_deg) + " must lie in (0, 180) degrees");
    if (!a.camera.empty() && !a.camera_name.empty()) throw InputError("--camera and --view: give one of them");
}

// Where the PNG and EXR of a view go: -o names the PNG (or the EXR, or a stem);
// with several views each gets its camera name appended.
ViewJob place(const RenderArgs& a, const Camera& cam, bool several) {
    ViewJob job{cam, {}, {}};
    fs::path base;
    if (a.output.empty()) {
        const fs::path result(a.result);
        base = result.parent_path() / (result.stem().string() + "_" + cam.name + ".png");
    } else {
        base = a.output;
        const std::string ext = base.extension().string();
        if (!ext.empty() && ext != ".png" && ext != ".exr")
            throw InputError("-o: '" + a.output + "' must end in .png or .exr (both are written)");
        if (several) base = base.parent_path() / (base.stem().string() + "_" + cam.name + ".png");
        const fs::path dir = base.parent_path().empty() ? fs::path(".") : base.parent_path();
        if (!fs::is_directory(dir)) throw InputError("-o: folder '" + dir.string() + "' does not exist");
    }
    job.png = fs::path(base).replace_extension(".png");
    job.exr = fs::path(base).replace_extension(".exr");
    if (fs::is_directory(job.png) || fs::is_directory(job.exr))
        throw InputError("-o: '" + job.png.string() + "' is a folder");
    return job;
}

std::vector<ViewJob> plan_views(const RenderArgs& a, const Scene& scene) {
    std::vector<Camera> cams;
    if (!a.camera.empty()) {
        Camera c = parse_camera_option(a.camera);
        c.name = "view";
        cams.push_back(c);
    } else if (!a.camera_name.empty()) {
        const auto it = std::find_if(scene.cameras.begin(), scene.cameras.end(),
                                     [&](const Camera& c) { return c.name == a.camera_name; });
        if (it == scene.cameras.end()) {
            std::string have;
            for (const Camera& c : scene.cameras) have += (have.empty() ? "" : ", ") + c.name;
            throw InputError("--view: the scene " + scene.file.string() + " has no [[camera]] named '" + a.camera_name +
                             "'" + (have.empty() ? " (it defines none)" : " (it has: " + have + ")"));
        }
        cams.push_back(*it);
    } else {
        cams = scene.cameras;
        if (cams.empty())
            throw InputError(a.result + ": nothing to render: give --camera or --view (the scene " +
                             scene.file.string() + " defines no [[camera]])");
    }
    const std::optional<std::pair<int, int>> size = a.size.empty() ? std::nullopt
                                                                   : std::optional(parse_size_option(a.size));
    std::vector<ViewJob> jobs;
    for (Camera& c : cams) {
        if (a.fov_deg) c.fov_deg = *a.fov_deg;
        if (size) std::tie(c.width, c.height) = *size;
        PinholeCamera{c};  // validates: throws InputError naming the camera
        jobs.push_back(place(a, c, cams.size() > 1));
    }
    return jobs;
}

std::string fmt(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.4g", v);
    return buf;
}

}  // namespace

int cmd_render(const RenderArgs& args) {
    check_options(args);
    if (!args.size.empty()) parse_size_option(args.size);
    if (!args.camera.empty()) parse_camera_option(args.camera);
    // Everything is read and checked before anything is written. (Detector pictures are
    // drawn by the Python package: python3 -m luxtrace.plot, scripts/plot_detector.py.)
    RenderInput input = load_render_input(args.result, args.light_scene);
    const std::vector<ViewJob> jobs = plan_views(args, input.scene);

    const EmbreeScene embree(input.scene);
    const Renderer renderer(input.scene, embree, std::move(input.secondary_lx), std::move(input.light_weight));
    RenderOptions opt;
    opt.samples = args.samples;
    opt.threads = args.threads;
    for (const ViewJob& job : jobs) {
        const auto t0 = std::chrono::steady_clock::now();
        const LuminanceImage image = renderer.render(PinholeCamera(job.camera), opt);
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        AutoToneParams tone;
        const DisplayImage auto_image = tone_map_auto(image, args.gamma, &tone);
        std::string how;
        if (args.tonemap == "auto") {
            write_png(job.png, auto_image);
            how = "auto tone mapping: adaptation " + fmt(tone.adaptation_cd_m2) + " cd/m^2, white " +
                  fmt(tone.white_cd_m2) + " cd/m^2";
        } else if (args.tonemap == "exposure") {
            const double white = args.exposure.value_or(tone.white_cd_m2);
            write_png(job.png, tone_map_exposure(image, white, args.gamma));
            how = "exposure: white " + fmt(white) + " cd/m^2, gamma " + fmt(args.gamma);
        } else {
            const FalseColourScale scale = FalseColourScale::log_below(args.falsecolour_max.value_or(tone.white_cd_m2));
            write_png(job.png, tone_map_false_colour(image, scale), &scale);
            how = "false colour " + fmt(scale.min_cd_m2) + " .. " + fmt(scale.max_cd_m2) + " cd/m^2 (log)";
        }
        write_exr(job.exr, image);
        std::cout << "view '" << job.camera.name << "': " << image.width << "x" << image.height << ", " << opt.samples
                  << " rays/pixel, rendered in " << fmt(seconds) << " s; " << how << '\n'
                  << "  " << fs::absolute(job.png).string() << "\n  " << fs::absolute(job.exr).string()
                  << " (luminance, cd/m^2)\n";
    }
    return 0;
}

}  // namespace luxtrace
