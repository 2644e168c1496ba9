// lookup_bench.frag — the fragment stage of bench/gl_lookup_bench.cpp, the GPU analogue of
// bench/lookup_bench.cpp (the paper's Table 1, Kuang et al. 2013, section 3.2): the cost of one
// random-access lookup into an n x n x n NUT, per axis a cell index, then one texel fetch.
//
// Assembled after format_constants.glsl, common.glsl and hni_access.glsl, whose lookups it times
// as the ray caster calls them (stepOf / pixelOf + metaTexel + cellHeuristic / cellExact). Defines:
//   METHOD      0 native (uniform grid), 1 heuristic, 2 exact, 3 binary search
//   LOOKUPS     K: lookups per fragment
//   CHECK_PASS  1: write lookup uCheckIndex's point and cells instead of the sum (correctness pass)
//
// uHni (hni_access.glsl) holds the metadata region of the CPU benchmark: axis a's metadata row at
// v = 2a, its exact row at v = 2a + 1, and, for the binary search, its interior boundaries
// b_1 .. b_{n-1} as u24 at v = 6 + a. uData is the (n n) x n data image, z tiled along u.
//
// The points: per fragment a base point from a hash of the pixel, per lookup i a uniform offset
// (drawn on the CPU), wrapped into [0, D): x = base + offset, minus D where that reaches D. Only an
// add, a compare and a select per axis, shared by every method, and exactly rounded, so the CPU
// recomputes the same points bit for bit for the check.

uniform usampler2D uData;
uniform int uN;                  // n: cells per axis
uniform vec3 uSize;              // D per axis (mm)
uniform vec3 uSizeBelow;         // the largest float below D
uniform vec3 uNativeScale;       // n / D
uniform float uNativeLast;       // the largest float below n
// The axis views (nut::AxisView's fields, computed on the CPU so the lookups match it exactly).
uniform vec3 uPixels;            // M per axis
uniform vec3 uScale;             // M / D
uniform vec3 uStepScale;         // 256 M / D
uniform vec3 uStepSize;          // D / (256 M)
uniform vec3 uLastPixel;         // the largest float below M
uniform vec3 uLastStep;          // the largest float below 256 M
uniform int uSearchStep;         // binary search: the largest power of two <= n - 1
uniform vec3 uOffsets[LOOKUPS];  // per lookup, in [0, D)
uniform int uCheckIndex;         // CHECK_PASS: the lookup written out

layout(location = 0) out uvec4 fragResult;

const int kBoundaryRow = 6;

#if __VERSION__ >= 400
#define POINT_PRECISE precise
#else
#define POINT_PRECISE
#endif

BlockInfo gBlock;

// The block of the benchmark, as loadBlock would decode it, from the CPU's AxisView fields.
BlockInfo benchBlock() {
  BlockInfo b;
  b.cells = ivec3(uN);
  b.pixels = ivec3(uPixels);
  b.size = uSize;
  for (int a = 0; a < 3; ++a) b.meta[a] = ivec2(0, 2 * a);
  b.data = ivec2(0);
  b.scale = uScale;
  b.stepScale = uStepScale;
  b.stepSize = uStepSize;
  b.lastPixel = uLastPixel;
  b.lastStep = uLastStep;
  return b;
}

// MurmurHash3's 32-bit finaliser; gl_lookup_bench.cpp has the same.
uint mix32(uint h) {
  h ^= h >> 16;
  h *= 0x85EBCA6Bu;
  h ^= h >> 13;
  h *= 0xC2B2AE35u;
  h ^= h >> 16;
  return h;
}

// The fragment's base point in [0, D): 24 random bits per axis times D.
vec3 fragmentBase(uvec2 pixel) {
  uint key = pixel.x | (pixel.y << 16);
  vec3 base;
  for (int a = 0; a < 3; ++a)
    base[a] = float(mix32(key + 0x9E3779B9u * uint(a + 1)) >> 8) * (1.0 / 16777216.0) * uSize[a];
  return min(base, uSizeBelow);
}

vec3 lookupPoint(vec3 base, int i) {
  POINT_PRECISE vec3 x = base + uOffsets[i];
  POINT_PRECISE vec3 wrapped = mix(x, x - uSize, greaterThanEqual(x, uSize));
  return wrapped;
}

// Binary search: the number of interior boundaries <= x, in power-of-two steps (upper_bound).
int cellBinary(int a, float x) {
  int count = 0;
  for (int step = uSearchStep; step > 0; step >>= 1) {
    int next = count + step;
    float boundary = float(readU24(hniTexel(ivec2(min(next, uN - 1) - 1, kBoundaryRow + a))));
    if (next <= uN - 1 && boundary <= x) count = next;
  }
  return count;
}

ivec3 cellsOf(vec3 x) {
#if METHOD == 0
  return ivec3(min(vec3(uNativeLast), max(vec3(0.0), x * uNativeScale)));
#else
  ivec3 c;
  for (int a = 0; a < 3; ++a) {
#if METHOD == 1
    int q = stepOf(gBlock, a, x[a]);
    c[a] = cellHeuristic(metaTexel(gBlock, a, q >> 8), q);
#elif METHOD == 2
    int k = pixelOf(gBlock, a, x[a]);
    c[a] = cellExact(gBlock, a, x[a], k, metaTexel(gBlock, a, k));
#else
    c[a] = cellBinary(a, x[a]);
#endif
  }
  return c;
#endif
}

void main() {
  gHniOrigin = ivec2(0);
  gBlock = benchBlock();
  vec3 base = fragmentBase(uvec2(gl_FragCoord.xy));
#if CHECK_PASS
  vec3 x = lookupPoint(base, uCheckIndex);
  ivec3 c = cellsOf(x);
  fragResult = uvec4(floatBitsToUint(x), uint(c.x) | (uint(c.y) << 8) | (uint(c.z) << 16));
#else
  uvec4 sum = uvec4(0u);
  for (int i = 0; i < LOOKUPS; ++i) {
    ivec3 c = cellsOf(lookupPoint(base, i));
    sum += texelFetch(uData, ivec2(c.x + c.z * uN, c.y), 0);
  }
  fragResult = sum;
#endif
}
