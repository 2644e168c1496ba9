// The packet caster, HniRayCaster::traceMany (raycast.hpp): the one-ray walk of ray_walk.hpp run
// on SIMD lanes, one ray per lane, with Google Highway (compiled for each x86 target, the widest
// the CPU has chosen at run time: 16 lanes with AVX-512, 8 with AVX2).
//
// Each lane keeps its ray's top stack level in the arrays of Lanes (one array per field, so that
// a field of every lane is one vector), with the constants of that level's block, and the levels
// below it in the ray's own Walk, in trace()'s layout. A pass over the lanes is one iteration of
// Walk::walkFrom for each: the lanes whose cell is empty step out of it on the vector unit
// (returning to parent levels as they leave them); those whose cell is a redirection land in its
// sub-block through the Walk's own descend(), one lane at a time (a landing reads a dozen tables
// per axis, which gathers pay more for than a lane does); and those that meet anything else are
// handed to their Walk, which finishes the ray from where it stands. A lane whose ray ends takes
// the next ray.
//
// Every lane computes what the one-ray walk computes, with the same float operations in the same
// order (no fused multiply-add: both files build with -ffp-contract=off), and mirrors std::min,
// std::max and argMin's choices on ties, so the results are the one-ray walk's to the bit. Lanes
// out of the current step compute too, but every gather index they use is masked to 0.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "raycast_packet.cpp"
// SSSE3 and SSE4 add nothing here over the baseline that AVX2 does not: fewer targets, a faster build.
#ifndef HWY_DISABLED_TARGETS
#define HWY_DISABLED_TARGETS (HWY_SSSE3 | HWY_SSE4)
#endif
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include <array>
#include <cstdint>
#include <limits>
#include <memory>
#include <optional>

#include <nut/raycast.hpp>

#include "ray_packets.hpp"

HWY_BEFORE_NAMESPACE();
namespace nut {
namespace HWY_NAMESPACE {
namespace {

namespace hn = hwy::HWY_NAMESPACE;

using DF = hn::ScalableTag<float>;
using DI = hn::RebindToSigned<DF>;
using VF = hn::Vec<DF>;
using VI = hn::Vec<DI>;
using MF = hn::Mask<DF>;
using MI = hn::Mask<DI>;

constexpr std::size_t kMaxLanes = HWY_MAX_BYTES / sizeof(float);

// std::min(a, b) and std::max(a, b) as the one-ray walk evaluates them: b < a ? b : a, a < b ? b : a.
VF stdMin(VF a, VF b) { return hn::IfThenElse(hn::Lt(b, a), b, a); }
VF stdMax(VF a, VF b) { return hn::IfThenElse(hn::Lt(a, b), b, a); }

MI toInt(MF m) { return hn::RebindMask(DI(), m); }
MF toFloat(MI m) { return hn::RebindMask(DF(), m); }

// Gathers base[index] where `valid`, base[0] elsewhere (never out of bounds).
VI gather(const std::int32_t* base, MI valid, VI index) {
  return hn::GatherIndex(DI(), base, hn::IfThenElseZero(valid, index));
}
VF gather(const float* base, MI valid, VI index) {
  return hn::GatherIndex(DF(), base, hn::IfThenElseZero(valid, index));
}

// The ray parameter where the ray leaves [lo, hi] (shifted by tile) along one axis: exitParameter.
VF exitParameter(VF tile, VF lo, VF hi, VF o, VF d, VF invD) {
  const VF zero = hn::Zero(DF());
  const VF up = hn::Mul(hn::Sub(hn::Add(tile, hi), o), invD);
  const VF down = hn::Mul(hn::Sub(hn::Add(tile, lo), o), invD);
  return hn::IfThenElse(hn::Gt(d, zero), up,
                        hn::IfThenElse(hn::Lt(d, zero), down, hn::Set(DF(), std::numeric_limits<float>::infinity())));
}

// The per-lane state: each lane's top level, as Level holds it, one array per field.
struct alignas(64) Lanes {
  float o[3][kMaxLanes], d[3][kMaxLanes], invD[3][kMaxLanes], tile[3][kMaxLanes];
  float lo[3][kMaxLanes], hi[3][kMaxLanes], tNext[3][kMaxLanes];
  float tExit[kMaxLanes], tStepLimit[kMaxLanes], t[kMaxLanes];
  std::int32_t cell[3][kMaxLanes], block[kMaxLanes], wrap[kMaxLanes], entryAxis[kMaxLanes];
  std::int32_t top[kMaxLanes], iterations[kMaxLanes], busy[kMaxLanes];
  // The block's constants, copied when the lane enters the level.
  float size[3][kMaxLanes];
  std::int32_t cells[3][kMaxLanes], boundsStart[3][kMaxLanes], bottomPixel[kMaxLanes], cellsX[kMaxLanes];
};

template <Lookup mode>
class PacketWalk {
 public:
  using Walk = RayPackets::Walk<mode>;

