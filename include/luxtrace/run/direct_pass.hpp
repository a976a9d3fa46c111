#pragma once
// The annual grids' direct light by shadow rays ([annual] direct = "shadow_rays", issue 37),
// computed before tracing: every rank takes its share of each grid's cells, with all its
// cores, and rank 0 gathers them. The values are those of one rank alone (each cell's
// samples depend only on the seed, the detector and the cell).
#include "luxtrace/annual/direct_coefficients.hpp"

namespace luxtrace {

class Communicator;
class EmbreeScene;
struct Scene;

// Rank 0: per detector, its coefficients (cells 0 for a detector that is no annual grid);
// the other ranks: empty. Empty on every rank for a scene without shadow rays.
AnnualDirect annual_direct_pass(const Scene& scene, const EmbreeScene& embree, const Communicator& comm);

}  // namespace luxtrace
