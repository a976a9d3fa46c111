#include "luxtrace/run/write_steps.hpp"

#include "luxtrace/core/error.hpp"

#include <array>
#include <vector>

namespace luxtrace {

namespace {

constexpr std::array<std::string_view, 4> kFiles{"result", "checkpoint", "tallies", "run"};

// Each step with the words a message says it with.
struct Step {
    std::string_view name, doing;
};
constexpr std::array<Step, 6> kSteps{{{"estimates", "computing the estimates"},
                                      {"annual", "computing the annual metrics"},
                                      {"image", "making the HDF5 file"},
                                      {"rename", "writing the file"},
                                      {"ladybug", "writing the Ladybug results folder"},
                                      {"decide", "deciding after a reduction"}}};

std::string_view doing(std::string_view step) {
    for (const Step& s : kSteps)
        if (s.name == step) return s.doing;
    return step;
}

// The FILE:STEP items of a comma-separated list.
std::vector<std::string_view> items(std::string_view list) {
    std::vector<std::string_view> out;
    while (!list.empty()) {
        const std::size_t comma = list.find(',');
        out.push_back(list.substr(0, comma));
        list = comma == std::string_view::npos ? std::string_view{} : list.substr(comma + 1);
    }
    return out;
}

}  // namespace

std::string injected_fault_invalid(const std::string& spec) {
    for (const std::string_view item : items(spec)) {
        const std::size_t colon = item.find(':');
        const std::string_view file = item.substr(0, colon);
        const std::string_view step = colon == std::string_view::npos ? std::string_view{} : item.substr(colon + 1);
        bool file_ok = false, step_ok = false;
        for (std::string_view f : kFiles) file_ok = file_ok || f == file;
        for (const Step& s : kSteps) step_ok = step_ok || s.name == step;
        if (!file_ok || !step_ok) {
            // Appended to, not built with "'" + ...: GCC 12 warns falsely on that (-Wrestrict,
            // its bug 105329).
            std::string why(1, '\'');
            why += item;
            why += "' is not FILE:STEP with FILE result, checkpoint, tallies or run and STEP estimates, annual, "
                   "image, rename, ladybug or decide";
            return why;
        }
    }
    return {};
}

bool WriteSteps::injected(std::string_view step) const {
    for (const std::string_view item : items(inject_))
        if (item.size() == file_.size() + 1 + step.size() && item.substr(0, file_.size()) == file_ &&
            item[file_.size()] == ':' && item.substr(file_.size() + 1) == step)
            return true;
    return false;
}

void WriteSteps::fail_if_injected(std::string_view step) const {
    if (step != "rename" && injected(step)) throw std::runtime_error("injected fault (--inject-fault " + inject_ + ")");
}

void WriteSteps::rethrow_named(std::string_view step, const std::exception& e) const {
    if (const auto* io = dynamic_cast<const IoError*>(&e)) throw *io;
    throw WriteStepError("internal error while " + std::string(doing(step)) + ": " + e.what());
}

std::function<void()> WriteSteps::before_rename(const std::string& path) const {
    if (!injected("rename")) return {};
    return [path, inject = inject_] {
        throw IoError(path + ": cannot replace the file: injected fault (--inject-fault " + inject + ")");
    };
}

}  // namespace luxtrace
