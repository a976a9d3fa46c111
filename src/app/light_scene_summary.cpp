#include "light_scene_summary.hpp"

#include "luxtrace/core/error.hpp"
#include "luxtrace/core/text.hpp"
#include "luxtrace/io/result_data.hpp"
#include "luxtrace/stats/estimates.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <ostream>

namespace luxtrace {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::string trim(const std::string& s) {
    const auto b = s.find_first_not_of(" \t");
    if (b == std::string::npos) return {};
    return s.substr(b, s.find_last_not_of(" \t") - b + 1);
}

// The global map of the combination, estimated by the run's own estimate_global: the
// groups' surface counts laid out as a run's tallies (one map group per light group, no
// detectors) and read through WeightedTallies with the combination's weights.
GlobalEstimate recombine_global(const std::vector<LightGroupData>& groups, const std::vector<double>& w,
                                const std::vector<double>& area, double e0, std::uint64_t photons,
                                const std::vector<std::uint64_t>& rep_photons) {
    const SurfaceShape& shape = groups.front().surface->shape;
    const std::size_t R = rep_photons.size();
    for (const LightGroupData& g : groups)
        if (g.surface->shape.size() != shape.size() || shape.sides != TallyLayout::kSides ||
            area.size() != shape.triangles || g.surface->sumsq.empty() ||
            g.surface->replicate_count.size() != shape.size() * R)
            throw InputError("/light_groups/" + g.name + ": its maps do not agree with /mesh and the other groups");
    const TallyLayout L(shape.triangles, TallyDims{shape.bands, groups.size(), groups.size(), R}, {});
    std::vector<std::uint64_t> data(L.size(), 0);
    for (std::size_t g = 0; g < groups.size(); ++g) {
        const SurfaceCounts& c = *groups[g].surface;
        for (std::size_t t = 0; t < shape.triangles; ++t)
            for (std::size_t side = 0; side < shape.sides; ++side)
                for (std::size_t b = 0; b < shape.bands; ++b) {
                    const std::size_t i = shape.index(t, side, b), s = L.side_index(t, side);
                    data[L.side_slot(s, b, TallyLayout::kCountOdd, g)] = c.count_odd[i];
                    data[L.side_slot(s, b, TallyLayout::kCountEven, g)] = c.count_even[i];
                    data[L.side_slot(s, b, TallyLayout::kDirectOdd, g)] = c.direct_odd[i];
                    data[L.side_slot(s, b, TallyLayout::kDirectEven, g)] = c.direct_even[i];
                    // sumsq = count + repeats (tally.hpp)
                    data[L.side_slot(s, b, TallyLayout::kRepeats, g)] = c.sumsq[i] - c.count_odd[i] - c.count_even[i];
                    for (std::size_t r = 0; r < R; ++r)
                        data[L.map_replicate(s, L.map_column(b, g), r)] = c.replicate_count[i * R + r];
                }
    }
    for (std::size_t r = 0; r < R; ++r) data[L.replicate_photons(r)] = rep_photons[r];
    return estimate_global(WeightedTallies(L, data, w), area, e0, photons);
}

// A detector's mean and its relative error: the weighted totals n = sum_g w_g n_g and
// q = sum_g w_g^2 q_g in eq. (8), or (sobol) the spread of the weighted replicate totals.
std::pair<double, double> recombine_detector(const ResultFile& file, const std::vector<LightGroupData>& groups,
                                             std::size_t di, const std::vector<double>& w, double photons,
                                             const std::vector<std::uint64_t>& rep_photons) {
    const DetectorData plain = file.detector(groups.front().detectors[di].first);
    // value = n e0 value_per_lm: the plain grid's factor, from a lit cell.
    double per_count = 0.0;
    for (std::size_t c = 0; c < plain.count.size() && per_count == 0.0; ++c)
        if (plain.count[c] > 0) per_count = plain.value[c] / static_cast<double>(plain.count[c]);
    double n = 0.0, q = 0.0;
    std::vector<double> rep(rep_photons.size(), 0.0);
    bool replicates = !rep_photons.empty();
    for (std::size_t g = 0; g < groups.size(); ++g) {
        const LightGroupDetector& d = groups[g].detectors[di].second;
        n += w[g] * static_cast<double>(d.total_count);
        q += w[g] * w[g] * static_cast<double>(d.total_sumsq);
        replicates = replicates && d.replicate_total.size() == rep.size();
        for (std::size_t r = 0; replicates && r < rep.size(); ++r) rep[r] += w[g] * d.replicate_total[r];
    }
    const double mean = n * per_count / static_cast<double>(plain.nx * plain.ny);
    double rel = kNaN;
    if (replicates) {
        const ReplicateEstimate e = replicate_estimate(rep, rep_photons);
        rel = e.mean > 0.0 ? e.sigma / e.mean : kNaN;
    } else if (n > 0.0) {
        rel = std::sqrt(std::max(0.0, q / (n * n) - 1.0 / photons));
    }
    return {mean, rel};
}

}  // namespace

