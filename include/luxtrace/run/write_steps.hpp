#pragma once
// The steps a run takes after tracing to write a file (the result, a checkpoint, or the
// tally checkpoint it falls back on), each named in the message when it fails, and each
// one a test can make fail on purpose (RunOptions::inject_fault; the hidden option
// `--inject-fault FILE:STEP[,FILE:STEP...]`; docs/RELIABILITY.md "Nothing traced is lost").
//
//   FILE  result | checkpoint (periodic or final) | tallies (the tally checkpoint)
//   STEP  estimates | annual | image | rename | ladybug
// and run:decide, rank 0's decision after a reduction (the run then stops and keeps its
// tallies).
#include <chrono>
#include <functional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace luxtrace {

// Empty when `spec` is a comma-separated list of FILE:STEP as above; otherwise what is
// wrong with it.
std::string injected_fault_invalid(const std::string& spec);

// A write step that failed other than by the file system (an IoError): a bug of ours or a
// library's. Its message names the step.
struct WriteStepError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

class WriteSteps {
public:
    // Steps of writing `file` (result, checkpoint or tallies); `inject` as RunOptions has it.
    WriteSteps(std::string file, std::string inject) : file_(std::move(file)), inject_(std::move(inject)) {}

    // Runs `step`: an IoError passes as it is (it names the file and the system's reason),
    // any other exception comes out as a WriteStepError naming the step; an injected fault
    // of the step throws before it runs.
    template <class F>
    decltype(auto) run(std::string_view step, F&& f) const {
        try {
            fail_if_injected(step);
            const Timer timer(*this, step);
            return std::forward<F>(f)();
        } catch (const std::exception& e) {
            rethrow_named(step, e);
        } catch (...) {
            rethrow_named(step, std::runtime_error("an unknown exception"));
        }
        throw;  // not reached: rethrow_named always throws
    }

    // Adds to the latest run of `step` the seconds it took elsewhere (work done for it
    // before the write, e.g. by every rank).
    void add_seconds(std::string_view step, double s) const {
        for (auto it = seconds_.rbegin(); it != seconds_.rend(); ++it)
            if (it->first == step) {
                it->second += s;
                return;
            }
    }
    // The wall seconds each step took, in the order they ran (a step run twice, twice).
    const std::vector<std::pair<std::string, double>>& seconds() const { return seconds_; }

    // What write_file_atomically runs before its rename: an injected fault of the step
    // "rename" fails there, as a rename the file system refuses (an IoError).
    std::function<void()> before_rename(const std::string& path) const;

private:
    // Adds the step's wall time when it ends, by return or by exception.
    struct Timer {
        const WriteSteps& steps;
        std::string_view step;
        std::chrono::steady_clock::time_point start = std::chrono::steady_clock::now();
        Timer(const WriteSteps& s, std::string_view name) : steps(s), step(name) {}
        ~Timer() {
            steps.seconds_
                .emplace_back(std::string(step),
                              std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
        }
    };

    void fail_if_injected(std::string_view step) const;
    [[noreturn]] void rethrow_named(std::string_view step, const std::exception& e) const;
    bool injected(std::string_view step) const;

    std::string file_, inject_;
    mutable std::vector<std::pair<std::string, double>> seconds_;
};

}  // namespace luxtrace
