// The result's /daylight group (scenes with sun or sky lights): the site and time, and per
// daylight source its sky model, the sun's position it used and the illuminance it gives
// an unobstructed horizontal plane (docs/DAYLIGHT.md).
#include "luxtrace/scene/scene.hpp"
#include "result_parts.hpp"

namespace luxtrace::result_parts {

using namespace hdf5;

void write_daylight(hid_t file, const Scene& scene) {
    std::vector<std::string> labels, kinds;
    std::vector<double> altitude, azimuth, horizontal, normal;
    std::vector<std::uint64_t> light, group;
    const auto& lights = scene.lights.lights();
    for (std::size_t i = 0; i < lights.size(); ++i) {
        const Light& l = lights[i];
        const auto reference = l.daylight();
        if (!reference) continue;
        labels.push_back(l.label);
        kinds.push_back(reference->model);
        altitude.push_back(reference->sun_altitude_deg);
        azimuth.push_back(reference->sun_azimuth_deg);
        horizontal.push_back(l.unobstructed_horizontal_lx);
        normal.push_back(reference->direct_normal_lx);
        light.push_back(i);
        group.push_back(l.group);
    }
    if (labels.empty()) return;
    const Id g = create_group(file, "daylight", "group /daylight");
    const std::size_t n = labels.size();
    string_dataset(g, "labels", labels);
    string_dataset(g, "model", kinds);
    dataset(g, "light_index", {n}, light.data());
    dataset(g, "light_group", {n}, group.data());
    dataset(g, "sun_altitude_deg", {n}, altitude.data());
    dataset(g, "sun_azimuth_deg", {n}, azimuth.data());
    dataset(g, "unobstructed_horizontal_lx", {n}, horizontal.data());
    dataset(g, "direct_normal_lx", {n}, normal.data());
    double total = 0.0;
    for (double e : horizontal) total += e;
    attr(g, "unobstructed_horizontal_lx", total);
    const Site& site = scene.site;
    if (site.located) {
        attr(g, "latitude_deg", site.sun_site.latitude_deg);
        attr(g, "longitude_deg", site.sun_site.longitude_deg);
        attr(g, "utc_offset_h", site.utc_offset_h);
        attr(g, "elevation_m", site.sun_site.elevation_m);
    }
    if (site.time) attr(g, "time", site.time_text);
    attr(g, "north", std::vector<double>{site.north.x, site.north.y, site.north.z});
}

}  // namespace luxtrace::result_parts
