// The packet caster, HniRayCaster::traceMany (raycast.hpp): the one-ray walk of ray_walk.hpp run
// on SIMD lanes, one ray per lane, with Google Highway (compiled for each x86 target, the widest
// the CPU has chosen at run time: 16 lanes with AVX-512, 8 with AVX2).
//
// The lanes' current levels are one LevelLanes (each field an array of lanes, so that a field of
// every lane is one vector), with the constants of each level's block; the levels below are
// LevelLanes too, one per depth, written and read back with masked vector stores and loads. A
// pass over the lanes is one iteration of Walk::walkFrom for each: the lanes whose cell is empty
// step out of it (returning to parent levels as they leave them), those whose cell is a
// redirection land in the sub-block, and those that meet anything else (a surface, a summary,
// the cap) are handed to the ray's one-ray Walk, given the lane's levels, which finishes the ray.
// A lane whose ray ends takes the next ray.
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
#include <vector>

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
MI noLanes() { return hn::FirstN(DI(), 0); }

// Gathers base[index] where `valid`, base[0] elsewhere (never out of bounds).
VI gather(const std::int32_t* base, MI valid, VI index) {
  return hn::GatherIndex(DI(), base, hn::IfThenElseZero(valid, index));
}
VF gather(const float* base, MI valid, VI index) {
  return hn::GatherIndex(DF(), base, hn::IfThenElseZero(valid, index));
}

// Where every lane reads the same entry of a table, that entry (kNone: the lanes read different ones).
constexpr std::size_t kNone = ~std::size_t{0};

// table[index] on the lanes of `valid`: broadcast from entry `shared` when it is not kNone (a
// gather costs far more than a broadcast), gathered otherwise.
VF perLane(const std::vector<float>& table, MI valid, VI index, std::size_t shared) {
  return shared != kNone ? hn::Set(DF(), table[shared]) : gather(table.data(), valid, index);
}
VI perLane(const std::vector<std::int32_t>& table, MI valid, VI index, std::size_t shared) {
  return shared != kNone ? hn::Set(DI(), table[shared]) : gather(table.data(), valid, index);
}
std::size_t axisOf(std::size_t block, int a) {
  return block == kNone ? kNone : 3 * block + static_cast<std::size_t>(a);
}

// The ray parameter where the ray leaves [lo, hi] (shifted by tile) along one axis: exitParameter.
VF exitParameter(VF tile, VF lo, VF hi, VF o, VF d, VF invD) {
  const VF zero = hn::Zero(DF());
  const VF up = hn::Mul(hn::Sub(hn::Add(tile, hi), o), invD);
  const VF down = hn::Mul(hn::Sub(hn::Add(tile, lo), o), invD);
  return hn::IfThenElse(hn::Gt(d, zero), up,
                        hn::IfThenElse(hn::Lt(d, zero), down, hn::Set(DF(), std::numeric_limits<float>::infinity())));
}

// The fields of a Level (ray_walk.hpp) with the constants of its block, for every lane: a float
// field x of axis a is f[kX + a], an int field i[kX + a].
enum FloatField {
  kO = 0,
  kD = 3,
  kInvD = 6,
  kTile = 9,
  kLo = 12,
  kHi = 15,
  kTNext = 18,
  kTExit = 21,
  kTStepLimit,
  kSize,
  kFloatFields = kSize + 3
};
enum IntField {
  kCell = 0,
  kBlock = 3,
  kWrap,
  kEntryAxis,
  kRedirect,
  kCells,
  kBoundsStart = kCells + 3,
  kBottomPixel = kBoundsStart + 3,
  kCellsX,
  kIntFields
};
struct alignas(64) LevelLanes {
  float f[kFloatFields][kMaxLanes];
  std::int32_t i[kIntFields][kMaxLanes];
};

