#include "result_summary.hpp"

#include "annual_summary.hpp"

#include "luxtrace/io/result_data.hpp"

#include "luxtrace/core/error.hpp"
#include "luxtrace/io/result_file.hpp"
#include "luxtrace/stats/daylight_metrics.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <ostream>
#include <sstream>
#include <string>
#include <vector>

namespace luxtrace {

namespace {

// Eavg, Emin, Emax and U0 stored on an illuminance detector or a task area (SPEC §4).
void print_metrics(const ResultReader& r, const std::string& g, const std::string& label, std::ostream& out) {
    auto f = [&](const char* name) { return r.attr_f64(g, name); };
    auto cell = [&](const char* name) {
        const std::vector<double> c = r.f64_attr_array(g, name);
        return c.size() == 2 ? std::to_string(static_cast<long>(c[0])) + "," + std::to_string(static_cast<long>(c[1]))
                             : std::string("?");
    };
    out << std::fixed << std::setprecision(2) << "  " << std::left << std::setw(13) << label << std::right << "Eavg "
        << f("E_avg_lx") << " +- " << f("E_avg_sigma_lx") << " lx, Emin " << f("E_min_lx") << " +- "
        << f("E_min_sigma_lx") << " lx (cell " << cell("E_min_cell") << std::defaultfloat << std::setprecision(3)
        << "; ";
    if (f("E_min_bias_lx") < 0.0)
        out << "biased low by about " << -f("E_min_bias_lx") << " lx: " << r.attr_u64(g, "E_min_competitors")
            << " cells within 3 sigma)";
    else out << "no other cell within 3 sigma)";
    out << std::fixed << std::setprecision(2) << ", Emax " << f("E_max_lx") << " +- " << f("E_max_sigma_lx")
        << " lx (cell " << cell("E_max_cell") << ")\n";
    out << std::setprecision(3) << "  " << std::setw(13) << ""
        << "U0 = Emin/Eavg " << f("U0") << " +- " << f("U0_sigma") << ", Emin/Emax " << f("E_min_over_max") << " +- "
        << f("E_min_over_max_sigma");
    if (r.attr_u64(g, "U0_unreliable") != 0)
        out << "  WARNING: Emin too noisy or biased (error or bias above 2 % of Emin, or a cell without photons): "
               "U0 not meaningful; run longer or use coarser cells";
    out << '\n';
    if (r.has_attr("/", "maintenance_factor") && r.attr_f64("/", "maintenance_factor") < 1.0)
        out << std::setprecision(2) << "  " << std::setw(13) << ""
            << "maintained Eavg " << f("E_avg_maintained_lx") << " +- " << f("E_avg_maintained_sigma_lx")
            << " lx, Emin " << f("E_min_maintained_lx") << " +- " << f("E_min_maintained_sigma_lx") << " lx, Emax "
            << f("E_max_maintained_lx") << " lx\n";
}

// A daylight_factor detector's DF figures of a grid or task area, and its EN 17037 verdict
// with what would decide it (docs/DAYLIGHT.md).
void print_daylight(const ResultReader& r, const std::string& g, std::ostream& out) {
    if (!r.has_attr(g, "DF_median_pct")) return;
    auto f = [&](const std::string& name) { return r.attr_f64(g, name); };
    auto quantile = [&](const std::string& q) {
        std::ostringstream s;
        s << std::fixed << std::setprecision(2) << f(q + "_pct") << " +- " << f(q + "_sigma_pct") << " %"
          << std::defaultfloat << std::setprecision(2) << " (bias " << f(q + "_bias_pct") << " %)";
        return s.str();
    };
    out << "  " << std::setw(13) << ""
        << "DF mean " << std::fixed << std::setprecision(2) << f("DF_mean_pct") << " +- " << f("DF_mean_sigma_pct")
        << " %, median " << quantile("DF_median") << ", exceeded over 95 % " << quantile("DF_95");
    if (r.attr_u64(g, "DF_cells_without_photons") > 0)
        out << "; " << r.attr_u64(g, "DF_cells_without_photons") << " cells without photons (errors too low)";
    out << '\n';
    if (!r.has_attr(g, "en17037_verdict")) return;
    auto criterion = [&](const char* what, const std::string& key, const std::string& q) {
        const std::string v = r.attr_str(g, "en17037_" + key + "_verdict");
        const double target = f("en17037_" + key + "_df_pct");
        out << what << ' ' << std::defaultfloat << std::setprecision(3) << target << " %: " << v;
        if (v != "undecided") return;
        const double factor = f("en17037_" + key + "_photons_factor");
        const double value = f(q + "_pct") - f(q + "_bias_pct");
        if (std::isfinite(factor))
            out << " (about " << std::setprecision(3) << factor << " x the photons would decide it)";
        else
            out << " (cannot decide: the value equals the target within " << std::setprecision(2)
                << std::max(std::abs(value - target),
                            kVerdictSigmas * std::hypot(f(q + "_sigma_pct"), f(q + "_bias_pct")))
                << " %)";
    };
    out << "  " << std::setw(13) << ""
        << "EN 17037 ";
    criterion("D_T over 50 %", "target", "DF_median");
    out << "; ";
    criterion("D_TM over 95 %", "minimum", "DF_95");
    out << "; verdict " << r.attr_str(g, "en17037_verdict") << " (95 % one-sided)";
    const double factor = f("en17037_photons_factor");
    if (r.attr_str(g, "en17037_verdict") == "undecided" && std::isfinite(factor))
        out << ", about " << std::setprecision(3) << factor << " x the photons to decide";
    out << '\n' << std::fixed << std::setprecision(2);
}

// Scene, version, sampler, ranks, photons and how the run spent its time.
void print_run(const ResultReader& r, std::ostream& out) {
    const std::uint64_t photons = r.attr_u64("/", "photons");
    const double elapsed = r.attr_f64("/", "elapsed_s");
    out << "scene          " << r.attr_str("/", "scene_file") << '\n'
        << "luxtrace       " << r.attr_str("/", "luxtrace_version") << ", sampler " << r.attr_str("/", "sampler")
        << (r.has_attr("/", "replicates") && r.attr_u64("/", "replicates") > 0
                ? " (" + std::to_string(r.attr_u64("/", "replicates")) + " replicates)"
                : std::string())
        << ", seed " << r.attr_u64("/", "seed") << '\n'
        << "run            " << r.attr_u64("/", "ranks") << " rank(s) x " << r.attr_u64("/", "threads_per_rank")
        << " thread(s), stopped by: " << r.attr_str("/", "stop_reason") << '\n'
        << "photons        " << photons << " in " << std::fixed << std::setprecision(2) << elapsed << " s ("
        << std::scientific << std::setprecision(3) << (elapsed > 0 ? photons / elapsed : 0.0) << " photons/s)\n";
    if (r.has_attr("/", "bvh_build_s"))
        out << "setup          scene loaded in " << std::fixed << std::setprecision(2) << r.attr_f64("/", "load_s")
            << " s (before the run's time), BVH built in " << r.attr_f64("/", "bvh_build_s") << " s (within it)\n";
    if (!r.has_attr("/", "reductions")) return;
    out << "reductions     " << r.attr_u64("/", "reductions") << ", tracing stalled " << std::fixed
        << std::setprecision(3) << r.attr_f64("/", "reduction_stall_s") << " s (" << std::setprecision(2)
        << (elapsed > 0 ? 100.0 * r.attr_f64("/", "reduction_stall_s") / elapsed : 0.0) << " % of the run)";
    if (r.has_attr("/", "reduction_work_s")) {
        const double work = r.attr_f64("/", "reduction_work_s");
        out << ", main thread's work " << std::setprecision(3) << work << " s (" << std::setprecision(2)
            << (elapsed > 0 ? 100.0 * work / elapsed : 0.0) << " %)";
    }
    if (r.has_attr("/", "tracing_busy"))
        out << ", tracing threads busy " << std::setprecision(1) << 100.0 * r.attr_f64("/", "tracing_busy") << " %";
    out << '\n';
}

// A checkpoint's photon ranges done and its budget.
void print_checkpoint(const ResultReader& r, std::ostream& out) {
    if (!r.has("/checkpoint/done_ranges")) return;
    const std::vector<std::uint64_t> done = r.u64("/checkpoint/done_ranges");
    std::uint64_t n = 0, highest = 0;
    for (std::size_t i = 0; i + 1 < done.size(); i += 2) {
        if (done[i + 1] < done[i])
            throw InputError(r.path().string() + ": damaged checkpoint: a done range ends before it begins");
        n += done[i + 1] - done[i];
        highest = std::max(highest, done[i + 1]);
    }
    out << "checkpoint     " << n << " photons done in " << done.size() / 2 << " range(s) below index " << highest
        << ", budget " << r.attr_u64("/checkpoint", "budget") << '\n';
}

// The global map's mean and its RMS error by each estimate the file holds.
void print_global_map(const ResultReader& r, std::ostream& out) {
    out << std::fixed << std::setprecision(2);
    // Format 2 (issue 13) adds the second-moment estimate and says which one targets use.
    const bool moment = r.has_attr("/global", "moment_sigma_lx");
    const std::string used = r.has_attr("/global", "error_estimator") ? r.attr_str("/global", "error_estimator")
                                                                      : "odd_even";
    auto global_line = [&](const char* label, const std::string& prefix, const std::string& estimator) {
        out << label << r.attr_f64("/global", prefix + "sigma_lx") << " lx, relative "
            << 100.0 * r.attr_f64("/global", prefix + "sigma_rel_arithmetic") << " % (arithmetic), "
            << 100.0 * r.attr_f64("/global", prefix + "sigma_rel_quadratic") << " % (quadratic)"
            << (moment && used == estimator ? ", used by targets" : "") << '\n';
    };
    out << "global map     mean " << r.attr_f64("/global", "mean_arithmetic_lx") << " lx";
    if (r.has_attr("/global", "lit_sides") && r.has_attr("/global", "lit_area_m2"))
        out << " over " << r.attr_u64("/global", "lit_sides") << " lit triangle sides, "
            << r.attr_f64("/global", "lit_area_m2") << " m^2";
    out << '\n';
    global_line("  odd/even     RMS error ", "", "odd_even");
    if (moment) global_line("  2nd moment   RMS error ", "moment_", "second_moment");
    // sobol (issue 22): the spread of the replicate maps, which its targets use.
    if (r.has_attr("/global", "replicate_sigma_lx"))
        global_line("  replicates   RMS error ", "replicate_", "replicate_spread");
}

// A detector's line, then what it adds: the modelling ratio, the maintained mean and the
// daylight model's reference.
void print_detector_means(const ResultReader& r, const std::string& name, const std::string& g, std::ostream& out) {
    const std::string units = r.attr_str(g, "units");
    out << "detector " << std::left << std::setw(14) << name << std::right << " " << r.attr_str(g, "type") << ", mean "
        << std::setprecision(2) << r.attr_f64(g, "mean_value") << " " << units << " +- "
        << 100.0 * r.attr_f64(g, "mean_sigma_rel") << " %, per-cell error "
        << 100.0 * r.attr_f64(g, "sigma_rel_arithmetic") << " % (eq. 9), " << r.attr_u64(g, "photons_received")
        << " photons received";
    if (r.has_attr(g, "error_estimator") && r.attr_str(g, "error_estimator") == "replicate_spread")
        out << "; errors from the replicate spread, " << r.attr_u64(g, "error_dof") << " dof";
    out << '\n';
    if (r.has_attr(g, "modelling_ratio_mean"))
        out << "  modelling    E_c/E_h of the means " << std::setprecision(3) << r.attr_f64(g, "modelling_ratio_mean")
            << " +- " << std::setprecision(2) << 100.0 * r.attr_f64(g, "modelling_ratio_mean_sigma_rel")
            << " %, points " << std::setprecision(3) << r.attr_f64(g, "modelling_ratio_min") << " to "
            << r.attr_f64(g, "modelling_ratio_max") << " (horizontal: " << r.attr_str(g, "horizontal") << ")\n"
            << std::setprecision(2);
    if (r.has_attr("/", "maintenance_factor") && r.attr_f64("/", "maintenance_factor") < 1.0) {
        const double mf = r.attr_f64("/", "maintenance_factor");
        out << "  maintained   mean " << mf * r.attr_f64(g, "mean_value") << " " << units << " (initial x MF "
            << std::defaultfloat << std::setprecision(3) << mf
            << (r.attr_u64("/", "maintenance_factor_uniform") ? "" : ", flux-weighted over lights that differ") << ")\n"
            << std::fixed << std::setprecision(2);
    }
    if (r.has_attr(g, "daylight_reference_lx"))
        out << "  daylight     E_h,ext " << std::setprecision(1) << r.attr_f64(g, "daylight_reference_lx")
            << " lx (unobstructed horizontal, from the daylight model)\n"
            << std::setprecision(2);
}

// An illuminance grid's EN 12464-1 metrics and daylight factors, whole and per task area.
void print_grid_metrics(const ResultReader& r, const std::string& g, std::ostream& out) {
    if (!r.has_attr(g, "U0")) return;
    print_metrics(r, g, "whole grid", out);
    print_daylight(r, g, out);
    for (const std::string& area : r.children(g + "/task_areas")) {
        const std::string ga = g + "/task_areas/" + area;
        std::vector<long> c;
        for (double x : r.f64_attr_array(ga, "cell_range")) c.push_back(static_cast<long>(x));
        if (c.size() != 4) c.assign(4, 0);
        out << "  task area '" << area << "' cells [" << c[0] << ":" << c[1] << "," << c[2] << ":" << c[3] << "], "
            << r.attr_u64(ga, "metrics_cells") << " cells\n";
        print_metrics(r, ga, "", out);
        print_daylight(r, ga, out);
    }
    out << std::fixed << std::setprecision(2);
}

void print_detector(const ResultReader& r, const std::string& name, std::ostream& out) {
    const std::string g = "/detectors/" + name;
    // An annual grid's photons carry every hour's sky and sun at once: their plain mean and
    // grid metrics are no illuminance (with the direct light by shadow rays or the gather,
    // only a part of one); its year is what it says.
    if (r.has("/annual/detectors/" + name)) {
        out << "detector " << std::left << std::setw(14) << name << std::right << " " << r.attr_str(g, "type")
            << ", an annual grid:\n";
        print_annual_grid(r, name, out);
        return;
    }
    print_detector_means(r, name, g, out);
    print_grid_metrics(r, g, out);
}

// Each observer's UGR with its background luminance, and the maintained UGR.
void print_observers(const ResultReader& r, std::ostream& out) {
    for (const std::string& name : r.has("/observers") ? r.children("/observers") : std::vector<std::string>{}) {
        const std::string g = "/observers/" + name;
        const double ugr = r.attr_f64(g, "ugr");
        out << "observer " << std::left << std::setw(14) << name << std::right << " UGR ";
        if (std::isfinite(ugr))
            out << std::setprecision(1) << ugr << " +- " << std::setprecision(2) << r.attr_f64(g, "ugr_sigma");
        else out << "undefined";
        out << " (" << r.attr_u64(g, "luminaires_in_view") << " luminaire(s) in view), Lb " << std::setprecision(2)
            << r.attr_f64(g, "background_luminance_cd_m2") << " cd/m^2 from E_ind "
            << r.attr_f64(g, "indirect_vertical_illuminance_lx") << " lx +- "
            << 100.0 * r.attr_f64(g, "indirect_vertical_illuminance_sigma_rel") << " %";
        if (std::isfinite(ugr) && !r.attr_u64(g, "in_cie117_range")) out << "; outside CIE 117's range 10-30";
        out << '\n';
        if (r.has_attr(g, "ugr_maintained") && std::isfinite(ugr))
            out << "  maintained   UGR " << std::setprecision(1) << r.attr_f64(g, "ugr_maintained") << " (x MF "
                << std::defaultfloat << std::setprecision(3) << r.attr_f64("/", "maintenance_factor") << ")\n"
                << std::fixed;
    }
}

// A light scene's weights and flux, and its global map with the error its targets use
// (the replicate spread for sobol) and D / 2.
void print_light_scene_map(const ResultReader& r, const std::string& scene, const std::vector<std::string>& groups,
                           std::ostream& out) {
    const std::string base = "/light_scenes/" + scene;
    const std::vector<double> w = r.f64_attr_array(base, "weights");
    out << "light scene    " << scene << " (" << std::defaultfloat << std::setprecision(3);
    for (std::size_t g = 0; g < w.size() && g < groups.size(); ++g)
        out << (g > 0 ? ", " : "") << groups[g] << ' ' << (w[g] > 0.0 ? w[g] : 0.0);
    out << "; " << std::fixed << std::setprecision(0) << r.attr_f64(base, "flux_lm") << " lm)\n"
        << std::setprecision(2);
    if (!r.has(base + "/global")) return;
    const bool replicates = r.attr_str(base + "/global", "error_estimator") == "replicate_spread";
    out << "  global map   mean " << r.attr_f64(base + "/global", "mean_arithmetic_lx") << " lx, RMS error "
        << r.attr_f64(base + "/global", replicates ? "replicate_sigma_lx" : "moment_sigma_lx")
        << (replicates ? " lx (replicates), " : " lx (2nd moment), ") << r.attr_f64(base + "/global", "sigma_lx")
        << " lx (odd/even)\n";
}

// A light scene's detectors with their EN 12464-1 metrics, and its observers' UGR.
void print_light_scene_detectors(const ResultReader& r, const std::string& scene, std::ostream& out) {
    const std::string base = "/light_scenes/" + scene;
    const std::string gs = base + "/detectors";
    for (const std::string& name : r.has(gs) ? r.children(gs) : std::vector<std::string>{}) {
        const std::string g = gs + "/" + name;
        out << "light scene    " << scene << ": detector " << name << " mean " << std::setprecision(2)
            << r.attr_f64(g, "mean_value") << " " << r.attr_str(g, "units") << " +- "
            << 100.0 * r.attr_f64(g, "mean_sigma_rel") << " %, per-cell error "
            << 100.0 * r.attr_f64(g, "sigma_rel_arithmetic") << " %\n";
        if (!r.has_attr(g, "U0")) continue;
        if (r.has_attr(g, "daylight_reference_lx"))
            out << "  daylight     E_h,ext " << std::setprecision(1) << r.attr_f64(g, "daylight_reference_lx")
                << " lx (the scene's weighted daylight)\n"
                << std::setprecision(2);
        print_metrics(r, g, "whole grid", out);
        print_daylight(r, g, out);
        for (const std::string& area :
             r.has(g + "/task_areas") ? r.children(g + "/task_areas") : std::vector<std::string>{}) {
            out << "  task area '" << area << "'\n";
            print_metrics(r, g + "/task_areas/" + area, "", out);
            print_daylight(r, g + "/task_areas/" + area, out);
        }
        out << std::fixed << std::setprecision(2);
    }
    const std::string os = base + "/observers";
    for (const std::string& name : r.has(os) ? r.children(os) : std::vector<std::string>{}) {
        const double ugr = r.attr_f64(os + "/" + name, "ugr");
        out << "  observer " << name << " UGR ";
        if (std::isfinite(ugr))
            out << std::setprecision(1) << ugr << " +- " << std::setprecision(2)
                << r.attr_f64(os + "/" + name, "ugr_sigma") << '\n';
        else out << "undefined\n";
    }
}

// Each [[light_scene]] (issue 22): its weights, global map, detectors with their
// EN 12464-1 metrics, and UGR; other combinations: info --scene.
void print_light_scenes(const ResultReader& r, std::ostream& out) {
    const std::vector<std::string> groups = r.has_attr("/", "light_groups") ? r.attr_strs("/", "light_groups")
                                                                            : std::vector<std::string>{};
    for (const std::string& scene : r.has("/light_scenes") ? r.children("/light_scenes") : std::vector<std::string>{}) {
        print_light_scene_map(r, scene, groups, out);
        print_light_scene_detectors(r, scene, out);
    }
}

// Each target's value at the last reduction against its goal.
void print_targets(const ResultReader& r, std::ostream& out) {
    if (!r.has("/history/target_value")) return;
    std::vector<std::size_t> shape;
    const std::vector<double> v = r.f64("/history/target_value", &shape);
    const std::vector<std::string> labels = r.attr_strs("/history", "target_labels");
    const std::vector<double> goals = r.f64_attr_array("/history", "target_goals");
    const std::size_t nt = shape.size() == 2 ? shape[1] : 0;
    for (std::size_t i = 0; i < nt && i < labels.size() && i < goals.size() && shape[0] > 0; ++i) {
        const double last = v[(shape[0] - 1) * nt + i];
        const bool count = labels[i].find("received") != std::string::npos;
        const bool rel = labels[i].find(" rel") != std::string::npos;
        const bool met = count ? last >= goals[i] : (last > 0.0 && last <= goals[i]);
        out << "target         " << labels[i] << ": " << std::setprecision(4) << (rel ? 100.0 * last : last)
            << (rel ? " %" : "") << " (goal " << (rel ? 100.0 * goals[i] : goals[i]) << (rel ? " %" : "")
            << ") at the last reduction, " << (met ? "met" : "not met") << '\n';
    }
}

}  // namespace

void print_result_summary(const ResultFile& file, std::ostream& out) {
    const ResultReader& r = file.raw();
    const auto flags = out.flags();
    print_run(r, out);
    print_checkpoint(r, out);
    out << std::defaultfloat << std::setprecision(6);
    out << "flux           " << r.attr_f64("/", "total_flux_lm") << " lm, " << r.attr_f64("/", "flux_per_photon_lm")
        << " lm per photon\n";
    // A tally checkpoint (a failed write kept the tallies alone, docs/RELIABILITY.md §8)
    // has no estimates: a restart from it writes them.
    if (r.has("/checkpoint") && !r.has("/global")) {
        out << "tallies only   no maps or estimates: luxtrace run SCENE --restart " << r.path().string()
            << " writes the result\n";
        return;
    }
    print_global_map(r, out);
    print_annual_year(r, out);
    for (const std::string& name : r.children("/detectors")) print_detector(r, name, out);
    print_observers(r, out);
    print_light_scenes(r, out);
    print_targets(r, out);
    out.flags(flags);
}

}  // namespace luxtrace
