#include "luxtrace/io/annual_series_file.hpp"

#include "luxtrace/core/error.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <string>

namespace luxtrace {

namespace {
std::string reason(int err) { return std::strerror(err); }
}  // namespace

AnnualSeriesFile::AnnualSeriesFile(const std::filesystem::path& beside, const std::vector<std::size_t>& grid_cells,
                                   const std::vector<std::uint8_t>& daylit, std::size_t block_cells)
    : block_cells_(block_cells), cells_(grid_cells) {
    for (const std::uint8_t d : daylit) row_of_hour_.push_back(d != 0 ? static_cast<std::ptrdiff_t>(rows_++) : -1);
    std::size_t offset = 0;
    for (const std::size_t cells : cells_) {
        det_offset_.push_back(offset);
        const std::size_t blocks = (cells + block_cells_ - 1) / block_cells_;
        offset += blocks * kKinds * rows_ * block_cells_ * sizeof(float);
    }
    const std::filesystem::path dir = beside.parent_path().empty() ? "." : beside.parent_path();
    // Appended to, not built with "." + ...: GCC 12 warns falsely on that (-Wrestrict, its bug
    // 105329).
    std::string name(1, '.');
    name += beside.filename().string();
    name += ".series.";
    name += std::to_string(::getpid());
    name += ".tmp";
    path_ = dir / name;
    fd_ = ::open(path_.c_str(), O_RDWR | O_CREAT | O_TRUNC | O_CLOEXEC, 0600);
    if (fd_ < 0) throw IoError(path_.string() + ": cannot create the annual series' scratch file: " + reason(errno));
    // Unlinked at once: the file lives as long as this object's descriptor, and a run that
    // dies leaves nothing behind.
    ::unlink(path_.c_str());
}

AnnualSeriesFile::~AnnualSeriesFile() {
    if (fd_ >= 0) ::close(fd_);
}

std::size_t AnnualSeriesFile::block_offset(std::size_t det, std::size_t block) const {
    return det_offset_[det] + block * kKinds * rows_ * block_cells_ * sizeof(float);
}

void AnnualSeriesFile::pwrite_all(const void* data, std::size_t bytes, std::size_t offset) {
    const char* p = static_cast<const char*>(data);
    while (bytes > 0) {
        const ssize_t n = ::pwrite(fd_, p, bytes, static_cast<off_t>(offset));
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0)
            throw IoError(path_.string() +
                          ": cannot write the annual series' scratch file: " + reason(n < 0 ? errno : ENOSPC));
        p += n;
        offset += static_cast<std::size_t>(n);
        bytes -= static_cast<std::size_t>(n);
    }
}

void AnnualSeriesFile::pread_all(void* data, std::size_t bytes, std::size_t offset) const {
    char* p = static_cast<char*>(data);
    while (bytes > 0) {
        const ssize_t n = ::pread(fd_, p, bytes, static_cast<off_t>(offset));
        if (n < 0 && errno == EINTR) continue;
        if (n < 0) throw IoError(path_.string() + ": cannot read the annual series' scratch file: " + reason(errno));
        if (n == 0) {  // never written: a hole reads as zeros, past the end as nothing
            std::fill(p, p + bytes, 0);
            return;
        }
        p += n;
        offset += static_cast<std::size_t>(n);
        bytes -= static_cast<std::size_t>(n);
    }
}