  explicit PacketWalk(const RayPacketJob& job)
      : job_(job),
        tables_(RayPackets::tables(*job.caster)),
        options_(*job.options),
        lanes_(hn::Lanes(DF())),
        bounds_((mode == Lookup::Exact ? tables_.exactBounds : tables_.heuristicBounds).data()),
        lod_(options_.lodAuto || options_.lodPx > 0) {}

  void run() {
    for (std::size_t lane = 0; lane < lanes_; ++lane) takeNextRay(lane);
    while (true) {
      std::size_t busy = 0;
      for (std::size_t lane = 0; lane < lanes_; ++lane) busy += s_.busy[lane] != 0;
      if (busy == 0) return;
      // The last rays, too few to fill the lanes, go on one at a time.
      if (next_ == job_.count && busy * 4 <= lanes_) {
        for (std::size_t lane = 0; lane < lanes_; ++lane)
          if (s_.busy[lane]) handOver(lane, s_.iterations[lane]);
        return;
      }
      iterate();
    }
  }

 private:
  // Starts the lane on the next ray, or leaves it idle when none is left. A ray that misses the
  // root box ends at once (background, 0 iterations), and the lane takes the one after it.
  void takeNextRay(std::size_t lane) {
    s_.busy[lane] = 0;
    while (next_ < job_.count) {
      const std::size_t ray = next_++;
      ray_[lane] = ray;
      job_.results[ray] = RayResult{};
      Walk& walk =
          walks_[lane].emplace(*job_.caster, job_.directions[ray], job_.pixelAngle, options_, job_.results[ray]);
      const float t = walk.enterRoot(job_.origins[job_.oneOrigin ? 0 : ray]);
      if (t < 0) continue;
      load(lane, walk.stack()[0]);
      s_.t[lane] = t;
      s_.top[lane] = 0;
      s_.iterations[lane] = 0;
      s_.busy[lane] = 1;
      return;
    }
  }

  // The lane's ray goes on in its Walk from the lane's state, after `iterations` iterations.
  void handOver(std::size_t lane, int iterations) {
    Walk& walk = *walks_[lane];
    store(lane, walk.stack()[s_.top[lane]]);
    walk.resume(s_.t[lane], s_.top[lane], iterations);
    takeNextRay(lane);
  }

