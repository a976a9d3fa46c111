#include "light_scene_summary.hpp"

#include "luxtrace/core/error.hpp"
#include "luxtrace/core/text.hpp"
#include "luxtrace/estimate/result_estimates.hpp"
#include "luxtrace/io/light_group_tallies.hpp"
#include "luxtrace/io/result_data.hpp"
#include "luxtrace/scene/scene.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <optional>
#include <ostream>

namespace luxtrace {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::string trim(const std::string& s) {
    const auto b = s.find_first_not_of(" \t");
    if (b == std::string::npos) return {};
    return s.substr(b, s.find_last_not_of(" \t") - b + 1);
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

void print_light_scene(const ResultFile& file, const std::string& spec, std::ostream& out) {
    const LightGroupTallies t = read_light_group_tallies(file);
    if (t.groups.empty())
        throw InputError("--scene: " + file.path().string() +
                         " has no light groups (its scene had one; a light scene needs two or more)");
    const std::vector<double> w = parse_scene_weights(spec, t.groups);
    // The run's own estimate of a light scene, on the groups' stored counts.
    const ResultEstimates e =
        estimate_light_scene(t.scene(), LightScene{spec, w}, t.layout, t.data, t.e0, t.photons).estimates;
    const auto flags = out.flags();
    out << "light scene    ";
    for (std::size_t g = 0; g < t.groups.size(); ++g)
        out << (g ? ", " : "") << t.groups[g] << " = " << std::defaultfloat << std::setprecision(6) << w[g];
    out << " (recombined from /light_groups)\n" << std::fixed << std::setprecision(2);
    if (t.group_maps && t.photons > 0) {
        const GlobalEstimate& g = e.global;
        auto line = [&](const char* label, double sigma, double rel, GlobalEstimate::Estimator estimator) {
            out << label << sigma << " lx, relative " << 100.0 * rel << " % (arithmetic)"
                << (g.primary == estimator ? ", used by targets" : "") << '\n';
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
    for (std::size_t di = 0; di < t.detectors.size(); ++di) {
        const Detector& d = t.detectors[di];
        const double mean = e.detectors[di].mean_value, rel = e.detectors[di].mean_sigma_rel;
        out << "detector " << std::left << std::setw(14) << d.name << std::right << " mean " << mean << " " << d.units()
            << " +- " << 100.0 * rel << " %\n";
        // A daylight_factor detector: its mean DF under this combination's daylight.
        if (!d.daylight_factor) continue;
        if (const std::optional<DaylightEstimate>& df = e.daylight[di]) {
            const double reference_lx = df->reference_lx;
            out << "  daylight     DF mean " << 100.0 * mean / reference_lx << " +- "
                << 100.0 * mean * rel / reference_lx << " % (E_h,ext " << reference_lx << " lx)\n";
        } else {
            out << "  daylight     no daylight in this combination: no daylight factor\n";
        }
    }
    out.flags(flags);
}

}  // namespace luxtrace
