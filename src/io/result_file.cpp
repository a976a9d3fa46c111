#include "luxtrace/io/result_file.hpp"

#include "luxtrace/core/error.hpp"
#include "luxtrace/glare/ugr.hpp"
#include "luxtrace/io/atomic_file.hpp"
#include "luxtrace/io/file_seal.hpp"
#include "luxtrace/scene/scene.hpp"
#include "luxtrace/stats/modelling_ratio.hpp"

#include <hdf5.h>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <type_traits>

namespace luxtrace {

namespace fs = std::filesystem;

namespace {

// Owns one HDF5 identifier and closes it with the matching function.
class H5Id {
public:
    using Closer = herr_t (*)(hid_t);
    H5Id(hid_t id, Closer close, const std::string& what) : id_(id), close_(close) {
        if (id_ < 0) throw std::runtime_error("HDF5: " + what + " failed");
    }
    ~H5Id() { close(); }
    void close() {
        if (id_ >= 0 && close_(id_) < 0) {
            id_ = -1;
            throw std::runtime_error("HDF5: close failed");
        }
        id_ = -1;
    }
    H5Id(const H5Id&) = delete;
    H5Id& operator=(const H5Id&) = delete;
    operator hid_t() const { return id_; }

private:
    hid_t id_;
    Closer close_;
};

// The core driver's buffer, kept when HDF5 lets go of it at file close.
struct MemoryImage {
    void* ptr = nullptr;
    std::size_t size = 0;
    std::vector<char> bytes;

