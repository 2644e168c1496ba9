// hni_access.glsl — reading an HNI from an unsigned-integer texture, as nut::HniView and
// nut::AxisView read it on the CPU (nut/hni_view.hpp, nut/metadata.hpp): same fields, same float
// arithmetic, so that the GLSL ray caster lands in the same cells as the CPU reference.
//
// References: Kuang et al. 2013, section 3.2 (metadata arrays: i, f, j_left, j_right; the
// heuristic lookup and its bound D / (512 M)), section 4 (HNI layout: headers, data components,
// redirection records, relative addressing) and Figure 14a (traversal with the j numbers);
// docs/FORMAT.md for the byte layout. Every fetch is texelFetch: no filtering, no normalisation.

uniform usampler2D uHni;  // the atlas: one or many HNIs, GL_RGBA8UI
ivec2 gHniOrigin;         // the current HNI's origin in the atlas; every address is relative to it

uvec4 hniTexel(ivec2 uv) { return texelFetch(uHni, gHniOrigin + uv, 0); }

uint readU24(uvec4 p) { return p.r | (p.g << 8) | (p.b << 16); }
int readS24(uvec4 p) { return int(readU24(p) ^ 0x800000u) - 0x800000; }
// A 12-bit address: u in bits 0-11, v in bits 12-23.
ivec2 unpackAddress(uint address) { return ivec2(address & 0xFFFu, (address >> 12) & 0xFFFu); }

ivec2 rootHeader() { return ivec2(hniTexel(ivec2(kFileRoot, 0)).rg); }

vec3 blockSize(ivec2 header) {
  return vec3(float(readU24(hniTexel(header + ivec2(kHeaderSize, 0)))),
              float(readU24(hniTexel(header + ivec2(kHeaderSize + 1, 0)))),
              float(readU24(hniTexel(header + ivec2(kHeaderSize + 2, 0)))));
}

// The largest float below x (x > 0): AxisView's lastPixel and lastStep.
vec3 floatBelow(vec3 x) { return uintBitsToFloat(floatBitsToUint(x) - 1u); }

// A block header with its three axis views (nut::BlockHeader + nut::AxisView::make).
struct BlockInfo {
  ivec3 cells;    // W per axis
  ivec3 pixels;   // M per axis
  vec3 size;      // D per axis, units (mm)
  ivec2 meta[3];  // metadata item per axis: row 0 (i, f, j_left, j_right), row 1 exact positions
  ivec2 data;     // data component corner
  vec3 scale;     // M / D: metadata pixels per unit
  vec3 stepScale; // 256 M / D: steps of f per unit
  vec3 stepSize;  // D / (256 M): units per step of f
  vec3 lastPixel; // the largest float below M
  vec3 lastStep;  // the largest float below 256 M
};

BlockInfo loadBlock(ivec2 header) {
  BlockInfo b;
  for (int a = 0; a < 3; ++a) {
    uvec4 p = hniTexel(header + ivec2(kHeaderSize + a, 0));
    b.size[a] = float(readU24(p));
    b.cells[a] = int(p.a) + 1;
  }
  uvec4 m = hniTexel(header + ivec2(kHeaderMetaSizes, 0));
  uvec4 xy = hniTexel(header + ivec2(kHeaderMetaXY, 0));
  uvec4 z = hniTexel(header + ivec2(kHeaderMetaZ, 0));
  b.pixels = ivec3(m.rgb) + 1;
  b.meta[0] = ivec2(xy.rg);
  b.meta[1] = ivec2(xy.ba);
  b.meta[2] = ivec2(z.rg);
  b.data = unpackAddress(m.a | (z.b << 8) | (z.a << 16));
  vec3 pixels = vec3(b.pixels);
  b.scale = pixels / b.size;
  b.stepScale = b.scale * float(kFractionSteps);  // exact: a power-of-two multiple
  b.stepSize = b.size / (pixels * float(kFractionSteps));
  b.lastPixel = floatBelow(pixels);
  b.lastStep = floatBelow(pixels * float(kFractionSteps));
  return b;
}

// The data pixel of a cell: z slices tiled along u, rows from the top cell down.
uvec4 cellTexel(BlockInfo b, ivec3 c) {
  return hniTexel(b.data + ivec2(c.x + c.z * b.cells.x, b.cells.y - 1 - c.y));
}

