// make_obj_samples OUTDIR: writes the sample OBJ buildings (samples/obj/ holds the committed
// outputs): highrise, residential, carpark, house, street, each with its MTL file.
#include <cstdio>
#include <filesystem>
#include <functional>
#include <string>

#include "buildings.hpp"
#include "obj_builder.hpp"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: make_obj_samples OUTDIR\n");
    return 1;
  }
  const std::filesystem::path dir(argv[1]);
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  struct Sample {
    const char* name;
    const char* description;
    std::function<void(nut::samples::ObjBuilder&)> build;
  };
  const Sample samples[] = {
      {"highrise", "high-rise: 40 storeys, recessed windows with mullions, transoms, sills and trims", nut::samples::highRise},
      {"residential", "residential block: balconies, chimneys, gable roof", nut::samples::residential},
      {"carpark", "car park: decks on pillars, parapets, ramps, stair tower", nut::samples::carPark},
      {"house", "house: round corners, domed rotunda", nut::samples::house},
      {"street", "street block: four touching buildings, one object each", nut::samples::streetBlock},
  };
  for (const Sample& s : samples) {
    nut::samples::ObjBuilder builder;
    s.build(builder);
    const std::string path = (dir / (std::string(s.name) + ".obj")).string();
    if (!builder.write(path, std::string("nut sample ") + s.name + ": " + s.description + " (CC0)")) return 2;
    std::printf("%s: %zu triangles\n", path.c_str(), builder.triangleCount());
  }
  return 0;
}