  void store(std::size_t lane, Level& L) const {
    L.block = s_.block[lane];
    for (std::size_t a = 0; a < 3; ++a) {
      L.o[a] = s_.o[a][lane], L.d[a] = s_.d[a][lane], L.invD[a] = s_.invD[a][lane];
      L.tile[a] = s_.tile[a][lane], L.lo[a] = s_.lo[a][lane], L.hi[a] = s_.hi[a][lane];
      L.tNext[a] = s_.tNext[a][lane], L.cell[a] = s_.cell[a][lane];
    }
    L.wrap = static_cast<std::uint8_t>(s_.wrap[lane]);
    L.tExit = s_.tExit[lane], L.tStepLimit = s_.tStepLimit[lane];
    L.entryAxis = s_.entryAxis[lane];
  }
  void load(std::size_t lane, const Level& L) {
    s_.block[lane] = L.block;
    for (std::size_t a = 0; a < 3; ++a) {
      s_.o[a][lane] = L.o[a], s_.d[a][lane] = L.d[a], s_.invD[a][lane] = L.invD[a];
      s_.tile[a][lane] = L.tile[a], s_.lo[a][lane] = L.lo[a], s_.hi[a][lane] = L.hi[a];
      s_.tNext[a][lane] = L.tNext[a], s_.cell[a][lane] = L.cell[a];
    }
    s_.wrap[lane] = L.wrap;
    s_.tExit[lane] = L.tExit, s_.tStepLimit[lane] = L.tStepLimit;
    s_.entryAxis[lane] = L.entryAxis;
    const std::size_t b = static_cast<std::size_t>(L.block);
    for (std::size_t a = 0; a < 3; ++a) {
      s_.size[a][lane] = tables_.size[3 * b + a];
      s_.cells[a][lane] = tables_.cells[3 * b + a];
      s_.boundsStart[a][lane] = tables_.boundsStart[3 * b + a];
    }
    s_.bottomPixel[lane] = tables_.bottomPixel[b];
    s_.cellsX[lane] = tables_.cellsX[b];
  }

  // argMin of the lanes' tNext, and the smallest tNext.
  void nearestExit(VI& axis, VF& tMin) const {
    const DF df;
    const DI di;
    const VF t0 = hn::Load(df, s_.tNext[0]), t1 = hn::Load(df, s_.tNext[1]), t2 = hn::Load(df, s_.tNext[2]);
    const MF le01 = hn::Le(t0, t1), le02 = hn::Le(t0, t2), le12 = hn::Le(t1, t2);
    axis = hn::IfThenElse(toInt(le01), hn::IfThenElse(toInt(le02), hn::Zero(di), hn::Set(di, 2)),
                          hn::IfThenElse(toInt(le12), hn::Set(di, 1), hn::Set(di, 2)));
    tMin = hn::IfThenElse(le01, hn::IfThenElse(le02, t0, t2), hn::IfThenElse(le12, t1, t2));
  }

  // One iteration of Walk::walkFrom on every busy lane.
  void iterate() {
    const DF df;
    const DI di;
    const VI one = hn::Set(di, 1);
    const MI busy = hn::Ne(hn::Load(di, s_.busy), hn::Zero(di));
    const VI iterationsBefore = hn::Load(di, s_.iterations);
    const VI iterations = hn::Add(iterationsBefore, hn::IfThenElseZero(busy, one));
    hn::Store(iterations, di, s_.iterations);
    MI handing = hn::And(busy, hn::Gt(iterations, hn::Set(di, options_.maxIterations)));

    // The current cell's texel, where the ray enters it (tCellExit > t).
    VI axis;
    VF tMin;
    nearestExit(axis, tMin);
    const VF t = hn::Load(df, s_.t), tExit = hn::Load(df, s_.tExit);
    const VF tCellExit = stdMin(tMin, tExit);
    const MI inside = hn::And(busy, toInt(hn::Gt(tCellExit, t)));
    const VI cell[3] = {hn::Load(di, s_.cell[0]), hn::Load(di, s_.cell[1]), hn::Load(di, s_.cell[2])};
    const VI texelIndex =
        hn::Sub(hn::Add(hn::Add(hn::Load(di, s_.bottomPixel), cell[0]), hn::Mul(cell[2], hn::Load(di, s_.cellsX))),
                hn::Mul(hn::Set(di, tables_.rowPixels), cell[1]));
    const VI texel = gather(tables_.pixels, inside, texelIndex);
    const VI kind = hn::IfThenElseZero(inside, hn::And(hn::ShiftRight<24>(texel), hn::Set(di, 0xff)));
    const MI active = hn::AndNot(handing, busy);
    const MI empty = hn::And(active, hn::Eq(kind, hn::Set(di, format::kCellEmpty)));
    MI redirect = hn::And(active, hn::Eq(kind, hn::Set(di, format::kCellRedirection)));
    handing = hn::Or(handing, hn::AndNot(hn::Or(empty, redirect), active));

    // Redirections: those the one-ray walk draws as a summary are handed over; the others land.
    MI summary = hn::And(redirect, hn::Eq(hn::Add(hn::Load(di, s_.top), one), hn::Set(di, kMaxStackDepth)));
    if (lod_) summary = hn::Or(summary, hn::And(redirect, summaryStandsIn(redirect, texel, t)));
    handing = hn::Or(handing, summary);
    redirect = hn::AndNot(summary, redirect);
    MI leave = empty;
    if (!hn::AllFalse(di, redirect)) leave = hn::Or(leave, descend(redirect, texelIndex, tCellExit));

    if (!hn::AllFalse(di, leave)) leaveCells(leave);
    if (!hn::AllFalse(di, handing)) {
      alignas(64) std::int32_t handed[kMaxLanes] = {}, before[kMaxLanes] = {};
      hn::Store(hn::VecFromMask(di, handing), di, handed);
      hn::Store(iterationsBefore, di, before);
      for (std::size_t lane = 0; lane < lanes_; ++lane)
        if (handed[lane]) handOver(lane, before[lane]);
    }
  }