uvec4 metaTexel(BlockInfo b, int a, int k) { return hniTexel(b.meta[a] + ivec2(k, 0)); }
uvec4 exactTexel(BlockInfo b, int a, int k) { return hniTexel(b.meta[a] + ivec2(k, 1)); }

// Metadata pixel of coordinate x (units); outside [0, D) clamps to the end pixels.
int pixelOf(BlockInfo b, int a, float x) { return int(min(b.lastPixel[a], max(0.0, x * b.scale[a]))); }

// x in 1/256-pixel steps, clamped like pixelOf: its pixel q >> 8 is pixelOf's (stepScale is scale
// times a power of two), so the heuristic lookup needs no pixelOf of its own.
int stepOf(BlockInfo b, int a, float x) { return int(min(b.lastStep[a], max(0.0, x * b.stepScale[a]))); }

// Heuristic random access (one fetch, p = metaTexel(b, a, q >> 8) for q = stepOf(b, a, x)): the
// cell is i, plus one when the pixel holds a boundary (f != 0) and the fraction reaches f (f = 0
// wraps to 255: never).
int cellHeuristic(uvec4 p, int q) { return int(p.r) + ((uint(q) & 255u) > ((p.g - 1u) & 255u) ? 1 : 0); }

// Exact random access (a second fetch): the exact row decides; where f = 0 its 0 becomes 2^24,
// beyond every coordinate inside the block.
int cellExact(BlockInfo b, int a, float x, int k, uvec4 p) {
  float boundary = float((readU24(exactTexel(b, a, k)) - 1u) & 0xFFFFFFu) + 1.0;
  return int(p.r) + (min(x, b.size[a]) >= boundary ? 1 : 0);
}

// Position (units) of the boundary held by metadata pixel k: heuristic (k + f / 256) D / M, or
// exact from the exact row.
float boundaryHeuristic(BlockInfo b, int a, int k) {
  return float(k * kFractionSteps + int(metaTexel(b, a, k).g)) * b.stepSize[a];
}
float boundaryExact(BlockInfo b, int a, int k) { return float(readU24(exactTexel(b, a, k))); }

// Traversal (paper Figure 14a): the pixel holding the boundary ahead of a point of `cell` found at
// pixel k (whose texel is p), moving in direction dir (+1 or -1); callers handle the block's faces.
int boundaryPixelAhead(uvec4 p, int k, int cell, int dir) {
  if (p.g != 0u && cell == int(p.r) + (dir > 0 ? 0 : 1)) return k;
  return dir > 0 ? k + int(p.a) : k - int(p.b);
}
// The pixel holding the boundary after the one held by pixel k, in direction dir.
int nextBoundaryPixel(BlockInfo b, int a, int k, int dir) {
  uvec4 p = metaTexel(b, a, k);
  return dir > 0 ? k + int(p.a) : k - int(p.b);
}

// cos and sin of 2 pi yaw / 65536 to float precision. GLSL's sin and cos may be off by 2^-11;
// here the angle is reduced exactly in integers to [0, pi/4] and the Taylor series (error below
// 3e-9 there) is summed, so the result is what the C++ double computation rounds to, within an ulp.
vec2 yawCosSin(uint yaw) {
  uint quadrant = yaw >> 14;
  uint r = yaw & 0x3FFFu;
  bool swapped = r > 0x2000u;  // reduce to [0, pi/4]: sin(x) = cos(pi/2 - x)
  float x = float(swapped ? 0x4000u - r : r) * (6.28318530717958647692 / float(kYawSteps));
  float x2 = x * x;
  float s = x * (1.0 + x2 * (-1.0 / 6.0 + x2 * (1.0 / 120.0 + x2 * (-1.0 / 5040.0 + x2 * (1.0 / 362880.0)))));
  float c = 1.0 + x2 * (-0.5 + x2 * (1.0 / 24.0 + x2 * (-1.0 / 720.0 + x2 * (1.0 / 40320.0 + x2 * (-1.0 / 3628800.0)))));
  vec2 cs = swapped ? vec2(s, c) : vec2(c, s);
  if (quadrant == 1u) return vec2(-cs.y, cs.x);
  if (quadrant == 2u) return -cs;
  if (quadrant == 3u) return vec2(cs.y, -cs.x);
  return cs;
}

