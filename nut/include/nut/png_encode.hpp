// nut/png_encode.hpp — the PNG encoder behind writePng: RGBA8 pixels and HNI text chunks to PNG
// bytes, as small as the chosen effort allows.
//
// An HNI's size on the wire is its PNG size, so the encoder does what a PNG optimiser does: it
// tries several scanline filter strategies (each of the five filters on every row, and three
// per-row choices: the least sum of absolute values, as libpng does, the least byte entropy, and
// the fewest bytes zlib adds after the rows already chosen) and keeps the one zlib compresses best; at the highest effort the winner is deflated again with Zopfli,
// an exhaustive deflate encoder whose output any inflater reads. The pixels are stored exactly
// (8-bit RGBA, no colour chunks, no premultiplication).
#pragma once

#include <cstdint>
#include <string>

#include <glm/vec3.hpp>

#include <nut/image.hpp>

namespace nut {

// Stored as PNG text chunks nut:name, nut:generator, nut:units, nut:origin ("x y z", metres).
struct HniText {
  std::string name;
  std::string generator;
  std::string units = "m";
  glm::dvec3 originM{0.0};  // world position of the root block's origin, full double precision
};

enum class PngEffort {
  Quick,     // per-row least-sum filters, zlib level 6: renders and diff images
  Small,     // the best of three filter strategies, zlib level 9: comparing candidate layouts
  Smallest,  // every strategy, the winner re-deflated by Zopfli: HNIs (about 1 s per 150 KB of
             // pixels on two cores; images over 4 MB get Small's filters with zlib instead)
};

// The complete PNG file. `text` may be null (no text chunks, as for renders).
std::string encodePng(const Image& image, const HniText* text, PngEffort effort);

}  // namespace nut
