// converter/blocks.hpp — block extraction and simplification (paper section 5, steps 2 and 3):
// a solid grid G0 becomes a hierarchy of blocks in which repeated parts (windows, bays, floors,
// balconies) are stored once and redirected to.
//
// The paper needs a person to select each block S_i. Here the search is automatic: along each axis
// of a block, runs of cells whose width pattern repeats (within the tolerance) and whose content
// repeats cell for cell are candidates; touching repeats merge into one redirection that tiles
// (wraps) the extracted block; a block may also be cut in two where the halves need fewer
// boundaries. A candidate is taken when it removes at least BlockOptions::minSavedCells cells (the
// converter builds several thresholds and keeps the smallest PNG), or with `priced` when the
// estimated PNG bytes of the parts go down. Simplification removes boundaries that only the
// extracted cells needed and merges the cells they separated. The search repeats on the simplified
// grid and inside each extracted block until nothing pays. `manual` boxes are extracted first, as
// the paper's user would.
#pragma once

#include <array>
#include <memory>
#include <vector>

#include <glm/vec3.hpp>

#include <nut/camera.hpp>
#include <nut/error.hpp>
#include <nut/hierarchy.hpp>
#include <nut/hni.hpp>

namespace nut::converter {

struct BlockOptions {
  bool automatic = true;
  bool cuts = true;              // also split blocks in two where the halves need fewer boundaries
  // World metres; each is snapped outwards to whole cells of G0 and simplified into block S. A
  // place of G0 matches when its cells group along each axis into runs whose widths sum to S's
  // cell widths within the tolerance (the paper's one-to-many matching; boundaries from elsewhere
  // may cut an instance) and every cell equals the S cell it falls in.
  std::vector<WorldBox> manual;
  double toleranceM = 0.01;      // widths that match within this are equal
  // A repeat or split is taken only when it removes at least this many cells. A new block costs a
  // header, three metadata items and a record (about 100 bytes in a PNG) while a cell of a
  // repetitive grid deflates to a few hundredths of a byte, so the best threshold depends on the
  // building: the converter builds several and keeps the smallest PNG.
  long long minSavedCells = 32;
  // Choose in blocks of up to kMaxPricedCells cells whether to cut and where (every cut tried, and
  // the best repeat) by the estimated PNG bytes of the blocks that result: metadata pixels at the
  // format's rule, cells, records and headers (pngBytesEstimate). Larger blocks are cut as above.
  bool priced = false;
  // The compile option the priced search prices metadata items at (CompileOptions).
  double heuristicToleranceM = CompileOptions{}.heuristicToleranceM;
};

// A block's bytes in a PNG, estimated from `nut info --bytes` on the samples: about 30 for its
// header, 1.1 per metadata pixel (both rows, M at compile()'s rule with heuristicToleranceM), 0.05
// per cell and 4 per redirection record its cells use.
double pngBytesEstimate(const Block& b, double heuristicToleranceM);

struct ExtractedBlock {
  BlockId block = 0;
  std::array<int, 3> cells{};    // cells per axis of the extracted block
  glm::dvec3 sizeM{0.0};
  int instances = 0;             // places it shows up (each tiled run counts its repeats)
  std::array<bool, 3> wrap{};    // tiled along these axes
  bool manual = false;
  long long savedBytes = 0;      // estimated
};

struct BlockStats {
  std::vector<ExtractedBlock> found;
  long long cellsBefore = 0, cellsAfter = 0;   // all blocks
  long long bytesBefore = 0, bytesAfter = 0;   // estimated by the cost model
};

// Merges neighbouring layers that hold the same boxes and empty cells, or redirections that place
// the same block at the same place: their boundary is needed by nothing inside this block. buildHierarchy does it to every block; a caller building several
// hierarchies from one grid can do it once first.
void simplify(Block& b);

// Cells [lo, hi) of b as a block of its own: boundaries relative to its minimum corner, the
// redirections kept whole so that redirection cells keep their record indices.
Block subBlock(const Block& b, const std::array<int, 3>& lo, const std::array<int, 3>& hi);

// Raw bytes of a block in an HNI, roughly (4 per cell of a data component, 8 per metadata pixel at
// one pixel per cell, 48 per header, 16 per redirection record): the report's bytes before and
// after extraction.
long long estimatedBytes(const Block& b);

// The automatic search's first look at a grid: the repeat and the cut in two that remove the most
// cells. It is the same for every BlockOptions of one tolerance, so a caller building several
// hierarchies from one grid (the converter's variants) finds it once and passes it to each
// buildHierarchy; on the high-rise's 4.1 M cells it is most of a variant's search.
struct GridSearch;
std::shared_ptr<const GridSearch> searchGrid(const Block& grid, double toleranceM);

// Builds the hierarchy: the grid becomes the root with its world origin originM, and blocks are
// extracted from it as options say. Materials are passed through. The grid's redirection cells point
// into subBlocks (Redirection::target is an index there, SolidGrid::subBlocks), which are added
// first so that those indices are their block ids. `search`, when given, is searchGrid(grid,
// options.toleranceM).
Result<Hierarchy> buildHierarchy(const Block& grid, std::vector<Material> materials, const glm::dvec3& originM,
                                 const BlockOptions& options, BlockStats& stats, const std::vector<Block>& subBlocks = {},
                                 const GridSearch* search = nullptr);

}  // namespace nut::converter
