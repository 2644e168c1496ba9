// packer/src/width_search.cpp — packSearchWidth: the HNI layout's bin-width search. As in the
// paper, every image width is tried and the layout with the least waste is kept.
#include <packer/maxrects.hpp>

#include <algorithm>
#include <utility>

namespace packer {
namespace {

long long boundingArea(const Layout& layout) {
  return static_cast<long long>(layout.width) * layout.height;
}

}  // namespace

std::optional<Layout> packSearchWidth(std::span<const Item> items, int maxWidth, int maxHeight,
                                      const Options& options) {
  int minWidth = 1;
  for (const Item& item : items) minWidth = std::max(minWidth, item.width);
  for (const Rect& r : options.reserved) minWidth = std::max(minWidth, r.right());
  maxWidth = std::max(maxWidth, minWidth);

  // Every successful layout holds the same items, so less waste means a smaller bounding box.
  // That lets a width give up as soon as its bounding box outgrows the best one found, and lets
  // the search end at the first layout without waste.
  Options attempt = options;
  std::optional<Layout> best;
  for (int width = minWidth; width <= maxWidth; ++width) {
    std::optional<Layout> layout = pack(items, width, maxHeight, attempt);
    if (!layout) continue;
    const long long area = boundingArea(*layout);
    if (best && (area > boundingArea(*best) ||
                 (area == boundingArea(*best) && layout->width >= best->width))) {
      continue;
    }
    best = std::move(layout);
    attempt.maxBoundingArea = area;
    if (area == best->usedArea) break;
  }
  return best;
}

}  // namespace packer
