// packer/maxrects.hpp — MaxRects rectangle bin packing (Jylänki, "A thousand ways to pack the
// bin", 2010) and the bin-width search that HNI compilation and the viewer's atlases use.
//
// Rectangles are never rotated: an HNI's records have a fixed orientation. An item may carry a
// region limit (it must end at or before maxRight / maxBottom): HNI headers and metadata arrays
// use it to stay inside the 8-bit-addressed 256x256 metadata region.
#pragma once

#include <climits>
#include <optional>
#include <span>
#include <utility>
#include <vector>

namespace packer {

struct Rect {
  int x = 0, y = 0, width = 0, height = 0;
  int right() const { return x + width; }
  int bottom() const { return y + height; }
  long long area() const { return static_cast<long long>(width) * height; }
  friend bool operator==(const Rect&, const Rect&) = default;
};

struct Item {
  int id = 0;
  int width = 0, height = 0;
  int maxRight = INT_MAX;   // the placed rectangle must satisfy x + width <= maxRight
  int maxBottom = INT_MAX;  // and y + height <= maxBottom
};

struct Placement {
  int id = 0;
  Rect rect;
};

// Free-rectangle choice rules of the MaxRects family; names follow Jylänki.
enum class Heuristic {
  BestAreaFit,       // BAF: least leftover area, ties by short side
  BestShortSideFit,  // BSSF
  BestLongSideFit,   // BLSF
  BottomLeft,        // BL: lowest top edge, ties by x
  ContactPoint,      // CP: longest perimeter touching bin edges and placed rectangles
};

// Online: items sorted by area (descending, stable) and inserted one at a time.
// Global: Jylänki's batch mode, which at every step scores all remaining items against all free
// rectangles and places the best pair (slower, the reference for waste).
enum class Mode { Online, Global };

struct Options {
  Heuristic heuristic = Heuristic::BestAreaFit;
  Mode mode = Mode::Online;
  std::span<const Rect> reserved = {};  // already occupied before packing (e.g. a fixed record)
  // Give up (nullopt) as soon as the bounding box of what is placed exceeds this area; the width
  // search uses it to abandon a width that can no longer beat the best one found.
  long long maxBoundingArea = LLONG_MAX;
  // Online mode: insert items with a region limit before the others (each group by area). Large
  // HNIs need it: by area alone, data components fill the top rows before the small 8-bit-addressed
  // records come, and those then find no room in the metadata region. It costs some waste.
  bool regionLimitedFirst = false;
};

struct Layout {
  int width = 0;   // bounding width of everything placed (reserved included)
  int height = 0;  // bounding height
  std::vector<Placement> placements;  // in the order of the input items
  long long usedArea = 0;             // sum of item and reserved areas

  // Percentage of width * height not covered by items or reserved rectangles.
  double wastePct() const;
};

// One MaxRects bin. insert() places a rectangle and returns where, or nullopt if it fits nowhere.
class MaxRectsBin {
 public:
  MaxRectsBin(int width, int height);
  std::optional<Rect> insert(const Item& item, Heuristic heuristic);
  // Marks a rectangle as used (it must lie inside the bin).
  void occupy(const Rect& r);
  // Score of placing item in the best free rectangle (lower is better), without placing it.
  std::optional<std::pair<Rect, long long>> score(const Item& item, Heuristic heuristic) const;
  const std::vector<Rect>& freeRects() const { return free_; }

 private:
  void place(const Rect& r);
  int width_, height_;
  std::vector<Rect> free_;
  std::vector<Rect> used_;
};

// Packs all items into a bin of the given width and height; nullopt if one does not fit.
std::optional<Layout> pack(std::span<const Item> items, int binWidth, int binHeight,
                           const Options& options = {});

// Tries every bin width from the widest item (or reserved rectangle) up to maxWidth (inclusive;
// raised to the widest item if smaller) with unbounded height capped at maxHeight, and keeps the
// layout with the least waste (ties: smaller area, then smaller width). nullopt if no width fits.
std::optional<Layout> packSearchWidth(std::span<const Item> items, int maxWidth, int maxHeight,
                                      const Options& options = {});

}  // namespace packer
