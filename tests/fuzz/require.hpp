// The fuzz targets' check, NUT_FUZZ_REQUIRE(condition): on failure it prints the condition with
// its file and line and aborts, which libFuzzer reports as a crash and the plain corpus test as a
// dead test. (A macro, as assert is, for the line: clang 14 has no std::source_location.)
#pragma once

#include <cstdio>
#include <cstdlib>

namespace nut::fuzz {

[[noreturn]] inline void requirementFailed(const char* condition, const char* file, int line) {
  std::fprintf(stderr, "%s:%d: fuzz check failed: %s\n", file, line, condition);
  std::abort();
}

}  // namespace nut::fuzz

#define NUT_FUZZ_REQUIRE(condition) \
  ((condition) ? void(0) : ::nut::fuzz::requirementFailed(#condition, __FILE__, __LINE__))
