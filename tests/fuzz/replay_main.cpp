// Replays fuzz inputs through an entry function (fuzz_entry.hpp), with any compiler:
//   fuzz_replay TARGET DIR_OR_FILE...
// Every regular file under each argument (recursively, in name order; README* and dot
// files excepted) is one input.
// Exits 0 when every input ends normally or in InputError; otherwise prints the file
// and the exception and exits 1. A crash or an abort (a broken invariant) ends the
// process itself, after the name of the input has been printed.
#include "fuzz_entry.hpp"

#include <algorithm>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <string>
#include <vector>

int main(int argc, char** argv) {
    namespace fs = std::filesystem;
    if (argc < 3) {
        std::cerr << "usage: fuzz_replay scene|ies|mesh|result DIR_OR_FILE...\n";
        return 2;
    }
    const auto entry = luxtrace::fuzz::entry_by_name(argv[1]);
    if (entry == nullptr) {
        std::cerr << "fuzz_replay: unknown target '" << argv[1] << "'\n";
        return 2;
    }
    std::vector<fs::path> inputs;
    for (int i = 2; i < argc; ++i) {
        const fs::path p(argv[i]);
        if (fs::is_regular_file(p)) {
            inputs.push_back(p);
        } else if (fs::is_directory(p)) {
            for (const auto& e : fs::recursive_directory_iterator(p))
                if (e.is_regular_file() && e.path().filename().string().rfind("README", 0) != 0 &&
                    e.path().filename().string().front() != '.')
                    inputs.push_back(e.path());
        } else {
            std::cerr << "fuzz_replay: " << p << " does not exist\n";
            return 2;
        }
    }
    std::sort(inputs.begin(), inputs.end());
    int failed = 0;
    for (const fs::path& p : inputs) {
        std::ifstream in(p, std::ios::binary);
        const std::vector<char> bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
        std::cerr << "replay " << p.string() << " (" << bytes.size() << " bytes)\n";
        try {
            entry(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
        } catch (const std::exception& e) {
            std::cerr << "FAILED: " << p.string() << ": uncaught exception (not InputError): " << e.what() << '\n';
            ++failed;
        } catch (...) {
            std::cerr << "FAILED: " << p.string() << ": uncaught non-standard exception\n";
            ++failed;
        }
    }
    std::cout << "fuzz_replay " << argv[1] << ": " << inputs.size() << " inputs, " << failed << " failed\n";
    return failed == 0 ? 0 : 1;
}
