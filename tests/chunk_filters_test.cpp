// The chunk filters luxtrace applies itself before handing a large dataset's chunks to
// HDF5 (src/io/chunk_filters.hpp): each against its definition; the stored bytes against
// those HDF5's own filters make of the same chunks (the one place outside src/io that calls
// HDF5: the library is the reference here); and the whole pipeline through HDF5's reader
// on a checkpoint whose maps span several chunks, the last one partly filled.
#include "io/chunk_filters.hpp"
#include "luxtrace/io/result_data.hpp"
#include "luxtrace/io/result_reader.hpp"
#include "luxtrace/scene/scene.hpp"
#include "luxtrace/tally/tally.hpp"
#include "test_support.hpp"

#include <gtest/gtest.h>
#include <hdf5.h>
#include <zlib.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>

namespace fs = std::filesystem;
using namespace luxtrace;

namespace {

std::vector<unsigned char> random_bytes(std::size_t n, std::uint64_t seed, int zero_share_percent) {
    std::mt19937_64 g(seed);
    std::vector<unsigned char> b(n);
    for (unsigned char& c : b)
        c = static_cast<int>(g() % 100) < zero_share_percent ? 0 : static_cast<unsigned char>(g());
    return b;
}

}  // namespace

TEST(ChunkFilters, ShuffleGathersEachBytePlaneAndKeepsTheTail) {
    for (const std::size_t size : {std::size_t{4}, std::size_t{8}})
        for (const std::size_t n : {std::size_t{0}, std::size_t{1}, std::size_t{1000}}) {
            const std::vector<unsigned char> in = random_bytes(n * size + 3, 7 + n, 50);  // 3 bytes past the elements
            std::vector<unsigned char> out(in.size());
            hdf5::shuffle_bytes(in, size, out.data());
            for (std::size_t i = 0; i < n; ++i)
                for (std::size_t k = 0; k < size; ++k) ASSERT_EQ(out[k * n + i], in[i * size + k]) << i << " " << k;
            for (std::size_t b = n * size; b < in.size(); ++b) EXPECT_EQ(out[b], in[b]);
        }
}

// Fletcher's checksum is the pair of sums modulo 65535 of the 16-bit words and of their
// running sums; HDF5 reads the words most significant byte first and folds with
// end-around carries, which leaves each sum congruent to the modular one.
TEST(ChunkFilters, Fletcher32IsTheModularSumsOfBigEndianWords) {
    for (const std::size_t n : {std::size_t{0}, std::size_t{1}, std::size_t{2}, std::size_t{719}, std::size_t{720},
                                std::size_t{721}, std::size_t{100001}}) {
        const std::vector<unsigned char> b = random_bytes(n, n, 0);
        std::uint64_t s1 = 0, s2 = 0;
        for (std::size_t i = 0; i < n; i += 2) {
            const std::uint64_t word = (std::uint64_t{b[i]} << 8) | (i + 1 < n ? b[i + 1] : 0u);
            s1 = (s1 + word) % 65535;
            s2 = (s2 + s1) % 65535;
        }
        const std::uint32_t f = hdf5::fletcher32(b);
        EXPECT_EQ((f & 0xffffu) % 65535, s1) << n;
        EXPECT_EQ((f >> 16) % 65535, s2) << n;
    }
}

TEST(ChunkFilters, StoredChunkInflatesToTheShuffledBytesAndEndsWithTheirChecksum) {
    const std::vector<unsigned char> chunk = random_bytes(65536 * 8, 3, 90);  // mostly zero, as counts are
    const std::vector<unsigned char> stored = hdf5::filtered_chunk(chunk, 8, 1);
    ASSERT_GT(stored.size(), 4u);
    EXPECT_LT(stored.size(), chunk.size() / 2);
    const std::size_t body = stored.size() - 4;
    std::uint32_t sum = 0;
    for (int k = 3; k >= 0; --k) sum = (sum << 8) | stored[body + static_cast<std::size_t>(k)];
    EXPECT_EQ(sum, hdf5::fletcher32({stored.data(), body}));
    std::vector<unsigned char> inflated(chunk.size());
    uLongf size = static_cast<uLongf>(inflated.size());
    ASSERT_EQ(uncompress(inflated.data(), &size, stored.data(), static_cast<uLong>(body)), Z_OK);
    ASSERT_EQ(size, chunk.size());
    std::vector<unsigned char> shuffled(chunk.size());
    hdf5::shuffle_bytes(chunk, 8, shuffled.data());
    EXPECT_EQ(inflated, shuffled);
}

