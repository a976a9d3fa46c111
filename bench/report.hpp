#pragma once
// The bench's report: the tracer's rate against Embree alone per thread count, and the
// packets, floor and speed-up lines.
#include "measurements.hpp"

#include <cstddef>
#include <cstdint>

namespace luxtrace::bench {

// `floor_rays`: the rays of one floor run (0 without --floor).
void print_report(const Measurements& m, const MeasurePlan& plan, std::size_t floor_rays);

}  // namespace luxtrace::bench
