// The bytes of every result and checkpoint are built in memory by HDF5's core driver
// (src/io/hdf5_file.hpp) and written with one atomic rename. Issue 35: a result whose
// driver buffer ended inside space HDF5 had allocated but not written was refused as
// "incomplete" after the whole run. These tests state what the image must be, the file HDF5
// itself writes to disk from the same content, and sweep the files' sizes across the
// core driver's increments at every byte offset, each file read back whole by HDF5 (every
// dataset and attribute), by luxtrace's reader and by the Python package.
#include "io/hdf5_file.hpp"
#include "io/result_parts.hpp"
#include "luxtrace/estimate/annual_estimate.hpp"
#include "luxtrace/estimate/result_estimates.hpp"
#include "luxtrace/io/file_seal.hpp"
#include "luxtrace/io/result_data.hpp"
#include "luxtrace/io/result_file.hpp"
#include "luxtrace/scene/scene.hpp"
#include "luxtrace/stats/annual_metrics.hpp"
#include "luxtrace/tally/tally.hpp"
#include "test_support.hpp"

#include <gtest/gtest.h>
#include <hdf5.h>
#include <malloc.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <map>
#include <memory>
#include <set>

namespace fs = std::filesystem;
using namespace luxtrace;

namespace {

const fs::path kExamples = LUXTRACE_EXAMPLES_DIR;
const fs::path kData = LUXTRACE_TEST_DATA_DIR;
constexpr std::size_t kMiB = std::size_t{1} << 20;

// What a result holds, from a real run's checkpoint: its tallies, history and estimates.
struct Content {
    Scene scene;
    std::unique_ptr<TallyLayout> layout;
    CheckpointData checkpoint;
    RunInfo info;
    ResultEstimates estimates;
    std::vector<HistoryRow> history;