    static H5FD_file_image_callbacks_t callbacks(MemoryImage* m) {
        H5FD_file_image_callbacks_t c{};
        c.image_malloc = [](std::size_t n, H5FD_file_image_op_t, void* u) -> void* {
            auto* self = static_cast<MemoryImage*>(u);
            self->ptr = std::malloc(n);
            self->size = n;
            return self->ptr;
        };
        c.image_memcpy = [](void* dst, const void* src, std::size_t n, H5FD_file_image_op_t, void*) -> void* {
            return std::memcpy(dst, src, n);
        };
        c.image_realloc = [](void* p, std::size_t n, H5FD_file_image_op_t, void* u) -> void* {
            auto* self = static_cast<MemoryImage*>(u);
            void* q = std::realloc(p, n);
            if (q != nullptr) {
                self->ptr = q;
                self->size = n;
            }
            return q;
        };
        c.image_free = [](void* p, H5FD_file_image_op_t op, void* u) -> herr_t {
            auto* self = static_cast<MemoryImage*>(u);
            if (p != nullptr && p == self->ptr && op == H5FD_FILE_IMAGE_OP_FILE_CLOSE) {
                const char* b = static_cast<const char*>(p);
                self->bytes.assign(b, b + self->size);
            }
            if (p == self->ptr) self->ptr = nullptr;
            std::free(p);
            return 0;
        };
        // The property list is copied into the file: all copies share this one object.
        c.udata_copy = [](void* u) -> void* { return u; };
        c.udata_free = [](void*) -> herr_t { return 0; };
        c.udata = m;
        return c;
    }
};

// Length of the HDF5 file in `image`: the user block plus the "end of file address" of
// its version 2/3 superblock (HDF5 File Format Specification, section II.A), which
// H5F_LIBVER_V18 selects: signature (8 bytes), versions and sizes (4), base address (8),
// extension address (8), end of file address (8, little-endian, from the superblock on).
std::size_t file_length(const std::vector<char>& image) {
    const char* sb = image.data() + kSealBytes;
    if (image.size() < kSealBytes + 48 || std::memcmp(sb, kHdf5Signature, 8) != 0 || (sb[8] != 2 && sb[8] != 3) ||
        sb[9] != 8)
        throw std::runtime_error("HDF5: unexpected superblock in the in-memory file image");
    std::uint64_t eof = 0;
    for (int i = 7; i >= 0; --i) eof = (eof << 8) | static_cast<unsigned char>(sb[28 + i]);
    if (eof < 48 || eof > image.size() - kSealBytes)
        throw std::runtime_error("HDF5: the in-memory file image is incomplete");
    return kSealBytes + static_cast<std::size_t>(eof);
}

void check(herr_t status, const std::string& what) {
    if (status < 0) throw std::runtime_error("HDF5: " + what + " failed");
}

hid_t group(hid_t parent, const std::string& name) {
    return H5Gcreate2(parent, name.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
}

// The HDF5 types of the numbers luxtrace stores: in memory, and in the file (fixed
// little-endian, whatever the machine).
template <class T>
hid_t native_type() {
    static_assert(std::is_same_v<T, double> || std::is_same_v<T, std::uint64_t> || std::is_same_v<T, std::uint32_t>);
    if constexpr (std::is_same_v<T, double>) return H5T_NATIVE_DOUBLE;
    else if constexpr (std::is_same_v<T, std::uint64_t>) return H5T_NATIVE_UINT64;
    else return H5T_NATIVE_UINT32;
}
template <class T>
hid_t file_type() {
    if constexpr (std::is_same_v<T, double>) return H5T_IEEE_F64LE;
    else if constexpr (std::is_same_v<T, std::uint64_t>) return H5T_STD_U64LE;
    else return H5T_STD_U32LE;
}

template <class T>
void dataset(hid_t parent, const std::string& name, const std::vector<hsize_t>& dims, const T* data) {
    H5Id space(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr), H5Sclose, "dataspace");
    // Large maps are chunked and compressed: counts compress well.
    H5Id plist(H5Pcreate(H5P_DATASET_CREATE), H5Pclose, "property list");
    hsize_t total = 1;
    for (hsize_t d : dims) total *= d;
    if (total >= 4096 && !dims.empty()) {
        std::vector<hsize_t> chunk = dims;
        chunk[0] = std::max<hsize_t>(1, std::min<hsize_t>(dims[0], (1u << 16) / std::max<hsize_t>(1, total / dims[0])));
        check(H5Pset_chunk(plist, static_cast<int>(chunk.size()), chunk.data()), "chunk");
        check(H5Pset_shuffle(plist), "shuffle");
        check(H5Pset_deflate(plist, 1), "deflate");
        check(H5Pset_fletcher32(plist), "checksum");  // a damaged chunk fails to read
    }
    H5Id ds(H5Dcreate2(parent, name.c_str(), file_type<T>(), space, H5P_DEFAULT, plist, H5P_DEFAULT), H5Dclose,
            "create dataset " + name);
    check(H5Dwrite(ds, native_type<T>(), H5S_ALL, H5S_ALL, H5P_DEFAULT, data), "write " + name);
}

template <class T>
void attr(hid_t obj, const std::string& name, const std::vector<T>& values) {
    const hsize_t n = values.size();
    H5Id space(values.size() == 1 ? H5Screate(H5S_SCALAR) : H5Screate_simple(1, &n, nullptr), H5Sclose, "attr space");
    H5Id a(H5Acreate2(obj, name.c_str(), file_type<T>(), space, H5P_DEFAULT, H5P_DEFAULT), H5Aclose, "attr " + name);
    check(H5Awrite(a, native_type<T>(), values.data()), "write attr " + name);
}
template <class T>
void attr(hid_t obj, const std::string& name, T value) {
    attr(obj, name, std::vector<T>{value});
}

// Variable-length UTF-8 strings: h5py reads them as str.
void attr_strings(hid_t obj, const std::string& name, const std::vector<std::string>& values, bool scalar) {
    H5Id type(H5Tcopy(H5T_C_S1), H5Tclose, "string type");
    check(H5Tset_size(type, H5T_VARIABLE), "string size");
    check(H5Tset_cset(type, H5T_CSET_UTF8), "string cset");
    const hsize_t n = values.size();
    H5Id space(scalar ? H5Screate(H5S_SCALAR) : H5Screate_simple(1, &n, nullptr), H5Sclose, "attr space");
    H5Id a(H5Acreate2(obj, name.c_str(), type, space, H5P_DEFAULT, H5P_DEFAULT), H5Aclose, "attr " + name);
    std::vector<const char*> ptrs;
    for (const std::string& s : values) ptrs.push_back(s.c_str());
    check(H5Awrite(a, type, ptrs.data()), "write attr " + name);
}
void attr(hid_t obj, const std::string& name, const std::string& value) { attr_strings(obj, name, {value}, true); }
void attr(hid_t obj, const std::string& name, const char* value) { attr(obj, name, std::string(value)); }

void write_surface(hid_t file, const Scene& scene, const TallyLayout& L, const std::vector<std::uint64_t>& data,
                   const RunInfo& info, const GlobalEstimate& g) {
    const std::size_t T = scene.triangle_count(), B = scene.bands.size();
    {
        H5Id mesh(group(file, "mesh"), H5Gclose, "group /mesh");
        std::vector<double> v;
        for (const Vec3& p : scene.vertices) v.insert(v.end(), {p.x, p.y, p.z});
        dataset(mesh, "vertices", {scene.vertices.size(), 3}, v.data());
        std::vector<std::uint32_t> t;
        for (const glm::uvec3& tri : scene.triangles) t.insert(t.end(), {tri.x, tri.y, tri.z});
        dataset(mesh, "triangles", {T, 3}, t.data());
        dataset(mesh, "area", {T}, scene.triangle_area_m2.data());
        dataset(mesh, "material", {T}, scene.triangle_material.data());
        std::vector<std::string> names;
        for (const Material& m : scene.materials) names.push_back(m.name);
        attr_strings(mesh, "material_names", names, false);
        // Also as a dataset, so the index in /mesh/material names a dataset row.
        H5Id type(H5Tcopy(H5T_C_S1), H5Tclose, "string type");
        check(H5Tset_size(type, H5T_VARIABLE), "string size");
        check(H5Tset_cset(type, H5T_CSET_UTF8), "string cset");
        const hsize_t n = names.size();
        H5Id space(H5Screate_simple(1, &n, nullptr), H5Sclose, "space");
        H5Id ds(H5Dcreate2(mesh, "material_names", type, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Dclose,
                "material_names");
        std::vector<const char*> ptrs;
        for (const std::string& s : names) ptrs.push_back(s.c_str());
        check(H5Dwrite(ds, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, ptrs.data()), "material_names");
    }
    // Format 2 (issue 13): every surface dataset has a side axis, [T, 2, B] (side 0 the front).
    H5Id glob(group(file, "global"), H5Gclose, "group /global");
    constexpr std::size_t kS = TallyLayout::kSides;
    const std::vector<hsize_t> dims{T, kS, B};
    auto slot_of = [&](std::size_t t, std::size_t side, std::size_t b, TallyLayout::SurfaceSlot s) {
        return data[L.surface(t, side, b, s)];
    };
    const std::pair<const char*, TallyLayout::SurfaceSlot> slots[] = {{"count_odd", TallyLayout::kCountOdd},
                                                                      {"count_even", TallyLayout::kCountEven},
                                                                      {"direct_odd", TallyLayout::kDirectOdd},
                                                                      {"direct_even", TallyLayout::kDirectEven}};
    std::vector<std::uint64_t> buf(T * kS * B);
    for (const auto& [name, slot] : slots) {
        for (std::size_t t = 0; t < T; ++t)
            for (std::size_t side = 0; side < kS; ++side)
                for (std::size_t b = 0; b < B; ++b) buf[(t * kS + side) * B + b] = slot_of(t, side, b, slot);
        dataset(glob, name, dims, buf.data());
    }
    // Sum over photons of (arrivals on the side)^2 = arrivals + repeats (tally.hpp).
    for (std::size_t t = 0; t < T; ++t)
        for (std::size_t side = 0; side < kS; ++side)
            for (std::size_t b = 0; b < B; ++b)
                buf[(t * kS + side) * B + b] = slot_of(t, side, b, TallyLayout::kCountOdd) +
                                               slot_of(t, side, b, TallyLayout::kCountEven) +
                                               slot_of(t, side, b, TallyLayout::kRepeats);
    dataset(glob, "sumsq", dims, buf.data());
    std::vector<double> e(T * kS * B), direct(T * kS * B);
    for (std::size_t t = 0; t < T; ++t)
        for (std::size_t side = 0; side < kS; ++side)
            for (std::size_t b = 0; b < B; ++b) {
                const double k = info.flux_per_photon_lm / scene.triangle_area_m2[t];
                const std::size_t i = (t * kS + side) * B + b;
                e[i] = k * static_cast<double>(slot_of(t, side, b, TallyLayout::kCountOdd) +
                                               slot_of(t, side, b, TallyLayout::kCountEven));
                direct[i] = k * static_cast<double>(slot_of(t, side, b, TallyLayout::kDirectOdd) +
                                                    slot_of(t, side, b, TallyLayout::kDirectEven));
            }
    dataset(glob, "illuminance", dims, e.data());
    dataset(glob, "illuminance_direct", dims, direct.data());
    // Per side, band-summed: E_odd - E_even (the terms of eq. 5) and the second-moment
    // standard error; float maps the XDMF companion can show as they are.
    std::vector<double> odd_even(T * kS);
    for (std::size_t t = 0; t < T; ++t)
        for (std::size_t side = 0; side < kS; ++side) {
            double d = 0.0;
            for (std::size_t b = 0; b < B; ++b)
                d += static_cast<double>(slot_of(t, side, b, TallyLayout::kCountOdd)) -
                     static_cast<double>(slot_of(t, side, b, TallyLayout::kCountEven));
            odd_even[t * kS + side] = 2.0 * d * info.flux_per_photon_lm / scene.triangle_area_m2[t];
        }
    dataset(glob, "odd_even_difference_lx", {T, kS}, odd_even.data());
    const std::vector<double> sigma = side_sigma_lx(L, data, scene.triangle_area_m2, info.flux_per_photon_lm,
                                                    info.photons);
    dataset(glob, "sigma_lx", {T, kS}, sigma.data());
    attr(glob, "sigma_lx", g.sigma_lx);
    attr(glob, "sigma_rel_arithmetic", g.sigma_rel_arithmetic);
    attr(glob, "sigma_rel_quadratic", g.sigma_rel_quadratic);
    attr(glob, "odd_even_rms_lx", g.odd_even_rms_lx);
    attr(glob, "moment_sigma_lx", g.moment_sigma_lx);
    attr(glob, "moment_sigma_rel_arithmetic", g.moment_sigma_rel_arithmetic);
    attr(glob, "moment_sigma_rel_quadratic", g.moment_sigma_rel_quadratic);
    if (L.replicates() > 0) {
        attr(glob, "replicate_sigma_lx", g.replicate_sigma_lx);
        attr(glob, "replicate_sigma_rel_arithmetic", g.replicate_sigma_rel_arithmetic);
        attr(glob, "replicate_sigma_rel_quadratic", g.replicate_sigma_rel_quadratic);
    }
    attr(glob, "error_estimator", g.estimator_name());
    attr(glob, "lit_area_m2", g.lit_area_m2);
    attr(glob, "lit_sides", g.lit_sides);
    attr(glob, "mean_arithmetic_lx", g.mean_arithmetic_lx);
    attr(glob, "mean_quadratic_lx", g.mean_quadratic_lx);
    attr(glob, "photons_escaped", data[L.counter(TallyLayout::kEscaped)]);
    attr(glob, "photons_absorbed", data[L.counter(TallyLayout::kAbsorbed)]);
    attr(glob, "photons_truncated", data[L.counter(TallyLayout::kTruncated)]);
}

// Cylindrical and semicylindrical detectors: the cylinders, and for a cylindrical one
// with a `horizontal` detector the modelling ratio per point and of the grid means.
void write_cylinders(hid_t g, const Scene& scene, std::size_t di, const std::vector<DetectorEstimate>& est) {
    const Detector& d = scene.detectors[di];
    attr(g, "radius_m", d.radius_m);
    attr(g, "height_m", d.height_m);
    attr(g, "lateral_area_m2", d.lateral_area_m2());
    if (d.type == DetectorType::semicylindrical)
        attr(g, "facing", std::vector<double>{d.facing.x, d.facing.y, d.facing.z});
    if (d.horizontal_index < 0) return;
    const std::size_t B = scene.bands.size();
    const ModellingRatio m = modelling_ratio(est[di], est[static_cast<std::size_t>(d.horizontal_index)], B);
    const std::vector<hsize_t> dims{static_cast<hsize_t>(d.ny), static_cast<hsize_t>(d.nx), B};
    dataset(g, "modelling_ratio", dims, m.ratio.data());
    dataset(g, "modelling_ratio_sigma_rel", dims, m.sigma_rel.data());
    attr(g, "horizontal", d.horizontal);
    attr(g, "modelling_ratio_mean", m.mean);
    attr(g, "modelling_ratio_mean_sigma_rel", m.mean_sigma_rel);
    attr(g, "modelling_ratio_min", m.min);
    attr(g, "modelling_ratio_max", m.max);
}

// Eavg, Emin, Emax, U0 of a grid or task area (illuminance_metrics.hpp), initial and
// maintained (times the lights' flux-weighted maintenance factor).
void write_metrics(hid_t g, const IlluminanceMetrics& initial, double mf) {
    attr(g, "metrics_cells", initial.cells);
    const IlluminanceMetrics maint = maintained(initial, mf);
    using Named = std::pair<std::string, const IlluminanceMetrics&>;
    for (const auto& [suffix, m] : {Named{"", initial}, Named{"_maintained", maint}}) {
        attr(g, "E_avg" + suffix + "_lx", m.avg_lx);
        attr(g, "E_avg" + suffix + "_sigma_lx", m.avg_sigma_lx);
        attr(g, "E_min" + suffix + "_lx", m.min_lx);
        attr(g, "E_min" + suffix + "_sigma_lx", m.min_sigma_lx);
        attr(g, "E_min" + suffix + "_bias_lx", m.min_bias_lx);
        attr(g, "E_max" + suffix + "_lx", m.max_lx);
        attr(g, "E_max" + suffix + "_sigma_lx", m.max_sigma_lx);
        attr(g, "E_max" + suffix + "_bias_lx", m.max_bias_lx);
    }
    attr(g, "E_min_cell",
         std::vector<std::uint64_t>{static_cast<std::uint64_t>(initial.min_i),
                                    static_cast<std::uint64_t>(initial.min_j)});
    attr(g, "E_max_cell",
         std::vector<std::uint64_t>{static_cast<std::uint64_t>(initial.max_i),
                                    static_cast<std::uint64_t>(initial.max_j)});
    attr(g, "E_min_competitors", initial.min_competitors);
    attr(g, "E_max_competitors", initial.max_competitors);
    attr(g, "U0", initial.u0);
    attr(g, "U0_sigma", initial.u0_sigma);
    attr(g, "U0_bias", initial.u0_bias);
    attr(g, "E_min_over_max", initial.min_over_max);
    attr(g, "E_min_over_max_sigma", initial.min_over_max_sigma);
    attr(g, "E_min_over_max_bias", initial.min_over_max_bias);
    attr(g, "U0_unreliable", std::uint64_t{initial.unreliable ? 1u : 0u});
}

void write_detectors(hid_t file, const Scene& scene, const TallyLayout& L, const std::vector<std::uint64_t>& data,
                     const std::vector<DetectorEstimate>& est) {
    H5Id dets(group(file, "detectors"), H5Gclose, "group /detectors");
    const std::size_t B = scene.bands.size();
    for (std::size_t di = 0; di < scene.detectors.size(); ++di) {
        const Detector& d = scene.detectors[di];
        if (d.observer >= 0) continue;  // an eye detector: /observers/NAME
        const DetectorEstimate& e = est[di];
        H5Id g(group(dets, d.name), H5Gclose, "group /detectors/" + d.name);
        const std::vector<hsize_t> dims{static_cast<hsize_t>(d.ny), static_cast<hsize_t>(d.nx), B};
        std::vector<std::uint64_t> n(d.cells() * B), q(d.cells() * B);
        for (int c = 0; c < d.cells(); ++c)
            for (std::size_t b = 0; b < B; ++b) {
                n[c * B + b] = data[L.detector_n(di, c, b)];
                q[c * B + b] = data[L.detector_q(di, c, b)];
            }
        dataset(g, "count", dims, n.data());
        dataset(g, "sumsq", dims, q.data());
        dataset(g, "value", dims, e.value.data());
        dataset(g, "sigma_rel", dims, e.sigma_rel.data());
        attr(g, "type", detector_type_name(d.type));
        attr(g, "units", d.units());
        attr(g, "center", std::vector<double>{d.center.x, d.center.y, d.center.z});
        attr(g, "normal", std::vector<double>{d.normal.x, d.normal.y, d.normal.z});
        attr(g, "up", std::vector<double>{d.v_axis.x, d.v_axis.y, d.v_axis.z});
        attr(g, "size", std::vector<double>{d.size_u, d.size_v});
        attr(g, "cells",
             std::vector<std::uint64_t>{static_cast<std::uint64_t>(d.nx), static_cast<std::uint64_t>(d.ny)});
        attr(g, "sigma_rel_arithmetic", e.sigma_rel_arithmetic);
        attr(g, "sigma_rel_quadratic", e.sigma_rel_quadratic);
        attr(g, "mean_arithmetic", e.mean_arithmetic);
        attr(g, "mean_quadratic", e.mean_quadratic);
        attr(g, "photons_received", e.photons_received);
        attr(g, "mean_value", e.mean_value);
        attr(g, "mean_sigma_rel", e.mean_sigma_rel);
        // What sigma_rel and the summaries are (docs/QMC.md): eq. (8) for independent
        // photons, or the spread of the R replicate means (sobol) with R - 1 dof.
        attr(g, "error_estimator", e.replicate_spread ? "replicate_spread" : "independent_photons_eq8");
        attr(g, "error_dof", static_cast<std::uint64_t>(e.dof));
        if (const std::size_t R = L.replicates(); R > 0) {
            std::vector<std::uint64_t> rn(R * d.cells() * B), rt(R);
            for (std::size_t r = 0; r < R; ++r) {
                rt[r] = data[L.detector_replicate_total_n(di, r)];
                for (int c = 0; c < d.cells(); ++c)
                    for (std::size_t b = 0; b < B; ++b)
                        rn[(r * d.cells() + c) * B + b] = data[L.detector_replicate_n(di, r, c, b)];
            }
            dataset(g, "replicate_count", {R, static_cast<hsize_t>(d.ny), static_cast<hsize_t>(d.nx), B}, rn.data());
            attr(g, "replicate_total", rt);
        }
        if (!e.metrics.empty()) {
            const double mf = scene.lights.maintenance_factor();
            write_metrics(g, e.metrics.front(), mf);
            if (e.metrics.size() > 1) {
                H5Id areas(group(g, "task_areas"), H5Gclose, "group /detectors/" + d.name + "/task_areas");
                for (std::size_t k = 1; k < e.metrics.size(); ++k) {
                    const IlluminanceMetrics& m = e.metrics[k];
                    H5Id a(group(areas, m.area), H5Gclose, "group task_areas/" + m.area);
                    attr(a, "cell_range",
                         std::vector<std::uint64_t>{static_cast<std::uint64_t>(m.i0), static_cast<std::uint64_t>(m.i1),
                                                    static_cast<std::uint64_t>(m.j0),
                                                    static_cast<std::uint64_t>(m.j1)});
                    write_metrics(a, m, mf);
                }
            }
        }
        if (d.type == DetectorType::luminance) {
            attr(g, "view_direction", std::vector<double>{d.cone_axis.x, d.cone_axis.y, d.cone_axis.z});
            attr(g, "half_angle_deg", d.half_angle_deg);
        }
        if (d.cylinders()) write_cylinders(g, scene, di, est);
    }
}

// /observers/NAME: UGR (CIE 117) from the eye detector's indirect illuminance and the
// luminaires' terms fixed at load (glare/observer.hpp), with the eye detector's tallies.
void write_observers(hid_t file, const Scene& scene, const TallyLayout& L, const std::vector<std::uint64_t>& data,
                     const std::vector<DetectorEstimate>& est) {
    if (scene.observers.empty()) return;
    H5Id obs(group(file, "observers"), H5Gclose, "group /observers");
    const std::size_t B = scene.bands.size();
    for (const Observer& o : scene.observers) {
        const std::size_t di = o.eye_detector;
        const Detector& d = scene.detectors[di];
        const DetectorEstimate& e = est[di];
        const UgrEstimate u = estimate_ugr(o.sources, e.mean_value, e.mean_sigma_rel);
        H5Id g(group(obs, o.name), H5Gclose, "group /observers/" + o.name);
        attr(g, "ugr", u.ugr);
        attr(g, "ugr_sigma", u.ugr_sigma);
        // Maintained: L^2 / Lb scales as a maintenance factor that all lights share.
        if (const double mf = scene.lights.maintenance_factor(); scene.lights.maintenance_factor_uniform() && mf < 1.0)
            attr(g, "ugr_maintained", u.ugr + 8.0 * std::log10(mf));
        attr(g, "background_luminance_cd_m2", u.background_luminance_cd_m2);
        attr(g, "indirect_vertical_illuminance_lx", u.indirect_illuminance_lx);
        attr(g, "indirect_vertical_illuminance_sigma_rel", u.indirect_sigma_rel);
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
        std::vector<std::uint64_t> n(B), q(B);
        for (std::size_t b = 0; b < B; ++b) {
            n[b] = data[L.detector_n(di, 0, b)];
            q[b] = data[L.detector_q(di, 0, b)];
        }
        dataset(g, "eye_count", {B}, n.data());
        dataset(g, "eye_sumsq", {B}, q.data());
        // Per luminaire in view, in the order of the lights.
        const std::size_t S = o.sources.size();
        if (S == 0) continue;
        std::vector<double> L_, omega, p, pos, alpha, beta, inten, area, dist;
        std::vector<std::uint64_t> light;
        std::vector<std::string> labels;
        for (const GlareSource& s : o.sources) {
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
}

void write_history(hid_t file, const std::vector<HistoryRow>& history, const RunInfo& info) {
    H5Id h(group(file, "history"), H5Gclose, "group /history");
    // Per-target columns: [rows, targets].
    const std::size_t nt = info.target_labels.size();
    std::vector<double> tv, tf, tp;
    for (const HistoryRow& r : history)
        for (std::size_t i = 0; i < nt; ++i) {
            tv.push_back(i < r.target_value.size() ? r.target_value[i] : std::nan(""));
            tf.push_back(i < r.target_forecast_s.size() ? r.target_forecast_s[i] : std::nan(""));
            tp.push_back(i < r.target_forecast_photons.size() ? r.target_forecast_photons[i] : std::nan(""));
        }
    if (nt > 0) {
        dataset(h, "target_value", {history.size(), nt}, tv.data());
        dataset(h, "target_forecast_s", {history.size(), nt}, tf.data());
        dataset(h, "target_forecast_photons", {history.size(), nt}, tp.data());
        attr_strings(h, "target_labels", info.target_labels, false);
        attr(h, "target_goals", info.target_goals);
    }
    std::vector<double> t, s, f;
    std::vector<std::uint64_t> p;
    for (const HistoryRow& r : history) {
        t.push_back(r.time_s);
        p.push_back(r.photons);
        s.push_back(r.sigma_rel_global);
        f.push_back(r.forecast_s);
    }
    const std::vector<hsize_t> dims{history.size()};
    dataset(h, "time_s", dims, t.data());
    dataset(h, "photons", dims, p.data());
    dataset(h, "sigma_rel_global", dims, s.data());
    dataset(h, "forecast_s", dims, f.data());
}

}  // namespace

void write_result(const fs::path& path, const Scene& scene, const TallyLayout& layout,
                  const std::vector<std::uint64_t>& tallies, const RunInfo& info, const GlobalEstimate& global,
                  const std::vector<DetectorEstimate>& detectors, const std::vector<HistoryRow>& history,
                  const CheckpointData* checkpoint) {
    std::vector<char> image;
    // HDF5 builds the file in memory (core driver, no backing store) and never touches
    // the disk: writing it is then plain POSIX I/O whose errors name the OS's reason, and
    // HDF5's own error stack stays silent.
    H5E_BEGIN_TRY {
        H5Id fapl(H5Pcreate(H5P_FILE_ACCESS), H5Pclose, "file access list");
        check(H5Pset_fapl_core(fapl, 1 << 20, 0), "core driver");
        // The image is taken when HDF5 frees it at close, after the superblock is final
        // (H5Fget_file_image on an open file has stale checksums in this format).
        MemoryImage captured;
        H5FD_file_image_callbacks_t callbacks = MemoryImage::callbacks(&captured);
        check(H5Pset_file_image_callbacks(fapl, &callbacks), "file image callbacks");
        // Format of HDF5 1.8 and later: every metadata block carries a checksum, so a
        // damaged file is refused by the reader instead of being misread.
        check(H5Pset_libver_bounds(fapl, H5F_LIBVER_V18, H5F_LIBVER_LATEST), "format bounds");
        // The first 512 bytes are kept for luxtrace's seal (file_seal.hpp).
        H5Id fcpl(H5Pcreate(H5P_FILE_CREATE), H5Pclose, "file creation list");
        check(H5Pset_userblock(fcpl, kSealBytes), "user block");
        H5Id file(H5Fcreate(path.c_str(), H5F_ACC_TRUNC, fcpl, fapl), H5Fclose, "create in memory");
        attr(file, "format", checkpoint != nullptr ? "luxtrace-checkpoint" : "luxtrace-result");
        attr(file, "format_version", kResultFormatVersion);
        attr(file, "luxtrace_version", info.luxtrace_version);
        attr(file, "scene_file", info.scene_file);
        attr(file, "scene_name", scene.name);
        attr(file, "seed", info.seed);
        attr(file, "ranks", static_cast<std::uint64_t>(info.ranks));
        attr(file, "threads_per_rank", static_cast<std::uint64_t>(info.threads_per_rank));
        attr(file, "photons", info.photons);
        attr(file, "flux_per_photon_lm", info.flux_per_photon_lm);
        attr(file, "total_flux_lm", scene.lights.total_flux_lm());
        // Values are initial; maintained ones are these times the maintenance factor
        // (flux-weighted over the lights; exact when all lights share one).
        attr(file, "maintenance_factor", scene.lights.maintenance_factor());
        attr(file, "maintenance_factor_uniform", std::uint64_t{scene.lights.maintenance_factor_uniform() ? 1u : 0u});
        attr(file, "elapsed_s", info.elapsed_s);
        attr(file, "stop_reason", info.stop_reason);
        attr_strings(file, "bands", scene.bands, false);
        attr(file, "sampler", info.sampler);
        attr(file, "replicates", static_cast<std::uint64_t>(layout.replicates()));  // 0: random
        if (layout.replicates() > 0) {
            std::vector<std::uint64_t> per(layout.replicates());
            for (std::size_t r = 0; r < per.size(); ++r) per[r] = tallies[layout.replicate_photons(r)];
            attr(file, "replicate_photons", per);
        }
        attr(file, "photon_layout", info.photon_layout);
        attr(file, "reductions", info.reductions);
        attr(file, "reduction_stall_s", info.reduction_stall_s);
        attr(file, "reduction_wait_s", info.reduction_wait_s);
        attr(file, "reduction_message_words", info.reduction_message_words);
        attr(file, "tally_words", static_cast<std::uint64_t>(layout.size()));
        write_surface(file, scene, layout, tallies, info, global);
        write_detectors(file, scene, layout, tallies, detectors);
        write_observers(file, scene, layout, tallies, detectors);
        write_history(file, history, info);
        if (checkpoint != nullptr) {
            H5Id ck(group(file, "checkpoint"), H5Gclose, "group /checkpoint");
            dataset(ck, "tallies", {checkpoint->tallies.size()}, checkpoint->tallies.data());
            dataset(ck, "done_ranges", {checkpoint->done.size() / 2, 2}, checkpoint->done.data());
            attr(ck, "budget", checkpoint->budget);
            attr(ck, "layout_size", static_cast<std::uint64_t>(layout.size()));
            attr(ck, "triangles", static_cast<std::uint64_t>(layout.triangles()));
            attr(ck, "bands", static_cast<std::uint64_t>(layout.bands()));
        }
        check(H5Fflush(file, H5F_SCOPE_GLOBAL), "flush");
        file.close();
        image = std::move(captured.bytes);
        image.resize(file_length(image));  // the driver's buffer grows in whole increments
        seal_image(image);
    }
    H5E_END_TRY;
    write_file_atomically(path, image);
}

}  // namespace luxtrace
