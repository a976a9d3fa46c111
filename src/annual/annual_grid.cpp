#include "luxtrace/annual/annual_grid.hpp"

#include "luxtrace/detector/detector.hpp"

namespace luxtrace {

bool annual_grid(const Detector& d) {
    return (d.type == DetectorType::illuminance || d.type == DetectorType::points) && !d.indirect_only;
}

}  // namespace luxtrace
