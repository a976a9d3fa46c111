// [run] and its [[run.target]] -> the scene's run settings (docs/REFERENCE.md §2). The
// command line overrides them (src/app).
#include "luxtrace/annual/annual_grid.hpp"
#include "luxtrace/sampler/photon_sampler.hpp"
#include "luxtrace/stats/annual_metrics.hpp"
#include "scene_loader.hpp"

#include <algorithm>
#include <sstream>

namespace luxtrace::detail {

namespace {

namespace fs = std::filesystem;

struct RunReader : StepReader {
    using StepReader::StepReader;

    void parse_run(TableReader& root) {
        RunConfig& run = scene.run;
        run.output = (fs::path(load.file.stem().string() + ".h5")).string();
        // An annual run's thousands of groups share one surface map: its detectors keep them apart.
        if (load.scene.annual) run.group_maps = false;
        const toml::table* t = root.table("run");
        if (t == nullptr) return;
        TableReader r(*t, fname, "[run]", "run");
        run.seed = r.count("seed").value_or(run.seed);
        run.photons = r.count("photons").value_or(run.photons);
        if (run.photons == 0) r.fail("photons", "must be positive");
        auto nonneg = [&](const std::string& key, double def) {
            const double v = r.number(key).value_or(def);
            if (!(v >= 0.0)) r.fail(key, "must not be negative");
            return v;
        };
        run.time_limit_s = nonneg("time_limit_s", run.time_limit_s);
        run.report_every_s = nonneg("report_every_s", run.report_every_s);
        run.report_every_photons = r.count("report_every_photons").value_or(0);
        run.checkpoint_every_s = nonneg("checkpoint_every_s", run.checkpoint_every_s);
        if (auto o = r.string("output")) run.output = load.resolve(*o).string();
        if (auto c = r.string("checkpoint")) run.checkpoint = load.resolve(*c).string();
        run.sampler = r.string("sampler").value_or(run.sampler);
        if (const std::string why = sampler_unavailable(run.sampler); !why.empty()) r.fail("sampler", why);
        if (const auto reps = r.integer("replicates")) {
            if (const std::string why = replicates_invalid(*reps); !why.empty()) r.fail("replicates", why);
            run.replicates = static_cast<std::uint32_t>(*reps);
        }
        if (const auto mb = r.integer("max_bounces")) {
            if (*mb < 1 || *mb > 1000000) r.fail("max_bounces", "must lie in [1, 1000000]");
            run.max_bounces = static_cast<int>(*mb);
        }
        run.group_maps = r.boolean("group_maps").value_or(run.group_maps);
        run.bvh_quality = r.string("bvh_quality").value_or(run.bvh_quality);
        if (run.bvh_quality != "auto" && run.bvh_quality != "low" && run.bvh_quality != "medium" &&
            run.bvh_quality != "high")
            r.fail("bvh_quality",
                   "expected \"auto\", \"low\", \"medium\" or \"high\", got \"" + run.bvh_quality + "\"");
        if (load.scene.annual && run.group_maps)
            r.fail("group_maps", "an annual run keeps one surface map for its sky patches and suns");
        if (const toml::array* targets = r.array("target"))
            for (std::size_t i = 0; i < targets->size(); ++i) {
                const toml::table* tt = (*targets)[i].as_table();
                if (tt == nullptr) r.fail("target", "expected [[run.target]] tables");
                run.targets.push_back(parse_target(*tt, i));
            }
        r.finish();
    }

    Target parse_target(const toml::table& t, std::size_t i) {
        TableReader r(t, fname, "[[run.target]] #" + std::to_string(i + 1), "run.target");
        Target g;
        g.on = r.string("on").value_or("global");
        if (g.on.rfind("observer:", 0) == 0) target_on_observer(r, g);
        else if (g.on.rfind("annual:", 0) == 0) target_on_annual_metric(r, g);
        else if (g.on != "global") target_on_detector(r, g);
        read_goal(r, g);
        read_averaging(r, g);
        read_light_scene(r, g);
        r.finish();
        return g;
    }

    // The scene's detector of that name; end() if none.
    std::vector<Detector>::const_iterator find_detector(const std::string& name) const {
        return std::find_if(scene.detectors.begin(), scene.detectors.end(),
                            [&](const Detector& d) { return d.name == name; });
    }

    // 'observer:NAME'
    void target_on_observer(const TableReader& r, Target& g) const {
        // An observer's eye detector (one cell): its relative error is E_ind's, and
        // UGR's error is 8 / ln 10 = 3.47 times it (glare/ugr.hpp).
        g.detector = g.on;
        const auto det = find_detector(g.detector);
        if (det == scene.detectors.end()) r.fail("on", "no [[observer]] is named '" + g.on.substr(9) + "'");
        g.i1 = det->nx;
        g.j1 = det->ny;
    }

