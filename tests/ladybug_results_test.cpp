// The Ladybug Tools results folder (issue 24 §4): the .npy bytes follow the NumPy format
// 1.0, and the folder read back by NumPy along honeybee-radiance-postprocess's own loading
// steps (tests/ladybug_results_reader.py) holds exactly the values, hours and grid
// information written; a folder is replaced whole or not at all.
#include "luxtrace/io/ladybug_results.hpp"
#include "luxtrace/core/error.hpp"

#include "test_support.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace luxtrace {
namespace {

namespace fs = std::filesystem;

constexpr const char* kPython = "/usr/bin/python3";

// Values no float32 rounding hides (0.1 steps are not exact in binary), per sensor and hour.
std::vector<float> pattern(std::size_t sensors, std::size_t hours, float offset) {
    std::vector<float> v(sensors * hours);
    for (std::size_t s = 0; s < sensors; ++s)
        for (std::size_t h = 0; h < hours; ++h)
            v[s * hours + h] = offset + 1000.0f * static_cast<float>(s) + 0.1f * static_cast<float>(h) + 1e-3f;
    return v;
}

LadybugGrid grid(const std::string& id, const std::string& name, std::size_t sensors, std::size_t hours) {
    LadybugGrid g;
    g.identifier = id;
    g.name = name;
    g.sensors = sensors;
    g.total_lx = pattern(sensors, hours, 300.0f);
    g.direct_lx = pattern(sensors, hours, 0.5f);
    return g;
}

std::string run_python(const std::string& args, const fs::path& out) {
    const std::string cmd = std::string(kPython) + " " + args + " > \"" + out.string() + "\" 2>&1";
    const int status = std::system(cmd.c_str());
    std::stringstream ss;
    ss << std::ifstream(out).rdbuf();
    EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << cmd << "\n" << ss.str();
    return ss.str();
}

// Hidden leftovers (`.NAME.tmp.PID`, `.NAME.old.PID`) beside the folder.
int hidden_entries(const fs::path& dir) {
    int n = 0;
    for (const auto& e : fs::directory_iterator(dir))
        if (e.path().filename().string().front() == '.') ++n;
    return n;
}

TEST(Npy, HeaderIsFormatOneZeroAlignedTo64AndDataAreLittleEndianFloat32) {
    const std::vector<float> v = {1.0f, -2.5f, 3.25e7f, 0.1f, 0.0f, 7.0f};
    const std::string b = npy_float32(v, 2, 3);
    ASSERT_GE(b.size(), 10u);
    EXPECT_EQ(b.substr(0, 6), std::string("\x93NUMPY", 6));
    EXPECT_EQ(b[6], 1);
    EXPECT_EQ(b[7], 0);
    const std::size_t header_len = static_cast<unsigned char>(b[8]) | (static_cast<unsigned char>(b[9]) << 8);
    const std::size_t data_offset = 10 + header_len;
    EXPECT_EQ(data_offset % 64, 0u);
    EXPECT_EQ(b[data_offset - 1], '\n');
    const std::string header = b.substr(10, header_len);
    EXPECT_NE(header.find("'descr': '<f4'"), std::string::npos) << header;
    EXPECT_NE(header.find("'fortran_order': False"), std::string::npos) << header;
    EXPECT_NE(header.find("'shape': (2, 3)"), std::string::npos) << header;
    ASSERT_EQ(b.size(), data_offset + 4 * v.size());
    for (std::size_t i = 0; i < v.size(); ++i) {
        std::uint32_t bits = 0;
        for (int k = 3; k >= 0; --k) bits = (bits << 8) | static_cast<unsigned char>(b[data_offset + 4 * i + k]);
        float f;
        std::memcpy(&f, &bits, 4);
        EXPECT_EQ(f, v[i]) << i;
    }
    EXPECT_THROW(npy_float32(v, 4, 2), InputError);
}

TEST(Npy, NumPysOwnFormatReaderAcceptsTheBytes) {
    test_support::ScratchDir dir("ladybug_npy");
    const std::vector<float> v = pattern(5, 7, 12.0f);
    const std::string b = npy_float32(v, 5, 7);
    std::ofstream(dir.path() / "a.npy", std::ios::binary).write(b.data(), static_cast<std::streamsize>(b.size()));
    // read_magic / read_array_header_1_0 are NumPy's strict parsers of the version-1.0 header.
    const std::string out =
        run_python("-c \"import sys, numpy as np; f = open(sys.argv[1], 'rb'); "
                   "print(np.lib.format.read_magic(f), np.lib.format.read_array_header_1_0(f))\" \"" +
                       (dir.path() / "a.npy").string() + "\"",
                   dir.path() / "out.txt");
    EXPECT_NE(out.find("(1, 0) ((5, 7), False, dtype('float32'))"), std::string::npos) << out;
}

TEST(LadybugResults, ReadBackAlongThePostprocessLoadingStepsGivesWhatWasWritten) {
    test_support::ScratchDir dir("ladybug_read");
    const fs::path folder = dir.path() / "results";
    const std::vector<double> hours = {7.5, 8.5, 12.5, 17.5};
    const std::vector<LadybugGrid> grids = {grid("Office_desk", "Office \"desk\" plane", 3, hours.size()),
                                            grid("Corridor-1", "", 1, hours.size())};
    write_ladybug_results(folder, grids, hours);
    EXPECT_EQ(hidden_entries(dir.path()), 0);

    const fs::path script = fs::path(LUXTRACE_TEST_DATA_DIR).parent_path() / "ladybug_results_reader.py";
    std::istringstream out(run_python("\"" + script.string() + "\" \"" + folder.string() + "\"", dir.path() / "o"));
    std::map<std::string, std::string> name_of;
    int arrays = 0;
    std::string line;
    while (std::getline(out, line)) {
        std::istringstream ls(line);
        std::string what;
        ls >> what;
        if (what == "timestep") {
            int t = 0;
            ls >> t;
            EXPECT_EQ(t, 1);
        } else if (what == "study_hours") {
            int n = 0;
            ls >> n;
            EXPECT_EQ(n, 8760);
        } else if (what == "sun_up_hours") {
            // Hour-of-year midpoints come back as the reader's whole hours, in order.
            std::vector<int> got;
            for (int h; ls >> h;) got.push_back(h);
            EXPECT_EQ(got, (std::vector<int>{7, 8, 12, 17}));
        } else if (what == "sun_up_hours_mask_size") {
            std::size_t n = 0;
            ls >> n;
            EXPECT_EQ(n, hours.size());  // every sun-up hour matches one study hour
        } else if (what == "light_paths") {
            std::string p, extra;
            ls >> p >> extra;
            EXPECT_EQ(p, "__static_apertures__");
            EXPECT_TRUE(extra.empty());
        } else if (what == "valid_states") {
            EXPECT_EQ(line, "valid_states __static_apertures__ 0");
        } else if (what == "grid") {
            std::string id;
            ls >> id;
            const std::size_t bar = line.find(" | name ");
            ASSERT_NE(bar, std::string::npos);
            EXPECT_EQ(line.substr(0, bar), "grid " + id + " keys count name identifier group full_id light_path");
            name_of[id] = line.substr(bar + 8);
        } else if (what == "array") {
            std::string id, res_type, file, dtype, c_order;
            std::size_t rows = 0, cols = 0;
            ls >> id >> res_type >> file >> dtype >> c_order >> rows >> cols;
            const LadybugGrid* g = nullptr;
            for (const LadybugGrid& x : grids)
                if (x.identifier == id) g = &x;
            ASSERT_NE(g, nullptr) << id;
            EXPECT_EQ(file, "__static_apertures__/default/" + res_type + "/" + id + ".npy");
            EXPECT_EQ(dtype, "float32");
            EXPECT_EQ(c_order, "True");
            EXPECT_EQ(rows, g->sensors);
            EXPECT_EQ(cols, hours.size());
            const std::vector<float>& expected = res_type == "total" ? g->total_lx : g->direct_lx;
            std::vector<double> got;
            for (std::string v; ls >> v;) got.push_back(std::stod(v));
            ASSERT_EQ(got.size(), expected.size());
            for (std::size_t k = 0; k < got.size(); ++k)
                EXPECT_EQ(got[k], static_cast<double>(expected[k])) << id << " " << res_type << " " << k;
            ++arrays;
        } else {
            ADD_FAILURE() << "unexpected line: " << line;
        }
    }
    EXPECT_EQ(arrays, 4);
    EXPECT_EQ(name_of["Office_desk"], "Office \"desk\" plane");
    EXPECT_EQ(name_of["Corridor-1"], "Corridor-1");  // no display name: the identifier
}

TEST(LadybugResults, SunUpHoursAreWrittenAsTheyReadBackExactly) {
    test_support::ScratchDir dir("ladybug_hours");
    const std::vector<double> hours = {0.5, 4380.25, 8759.5};
    write_ladybug_results(dir.path() / "r", {grid("g", "", 1, hours.size())}, hours);
    std::ifstream in(dir.path() / "r" / "sun-up-hours.txt");
    std::vector<double> got;
    for (std::string s; std::getline(in, s);) got.push_back(std::stod(s));
    EXPECT_EQ(got, hours);
}

TEST(LadybugResults, AnExistingFolderIsReplacedWholeAndNothingIsLeftBeside) {
    test_support::ScratchDir dir("ladybug_replace");
    const fs::path folder = dir.path() / "results";
    const std::vector<double> hours = {9.5, 10.5};
    write_ladybug_results(folder, {grid("first", "", 2, 2)}, hours);
    std::ofstream(folder / "note.txt") << "a user's file inside the old folder\n";
    write_ladybug_results(folder, {grid("second", "", 2, 2)}, hours);
    const fs::path total = folder / "__static_apertures__" / "default" / "total";
    EXPECT_TRUE(fs::exists(total / "second.npy"));
    EXPECT_FALSE(fs::exists(total / "first.npy"));
    EXPECT_FALSE(fs::exists(folder / "note.txt"));
    EXPECT_EQ(hidden_entries(dir.path()), 0);
    int files = 0;
    for (const auto& e : fs::recursive_directory_iterator(folder)) files += e.is_regular_file() ? 1 : 0;
    EXPECT_EQ(files, 5);  // two arrays and three index files, no temporaries
}

TEST(LadybugResults, BadArgumentsWriteNothingAndKeepTheOldFolder) {
    test_support::ScratchDir dir("ladybug_bad");
    const fs::path folder = dir.path() / "results";
    const std::vector<double> hours = {9.5, 10.5, 11.5};
    write_ladybug_results(folder, {grid("kept", "", 2, 3)}, hours);

    auto rejected = [&](std::vector<LadybugGrid> grids, std::vector<double> h, const std::string& says) {
        try {
            write_ladybug_results(folder, grids, h);
            ADD_FAILURE() << "accepted; expected: " << says;
        } catch (const InputError& e) {
            EXPECT_NE(std::string(e.what()).find(says), std::string::npos) << e.what();
        }
    };
    LadybugGrid short_total = grid("short", "", 2, 3);
    short_total.total_lx.pop_back();
    rejected({short_total}, hours, "grid 'short': total_lx holds 5 values, expected sensors x sun-up hours = 2 x 3");
    LadybugGrid nan = grid("nan", "", 2, 3);
    nan.direct_lx[4] = std::nanf("");
    rejected({nan}, hours, "grid 'nan': direct_lx is not finite at sensor 1, hour 1");
    rejected({grid("a/b", "", 2, 3)}, hours, "grid 'a/b': the identifier must be");
    rejected({grid(".hidden", "", 2, 3)}, hours, "grid '.hidden': the identifier must be");
    rejected({grid("twice", "", 2, 3), grid("twice", "", 1, 3)}, hours, "grid 'twice': the identifier is used twice");
    rejected({grid("g", "", 2, 3)}, {9.5, 9.75, 11.5}, "sun-up hour 1 (9.750000) is not in a later hour");
    rejected({grid("g", "", 2, 3)}, {9.5, 10.5, 8760.5}, "sun-up hour 2 is 8760.500000");
    rejected({grid("g", "", 1, 1)}, {9.5}, "1 sun-up hours; the reader needs at least 2");
    rejected({}, hours, "no sensor grid");

    EXPECT_TRUE(fs::exists(folder / "__static_apertures__" / "default" / "total" / "kept.npy"));
    EXPECT_EQ(hidden_entries(dir.path()), 0);
}

TEST(LadybugResults, AFileInTheFoldersPlaceIsAWriteErrorAndStaysAsItWas) {
    test_support::ScratchDir dir("ladybug_file");
    const fs::path folder = dir.path() / "results";
    std::ofstream(folder) << "not a folder\n";
    EXPECT_THROW(write_ladybug_results(folder, {grid("g", "", 1, 2)}, {9.5, 10.5}), IoError);
    std::stringstream ss;
    ss << std::ifstream(folder).rdbuf();
    EXPECT_EQ(ss.str(), "not a folder\n");
    EXPECT_EQ(hidden_entries(dir.path()), 0);
}

}  // namespace
}  // namespace luxtrace
