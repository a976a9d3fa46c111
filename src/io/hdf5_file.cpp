#include "hdf5_file.hpp"

#include "chunk_filters.hpp"
#include "luxtrace/core/error.hpp"
#include "luxtrace/io/file_seal.hpp"

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <stdexcept>

namespace luxtrace::hdf5 {

Id::Id(hid_t id, Closer close, const std::string& what) : id_(id), close_(close) {
    if (id_ < 0) throw std::runtime_error("HDF5: " + what + " failed");
}

void Id::close() {
    if (id_ >= 0 && close_(id_) < 0) {
        id_ = -1;
        throw std::runtime_error("HDF5: close failed");
    }
    id_ = -1;
}

void check(herr_t status, const std::string& what) {
    if (status < 0) throw std::runtime_error("HDF5: " + what + " failed");
}

namespace {

// A creation property list without the object's modification time: a file's bytes then
// depend on its content alone, not on the second it was written.
Id untimed(hid_t plist_class) {
    Id plist(H5Pcreate(plist_class), H5Pclose, "property list");
    check(H5Pset_obj_track_times(plist, 0), "object times");
    return plist;
}

}  // namespace

Id create_group(hid_t parent, const std::string& name, const std::string& what) {
    const Id gcpl = untimed(H5P_GROUP_CREATE);
    return Id(H5Gcreate2(parent, name.c_str(), H5P_DEFAULT, gcpl, H5P_DEFAULT), H5Gclose, what);
}

namespace {

constexpr int kDeflateLevel = 1;

// Writes chunks [first, last) of the dataset (rows [c * chunk_rows, + chunk_rows)) from
// `bytes`, their rows (the first chunk's first row at bytes[0]), each filtered on whichever
// core is free (chunk_filters.hpp: the bytes HDF5's own pipeline makes) and handed to HDF5
// as it is, in chunk order. A large map's compression took most of a ten-million-triangle
// result's write on one core (issue 26).
void write_chunk_range(hid_t ds, const std::string& name, const std::vector<hsize_t>& dims, hsize_t chunk_rows,
                       std::size_t element_size, const unsigned char* bytes, std::size_t first, std::size_t last) {
    std::size_t row_bytes = element_size;
    for (std::size_t d = 1; d < dims.size(); ++d) row_bytes *= static_cast<std::size_t>(dims[d]);
    const std::size_t chunk_bytes = static_cast<std::size_t>(chunk_rows) * row_bytes;
    const std::size_t data_end = static_cast<std::size_t>(dims[0]) * row_bytes - first * chunk_bytes;
    std::vector<std::vector<unsigned char>> stored(last - first);
    tbb::parallel_for(first, last, [&](std::size_t c) {
        const std::size_t begin = (c - first) * chunk_bytes, end = std::min(data_end, begin + chunk_bytes);
        if (end - begin == chunk_bytes) {
            stored[c - first] = filtered_chunk({bytes + begin, chunk_bytes}, element_size, kDeflateLevel);
            return;
        }
        // The last chunk is stored whole, zero (the fill value) past the data's end.
        std::vector<unsigned char> padded(chunk_bytes, 0);
        std::copy(bytes + begin, bytes + end, padded.begin());
        stored[c - first] = filtered_chunk(padded, element_size, kDeflateLevel);
    });
    std::vector<hsize_t> offset(dims.size(), 0);
    for (std::size_t c = first; c < last; ++c) {
        offset[0] = static_cast<hsize_t>(c) * chunk_rows;
        const std::vector<unsigned char>& st = stored[c - first];
        check(H5Dwrite_chunk(ds, H5P_DEFAULT, 0, offset.data(), st.size(), st.data()), "write " + name);
    }
}

// A batch of chunks at a time, so that memory stays a few chunks per core.
std::size_t chunk_batch() { return 8 * static_cast<std::size_t>(std::max(1, tbb::this_task_arena::max_concurrency())); }

void write_chunks(hid_t ds, const std::string& name, const std::vector<hsize_t>& dims, hsize_t chunk_rows,
                  std::size_t element_size, const void* data) {
    std::size_t row_bytes = element_size;
    for (std::size_t d = 1; d < dims.size(); ++d) row_bytes *= static_cast<std::size_t>(dims[d]);
    const std::size_t chunk_bytes = static_cast<std::size_t>(chunk_rows) * row_bytes;
    const std::size_t chunks = static_cast<std::size_t>((dims[0] + chunk_rows - 1) / chunk_rows);
    const auto* bytes = static_cast<const unsigned char*>(data);
    for (std::size_t first = 0; first < chunks; first += chunk_batch())
        write_chunk_range(ds, name, dims, chunk_rows, element_size, bytes + first * chunk_bytes, first,
                          std::min(chunks, first + chunk_batch()));
}

// The chunk's rows for a dataset of `dims` (0: not chunked): about 64 k elements a chunk.
hsize_t chunk_rows_for(const std::vector<hsize_t>& dims) {
    hsize_t total = 1;
    for (hsize_t d : dims) total *= d;
    if (total < 4096 || dims.empty()) return 0;
    return std::max<hsize_t>(1, std::min<hsize_t>(dims[0], (1u << 16) / std::max<hsize_t>(1, total / dims[0])));
}

Id create_dataset(hid_t parent, const std::string& name, const std::vector<hsize_t>& dims, hid_t file_type,
                  hsize_t chunk_rows) {
    Id space(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr), H5Sclose, "dataspace");
    // Large maps are chunked and compressed: counts compress well.
    Id plist = untimed(H5P_DATASET_CREATE);
    if (chunk_rows > 0) {
        std::vector<hsize_t> chunk = dims;
        chunk[0] = chunk_rows;
        check(H5Pset_chunk(plist, static_cast<int>(chunk.size()), chunk.data()), "chunk");
        check(H5Pset_shuffle(plist), "shuffle");
        check(H5Pset_deflate(plist, kDeflateLevel), "deflate");
        check(H5Pset_fletcher32(plist), "checksum");  // a damaged chunk fails to read
    }
    return Id(H5Dcreate2(parent, name.c_str(), file_type, space, H5P_DEFAULT, plist, H5P_DEFAULT), H5Dclose,
              "create dataset " + name);
}

}  // namespace

