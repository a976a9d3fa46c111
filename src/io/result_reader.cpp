// Reading result files back by HDF5 path, and checkpoints for a restart.
#include "hdf5_file.hpp"
#include "luxtrace/core/error.hpp"
#include "luxtrace/io/file_seal.hpp"
#include "luxtrace/io/result_file.hpp"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <stdexcept>

namespace luxtrace {

using hdf5::attr_points;
using hdf5::fail;
using hdf5::Held;
using hdf5::open_attr;

ResultReader::ResultReader(const std::filesystem::path& path) : path_(path) {
    if (!std::filesystem::is_regular_file(path)) throw InputError(path.string() + ": no such result file");
    sealed_ = check_seal(path);  // before HDF5 parses a byte of it
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
    return hdf5::read_dataset<std::uint64_t>(path_, file_, name, shape);
}

std::vector<double> ResultReader::f64(const std::string& name, std::vector<std::size_t>* shape) const {
    return hdf5::read_dataset<double>(path_, file_, name, shape);
}

double ResultReader::attr_f64(const std::string& object, const std::string& name) const {
    const std::vector<double> v = f64_attr_array(object, name);
    return v.empty() ? 0.0 : v[0];
}

std::vector<double> ResultReader::f64_attr_array(const std::string& object, const std::string& name) const {
    Held a{open_attr(path_, file_, object, name), H5Aclose};
    Held space{H5Aget_space(a.id), H5Sclose};
    std::vector<double> v(attr_points(path_, space.id, object + "@" + name));
    herr_t ok = 0;
    if (!v.empty()) {
        H5E_BEGIN_TRY { ok = H5Aread(a.id, H5T_NATIVE_DOUBLE, v.data()); }
        H5E_END_TRY;
    }
    if (ok < 0) fail(path_, "attribute " + object + "@" + name + " is not a number (or is damaged)");
    return v;
}

std::uint64_t ResultReader::attr_u64(const std::string& object, const std::string& name) const {
    Held a{open_attr(path_, file_, object, name), H5Aclose};
    Held space{H5Aget_space(a.id), H5Sclose};
    // Read every element (an array attribute must not overrun a scalar), return the first.
    std::vector<std::uint64_t> v(std::max<std::size_t>(1, attr_points(path_, space.id, object + "@" + name)));
    herr_t ok = 0;
    H5E_BEGIN_TRY { ok = H5Aread(a.id, H5T_NATIVE_UINT64, v.data()); }
    H5E_END_TRY;
    if (ok < 0) fail(path_, "attribute " + object + "@" + name + " is not a whole number (or is damaged)");
    return v[0];
}

std::vector<std::string> ResultReader::attr_strs(const std::string& object, const std::string& name) const {
    const std::string what = object + "@" + name;
    Held a{open_attr(path_, file_, object, name), H5Aclose};
    Held type{H5Aget_type(a.id), H5Tclose};
    Held space{H5Aget_space(a.id), H5Sclose};
    const std::size_t n = attr_points(path_, space.id, what);
    if (type.id < 0 || H5Tget_class(type.id) != H5T_STRING) fail(path_, "attribute " + what + " is not text");
    std::vector<std::string> out;
    herr_t ok = 0;
    if (H5Tis_variable_str(type.id) > 0) {
        std::vector<char*> ptrs(n, nullptr);
        H5E_BEGIN_TRY { ok = H5Aread(a.id, type.id, ptrs.data()); }
        H5E_END_TRY;
        if (ok >= 0)
            for (char* p : ptrs) out.emplace_back(p ? p : "");
        if (n > 0) H5Dvlen_reclaim(type.id, space.id, H5P_DEFAULT, ptrs.data());
    } else {
        const std::size_t len = H5Tget_size(type.id);
        if (len == 0 || len > (std::size_t{1} << 20)) fail(path_, "attribute " + what + " has a damaged type");
        std::vector<char> buf(len * n + 1, '\0');
        if (n > 0) {
            H5E_BEGIN_TRY { ok = H5Aread(a.id, type.id, buf.data()); }
            H5E_END_TRY;
        }
        if (ok >= 0)
            for (std::size_t i = 0; i < n; ++i)
                out.emplace_back(buf.data() + i * len, strnlen(buf.data() + i * len, len));
    }
    if (ok < 0) fail(path_, "attribute " + what + " cannot be read (damaged)");
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
    herr_t ok = 0;
    H5E_BEGIN_TRY {
        ok = H5Literate_by_name(file_, group.c_str(), H5_INDEX_NAME, H5_ITER_INC, nullptr, cb, &names, H5P_DEFAULT);
    }
    H5E_END_TRY;
    if (ok < 0) fail(path_, "cannot list group " + group + " (damaged)");
    return names;
}

CheckpointState read_checkpoint(const std::filesystem::path& path) {
    const ResultReader r(path);
    const std::string where = path.string() + ": ";
    if (r.attr_str("/", "format") != "luxtrace-checkpoint" || !r.has("/checkpoint"))
        throw InputError(where + "not a luxtrace checkpoint (it is a result file; restart needs a checkpoint)");
    // Unsealed checkpoints come from luxtrace 0.1, whose photons drew other random numbers.
    if (!r.sealed())
        throw InputError(where +
                         "this checkpoint has no luxtrace seal: it was written by luxtrace 0.1 (photon layout 1); "
                         "continue it with that version or start anew");
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
        if (r.has_attr("/", "photon_layout")) s.photon_layout = r.attr_u64("/", "photon_layout");
        if (r.has_attr("/", "replicates")) s.replicates = r.attr_u64("/", "replicates");
        if (r.has_attr("/", "light_groups")) s.light_groups = r.attr_strs("/", "light_groups");
        if (r.has_attr("/", "group_maps")) s.group_maps = r.attr_u64("/", "group_maps") != 0;
        s.format_version = r.attr_u64("/", "format_version");
        s.elapsed_s = r.attr_f64("/", "elapsed_s");
        const auto t = r.f64("/history/time_s");
        const auto p = r.u64("/history/photons");
        const auto g = r.f64("/history/sigma_rel_global");
        const auto f = r.f64("/history/forecast_s");
        if (p.size() != t.size() || g.size() != t.size() || f.size() != t.size())
            throw InputError(where + "the /history columns differ in length");
        std::vector<std::size_t> shape;
        std::vector<double> tv, tf, tp;
        if (r.has("/history/target_value")) {
            tv = r.f64("/history/target_value", &shape);
            tf = r.f64("/history/target_forecast_s");
            if (r.has("/history/target_forecast_photons")) tp = r.f64("/history/target_forecast_photons");
            if (shape.size() != 2 || shape[0] != t.size() || tf.size() != tv.size() ||
                (!tp.empty() && tp.size() != tv.size()))
                throw InputError(where + "the /history target columns do not match its rows");
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
    } catch (const InputError& e) {
        throw InputError(std::string(e.what()) + " (damaged checkpoint)");
    }
    if (s.tallies.size() != s.layout_size || s.done.size() % 2 != 0)
        throw InputError(where + "damaged checkpoint: inconsistent sizes");
    for (std::size_t i = 0; i < s.done.size(); i += 2)
        if (s.done[i] > s.done[i + 1])
            throw InputError(where + "damaged checkpoint: photon range " + std::to_string(s.done[i]) + ".." +
                             std::to_string(s.done[i + 1]) + " runs backwards");
    return s;
}

}  // namespace luxtrace
