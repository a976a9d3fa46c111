#pragma once
// The result file of SPEC §4. This module is the only code that knows the HDF5 layout.
#include "luxtrace/stats/estimates.hpp"
#include "luxtrace/tally/tally.hpp"

#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace luxtrace {

struct Scene;

// One row per reduction (SPEC §4 /history).
struct HistoryRow {
    double time_s = 0.0;
    std::uint64_t photons = 0;
    double sigma_rel_global = 0.0;
    double forecast_s = 0.0;
};

struct RunInfo {
    std::string luxtrace_version;
    std::string scene_file;
    std::uint64_t seed = 0;
    int ranks = 1;
    int threads_per_rank = 1;
    std::uint64_t photons = 0;
    double flux_per_photon_lm = 0.0;
    double elapsed_s = 0.0;
    std::string stop_reason;
    std::string sampler;
};

// Writes `path` atomically (a temporary file in the same directory, then rename).
void write_result(const std::filesystem::path& path, const Scene& scene, const TallyLayout& layout,
                  const std::vector<std::uint64_t>& tallies, const RunInfo& info,
                  const GlobalEstimate& global, const std::vector<DetectorEstimate>& detectors,
                  const std::vector<HistoryRow>& history);

// Reading back, for `luxtrace info` and for tests.
class ResultReader {
public:
    explicit ResultReader(const std::filesystem::path& path);  // throws InputError
    ~ResultReader();
    ResultReader(const ResultReader&) = delete;
    ResultReader& operator=(const ResultReader&) = delete;

    bool has(const std::string& object) const;
    std::vector<std::uint64_t> u64(const std::string& dataset, std::vector<std::size_t>* shape = nullptr) const;
    std::vector<double> f64(const std::string& dataset, std::vector<std::size_t>* shape = nullptr) const;
    double attr_f64(const std::string& object, const std::string& name) const;
    std::uint64_t attr_u64(const std::string& object, const std::string& name) const;
    std::string attr_str(const std::string& object, const std::string& name) const;
    std::vector<std::string> attr_strs(const std::string& object, const std::string& name) const;
    std::vector<std::string> children(const std::string& group) const;

private:
    std::filesystem::path path_;
    std::int64_t file_ = -1;  // hid_t
};

}  // namespace luxtrace