void write_dataset(hid_t parent, const std::string& name, const std::vector<hsize_t>& dims, hid_t file_type,
                   hid_t mem_type, const void* data) {
    const hsize_t chunk_rows = chunk_rows_for(dims);
    const Id ds = create_dataset(parent, name, dims, file_type, chunk_rows);
    // The numbers' bytes are the file's when the types agree (little-endian machines).
    if (chunk_rows > 0 && H5Tequal(file_type, mem_type) > 0)
        write_chunks(ds, name, dims, chunk_rows, H5Tget_size(mem_type), data);
    else check(H5Dwrite(ds, mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data), "write " + name);
}

void write_float_rows(hid_t parent, const std::string& name, const std::vector<hsize_t>& dims,
                      const std::function<void(hsize_t first, hsize_t count, std::span<float> out)>& rows) {
    const hsize_t chunk_rows = chunk_rows_for(dims);
    const Id ds = create_dataset(parent, name, dims, H5T_IEEE_F32LE, chunk_rows);
    std::size_t row = 1;
    for (std::size_t d = 1; d < dims.size(); ++d) row *= static_cast<std::size_t>(dims[d]);
    if (chunk_rows == 0 || H5Tequal(H5T_IEEE_F32LE, H5T_NATIVE_FLOAT) <= 0) {  // small, or a big-endian machine
        std::vector<float> all(static_cast<std::size_t>(dims.empty() ? 0 : dims[0]) * row);
        if (!dims.empty()) rows(0, dims[0], all);
        check(H5Dwrite(ds, H5T_NATIVE_FLOAT, H5S_ALL, H5S_ALL, H5P_DEFAULT, all.data()), "write " + name);
        return;
    }
    const std::size_t chunks = static_cast<std::size_t>((dims[0] + chunk_rows - 1) / chunk_rows);
    std::vector<float> buf;
    for (std::size_t first = 0; first < chunks; first += chunk_batch()) {
        const std::size_t last = std::min(chunks, first + chunk_batch());
        const hsize_t r0 = first * chunk_rows, r1 = std::min<hsize_t>(dims[0], last * chunk_rows);
        buf.assign(static_cast<std::size_t>(r1 - r0) * row, 0.0F);
        rows(r0, r1 - r0, buf);
        write_chunk_range(ds, name, dims, chunk_rows, sizeof(float), reinterpret_cast<const unsigned char*>(buf.data()),
                          first, last);
    }
}

namespace {

Id utf8_string_type() {
    Id type(H5Tcopy(H5T_C_S1), H5Tclose, "string type");
    check(H5Tset_size(type, H5T_VARIABLE), "string size");
    check(H5Tset_cset(type, H5T_CSET_UTF8), "string cset");
    return type;
}

std::vector<const char*> c_strings(const std::vector<std::string>& values) {
    std::vector<const char*> ptrs;
    for (const std::string& s : values) ptrs.push_back(s.c_str());
    return ptrs;
}

}  // namespace

