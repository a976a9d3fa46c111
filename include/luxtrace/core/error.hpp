#pragma once
// Errors that reach the user. InputError means "the user's input is wrong": the CLI
// maps it to exit code 2 and prints what() as the single message. The message
// already names the file, the line or key, and what is wrong.
#include <stdexcept>
#include <string>

namespace luxtrace {

class InputError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// A file could not be written (no space, no permission, read-only file system...).
// what() names the file and the operating system's reason. `luxtrace run` exits with
// kExitWriteFailed after saying where the run's tallies are kept.
class IoError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// Exit codes of the command line (README "Exit codes").
inline constexpr int kExitOk = 0;
inline constexpr int kExitInternal = 1;
inline constexpr int kExitBadInput = 2;
inline constexpr int kExitStoppedEarly = 3;
inline constexpr int kExitWriteFailed = 4;

}  // namespace luxtrace