    // 'annual:DETECTOR:METRIC'
    void target_on_annual_metric(const TableReader& r, Target& g) const {
        const std::string rest = g.on.substr(7);
        const auto colon = rest.rfind(':');
        if (!load.scene.annual) r.fail("on", "an annual target needs [annual]");
        if (colon == std::string::npos) r.fail("on", "expected 'annual:DETECTOR:METRIC', e.g. 'annual:desk:sda'");
        g.detector = rest.substr(0, colon);
        g.annual_metric = rest.substr(colon + 1);
        const auto det = find_detector(g.detector);
        if (det == scene.detectors.end() || !annual_grid(*det))
            r.fail("on", "no illuminance or points [[detector]] is named '" + g.detector + "'");
        if (std::none_of(std::begin(kAnnualTargetFigures), std::end(kAnnualTargetFigures),
                         [&](const AnnualGridFigure& f) { return g.annual_metric == f.name; })) {
            std::string names;
            for (const AnnualGridFigure& f : kAnnualTargetFigures)
                names += (names.empty() ? "" : ", ") + std::string(f.name);
            r.fail("on", "an annual target is on one of " + names + ", not '" + g.annual_metric + "'");
        }
        g.i1 = det->nx;
        g.j1 = det->ny;
    }

    // 'detector:NAME' or 'detector:NAME[i0:i1,j0:j1]'
    void target_on_detector(const TableReader& r, Target& g) const {
        if (g.on.rfind("detector:", 0) != 0)
            r.fail("on", "expected 'global', 'detector:NAME', 'detector:NAME[i0:i1,j0:j1]' or 'observer:NAME'");
        std::string rest = g.on.substr(9);
        const auto br = rest.find('[');
        g.detector = rest.substr(0, br);
        const auto det = find_detector(g.detector);
        if (det == scene.detectors.end()) r.fail("on", "no [[detector]] is named '" + g.detector + "'");
        if (br == std::string::npos) {
            g.i1 = det->nx;
            g.j1 = det->ny;
            return;
        }
        char close = 0;
        std::istringstream in(rest.substr(br + 1));
        char c1 = 0, c2 = 0, c3 = 0, extra = 0;
        if (!(in >> g.i0 >> c1 >> g.i1 >> c2 >> g.j0 >> c3 >> g.j1 >> close) || c1 != ':' || c2 != ',' || c3 != ':' ||
            close != ']' || (in >> extra))
            r.fail("on", "cell range must read [i0:i1,j0:j1]");
        if (!(0 <= g.i0 && g.i0 < g.i1 && g.i1 <= det->nx && 0 <= g.j0 && g.j0 < g.j1 && g.j1 <= det->ny))
            r.fail("on", "cell range lies outside the " + std::to_string(det->nx) + " x " + std::to_string(det->ny) +
                             " grid or is empty");
    }

    // Exactly one of relative_error, absolute_error, photons_received.
    static void read_goal(TableReader& r, Target& g) {
        int kinds = 0;
        if (auto v = r.number("relative_error")) {
            g.relative_error = *v;
            ++kinds;
            if (!(*v > 0)) r.fail("relative_error", "must be positive");
        }
        if (auto v = r.number("absolute_error")) {
            g.absolute_error = *v;
            ++kinds;
            if (!(*v > 0)) r.fail("absolute_error", "must be positive");
        }
        if (auto v = r.count("photons_received")) {
            g.photons_received = static_cast<double>(*v);
            ++kinds;
            if (g.detector.empty()) r.fail("photons_received", "applies to a detector target only");
        }
        if (kinds != 1) r.fail_entry("needs exactly one of relative_error, absolute_error, photons_received");
        if (!g.annual_metric.empty() && g.photons_received > 0.0)
            r.fail("photons_received", "an annual target is on a metric's error: relative_error or absolute_error");
    }

    static void read_averaging(TableReader& r, Target& g) {
        const std::string avg = r.string("averaging").value_or("quadratic");
        if (avg == "quadratic") g.averaging = Averaging::quadratic;
        else if (avg == "arithmetic") g.averaging = Averaging::arithmetic;
        else r.fail("averaging", "expected 'quadratic' or 'arithmetic'");
    }

    // `scene`: the target is on a [[light_scene]]'s estimates.
    void read_light_scene(TableReader& r, Target& g) const {
        const auto ls = r.string("scene");
        if (!ls) return;
        const auto& scenes = scene.light_scenes;
        if (std::none_of(scenes.begin(), scenes.end(), [&](const LightScene& s) { return s.name == *ls; })) {
            std::string names;
            for (const LightScene& s : scenes) names += (names.empty() ? "" : ", ") + s.name;
            r.fail("scene",
                   "no [[light_scene]] is named '" + *ls + "'" +
                       (names.empty() ? std::string(" (the scene has none)") : " (the light scenes: " + names + ")"));
        }
        if (g.detector.empty() && !scene.run.group_maps)
            r.fail("scene", "a global target on a light scene needs the surface map per light group; "
                            "[run] group_maps = false keeps one map for all groups");
        g.light_scene = *ls;
    }
};

}  // namespace

void read_run(SceneLoad& load, TableReader& root) { RunReader(load).parse_run(root); }

}  // namespace luxtrace::detail