  // Walk::summaryStandsIn on the lanes, whose cells are redirections (texel).
  MI summaryStandsIn(MI valid, VI texel, VF t) const {
    const DF df;
    const VF pixelSpan = hn::Mul(stdMax(t, hn::Set(df, 1.0f)), hn::Set(df, static_cast<float>(job_.pixelAngle)));
    MF stands = hn::FirstN(df, 0);
    if (options_.lodAuto) {
      const VF footprint = gather(tables_.lodFootprintByRecord.data(), valid, hn::And(texel, hn::Set(DI(), 0xffff)));
      stands = hn::And(hn::Gt(footprint, hn::Zero(df)), hn::Gt(pixelSpan, footprint));
    }
    if (options_.lodPx > 0) {
      VF cellSize = hn::Zero(df);
      for (int a = 0; a < 3; ++a) {
        const VF extent = hn::Sub(hn::Load(df, s_.hi[a]), hn::Load(df, s_.lo[a]));
        cellSize = a == 0 ? extent : hn::Max(cellSize, extent);
      }
      stands = hn::Or(stands, hn::Lt(cellSize, hn::Mul(hn::Set(df, static_cast<float>(options_.lodPx)), pixelSpan)));
    }
    return toInt(stands);
  }

  // Walk::descend on the lanes of `landing`, one at a time: a lane that lands goes on in the
  // sub-block. Returns the lanes whose sub-block does not reach into [t, tCellExit]: they leave
  // the cell.
  MI descend(MI landing, VI texelIndex, VF tCellExit) {
    const DI di;
    alignas(64) std::int32_t lanes[kMaxLanes] = {}, texels[kMaxLanes] = {};
    alignas(64) float exits[kMaxLanes] = {};
    hn::Store(hn::VecFromMask(di, landing), di, lanes);
    hn::Store(texelIndex, di, texels);
    hn::Store(tCellExit, DF(), exits);
    for (std::size_t lane = 0; lane < lanes_; ++lane) {
      if (!lanes[lane]) continue;
      Walk& walk = *walks_[lane];
      const int top = s_.top[lane];
      store(lane, walk.stack()[top]);
      const auto* texel = reinterpret_cast<const std::uint8_t*>(tables_.pixels + texels[lane]);
      const float landed = walk.descendFrom(top, texel, s_.t[lane], exits[lane]);
      if (landed < 0) continue;  // leaves the cell
      load(lane, walk.stack()[top + 1]);
      s_.t[lane] = landed;
      s_.top[lane] = top + 1;
      lanes[lane] = 0;
    }
    return hn::Ne(hn::Load(di, lanes), hn::Zero(di));
  }