void string_dataset(hid_t parent, const std::string& name, const std::vector<std::string>& values) {
    const Id type = utf8_string_type();
    const hsize_t n = values.size();
    Id space(H5Screate_simple(1, &n, nullptr), H5Sclose, "space");
    const Id dcpl = untimed(H5P_DATASET_CREATE);
    Id ds(H5Dcreate2(parent, name.c_str(), type, space, H5P_DEFAULT, dcpl, H5P_DEFAULT), H5Dclose, name);
    const std::vector<const char*> ptrs = c_strings(values);
    check(H5Dwrite(ds, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, ptrs.data()), name);
}

void write_attr(hid_t obj, const std::string& name, std::size_t n, hid_t file_type, hid_t mem_type,
                const void* values) {
    const hsize_t dim = n;
    Id space(n == 1 ? H5Screate(H5S_SCALAR) : H5Screate_simple(1, &dim, nullptr), H5Sclose, "attr space");
    Id a(H5Acreate2(obj, name.c_str(), file_type, space, H5P_DEFAULT, H5P_DEFAULT), H5Aclose, "attr " + name);
    check(H5Awrite(a, mem_type, values), "write attr " + name);
}

void attr_strings(hid_t obj, const std::string& name, const std::vector<std::string>& values, bool scalar) {
    const Id type = utf8_string_type();
    const hsize_t n = values.size();
    Id space(scalar ? H5Screate(H5S_SCALAR) : H5Screate_simple(1, &n, nullptr), H5Sclose, "attr space");
    Id a(H5Acreate2(obj, name.c_str(), type, space, H5P_DEFAULT, H5P_DEFAULT), H5Aclose, "attr " + name);
    const std::vector<const char*> ptrs = c_strings(values);
    check(H5Awrite(a, type, ptrs.data()), "write attr " + name);
}

void attr(hid_t obj, const std::string& name, const std::string& value) { attr_strings(obj, name, {value}, true); }
void attr(hid_t obj, const std::string& name, const char* value) { attr(obj, name, std::string(value)); }

namespace {

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

// Length of the HDF5 file in `image`: the "end of file address" of its version 2/3
// superblock (HDF5 File Format Specification, section II.A), which H5F_LIBVER_V18 selects:
// signature (8 bytes), versions and sizes (4), base address (8), extension address (8),
// end of file address (8, little-endian). HDF5 stores it as an absolute address, its
// relative end of allocated space plus the base address, which is the user block's size
// (H5F__cache_superblock_serialize): the user block is in it already. Issue 35: adding it
// again asked for 512 bytes past the file, which the driver's buffer held (zeros) except
// when the file ended in the last 512 bytes before a multiple of its increment.
std::size_t file_length(const std::vector<char>& image, std::size_t userblock) {
    const char* sb = image.data() + userblock;
    if (image.size() < userblock + 48 || std::memcmp(sb, kHdf5Signature, 8) != 0 || (sb[8] != 2 && sb[8] != 3) ||
        sb[9] != 8)
        throw std::runtime_error("HDF5: unexpected superblock in the in-memory file image");
    auto address = [&](int at) {
        std::uint64_t a = 0;
        for (int i = 7; i >= 0; --i) a = (a << 8) | static_cast<unsigned char>(sb[at + i]);
        return a;
    };
    const std::uint64_t base = address(12), eof = address(28);
    if (base != userblock || eof < userblock + 48 || eof > (std::uint64_t{1} << 62))
        throw std::runtime_error("HDF5: the in-memory file image's superblock gives base address " +
                                 std::to_string(base) + " and end of file " + std::to_string(eof) + " with a " +
                                 std::to_string(userblock) + "-byte user block");
    return static_cast<std::size_t>(eof);
}

}  // namespace

std::vector<char> file_image(const std::filesystem::path& name, std::size_t userblock,
                             const std::function<void(hid_t file)>& fill, std::size_t increment) {
    std::vector<char> image;
    H5E_BEGIN_TRY {
        Id fapl(H5Pcreate(H5P_FILE_ACCESS), H5Pclose, "file access list");
        check(H5Pset_fapl_core(fapl, increment, 0), "core driver");
        // The image is taken when HDF5 frees it at close, after the superblock is final
        // (H5Fget_file_image on an open file has stale checksums in this format).
        MemoryImage captured;
        H5FD_file_image_callbacks_t callbacks = MemoryImage::callbacks(&captured);
        check(H5Pset_file_image_callbacks(fapl, &callbacks), "file image callbacks");
        // Format of HDF5 1.8 and later: every metadata block carries a checksum, so a
        // damaged file is refused by the reader instead of being misread.
        check(H5Pset_libver_bounds(fapl, H5F_LIBVER_V18, H5F_LIBVER_LATEST), "format bounds");
        Id fcpl = untimed(H5P_FILE_CREATE);  // the root group's header too
        check(H5Pset_userblock(fcpl, userblock), "user block");
        Id file(H5Fcreate(name.c_str(), H5F_ACC_TRUNC, fcpl, fapl), H5Fclose, "create in memory");
        fill(file);
        check(H5Fflush(file, H5F_SCOPE_GLOBAL), "flush");
        file.close();
        image = std::move(captured.bytes);
        // The driver's buffer is the bytes written, rounded up to a whole increment: the
        // file is its first file_length bytes. Should HDF5 leave allocated space unwritten
        // at the end, the file on disk has zeros there (HDF5 extends it to its end of file
        // when it closes it, which the core driver skips without a backing store): so
        // does the image (FileImage.IsTheFileHdf5WritesToDisk).
        image.resize(file_length(image, userblock), 0);
    }
    H5E_END_TRY;
    return image;
}

