#pragma once
// The HDF5 calls luxtrace's result files are made of, shared by the writer's parts and the
// readers. Internal to src/io: no other code includes an HDF5 header.
#include <hdf5.h>

#include <cstdint>
#include <filesystem>
#include <functional>
#include <span>
#include <string>
#include <type_traits>
#include <vector>

namespace luxtrace::hdf5 {

// Owns one HDF5 identifier and closes it with the matching function; a failed call
// (negative id) throws, naming `what`.
class Id {
public:
    using Closer = herr_t (*)(hid_t);
    Id(hid_t id, Closer close, const std::string& what);
    ~Id() { close(); }
    void close();
    Id(Id&& other) noexcept : id_(other.id_), close_(other.close_) { other.id_ = -1; }
    Id(const Id&) = delete;
    Id& operator=(const Id&) = delete;
    operator hid_t() const { return id_; }

private:
    hid_t id_;
    Closer close_;
};

void check(herr_t status, const std::string& what);

// ---- Writing (errors are std::runtime_error: the file is luxtrace's own) ----

// A new group under `parent`.
Id create_group(hid_t parent, const std::string& name, const std::string& what);

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

// A dataset of `dims` from `data` (row-major, dims' product elements).
void write_dataset(hid_t parent, const std::string& name, const std::vector<hsize_t>& dims, hid_t file_type,
                   hid_t mem_type, const void* data);
template <class T>
void dataset(hid_t parent, const std::string& name, const std::vector<hsize_t>& dims, const T* data) {
    write_dataset(parent, name, dims, file_type<T>(), native_type<T>(), data);
}
// A dataset of 32-bit floats of `dims` whose rows come a slab at a time from `rows` (rows
// [first, first + count), row-major into `out`): the dataset write_dataset makes of the
// whole, without the whole in memory.
void write_float_rows(hid_t parent, const std::string& name, const std::vector<hsize_t>& dims,
                      const std::function<void(hsize_t first, hsize_t count, std::span<float> out)>& rows);
// A one-dimensional dataset of variable-length UTF-8 strings.
void string_dataset(hid_t parent, const std::string& name, const std::vector<std::string>& values);

// Numeric attributes: one value is stored as a scalar, several as an array.
void write_attr(hid_t obj, const std::string& name, std::size_t n, hid_t file_type, hid_t mem_type, const void* values);
template <class T>
void attr(hid_t obj, const std::string& name, const std::vector<T>& values) {
    write_attr(obj, name, values.size(), file_type<T>(), native_type<T>(), values.data());
}
template <class T>
void attr(hid_t obj, const std::string& name, T value) {
    attr(obj, name, std::vector<T>{value});
}
// Variable-length UTF-8 strings: h5py reads them as str. `scalar`: one string, not an array.
void attr_strings(hid_t obj, const std::string& name, const std::vector<std::string>& values, bool scalar);
void attr(hid_t obj, const std::string& name, const std::string& value);
void attr(hid_t obj, const std::string& name, const char* value);

// Builds an HDF5 file in memory (core driver, no backing store) with a user block of
// `userblock` bytes, lets `fill` write its content, and returns the file's bytes: those
// HDF5 writes to disk from the same content. HDF5 never touches the disk, so writing the
// bytes is plain POSIX I/O whose errors name the OS's reason, and HDF5's own error stack
// stays silent. `name` only names the file; `increment`, the core driver's buffer's
// growth step, changes nothing in the bytes (tests sweep it).
inline constexpr std::size_t kCoreIncrement = std::size_t{1} << 20;
std::vector<char> file_image(const std::filesystem::path& name, std::size_t userblock,
                             const std::function<void(hid_t file)>& fill, std::size_t increment = kCoreIncrement);

// ---- Reading (errors are InputError naming the file: a damaged file is bad input) ----

[[noreturn]] void fail(const std::filesystem::path& path, const std::string& what);

// Closes an identifier a reader opened, if it is valid; never throws (a destructor on the
// way out of a failed read).
struct Held {
    hid_t id;
    herr_t (*close)(hid_t);
    ~Held() {
        if (id >= 0) close(id);
    }
};

// The elements of dataset `name` as `mem_type` (double or uint64), and its shape.
template <class T>
std::vector<T> read_dataset(const std::filesystem::path& path, hid_t file, const std::string& name,
                            std::vector<std::size_t>* shape);

// Opens attribute object@name; the caller closes it.
hid_t open_attr(const std::filesystem::path& path, hid_t file, const std::string& object, const std::string& name);

// Elements of an attribute's dataspace, refused when damaged or absurd.
std::size_t attr_points(const std::filesystem::path& path, hid_t space, const std::string& what);

}  // namespace luxtrace::hdf5
