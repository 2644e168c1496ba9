// viewer/atlas_pages.hpp — HNIs streamed into atlas pages: square HniAtlas textures (4096 texels a
// side, or less where GL allows less), each with a MaxRects bin. An HNI goes to the first page
// with room for it; a new page opens when none has, up to a limit that bounds the texture memory.
#pragma once

#include <cstddef>
#include <vector>

#include <glm/vec2.hpp>

#include <packer/maxrects.hpp>

#include <nut/error.hpp>
#include <nut/image.hpp>

#include <viewer/hni_renderer.hpp>

namespace nut::viewer {

struct AtlasSlot {
  int page = 0;
  glm::ivec2 origin{0};
};

class AtlasPages {
 public:
  // Pages of pageSize^2 texels (clamped to GL_MAX_TEXTURE_SIZE), at most maxPages of them.
  AtlasPages(const Gl& gl, int pageSize, int maxPages);

  // Whether place() would find room: in an open page, or by opening one.
  bool fits(const Image& hni) const;
  // Uploads a valid HNI into a page. Errors: larger than a page; every page full and the limit
  // reached; a GL error.
  Result<AtlasSlot> place(const Image& hni);
  // Empties a page for reuse: what it held must no longer be drawn.
  void clear(int page);

  int pageCount() const { return static_cast<int>(pages_.size()); }
  int pageSize() const { return pageSize_; }
  const HniAtlas& page(int i) const { return pages_[static_cast<std::size_t>(i)].atlas; }
  // Texture memory of the open pages (4 bytes a texel).
  std::size_t bytes() const;

 private:
  struct Page {
    HniAtlas atlas;
    packer::MaxRectsBin bin;
  };
  const Gl* gl_;
  int pageSize_, maxPages_;
  std::vector<Page> pages_;
};

}  // namespace nut::viewer
