// packer/src/maxrects.cpp — the MaxRects bin (free-rectangle bookkeeping and Jylänki's
// placement heuristics) and pack() in its online and global (batch) modes.
#include <packer/maxrects.hpp>

#include <algorithm>
#include <cstddef>
#include <numeric>
#include <tuple>

namespace packer {
namespace {

bool overlaps(const Rect& a, const Rect& b) {
  return a.x < b.right() && b.x < a.right() && a.y < b.bottom() && b.y < a.bottom();
}

bool contains(const Rect& outer, const Rect& inner) {
  return inner.x >= outer.x && inner.y >= outer.y && inner.right() <= outer.right() &&
         inner.bottom() <= outer.bottom();
}

// Whether any of rects contains inner. The scan has no early exit, so that the compiler can
// vectorize it: this is the hot loop of online packing.
bool anyContains(std::span<const Rect> rects, const Rect& inner) {
  int smallestMargin = INT_MAX;
  for (const Rect& outer : rects) {
    smallestMargin = std::min(smallestMargin, std::max({outer.x - inner.x, outer.y - inner.y,
                                                        inner.right() - outer.right(),
                                                        inner.bottom() - outer.bottom()}));
  }
  return smallestMargin <= 0;
}

// Length shared by the intervals [a0, a1) and [b0, b1).
long long sharedLength(int a0, int a1, int b0, int b1) {
  return std::max(0, std::min(a1, b1) - std::max(a0, b0));
}

// Length of the edge that r shares with an adjacent, non-overlapping rectangle.
long long touchingLength(const Rect& r, const Rect& other) {
  if (other.x == r.right() || other.right() == r.x) {
    return sharedLength(r.y, r.bottom(), other.y, other.bottom());
  }
  if (other.y == r.bottom() || other.bottom() == r.y) {
    return sharedLength(r.x, r.right(), other.x, other.right());
  }
  return 0;
}

// CP's score: how much of r's perimeter touches the bin's edges or a used rectangle.
long long contactPerimeter(const Rect& r, int binWidth, int binHeight,
                           const std::vector<Rect>& used) {
  long long contact = 0;
  if (r.x == 0 || r.right() == binWidth) contact += r.height;
  if (r.y == 0 || r.bottom() == binHeight) contact += r.width;
  for (const Rect& u : used) contact += touchingLength(r, u);
  return contact;
}

// A heuristic's (primary, secondary) rule packed into one integer, so that scores also compare
// across items (global mode). Secondary terms are coordinates or side lengths, 0..INT_MAX.
// A primary too large to pack (a leftover area over 2^32, only in bins far larger than any
// texture) saturates, and such candidates are then told apart by the secondary term alone.
long long combine(long long primary, long long secondary) {
  constexpr long long kSecondaryRange = 1LL << 31;
  constexpr long long kPrimaryLimit = LLONG_MAX / kSecondaryRange - 1;
  return std::clamp(primary, -kPrimaryLimit, kPrimaryLimit) * kSecondaryRange + secondary;
}

// Online insertion order: region-limited items first if asked, then larger area first; ties by larger height, then larger width, then
// input order, so that the result never depends on the sort algorithm.
std::vector<std::size_t> insertionOrder(std::span<const Item> items, bool regionLimitedFirst) {
  std::vector<std::size_t> order(items.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  auto key = [&](std::size_t i) {
    const Item& item = items[i];
    const bool limited = item.maxRight != INT_MAX || item.maxBottom != INT_MAX;
    return std::tuple(regionLimitedFirst && !limited, -static_cast<long long>(item.width) * item.height,
                      -item.height, -item.width, i);
  };
  std::sort(order.begin(), order.end(),
            [&](std::size_t a, std::size_t b) { return key(a) < key(b); });
  return order;
}

// The bounding box and used area of a layout being built; refuses a rectangle that would push
// the bounding box past the caller's area limit.
class LayoutBuilder {
 public:
  LayoutBuilder(std::size_t itemCount, long long maxBoundingArea) : maxArea_(maxBoundingArea) {
    layout_.placements.resize(itemCount);
  }
  bool add(const Rect& r) {
    layout_.width = std::max(layout_.width, r.right());
    layout_.height = std::max(layout_.height, r.bottom());
    layout_.usedArea += r.area();
    return static_cast<long long>(layout_.width) * layout_.height <= maxArea_;
  }
  bool place(std::size_t index, int id, const Rect& r) {
    layout_.placements[index] = {id, r};
    return add(r);
  }
  Layout take() { return std::move(layout_); }

 private:
  Layout layout_;
  long long maxArea_;
};

}  // namespace

double Layout::wastePct() const {
  const long long boundingArea = static_cast<long long>(width) * height;
  if (boundingArea == 0) return 0.0;
  return 100.0 * static_cast<double>(boundingArea - usedArea) / static_cast<double>(boundingArea);
}

MaxRectsBin::MaxRectsBin(int width, int height) : width_(width), height_(height) {
  if (width > 0 && height > 0) free_.push_back({0, 0, width, height});
}

std::optional<std::pair<Rect, long long>> MaxRectsBin::score(const Item& item,
                                                             Heuristic heuristic) const {
  std::optional<std::pair<Rect, long long>> best;
  for (const Rect& f : free_) {
    if (item.width > f.width || item.height > f.height) continue;
    // The item goes in the free rectangle's top-left corner, its lowest x and y: if the region
    // limit fails there, it fails everywhere in this free rectangle.
    if (static_cast<long long>(f.x) + item.width > item.maxRight ||
        static_cast<long long>(f.y) + item.height > item.maxBottom) {
      continue;
    }
    const Rect placed{f.x, f.y, item.width, item.height};
    const long long leftoverX = f.width - item.width;
    const long long leftoverY = f.height - item.height;
    const long long shortSide = std::min(leftoverX, leftoverY);
    const long long longSide = std::max(leftoverX, leftoverY);
    long long s = 0;
    switch (heuristic) {
      case Heuristic::BestAreaFit: s = combine(f.area() - placed.area(), shortSide); break;
      case Heuristic::BestShortSideFit: s = combine(shortSide, longSide); break;
      case Heuristic::BestLongSideFit: s = combine(longSide, shortSide); break;
      case Heuristic::BottomLeft: s = combine(placed.bottom(), placed.x); break;
      case Heuristic::ContactPoint:
        s = combine(-contactPerimeter(placed, width_, height_, used_), placed.bottom());
        break;
    }
    if (!best || s < best->second) best = {placed, s};
  }
  return best;
}

std::optional<Rect> MaxRectsBin::insert(const Item& item, Heuristic heuristic) {
  const auto best = score(item, heuristic);
  if (!best) return std::nullopt;
  place(best->first);
  return best->first;
}

void MaxRectsBin::occupy(const Rect& r) { place(r); }

void MaxRectsBin::place(const Rect& r) {
  // Split every free rectangle that r overlaps into its (up to four) maximal parts outside r.
  // The parts are appended behind the old rectangles; the overlapped ones are dropped.
  const std::size_t oldCount = free_.size();
  std::size_t kept = 0;
  for (std::size_t i = 0; i < oldCount; ++i) {
    const Rect f = free_[i];
    if (!overlaps(f, r)) {
      free_[kept++] = f;
      continue;
    }
    if (r.y > f.y) free_.push_back({f.x, f.y, f.width, r.y - f.y});
    if (r.bottom() < f.bottom()) free_.push_back({f.x, r.bottom(), f.width, f.bottom() - r.bottom()});
    if (r.x > f.x) free_.push_back({f.x, f.y, r.x - f.x, f.height});
    if (r.right() < f.right()) free_.push_back({r.right(), f.y, f.right() - r.right(), f.height});
  }
  free_.erase(free_.begin() + static_cast<std::ptrdiff_t>(kept),
              free_.begin() + static_cast<std::ptrdiff_t>(oldCount));

  // Prune the new parts only, first among themselves (of two equal parts the first stays), then
  // against the old rectangles. The old rectangles were pairwise non-containing already, and none
  // can lie inside a new part: that part lies inside an old rectangle that did not contain them.
  const auto firstPart = free_.begin() + static_cast<std::ptrdiff_t>(kept);
  auto partsEnd = firstPart;
  for (auto it = firstPart; it != free_.end(); ++it) {
    const Rect part = *it;
    if (std::any_of(firstPart, partsEnd, [&](const Rect& f) { return contains(f, part); })) {
      continue;
    }
    partsEnd = std::remove_if(firstPart, partsEnd, [&](const Rect& f) { return contains(part, f); });
    *partsEnd++ = part;
  }
  const std::span<const Rect> oldRects(free_.data(), kept);
  partsEnd = std::remove_if(firstPart, partsEnd,
                            [&](const Rect& part) { return anyContains(oldRects, part); });
  free_.erase(partsEnd, free_.end());
  used_.push_back(r);
}

std::optional<Layout> pack(std::span<const Item> items, int binWidth, int binHeight,
                           const Options& options) {
  MaxRectsBin bin(binWidth, binHeight);
  LayoutBuilder layout(items.size(), options.maxBoundingArea);
  const Rect binRect{0, 0, binWidth, binHeight};
  for (const Rect& r : options.reserved) {
    if (!contains(binRect, r)) return std::nullopt;
    bin.occupy(r);
    if (!layout.add(r)) return std::nullopt;
  }

  std::vector<std::size_t> order = insertionOrder(items, options.regionLimitedFirst);
  if (options.mode == Mode::Online) {
    for (std::size_t index : order) {
      const std::optional<Rect> r = bin.insert(items[index], options.heuristic);
      if (!r || !layout.place(index, items[index].id, *r)) return std::nullopt;
    }
    return layout.take();
  }

  // Global: place the best-scoring (item, free rectangle) pair of all remaining items; ties go to
  // the item earliest in the online order. Free space only shrinks, so an item that fits nowhere
  // now never will.
  while (!order.empty()) {
    std::size_t bestSlot = 0;
    std::optional<std::pair<Rect, long long>> best;
    for (std::size_t slot = 0; slot < order.size(); ++slot) {
      const auto candidate = bin.score(items[order[slot]], options.heuristic);
      if (!candidate) return std::nullopt;
      if (!best || candidate->second < best->second) {
        best = candidate;
        bestSlot = slot;
      }
    }
    const std::size_t index = order[bestSlot];
    bin.occupy(best->first);
    if (!layout.place(index, items[index].id, best->first)) return std::nullopt;
    order.erase(order.begin() + static_cast<std::ptrdiff_t>(bestSlot));
  }
  return layout.take();
}

}  // namespace packer
