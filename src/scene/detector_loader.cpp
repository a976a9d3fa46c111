// [[detector]] (with [[detector.task_area]]) and [[observer]] -> the scene's detectors and
// observers (docs/REFERENCE.md §2).
#include "luxtrace/detector/pts_file.hpp"
#include "luxtrace/scene/shapes.hpp"
#include "scene_loader.hpp"

#include <algorithm>
#include <cmath>

namespace luxtrace::detail {

namespace {

constexpr double kMaxDetectorCells = 1e8;
// A points detector's disc radius when no two of its sensors share a plane (so no spacing
// to take half of): a disc of 0.031 m^2, the area of an 18 cm square cell.
constexpr double kLoneSensorRadiusM = 0.1;

// Detector, task area and observer names become HDF5 group names and parts of a target's
// `on` ("detector:NAME[i0:i1,j0:j1]").
void check_path_name(const TableReader& r, const std::string& key, const std::string& name) {
    if (name.find_first_of("/[]:. ") != std::string::npos)
        r.fail(key, "may not contain '/', '[', ']', ':', '.' or spaces");
}

struct DetectorReader : StepReader {
    using StepReader::StepReader;

    // [[detector.task_area]] (or task_area = [{...}]): name, cells = [i0, i1, j0, j1],
    // half-open and 0-based like a run target's [i0:i1,j0:j1].
    void parse_task_areas(TableReader& r, const toml::array& areas, Detector& d) {
        if (d.type != DetectorType::illuminance && d.type != DetectorType::points)
            r.fail("task_area",
                   std::string("task areas belong to illuminance detectors and points detectors (this one is ") +
                       detector_type_name(d.type) + ": no uniformity U0 is computed for it)");
        for (std::size_t k = 0; k < areas.size(); ++k) {
            const toml::table* t = areas[k].as_table();
            if (t == nullptr)
                r.fail("task_area", "expected [[detector.task_area]] tables { name, cells = [i0, i1, j0, j1] }");
            std::string context = r.context() + " task_area #" + std::to_string(k + 1);
            if (const auto n = (*t)["name"].value<std::string>()) context += " '" + *n + "'";
            TableReader ar(*t, fname, context, "detector.task_area");
            const auto name = ar.string("name");
            if (!name || name->empty()) ar.fail_entry("needs a 'name'");
            check_path_name(ar, "name", *name);
            for (const TaskArea& other : d.task_areas)
                if (other.name == *name) ar.fail("name", "task area '" + *name + "' is defined twice in this detector");
            const auto cells = ar.numbers("cells", 4);
            if (!cells) ar.fail_entry("needs 'cells' = [i0, i1, j0, j1] (cells i0 <= i < i1, j0 <= j < j1, from 0)");
            for (double c : *cells)
                if (c != std::floor(c) || c < 0)
                    ar.fail("cells", "expected four whole numbers [i0, i1, j0, j1], none negative");
            const std::vector<double>& c = *cells;
            if (!(c[0] < c[1] && c[1] <= d.nx && c[2] < c[3] && c[3] <= d.ny))
                ar.fail("cells", "[" + fmt_number(c[0]) + ", " + fmt_number(c[1]) + ", " + fmt_number(c[2]) + ", " +
                                     fmt_number(c[3]) + "] is empty or outside the " + std::to_string(d.nx) + " x " +
                                     std::to_string(d.ny) + " cells (need i0 < i1 <= nx, j0 < j1 <= ny)");
            const TaskArea a{*name, static_cast<int>(c[0]), static_cast<int>(c[1]), static_cast<int>(c[2]),
                             static_cast<int>(c[3])};
            ar.finish();
            d.task_areas.push_back(a);
        }
    }

