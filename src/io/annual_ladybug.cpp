#include "luxtrace/io/annual_ladybug.hpp"

#include "luxtrace/io/ladybug_results.hpp"
#include "luxtrace/scene/scene.hpp"

namespace luxtrace {

std::filesystem::path ladybug_folder_for(const Scene& scene, const std::filesystem::path& result) {
    if (scene.annual && !scene.annual->options.ladybug_folder.empty()) return scene.annual->options.ladybug_folder;
    return result.parent_path() / (result.stem().string() + "_ladybug");
}

namespace {
// A detector name as a plain file name (the arrays are named by it).
std::string file_name(const std::string& name) {
    std::string out;
    for (const char c : name)
        out += (std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.') ? c : '_';
    if (out.empty() || out[0] == '.') out = "grid" + out;
    return out;
}
}  // namespace

void write_annual_ladybug(const std::filesystem::path& folder, const Scene& scene,
                          const std::vector<std::optional<AnnualDetectorEstimate>>& annual,
                          const AnnualSeriesSource& source) {
    if (!scene.annual) return;
    const std::vector<AnnualHour>& hours = scene.annual->sky->hours();
    // The hours the reader's 8760-hour year has, and of those the sun-up ones.
    std::vector<std::size_t> kept;
    std::vector<double> sun_up;
    std::size_t hour_of_year = 0;
    for (std::size_t h = 0; h < hours.size(); ++h) {
        if (hours[h].month == 2 && hours[h].day == 29) continue;
        if (hours[h].sun_altitude_deg > 0.0) {
            kept.push_back(h);
            sun_up.push_back(static_cast<double>(hour_of_year) + 0.5);
        }
        ++hour_of_year;
    }
    std::vector<LadybugGrid> grids;
    for (std::size_t d = 0; d < annual.size(); ++d) {
        if (!annual[d]) continue;
        const AnnualSeries& s = annual[d]->value;
        LadybugGrid g;
        g.name = scene.detectors[d].name;
        g.identifier = file_name(g.name);
        g.sensors = s.sensors;
        if (s.total_lx.empty() && source) {
            // A few sensors at a time from where the post-processing put them.
            g.rows = [&source, &kept, d, hours = s.hours](bool direct, std::size_t first, std::size_t count,
                                                          std::span<float> out) {
                std::vector<float> all(count * hours);
                source.read_cells(d, direct ? AnnualSeriesKind::direct : AnnualSeriesKind::total, first, count, all);
                for (std::size_t c = 0; c < count; ++c)
                    for (std::size_t k = 0; k < kept.size(); ++k) out[c * kept.size() + k] = all[c * hours + kept[k]];
            };
            grids.push_back(std::move(g));
            continue;
        }
        g.total_lx.resize(s.sensors * kept.size());
        g.direct_lx.resize(s.sensors * kept.size());
        for (std::size_t c = 0; c < s.sensors; ++c)
            for (std::size_t k = 0; k < kept.size(); ++k) {
                g.total_lx[c * kept.size() + k] = static_cast<float>(s.total_lx[kept[k] * s.sensors + c]);
                g.direct_lx[c * kept.size() + k] = static_cast<float>(s.direct_lx[kept[k] * s.sensors + c]);
            }
        grids.push_back(std::move(g));
    }
    if (grids.empty()) return;
    write_ladybug_results(folder, grids, sun_up);
}

}  // namespace luxtrace
