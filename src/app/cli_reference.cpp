#include "cli_reference.hpp"

#include <string>

namespace luxtrace {

namespace {

// A table cell: '|' would end the cell.
std::string cell(const std::string& text) {
    std::string out;
    for (char c : text) {
        if (c == '|') out += '\\';
        out += c;
    }
    return out;
}

// "-o,--output" -> "`-o`, `--output`"
std::string names(const CLI::Option& opt) {
    const std::string all = opt.nonpositional() ? opt.get_name(false, true) : opt.get_name(true);
    std::string out, part;
    auto flush = [&] {
        if (part.empty()) return;
        out += (out.empty() ? "`" : ", `") + part + "`";
        part.clear();
    };
    for (char c : all) {
        if (c == ',') flush();
        else part += c;
    }
    flush();
    return out;
}

// Subcommands leave out their -h/--help, which the program's own table lists once.
void print_options(const CLI::App& app, std::ostream& os, bool with_help) {
    os << "| argument or option | value | meaning |\n|---|---|---|\n";
    // Positionals first, in order, then options as declared.
    for (bool positional : {true, false})
        for (const CLI::Option* opt : app.get_options()) {
            // Hidden options (group "") are for tests, not users.
            if (opt->nonpositional() == positional || (!with_help && opt == app.get_help_ptr()) ||
                opt->get_group().empty())
                continue;
            std::string value = opt->get_type_size() == 0 ? "" : opt->get_type_name();
            if (opt->get_required()) value += value.empty() ? "required" : ", required";
            if (opt->get_expected_max() > 1) value += ", repeatable";
            os << "| " << names(*opt) << " | " << cell(value) << " | " << cell(opt->get_description()) << " |\n";
        }
}

}  // namespace

void print_cli_reference(const CLI::App& app, std::ostream& os) {
    os << "#### `" << app.get_name() << "`\n\n" << app.get_description() << "\n\n";
    print_options(app, os, true);
    for (const CLI::App* sub : app.get_subcommands([](const CLI::App* s) { return !s->get_group().empty(); })) {
        os << "\n#### `" << app.get_name() << ' ' << sub->get_name() << "`\n\n" << sub->get_description() << "\n\n";
        print_options(*sub, os, false);
    }
}

}  // namespace luxtrace
