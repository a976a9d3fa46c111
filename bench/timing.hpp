#pragma once
// Timing of the bench's measurements: wall and process CPU time of work spread over threads.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <thread>
#include <vector>

namespace luxtrace::bench {

using Clock = std::chrono::steady_clock;

inline double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// CPU time of the whole process: CPU / (wall x threads) well below 1 means other
// processes took the cores during a measurement.
double process_cpu_seconds();
// CPU time of the calling thread alone.
double thread_cpu_seconds();

double median(std::vector<double> v);

struct Timed {
    double seconds = 0.0, cpu_seconds = 0.0;
    std::uint64_t rays = 0, hits = 0;
};

// Runs `worker` on `threads` threads (the calling one among them) and times the whole:
// wall and process CPU seconds.
template <class Worker>
Timed run_on_threads(int threads, const Worker& worker) {
    const auto t0 = Clock::now();
    const double c0 = process_cpu_seconds();
    {
        std::vector<std::jthread> pool;
        for (int i = 1; i < threads; ++i) pool.emplace_back(worker);
        worker();
    }
    return {seconds_since(t0), process_cpu_seconds() - c0, 0, 0};
}

// Runs `hits_in(first, last)` over every chunk of 1024 rays, `threads` threads taking
// chunks from one counter (as the tracer's threads take photons); times the whole.
template <class Chunk>
Timed on_threads(std::size_t rays, int threads, const Chunk& hits_in) {
    constexpr std::size_t kChunk = 1024;  // a multiple of 8, for the packets
    std::atomic<std::size_t> next{0};
    std::atomic<std::uint64_t> hits{0};
    auto worker = [&] {
        std::uint64_t mine = 0;
        for (std::size_t first; (first = next.fetch_add(kChunk)) < rays;)
            mine += hits_in(first, std::min(rays, first + kChunk));
        hits += mine;
    };
    Timed t = run_on_threads(threads, worker);
    t.rays = rays;
    t.hits = hits.load();
    return t;
}

}  // namespace luxtrace::bench
