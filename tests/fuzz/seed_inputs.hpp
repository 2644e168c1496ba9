// The generated seed inputs of the fuzz targets, shared by fuzz_seeds (which writes them as a
// libFuzzer corpus) and the plain corpus test (which runs every target over them). Hand-made
// inputs are files under tests/fuzz/corpus/<target>/, and inputs that once failed under
// tests/fuzz/regressions/<target>/; both are read as they are.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <nut/error.hpp>

namespace nut::fuzz {

struct SeedInput {
  std::string name;
  std::vector<std::uint8_t> bytes;
};

// hni_fuzz and render_fuzz: framed HNIs (frame.hpp) of 32 seeded random hierarchies and of the
// sample HNIs (samples/hni/*.png).
Result<std::vector<SeedInput>> hniSeeds();

// obj_fuzz: every OBJ of samples/obj/ and tests/data/, whole, framed with its MTL (obj_input.hpp).
std::vector<SeedInput> objSeeds();

// glb_fuzz: every .glb of tests/data/ (gltfpack's output).
std::vector<SeedInput> glbSeeds();

// city_fuzz: a manifest as the writer (scene::cityJson) makes it, with and without complements.
std::vector<SeedInput> citySeeds();

// grammar_fuzz: every grammar of samples/grammars/.
std::vector<SeedInput> grammarSeeds();

// The files of a folder under tests/fuzz/ (e.g. "corpus/obj_fuzz"), README.md aside; none when
// the folder does not exist.
std::vector<SeedInput> committedInputs(const std::string& folder);

}  // namespace nut::fuzz