    // daylight_factor = true and en17037 = { target_df, minimum_df } (percent; implies
    // daylight_factor): DF = E / E_h,ext needs E_h,ext > 0, so a daylight source.
    void parse_daylight(TableReader& r, Detector& d) {
        const std::optional<bool> df = r.boolean("daylight_factor");
        if (r.has("en17037")) {
            const toml::table* e = r.table("en17037");
            if (e == nullptr) r.fail("en17037", "expected a table { target_df = D_T, minimum_df = D_TM } (percent)");
            TableReader er(*e, fname, r.context() + " en17037", "detector.en17037");
            const auto target = er.number("target_df");
            const auto minimum = er.number("minimum_df");
            if (!target || !minimum)
                er.fail_entry("needs 'target_df' (D_T, exceeded over 50 % of the cells) and 'minimum_df' (D_TM, over "
                              "95 %), in percent");
            if (!(*target > 0.0 && *target <= 100.0)) er.fail("target_df", "must lie in (0, 100] percent");
            if (!(*minimum > 0.0 && *minimum <= 100.0)) er.fail("minimum_df", "must lie in (0, 100] percent");
            er.finish();
            if (df == false) r.fail("daylight_factor", "is false, but en17037 judges daylight factors (leave it out)");
            d.en17037 = En17037Targets{*target, *minimum};
        }
        d.daylight_factor = df.value_or(false) || d.en17037.has_value();
        if (!d.daylight_factor) return;
        const std::string key = df ? "daylight_factor" : "en17037";
        if (d.type != DetectorType::illuminance && d.type != DetectorType::points)
            r.fail(key,
                   std::string("daylight factors belong to illuminance detectors and points detectors (this one is ") +
                       detector_type_name(d.type) + ")");
        const auto& lights = scene.lights.lights();
        if (std::none_of(lights.begin(), lights.end(),
                         [](const Light& l) { return l.unobstructed_horizontal_lx > 0.0; }))
            r.fail(key, "needs a daylight source ([[light]] type \"sky\" or \"sun\" above the horizon): DF = E / "
                        "E_h,ext and this scene's lights give no unobstructed horizontal illuminance E_h,ext");
    }

    void parse_detector(const toml::table& t, std::size_t i) {
        TableReader r(t, fname, entry_name("detector", i, t), "detector");
        Detector d;
        const auto name = r.string("name");
        if (!name || name->empty()) r.fail_entry("needs a 'name'");
        for (const Detector& other : scene.detectors)
            if (other.name == *name) r.fail("name", "detector '" + *name + "' is defined twice");
        check_path_name(r, "name", *name);
        d.name = *name;
        const std::string type = r.string("type").value_or("illuminance");
        if (type == "illuminance") d.type = DetectorType::illuminance;
        else if (type == "luminance") d.type = DetectorType::luminance;
        else if (type == "cylindrical") d.type = DetectorType::cylindrical;
        else if (type == "semicylindrical") d.type = DetectorType::semicylindrical;
        else if (type == "points") d.type = DetectorType::points;
        else
            r.fail("type", "unknown detector type '" + type +
                               "' (expected illuminance, luminance, cylindrical, semicylindrical or points)");
        if (d.type == DetectorType::points) parse_points(r, d);
        else parse_grid(r, d);
        if (const toml::array* areas = r.array("task_area")) parse_task_areas(r, *areas, d);
        parse_daylight(r, d);
        if (d.type == DetectorType::luminance) {
            d.view_direction = unit_vector(r, "view_direction", r.vec3("view_direction").value_or(d.normal));
            d.half_angle_deg = r.number("half_angle_deg").value_or(5.0);
            if (!(d.half_angle_deg > 0.0 && d.half_angle_deg <= 90.0)) r.fail("half_angle_deg", "must lie in (0, 90]");
            if (std::abs(glm::dot(d.view_direction, d.normal)) < 1e-3)
                r.fail("view_direction", "must not lie in the detector plane");
        }
        if (d.cylinders()) parse_cylinder(r, d);
        r.finish();
        d.finalize();
        if (!(d.value_per_lm() > 0.0 && std::isfinite(d.value_per_lm())))
            r.fail_entry("its cells are too small (or its cone too narrow) to measure anything");
        if (d.type == DetectorType::luminance && d.cone_below_plane())
            scene.warnings.push_back(fname + ": " + entry_name("detector", i, t) +
                                     ": the view cone dips below the detector plane (view angle + half_angle_deg > "
                                     "90): its luminance is then underestimated");
        scene.detectors.push_back(d);
    }

