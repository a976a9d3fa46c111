// luxtrace command line (docs/REFERENCE.md §1). Thin: parse, call the library, map errors
// to exit codes.
#include "cli_reference.hpp"
#include "commands.hpp"
#include "light_scene_summary.hpp"
#include "luxtrace/core/count.hpp"
#include "luxtrace/core/error.hpp"
#include "luxtrace/core/text.hpp"
#include "luxtrace/io/result_data.hpp"
#include "luxtrace/io/result_file.hpp"
#include "luxtrace/io/xdmf.hpp"
#include "luxtrace/reduction/communicator.hpp"
#include "luxtrace/run/simulation.hpp"
#include "luxtrace/run/write_steps.hpp"
#include "luxtrace/sampler/photon_sampler.hpp"
#include "luxtrace/scene/scene.hpp"
#include "luxtrace/tracer/embree_scene.hpp"
#include "luxtrace/tracer/probe.hpp"
#include "result_summary.hpp"
#include "scene_summary.hpp"

#include <CLI/CLI.hpp>

#include <atomic>
#include <cmath>
#include <csignal>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <optional>

namespace fs = std::filesystem;
using namespace luxtrace;

namespace {

// The scene: one TOML scene file, or Radiance model files (sky first, as oconv takes them)
// with a sensor file.
struct SceneArgs {
    std::vector<std::string> files;
    std::string sensors;
    std::optional<double> sensor_radius_m, scale;
    std::optional<double> sensors_target;  // run's --target with --sensors: on the sensors