    void write(hid_t file, bool as_checkpoint) const {
        result_parts::write_all(file, scene, *layout, checkpoint.tallies, info, estimates, history,
                                as_checkpoint ? &checkpoint : nullptr);
    }
};

// Runs `scene_file` for `photons` and makes the content of its result from the checkpoint.
std::unique_ptr<Content> content_of(const fs::path& scene_file, const std::string& photons, const std::string& quarter,
                                    const test_support::ScratchDir& dir, const std::string& tag) {
    const fs::path ck = dir.path() / (tag + ".ck.h5"), out = dir.path() / (tag + ".h5");
    // Reductions at a quarter and half the budget, each with a checkpoint.
    const auto run = test_support::run_luxtrace(
        "run " + scene_file.string() + " --photons " + photons + " --threads 2 --quiet --report-every-photons " +
        quarter + " --checkpoint-every 0.000001 --checkpoint " + ck.string() + " --output " + out.string());
    if (run.code != 0 || !fs::exists(ck)) throw std::runtime_error("run failed: " + run.out);
    auto c = std::make_unique<Content>();
    c->scene = load_scene(scene_file);
    c->layout = std::make_unique<TallyLayout>(tally_layout(c->scene));
    const CheckpointState s = read_checkpoint(ck);
    const ResultFile r(ck);
    c->checkpoint.tallies = s.tallies;
    c->checkpoint.done = s.done;
    c->checkpoint.budget = s.budget;
    c->history = s.history;
    c->info = r.run_info();
    const std::uint64_t n = c->info.photons;
    const double e0 = c->scene.lights.total_flux_lm() / static_cast<double>(n);
    c->estimates = estimate_result(c->scene, *c->layout, c->checkpoint.tallies, e0, n);
    if (c->scene.annual)
        c->estimates.annual = estimate_annual(c->scene, *c->layout, c->checkpoint.tallies, e0, n, 0, {});
    return c;
}

// A contiguous dataset of `bytes` bytes created first: everything after it moves by as
// many bytes, so the file's length follows `bytes` one for one.
void pad(hid_t file, std::size_t bytes) {
    const hsize_t n = bytes;
    const hid_t space = H5Screate_simple(1, &n, nullptr);
    const hid_t dcpl = H5Pcreate(H5P_DATASET_CREATE);
    H5Pset_obj_track_times(dcpl, 0);
    const hid_t ds = H5Dcreate2(file, "padding", H5T_STD_U8LE, space, H5P_DEFAULT, dcpl, H5P_DEFAULT);
    std::vector<unsigned char> v(bytes, 0);  // zeros: holes in the files' copies on disk
    if (ds < 0 || H5Dwrite(ds, H5T_NATIVE_UCHAR, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data()) < 0)
        throw std::runtime_error("padding not written");
    H5Dclose(ds);
    H5Pclose(dcpl);
    H5Sclose(space);
}

// The same content written by HDF5 to disk (its default POSIX driver), with the file
// properties file_image uses, and read back as bytes.
std::vector<char> written_to_disk(const fs::path& path, std::size_t userblock, const std::function<void(hid_t)>& fill) {
    const hid_t fapl = H5Pcreate(H5P_FILE_ACCESS);
    H5Pset_libver_bounds(fapl, H5F_LIBVER_V18, H5F_LIBVER_LATEST);
    const hid_t fcpl = H5Pcreate(H5P_FILE_CREATE);
    H5Pset_userblock(fcpl, userblock);
    H5Pset_obj_track_times(fcpl, 0);
    const hid_t file = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, fcpl, fapl);
    if (file < 0) throw std::runtime_error("cannot create " + path.string());
    fill(file);
    H5Fflush(file, H5F_SCOPE_GLOBAL);
    H5Fclose(file);
    H5Pclose(fcpl);
    H5Pclose(fapl);
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Reads a dataset's or attribute's every element in its own type (variable-length
// strings reclaimed): a damaged chunk, heap or header fails here.
bool read_all_elements(hid_t obj, bool attribute) {
    const hid_t type = attribute ? H5Aget_type(obj) : H5Dget_type(obj);
    const hid_t space = attribute ? H5Aget_space(obj) : H5Dget_space(obj);
    const hid_t mem = H5Tget_native_type(type, H5T_DIR_ASCEND);
    const hssize_t n = H5Sget_simple_extent_npoints(space);
    bool ok = type >= 0 && space >= 0 && mem >= 0 && n >= 0;
    if (ok && n > 0) {
        std::vector<unsigned char> buf(static_cast<std::size_t>(n) * H5Tget_size(mem));
        ok = (attribute ? H5Aread(obj, mem, buf.data())
                        : H5Dread(obj, mem, H5S_ALL, H5S_ALL, H5P_DEFAULT, buf.data())) >= 0;
        if (ok && H5Tdetect_class(mem, H5T_VLEN) > 0) H5Dvlen_reclaim(mem, space, H5P_DEFAULT, buf.data());
        if (ok && H5Tis_variable_str(mem) > 0) H5Dvlen_reclaim(mem, space, H5P_DEFAULT, buf.data());
    }
    H5Tclose(mem);
    H5Sclose(space);
    H5Tclose(type);
    return ok;
}

struct Census {
    std::size_t datasets = 0, attributes = 0, failures = 0;
};

herr_t read_attribute(hid_t obj, const char* name, const H5A_info_t*, void* data) {
    auto* c = static_cast<Census*>(data);
    const hid_t a = H5Aopen(obj, name, H5P_DEFAULT);
    ++c->attributes;
    if (a < 0 || !read_all_elements(a, true)) ++c->failures;
    if (a >= 0) H5Aclose(a);
    return 0;
}

herr_t read_object(hid_t file, const char* name, const H5O_info_t* info, void* data) {
    auto* c = static_cast<Census*>(data);
    const hid_t obj = H5Oopen(file, name, H5P_DEFAULT);
    if (obj < 0) {
        ++c->failures;
        return 0;
    }
    if (H5Aiterate2(obj, H5_INDEX_NAME, H5_ITER_INC, nullptr, read_attribute, c) < 0) ++c->failures;
    if (info->type == H5O_TYPE_DATASET && std::string_view(name) != "padding") {
        ++c->datasets;
        if (!read_all_elements(obj, false)) ++c->failures;
    }
    H5Oclose(obj);
    return 0;
}

// Opens `image` as HDF5 does a file's bytes (from memory) and reads every object in it.
Census read_whole(const std::vector<char>& image) {
    Census c;
    H5E_BEGIN_TRY {
        const hid_t fapl = H5Pcreate(H5P_FILE_ACCESS);
        H5Pset_fapl_core(fapl, kMiB, 0);
        H5Pset_file_image(fapl, const_cast<char*>(image.data()), image.size());
        const hid_t file = H5Fopen("image", H5F_ACC_RDONLY, fapl);
        if (file < 0 || H5Ovisit2(file, H5_INDEX_NAME, H5_ITER_INC, read_object, &c, H5O_INFO_BASIC) < 0) ++c.failures;
        if (file >= 0) H5Fclose(file);
        H5Pclose(fapl);
    }
    H5E_END_TRY;
    return c;
}

// The superblock's end of file address: the file's length, user block included (HDF5
// stores the end of its allocated space plus the base address, the user block's size).
std::size_t superblock_length(const std::vector<char>& image, std::size_t userblock) {
    std::uint64_t eof = 0;
    for (int i = 7; i >= 0; --i) eof = (eof << 8) | static_cast<unsigned char>(image[userblock + 28 + i]);
    return eof;
}

// A real run's content, made once per test program: the office example's result, and
// the annual test room's (4,071 light groups, its coefficients).
const Content& office() {
    static const test_support::ScratchDir dir("file_image_office");
    static const std::unique_ptr<Content> c = content_of(kExamples / "office" / "office.toml", "20000", "5000", dir,
                                                         "o");
    return *c;
}

// The run-control tests' small room (two detectors): a result of few objects, for sweeps
// of thousands of files.
const Content& small_room() {
    static const test_support::ScratchDir dir("file_image_small");
    static const std::unique_ptr<Content> c = content_of(kData / "run" / "room.toml", "20000", "5000", dir, "s");
    return *c;
}

const Content& annual() {
    static const test_support::ScratchDir dir("file_image_annual");
    static const std::unique_ptr<Content> c = content_of(kData / "run" / "annual_room.toml", "20000", "5000", dir, "a");
    return *c;
}

}  // namespace

// The image is byte for byte what HDF5 writes to disk from the same content, whatever the
// core driver's increment: 1 byte (the buffer then holds exactly the bytes written), a
// page, 1 MiB. For results and checkpoints, the office's and an annual one, with and
// without the user block the seal goes in. (Before issue 35's fix, every image with the
// user block asked for 512 bytes past the file, and failed at the 1-byte increment.)
TEST(FileImage, IsTheFileHdf5WritesToDisk) {
    const test_support::ScratchDir dir("file_image_disk");
    for (const Content* content : {&office(), &annual()})
        for (const bool as_checkpoint : {false, true})
            for (const std::size_t userblock : {std::size_t{0}, kSealBytes}) {
                auto fill = [&](hid_t f) { content->write(f, as_checkpoint); };
                const std::vector<char> disk = written_to_disk(dir.path() / "disk.h5", userblock, fill);
                ASSERT_EQ(disk.size(), superblock_length(disk, userblock));
                for (const std::size_t increment : {std::size_t{1}, std::size_t{4096}, kMiB}) {
                    const std::vector<char> image = hdf5::file_image("x.h5", userblock, fill, increment);
                    ASSERT_EQ(image.size(), disk.size()) << increment;
                    const auto differ = std::mismatch(image.begin(), image.end(), disk.begin());
                    EXPECT_TRUE(differ.first == image.end())
                        << content->scene.name << (as_checkpoint ? " checkpoint" : " result") << ", user block "
                        << userblock << ", increment " << increment << ": first difference at byte "
                        << (differ.first - image.begin());
                }
            }
}

namespace {

// Writes `image` to `path` with holes where it has whole pages of zeros (the padding), so
// that thousands of files of a few MiB take little disk.
void write_sparse(const fs::path& path, const std::vector<char>& image) {
    std::ofstream out(path, std::ios::binary);
    constexpr std::size_t kPage = 4096;
    for (std::size_t at = 0; at < image.size(); at += kPage) {
        const std::size_t n = std::min(kPage, image.size() - at);
        const bool zero = std::all_of(image.begin() + static_cast<long>(at), image.begin() + static_cast<long>(at + n),
                                      [](char b) { return b == 0; });
        if (zero && at + n < image.size()) out.seekp(static_cast<std::streamoff>(at + n));
        else {
            out.seekp(static_cast<std::streamoff>(at));
            out.write(image.data() + at, static_cast<std::streamsize>(n));
        }
    }
}

// Files whose lengths sweep every byte offset from 600 bytes before to 64 after k MiB
// (the core driver's increment and its multiples; the lost results ended in the 512 bytes
// before one), results and checkpoints, with the user block (as luxtrace writes them) and,
// around 1 MiB, without: each is as long as its superblock says and reads back whole in
// HDF5 (every dataset and attribute); the sealed ones also in luxtrace's reader and the
// Python package.
void sweep_lengths_around(std::size_t k) {
    const test_support::ScratchDir dir("file_image_sweep_" + std::to_string(k));
    const Content& content = small_room();
    // Thousands of images of a few MiB: the allocator keeps their pages instead of mapping
    // and faulting in new ones for each.
    mallopt(M_MMAP_THRESHOLD, 256 << 20);
    mallopt(M_TRIM_THRESHOLD, 512 << 20);
    constexpr long kBefore = 600, kAfter = 64;
    const fs::path files = dir.path() / "sealed";
    fs::create_directories(files);
    // Without the user block around 1 MiB only: the length's rule is the same for both.
    std::vector<std::size_t> userblocks{kSealBytes};
    if (k == 1) userblocks.push_back(0);
    for (const bool as_checkpoint : {false, true})
        for (const std::size_t userblock : userblocks) {
            auto image_with = [&](std::size_t padding) {
                return hdf5::file_image("x.h5", userblock, [&](hid_t f) {
                    pad(f, padding);
                    content.write(f, as_checkpoint);
                });
            };
            const std::size_t base = image_with(1).size() - 1;  // the length without padding
            std::set<long> offsets;
            for (long d = -kBefore; d <= kAfter; ++d) {
                const long padding = static_cast<long>(k * kMiB) + d - static_cast<long>(base);
                std::vector<char> image = image_with(static_cast<std::size_t>(padding));
                ASSERT_EQ(image.size(), superblock_length(image, userblock));
                offsets.insert(static_cast<long>(image.size()) - static_cast<long>(k * kMiB));
                const Census census = read_whole(image);
                ASSERT_EQ(census.failures, 0u) << "length " << image.size();
                ASSERT_GT(census.datasets, 10u);
                if (userblock == kSealBytes) {
                    seal_image(image);
                    const fs::path p = files /
                                       ((as_checkpoint ? "ck_" : "result_") + std::to_string(d + kBefore) + ".h5");
                    write_sparse(p, image);
                    const ResultFile r(p);  // the seal checked, then HDF5
                    ASSERT_EQ(r.is_checkpoint(), as_checkpoint);
                    ASSERT_EQ(r.surface_counts().count_odd.size(), 2 * content.scene.triangle_count());
                }
            }
            // The length follows the padding one for one: every offset was a file's end.
            for (long d = -kBefore; d <= kAfter; ++d)
                ASSERT_TRUE(offsets.count(d)) << "no file ends " << d << " bytes from " << k << " MiB";
        }
    // The Python package reads each sealed file, and h5py every dataset in it.
    const fs::path log = dir.path() / "python.log";
    const std::string cmd = "PYTHONPATH=" + std::string(LUXTRACE_PYTHON_DIR) +
                            " /usr/bin/python3 -c \"import sys, glob, h5py, luxtrace\n"
                            "n = 0\n"
                            "for p in sorted(glob.glob(sys.argv[1] + '/*.h5')):\n"
                            "    luxtrace.open(p)\n"
                            "    with h5py.File(p, 'r') as f:\n"
                            "        f.visititems(lambda name, o: o[()] if isinstance(o, h5py.Dataset) and name != "
                            "'padding' else None)\n"
                            "    n += 1\n"
                            "print(n)\" " +
                            files.string() + " > " + log.string() + " 2>&1";
    const int code = std::system(cmd.c_str());
    std::ifstream in(log);
    const std::string out((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    ASSERT_EQ(code, 0) << out;
    EXPECT_EQ(out, std::to_string(2 * (kBefore + kAfter + 1)) + "\n");
}

}  // namespace

TEST(FileImage, LengthsAroundOneMebibyteReadBackWhole) { sweep_lengths_around(1); }
TEST(FileImage, LengthsAroundTwoMebibytesReadBackWhole) { sweep_lengths_around(2); }
TEST(FileImage, LengthsAroundThreeMebibytesReadBackWhole) { sweep_lengths_around(3); }
