// libFuzzer driver: one executable per target, the target chosen at compile time
// (LUXTRACE_FUZZ_ENTRY, e.g. fuzz_scene). Built only with -DLUXTRACE_FUZZ=ON and clang.
#include "fuzz_entry.hpp"

#include <cstddef>
#include <cstdint>

#ifndef LUXTRACE_FUZZ_ENTRY
#error "define LUXTRACE_FUZZ_ENTRY (fuzz_scene, fuzz_ies, fuzz_mesh or fuzz_result)"
#endif

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    return luxtrace::fuzz::LUXTRACE_FUZZ_ENTRY(data, size);
}