// Datasets of the shapes a result has ([T, 2, 1] counts, [V, 3] vertices, [T, 3] indices),
// each of several chunks and a partial last one, filtered by HDF5 itself (shuffle, deflate
// 1, Fletcher-32, as write_dataset asks for); each stored chunk, read raw, is what
// filtered_chunk makes of the same rows.
template <class T>
void expect_hdf5_stores_what_we_make(hid_t file, const char* name, std::vector<hsize_t> dims, hsize_t chunk_rows,
                                     hid_t type, const std::vector<T>& data) {
    const hid_t space = H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr);
    const hid_t plist = H5Pcreate(H5P_DATASET_CREATE);
    std::vector<hsize_t> chunk = dims;
    chunk[0] = chunk_rows;
    ASSERT_GE(H5Pset_chunk(plist, static_cast<int>(chunk.size()), chunk.data()), 0);
    ASSERT_GE(H5Pset_shuffle(plist), 0);
    ASSERT_GE(H5Pset_deflate(plist, 1), 0);
    ASSERT_GE(H5Pset_fletcher32(plist), 0);
    const hid_t ds = H5Dcreate2(file, name, type, space, H5P_DEFAULT, plist, H5P_DEFAULT);
    ASSERT_GE(ds, 0);
    ASSERT_GE(H5Dwrite(ds, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data.data()), 0);
    std::size_t row = 1;
    for (std::size_t d = 1; d < dims.size(); ++d) row *= static_cast<std::size_t>(dims[d]);
    const std::size_t chunks = static_cast<std::size_t>((dims[0] + chunk_rows - 1) / chunk_rows);
    EXPECT_GE(chunks, 3u);
    for (std::size_t c = 0; c < chunks; ++c) {
        std::vector<hsize_t> offset(dims.size(), 0);
        offset[0] = c * chunk_rows;
        hsize_t stored_size = 0;
        ASSERT_GE(H5Dget_chunk_storage_size(ds, offset.data(), &stored_size), 0);
        std::vector<unsigned char> stored(stored_size);
        std::uint32_t mask = 1;
        ASSERT_GE(H5Dread_chunk(ds, H5P_DEFAULT, offset.data(), &mask, stored.data()), 0);
        EXPECT_EQ(mask, 0u) << name << " chunk " << c;  // every filter applied
        std::vector<unsigned char> rows(static_cast<std::size_t>(chunk_rows) * row * sizeof(T), 0);
        const std::size_t n = std::min<std::size_t>(chunk_rows, dims[0] - offset[0]) * row;
        std::memcpy(rows.data(), data.data() + offset[0] * row, n * sizeof(T));
        EXPECT_EQ(hdf5::filtered_chunk(rows, sizeof(T), 1), stored) << name << " chunk " << c;
    }
    H5Dclose(ds);
    H5Pclose(plist);
    H5Sclose(space);
}