    // Points: the sensors of a Radiance .pts file (path relative to the scene file), each a
    // disc of radius_m. The default radius is half the smallest distance between two
    // sensors of one plane: the discs of a regular grid then touch without overlapping and
    // each averages the illuminance over nearly the square a grid cell of the same spacing
    // would (pi/4 of it), so a Honeybee grid of 0.5-1 m spacing catches about as many
    // photons per sensor as an illuminance grid of that spacing. A fixed small radius
    // would instead make every sensor's error grow with 1/r for no gain in locality beyond
    // what the spacing already resolves.
    void parse_points(TableReader& r, Detector& d) {
        const auto file = r.string("points");
        if (!file || file->empty())
            r.fail_entry("type 'points' needs 'points' = \"FILE.pts\" (one sensor a line: x y z dx dy dz)");
        const std::string path = load.resolve(*file).string();
        SensorPointList list;
        try {
            list = read_pts(path);
        } catch (const InputError& e) {
            r.fail("points", e.what());
        }
        if (static_cast<double>(list.positions.size()) > kMaxDetectorCells)
            r.fail("points", path + " holds " + std::to_string(list.positions.size()) +
                                 " sensors; a detector may have at most " + fmt_number(kMaxDetectorCells));
        if (r.has("radius_m")) {
            d.radius_m = *r.number("radius_m");
            if (!(d.radius_m > 0.0 && std::isfinite(d.radius_m))) r.fail("radius_m", "must be positive (metres)");
        } else {
            int a = -1, b = -1;
            d.radius_m = SensorPoints::half_smallest_spacing_m(list.positions, list.directions, &a, &b);
            if (a >= 0 && !(d.radius_m > 0.0))
                r.fail("points", path + ": lines " + std::to_string(list.lines[static_cast<std::size_t>(a)]) + " and " +
                                     std::to_string(list.lines[static_cast<std::size_t>(b)]) +
                                     ": two sensors at the same point of one plane leave no default disc radius "
                                     "(give 'radius_m')");
            if (a < 0) d.radius_m = kLoneSensorRadiusM;
        }
        d.points_file = *file;
        d.nx = static_cast<int>(list.positions.size());
        d.ny = 1;
        d.sensors = SensorPoints(std::move(list.positions), std::move(list.directions), d.radius_m);
    }

    // Illuminance, luminance and cylinder grids: a rectangle of nx x ny cells.
    void parse_grid(TableReader& r, Detector& d) {
        const auto c = r.vec3("center");
        if (!c) r.fail_entry("needs 'center'");
        d.center = *c;
        d.normal = unit_vector(r, "normal", r.vec3("normal").value_or(Vec3(0, 0, 1)));
        d.up = unit_vector(r, "up", r.vec3("up").value_or(default_up(d.normal)));
        if (glm::length(glm::cross(d.up, d.normal)) < 1e-6) r.fail("up", "must not be parallel to 'normal'");
        const auto size = r.numbers("size", 2);
        if (!size) r.fail_entry("needs 'size' = [w, h]");
        if (!((*size)[0] > 0.0 && (*size)[1] > 0.0)) r.fail("size", "the detector has zero or negative area");
        d.size_u = (*size)[0];
        d.size_v = (*size)[1];
        if (const auto cells = r.numbers("cells", 2)) {
            const double nx = (*cells)[0], ny = (*cells)[1];
            if (!(nx >= 1 && ny >= 1 && nx == std::floor(nx) && ny == std::floor(ny)))
                r.fail("cells", "expected two positive whole numbers [nx, ny]");
            // Every cell costs 16 bytes per band in each copy of the tallies (the rank's
            // store, the reduction message, rank 0's reduced copy).
            if (nx * ny > kMaxDetectorCells)
                r.fail("cells", fmt_number(nx) + " x " + fmt_number(ny) + " = " + fmt_number(nx * ny) +
                                    " cells; a detector may have at most " + fmt_number(kMaxDetectorCells) +
                                    " (e.g. 10000 x 10000)");
            d.nx = static_cast<int>(nx);
            d.ny = static_cast<int>(ny);
        }
    }

