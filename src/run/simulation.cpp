#include "luxtrace/run/simulation.hpp"

#include "luxtrace/run/run_loop.hpp"

#include <thread>

namespace luxtrace {

RunSummary run_simulation(const Scene& scene, const Communicator& comm, const RunOptions& opt, std::ostream& out) {
    RunLoop loop(scene, comm, opt, out);  // restore
    loop.check_writable();
    loop.trace();
    Decision decision;
    do {
        loop.wait_for_reduction();
        loop.snapshot();
        loop.reduce();
        decision = loop.broadcast(loop.decide());
        loop.checkpoint(decision);
    } while (!decision.stop);
    return loop.write(decision);
}

}  // namespace luxtrace
