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

}  // namespace luxtrace