  // Walk::leaveCell on the lanes of `leaving`: each steps out of its cell through the nearest
  // boundary; a lane that leaves its level returns to the parent, which leaves its cell in turn,
  // and a lane that leaves the root ends on the background.
  void leaveCells(MI leaving) {
    const DF df;
    const DI di;
    const VF zero = hn::Zero(df);
    while (!hn::AllFalse(di, leaving)) {
      VI axis;
      VF tCross;
      nearestExit(axis, tCross);
      const MI inLevel = hn::And(leaving, toInt(hn::Lt(tCross, hn::Load(df, s_.tStepLimit))));
      const VI wrap = hn::Load(di, s_.wrap);
      MI stepped = hn::FirstN(di, 0);
      for (int a = 0; a < 3; ++a) {
        const MI along = hn::And(inLevel, hn::Eq(axis, hn::Set(di, a)));
        if (hn::AllFalse(di, along)) continue;
        const VF d = hn::Load(df, s_.d[a]);
        const MI up = toInt(hn::Gt(d, zero)), down = toInt(hn::Lt(d, zero));
        const VI cells = hn::Load(di, s_.cells[a]);
        VI cell = hn::Load(di, s_.cell[a]);
        cell = hn::Add(cell, hn::Sub(hn::IfThenElseZero(up, hn::Set(di, 1)), hn::IfThenElseZero(down, hn::Set(di, 1))));
        const MI wrapped = hn::Ne(hn::And(wrap, hn::Set(di, 1 << a)), hn::Zero(di));
        const MI over = hn::And(up, hn::Eq(cell, cells)), under = hn::And(down, hn::Lt(cell, hn::Zero(di)));
        const MI out = hn::AndNot(wrapped, hn::Or(over, under));
        const MI moved = hn::AndNot(out, along);
        const MI overWrapped = hn::And(over, wrapped), underWrapped = hn::And(under, wrapped);
        cell = hn::IfThenElse(overWrapped, hn::Zero(di),
                              hn::IfThenElse(underWrapped, hn::Sub(cells, hn::Set(di, 1)), cell));
        const VF size = hn::Load(df, s_.size[a]);
        VF tile = hn::Load(df, s_.tile[a]);
        tile = hn::IfThenElse(toFloat(overWrapped), hn::Add(tile, size),
                              hn::IfThenElse(toFloat(underWrapped), hn::Sub(tile, size), tile));
        const VI at = hn::Add(hn::Load(di, s_.boundsStart[a]), cell);
        const VF lo = gather(bounds_, moved, at), hi = gather(bounds_, moved, hn::Add(at, hn::Set(di, 1)));
        const VF tNext = exitParameter(tile, lo, hi, hn::Load(df, s_.o[a]), d, hn::Load(df, s_.invD[a]));
        const MF movedF = toFloat(moved);
        hn::Store(hn::IfThenElse(moved, cell, hn::Load(di, s_.cell[a])), di, s_.cell[a]);
        hn::Store(hn::IfThenElse(movedF, tile, hn::Load(df, s_.tile[a])), df, s_.tile[a]);
        hn::Store(hn::IfThenElse(movedF, lo, hn::Load(df, s_.lo[a])), df, s_.lo[a]);
        hn::Store(hn::IfThenElse(movedF, hi, hn::Load(df, s_.hi[a])), df, s_.hi[a]);
        hn::Store(hn::IfThenElse(movedF, tNext, hn::Load(df, s_.tNext[a])), df, s_.tNext[a]);
        hn::Store(hn::IfThenElse(moved, hn::Set(di, a), hn::Load(di, s_.entryAxis)), di, s_.entryAxis);
        stepped = hn::Or(stepped, moved);
      }
      const VF t = hn::Load(df, s_.t);
      hn::Store(hn::IfThenElse(toFloat(stepped), stdMax(t, tCross), t), df, s_.t);
      leaving = hn::AndNot(stepped, leaving);
      if (hn::AllFalse(di, leaving)) return;
      // The rest leave their level: the root's end on the background, the others return to the
      // parent at the level's exit.
      alignas(64) std::int32_t left[kMaxLanes] = {};
      hn::Store(hn::VecFromMask(di, leaving), di, left);
      for (std::size_t lane = 0; lane < lanes_; ++lane) {
        if (!left[lane]) continue;
        const int top = s_.top[lane];
        if (top == 0) {
          job_.results[ray_[lane]].iterations = s_.iterations[lane];
          takeNextRay(lane);
          left[lane] = 0;
          continue;
        }
        s_.t[lane] = s_.tExit[lane];
        s_.top[lane] = top - 1;
        load(lane, walks_[lane]->stack()[top - 1]);
      }
      leaving = hn::Ne(hn::Load(di, left), hn::Zero(di));
    }
  }

