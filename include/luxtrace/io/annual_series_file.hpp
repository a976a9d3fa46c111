#pragma once
// The annual grids' hourly series kept on disk while the post-processing makes them
// (issue 37 §4): a whole building's 100,000 sensors x 4,410 daylit hours x 4 series (the
// illuminance, the direct sun and their errors) are 7 GB as floats, more than a rank should
// hold. The blocks (estimate/annual_estimate.hpp, kBlockCells cells each) are written as they
// come, from any core in any order, and read back by hours (the result file's datasets,
// hours x cells) or by cells (the Ladybug results' arrays, cells x hours). Floats: the result
// file stores them so (seven digits, far below any run's error).
//
// A scratch file beside the result (hidden, named after it and the process), removed when
// this object goes; only the daylit hours are stored (the others are 0).
#include "luxtrace/estimate/annual_estimate.hpp"

#include <cstddef>
#include <filesystem>
#include <span>
#include <vector>

namespace luxtrace {

class AnnualSeriesFile {
public:
    using Kind = AnnualSeriesKind;
    static constexpr std::size_t kKinds = kAnnualSeriesKinds;
    // Per detector its cells (0: not an annual grid); `daylit` per hour of the year, 1 where
    // the hour has a sky. Throws IoError naming the file when it cannot be made.
    AnnualSeriesFile(const std::filesystem::path& beside, const std::vector<std::size_t>& grid_cells,
                     const std::vector<std::uint8_t>& daylit, std::size_t block_cells);
    ~AnnualSeriesFile();
    AnnualSeriesFile(const AnnualSeriesFile&) = delete;
    AnnualSeriesFile& operator=(const AnnualSeriesFile&) = delete;

    std::size_t hours() const { return row_of_hour_.size(); }
    std::size_t cells(std::size_t det) const { return det < cells_.size() ? cells_[det] : 0; }
    // Cells [first, first + value.sensors) of grid `det`, every hour (hour-major, as the
    // estimator makes them); `first` a multiple of the block size. Safe from several threads.
    void write(std::size_t det, std::size_t first, const AnnualSeries& value, const AnnualSeries& sigma);
    // Hours [h0, h1) of every cell, hour-major: out[(h - h0) * cells + c].
    void read_hours(std::size_t det, Kind kind, std::size_t h0, std::size_t h1, std::span<float> out) const;
    // Cells [first, first + count) of every hour, cell-major: out[c * hours + h].
    void read_cells(std::size_t det, Kind kind, std::size_t first, std::size_t count, std::span<float> out) const;
    const std::filesystem::path& path() const { return path_; }

private:
    std::size_t block_offset(std::size_t det, std::size_t block) const;
    void pwrite_all(const void* data, std::size_t bytes, std::size_t offset);
    void pread_all(void* data, std::size_t bytes, std::size_t offset) const;

    std::filesystem::path path_;
    int fd_ = -1;
    std::size_t block_cells_ = 0, rows_ = 0;  // floats per block: kKinds x rows_ x block_cells_
    std::vector<std::size_t> cells_, det_offset_;
    std::vector<std::ptrdiff_t> row_of_hour_;  // -1 for a dark hour
};

}  // namespace luxtrace