// A redirection record (docs/FORMAT.md): target-frame to cell-frame rotation R = Yaw * Cube, the
// offset O in units, the target header, the tiling flags and the target's level-of-detail
// footprint in units (0 = none).
struct Redirect {
  mat3 rotation;
  vec3 offset;
  ivec2 target;
  int wrap;
  float lodFootprint;
};

Redirect loadRedirect(ivec2 at) {
  uvec4 p0 = hniTexel(at);
  uvec4 p1 = hniTexel(at + ivec2(1, 0));
  uvec4 p2 = hniTexel(at + ivec2(2, 0));
  uvec4 p3 = hniTexel(at + ivec2(3, 0));
  Redirect r;
  r.offset = vec3(float(readS24(p0)), float(readS24(p1)), float(readS24(p2)));
  r.wrap = int(p0.a);
  r.target = ivec2(p3.rg);
  r.rotation = kCubeRotation[int(p1.a)];
  r.lodFootprint = p2.a == 0u ? 0.0
                              : exp2(float(int(p2.a) - kLodCodeOneMetre) / float(kLodCodesPerOctave)) / kMetresPerUnit;
  uint yaw = p3.b | (p3.a << 8);
  if (yaw != 0u) {
    // Right-handed about +y; a cube rotation is a signed permutation, so the product is exact.
    vec2 cs = yawCosSin(yaw);
    r.rotation = mat3(vec3(cs.x, 0.0, -cs.y), vec3(0.0, 1.0, 0.0), vec3(cs.y, 0.0, cs.x)) * r.rotation;
  }
  return r;
}

// Material m: (r, g, b, opacity) of its first pixel.
uvec4 loadMaterial(int index) {
  uvec4 f = hniTexel(ivec2(kFileMaterials, 0));
  ivec2 origin = unpackAddress(readU24(f));
  int perRow = int(f.a);
  return hniTexel(origin + ivec2(kMaterialPixels * (index % perRow), index / perRow));
}

// A plane cell record (docs/FORMAT.md, version 3): material, combination and up to two planes in
// the block's frame, units (nut::HniRayCaster::PlaneCell).
struct PlaneCell {
  vec3 normals[2];
  float offsets[2];
  int combine;
  int material;             // the box's sides
  int surfaceMaterials[2];  // each plane's surface
};

// The octahedral pair (e_x, e_y) as a unit normal, with nut::decodeNormalFloat's operations.
vec3 decodeOctahedral(uint ex, uint ey) {
  vec2 e = (vec2(float(ex), float(ey)) - kOctahedralCentre) / kOctahedralSteps;
  float z = 1.0 - abs(e.x) - abs(e.y);
  if (z < 0.0) e = (1.0 - abs(e.yx)) * vec2(e.x < 0.0 ? -1.0 : 1.0, e.y < 0.0 ? -1.0 : 1.0);
  return normalize(vec3(e, z));
}

PlaneCell loadPlaneCell(ivec2 at) {
  uvec4 head = hniTexel(at);
  PlaneCell c;
  c.material = int(head.r | (head.g << 8));
  c.combine = int(head.a);
  for (int p = 0; p < 2; ++p) {
    c.normals[p] = vec3(0.0);
    c.offsets[p] = 0.0;
    c.surfaceMaterials[p] = c.material;
    if (p == 1 && c.combine == kPlaneCombineOne) break;
    ivec2 first = at + ivec2(kPlaneRecordHeadPixels + kPixelsPerPlane * p, 0);
    uvec4 ex = hniTexel(first);
    uvec4 ey = hniTexel(first + ivec2(1, 0));
    uvec4 o = hniTexel(first + ivec2(2, 0));
    // The surface's material code over the two alpha channels: 0 the record's, k material k - 1.
    int code = int(ex.a | (ey.a << 8));
    if (code != 0) c.surfaceMaterials[p] = code - 1;
    c.normals[p] = decodeOctahedral(readU24(ex), readU24(ey));
    c.offsets[p] = float(int(readU24(o) | (o.a << 24))) / kPlaneOffsetStepsPerUnit;
  }
  return c;
}