std::vector<double> parse_scene_weights(const std::string& spec, const std::vector<std::string>& groups) {
    const std::string where = "--scene \"" + spec + "\": ";
    std::vector<double> w(groups.size(), 0.0);
    std::vector<bool> seen(groups.size(), false);
    std::size_t begin = 0;
    bool any = false;
    while (begin <= spec.size()) {
        const std::size_t end = std::min(spec.find(',', begin), spec.size());
        const std::string item = trim(spec.substr(begin, end - begin));
        begin = end + 1;
        const std::size_t eq = item.find('=');
        const std::string name = trim(item.substr(0, eq));
        if (eq == std::string::npos || name.empty())
            throw InputError(where + "'" + item + "' is not GROUP=WEIGHT (e.g. --scene \"a=0.5,b=1\")");
        const auto it = std::find(groups.begin(), groups.end(), name);
        if (it == groups.end())
            throw InputError(where + "no light group '" + name + "' (the file has: " + comma_list(groups) + ")");
        const std::size_t g = static_cast<std::size_t>(it - groups.begin());
        if (seen[g]) throw InputError(where + "light group '" + name + "' is named twice");
        const std::string value = trim(item.substr(eq + 1));
        double x = kNaN;
        std::size_t used = 0;
        try {
            x = std::stod(value, &used);
        } catch (const std::exception&) {
            used = 0;
        }
        if (value.empty() || used != value.size() || !std::isfinite(x) || x < 0.0)
            throw InputError(where + "the weight of '" + name + "' ('" + value + "') is not a number >= 0");
        w[g] = x;
        seen[g] = true;
        any = true;
    }
    if (!any) throw InputError(where + "names no light group");
    return w;
}

namespace {
// E_h,ext of the combination: each daylight source's at its group's weight (/daylight).
double daylight_reference_lx(const ResultFile& file, const std::vector<double>& w) {
    const ResultReader& r = file.raw();
    if (!r.has("/daylight/light_group")) return 0.0;
    const std::vector<std::uint64_t> group = r.u64("/daylight/light_group");
    const std::vector<double> e = r.f64("/daylight/unobstructed_horizontal_lx");
    double sum = 0.0;
    for (std::size_t i = 0; i < group.size() && i < e.size(); ++i)
        if (group[i] < w.size()) sum += w[group[i]] * e[i];
    return sum;
}
}  // namespace

void print_light_scene(const ResultFile& file, const std::string& spec, std::ostream& out) {
    const std::vector<LightGroupData> groups = file.light_groups();
    if (groups.empty())
        throw InputError("--scene: " + file.path().string() +
                         " has no light groups (its scene had one; a light scene needs two or more)");
    std::vector<std::string> names;
    for (const LightGroupData& g : groups) names.push_back(g.name);
    const std::vector<double> w = parse_scene_weights(spec, names);
    const RunInfo& info = file.run_info();
    const double e0 = info.flux_per_photon_lm, photons = static_cast<double>(info.photons);
    const auto flags = out.flags();
    out << "light scene    ";
    for (std::size_t g = 0; g < groups.size(); ++g)
        out << (g ? ", " : "") << names[g] << " = " << std::defaultfloat << std::setprecision(6) << w[g];
    out << " (recombined from /light_groups)\n" << std::fixed << std::setprecision(2);
    const bool maps = std::all_of(groups.begin(), groups.end(), [](const auto& g) { return g.surface.has_value(); });
    if (maps && photons > 0.0) {
        const GlobalEstimate g = recombine_global(groups, w, file.triangle_areas(), e0, info.photons,
                                                  file.replicate_photons());
        auto line = [&](const char* label, double sigma, double rel, GlobalEstimate::Estimator e) {
            out << label << sigma << " lx, relative " << 100.0 * rel << " % (arithmetic)"
                << (g.primary == e ? ", used by targets" : "") << '\n';
        };
        out << "global map     mean " << g.mean_arithmetic_lx << " lx over " << g.lit_sides << " lit triangle sides\n";
        line("  odd/even     RMS error ", g.sigma_lx, g.sigma_rel_arithmetic, GlobalEstimate::Estimator::odd_even);
        line("  2nd moment   RMS error ", g.moment_sigma_lx, g.moment_sigma_rel_arithmetic,
             GlobalEstimate::Estimator::second_moment);
        if (g.primary == GlobalEstimate::Estimator::replicate_spread)
            line("  replicates   RMS error ", g.replicate_sigma_lx, g.replicate_sigma_rel_arithmetic,
                 GlobalEstimate::Estimator::replicate_spread);
    } else {
        out << "global map     not kept per light group (run.group_maps = false)\n";
    }
    const std::vector<std::uint64_t> rep_photons = file.replicate_photons();
    const double reference_lx = daylight_reference_lx(file, w);
    for (std::size_t di = 0; di < groups.front().detectors.size(); ++di) {
        const std::string& name = groups.front().detectors[di].first;
        const auto [mean, rel] = recombine_detector(file, groups, di, w, photons, rep_photons);
        out << "detector " << std::left << std::setw(14) << name << std::right << " mean " << mean << " "
            << file.detector(name).units << " +- " << 100.0 * rel << " %\n";
        // A daylight_factor detector: its mean DF under this combination's daylight (the
        // cells' quantiles need the cells, which only the declared light scenes keep).
        if (!file.raw().has("/detectors/" + name + "/daylight_factor")) continue;
        if (reference_lx > 0.0)
            out << "  daylight     DF mean " << 100.0 * mean / reference_lx << " +- "
                << 100.0 * mean * rel / reference_lx << " % (E_h,ext " << reference_lx << " lx)\n";
        else out << "  daylight     no daylight in this combination: no daylight factor\n";
    }
    out.flags(flags);
}

}  // namespace luxtrace
