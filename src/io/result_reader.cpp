// Reading result files back (luxtrace info, tests, later the renderer).
#include "luxtrace/core/error.hpp"
#include "luxtrace/io/result_file.hpp"

#include <hdf5.h>

#include <cmath>
#include <cstring>
#include <stdexcept>

namespace luxtrace {

namespace {

struct Closer {
    hid_t id;
    herr_t (*fn)(hid_t);
    ~Closer() { if (id >= 0) fn(id); }
};

template <class T>
std::vector<T> read_dataset(hid_t file, const std::string& name, hid_t mem_type, std::vector<std::size_t>* shape) {
    Closer ds{H5Dopen2(file, name.c_str(), H5P_DEFAULT), H5Dclose};
    if (ds.id < 0) throw std::runtime_error("result file has no dataset " + name);
    Closer space{H5Dget_space(ds.id), H5Sclose};
    const int rank = H5Sget_simple_extent_ndims(space.id);
    std::vector<hsize_t> dims(static_cast<std::size_t>(std::max(rank, 0)));
    H5Sget_simple_extent_dims(space.id, dims.data(), nullptr);
    std::size_t total = 1;
    for (hsize_t d : dims) total *= d;
    if (shape != nullptr) shape->assign(dims.begin(), dims.end());
    std::vector<T> out(total);
    if (total > 0 && H5Dread(ds.id, mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, out.data()) < 0)
        throw std::runtime_error("cannot read dataset " + name);
    return out;
}

hid_t open_attr(hid_t file, const std::string& object, const std::string& name) {
    const hid_t a = H5Aopen_by_name(file, object.c_str(), name.c_str(), H5P_DEFAULT, H5P_DEFAULT);
    if (a < 0) throw std::runtime_error("result file has no attribute " + object + "@" + name);
    return a;
}

}  // namespace

ResultReader::ResultReader(const std::filesystem::path& path) : path_(path) {
    if (!std::filesystem::is_regular_file(path)) throw InputError(path.string() + ": no such result file");
    H5E_BEGIN_TRY { file_ = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT); }
    H5E_END_TRY;
    if (file_ < 0) throw InputError(path.string() + ": not an HDF5 file");
    std::string format;
    try {
        format = attr_str("/", "format");
    } catch (const std::exception&) {
    }
    if (format != "luxtrace-result" && format != "luxtrace-checkpoint") {
        H5Fclose(file_);
        throw InputError(path.string() + ": not a luxtrace result (attribute 'format' is missing or wrong)");
    }
}

ResultReader::~ResultReader() {
    if (file_ >= 0) H5Fclose(file_);
}

bool ResultReader::has(const std::string& object) const {
    htri_t ok = 0;
    H5E_BEGIN_TRY { ok = H5Lexists(file_, object.c_str(), H5P_DEFAULT); }
    H5E_END_TRY;
    return ok > 0;
}

bool ResultReader::has_attr(const std::string& object, const std::string& name) const {
    htri_t ok = 0;
    H5E_BEGIN_TRY { ok = H5Aexists_by_name(file_, object.c_str(), name.c_str(), H5P_DEFAULT); }
    H5E_END_TRY;
    return ok > 0;
}

std::vector<std::uint64_t> ResultReader::u64(const std::string& name, std::vector<std::size_t>* shape) const {
    return read_dataset<std::uint64_t>(file_, name, H5T_NATIVE_UINT64, shape);
}

std::vector<double> ResultReader::f64(const std::string& name, std::vector<std::size_t>* shape) const {
    return read_dataset<double>(file_, name, H5T_NATIVE_DOUBLE, shape);
}

double ResultReader::attr_f64(const std::string& object, const std::string& name) const {
    const std::vector<double> v = f64_attr_array(object, name);
    return v.empty() ? 0.0 : v[0];
}

std::vector<double> ResultReader::f64_attr_array(const std::string& object, const std::string& name) const {
    Closer a{open_attr(file_, object, name), H5Aclose};
    Closer space{H5Aget_space(a.id), H5Sclose};
    std::vector<double> v(static_cast<std::size_t>(H5Sget_simple_extent_npoints(space.id)));
    if (!v.empty()) H5Aread(a.id, H5T_NATIVE_DOUBLE, v.data());
    return v;
}

std::uint64_t ResultReader::attr_u64(const std::string& object, const std::string& name) const {
    Closer a{open_attr(file_, object, name), H5Aclose};
    Closer space{H5Aget_space(a.id), H5Sclose};
    // Read every element (an array attribute must not overrun a scalar), return the first.
    std::vector<std::uint64_t> v(static_cast<std::size_t>(std::max<hssize_t>(1, H5Sget_simple_extent_npoints(space.id))));
    H5Aread(a.id, H5T_NATIVE_UINT64, v.data());
    return v[0];
}

