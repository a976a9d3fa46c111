#include "luxtrace/run/worker_pool.hpp"

#include "luxtrace/core/error.hpp"
#include "luxtrace/sampler/philox_sampler.hpp"

#include <time.h>

#include <chrono>

namespace luxtrace {

WorkerPool::WorkerPool(const Scene& scene, const EmbreeScene& embree, TallyStore& store, RankWork& work,
                       const TraceOptions& opt)
    : scene_(scene), embree_(embree), own_surfaces_(std::in_place, scene, embree), surfaces_(*own_surfaces_),
      store_(store), work_(work), opt_(opt) {
    start();
}

WorkerPool::WorkerPool(const Scene& scene, const EmbreeScene& embree, const SurfaceTable& surfaces, TallyStore& store,
                       RankWork& work, const TraceOptions& opt)
    : scene_(scene), embree_(embree), surfaces_(surfaces), store_(store), work_(work), opt_(opt) {
    start();
}

void WorkerPool::start() {
    start_ = std::chrono::steady_clock::now();
    for (int i = 0; i < std::max(1, opt_.threads); ++i) threads_.emplace_back([this] { worker(); });
}

WorkerPool::~WorkerPool() { stop(); }

namespace {
double thread_cpu_s() {
    timespec ts{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}
}  // namespace

double WorkerPool::busy_fraction() const {
    std::lock_guard lock(mutex_);
    return alive_s_ > 0.0 ? cpu_s_ / alive_s_ : 0.0;
}

double WorkerPool::tracing_s() const {
    std::lock_guard lock(mutex_);
    return last_done_s_;
}

void WorkerPool::worker() {
    ThreadTime time{thread_cpu_s()};
    run_worker(time);
    thread_done(time);
}

void WorkerPool::thread_done(ThreadTime& time) {
    if (time.counted) return;  // when it ran out of work
    time.counted = true;
    const double cpu = thread_cpu_s() - time.cpu0_s;
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    std::lock_guard lock(mutex_);
    cpu_s_ += cpu;
    alive_s_ += wall;
    last_done_s_ = std::max(last_done_s_, wall);
}

void WorkerPool::run_worker(ThreadTime& time) {
    try {
        trace_until_stopped(time);
    } catch (...) {
        {
            std::lock_guard lock(mutex_);
            if (!error_) error_ = std::current_exception();
        }
        failed_.store(true);
        // Park as an idle thread until the pool stops, so pause() and stop() return.
        idle_.fetch_add(1);
        std::unique_lock lock(mutex_);
        ++parked_;
        cv_main_.notify_all();
        cv_workers_.wait(lock, [&] { return stop_requested_; });
        --parked_;
    }
}

void WorkerPool::trace_until_stopped(ThreadTime& time) {
    PhotonTracer tracer(scene_, embree_, surfaces_, store_.layout(),
                        PhotonSampler(sampler_kind(opt_.sampler), opt_.seed, opt_.replicates));
    TallyBuffer buffer(store_);
    bool out_of_work = false, at_fence = false;
    while (true) {
        {
            std::unique_lock lock(mutex_);
            if (pause_requested_ || out_of_work || at_fence) {
                // Park at a chunk boundary with everything flushed; an idle thread stays
                // parked (and counted) until the pool stops, one at the fence until the
                // next resume.
                buffer.flush();
                ++parked_;
                cv_main_.notify_all();
                const std::uint64_t resumes = resumes_;
                cv_workers_.wait(lock, [&] {
                    return stop_requested_ || (!pause_requested_ && !out_of_work && (!at_fence || resumes_ != resumes));
                });
                --parked_;
                at_fence = false;
            }
            if (stop_requested_) break;
        }
        PhotonRange chunk;
        const RankWork::Next next = work_.next_chunk(opt_.chunk, chunk);
        if (next == RankWork::Next::fenced) {
            at_fence = true;
            continue;
        }
        if (next == RankWork::Next::exhausted) {
            // The thread's part of the tracing ends here: the parks and reductions after
            // it are the run's end, not time the tracer lost.
            buffer.flush();
            thread_done(time);
            out_of_work = true;
            idle_.fetch_add(1);
            continue;
        }
        tracer.trace(chunk.begin, chunk.end, buffer);
    }
    buffer.flush();
}

std::exception_ptr WorkerPool::error() const {
    std::lock_guard lock(mutex_);
    return error_;
}

void WorkerPool::pause() {
    std::unique_lock lock(mutex_);
    pause_requested_ = true;
    cv_main_.wait(lock, [&] { return parked_ == static_cast<int>(threads_.size()); });
}

void WorkerPool::wait_for_park(double max_s) {
    std::unique_lock lock(mutex_);
    const int parked = parked_;
    cv_main_.wait_for(lock, std::chrono::duration<double>(max_s), [&] { return parked_ != parked; });
}

void WorkerPool::resume() {
    {
        std::lock_guard lock(mutex_);
        pause_requested_ = false;
        ++resumes_;
    }
    cv_workers_.notify_all();
}

void WorkerPool::stop() {
    {
        std::lock_guard lock(mutex_);
        stop_requested_ = true;
    }
    cv_workers_.notify_all();
    for (std::thread& t : threads_)
        if (t.joinable()) t.join();
}

}  // namespace luxtrace
