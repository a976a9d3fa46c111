#pragma once
// What rank 0 decides after a reduction (RunController::after_reduction), and what every
// rank then acts on. It travels as doubles through Communicator::broadcast: every field
// but `reason` (rank 0's words for the result file). To add a field: a member here, a
// word in encode and decode (kWords grows), and a row in tests/run_control_test.cpp.
#include <span>
#include <string>
#include <vector>

namespace luxtrace {

struct Decision {
    bool stop = false;
    bool checkpoint = false;  // write a checkpoint: now (periodic) or with the final result (exit 3)
    int exit_code = 0;
    double next_period_s = 1.0;  // seconds to the next reduction
    // The run ends with this reduction's snapshot as its result: it holds every photon the
    // result may hold (reductions at photon counts, or every rank out of work), so no final
    // reduction follows (and none of the photons traced meanwhile enters the result).
    bool result_is_snapshot = false;
    std::string reason;  // rank 0 only: not broadcast

    // A rank could not trace: its tallies are incomplete, nothing is written (exit 1 for an
    // internal fault, 2 for bad input).
    static Decision fault(bool internal);
    // Rank 0 failed to decide (a bug between reductions): every rank's tallies are whole,
    // so the run stops and keeps them in a checkpoint (exit 1).
    static Decision decision_fault();

    static constexpr std::size_t kWords = 5;
    std::vector<double> encode() const;
    // `words` as encode made them (kWords of them); the reason stays empty.
    static Decision decode(std::span<const double> words);
};

}  // namespace luxtrace