    // Cylindrical and semicylindrical detectors: the small cylinder at each point, its
    // axis the grid's normal. A finite cylinder's lateral mean differs from the point
    // value by about -(pi r / 2 rho)(1 - 1.5 sin^2 gamma) for a light at horizontal
    // distance rho (first order in r), the height only in second order; so the default is
    // thin and tall, r = 1 cm, h = 20 cm: within 2 % of the point value for lights 0.5 m
    // or more to the side and 1.5 m above, 0.1 % beyond 1.5 m (docs/VALIDATION.md), while
    // its 2 pi r h = 0.0126 m^2 still catches photons like an 11 cm x 11 cm cell.
    void parse_cylinder(TableReader& r, Detector& d) {
        d.radius_m = r.number("radius").value_or(0.01);
        d.height_m = r.number("height").value_or(0.2);
        if (!(d.radius_m > 0.0)) r.fail("radius", "must be positive (metres)");
        if (!(d.height_m > 0.0)) r.fail("height", "must be positive (metres)");
        if (d.type == DetectorType::semicylindrical) {
            const auto f = r.vec3("facing");
            if (!f) r.fail_entry("type 'semicylindrical' needs 'facing' (the direction its curved half faces)");
            d.facing = unit_vector(r, "facing", *f);
            if (std::abs(glm::dot(d.facing, d.normal)) > 1e-6)
                r.fail("facing", "must be perpendicular to the cylinder axis (the detector's 'normal', default "
                                 "[0, 0, 1])");
        } else if (const auto h = r.string("horizontal")) {
            if (h->empty()) r.fail("horizontal", "needs the name of an illuminance [[detector]]");
            d.horizontal = *h;
        }
    }

    // A cylindrical detector's `horizontal` names an illuminance detector on the same grid
    // (the modelling ratio divides point by point); checked once every detector is known.
    void link_horizontal(const toml::table& t, std::size_t i) {
        Detector& d = scene.detectors[i];
        if (d.horizontal.empty()) return;
        TableReader r(t, fname, entry_name("detector", i, t), "detector");
        const auto it = std::find_if(scene.detectors.begin(), scene.detectors.end(),
                                     [&](const Detector& o) { return o.name == d.horizontal; });
        if (it == scene.detectors.end()) r.fail("horizontal", "no [[detector]] is named '" + d.horizontal + "'");
        if (it->type != DetectorType::illuminance)
            r.fail("horizontal", "detector '" + d.horizontal + "' is " + detector_type_name(it->type) +
                                     "; the modelling ratio needs an illuminance detector");
        const double scale = std::max({1.0, glm::length(d.center), d.size_u, d.size_v});
        std::string differs;
        if (glm::length(it->center - d.center) > 1e-9 * scale) differs = "center";
        else if (glm::dot(it->normal, d.normal) < 1.0 - 1e-12) differs = "normal";
        else if (glm::dot(it->v_axis, d.v_axis) < 1.0 - 1e-12) differs = "up";
        else if (std::abs(it->size_u - d.size_u) > 1e-9 * scale || std::abs(it->size_v - d.size_v) > 1e-9 * scale)
            differs = "size";
        else if (it->nx != d.nx || it->ny != d.ny) differs = "cells";
        if (!differs.empty())
            r.fail("horizontal", "detector '" + d.horizontal +
                                     "' must lie on the same grid as this one (center, "
                                     "normal, up, size, cells), but its '" +
                                     differs + "' differs");
        d.horizontal_index = static_cast<int>(it - scene.detectors.begin());
    }