  const RayPacketJob& job_;
  const RayPacketTables& tables_;
  const RayCastOptions& options_;
  const std::size_t lanes_;
  const float* bounds_;
  const bool lod_;
  std::size_t next_ = 0;  // the next ray to start
  Lanes s_;
  std::array<std::optional<Walk>, kMaxLanes> walks_;  // each lane's ray: its levels below the top
  std::array<std::size_t, kMaxLanes> ray_;            // and its index
};

}  // namespace

void TracePackets(const RayPacketJob& job) {
  if (job.options->lookup == Lookup::Exact)
    std::make_unique<PacketWalk<Lookup::Exact>>(job)->run();
  else
    std::make_unique<PacketWalk<Lookup::Heuristic>>(job)->run();
}

}  // namespace HWY_NAMESPACE
}  // namespace nut
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace nut {

HWY_EXPORT(TracePackets);

RayPacketTables RayPackets::build(const HniRayCaster& caster) {
  RayPacketTables t;
  const std::uint8_t* base = caster.image_.pixels.data();
  t.pixels = reinterpret_cast<const std::int32_t*>(base);
  t.rowPixels = caster.image_.width;
  for (const HniRayCaster::Block& block : caster.blocks_) {
    t.bottomPixel.push_back(static_cast<std::int32_t>((block.bottomRow - base) / 4));
    t.cellsX.push_back(block.header.cells.x);
    for (std::size_t a = 0; a < 3; ++a) {
      t.size.push_back(block.axes[a].size);
      t.cells.push_back(block.axes[a].cells);
      t.boundsStart.push_back(static_cast<std::int32_t>(t.exactBounds.size()));
      t.heuristicBounds.insert(t.heuristicBounds.end(), block.heuristicBounds[a].begin(),
                               block.heuristicBounds[a].end());
      t.exactBounds.insert(t.exactBounds.end(), block.exactBounds[a].begin(), block.exactBounds[a].end());
    }
  }
  t.lodFootprintByRecord.assign(caster.redirectByRecord_.size(), 0.0f);
  for (std::size_t record = 0; record < caster.redirectByRecord_.size(); ++record)
    if (const int r = caster.redirectByRecord_[record]; r >= 0)
      t.lodFootprintByRecord[record] = caster.redirects_[static_cast<std::size_t>(r)].lodFootprint;
  return t;
}

void HniRayCaster::traceMany(std::span<const glm::dvec3> originsM, std::span<const glm::dvec3> directions,
                             double pixelAngle, const RayCastOptions& options, std::span<RayResult> results) const {
  if (directions.empty()) return;
  const RayPacketJob job{this,       originsM.data(), originsM.size() == 1, directions.data(), directions.size(),
                         pixelAngle, &options,        results.data()};
  HWY_DYNAMIC_DISPATCH(TracePackets)(job);
}

}  // namespace nut
#endif  // HWY_ONCE