// ---- Reading ----

void fail(const std::filesystem::path& path, const std::string& what) { throw InputError(path.string() + ": " + what); }

// A dataset's elements come from its stored bytes: uncompressed one for one, deflated
// (large datasets) at most about 1032 to 1 (zlib's limit). A claim of more than that is
// damage, and must not allocate gigabytes.
constexpr std::size_t kMaxUnbackedBytes = std::size_t{64} << 20;
constexpr std::size_t kMaxDeflateRatio = 1100;

template <class T>
std::vector<T> read_dataset(const std::filesystem::path& path, hid_t file, const std::string& name,
                            std::vector<std::size_t>* shape) {
    Held ds{-1, H5Dclose};
    H5E_BEGIN_TRY { ds.id = H5Dopen2(file, name.c_str(), H5P_DEFAULT); }
    H5E_END_TRY;
    if (ds.id < 0) fail(path, "result file has no dataset " + name + " (or it is damaged)");
    Held space{H5Dget_space(ds.id), H5Sclose};
    if (space.id < 0) fail(path, "cannot read the shape of dataset " + name);
    const int rank = H5Sget_simple_extent_ndims(space.id);
    if (rank < 0 || rank > 8) fail(path, "dataset " + name + " has a damaged shape");
    std::vector<hsize_t> dims(static_cast<std::size_t>(rank));
    if (H5Sget_simple_extent_dims(space.id, dims.data(), nullptr) < 0)
        fail(path, "dataset " + name + " has a damaged shape");
    std::size_t total = 1;
    for (hsize_t d : dims) {
        if (d != 0 && total > SIZE_MAX / sizeof(T) / d) fail(path, "dataset " + name + " is impossibly large");
        total *= d;
    }
    if (total * sizeof(T) > kMaxUnbackedBytes) {
        hsize_t stored = 0;
        H5E_BEGIN_TRY { stored = H5Dget_storage_size(ds.id); }
        H5E_END_TRY;
        if (stored * kMaxDeflateRatio < total * sizeof(T))
            fail(path, "dataset " + name + " claims " + std::to_string(total) + " elements but stores " +
                           std::to_string(stored) + " bytes");
    }
    if (shape != nullptr) shape->assign(dims.begin(), dims.end());
    std::vector<T> out(total);
    herr_t ok = 0;
    if (total > 0) {
        H5E_BEGIN_TRY { ok = H5Dread(ds.id, native_type<T>(), H5S_ALL, H5S_ALL, H5P_DEFAULT, out.data()); }
        H5E_END_TRY;
    }
    if (ok < 0) fail(path, "cannot read dataset " + name + " (damaged or not numbers)");
    return out;
}

template std::vector<double> read_dataset<double>(const std::filesystem::path&, hid_t, const std::string&,
                                                  std::vector<std::size_t>*);
template std::vector<std::uint64_t> read_dataset<std::uint64_t>(const std::filesystem::path&, hid_t, const std::string&,
                                                                std::vector<std::size_t>*);

hid_t open_attr(const std::filesystem::path& path, hid_t file, const std::string& object, const std::string& name) {
    hid_t a = -1;
    H5E_BEGIN_TRY { a = H5Aopen_by_name(file, object.c_str(), name.c_str(), H5P_DEFAULT, H5P_DEFAULT); }
    H5E_END_TRY;
    if (a < 0) fail(path, "result file has no attribute " + object + "@" + name + " (or it is damaged)");
    return a;
}

// An attribute lives in an object header, which is at most 64 KiB per message.
std::size_t attr_points(const std::filesystem::path& path, hid_t space, const std::string& what) {
    const hssize_t n = space < 0 ? -1 : H5Sget_simple_extent_npoints(space);
    if (n < 0 || n > (hssize_t{1} << 24)) fail(path, "attribute " + what + " has a damaged shape");
    return static_cast<std::size_t>(n);
}

}  // namespace luxtrace::hdf5
