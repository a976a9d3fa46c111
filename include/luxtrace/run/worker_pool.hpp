#pragma once
// A rank's tracing threads. They take chunks from RankWork and trace them into the
// rank's TallyStore; the main thread can pause them at chunk boundaries (every thread
// has flushed its buffer, so the store holds exactly the photons handed out) to take a
// consistent snapshot, then let them go on.
#include "luxtrace/run/work_plan.hpp"
#include "luxtrace/tracer/surface_table.hpp"
#include "luxtrace/tracer/tracer.hpp"

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <exception>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

namespace luxtrace {

struct TraceOptions {
    std::uint64_t seed = 1;
    std::string sampler = "random";
    std::uint32_t replicates = PhotonSampler::kDefaultReplicates;  // sobol's R
    int threads = 1;
    std::uint64_t chunk = 256;  // photons a thread takes at a time (pause latency)
};

class WorkerPool {
public:
    // `surfaces` is the scene's on `embree`, built by the caller as part of its setup (a
    // large scene's takes a noticeable time); the first form builds its own.
    WorkerPool(const Scene& scene, const EmbreeScene& embree, TallyStore& store, RankWork& work,
               const TraceOptions& opt);
    WorkerPool(const Scene& scene, const EmbreeScene& embree, const SurfaceTable& surfaces, TallyStore& store,
               RankWork& work, const TraceOptions& opt);
    ~WorkerPool();  // stops and joins
    WorkerPool(const WorkerPool&) = delete;
    WorkerPool& operator=(const WorkerPool&) = delete;

    // Blocks until every thread is parked at a chunk boundary (or out of work, or at
    // RankWork's fence; those go on after resume() once the fence has been moved).
    void pause();
    void resume();
    // Finish the current chunks and end the threads.
    void stop();
    // Sleeps until a thread parks (out of work, at the fence, failed) or max_s passes,
    // so that the main thread learns at once that the work is done.
    void wait_for_park(double max_s);
    // True once every thread has run out of work.
    bool exhausted() const { return idle_.load() == static_cast<int>(threads_.size()); }
    // A tracing thread threw. The thread parks as if out of work (so pause() and stop()
    // still return) and keeps the first exception for the main thread; the tallies are
    // then incomplete and must not be written.
    bool failed() const { return failed_.load(); }
    // After stop(): the share of the threads' tracing time they ran on a core (their CPU
    // time over their wall time from the pool's start until each ran out of work or was
    // stopped, summed over the threads): parks for reductions and waits for the core
    // count the lost share.
    double busy_fraction() const;
    // After stop(): from the pool's start until its last thread ran out of work or stopped.
    double tracing_s() const;
    std::exception_ptr error() const;

private:
    void start();  // the threads
    struct ThreadTime {
        double cpu0_s = 0.0;  // the thread's CPU time at its start
        bool counted = false;
    };
    void worker();                       // times run_worker on its thread
    void thread_done(ThreadTime& time);  // adds the thread's CPU and wall time to the sums, once
    void run_worker(ThreadTime& time);   // traces until stopped; a failure parks it as idle
    void trace_until_stopped(ThreadTime& time);
    const Scene& scene_;
    const EmbreeScene& embree_;
    std::optional<SurfaceTable> own_surfaces_;
    const SurfaceTable& surfaces_;  // shared by the threads
    TallyStore& store_;
    RankWork& work_;
    TraceOptions opt_;
    mutable std::mutex mutex_;
    std::condition_variable cv_main_, cv_workers_;
    bool pause_requested_ = false, stop_requested_ = false;
    int parked_ = 0;
    std::uint64_t resumes_ = 0;  // a thread parked at the fence retries after a resume
    std::atomic<int> idle_{0};
    std::atomic<bool> failed_{false};
    std::exception_ptr error_;            // guarded by mutex_
    double cpu_s_ = 0.0, alive_s_ = 0.0;  // summed over finished threads, guarded by mutex_
    double last_done_s_ = 0.0;            // guarded by mutex_
    std::chrono::steady_clock::time_point start_;
    std::vector<std::thread> threads_;
};

}  // namespace luxtrace
