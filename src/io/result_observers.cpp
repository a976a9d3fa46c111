// The result's observers (/observers/NAME): UGR and the luminaires in view.
#include "luxtrace/scene/scene.hpp"
#include "result_parts.hpp"

namespace luxtrace::result_parts {

using namespace hdf5;

namespace {

// Per luminaire in view, in the order of the lights.
void write_glare_sources(hid_t g, const std::vector<GlareSource>& sources) {
    const std::size_t S = sources.size();
    std::vector<double> L_, omega, p, pos, alpha, beta, inten, area, dist;
    std::vector<std::uint64_t> light;
    std::vector<std::string> labels;
    for (const GlareSource& s : sources) {
        L_.push_back(s.luminance_cd_m2);
        omega.push_back(s.solid_angle_sr);
        p.push_back(s.position_index);
        pos.insert(pos.end(), {s.position.x, s.position.y, s.position.z});
        alpha.push_back(s.alpha_deg);
        beta.push_back(s.beta_deg);
        inten.push_back(s.intensity_cd);
        area.push_back(s.projected_area_m2);
        dist.push_back(s.distance_m);
        light.push_back(s.light);
        labels.push_back(s.label);
    }
    dataset(g, "luminance_cd_m2", {S}, L_.data());
    dataset(g, "solid_angle_sr", {S}, omega.data());
    dataset(g, "position_index", {S}, p.data());
    dataset(g, "luminaire_position", {S, 3}, pos.data());
    dataset(g, "alpha_deg", {S}, alpha.data());
    dataset(g, "beta_deg", {S}, beta.data());
    dataset(g, "intensity_cd", {S}, inten.data());
    dataset(g, "projected_area_m2", {S}, area.data());
    dataset(g, "distance_m", {S}, dist.data());
    dataset(g, "light_index", {S}, light.data());
    attr_strings(g, "luminaire_labels", labels, false);
}

}  // namespace

void write_ugr(hid_t g, const ObserverEstimate& e) {
    const UgrEstimate& u = e.ugr;
    attr(g, "ugr", u.ugr);
    attr(g, "ugr_sigma", u.ugr_sigma);
    if (e.ugr_maintained) attr(g, "ugr_maintained", *e.ugr_maintained);
    attr(g, "background_luminance_cd_m2", u.background_luminance_cd_m2);
    attr(g, "indirect_vertical_illuminance_lx", u.indirect_illuminance_lx);
    attr(g, "indirect_vertical_illuminance_sigma_rel", u.indirect_sigma_rel);
}

void write_observers(hid_t file, const Scene& scene, const TallyLayout& L, std::span<const std::uint64_t> data,
                     const ResultEstimates& est) {
    if (scene.observers.empty()) return;
    const Id obs = create_group(file, "observers", "group /observers");
    const std::size_t B = scene.bands.size();
    for (std::size_t oi = 0; oi < scene.observers.size(); ++oi) {
        const Observer& o = scene.observers[oi];
        const std::size_t di = o.eye_detector;
        const Detector& d = scene.detectors[di];
        const DetectorEstimate& e = est.detectors[di];
        const UgrEstimate& u = est.observers[oi].ugr;
        const Id g = create_group(obs, o.name, "group /observers/" + o.name);
        write_ugr(g, est.observers[oi]);
        attr(g, "glare_sum", u.glare_sum);
        attr(g, "position", std::vector<double>{o.position.x, o.position.y, o.position.z});
        attr(g, "view_direction", std::vector<double>{o.view_direction.x, o.view_direction.y, o.view_direction.z});
        attr(g, "eye_detector_size_m", o.eye_detector_size_m);
        attr(g, "eye_detector_normal", std::vector<double>{d.normal.x, d.normal.y, d.normal.z});
        attr(g, "photons_received", e.photons_received);
        attr(g, "error_estimator", e.replicate_spread ? "replicate_spread" : "independent_photons_eq8");
        attr(g, "error_dof", static_cast<std::uint64_t>(e.dof));
        attr(g, "luminaires_in_view", static_cast<std::uint64_t>(o.sources.size()));
        attr(g, "position_index_formula", "CIE 117:1995 analytic form of Guth's table");
        attr(g, "in_cie117_range", static_cast<std::uint64_t>(u.in_cie117_range() ? 1 : 0));
        if (!o.notes.empty()) attr_strings(g, "notes", o.notes, false);
        // The eye detector's n and q per band (one cell), as a detector's count / sumsq.
        // Every light group's together, as the plain detectors'.
        dataset(g, "eye_count", {B}, detector_sums(L, data, di, 1, false, 0, L.groups()).data());
        dataset(g, "eye_sumsq", {B}, detector_sums(L, data, di, 1, true, 0, L.groups()).data());
        if (!o.sources.empty()) write_glare_sources(g, o.sources);
    }
}

}  // namespace luxtrace::result_parts