// A landing computed on the lanes (land() of ray_walk.hpp): the child level's fields.
struct Landing {
  MI ok;
  VF t0, tExit, tStepLimit;
  VI entryAxis;
  VF tile[3], lo[3], hi[3], tNext[3];
  VI cell[3];
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
      for (std::size_t lane = 0; lane < lanes_; ++lane) busy += busy_[lane] != 0;
      if (busy == 0) return;
      // The last rays, too few to fill the lanes, go on one at a time.
      if (next_ == job_.count && busy * 4 <= lanes_) {
        for (std::size_t lane = 0; lane < lanes_; ++lane)
          if (busy_[lane]) handOver(lane, iterations_[lane]);
        return;
      }
      iterate();
    }
  }

 private:
  VF F(int field) const { return hn::Load(DF(), cur_.f[field]); }
  VI I(int field) const { return hn::Load(DI(), cur_.i[field]); }
  void setF(int field, MI where, VF value) {
    hn::Store(hn::IfThenElse(toFloat(where), value, F(field)), DF(), cur_.f[field]);
  }
  void setI(int field, MI where, VI value) { hn::Store(hn::IfThenElse(where, value, I(field)), DI(), cur_.i[field]); }

  // Starts the lane on the next ray, or leaves it idle when none is left. A ray that misses the
  // root box ends at once (background, 0 iterations), and the lane takes the one after it.
  void takeNextRay(std::size_t lane) {
    busy_[lane] = 0;
    while (next_ < job_.count) {
      const std::size_t ray = next_++;
      ray_[lane] = ray;
      job_.results[ray] = RayResult{};
      Walk& walk =
          walks_[lane].emplace(*job_.caster, job_.directions[ray], job_.pixelAngle, options_, job_.results[ray]);
      const float t = walk.enterRoot(job_.origins[job_.oneOrigin ? 0 : ray]);
      if (t < 0) continue;
      const Level& L = walk.stack()[0];
      for (int a = 0; a < 3; ++a) {
        const std::size_t k = static_cast<std::size_t>(a);
        cur_.f[kO + a][lane] = L.o[k], cur_.f[kD + a][lane] = L.d[k], cur_.f[kInvD + a][lane] = L.invD[k];
        cur_.f[kTile + a][lane] = L.tile[k], cur_.f[kLo + a][lane] = L.lo[k], cur_.f[kHi + a][lane] = L.hi[k];
        cur_.f[kTNext + a][lane] = L.tNext[k], cur_.i[kCell + a][lane] = L.cell[k];
        const std::size_t axis = 3 * static_cast<std::size_t>(L.block) + k;
        cur_.f[kSize + a][lane] = tables_.size[axis];
        cur_.i[kCells + a][lane] = tables_.cells[axis];
        cur_.i[kBoundsStart + a][lane] = tables_.boundsStart[axis];
      }
      cur_.f[kTExit][lane] = L.tExit, cur_.f[kTStepLimit][lane] = L.tStepLimit;
      cur_.i[kBlock][lane] = L.block, cur_.i[kWrap][lane] = L.wrap, cur_.i[kEntryAxis][lane] = L.entryAxis;
      cur_.i[kRedirect][lane] = -1;
      cur_.i[kBottomPixel][lane] = tables_.bottomPixel[static_cast<std::size_t>(L.block)];
      cur_.i[kCellsX][lane] = tables_.cellsX[static_cast<std::size_t>(L.block)];
      t_[lane] = t;
      top_[lane] = 0;
      iterations_[lane] = 0;
      busy_[lane] = 1;
      return;
    }
  }

  // The lane's ray goes on in its Walk, given the lane's levels, after `iterations` iterations.
  void handOver(std::size_t lane, int iterations) {
    Walk& walk = *walks_[lane];
    Level* stack = walk.stack();
    const int top = top_[lane];
    for (int k = 0; k <= top; ++k) {
      const LevelLanes& from = k == top ? cur_ : saved_[static_cast<std::size_t>(k)];
      Level& L = stack[k];
      for (int a = 0; a < 3; ++a) {
        const std::size_t c = static_cast<std::size_t>(a);
        L.o[c] = from.f[kO + a][lane], L.d[c] = from.f[kD + a][lane], L.invD[c] = from.f[kInvD + a][lane];
        L.tile[c] = from.f[kTile + a][lane], L.lo[c] = from.f[kLo + a][lane], L.hi[c] = from.f[kHi + a][lane];
        L.tNext[c] = from.f[kTNext + a][lane], L.cell[c] = from.i[kCell + a][lane];
      }
      L.tExit = from.f[kTExit][lane], L.tStepLimit = from.f[kTStepLimit][lane];
      L.block = from.i[kBlock][lane], L.wrap = static_cast<std::uint8_t>(from.i[kWrap][lane]);
      L.entryAxis = from.i[kEntryAxis][lane];
      // Level 0's rotation to the world is enterRoot()'s; each level's below it, descend()'s.
      if (k == 0) continue;
      const std::size_t r = static_cast<std::size_t>(from.i[kRedirect][lane]);
      L.toWorld = tables_.unrotated[r] ? stack[k - 1].toWorld : stack[k - 1].toWorld * tables_.rotation[r];
    }
    walk.resume(t_[lane], top, iterations);
    takeNextRay(lane);
  }

  // argMin of the lanes' tNext, and the smallest tNext.
  void nearestExit(VI& axis, VF& tMin) const {
    const DI di;
    const VF t0 = F(kTNext), t1 = F(kTNext + 1), t2 = F(kTNext + 2);
    const MF le01 = hn::Le(t0, t1), le02 = hn::Le(t0, t2), le12 = hn::Le(t1, t2);
    axis = hn::IfThenElse(toInt(le01), hn::IfThenElse(toInt(le02), hn::Zero(di), hn::Set(di, 2)),
                          hn::IfThenElse(toInt(le12), hn::Set(di, 1), hn::Set(di, 2)));
    tMin = hn::IfThenElse(le01, hn::IfThenElse(le02, t0, t2), hn::IfThenElse(le12, t1, t2));
  }

  // The distinct depths of the lanes of `lanes`, for the masked stores of their levels.
  template <typename PerDepth>
  void forEachDepth(MI lanes, const PerDepth& perDepth) const {
    const DI di;
    const VI top = hn::Load(di, top_);
    while (!hn::AllFalse(di, lanes)) {
      alignas(64) std::int32_t tops[kMaxLanes] = {};
      hn::Store(hn::IfThenElse(lanes, top, hn::Set(di, -1)), di, tops);
      std::int32_t depth = -1;
      for (std::size_t lane = 0; lane < lanes_ && depth < 0; ++lane) depth = tops[lane];
      const MI atDepth = hn::And(lanes, hn::Eq(top, hn::Set(di, depth)));
      perDepth(atDepth, static_cast<std::size_t>(depth));
      lanes = hn::AndNot(atDepth, lanes);
    }
  }

  // The cell of each lane holding in-tile coordinate x along axis index axisIndex (3 block + a):
  // AxisView::cellExact or cellHeuristic.
  // shared: the axis every lane reads, or kNone.
  VI cellOf(MI valid, VI axisIndex, std::size_t shared, VF x) const {
    const DF df;
    const DI di;
    const VF zero = hn::Zero(df);
    const VI metaPixel = perLane(tables_.metaPixel, valid, axisIndex, shared);
    if constexpr (mode == Lookup::Exact) {
      const VF last = perLane(tables_.exactLast, valid, axisIndex, shared);
      const VF positive = hn::IfThenElse(hn::Lt(zero, x), x, zero);
      const VF c = hn::IfThenElse(hn::Lt(positive, last), positive, last);
      const VI k = hn::ConvertTo(di, hn::Mul(c, perLane(tables_.scale, valid, axisIndex, shared)));
      const VI e = gather(tables_.pixels, valid, hn::Add(perLane(tables_.exactPixel, valid, axisIndex, shared), k));
      const VI first = hn::And(gather(tables_.pixels, valid, hn::Add(metaPixel, k)), hn::Set(di, 0xff));
      // e - 1 < trunc(c), unsigned: both sides with the sign bit flipped, compared signed.
      const VI flip = hn::Set(di, std::numeric_limits<std::int32_t>::min());
      const MI beyond = hn::Lt(hn::Xor(hn::Sub(e, hn::Set(di, 1)), flip), hn::Xor(hn::ConvertTo(di, c), flip));
      return hn::Add(first, hn::IfThenElseZero(beyond, hn::Set(di, 1)));
    } else {
      const VF steps = hn::Mul(x, perLane(tables_.stepScale, valid, axisIndex, shared));
      const VF positive = hn::IfThenElse(hn::Lt(zero, steps), steps, zero);
      const VF last = perLane(tables_.lastStep, valid, axisIndex, shared);
      const VI q = hn::ConvertTo(di, hn::IfThenElse(hn::Lt(positive, last), positive, last));
      const VI word = gather(tables_.pixels, valid, hn::Add(metaPixel, hn::ShiftRight<8>(q)));
      const VI byte = hn::Set(di, 0xff);
      const VI first = hn::And(word, byte);
      const VI fMinus1 = hn::And(hn::Sub(hn::And(hn::ShiftRight<8>(word), byte), hn::Set(di, 1)), byte);
      return hn::Add(first, hn::IfThenElseZero(hn::Gt(hn::And(q, byte), fMinus1), hn::Set(di, 1)));
    }
  }

  // land() of ray_walk.hpp on the lanes of `valid`: the child level of block `block` (wrap bits
  // `wrap`; sharedBlock: the block of every lane, or kNone) holding the ray o + t d, clipped to
  // [tStart, tLimit].
  Landing land(MI valid, VI block, std::size_t sharedBlock, VI wrap, const VF (&o)[3], const VF (&d)[3],
               const VF (&invD)[3], VF tStart, VF tLimit) const {
    const DF df;
    const DI di;
    const VF zero = hn::Zero(df);
    Landing out;
    VF t0 = tStart, t1 = tLimit;
    VI entry = hn::Set(di, -1);
    MI miss = hn::Not(valid);
    VI axisIndex[3];
    VF size[3];
    MI wrapped[3];
    for (int a = 0; a < 3; ++a) {
      axisIndex[a] = hn::Add(hn::Mul(block, hn::Set(di, 3)), hn::Set(di, a));
      size[a] = perLane(tables_.size, valid, axisIndex[a], axisOf(sharedBlock, a));
      wrapped[a] = hn::Ne(hn::And(wrap, hn::Set(di, 1 << a)), hn::Zero(di));
      const MF clipped = toFloat(hn::Not(wrapped[a]));
      const MF still = hn::Eq(d[a], zero);
      miss = hn::Or(miss, toInt(hn::And(hn::And(clipped, still), hn::Or(hn::Lt(o[a], zero), hn::Gt(o[a], size[a])))));
      const VF ta = hn::Mul(hn::Neg(o[a]), invD[a]), tb = hn::Mul(hn::Sub(size[a], o[a]), invD[a]);
      const MF swap = hn::Gt(ta, tb);
      const VF near = hn::IfThenElse(swap, tb, ta), far = hn::IfThenElse(swap, ta, tb);
      const MF moving = hn::AndNot(still, clipped);
      const MF later = hn::And(moving, hn::Gt(near, t0));
      t0 = hn::IfThenElse(later, near, t0);
      entry = hn::IfThenElse(toInt(later), hn::Set(di, a), entry);
      t1 = hn::IfThenElse(hn::And(moving, hn::Lt(far, t1)), far, t1);
    }
    out.ok = hn::AndNot(miss, toInt(hn::Lt(t0, t1)));
    if (hn::AllFalse(di, out.ok)) return out;
    out.t0 = t0;
    out.tExit = t1;
    out.entryAxis = entry;
    const VF reach = hn::Max(hn::Max(hn::Abs(o[0]), hn::Abs(o[1])), hn::Abs(o[2]));
    const VF ulps = hn::Set(df, 4.0f * std::numeric_limits<float>::epsilon());
    const VF half = hn::Mul(hn::Set(df, 0.5f), hn::Sub(t1, t0));
    const VF tProbe = hn::Add(t0, stdMin(hn::Mul(ulps, hn::Add(hn::Abs(t0), reach)), half));
    out.tStepLimit = hn::Sub(t1, stdMin(hn::Mul(ulps, hn::Add(hn::Abs(t1), reach)), half));
    for (int a = 0; a < 3; ++a) {
      VF x = hn::Add(o[a], hn::Mul(tProbe, d[a]));
      out.tile[a] = hn::IfThenElseZero(toFloat(wrapped[a]), hn::Mul(hn::Floor(hn::Div(x, size[a])), size[a]));
      x = hn::Sub(x, out.tile[a]);
      out.cell[a] = cellOf(out.ok, axisIndex[a], axisOf(sharedBlock, a), x);
      const VI at = hn::Add(perLane(tables_.boundsStart, out.ok, axisIndex[a], axisOf(sharedBlock, a)), out.cell[a]);
      out.lo[a] = gather(bounds_, out.ok, at);
      out.hi[a] = gather(bounds_, out.ok, hn::Add(at, hn::Set(di, 1)));
      out.tNext[a] = exitParameter(out.tile[a], out.lo[a], out.hi[a], o[a], d[a], invD[a]);
    }
    return out;
  }

  // One iteration of Walk::walkFrom on every busy lane.
  void iterate() {
    const DF df;
    const DI di;
    const VI one = hn::Set(di, 1);
    const MI busy = hn::Ne(hn::Load(di, busy_), hn::Zero(di));
    const VI iterationsBefore = hn::Load(di, iterations_);
    const VI iterations = hn::Add(iterationsBefore, hn::IfThenElseZero(busy, one));
    hn::Store(iterations, di, iterations_);
    MI handing = hn::And(busy, hn::Gt(iterations, hn::Set(di, options_.maxIterations)));

    // The current cell's texel, where the ray enters it (tCellExit > t).
    VI axis;
    VF tMin;
    nearestExit(axis, tMin);
    const VF t = hn::Load(df, t_);
    const VF tCellExit = stdMin(tMin, F(kTExit));
    const MI inside = hn::And(busy, toInt(hn::Gt(tCellExit, t)));
    const VI texelIndex = hn::Sub(hn::Add(hn::Add(I(kBottomPixel), I(kCell)), hn::Mul(I(kCell + 2), I(kCellsX))),
                                  hn::Mul(hn::Set(di, tables_.rowPixels), I(kCell + 1)));
    const VI texel = gather(tables_.pixels, inside, texelIndex);
    const VI kind = hn::IfThenElseZero(inside, hn::And(hn::ShiftRight<24>(texel), hn::Set(di, 0xff)));
    const MI active = hn::AndNot(handing, busy);
    const MI empty = hn::And(active, hn::Eq(kind, hn::Set(di, format::kCellEmpty)));
    MI redirect = hn::And(active, hn::Eq(kind, hn::Set(di, format::kCellRedirection)));
    handing = hn::Or(handing, hn::AndNot(hn::Or(empty, redirect), active));

    // Redirections: those the one-ray walk draws as a summary are handed over; the others land.
    MI leave = empty;
    if (!hn::AllFalse(di, redirect)) {
      const VI record = gather(tables_.redirectByRecord.data(), redirect, hn::And(texel, hn::Set(di, 0xffff)));
      MI summary = hn::Eq(hn::Add(hn::Load(di, top_), one), hn::Set(di, kMaxStackDepth));
      if (lod_) summary = hn::Or(summary, summaryStandsIn(redirect, record, t));
      summary = hn::And(summary, redirect);
      handing = hn::Or(handing, summary);
      redirect = hn::AndNot(summary, redirect);
      if (!hn::AllFalse(di, redirect)) leave = hn::Or(leave, descend(redirect, record, t, tCellExit));
    }
    if (!hn::AllFalse(di, leave)) leaveCells(leave);
    if (!hn::AllFalse(di, handing)) {
      alignas(64) std::int32_t handed[kMaxLanes] = {}, before[kMaxLanes] = {};
      hn::Store(hn::VecFromMask(di, handing), di, handed);
      hn::Store(iterationsBefore, di, before);
      for (std::size_t lane = 0; lane < lanes_; ++lane)
        if (handed[lane]) handOver(lane, before[lane]);
    }
  }

  // Walk::summaryStandsIn on the lanes.
  MI summaryStandsIn(MI valid, VI record, VF t) const {
    const DF df;
    const VF pixelSpan = hn::Mul(stdMax(t, hn::Set(df, 1.0f)), hn::Set(df, static_cast<float>(job_.pixelAngle)));
    MF stands = toFloat(noLanes());
    if (options_.lodAuto) {
      const VF footprint = gather(tables_.lodFootprint.data(), valid, record);
      stands = hn::And(hn::Gt(footprint, hn::Zero(df)), hn::Gt(pixelSpan, footprint));
    }
    if (options_.lodPx > 0) {
      const VF cellSize =
          hn::Max(hn::Max(hn::Sub(F(kHi), F(kLo)), hn::Sub(F(kHi + 1), F(kLo + 1))), hn::Sub(F(kHi + 2), F(kLo + 2)));
      stands = hn::Or(stands, hn::Lt(cellSize, hn::Mul(hn::Set(df, static_cast<float>(options_.lodPx)), pixelSpan)));
    }
    return toInt(stands);
  }

  // Walk::descend on the lanes of `valid`: lands in the record's sub-block; the lanes that land
  // push their level and go on in the child. Returns the lanes whose sub-block does not reach into
  // [t, tCellExit]: they leave the cell.
  MI descend(MI valid, VI record, VF t, VF tCellExit) {
    const DF df;
    const DI di;
    // Neighbouring rays mostly land in the same sub-block at once: then its record and block are
    // read once for all lanes.
    alignas(64) std::int32_t records[kMaxLanes] = {};
    hn::Store(hn::IfThenElse(valid, record, hn::Set(di, -1)), di, records);
    std::int32_t first = -1;
    for (std::size_t lane = 0; lane < lanes_ && first < 0; ++lane) first = records[lane];
    const bool shared = hn::AllTrue(di, hn::Or(hn::Not(valid), hn::Eq(record, hn::Set(di, first))));
    const std::size_t sharedRecord = shared ? static_cast<std::size_t>(first) : kNone;
    const std::size_t sharedBlock = shared ? static_cast<std::size_t>(tables_.target[sharedRecord]) : kNone;
    VF o[3], d[3], invD[3], inCell[3];
    for (int a = 0; a < 3; ++a) {
      inCell[a] = hn::Sub(hn::Sub(hn::Sub(F(kO + a), F(kTile + a)), F(kLo + a)),
                          perLane(tables_.offset[static_cast<std::size_t>(a)], valid, record, sharedRecord));
      o[a] = inCell[a];
      d[a] = F(kD + a);
      invD[a] = F(kInvD + a);
    }
    const MI unrotated = hn::Ne(perLane(tables_.unrotated, valid, record, sharedRecord), hn::Zero(di));
    if (!hn::AllTrue(di, hn::Or(unrotated, hn::Not(valid)))) {
      // toChild * v as glm computes it: row r is m[0][r] v.x + m[1][r] v.y + m[2][r] v.z.
      VF m[9];
      for (std::size_t k = 0; k < 9; ++k) m[k] = perLane(tables_.toChild[k], valid, record, sharedRecord);
      const auto turn = [&](const VF(&v)[3], int r) {
        return hn::Add(hn::Add(hn::Mul(m[r], v[0]), hn::Mul(m[3 + r], v[1])), hn::Mul(m[6 + r], v[2]));
      };
      const MF keep = toFloat(unrotated);
      const VF parentD[3] = {d[0], d[1], d[2]};
      for (int r = 0; r < 3; ++r) {
        const VF turnedD = turn(parentD, r);
        o[r] = hn::IfThenElse(keep, o[r], turn(inCell, r));
        d[r] = hn::IfThenElse(keep, d[r], turnedD);
        invD[r] = hn::IfThenElse(keep, invD[r], hn::Div(hn::Set(df, 1.0f), turnedD));
      }
    }
    const VI target = perLane(tables_.target, valid, record, sharedRecord);
    const VI wrap = perLane(tables_.wrap, valid, record, sharedRecord);
    const Landing child = land(valid, target, sharedBlock, wrap, o, d, invD, t, tCellExit);
    const MI landed = hn::And(valid, child.ok);
    if (hn::AllFalse(di, landed)) return valid;

    // Push: the landing lanes' levels are saved at their depths; the child replaces them.
    forEachDepth(landed, [&](MI atDepth, std::size_t depth) {
      LevelLanes& saved = saved_[depth];
      const MF atDepthF = toFloat(atDepth);
      for (int k = 0; k < kFloatFields; ++k) hn::BlendedStore(F(k), atDepthF, df, saved.f[k]);
      for (int k = 0; k < kIntFields; ++k) hn::BlendedStore(I(k), atDepth, di, saved.i[k]);
    });
    for (int a = 0; a < 3; ++a) {
      const VI axisIndex = hn::Add(hn::Mul(target, hn::Set(di, 3)), hn::Set(di, a));
      setF(kO + a, landed, o[a]), setF(kD + a, landed, d[a]), setF(kInvD + a, landed, invD[a]);
      setF(kTile + a, landed, child.tile[a]), setF(kLo + a, landed, child.lo[a]), setF(kHi + a, landed, child.hi[a]);
      setF(kTNext + a, landed, child.tNext[a]), setI(kCell + a, landed, child.cell[a]);
      setF(kSize + a, landed, perLane(tables_.size, landed, axisIndex, axisOf(sharedBlock, a)));
      setI(kCells + a, landed, perLane(tables_.cells, landed, axisIndex, axisOf(sharedBlock, a)));
      setI(kBoundsStart + a, landed, perLane(tables_.boundsStart, landed, axisIndex, axisOf(sharedBlock, a)));
    }
    setF(kTExit, landed, child.tExit), setF(kTStepLimit, landed, child.tStepLimit);
    setI(kBlock, landed, target), setI(kWrap, landed, wrap), setI(kEntryAxis, landed, child.entryAxis);
    setI(kRedirect, landed, record);
    setI(kBottomPixel, landed, perLane(tables_.bottomPixel, landed, target, sharedBlock));
    setI(kCellsX, landed, perLane(tables_.cellsX, landed, target, sharedBlock));
    hn::Store(hn::IfThenElse(toFloat(landed), child.t0, t), df, t_);
    hn::Store(hn::Add(hn::Load(di, top_), hn::IfThenElseZero(landed, hn::Set(di, 1))), di, top_);
    return hn::AndNot(landed, valid);
  }

  // Walk::leaveCell on the lanes of `leaving`: each steps out of its cell through the nearest
  // boundary; a lane that leaves its level returns to the parent, which leaves its cell in turn,
  // and a lane that leaves the root ends on the background.
  void leaveCells(MI leaving) {
    const DF df;
    const DI di;
    const VF zero = hn::Zero(df);
    while (true) {
      VI axis;
      VF tCross;
      nearestExit(axis, tCross);
      const MI inLevel = hn::And(leaving, toInt(hn::Lt(tCross, F(kTStepLimit))));
      const VI wrap = I(kWrap);
      MI stepped = noLanes();
      for (int a = 0; a < 3; ++a) {
        const MI along = hn::And(inLevel, hn::Eq(axis, hn::Set(di, a)));
        if (hn::AllFalse(di, along)) continue;
        const VF d = F(kD + a);
        const MI up = toInt(hn::Gt(d, zero)), down = toInt(hn::Lt(d, zero));
        const VI cells = I(kCells + a);
        VI cell = hn::Add(I(kCell + a),
                          hn::Sub(hn::IfThenElseZero(up, hn::Set(di, 1)), hn::IfThenElseZero(down, hn::Set(di, 1))));
        const MI wrapped = hn::Ne(hn::And(wrap, hn::Set(di, 1 << a)), hn::Zero(di));
        const MI over = hn::And(up, hn::Eq(cell, cells)), under = hn::And(down, hn::Lt(cell, hn::Zero(di)));
        const MI moved = hn::AndNot(hn::AndNot(wrapped, hn::Or(over, under)), along);
        const MI overWrapped = hn::And(over, wrapped), underWrapped = hn::And(under, wrapped);
        cell = hn::IfThenElse(overWrapped, hn::Zero(di),
                              hn::IfThenElse(underWrapped, hn::Sub(cells, hn::Set(di, 1)), cell));
        const VF size = F(kSize + a);
        VF tile = F(kTile + a);
        tile = hn::IfThenElse(toFloat(overWrapped), hn::Add(tile, size),
                              hn::IfThenElse(toFloat(underWrapped), hn::Sub(tile, size), tile));
        const VI at = hn::Add(I(kBoundsStart + a), cell);
        const VF lo = gather(bounds_, moved, at), hi = gather(bounds_, moved, hn::Add(at, hn::Set(di, 1)));
        setI(kCell + a, moved, cell);
        setF(kTile + a, moved, tile);
        setF(kLo + a, moved, lo);
        setF(kHi + a, moved, hi);
        setF(kTNext + a, moved, exitParameter(tile, lo, hi, F(kO + a), d, F(kInvD + a)));
        setI(kEntryAxis, moved, hn::Set(di, a));
        stepped = hn::Or(stepped, moved);
      }
      const VF t = hn::Load(df, t_);
      hn::Store(hn::IfThenElse(toFloat(stepped), stdMax(t, tCross), t), df, t_);
      leaving = hn::AndNot(stepped, leaving);
      if (hn::AllFalse(di, leaving)) return;
      // The rest leave their level: the root's end on the background, the others return to the
      // parent at the level's exit.
      const VI top = hn::Load(di, top_);
      const MI atRoot = hn::And(leaving, hn::Eq(top, hn::Zero(di)));
      leaving = hn::AndNot(atRoot, leaving);
      if (!hn::AllFalse(di, leaving)) {
        hn::Store(hn::IfThenElse(toFloat(leaving), F(kTExit), hn::Load(df, t_)), df, t_);
        hn::Store(hn::Sub(top, hn::IfThenElseZero(leaving, hn::Set(di, 1))), di, top_);
        forEachDepth(leaving, [&](MI atDepth, std::size_t depth) {
          const LevelLanes& parent = saved_[depth];
          for (int k = 0; k < kFloatFields; ++k) setF(k, atDepth, hn::Load(df, parent.f[k]));
          for (int k = 0; k < kIntFields; ++k) setI(k, atDepth, hn::Load(di, parent.i[k]));
        });
      }
      if (!hn::AllFalse(di, atRoot)) {
        alignas(64) std::int32_t ended[kMaxLanes] = {};
        hn::Store(hn::VecFromMask(di, atRoot), di, ended);
        for (std::size_t lane = 0; lane < lanes_; ++lane) {
          if (!ended[lane]) continue;
          job_.results[ray_[lane]].iterations = iterations_[lane];
          takeNextRay(lane);
        }
      }
      if (hn::AllFalse(di, leaving)) return;
    }
  }

  const RayPacketJob& job_;
  const RayPacketTables& tables_;
  const RayCastOptions& options_;
  const std::size_t lanes_;
  const float* bounds_;
  const bool lod_;
  std::size_t next_ = 0;                          // the next ray to start
  LevelLanes cur_;                                // each lane's current level
  std::array<LevelLanes, kMaxStackDepth> saved_;  // the levels below it, by depth
  alignas(64) float t_[kMaxLanes];
  alignas(64) std::int32_t top_[kMaxLanes], iterations_[kMaxLanes], busy_[kMaxLanes];
  std::array<std::optional<Walk>, kMaxLanes> walks_;  // each lane's ray, for the hand-over
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
  const auto pixelOf = [&](const std::uint8_t* p) { return static_cast<std::int32_t>((p - base) / 4); };
  t.pixels = reinterpret_cast<const std::int32_t*>(base);
  t.rowPixels = caster.image_.width;
  for (const HniRayCaster::Block& block : caster.blocks_) {
    t.bottomPixel.push_back(pixelOf(block.bottomRow));
    t.cellsX.push_back(block.header.cells.x);
    for (std::size_t a = 0; a < 3; ++a) {
      const AxisView& axis = block.axes[a];
      t.size.push_back(axis.size);
      t.scale.push_back(axis.scale);
      t.exactLast.push_back(axis.exactLast);
      t.stepScale.push_back(axis.stepScale);
      t.lastStep.push_back(axis.lastStep);
      t.cells.push_back(axis.cells);
      t.metaPixel.push_back(pixelOf(axis.meta));
      t.exactPixel.push_back(pixelOf(axis.exact));
      t.boundsStart.push_back(static_cast<std::int32_t>(t.exactBounds.size()));
      t.heuristicBounds.insert(t.heuristicBounds.end(), block.heuristicBounds[a].begin(),
                               block.heuristicBounds[a].end());
      t.exactBounds.insert(t.exactBounds.end(), block.exactBounds[a].begin(), block.exactBounds[a].end());
    }
  }
  t.redirectByRecord = caster.redirectByRecord_;
  for (const HniRayCaster::Redirect& r : caster.redirects_) {
    for (std::size_t a = 0; a < 3; ++a) t.offset[a].push_back(r.offset[static_cast<int>(a)]);
    const glm::mat3 toChild = glm::transpose(r.rotation);
    for (int c = 0; c < 3; ++c)
      for (int row = 0; row < 3; ++row) t.toChild[static_cast<std::size_t>(3 * c + row)].push_back(toChild[c][row]);
    t.rotation.push_back(r.rotation);
    t.target.push_back(r.target);
    t.wrap.push_back(r.wrap);
    t.unrotated.push_back(r.unrotated ? 1 : 0);
    t.lodFootprint.push_back(r.lodFootprint);
  }
  // Lanes out of a step gather index 0: every table has an entry there.
  if (caster.redirects_.empty()) {
    for (auto& v : t.offset) v.push_back(0.0f);
    for (auto& v : t.toChild) v.push_back(0.0f);
    t.rotation.emplace_back(1.0f);
    t.target.push_back(0), t.wrap.push_back(0), t.unrotated.push_back(1), t.lodFootprint.push_back(0.0f);
  }
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
