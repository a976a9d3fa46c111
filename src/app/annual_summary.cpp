#include "annual_summary.hpp"

#include "luxtrace/io/result_reader.hpp"
#include "luxtrace/stats/annual_metrics.hpp"

#include <cmath>
#include <cstdint>
#include <iomanip>
#include <numeric>
#include <ostream>
#include <sstream>
#include <string>
#include <vector>

namespace luxtrace {

namespace {

const std::string kAnnual = "/annual";

std::uint64_t count_ones(const ResultReader& r, const std::string& dataset) {
    const std::vector<std::uint64_t> v = r.u64(dataset);
    return std::accumulate(v.begin(), v.end(), std::uint64_t{0},
                           [](std::uint64_t n, std::uint64_t x) { return n + (x != 0 ? 1 : 0); });
}

// "98.36 +- 0.02 %", with " (bias -0.08 %)" when the bias shows at this precision and is at
// least half the error (a smaller one is lost in the noise); a checkpoint has no errors.
std::string share(const ResultReader& r, const std::string& g, const std::string& name) {
    std::ostringstream s;
    s << std::fixed << std::setprecision(2) << 100.0 * r.attr_f64(g, name);
    if (!r.has_attr(g, name + "_sigma")) return s.str() + " %";
    const double sigma = 100.0 * r.attr_f64(g, name + "_sigma");
    s << " +- " << sigma << " %";
    if (r.has_attr(g, name + "_bias")) {
        const double bias = 100.0 * r.attr_f64(g, name + "_bias");
        if (std::abs(bias) >= 0.005 && std::abs(bias) >= 0.5 * sigma) s << " (bias " << std::showpos << bias << " %)";
    }
    return s.str();
}

}  // namespace

void print_annual_year(const ResultReader& r, std::ostream& out) {
    if (!r.has(kAnnual)) return;
    const auto flags = out.flags();
    std::vector<std::size_t> shape;
    r.f64(kAnnual + "/patch_solid_angle_sr", &shape);
    const std::size_t patches = shape.empty() ? 0 : shape[0];
    const std::vector<double> occupied = r.f64_attr_array(kAnnual, "occupied_hours");
    const std::string sky = r.attr_str(kAnnual, "sky");
    out << "annual         " << r.attr_str(kAnnual, "weather") << ": " << r.attr_u64(kAnnual, "daylit_hours")
        << " daylit hours of " << r.u64(kAnnual + "/month").size() << ", " << r.attr_u64(kAnnual, "sun_hours")
        << " with a sun; "
        << (sky == "cie" ? "CIE type " + std::to_string(r.attr_u64(kAnnual, "cie_type")) : std::string("Perez"))
        << " skies over " << patches << " patches (sky_mf " << r.attr_u64(kAnnual, "sky_mf") << "), ground reflectance "
        << std::defaultfloat << std::setprecision(3) << r.attr_f64(kAnnual, "ground_reflectance") << "\n";
    out << "               occupied " << (occupied.size() == 2 ? occupied[0] : 0.0) << "-"
        << (occupied.size() == 2 ? occupied[1] : 0.0) << " h: " << count_ones(r, kAnnual + "/occupied")
        << " hours; EN 17037: " << count_ones(r, kAnnual + "/en17037_hour") << " daylight hours";
    if (r.attr_u64(kAnnual, "clamped_hours") > 0)
        out << "; " << r.attr_u64(kAnnual, "clamped_hours") << " hours outside the Perez model's range (clamped)";
    out << "\n               (the plain map and detectors hold the year's exposure, lx h)\n";
    const bool gathered = r.has_attr(kAnnual, "indirect") && r.attr_str(kAnnual, "indirect") == "gather";
    if (r.has_attr(kAnnual, "direct") && r.attr_str(kAnnual, "direct") == "shadow_rays")
        out << "               direct light by shadow rays: the grids' plain values hold the rest, the direct is\n"
               "               /annual/detectors/NAME/shadow_direct_sky_lx_h (with the ground) and ..._sun_lx_h\n";
    if (gathered)
        out << "               light after a diffuse reflection gathered: the grids' plain values hold what came\n"
               "               off other surfaces, the gathered is /annual/detectors/NAME/gathered_sky_lx_h and\n"
               "               ..._sun_lx_h\n";
    out.flags(flags);
}

void print_annual_grid(const ResultReader& r, const std::string& name, std::ostream& out) {
    const std::string g = kAnnual + "/detectors/" + name;
    if (!r.has(g)) return;
    const auto flags = out.flags();
    const std::uint64_t replicates = r.attr_u64(g, "replicates");
    out << "  annual       " << r.f64(g + "/da").size() << " sensors: sDA300/50% " << share(r, g, "sda")
        << ", ASE1000,250h " << share(r, g, "ase");
    if (replicates > 0) out << " (errors from " << replicates << " replicate years)";
    else out << " (a checkpoint: no errors)";
    out << '\n'
        << "  DA           mean " << share(r, g, "mean_da") << ", continuous " << share(r, g, "mean_continuous_da")
        << '\n'
        << "  UDI          fell short " << share(r, g, "mean_udi_fell_short") << ", useful "
        << share(r, g, "mean_udi_useful") << ", exceeded " << share(r, g, "mean_udi_exceeded") << '\n';
    for (std::size_t l = 0; l < kEn17037Levels.size(); ++l) {
        const En17037Level& level = kEn17037Levels[l];
        const std::string n = std::string("en17037_") + level.name;
        out << (l == 0 ? "  EN 17037     " : "               ") << std::left << std::setw(7) << level.name << std::right
            << std::defaultfloat << std::setprecision(3) << " " << level.target_lx << " lx over 50 % "
            << share(r, g, n + "_target_hours") << ", " << std::defaultfloat << level.minimum_lx << " lx over 95 % "
            << share(r, g, n + "_minimum_hours")
            << " of the hours: " << (r.attr_u64(g, n + "_pass") != 0 ? "pass" : "fail");
        if (replicates > 0)
            out << " (flip " << std::defaultfloat << std::setprecision(2)
                << 100.0 * r.attr_f64(g, n + "_flip_probability") << " %)";
        out << '\n';
    }
    out.flags(flags);
}

}  // namespace luxtrace