void AnnualSeriesFile::write(std::size_t det, std::size_t first, const AnnualSeries& value, const AnnualSeries& sigma) {
    const std::size_t count = value.sensors, hours = row_of_hour_.size();
    if (det >= cells_.size() || first % block_cells_ != 0 || first + count > cells_[det] || value.hours != hours ||
        sigma.sensors != count || sigma.hours != hours)
        throw std::logic_error("AnnualSeriesFile::write: a block beyond its grid");
    // In AnnualSeriesKind's order.
    const std::vector<double>* series[kKinds] = {&value.total_lx, &value.direct_lx, &sigma.total_lx, &sigma.direct_lx};
    std::vector<float> block(kKinds * rows_ * block_cells_);
    for (std::size_t b0 = 0; b0 < count; b0 += block_cells_) {
        const std::size_t n = std::min(block_cells_, count - b0);
        std::fill(block.begin(), block.end(), 0.0F);
        for (std::size_t k = 0; k < kKinds; ++k)
            for (std::size_t h = 0; h < hours; ++h) {
                if (row_of_hour_[h] < 0) continue;
                float* out = &block[(k * rows_ + static_cast<std::size_t>(row_of_hour_[h])) * block_cells_];
                const double* in = &(*series[k])[h * count + b0];
                for (std::size_t c = 0; c < n; ++c) out[c] = static_cast<float>(in[c]);
            }
        pwrite_all(block.data(), block.size() * sizeof(float), block_offset(det, (first + b0) / block_cells_));
    }
}

void AnnualSeriesFile::read_hours(std::size_t det, Kind kind, std::size_t h0, std::size_t h1,
                                  std::span<float> out) const {
    const std::size_t cells = cells_.at(det);
    if (h1 < h0 || h1 > hours() || out.size() != (h1 - h0) * cells)
        throw std::logic_error("AnnualSeriesFile::read_hours: hours beyond the year");
    std::fill(out.begin(), out.end(), 0.0F);
    // The daylit rows among the hours: one contiguous run of rows per block.
    std::ptrdiff_t r0 = -1, r1 = -1;
    for (std::size_t h = h0; h < h1; ++h)
        if (row_of_hour_[h] >= 0) {
            if (r0 < 0) r0 = row_of_hour_[h];
            r1 = row_of_hour_[h] + 1;
        }
    if (r0 < 0) return;
    const std::size_t rows = static_cast<std::size_t>(r1 - r0);
    std::vector<float> buf(rows * block_cells_);
    for (std::size_t b = 0; b * block_cells_ < cells; ++b) {
        const std::size_t n = std::min(block_cells_, cells - b * block_cells_);
        pread_all(buf.data(), buf.size() * sizeof(float),
                  block_offset(det, b) +
                      ((static_cast<std::size_t>(kind) * rows_ + static_cast<std::size_t>(r0)) * block_cells_) *
                          sizeof(float));
        for (std::size_t h = h0; h < h1; ++h) {
            if (row_of_hour_[h] < 0) continue;
            const float* in = &buf[static_cast<std::size_t>(row_of_hour_[h] - r0) * block_cells_];
            std::copy_n(in, n, &out[(h - h0) * cells + b * block_cells_]);
        }
    }
}

void AnnualSeriesFile::read_cells(std::size_t det, Kind kind, std::size_t first, std::size_t count,
                                  std::span<float> out) const {
    const std::size_t cells = cells_.at(det), hours = row_of_hour_.size();
    if (first + count > cells || out.size() != count * hours)
        throw std::logic_error("AnnualSeriesFile::read_cells: cells beyond the grid");
    std::fill(out.begin(), out.end(), 0.0F);
    std::vector<float> buf(rows_ * block_cells_);
    for (std::size_t c = first; c < first + count;) {
        const std::size_t b = c / block_cells_, in_block = c % block_cells_;
        const std::size_t n = std::min(block_cells_ - in_block, first + count - c);
        pread_all(buf.data(), buf.size() * sizeof(float),
                  block_offset(det, b) + static_cast<std::size_t>(kind) * rows_ * block_cells_ * sizeof(float));
        for (std::size_t h = 0; h < hours; ++h) {
            if (row_of_hour_[h] < 0) continue;
            const float* in = &buf[static_cast<std::size_t>(row_of_hour_[h]) * block_cells_ + in_block];
            for (std::size_t i = 0; i < n; ++i) out[(c - first + i) * hours + h] = in[i];
        }
        c += n;
    }
}

}  // namespace luxtrace
