// The libFuzzer entry point of one fuzz target, named at build time by NUT_FUZZ_TARGET
// (tests/CMakeLists.txt builds one binary per target from this file and the target's source).
#include "targets.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return nut::fuzz::NUT_FUZZ_TARGET(data, size);
}
