#pragma once
// Loops over every core (TBB) whose iterations each write their own elements, so that
// what they compute has the same bits on any core count: a ten-million-triangle scene's
// per-triangle tables and maps (issue 26). Header only: a template over the loop body.
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cstddef>

namespace luxtrace {

// Calls f(i) for every i in [0, n), in blocks of at least `grain` indices.
template <class F>
void for_each_index(std::size_t n, std::size_t grain, F&& f) {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, grain), [&](const tbb::blocked_range<std::size_t>& r) {
        for (std::size_t i = r.begin(); i != r.end(); ++i) f(i);
    });
}

}  // namespace luxtrace
