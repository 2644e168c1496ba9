// The generated LoD2 district, converted once (bench/lod2_district.hpp).
#include "lod2_district.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>

#include <glm/common.hpp>

#include <converter/convert.hpp>
#include <scene/obj.hpp>

namespace nut::bench {

namespace {

template <typename T>
T orExit(Result<T> result) {
  if (!result) {
    std::fprintf(stderr, "lod2 district: %s\n", result.error().message.c_str());
    std::exit(1);
  }
  return std::move(*result);
}

}  // namespace

const Lod2District& lod2District(int width, int height) {
  static const std::unique_ptr<Lod2District> district = [width, height] {
    auto d = std::make_unique<Lod2District>();
    const scene::ObjContents obj =
        orExit(scene::readObj(std::string(NUT_SOURCE_DIR) + "/tests/data/lod2_district_seed1.obj"));
    d->source = orExit(mergeMeshes(obj.objects, "district"));
    for (int planes = 0; planes < 2; ++planes) {
      converter::ConvertOptions options;
      options.solid.planeCells = planes == 1;
      ConvertedDistrict& c = d->converted[planes];
      for (const TriangleMesh& building : obj.objects) {
        converter::Conversion conversion = orExit(converter::convertMesh(building, options));
        c.complementTriangles += conversion.complement.triangles.size();
        c.planeCells += static_cast<std::size_t>(conversion.report.solid.planeCells);
        c.images.push_back(std::move(conversion.image));
        c.originsM.push_back(conversion.originM);
        c.complements.push_back(std::move(conversion.complement));
      }
    }
    WorldBox bounds{glm::dvec3(INFINITY), glm::dvec3(-INFINITY)};
    for (const glm::dvec3& p : d->source.positions) {
      bounds.min = glm::min(bounds.min, p);
      bounds.max = glm::max(bounds.max, p);
    }
    d->camera = fitCamera(bounds, width, height);
    return d;
  }();
  return *district;
}

}  // namespace nut::bench
