#pragma once
// The command-line part of docs/REFERENCE.md, written from the CLI11 definition itself
// (`luxtrace reference cli`), so the document and the program cannot drift apart:
// tests/reference_test.cpp compares the two, scripts/update_reference.sh rewrites the block.
#include <CLI/CLI.hpp>

#include <ostream>

namespace luxtrace {

// Markdown: one table per visible subcommand (arguments and options, value type, help text),
// the program's own options first (with -h/--help, which every subcommand also takes). Hidden subcommands (empty group)
// are left out.
void print_cli_reference(const CLI::App& app, std::ostream& os);

}  // namespace luxtrace
