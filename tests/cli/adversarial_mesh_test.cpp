// `nut convert` on adversarial meshes, as a user would run it: a million degenerate faces, every
// face duplicated many times, coordinates of 1e30, NaN in some vertices, a soup of disconnected
// triangles. Each either converts to an HNI that validates or is refused with one error line and a
// non-zero exit, leaving no output file; and the process's peak memory stays under the case's
// bound. Each case is a test of its own, so that ctest runs it in a process of its own and the
// peak resident size of its children (getrusage RUSAGE_CHILDREN) is that one conversion's.
#include <gtest/gtest.h>

#include <sys/resource.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <random>
#include <string>

#include <nut/hni.hpp>
#include <nut/png_io.hpp>

#include "cli_support.hpp"

namespace nut {
namespace {

namespace fs = std::filesystem;

std::string out(const std::string& name) { return testing::outputPath("adversarial", name); }

// A closed 10 m cube: vertices 1..8 and its twelve faces, so that a mesh has something to convert.
void writeCube(std::ofstream& f) {
  f << "v 0 0 0\nv 10 0 0\nv 10 10 0\nv 0 10 0\nv 0 0 10\nv 10 0 10\nv 10 10 10\nv 0 10 10\n";
}
const char* kCubeFaces =
    "f 1 3 2\nf 1 4 3\nf 5 6 7\nf 5 7 8\nf 1 2 6\nf 1 6 5\nf 2 3 7\nf 2 7 6\nf 3 4 8\nf 3 8 7\nf 4 1 5\nf 4 5 8\n";

struct Case {
  std::string name;
  std::function<void(std::ofstream&)> write;
  bool converts;        // else refused
  std::string error;    // what the one error line says
  long long maxRssMiB;  // the bound on the conversion's peak memory
};

std::ostream& operator<<(std::ostream& os, const Case& c) { return os << c.name; }

const Case kCases[] = {
    {"degenerate",
     [](std::ofstream& f) {
       writeCube(f);
       f << kCubeFaces << "v 5 5 5\n";
       for (int i = 0; i < 1'000'000; ++i) f << "f 9 9 9\n";  // a million faces of one point
     },
     true, "", 256},
    {"duplicated",
     [](std::ofstream& f) {
       writeCube(f);
       for (int i = 0; i < 20'000; ++i) f << kCubeFaces;  // 240,000 faces, each 20,000 times
     },
     true, "", 512},
    {"huge_coordinates",
     [](std::ofstream& f) {
       writeCube(f);
       f << kCubeFaces << "v 1e30 0 0\nv 0 1e30 0\nv 0 0 1e30\nf 9 10 11\n";
     },
     false, "the mesh spans 1e+30 m along x, more than an HNI holds", 128},
    {"nan",
     [](std::ofstream& f) {
       writeCube(f);
       f << kCubeFaces << "v nan 0 0\nv 1 nan 2\nv 3 3 3\nf 9 10 11\n";
     },
     false, "nan.obj:21: vertex 9 has a non-finite coordinate 'nan'", 128},
    {"soup",
     [](std::ofstream& f) {
       std::mt19937 random(7);
       std::uniform_real_distribution<double> place(0, 100), jitter(-1, 1);
       for (int i = 0; i < 20'000; ++i) {  // 20,000 unconnected triangles in a 100 m box
         const double x = place(random), y = place(random), z = place(random);
         for (int k = 0; k < 3; ++k)
           f << "v " << x + jitter(random) << ' ' << y + jitter(random) << ' ' << z + jitter(random) << '\n';
         f << "f " << 3 * i + 1 << ' ' << 3 * i + 2 << ' ' << 3 * i + 3 << '\n';
       }
     },
     true, "", 512},
};

class AdversarialMesh : public ::testing::TestWithParam<Case> {};

TEST_P(AdversarialMesh, ConvertsOrIsRefusedInBoundedMemory) {
  const Case& c = GetParam();
  const std::string obj = out(c.name + ".obj"), png = out(c.name + ".png");
  {
    std::ofstream f(obj);
    c.write(f);
  }
  fs::remove(png);
  const testing::CliRun r = testing::runNut("convert " + obj + " -o " + png + " --quiet", "adversarial");
  if (c.converts) {
    EXPECT_EQ(r.exitCode, 0) << r.stderrText;
    auto image = readPng(png);
    ASSERT_TRUE(image) << image.error().message;
    EXPECT_TRUE(validate(image->image).ok());
  } else {
    EXPECT_EQ(r.exitCode, 1) << r.stderrText;
    EXPECT_EQ(r.stderrText.rfind("error: ", 0), 0u) << r.stderrText;
    EXPECT_EQ(std::count(r.stderrText.begin(), r.stderrText.end(), '\n'), 1) << r.stderrText;
    EXPECT_NE(r.stderrText.find(c.error), std::string::npos) << r.stderrText;
    EXPECT_FALSE(fs::exists(png));
  }
  rusage usage{};
  ASSERT_EQ(getrusage(RUSAGE_CHILDREN, &usage), 0);
  const long long peakMiB = usage.ru_maxrss / 1024;  // kilobytes on Linux
  std::printf("%s: peak resident memory %lld MiB (bound %lld)\n", c.name.c_str(), peakMiB, c.maxRssMiB);
#if defined(__SANITIZE_ADDRESS__)
  // AddressSanitizer's shadow memory and quarantine are not the converter's: make test-sanitize
  // checks the behaviour here and `make test` the memory.
  std::printf("%s: memory bound not checked under AddressSanitizer\n", c.name.c_str());
#else
  EXPECT_LT(peakMiB, c.maxRssMiB);
#endif
  fs::remove(obj);
}

INSTANTIATE_TEST_SUITE_P(Meshes, AdversarialMesh, ::testing::ValuesIn(kCases),
                         [](const ::testing::TestParamInfo<Case>& param) { return param.param.name; });

}  // namespace
}  // namespace nut