    bool radiance() const { return !files.empty() && is_radiance_file(files.front()); }
    // As the user would type them again (for "continue with").
    std::string command_line() const {
        std::string s;
        for (const std::string& f : files) s += (s.empty() ? "" : " ") + f;
        if (!sensors.empty()) s += " --sensors " + sensors;
        if (sensor_radius_m) s += " --sensor-radius " + shortest_decimal(*sensor_radius_m);
        if (scale) s += " --scale " + shortest_decimal(*scale);
        return s;
    }
};

Scene load_scene_args(const SceneArgs& a, const AnnualSkyShare& sky_share = {}) {
    if (!a.radiance()) {
        if (a.files.size() != 1)
            throw InputError("give one scene file (TOML), or Radiance models (.rad) with --sensors; got " +
                             std::to_string(a.files.size()) + " files");
        if (!a.sensors.empty() || a.sensor_radius_m || a.scale)
            throw InputError("--sensors, --sensor-radius and --scale apply to Radiance models (.rad); a scene file "
                             "names its own sensors ([[detector]] type = \"points\") and [[radiance]] scale");
        return load_scene(a.files.front(), sky_share);
    }
    RadianceRun run;
    for (const std::string& f : a.files) {
        if (!is_radiance_file(f))
            throw InputError(f + ": give either one scene file (TOML) or Radiance files (.rad, .mat, .sky), not both");
        run.models.emplace_back(f);
    }
    if (!a.sensors.empty()) run.sensors = a.sensors;
    if (a.sensor_radius_m) {
        if (!(*a.sensor_radius_m > 0.0)) throw InputError("--sensor-radius: must be positive");
        if (a.sensors.empty()) throw InputError("--sensor-radius: applies with --sensors");
        run.sensor_radius_m = a.sensor_radius_m;
    }
    if (a.scale) {
        if (!(*a.scale > 0.0 && std::isfinite(*a.scale))) throw InputError("--scale: must be positive");
        run.scale = *a.scale;
    }
    if (a.sensors_target && !a.sensors.empty()) {
        if (!(*a.sensors_target > 0.0)) throw InputError("--target: must be positive");
        run.sensors_relative_error = a.sensors_target;
    }
    return load_radiance_scene(run);
}

void add_scene_options(CLI::App* app, SceneArgs& a, const std::string& verb) {
    app->add_option("scene", a.files,
                    "scene file (TOML), or Radiance files (.rad, .mat, .sky: sky first, as oconv takes them) to " +
                        verb)
        ->required();
    app->add_option("--sensors", a.sensors, "Radiance models: a sensor file (.pts, x y z dx dy dz a line)");
    app->add_option("--sensor-radius", a.sensor_radius_m,
                    "Radiance models: the sensors' disc radius in m (default: half the smallest spacing)");
    app->add_option("--scale", a.scale, "Radiance models: metres per model unit (0.3048 for feet; default 1)");
}

struct RunArgs {
    SceneArgs scene;
    std::string photons, seed, report_every_photons;
    std::optional<double> time_limit, target, report_every, checkpoint_every;
    std::optional<int> threads;
    std::optional<std::int64_t> replicates;
    std::string output, checkpoint, restart, sampler;
    std::string inject_fault;  // tests (hidden): run/write_steps.hpp
    std::string annual_parts;  // tests (hidden): "nodes" or "ranks", RunOptions::annual_parts_per_rank
    bool quiet = false;
};

std::uint64_t parse_count_option(const std::string& opt, const std::string& text) {
    if (const auto v = parse_count(text)) return *v;
    throw InputError(opt + ": '" + text + "' is not a count (use forms like 1000000, 1e6 or 100M)");
}

// Command-line values win over the scene's [run] table.
void apply_overrides(Scene& scene, const RunArgs& a) {
    RunConfig& run = scene.run;
    if (!a.photons.empty()) run.photons = parse_count_option("--photons", a.photons);
    if (run.photons == 0) throw InputError("--photons: must be positive");
    if (!a.seed.empty()) run.seed = parse_count_option("--seed", a.seed);
    if (a.time_limit) {
        if (!(*a.time_limit >= 0.0)) throw InputError("--time-limit: must not be negative");
        run.time_limit_s = *a.time_limit;
    }
    if (a.report_every) run.report_every_s = *a.report_every;
    if (!a.report_every_photons.empty()) {
        run.report_every_photons = parse_count_option("--report-every-photons", a.report_every_photons);
        if (run.report_every_photons == 0) throw InputError("--report-every-photons: must be positive");
    }
    if (a.checkpoint_every) {
        if (!(*a.checkpoint_every >= 0.0)) throw InputError("--checkpoint-every: must not be negative");
        run.checkpoint_every_s = *a.checkpoint_every;
    }
    if (a.target) {
        if (!(*a.target > 0.0)) throw InputError("--target: must be positive");
        if (run.targets.empty()) run.targets.push_back(Target{});
        run.targets.front().relative_error = *a.target;
        run.targets.front().absolute_error = 0.0;
        run.targets.front().photons_received = 0.0;
    }
    if (!a.output.empty()) run.output = a.output;
    if (!a.sampler.empty()) {
        if (const std::string why = sampler_unavailable(a.sampler); !why.empty()) throw InputError("--sampler: " + why);
        run.sampler = a.sampler;
    }
    if (a.replicates) {
        if (const std::string why = replicates_invalid(*a.replicates); !why.empty())
            throw InputError("--replicates: " + why);
        run.replicates = static_cast<std::uint32_t>(*a.replicates);
    }
    if (!a.checkpoint.empty()) run.checkpoint = a.checkpoint;
    if (!a.restart.empty()) {
        // A restart continues the checkpoint's photon sequence: same seed and sampler, and
        // by default the same budget.
        const ResultFile ck(a.restart);
        if (!ck.is_checkpoint()) throw InputError(a.restart + ": not a checkpoint (a result file cannot be continued)");
        const std::uint64_t seed = ck.run_info().seed;
        if (!a.seed.empty() && run.seed != seed)
            throw InputError("--seed: the checkpoint " + a.restart + " was made with seed " + std::to_string(seed));
        run.seed = seed;
        run.sampler = ck.run_info().sampler;
        // The checkpoint's R unless --replicates names one; run_simulation refuses a
        // different one, as it does a different seed or sampler.
        if (!a.replicates && ck.replicates() > 0) run.replicates = static_cast<std::uint32_t>(ck.replicates());
        if (const std::string why = sampler_unavailable(run.sampler); !why.empty())
            throw InputError(a.restart + ": the checkpoint's sampler: " + why);
        if (a.photons.empty()) run.photons = ck.checkpoint_budget();
    }
    const fs::path out(run.output);
    const fs::path dir = out.parent_path().empty() ? fs::path(".") : out.parent_path();
    if (!fs::is_directory(dir))
        throw InputError(run.output + ": output directory '" + dir.string() + "' does not exist");
    if (fs::is_directory(out)) throw InputError(run.output + ": output path is a directory");
}

// Set by SIGTERM / SIGUSR1 (a signal handler can only reach static storage); the run
// checkpoints and stops at its next reduction.
std::atomic<int> g_stop_signal{0};

extern "C" void on_stop_signal(int sig) { g_stop_signal.store(sig); }

// Rank 0, once the result is written: its companion, its summary and where it all is.
void report_result(const RunSummary& s, const RunArgs& a) {
    // The ParaView/VisIt companion (here, not in luxtrace_run, which does not link the
    // render library). The result is written already: a failure only warns.
    fs::path xdmf_path = fs::path(s.output).replace_extension(".xdmf");
    if (xdmf_path == fs::path(s.output)) xdmf_path += ".xdmf";  // never over the result
    bool xdmf_written = false;
    try {
        write_xdmf(s.output, xdmf_path);
        xdmf_written = true;
    } catch (const std::exception& e) {
        std::cerr << "luxtrace: warning: " << xdmf_path.string() << " not written: " << e.what() << '\n';
    }
    if (!a.quiet) print_result_summary(ResultFile(s.output), std::cout);
    if (!s.checkpoint.empty()) std::cout << "checkpoint: " << fs::absolute(s.checkpoint).string() << '\n';
    std::cout << "result: " << fs::absolute(s.output).string() << " (written in " << std::fixed << std::setprecision(2)
              << s.result_write_s << " s";
    // Where the time went: the estimates, the annual metrics, the file, the Ladybug folder.
    for (std::size_t i = 0; i < s.result_steps_s.size(); ++i)
        std::cout << (i == 0 ? ": " : ", ") << s.result_steps_s[i].first << ' ' << s.result_steps_s[i].second;
    std::cout << ")" << std::defaultfloat << '\n';
    for (const std::string& table : s.sensor_tables)
        std::cout << "sensor table: " << fs::absolute(table).string() << '\n';
    if (xdmf_written && !a.quiet) std::cout << "xdmf: " << fs::absolute(xdmf_path).string() << '\n';
    if (s.exit_code == 3)
        std::cout << "stopped early (" << s.stop_reason << "); continue with: luxtrace run " << a.scene.command_line()
                  << " --restart " << s.checkpoint << '\n';
}

int cmd_run(const Communicator& comm, const RunArgs& a) {
    SceneArgs scene_args = a.scene;
    scene_args.sensors_target = a.target;  // a Radiance model's sensors are what --target is about
    const double load0 = comm.wtime();
    // The ranks share building an annual year of skies: each its part of the hours, then
    // all of them to everyone (every rank reads the same input and fails, if it does, the
    // same way before this).
    AnnualSkyShare sky_share;
    sky_share.part = comm.rank();
    sky_share.parts = comm.size();
    sky_share.gather = [&comm](std::vector<double>& luminance, const std::vector<std::size_t>& offsets) {
        comm.allgather_parts(luminance, offsets);
    };
    Scene scene = load_scene_args(scene_args, sky_share);
    const double load_s = comm.wtime() - load0;
    apply_overrides(scene, a);
    if (a.threads && *a.threads < 1) throw InputError("--threads: must be at least 1");
    RunOptions opt;
    opt.threads = a.threads.value_or(0);
    opt.quiet = a.quiet;
    opt.load_s = load_s;
    opt.restart = a.restart;
    opt.scene_args = a.scene.command_line();
    if (!a.inject_fault.empty()) {
        if (const std::string why = injected_fault_invalid(a.inject_fault); !why.empty())
            throw InputError("--inject-fault: " + why);
        opt.inject_fault = a.inject_fault;
    }
    if (!a.annual_parts.empty() && a.annual_parts != "nodes" && a.annual_parts != "ranks")
        throw InputError("--annual-parts: \"" + a.annual_parts + "\" is neither nodes nor ranks");
    opt.annual_parts_per_rank = a.annual_parts == "ranks";
    opt.signal = &g_stop_signal;
    std::signal(SIGTERM, on_stop_signal);
    std::signal(SIGUSR1, on_stop_signal);
    if (comm.is_root() && !a.quiet)
        std::cout << "luxtrace: " << scene.file.string() << ": " << scene.triangle_count() << " triangles, "
                  << describe_lights(scene) << ", " << scene.run.photons << " photons on " << comm.size()
                  << " rank(s) x " << (opt.threads > 0 ? opt.threads : available_cores()) << " thread(s)\n"
                  << std::flush;
    // What the scene's loading noticed (a sun below the horizon, portals beside exterior
    // geometry, ...): `check` lists the same, with the probe's findings.
    if (comm.is_root() && !a.quiet)
        for (const std::string& w : scene.warnings) std::cerr << "luxtrace: warning: " << w << '\n';
    const RunSummary s = run_simulation(scene, comm, opt, std::cout);
    if (s.failed) {
        // Raised inside a tracing thread (the rank that saw it says what), or while writing
        // after tracing (rank 0 says what, and where the tallies are).
        if (!s.error.empty()) {
            if (s.exit_code == kExitBadInput || s.exit_code == kExitWriteFailed || s.write_failed)
                std::cerr << "luxtrace: error: " << s.error << '\n';
            else std::cerr << "luxtrace: internal error on rank " << comm.rank() << ": " << s.error << '\n';
        }
        return s.exit_code;
    }
    // The result is written: what follows only reports it, and a failure there warns.
    if (comm.is_root()) {
        try {
            report_result(s, a);
        } catch (const std::exception& e) {
            std::cerr << "luxtrace: warning: the result " << s.output
                      << " is written, but reporting it failed: " << e.what() << '\n';
        }
    }
    return s.exit_code;
}

int cmd_check(const SceneArgs& args) {
    const Scene scene = load_scene_args(args);
    const EmbreeScene embree(scene);
    std::vector<std::string> warnings = scene.warnings;
    for (std::string& w : probe_scene(scene, embree)) warnings.push_back(std::move(w));
    print_scene_summary(scene, warnings, std::cout);
    return 0;
}

int cmd_info(const std::string& path, const std::optional<std::string>& scene) {
    if (scene) {
        print_light_scene(ResultFile(path), *scene, std::cout);
        return 0;
    }
    print_result_summary(ResultFile(path), std::cout);
    return 0;
}

// Every subcommand, and what its arguments and options fill (the CLI keeps pointers
// into it: it stays where it was made).
struct CommandLine {
    CLI::App* run = nullptr;
    RunArgs run_args;
    CLI::App* check = nullptr;
    SceneArgs check_args;
    CLI::App* info = nullptr;
    std::string info_path;
    std::optional<std::string> info_scene;
    CLI::App* render = nullptr;
    RenderArgs render_args;
    CLI::App* photometry = nullptr;
    std::vector<std::string> photometry_files;
    int lamp_set = 1;
    CLI::App* xdmf = nullptr;
    std::string xdmf_result, xdmf_output;
    CLI::App* reference = nullptr;
    std::string reference_part;
};

void add_run_command(CLI::App& app, CommandLine& c) {
    RunArgs& ra = c.run_args;
    auto* run = c.run = app.add_subcommand("run", "simulate a scene and write the result file");
    add_scene_options(run, ra.scene, "simulate");
    run->add_option("--photons", ra.photons,
                    "photon budget (1000000, 1e6 and 1M are the same); with --restart the new budget, at least the "
                    "checkpoint's photons");
    run->add_option("--time-limit", ra.time_limit, "wall-time limit in seconds");
    run->add_option("--target", ra.target,
                    "relative error goal of the first [[run.target]] (a global target if the scene has none; with "
                    "Radiance models and --sensors, the sensors' error pooled by eq. 9)");
    run->add_option("--seed", ra.seed, "random seed (a restart keeps the checkpoint's)");
    run->add_option("--threads", ra.threads, "threads per rank (default: all cores given to the rank)");
    run->add_option("--output", ra.output, "result file (.h5), relative to the working directory");
    run->add_option("--checkpoint", ra.checkpoint, "checkpoint file (default: OUTPUT.checkpoint.h5)");
    run->add_option("--checkpoint-every", ra.checkpoint_every, "seconds between checkpoints");
    run->add_option("--restart", ra.restart, "continue the run a checkpoint holds, on any number of ranks");
    run->add_option("--report-every", ra.report_every, "seconds between reductions and progress lines");
    run->add_option("--report-every-photons", ra.report_every_photons,
                    "reduce and report every N photons instead (a history that is the same on any machine)");
    run->add_option("--sampler", ra.sampler, "random (Philox) | sobol (Owen-scrambled, docs/QMC.md)");
    run->add_option("--replicates", ra.replicates, "sobol: independent randomisations R, even (default 8)");
    run->add_flag("--quiet", ra.quiet, "no progress output");
    // Hidden (group ""): tests make one step of a write after tracing fail (docs/RELIABILITY.md).
    run->add_option("--inject-fault", ra.inject_fault, "FILE:STEP of a write after tracing that fails (tests)")
        ->group("");
    // Hidden: tests share the annual post-processing among the ranks of one node.
    run->add_option("--annual-parts", ra.annual_parts, "nodes | ranks: who shares the annual post-processing (tests)")
        ->group("");
}

void add_check_and_info_commands(CLI::App& app, CommandLine& c) {
    c.check = app.add_subcommand("check", "parse and validate a scene, print a summary");
    add_scene_options(c.check, c.check_args, "check");
    c.info = app.add_subcommand("info", "print the stored summary of a result file");
    c.info->add_option("result", c.info_path, "result file (.h5)")->required();
    c.info->add_option("--scene", c.info_scene,
                       "light groups at these weights, e.g. \"a=0.5,b=1\" (groups not named are off): the detector "
                       "means (and mean daylight factors) and the global map with their errors, recombined from the "
                       "result's light groups");
}

void add_render_command(CLI::App& app, CommandLine& c) {
    RenderArgs& rd = c.render_args;
    auto* render = c.render =
        app.add_subcommand("render", "rendered views of a result (detector pictures: python3 -m luxtrace.plot)");
    render->add_option("result", rd.result, "result file (.h5)")->required();
    render->add_option("--camera", rd.camera, "position,target[,up] as 6 or 9 comma-separated numbers");
    render->add_option("--view", rd.camera_name, "name of a [[camera]] in the scene file");
    render->add_option("--scene", rd.light_scene, "render a [[light_scene]] of the run (its map and dimmed lights)");
    render->add_option("--fov", rd.fov_deg, "horizontal field of view in degrees");
    render->add_option("--size", rd.size, "image size WxH, e.g. 800x600");
    render->add_option("-o,--output", rd.output, "image file (.png; luminance also as .exr)");
    render->add_option("--tonemap", rd.tonemap, "auto | exposure | falsecolour");
    render->add_option("--exposure", rd.exposure, "exposure mapping: luminance (cd/m^2) shown as white");
    render->add_option("--gamma", rd.gamma, "display gamma of the exposure mapping");
    render->add_option("--falsecolour-max", rd.falsecolour_max, "top of the false-colour scale (cd/m^2)");
    render->add_option("--samples", rd.samples, "rays per pixel");
    render->add_option("--threads", rd.threads, "threads (default: all cores)");
}

void add_photometry_and_xdmf_commands(CLI::App& app, CommandLine& c) {
    c.photometry = app.add_subcommand("photometry", "read IES or EULUMDAT files and print what luxtrace makes of them");
    c.photometry->add_option("files", c.photometry_files, "IES LM-63 or EULUMDAT files")->required();
    c.photometry->add_option("--lamp-set", c.lamp_set, "EULUMDAT: the lamp set to scale by (default 1)");
    c.xdmf = app.add_subcommand("export-xdmf", "write the ParaView/VisIt companion (.xdmf) of a result");
    c.xdmf->add_option("result", c.xdmf_result, "result file (.h5)")->required();
    c.xdmf->add_option("-o,--output", c.xdmf_output, "XDMF file (default: RESULT.xdmf)");
}

// Hidden: the reference tables of docs/REFERENCE.md that are made from the program itself.
void add_reference_command(CLI::App& app, CommandLine& c) {
    c.reference = app.add_subcommand("reference", "print the reference tables made from the program")->group("");
    c.reference->add_option("part", c.reference_part, "cli: the command line")
        ->required()
        ->check(CLI::IsMember({"cli"}));
}

// The parsed subcommand, its errors mapped to exit codes.
int run_command(const Communicator& comm, const CLI::App& app, const CommandLine& c) {
    try {
        if (*c.run) return cmd_run(comm, c.run_args);
        if (*c.check) return comm.is_root() ? cmd_check(c.check_args) : 0;
        if (*c.info) return comm.is_root() ? cmd_info(c.info_path, c.info_scene) : 0;
        if (*c.render) return comm.is_root() ? cmd_render(c.render_args) : 0;
        if (*c.photometry) return comm.is_root() ? cmd_photometry(c.photometry_files, c.lamp_set) : 0;
        if (*c.xdmf) return comm.is_root() ? cmd_export_xdmf(c.xdmf_result, c.xdmf_output) : 0;
        if (*c.reference) {
            if (comm.is_root()) print_cli_reference(app, std::cout);
            return 0;
        }
    } catch (const InputError& e) {
        // Every rank reads the same input and fails the same way; one message is enough.
        if (comm.is_root()) std::cerr << "luxtrace: error: " << e.what() << '\n';
        return kExitBadInput;
    } catch (const std::exception& e) {
        std::cerr << "luxtrace: internal error on rank " << comm.rank() << ": " << e.what() << '\n';
        comm.abort(1);
    }
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    Communicator comm(&argc, &argv);
    CLI::App app{"luxtrace: forward Monte Carlo photon simulation for lighting"};
    app.name("luxtrace");  // not argv[0]: the reference (run_command) must not depend on the path
    app.require_subcommand(1);
    app.set_version_flag("--version", "luxtrace " LUXTRACE_VERSION, "print the version and git commit, then exit");
    CommandLine command_line;
    add_run_command(app, command_line);
    add_check_and_info_commands(app, command_line);
    add_render_command(app, command_line);
    add_photometry_and_xdmf_commands(app, command_line);
    add_reference_command(app, command_line);
    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        if (comm.is_root()) app.exit(e);
        return 0;
    } catch (const CLI::ParseError& e) {
        if (comm.is_root()) app.exit(e);
        return e.get_exit_code() == 0 ? 0 : kExitBadInput;
    }
    return run_command(comm, app, command_line);
}
