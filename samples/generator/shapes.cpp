// Sloped and curved parts, and facade helpers, for the sample buildings (shapes.hpp).
#include "shapes.hpp"

#include <cmath>
#include <numbers>

#include <glm/geometric.hpp>

namespace nut::samples {

using glm::dvec3;

void convexSolid(ObjBuilder& out, const std::vector<ConvexFace>& faces) {
  dvec3 centre(0.0);
  int count = 0;
  for (const ConvexFace& f : faces)
    for (const dvec3& p : f.corners) {
      centre += p;
      ++count;
    }
  centre /= static_cast<double>(count);
  for (const ConvexFace& f : faces) {
    dvec3 normal(0.0), faceCentre(0.0);
    for (std::size_t i = 0; i < f.corners.size(); ++i) {
      normal += glm::cross(f.corners[i], f.corners[(i + 1) % f.corners.size()]);  // Newell
      faceCentre += f.corners[i];
    }
    faceCentre /= static_cast<double>(f.corners.size());
    const bool flip = glm::dot(normal, faceCentre - centre) < 0;
    const std::size_t n = f.corners.size();
    for (std::size_t i = 1; i + 1 < n; ++i) {
      if (flip) out.triangle(f.corners[0], f.corners[i + 1], f.corners[i], f.material);
      else out.triangle(f.corners[0], f.corners[i], f.corners[i + 1], f.material);
    }
  }
}

void gableRoof(ObjBuilder& out, double x0, double x1, double z0, double z1, double yBase, double height, int roof, int gable) {
  const double zm = 0.5 * (z0 + z1), yr = yBase + height;
  const dvec3 a(x0, yBase, z0), b(x1, yBase, z0), c(x1, yBase, z1), d(x0, yBase, z1), r0(x0, yr, zm), r1(x1, yr, zm);
  convexSolid(out, {{{a, b, r1, r0}, roof}, {{d, c, r1, r0}, roof}, {{a, d, r0}, gable}, {{b, c, r1}, gable}, {{a, b, c, d}, gable}});
}

void ramp(ObjBuilder& out, double x0, double x1, double z0, double z1, double yLow, double yHigh, double thickness, int material) {
  const dvec3 b00(x0, yLow, z0), b10(x1, yHigh, z0), b11(x1, yHigh, z1), b01(x0, yLow, z1);
  const dvec3 up(0, thickness, 0);
  convexSolid(out, {{{b00, b10, b11, b01}, material},
                    {{b00 + up, b10 + up, b11 + up, b01 + up}, material},
                    {{b00, b10, b10 + up, b00 + up}, material},
                    {{b01, b11, b11 + up, b01 + up}, material},
                    {{b00, b01, b01 + up, b00 + up}, material},
                    {{b10, b11, b11 + up, b10 + up}, material}});
}

void quarterCylinder(ObjBuilder& out, double cx, double cz, double r, double y0, double y1, int signX, int signZ,
                     int segments, int material) {
  std::vector<dvec3> arc;
  for (int i = 0; i <= segments; ++i) {
    const double t = 0.5 * std::numbers::pi * i / segments;
    arc.emplace_back(cx + signX * r * std::cos(t), 0.0, cz + signZ * r * std::sin(t));
  }
  const auto at = [](dvec3 p, double y) { return dvec3(p.x, y, p.z); };
  std::vector<ConvexFace> faces;
  std::vector<dvec3> bottom{dvec3(cx, y0, cz)}, top{dvec3(cx, y1, cz)};
  for (const dvec3& p : arc) {
    bottom.push_back(at(p, y0));
    top.push_back(at(p, y1));
  }
  faces.push_back({bottom, material});
  faces.push_back({top, material});
  for (int i = 0; i < segments; ++i)
    faces.push_back({{at(arc[static_cast<std::size_t>(i)], y0), at(arc[static_cast<std::size_t>(i + 1)], y0),
                      at(arc[static_cast<std::size_t>(i + 1)], y1), at(arc[static_cast<std::size_t>(i)], y1)},
                     material});
  faces.push_back({{dvec3(cx, y0, cz), at(arc.front(), y0), at(arc.front(), y1), dvec3(cx, y1, cz)}, material});
  faces.push_back({{dvec3(cx, y0, cz), at(arc.back(), y0), at(arc.back(), y1), dvec3(cx, y1, cz)}, material});
  convexSolid(out, faces);
}

void domedDrum(ObjBuilder& out, double cx, double cz, double r, double y0, double y1, int segments, int rings, int drum, int dome) {
  const auto ring = [&](double radius, double y) {
    std::vector<dvec3> pts;
    for (int i = 0; i < segments; ++i) {
      const double t = 2.0 * std::numbers::pi * i / segments;
      pts.emplace_back(cx + radius * std::cos(t), y, cz + radius * std::sin(t));
    }
    return pts;
  };
  std::vector<ConvexFace> faces;
  const std::vector<dvec3> base = ring(r, y0), rim = ring(r, y1);
  faces.push_back({base, drum});
  for (int i = 0; i < segments; ++i) {
    const auto j = static_cast<std::size_t>((i + 1) % segments), k = static_cast<std::size_t>(i);
    faces.push_back({{base[k], base[j], rim[j], rim[k]}, drum});
  }
  std::vector<dvec3> previous = rim;
  for (int q = 1; q <= rings; ++q) {
    const double phi = 0.5 * std::numbers::pi * q / rings;
    if (q == rings) {
      const dvec3 apex(cx, y1 + r, cz);
      for (int i = 0; i < segments; ++i)
        faces.push_back({{previous[static_cast<std::size_t>(i)], previous[static_cast<std::size_t>((i + 1) % segments)], apex}, dome});
      break;
    }
    const std::vector<dvec3> next = ring(r * std::cos(phi), y1 + r * std::sin(phi));
    for (int i = 0; i < segments; ++i) {
      const auto j = static_cast<std::size_t>((i + 1) % segments), k = static_cast<std::size_t>(i);
      faces.push_back({{previous[k], previous[j], next[j], next[k]}, dome});
    }
    previous = next;
  }
  convexSolid(out, faces);
}

void Facade::box(PaintGrid& grid, double n0, double n1, double t0, double t1, double y0, double y1, int material) const {
  const int along = normalAxis == 0 ? 2 : 0;
  dvec3 lo, hi;
  lo[normalAxis] = plane + sign * n0;
  hi[normalAxis] = plane + sign * n1;
  lo[along] = t0;
  hi[along] = t1;
  lo.y = y0;
  hi.y = y1;
  grid.box(lo, hi, material);
}

void window(PaintGrid& grid, const Facade& f, double t0, double y0, double w, double h, const WindowStyle& s) {
  const double t1 = t0 + w, y1 = y0 + h;
  constexpr double kPane = 0.05;
  f.box(grid, -s.depth, 0.0, t0, t1, y0, y1, PaintGrid::kCarve);
  f.box(grid, -s.depth - kPane, -s.depth, t0, t1, y0, y1, s.glass);
  if (s.mullion > 0) {
    const double tm = 0.5 * (t0 + t1);
    f.box(grid, -s.depth, -s.depth + 0.06, tm - 0.5 * s.mullion, tm + 0.5 * s.mullion, y0, y1, s.frame);
  }
  if (s.transomAt > 0) {
    const double ym = y0 + s.transomAt * h;
    f.box(grid, -s.depth, -s.depth + 0.06, t0, t1, ym - 0.03, ym + 0.03, s.frame);
  }
  if (s.trim > 0) {
    const double t = s.trim;
    f.box(grid, 0.0, 0.03, t0 - t, t1 + t, y1, y1 + t, s.frame);
    f.box(grid, 0.0, 0.03, t0 - t, t0, y0, y1, s.frame);
    f.box(grid, 0.0, 0.03, t1, t1 + t, y0, y1, s.frame);
  }
  if (s.sillOut > 0) f.box(grid, 0.0, s.sillOut, t0 - 0.08, t1 + 0.08, y0 - 0.08, y0, s.frame);
}

}  // namespace nut::samples
