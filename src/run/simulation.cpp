#include "luxtrace/run/simulation.hpp"

#include "luxtrace/run/run_loop.hpp"

#include <sched.h>

#include <algorithm>
#include <thread>

namespace luxtrace {

int available_cores() {
    cpu_set_t set;
    CPU_ZERO(&set);
    if (sched_getaffinity(0, sizeof(set), &set) == 0) return std::max(1, CPU_COUNT(&set));
    return std::max(1u, std::thread::hardware_concurrency());
}

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
