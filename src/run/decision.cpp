#include "luxtrace/run/decision.hpp"

#include "luxtrace/core/error.hpp"

#include <stdexcept>

namespace luxtrace {

Decision Decision::fault(bool internal) {
    Decision d;
    d.stop = true;
    d.exit_code = internal ? kExitInternal : kExitBadInput;
    d.reason = "error";
    return d;
}

Decision Decision::decision_fault() {
    Decision d = fault(true);
    d.checkpoint = true;  // unlike a tracing fault's, the tallies are whole
    return d;
}

std::vector<double> Decision::encode() const {
    return {stop ? 1.0 : 0.0, checkpoint ? 1.0 : 0.0, static_cast<double>(exit_code), next_period_s,
            result_is_snapshot ? 1.0 : 0.0};
}

Decision Decision::decode(std::span<const double> words) {
    if (words.size() != kWords) throw std::logic_error("Decision::decode: not a decision's words");
    Decision d;
    d.stop = words[0] != 0.0;
    d.checkpoint = words[1] != 0.0;
    d.exit_code = static_cast<int>(words[2]);
    d.next_period_s = words[3];
    d.result_is_snapshot = words[4] != 0.0;
    return d;
}

}  // namespace luxtrace
