#include "light_scene_summary.hpp"

#include "luxtrace/core/error.hpp"
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

std::string joined(const std::vector<std::string>& names) {
    std::string s;
    for (const std::string& n : names) s += (s.empty() ? "" : ", ") + n;
    return s;
}

// The global map of the combination: eqs. (4)-(5) over the lit sides, with the odd and even
// half-maps weighted like the counts, and each side's sigma from S = sum_g w_g (odd + even)_g
// and Q = sum_g w_g^2 sumsq_g (as estimate_global on WeightedTallies).
struct GlobalFigures {
    double mean_lx = 0.0, odd_even_sigma_lx = kNaN, moment_sigma_lx = kNaN;
    std::size_t lit_sides = 0;
};

GlobalFigures recombine_global(const std::vector<LightGroupData>& groups, const std::vector<double>& w,
                               const std::vector<double>& area, double e0, double photons) {
    const SurfaceShape& shape = groups.front().surface->shape;
    for (const LightGroupData& g : groups)
        if (g.surface->shape.size() != shape.size() || area.size() != shape.triangles || g.surface->sumsq.empty())
            throw InputError("/light_groups/" + g.name + ": its maps do not agree with /mesh and the other groups");
    double s = 0.0, sum_d2 = 0.0, sum_e = 0.0, sum_var = 0.0;
    GlobalFigures out;
    for (std::size_t t = 0; t < shape.triangles; ++t)
        for (std::size_t side = 0; side < shape.sides; ++side) {
            double odd = 0.0, even = 0.0, q = 0.0;
            for (std::size_t b = 0; b < shape.bands; ++b)
                for (std::size_t g = 0; g < groups.size(); ++g) {
                    const SurfaceCounts& c = *groups[g].surface;
                    const std::size_t i = shape.index(t, side, b);
                    odd += w[g] * static_cast<double>(c.count_odd[i]);
                    even += w[g] * static_cast<double>(c.count_even[i]);
                    q += w[g] * w[g] * static_cast<double>(c.sumsq[i]);
                }
            if (odd + even == 0.0) continue;
            const double a = area[t], k = e0 / a;
            const double d = 2.0 * (odd - even) * k, e = (odd + even) * k;
            const double sigma = std::sqrt(std::max(0.0, q - (odd + even) * (odd + even) / photons)) * k;
            s += a;
            ++out.lit_sides;
            sum_d2 += a * d * d;
            sum_e += a * e;
            sum_var += a * sigma * sigma;
        }
    if (s <= 0.0) return out;
    out.mean_lx = sum_e / s;
    out.odd_even_sigma_lx = 0.5 * std::sqrt(sum_d2 / s);
    out.moment_sigma_lx = std::sqrt(sum_var / s);
    return out;
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
            throw InputError(where + "no light group '" + name + "' (the file has: " + joined(groups) + ")");
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
        const GlobalFigures gf = recombine_global(groups, w, file.triangle_areas(), e0, photons);
        auto rel = [&](double s) { return gf.mean_lx > 0.0 ? 100.0 * s / gf.mean_lx : kNaN; };
        out << "global map     mean " << gf.mean_lx << " lx over " << gf.lit_sides << " lit triangle sides\n"
            << "  odd/even     RMS error " << gf.odd_even_sigma_lx << " lx, relative " << rel(gf.odd_even_sigma_lx)
            << " % (arithmetic)\n"
            << "  2nd moment   RMS error " << gf.moment_sigma_lx << " lx, relative " << rel(gf.moment_sigma_lx)
            << " % (arithmetic)\n";
    } else {
        out << "global map     not kept per light group (run.group_maps = false)\n";
    }
    const std::vector<std::uint64_t> rep_photons = file.replicate_photons();
    for (std::size_t di = 0; di < groups.front().detectors.size(); ++di) {
        const std::string& name = groups.front().detectors[di].first;
        const auto [mean, rel] = recombine_detector(file, groups, di, w, photons, rep_photons);
        out << "detector " << std::left << std::setw(14) << name << std::right << " mean " << mean << " "
            << file.detector(name).units << " +- " << 100.0 * rel << " %\n";
    }
    out.flags(flags);
}

}  // namespace luxtrace
