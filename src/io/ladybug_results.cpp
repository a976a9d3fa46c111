#include "luxtrace/io/ladybug_results.hpp"

#include "luxtrace/core/error.hpp"
#include "luxtrace/core/text.hpp"
#include "luxtrace/io/atomic_file.hpp"

#include <fcntl.h>
#include <unistd.h>
#include <algorithm>
#include <bit>
#include <cerrno>
#include <cmath>
#include <csignal>
#include <cstdint>
#include <cstdio>  // renameat2
#include <cstring>
#include <set>

namespace luxtrace {

namespace fs = std::filesystem;

namespace {

// The light path and state of a model whose apertures never change: the only ones
// luxtrace writes (the reader's default light path and its state 0).
constexpr const char* kStaticLightPath = "__static_apertures__";
constexpr const char* kDefaultState = "default";
constexpr double kHoursPerYear = 8760.0;  // the reader's study hours: a 365-day year, hourly

std::string reason(int err) { return std::strerror(err); }

bool plain_file_name(const std::string& s) {
    if (s.empty() || s.front() == '.') return false;
    for (const char c : s) {
        const bool ok = (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_' ||
                        c == '-' || c == '.';
        if (!ok) return false;
    }
    return true;
}

void check_arguments(const fs::path& folder, const std::vector<LadybugGrid>& grids, const std::vector<double>& hours) {
    const std::string where = "Ladybug results " + folder.string() + ": ";
    if (grids.empty()) throw InputError(where + "no sensor grid to write");
    // The reader's np.loadtxt turns a one-line sun-up-hours.txt into a number, not a list.
    if (hours.size() < 2)
        throw InputError(where + std::to_string(hours.size()) + " sun-up hours; the reader needs at least 2");
    for (std::size_t i = 0; i < hours.size(); ++i) {
        const double h = hours[i];
        if (!(h >= 0.0 && h < kHoursPerYear))
            throw InputError(where + "sun-up hour " + std::to_string(i) + " is " + std::to_string(h) +
                             ", expected an hour of the year in [0, 8760)");
        // The reader truncates hourly values to whole hours and matches them to the study
        // hours: two values within one hour would be one hour to it.
        if (i > 0 && std::floor(h) <= std::floor(hours[i - 1]))
            throw InputError(where + "sun-up hour " + std::to_string(i) + " (" + std::to_string(h) +
                             ") is not in a later hour than the one before it (" + std::to_string(hours[i - 1]) + ")");
    }
    std::set<std::string> seen;
    for (const LadybugGrid& g : grids) {
        const std::string grid = where + "grid '" + g.identifier + "': ";
        if (!plain_file_name(g.identifier))
            throw InputError(grid + "the identifier must be letters, digits, '_', '-' or '.' and not start with '.'");
        if (!seen.insert(g.identifier).second) throw InputError(grid + "the identifier is used twice");
        if (g.sensors == 0) throw InputError(grid + "no sensors");
        const std::size_t expected = g.sensors * hours.size();
        if (g.rows && g.total_lx.empty() && g.direct_lx.empty()) continue;  // checked as written
        for (const auto& [label, values] : {std::pair{"total_lx", &g.total_lx}, std::pair{"direct_lx", &g.direct_lx}}) {
            if (values->size() != expected)
                throw InputError(grid + label + " holds " + std::to_string(values->size()) +
                                 " values, expected sensors x sun-up hours = " + std::to_string(g.sensors) + " x " +
                                 std::to_string(hours.size()));
            for (std::size_t k = 0; k < values->size(); ++k)
                if (!std::isfinite((*values)[k]))
                    throw InputError(grid + label + " is not finite at sensor " + std::to_string(k / hours.size()) +
                                     ", hour " + std::to_string(k % hours.size()));
        }
    }
}

std::string json_string(const std::string& s) {
    std::string out = "\"";
    for (const unsigned char c : s) {
        if (c == '"' || c == '\\') {
            out += '\\';
            out += static_cast<char>(c);
        } else if (c < 0x20) {
            char buf[8];
            std::snprintf(buf, sizeof buf, "\\u%04x", c);
            out += buf;
        } else {
            out += static_cast<char>(c);
        }
    }
    return out + "\"";
}

// The recipe's grids_info.json: the keys of honeybee-radiance's SensorGrid.info_dict,
// with the light path the reader would assume anyway.
std::string grids_info_json(const std::vector<LadybugGrid>& grids) {
    std::string out = "[\n";
    for (std::size_t i = 0; i < grids.size(); ++i) {
        const LadybugGrid& g = grids[i];
        const std::string& name = g.name.empty() ? g.identifier : g.name;
        out += "  {\n    \"count\": " + std::to_string(g.sensors) + ",\n    \"name\": " + json_string(name) +
               ",\n    \"identifier\": " + json_string(g.identifier) +
               ",\n    \"group\": \"\",\n    \"full_id\": " + json_string(g.identifier) + ",\n    \"light_path\": [[" +
               json_string(kStaticLightPath) + "]]\n  }";
        out += i + 1 < grids.size() ? ",\n" : "\n";
    }
    return out + "]\n";
}

std::string grid_states_json(const std::vector<LadybugGrid>& grids) {
    std::string out = "{\n";
    for (std::size_t i = 0; i < grids.size(); ++i)
        out += "  " + json_string(grids[i].identifier) + ": {}" + (i + 1 < grids.size() ? ",\n" : "\n");
    return out + "}\n";
}

// Shortest text that reads back as the same double (7.5, 8760 -> "7.5", "8760").
std::string sun_up_hours_text(const std::vector<double>& hours) {
    std::string out;
    for (const double h : hours) out += shortest_decimal(h) + '\n';
    return out;
}

void write_text(const fs::path& path, const std::string& text) {
    write_file_atomically(path, std::span<const char>(text.data(), text.size()));
}

void make_directory(const fs::path& dir) {
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (ec) throw IoError(dir.string() + ": cannot create the folder: " + ec.message());
}

// Directory entries on disk before the swap (the files themselves are synced as written).
void sync_directory(const fs::path& dir) {
    const int fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (fd < 0) return;
    ::fsync(fd);
    ::close(fd);
}

std::string hidden_name(const fs::path& folder, const char* kind, long pid) {
    std::string name(1, '.');
    name += folder.filename().string();
    name += kind;
    name += std::to_string(pid);
    return name;
}

// `.NAME.tmp.PID` and `.NAME.old.PID` left beside the folder by writers that died before
// they finished: removed when their PID is no longer a live process (or is ours).
void remove_stale(const fs::path& folder) {
    const fs::path parent = folder.parent_path();
    std::error_code ec;
    for (const char* kind : {".tmp.", ".old."}) {
        const std::string prefix = hidden_name(folder, kind, 0).substr(0, folder.filename().string().size() + 6);
        for (fs::directory_iterator it(parent, ec), end; !ec && it != end; it.increment(ec)) {
            const std::string name = it->path().filename().string();
            if (name.size() <= prefix.size() || name.compare(0, prefix.size(), prefix) != 0) continue;
            const std::string digits = name.substr(prefix.size());
            if (digits.size() > 9 || digits.find_first_not_of("0123456789") != std::string::npos) continue;
            const long pid = std::stol(digits);
            const bool dead = ::kill(static_cast<pid_t>(pid), 0) != 0 && errno == ESRCH;
            std::error_code rm;
            if (dead || pid == ::getpid()) fs::remove_all(it->path(), rm);
        }
    }
}

// Removes the temporary folder unless released (every failure path leaves nothing).
class TemporaryFolder {
public:
    explicit TemporaryFolder(fs::path path) : path_(std::move(path)) {}
    ~TemporaryFolder() {
        std::error_code ec;
        if (!released_) fs::remove_all(path_, ec);
    }
    TemporaryFolder(const TemporaryFolder&) = delete;
    TemporaryFolder& operator=(const TemporaryFolder&) = delete;
    const fs::path& path() const { return path_; }
    void release() { released_ = true; }

private:
    fs::path path_;
    bool released_ = false;
};

// Puts the complete new folder in place of `folder`. An existing folder is exchanged with
// the new one in a single step where the file system allows (renameat2 RENAME_EXCHANGE),
// else moved aside first; the old contents are removed afterwards.
void swap_into_place(TemporaryFolder& tmp, const fs::path& folder) {
    std::error_code ec;
    const fs::file_status st = fs::symlink_status(folder, ec);
    if (!fs::exists(st)) {
        if (::rename(tmp.path().c_str(), folder.c_str()) != 0)
            throw IoError(folder.string() + ": cannot put the results folder in place: " + reason(errno));
        tmp.release();
        return;
    }
    if (!fs::is_directory(st)) throw IoError(folder.string() + ": exists and is not a folder; choose another path");
    if (::renameat2(AT_FDCWD, tmp.path().c_str(), AT_FDCWD, folder.c_str(), RENAME_EXCHANGE) == 0) {
        // The old folder now sits at the temporary's name; the guard removes it.
        return;
    }
    if (errno != EINVAL && errno != ENOSYS)
        throw IoError(folder.string() + ": cannot replace the results folder: " + reason(errno));
    const fs::path old = folder.parent_path() / hidden_name(folder, ".old.", ::getpid());
    if (::rename(folder.c_str(), old.c_str()) != 0)
        throw IoError(folder.string() + ": cannot move the old results folder aside: " + reason(errno));
    if (::rename(tmp.path().c_str(), folder.c_str()) != 0) {
        const int err = errno;
        ::rename(old.c_str(), folder.c_str());
        throw IoError(folder.string() + ": cannot put the results folder in place: " + reason(err));
    }
    tmp.release();
    fs::remove_all(old, ec);
}

}  // namespace

std::string npy_float32_header(std::size_t rows, std::size_t cols) {
    std::string header = "{'descr': '<f4', 'fortran_order': False, 'shape': (" + std::to_string(rows) + ", " +
                         std::to_string(cols) + "), }";
    // magic (6) + version (2) + header length (2) + header, a multiple of 64, ending in '\n'.
    constexpr std::size_t kPreamble = 10;
    const std::size_t total = (kPreamble + header.size() + 1 + 63) / 64 * 64;
    header.append(total - kPreamble - header.size() - 1, ' ');
    header += '\n';
    std::string out("\x93NUMPY\x01\x00", 8);
    out += static_cast<char>(header.size() & 0xff);
    out += static_cast<char>((header.size() >> 8) & 0xff);
    return out + header;
}

namespace {
void append_little_endian(std::span<const float> values, std::string& out) {
    out.reserve(out.size() + values.size() * 4);
    for (const float v : values) {
        std::uint32_t bits = std::bit_cast<std::uint32_t>(v);
        for (int b = 0; b < 4; ++b) {  // little-endian whatever the host
            out += static_cast<char>(bits & 0xff);
            bits >>= 8;
        }
    }
}

// A grid's array from its rows callback, a block of sensors at a time, into `path` (in the
// temporary folder: the folder is swapped in whole, so the file need not be atomic itself).
void write_npy_rows(const fs::path& path, const LadybugGrid& g, bool direct, std::size_t hours) {
    const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (fd < 0) throw IoError(path.string() + ": cannot create the file: " + reason(errno));
    auto put = [&](const std::string& bytes) {
        if (const int err = write_all(fd, bytes); err != 0) {
            ::close(fd);
            throw IoError(path.string() + ": cannot write the file: " + reason(err));
        }
    };
    put(npy_float32_header(g.sensors, hours));
    constexpr std::size_t kSensors = 256;
    std::vector<float> values;
    std::string bytes;
    for (std::size_t first = 0; first < g.sensors; first += kSensors) {
        const std::size_t count = std::min(kSensors, g.sensors - first);
        values.assign(count * hours, 0.0F);
        g.rows(direct, first, count, values);
        for (std::size_t k = 0; k < values.size(); ++k)
            if (!std::isfinite(values[k])) {
                ::close(fd);
                throw InputError("Ladybug results: grid '" + g.identifier +
                                 "': " + (direct ? "direct_lx" : "total_lx") + " is not finite at sensor " +
                                 std::to_string(first + k / hours) + ", hour " + std::to_string(k % hours));
            }
        bytes.clear();
        append_little_endian(values, bytes);
        put(bytes);
    }
    const bool synced = ::fsync(fd) == 0;
    const int err = errno;
    ::close(fd);
    if (!synced) throw IoError(path.string() + ": cannot write the file: " + reason(err));
}
}  // namespace

std::string npy_float32(std::span<const float> values, std::size_t rows, std::size_t cols) {
    if (values.size() != rows * cols)
        throw InputError("npy array: " + std::to_string(values.size()) + " values for a " + std::to_string(rows) +
                         " x " + std::to_string(cols) + " array");
    std::string out = npy_float32_header(rows, cols);
    append_little_endian(values, out);
    return out;
}

void write_ladybug_results(const fs::path& folder_in, const std::vector<LadybugGrid>& grids,
                           const std::vector<double>& sun_up_hours) {
    const fs::path folder = folder_in.has_filename() ? folder_in : folder_in.parent_path();
    check_arguments(folder, grids, sun_up_hours);
    const fs::path parent = folder.parent_path().empty() ? fs::path(".") : folder.parent_path();
    const fs::path target = parent / folder.filename();
    remove_stale(target);

    TemporaryFolder tmp(parent / hidden_name(target, ".tmp.", ::getpid()));
    const fs::path state = tmp.path() / kStaticLightPath / kDefaultState;
    const std::size_t hours = sun_up_hours.size();
    for (const char* kind : {"total", "direct"}) {
        make_directory(state / kind);
        for (const LadybugGrid& g : grids) {
            const bool direct = std::string(kind) == "direct";
            if (g.rows && g.total_lx.empty() && g.direct_lx.empty()) {
                write_npy_rows(state / kind / (g.identifier + ".npy"), g, direct, hours);
                continue;
            }
            const std::vector<float>& values = direct ? g.direct_lx : g.total_lx;
            const std::string bytes = npy_float32(values, g.sensors, hours);
            write_file_atomically(state / kind / (g.identifier + ".npy"), std::span(bytes.data(), bytes.size()));
        }
        sync_directory(state / kind);
    }
    write_text(tmp.path() / "grids_info.json", grids_info_json(grids));
    write_text(tmp.path() / "grid_states.json", grid_states_json(grids));
    write_text(tmp.path() / "sun-up-hours.txt", sun_up_hours_text(sun_up_hours));
    sync_directory(state);
    sync_directory(state.parent_path());
    sync_directory(tmp.path());

    swap_into_place(tmp, target);
    sync_directory(parent);
}

}  // namespace luxtrace
