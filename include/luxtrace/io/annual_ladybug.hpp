#pragma once
// An annual run's hourly values as the Ladybug Tools results folder (docs/LADYBUG.md,
// io/ladybug_results.hpp): one grid per annual sensor grid, the sun-up hours of a 365-day
// year (the hours whose middle has the sun above the horizon; 29 February of a leap-year
// file is left out, as the reader's year has 8760 hours).
#include "luxtrace/estimate/annual_estimate.hpp"

#include <filesystem>
#include <optional>
#include <vector>

namespace luxtrace {

struct Scene;

// Where the folder goes: [annual] ladybug_folder, or beside the result as NAME_ladybug.
std::filesystem::path ladybug_folder_for(const Scene& scene, const std::filesystem::path& result);

// `source`: where the series are for estimates that hold none (AnnualSeriesSink).
void write_annual_ladybug(const std::filesystem::path& folder, const Scene& scene,
                          const std::vector<std::optional<AnnualDetectorEstimate>>& annual,
                          const AnnualSeriesSource& source = {});

}  // namespace luxtrace
