// nut/lod.hpp — level of detail from measured error, as the PGA thesis derives its surrogate
// terminals' switching distances (3.5): each block's full render is compared with its visual
// summary at shrinking projected sizes, and the finest pixel footprint at which the summary still
// matches becomes the block's lodFootprintM. The casters use it with --lod auto.
#pragma once

#include <nut/hierarchy.hpp>
#include <nut/image.hpp>

namespace nut {

struct LodMeasureOptions {
  int tolerance = 8;      // largest difference per channel (of 255) between summary and full render
  int supersampling = 4;  // reference rays per pixel along each axis, box-filtered
  int finestPixels = 32;  // the finest level measured: the block's largest side this many pixels across
};

// For every block a redirection targets, renders it alone with the CPU caster from outside each of
// its six sides, head-on and tilted by 30 degrees towards each of the side's four edges, with
// parallel rays on a pixel grid whose pixels are the block's largest side divided by 1, 2, 4, ...
// finestPixels. The reference pixel is the mean of supersampling^2 rays at full detail; the
// candidate is what the caster draws for the summary there (the side's summary colour, shaded,
// over the background by its coverage). A view passes a level when no pixel differs by more than
// the tolerance; the block's footprint is the pixel size of the finest level that every view
// passes along with all coarser ones, and 0 (never) when a view fails already at one pixel.
// Sets lodFootprintM of those blocks and leaves the others at 0. `image` must be compile(h).
void measureLevelOfDetail(Hierarchy& h, const Image& image, const LodMeasureOptions& options = {});

}  // namespace nut