TEST(ChunkFilters, StoredBytesAreThoseOfHdf5sOwnFilters) {
    const test_support::ScratchDir dir("chunk_filters_hdf5");
    const hid_t file = H5Fcreate((dir.path() / "f.h5").c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
    ASSERT_GE(file, 0);
    std::mt19937_64 g(11);
    std::vector<std::uint64_t> counts(100003 * 2);  // sparse, as a room's back sides
    for (std::uint64_t& x : counts) x = g() % 7 == 0 ? g() % 1000 : 0;
    std::vector<double> vertices(50001 * 3);
    for (double& x : vertices) x = std::uniform_real_distribution<double>(-5.0, 5.0)(g);
    std::vector<std::uint32_t> indices(70001 * 3);
    for (std::uint32_t& x : indices) x = static_cast<std::uint32_t>(g() % 5000000);
    expect_hdf5_stores_what_we_make(file, "counts", {100003, 2, 1}, 32768, H5T_NATIVE_UINT64, counts);
    expect_hdf5_stores_what_we_make(file, "vertices", {50001, 3}, 21845, H5T_NATIVE_DOUBLE, vertices);
    expect_hdf5_stores_what_we_make(file, "indices", {70001, 3}, 21845, H5T_NATIVE_UINT32, indices);
    H5Fclose(file);
}

// HDF5 checks every chunk's checksum and undoes deflate and shuffle as it reads. A box of
// 76,800 triangles: each [T, 2, 1] map is three chunks of 32,768 triangles, the last one
// partly filled, and the tallies twelve chunks of their own. A checkpoint holds both, from
// the same tallies: its maps are its tallies' words.
TEST(ChunkFilters, AResultsChunkedMapsReadBackAsTheCheckpointsTallies) {
    const test_support::ScratchDir dir("chunk_filters");
    const std::string text = R"([scene]
name = "chunked maps"

[[material]]
name = "wall"
type = "diffuse"
reflectance = 0.5

[[shape]]
type = "box"
center = [2, 1.5, 1.25]
size = [4, 3, 2.5]
inward = true
subdivisions = 80
material = "wall"

[[light]]
type = "point"
position = [1.3, 1.1, 1.7]
flux_lm = 1000
)";
    const fs::path scene_file = dir.path() / "box.toml";
    std::ofstream(scene_file) << text;
    const fs::path out = dir.path() / "r.h5", ck = dir.path() / "ck.h5";
    // A reduction and a checkpoint every 10k photons.
    const auto run = test_support::run_luxtrace(
        "run " + scene_file.string() + " --photons 30k --threads 2 --quiet --report-every-photons 10k" +
        " --checkpoint-every 0.000001 --checkpoint " + ck.string() + " --output " + out.string());
    ASSERT_EQ(run.code, 0) << run.out;
    ASSERT_TRUE(fs::exists(ck)) << run.out;
    const Scene scene = load_scene(scene_file);
    ASSERT_EQ(scene.triangle_count(), 76800u);
    const TallyLayout L = tally_layout(scene);
    const ResultFile c(ck);
    ASSERT_TRUE(c.is_checkpoint());
    const std::vector<std::uint64_t> tallies = ResultReader(ck).u64("/checkpoint/tallies");
    ASSERT_EQ(tallies.size(), L.size());
    const SurfaceCounts s = c.surface_counts();
    std::uint64_t arrivals = 0;
    for (std::size_t t = 0; t < L.triangles(); ++t)
        for (std::size_t side = 0; side < TallyLayout::kSides; ++side) {
            const std::size_t k = t * TallyLayout::kSides + side;
            auto word = [&](TallyLayout::SurfaceSlot slot) { return tallies[L.surface(t, side, 0, slot, 0)]; };
            ASSERT_EQ(s.count_odd[k], word(TallyLayout::kCountOdd)) << t << " " << side;
            ASSERT_EQ(s.count_even[k], word(TallyLayout::kCountEven));
            ASSERT_EQ(s.direct_odd[k], word(TallyLayout::kDirectOdd));
            ASSERT_EQ(s.direct_even[k], word(TallyLayout::kDirectEven));
            ASSERT_EQ(s.sumsq[k], s.count_odd[k] + s.count_even[k] + word(TallyLayout::kRepeats));
            arrivals += s.count_odd[k] + s.count_even[k];
        }
    // A closed room: every photon arrives somewhere at least once.
    EXPECT_GE(arrivals, c.run_info().photons);
    EXPECT_GE(c.run_info().photons, 10000u);
    // The result, from all the tallies, reads back too.
    EXPECT_EQ(ResultFile(out).surface_counts().count_odd.size(), L.sides());
}