std::vector<std::string> ResultReader::attr_strs(const std::string& object, const std::string& name) const {
    Closer a{open_attr(file_, object, name), H5Aclose};
    Closer type{H5Aget_type(a.id), H5Tclose};
    Closer space{H5Aget_space(a.id), H5Sclose};
    const hssize_t n = H5Sget_simple_extent_npoints(space.id);
    std::vector<std::string> out;
    if (H5Tis_variable_str(type.id) > 0) {
        std::vector<char*> ptrs(static_cast<std::size_t>(n), nullptr);
        H5Aread(a.id, type.id, ptrs.data());
        for (char* p : ptrs) out.emplace_back(p ? p : "");
        H5Dvlen_reclaim(type.id, space.id, H5P_DEFAULT, ptrs.data());
    } else {
        const std::size_t len = H5Tget_size(type.id);
        std::vector<char> buf(len * static_cast<std::size_t>(n) + 1, '\0');
        H5Aread(a.id, type.id, buf.data());
        for (hssize_t i = 0; i < n; ++i) out.emplace_back(buf.data() + i * len, strnlen(buf.data() + i * len, len));
    }
    return out;
}

std::string ResultReader::attr_str(const std::string& object, const std::string& name) const {
    const auto v = attr_strs(object, name);
    return v.empty() ? std::string() : v[0];
}

std::vector<std::string> ResultReader::children(const std::string& group) const {
    std::vector<std::string> names;
    if (!has(group)) return names;
    auto cb = [](hid_t, const char* name, const H5L_info_t*, void* data) -> herr_t {
        static_cast<std::vector<std::string>*>(data)->emplace_back(name);
        return 0;
    };
    H5Literate_by_name(file_, group.c_str(), H5_INDEX_NAME, H5_ITER_INC, nullptr, cb, &names, H5P_DEFAULT);
    return names;
}

}  // namespace luxtrace

namespace luxtrace {

CheckpointState read_checkpoint(const std::filesystem::path& path) {
    const ResultReader r(path);
    const std::string where = path.string() + ": ";
    if (r.attr_str("/", "format") != "luxtrace-checkpoint" || !r.has("/checkpoint"))
        throw InputError(where + "not a luxtrace checkpoint (it is a result file; restart needs a checkpoint)");
    CheckpointState s;
    try {
        s.tallies = r.u64("/checkpoint/tallies");
        s.done = r.u64("/checkpoint/done_ranges");
        s.budget = r.attr_u64("/checkpoint", "budget");
        s.layout_size = r.attr_u64("/checkpoint", "layout_size");
        s.triangles = r.attr_u64("/checkpoint", "triangles");
        s.bands = r.attr_u64("/checkpoint", "bands");
        s.seed = r.attr_u64("/", "seed");
        s.sampler = r.attr_str("/", "sampler");
        s.elapsed_s = r.attr_f64("/", "elapsed_s");
        const auto t = r.f64("/history/time_s");
        const auto p = r.u64("/history/photons");
        const auto g = r.f64("/history/sigma_rel_global");
        const auto f = r.f64("/history/forecast_s");
        std::vector<std::size_t> shape;
        std::vector<double> tv, tf, tp;
        if (r.has("/history/target_value")) {
            tv = r.f64("/history/target_value", &shape);
            tf = r.f64("/history/target_forecast_s");
            if (r.has("/history/target_forecast_photons")) tp = r.f64("/history/target_forecast_photons");
        }
        const std::size_t nt = shape.size() == 2 ? shape[1] : 0;
        for (std::size_t i = 0; i < t.size(); ++i) {
            HistoryRow row{t[i], p[i], g[i], f[i], {}, {}, {}};
            for (std::size_t j = 0; j < nt; ++j) {
                row.target_value.push_back(tv[i * nt + j]);
                row.target_forecast_s.push_back(tf[i * nt + j]);
                row.target_forecast_photons.push_back(tp.empty() ? std::nan("") : tp[i * nt + j]);
            }
            s.history.push_back(std::move(row));
        }
    } catch (const std::runtime_error& e) {
        throw InputError(where + "damaged checkpoint: " + e.what());
    }
    if (s.tallies.size() != s.layout_size || s.done.size() % 2 != 0)
        throw InputError(where + "damaged checkpoint: inconsistent sizes");
    return s;
}

}  // namespace luxtrace
