// Atlas pages for streamed HNIs (viewer/atlas_pages.hpp).
#include <viewer/atlas_pages.hpp>

#include <algorithm>
#include <string>

namespace nut::viewer {

AtlasPages::AtlasPages(const Gl& gl, int pageSize, int maxPages) : gl_(&gl), maxPages_(maxPages) {
  GLint maxSize = 0;
  gl.GetIntegerv(GL_MAX_TEXTURE_SIZE, &maxSize);
  pageSize_ = std::min(pageSize, static_cast<int>(maxSize));
}

Result<AtlasSlot> AtlasPages::place(const Image& hni) {
  if (hni.width > pageSize_ || hni.height > pageSize_)
    return Error{"a " + std::to_string(hni.width) + "x" + std::to_string(hni.height) + " HNI exceeds the " +
                 std::to_string(pageSize_) + "^2 atlas page"};
  // Bottom-left keeps each page's free space in few large rectangles as it fills.
  const packer::Item item{0, hni.width, hni.height};
  for (std::size_t p = 0; p < pages_.size(); ++p)
    if (const auto rect = pages_[p].bin.insert(item, packer::Heuristic::BottomLeft)) {
      if (Status s = pages_[p].atlas.put(hni, {rect->x, rect->y}); !s) return s.error();
      return AtlasSlot{static_cast<int>(p), {rect->x, rect->y}};
    }
  if (pageCount() >= maxPages_)
    return Error{"the atlas is full: " + std::to_string(maxPages_) + " pages of " + std::to_string(pageSize_) + "^2"};
  auto atlas = HniAtlas::create(*gl_, pageSize_, pageSize_);
  if (!atlas) return atlas.error();
  pages_.push_back({std::move(*atlas), packer::MaxRectsBin(pageSize_, pageSize_)});
  const auto rect = pages_.back().bin.insert(item, packer::Heuristic::BottomLeft);  // fits: checked above
  if (Status s = pages_.back().atlas.put(hni, {rect->x, rect->y}); !s) return s.error();
  return AtlasSlot{pageCount() - 1, {rect->x, rect->y}};
}

bool AtlasPages::fits(const Image& hni) const {
  if (hni.width > pageSize_ || hni.height > pageSize_) return false;
  if (pageCount() < maxPages_) return true;
  const packer::Item item{0, hni.width, hni.height};
  return std::any_of(pages_.begin(), pages_.end(),
                     [&](const Page& p) { return p.bin.score(item, packer::Heuristic::BottomLeft).has_value(); });
}

void AtlasPages::clear(int page) { pages_[static_cast<std::size_t>(page)].bin = packer::MaxRectsBin(pageSize_, pageSize_); }

std::size_t AtlasPages::bytes() const {
  return pages_.size() * static_cast<std::size_t>(pageSize_) * static_cast<std::size_t>(pageSize_) * 4;
}

}  // namespace nut::viewer