    // [[observer]]: an eye and a line of sight for UGR (glare/observer.hpp), with its eye
    // detector appended to the detectors (after the user's).
    void parse_observer(const toml::table& t, std::size_t i) {
        TableReader r(t, fname, entry_name("observer", i, t), "observer");
        Observer o;
        o.name = r.string("name").value_or("observer_" + std::to_string(i + 1));
        if (o.name.empty()) r.fail("name", "must not be empty");
        check_path_name(r, "name", o.name);
        for (const Observer& other : scene.observers)
            if (other.name == o.name) r.fail("name", "observer '" + o.name + "' is defined twice");
        const auto pos = r.vec3("position");
        if (!pos) r.fail_entry("needs 'position' (the eye)");
        o.position = *pos;
        const auto view = r.vec3("view_direction");
        if (!view) r.fail_entry("needs 'view_direction' (the line of sight)");
        o.view_direction = unit_vector(r, "view_direction", *view);
        // Guth's index is defined about a line of sight with a vertical beside it.
        if (std::abs(o.view_direction.z) > std::cos(10.0 * kPi / 180.0))
            r.fail("view_direction", "must lie more than 10 degrees from the vertical (CIE 117's line of sight is "
                                     "about horizontal)");
        // Side of the square eye detector: a head's width (0.2 m) is local on the scale over
        // which a room's indirect light changes (metres), and gathers 16 times the photons a
        // 5 cm one would.
        o.eye_detector_size_m = r.number("eye_detector_size").value_or(0.2);
        if (!(o.eye_detector_size_m > 0.0 && o.eye_detector_size_m <= 1.0))
            r.fail("eye_detector_size", "must lie in (0, 1] metres");
        r.finish();
        o.finalize();
        if (std::abs(o.view_direction.z) > std::sin(1.0 * kPi / 180.0))
            scene.warnings.push_back(fname + ": " + entry_name("observer", i, t) +
                                     ": the line of sight is not horizontal; CIE 117 assumes a horizontal one (UGR "
                                     "is computed about the given one, the eye detector stays vertical)");
        Detector d;
        d.name = "observer:" + o.name;
        d.type = DetectorType::illuminance;
        d.center = o.position;
        // Vertical, facing along the horizontal line of sight: it counts the light arriving
        // at the eye from in front (CIE 117's vertical illuminance at the eye).
        d.normal = glm::normalize(Vec3(o.view_direction.x, o.view_direction.y, 0.0));
        d.up = Vec3(0, 0, 1);
        d.size_u = d.size_v = o.eye_detector_size_m;
        d.indirect_only = true;
        d.observer = static_cast<int>(scene.observers.size());
        d.finalize();
        o.eye_detector = scene.detectors.size();
        scene.detectors.push_back(d);
        o.sources = glare_sources(o, scene.lights);
        if (o.sources.empty())
            o.notes.push_back("observer '" + o.name + "': no luminaire in the field of view: UGR is undefined");
        for (const std::string& n : o.notes) scene.warnings.push_back(fname + ": " + n);
        scene.observers.push_back(std::move(o));
    }
};

}  // namespace

namespace {

// Whether the run (every light at full output) or some light scene lights with daylight
// alone: electric light in a DF is counted as daylight, which a user rarely means.
bool daylight_isolated(const Scene& scene) {
    const auto& lights = scene.lights.lights();
    // Sun and sky lights, their ground glow included, are daylight: they have a daylight
    // reference.
    auto daylit = [](const Light& l) { return l.daylight().has_value(); };
    auto electric = [&](const Light& l) { return !daylit(l) && l.flux_lm > 0.0; };
    if (std::none_of(lights.begin(), lights.end(), electric)) return true;
    for (const LightScene& ls : scene.light_scenes) {
        bool any_daylight = false, any_electric = false;
        for (const Light& l : lights) {
            if (!(ls.weights[l.group] > 0.0)) continue;
            any_daylight = any_daylight || daylit(l);
            any_electric = any_electric || electric(l);
        }
        if (any_daylight && !any_electric) return true;
    }
    return false;
}

}  // namespace

void read_detectors(SceneLoad& load, TableReader& root) {
    DetectorReader reader(load);
    const auto tables = tables_of(root, "detector");
    for (std::size_t i = 0; i < tables.size(); ++i) reader.parse_detector(*tables[i], i);
    for (std::size_t i = 0; i < tables.size(); ++i) reader.link_horizontal(*tables[i], i);
    if (daylight_isolated(load.scene)) return;
    for (std::size_t i = 0; i < tables.size(); ++i)
        if (load.scene.detectors[i].daylight_factor)
            load.scene.warnings.push_back(
                load.fname + ": " + entry_name("detector", i, *tables[i]) +
                ": daylight factor with daylight and electric light together, and no [[light_scene]] that lights "
                "with the daylight alone: DF = E / E_h,ext then counts the electric light as daylight (put the "
                "daylight in its own light group and add a light scene of it)");
}

void read_observers(SceneLoad& load, TableReader& root) {
    DetectorReader reader(load);
    const auto tables = tables_of(root, "observer");
    for (std::size_t i = 0; i < tables.size(); ++i) reader.parse_observer(*tables[i], i);
}

}  // namespace luxtrace::detail
