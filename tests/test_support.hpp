#pragma once
// Helpers shared by the tests: scratch directories, running the luxtrace binary,
// chi-square limits.
#include <sys/wait.h>
#include <unistd.h>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace luxtrace::test_support {

// The least geometry a scene needs: a black 5 cm square facing up at z = -0.6, for runs
// of lights over unobstructed detectors.
inline constexpr const char* kBlackSpeck = R"([[material]]
name = "black"
type = "black"

[[shape]]
type = "rectangle"
center = [0, 0, -0.6]
normal = [0, 0, 1]
size = [0.05, 0.05]
material = "black"
)";

// A scratch directory luxtrace_<tag>_<pid> in the system's temporary folder, empty when
// made and removed with everything in it at the end of its scope.
class ScratchDir {
public:
    explicit ScratchDir(const std::string& tag)
        : path_(std::filesystem::temp_directory_path() / ("luxtrace_" + tag + "_" + std::to_string(::getpid()))) {
        std::filesystem::remove_all(path_);
        std::filesystem::create_directories(path_);
    }
    ~ScratchDir() {
        std::error_code ec;
        std::filesystem::remove_all(path_, ec);
    }
    ScratchDir(const ScratchDir&) = delete;
    ScratchDir& operator=(const ScratchDir&) = delete;
    const std::filesystem::path& path() const { return path_; }

private:
    std::filesystem::path path_;
};

struct CommandOutcome {
    int code;         // exit code, -1 if the process did not exit normally
    std::string out;  // stdout and stderr together
};

// Runs `LUXTRACE_BINARY args` and captures what it prints.
inline CommandOutcome run_luxtrace(const std::string& args) {
    static int serial = 0;
    const std::filesystem::path log = std::filesystem::temp_directory_path() /
                                      ("luxtrace_test_" + std::to_string(::getpid()) + "_" + std::to_string(serial++) +
                                       ".log");
    const std::string cmd = std::string(LUXTRACE_BINARY) + " " + args + " > " + log.string() + " 2>&1";
    const int status = std::system(cmd.c_str());
    std::stringstream ss;
    ss << std::ifstream(log).rdbuf();
    std::filesystem::remove(log);
    return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, ss.str()};
}

inline constexpr double kZ999 = 3.090232306167813;  // standard normal quantile at 0.999

// Upper quantile of chi-square with `dof` degrees of freedom for the standard normal
// quantile z (Wilson-Hilferty cube-root approximation; well under 1% off for dof >= 5).
inline double chi2_quantile(double dof, double z) {
    const double a = 2.0 / (9.0 * dof);
    const double c = 1.0 - a + z * std::sqrt(a);
    return dof * c * c * c;
}

// Writes `text` as DIR/NAME.toml and runs it (quiet, 2 threads) into DIR/NAME.h5: that
// path, and in `outcome` (if given) what the run printed and returned.
inline std::filesystem::path run_scene_text(const ScratchDir& dir, const std::string& name, const std::string& text,
                                            CommandOutcome* outcome = nullptr) {
    const std::filesystem::path scene = dir.path() / (name + ".toml"), out = dir.path() / (name + ".h5");
    std::ofstream(scene) << text;
    const CommandOutcome o = run_luxtrace("run \"" + scene.string() + "\" --output \"" + out.string() +
                                          "\" --quiet --threads 2");
    if (outcome != nullptr) *outcome = o;
    return out;
}

}  // namespace luxtrace::test_support
