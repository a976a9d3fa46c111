#include "luxtrace/io/result_reader.hpp"

#include "hdf5_file.hpp"
#include "luxtrace/core/error.hpp"
#include "luxtrace/io/file_seal.hpp"

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

}  // namespace luxtrace
