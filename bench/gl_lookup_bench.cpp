// bench/gl_lookup_bench.cpp — the GPU analogue of lookup_bench.cpp (the paper's Table 1, Kuang et
// al. 2013, section 3.2): the cost of one random-access lookup into a 3D NUT of n x n x n cells,
// n = 4 .. 64, in GLSL, by
//   native     a uniform grid: per axis cell = int(min(n - eps, max(0, x * n / D))), then the fetch
//   heuristic  per axis hni_access.glsl's stepOf + metaTexel + cellHeuristic, then the fetch
//   exact      per axis pixelOf + metaTexel + cellExact (a second, exact-row texel), then the fetch
//   binary     per axis a binary search over a texture row of the interior boundaries, then the fetch
// Why: the lookup targets (heuristic <= 1.3x native, exact <= 1.6x) are about the GPU, where the
// paper measured 1.41x; on a CPU the ratio is about 1.9x (docs/BENCHMARKS.md, "Lookup cost").
//
// The scene is lookup_bench's (lookup_scene.hpp: the same widths, metadata and data image). The
// metadata region is an RGBA8UI texture (the ray caster's uHni), the data image another; the
// lookups are the ray caster's own GLSL (shaders/hni_access.glsl), not copies. One draw covers a
// size x size off-screen target (RGBA32UI) where each fragment performs K independent lookups at
// pseudo-random points (a hash of the pixel plus a per-lookup offset, the same points for every
// method; shaders/lookup_bench.frag) and writes the sum of the fetched texels, so nothing is
// optimised away. A sample is as many draws as take --min-ms, timed by a GL_TIME_ELAPSED query on a
// GPU, by glFinish and the wall clock on a software renderer (llvmpipe's query misses most of the
// work of its rasterizer threads: the wall clock read up to 7x its time here) or without queries;
// the methods take turns sample by sample, and the table reports the median sample as ns per
// lookup and its ratio to native.
//
// Before timing, for every n and method: a check pass writes the point and the three cells of a
// few lookups per pixel over a region, compared with the CPU (nut::AxisView::cellHeuristic for the
// heuristic, the exact cell for exact and binary, UniformAxis for native); and the sums the timed
// program wrote over a corner of the target are compared with the CPU's. Any difference fails.
//
//   build/bench/gl_lookup_bench --gl egl        # a GPU where there is one (else llvmpipe)
//   build/bench/gl_lookup_bench --gl osmesa --size 256 --lookups 64
#include "lookup_scene.hpp"

#include <viewer/context.hpp>
#include <viewer/gl.hpp>
#include <viewer/gl_object.hpp>
#include <viewer/shader_library.hpp>

#if NUT_HAVE_OSMESA
#include <GL/osmesa.h>  // after <viewer/gl.hpp>, which includes GL/glcorearb.h
#endif
#include <EGL/egl.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <random>
#include <string>
#include <vector>

namespace {

using namespace nut::bench;  // the scene: lookup_scene.hpp
namespace viewer = nut::viewer;

constexpr int kMaxLookups = 128;   // uOffsets is a uniform array: keep it well below the limits
constexpr int kCheckRegion = 128;  // the check pass covers kCheckRegion^2 pixels ...
constexpr int kSumRegion = 32;     // ... and the timed sums are compared over kSumRegion^2
constexpr std::uint32_t kPointSeed = kSeed + 1000;  // the per-lookup offsets
constexpr int kBoundaryRow = 6;    // lookup_bench.frag: the interior boundaries of axis a at v = 6 + a
constexpr int kHniRows = kRegionRows + 3;

[[noreturn]] void fail(const std::string& message) {
  std::fprintf(stderr, "gl_lookup_bench: %s\n", message.c_str());
  std::exit(1);
}

// ---- Options ----------------------------------------------------------------------------------

struct Options {
  std::string backend = "egl";
  int size = 0;  // 0: 2048 on a GPU, 256 on a software renderer (llvmpipe)
  int lookups = 64;
  int samples = 5;
  double minMs = 20;
  std::string timer = "auto";  // auto: the timer query on a GPU, the wall clock on a software renderer
};

void printHelp() {
  std::printf(
      "gl_lookup_bench: ns per random-access lookup into an n x n x n NUT (n = 4 .. 64) on the GL\n"
      "context's device: native uniform grid, heuristic, exact and binary-search lookups (the GLSL\n"
      "of shaders/hni_access.glsl), each followed by one data texel fetch; ratios to native.\n\n"
      "  --gl osmesa|egl   GL back-end (default egl: a GPU if any, else llvmpipe; falls back to osmesa)\n"
      "  --size N          the off-screen target is N x N fragments (default 2048 on a GPU, 256 on\n"
      "                    a software renderer)\n"
      "  --lookups K       lookups per fragment, 1 .. %d (default 64)\n"
      "  --samples S       timed samples per method and size; the median is reported (default 5)\n"
      "  --min-ms T        draws per sample: as many as take at least T ms (default 20)\n"
      "  --timer auto|query|wall  GL_TIME_ELAPSED or glFinish + wall clock (default auto: the query on\n"
      "                    a GPU, the wall clock on a software renderer, whose query misses its threads)\n"
      "  --help            this text\n\n"
      "Example:\n"
      "  build/bench/gl_lookup_bench --gl egl\n"
      "  build/bench/gl_lookup_bench --gl osmesa --size 256 --lookups 32\n",
      kMaxLookups);
}

int parseInt(const std::string& flag, const char* text, int lo, int hi) {
  char* end = nullptr;
  const long value = std::strtol(text, &end, 10);
  if (end == text || *end != '\0' || value < lo || value > hi)
    fail(flag + " takes an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "], not '" + text + "'");
  return static_cast<int>(value);
}

Options parseOptions(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string flag = argv[i];
    if (flag == "--help" || flag == "-h") {
      printHelp();
      std::exit(0);
    }
    if (i + 1 >= argc) fail("unknown flag or missing value: " + flag + " (see --help)");
    const char* value = argv[++i];
    if (flag == "--gl") {
      o.backend = value;
      if (o.backend != "egl" && o.backend != "osmesa") fail("--gl takes osmesa or egl");
    } else if (flag == "--size") {
      o.size = parseInt(flag, value, kSumRegion, 8192);
    } else if (flag == "--lookups") {
      o.lookups = parseInt(flag, value, 1, kMaxLookups);
    } else if (flag == "--samples") {
      o.samples = parseInt(flag, value, 1, 1000);
    } else if (flag == "--min-ms") {
      o.minMs = parseInt(flag, value, 0, 100000);
    } else if (flag == "--timer") {
      o.timer = value;
      if (o.timer != "auto" && o.timer != "query" && o.timer != "wall") fail("--timer takes auto, query or wall");
    } else {
      fail("unknown flag " + flag + " (see --help)");
    }
  }
  return o;
}

// ---- Context and the GL functions beyond viewer::Gl --------------------------------------------

// EGL first, falling back to OSMesa (as the renderer's --gl egl does with llvmpipe) with a note.
std::unique_ptr<viewer::Context> openContext(const std::string& name) {
  auto backend = viewer::parseBackend(name);
  if (!backend) fail(backend.error().message);
  auto context = viewer::createContext(*backend);
  if (!context && *backend == viewer::Backend::Egl) {
    std::fprintf(stderr, "gl_lookup_bench: %s; falling back to osmesa\n", context.error().message.c_str());
    context = viewer::createContext(viewer::Backend::OSMesa);
  }
  if (!context) fail(context.error().message);
  return std::move(*context);
}

// Timer queries (core in GL 3.3, but not in viewer::Gl), through the back-end's own loader.
struct TimerQueries {
  PFNGLGENQUERIESPROC GenQueries = nullptr;
  PFNGLDELETEQUERIESPROC DeleteQueries = nullptr;
  PFNGLBEGINQUERYPROC BeginQuery = nullptr;
  PFNGLENDQUERYPROC EndQuery = nullptr;
  PFNGLGETQUERYOBJECTUI64VPROC GetQueryObjectui64v = nullptr;
  PFNGLGETQUERYIVPROC GetQueryiv = nullptr;
  bool available() const {
    return GenQueries && DeleteQueries && BeginQuery && EndQuery && GetQueryObjectui64v && GetQueryiv;
  }
};

TimerQueries loadTimerQueries(const viewer::Context& context) {
  const auto load = [&context](const char* name) -> void (*)() {
#if NUT_HAVE_OSMESA
    if (context.backend() == viewer::Backend::OSMesa) return reinterpret_cast<void (*)()>(OSMesaGetProcAddress(name));
#endif
    return reinterpret_cast<void (*)()>(eglGetProcAddress(name));
  };
  TimerQueries q;
  q.GenQueries = reinterpret_cast<PFNGLGENQUERIESPROC>(load("glGenQueries"));
  q.DeleteQueries = reinterpret_cast<PFNGLDELETEQUERIESPROC>(load("glDeleteQueries"));
  q.BeginQuery = reinterpret_cast<PFNGLBEGINQUERYPROC>(load("glBeginQuery"));
  q.EndQuery = reinterpret_cast<PFNGLENDQUERYPROC>(load("glEndQuery"));
  q.GetQueryObjectui64v = reinterpret_cast<PFNGLGETQUERYOBJECTUI64VPROC>(load("glGetQueryObjectui64v"));
  q.GetQueryiv = reinterpret_cast<PFNGLGETQUERYIVPROC>(load("glGetQueryiv"));
  if (q.available()) {
    GLint bits = 0;
    q.GetQueryiv(GL_TIME_ELAPSED, GL_QUERY_COUNTER_BITS, &bits);
    if (bits == 0) q = {};
  }
  return q;
}

void checkGl(const viewer::Gl& gl, const char* where) {
  if (const GLenum error = gl.GetError(); error != GL_NO_ERROR)
    fail(std::string(where) + ": " + viewer::glErrorName(error));
}

bool isSoftwareRenderer(const viewer::Context& context) {
  const std::string d = context.description();
  return d.find("llvmpipe") != std::string::npos || d.find("softpipe") != std::string::npos ||
         d.find("swrast") != std::string::npos;
}

// ---- Methods and programs ---------------------------------------------------------------------

enum class Method { kNative, kHeuristic, kExact, kBinary };
constexpr Method kMethods[] = {Method::kNative, Method::kHeuristic, Method::kExact, Method::kBinary};
constexpr int kMethodCount = 4;

const char* methodName(Method m) {
  switch (m) {
    case Method::kNative: return "native";
    case Method::kHeuristic: return "heuristic";
    case Method::kExact: return "exact";
    case Method::kBinary: return "binary";
  }
  return "?";
}

viewer::Program buildProgram(const viewer::Context& context, const viewer::ShaderLibrary& library, Method method,
                             int lookups, bool checkPass) {
  const viewer::ProgramSpec spec{
      .role = std::string("lookup_bench ") + methodName(method) + (checkPass ? " (check)" : ""),
      .vertexFiles = {"fullscreen.vert"},
      .fragmentFiles = {"hni_access.glsl", "lookup_bench.frag"},
      .defines = {"METHOD " + std::to_string(static_cast<int>(method)), "LOOKUPS " + std::to_string(lookups),
                  std::string("CHECK_PASS ") + (checkPass ? "1" : "0")}};
  auto program = viewer::Program::build(context.gl(), library, spec, context.glslVersion());
  if (!program) fail(program.error().message);
  return std::move(*program);
}

// ---- Textures and the target ------------------------------------------------------------------

viewer::GlObject makeIntegerTexture(const viewer::Gl& gl, GLenum internalFormat, GLenum type, int width, int height,
                                    const void* pixels) {
  viewer::GlObject texture = viewer::makeTexture(gl);
  gl.BindTexture(GL_TEXTURE_2D, texture.get());
  gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);  // integer textures: no filtering
  gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  gl.PixelStorei(GL_UNPACK_ALIGNMENT, 1);
  gl.TexImage2D(GL_TEXTURE_2D, 0, static_cast<GLint>(internalFormat), width, height, 0, GL_RGBA_INTEGER, type, pixels);
  checkGl(gl, "texture upload");
  return texture;
}

// The uHni texture of lookup_bench.frag: the metadata region, then a row of interior boundaries
// (u24) per axis.
std::vector<std::uint8_t> hniRows(const LookupScene& s) {
  std::vector<std::uint8_t> rows(s.metaRegion);
  rows.resize(static_cast<std::size_t>(4 * kRegionWidth * kHniRows), 0);
  for (std::size_t a = 0; a < 3; ++a)
    for (std::size_t m = 0; m < s.interior[a].size(); ++m) {
      const auto b = static_cast<std::uint32_t>(s.interior[a][m]);
      std::uint8_t* p = rows.data() + 4 * (kRegionWidth * (kBoundaryRow + a) + m);
      p[0] = static_cast<std::uint8_t>(b), p[1] = static_cast<std::uint8_t>(b >> 8), p[2] = static_cast<std::uint8_t>(b >> 16);
    }
  return rows;
}

struct Target {
  viewer::GlObject colour, framebuffer;
  int size = 0;
};

Target makeTarget(const viewer::Gl& gl, int size) {
  Target t;
  t.size = size;
  t.colour = makeIntegerTexture(gl, GL_RGBA32UI, GL_UNSIGNED_INT, size, size, nullptr);
  t.framebuffer = viewer::makeFramebuffer(gl);
  gl.BindFramebuffer(GL_FRAMEBUFFER, t.framebuffer.get());
  gl.FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, t.colour.get(), 0);
  if (gl.CheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) fail("the RGBA32UI target is incomplete");
  return t;
}

// The lower-left width x height pixels of the bound target, row 0 at the bottom (as gl_FragCoord).
std::vector<std::uint32_t> readRegion(const viewer::Gl& gl, int width, int height) {
  std::vector<std::uint32_t> out(static_cast<std::size_t>(4) * width * height);
  gl.PixelStorei(GL_PACK_ALIGNMENT, 1);
  gl.ReadBuffer(GL_COLOR_ATTACHMENT0);
  gl.ReadPixels(0, 0, width, height, GL_RGBA_INTEGER, GL_UNSIGNED_INT, out.data());
  checkGl(gl, "read-back");
  return out;
}

// ---- The points, as lookup_bench.frag computes them -------------------------------------------

using Point = std::array<float, 3>;

std::uint32_t mix32(std::uint32_t h) {
  h ^= h >> 16;
  h *= 0x85EBCA6Bu;
  h ^= h >> 13;
  h *= 0xC2B2AE35u;
  h ^= h >> 16;
  return h;
}

Point fragmentBase(const LookupScene& s, int px, int py) {
  const auto key = static_cast<std::uint32_t>(px) | (static_cast<std::uint32_t>(py) << 16);
  Point base;
  for (std::size_t a = 0; a < 3; ++a) {
    const std::uint32_t h = mix32(key + 0x9E3779B9u * static_cast<std::uint32_t>(a + 1));
    base[a] = std::min(static_cast<float>(h >> 8) * (1.0f / 16777216.0f) * s.size[a], std::nextafter(s.size[a], 0.0f));
  }
  return base;
}

// Per lookup an offset in [0, D) per axis (the shader's uOffsets).
std::vector<Point> lookupOffsets(const LookupScene& s, int lookups) {
  std::mt19937 rng(kPointSeed + static_cast<std::uint32_t>(s.n));
  std::vector<Point> offsets(static_cast<std::size_t>(lookups));
  for (Point& o : offsets)
    for (std::size_t a = 0; a < 3; ++a) o[a] = std::min(randomUnit(rng) * s.size[a], std::nextafter(s.size[a], 0.0f));
  return offsets;
}

Point lookupPoint(const LookupScene& s, const Point& base, const Point& offset) {
  Point x;
  for (std::size_t a = 0; a < 3; ++a) {
    const float sum = base[a] + offset[a];
    x[a] = sum >= s.size[a] ? sum - s.size[a] : sum;
  }
  return x;
}

// The CPU's answer for one axis: what each method must compute.
int referenceCell(const LookupScene& s, Method method, std::size_t a, float x) {
  const BoundaryAxis truth{.interior = s.interior[a].data(), .count = s.n - 1};
  switch (method) {
    case Method::kNative: return s.native[a].cell(x);
    case Method::kHeuristic: return s.views[a].cellHeuristic(x);
    case Method::kExact:
    case Method::kBinary: return truth.cell(x);
  }
  return -1;
}

// ---- Uniforms of one scene --------------------------------------------------------------------

void setSceneUniforms(const viewer::Gl& gl, const viewer::Program& program, const LookupScene& s,
                      const std::vector<Point>& offsets) {
  gl.UseProgram(program.id());
  const auto vec3 = [&](const char* name, auto field) {
    gl.Uniform3f(program.uniform(name), field(0), field(1), field(2));
  };
  gl.Uniform1i(program.uniform("uHni"), 0);
  gl.Uniform1i(program.uniform("uData"), 1);
  gl.Uniform1i(program.uniform("uN"), s.n);
  vec3("uSize", [&](std::size_t a) { return s.size[a]; });
  vec3("uSizeBelow", [&](std::size_t a) { return std::nextafter(s.size[a], 0.0f); });
  vec3("uNativeScale", [&](std::size_t a) { return s.native[a].scale; });
  gl.Uniform1f(program.uniform("uNativeLast"), s.native[0].lastCell);
  vec3("uPixels", [&](std::size_t a) { return static_cast<float>(s.views[a].pixels); });
  vec3("uScale", [&](std::size_t a) { return s.views[a].scale; });
  vec3("uStepScale", [&](std::size_t a) { return s.views[a].stepScale; });
  vec3("uStepSize", [&](std::size_t a) { return s.views[a].stepSize; });
  vec3("uLastPixel", [&](std::size_t a) { return s.views[a].lastPixel; });
  vec3("uLastStep", [&](std::size_t a) { return s.views[a].lastStep; });
  int step = 1;
  while (2 * step <= s.n - 1) step *= 2;
  gl.Uniform1i(program.uniform("uSearchStep"), s.n > 1 ? step : 0);
  for (std::size_t i = 0; i < offsets.size(); ++i) {
    const std::string name = "uOffsets[" + std::to_string(i) + "]";
    gl.Uniform3f(program.uniform(name.c_str()), offsets[i][0], offsets[i][1], offsets[i][2]);
  }
  checkGl(gl, "uniforms");
}

// ---- What every step uses: the GL state of the run ---------------------------------------------

struct Bench {
  const viewer::Gl& gl;
  const Options& options;
  const TimerQueries& queries;
  std::array<viewer::Program, kMethodCount>& timed;
  std::array<viewer::Program, kMethodCount>& check;
  const Target& target;
  bool useQuery = false;  // time by GL_TIME_ELAPSED, else by glFinish + steady_clock
};

void draw(const viewer::Gl& gl, int width, int height) {
  gl.Viewport(0, 0, width, height);
  gl.DrawArrays(GL_TRIANGLES, 0, 3);
}

// ---- Correctness ------------------------------------------------------------------------------

// Cells and points of lookups 0, K/2 and K-1 over the check region, against the CPU. Returns how
// many per-axis heuristic cells differ from the exact cell (for the heuristic method).
long checkCells(const Bench& b, const LookupScene& s, const std::vector<Point>& offsets, Method method) {
  const viewer::Program& program = b.check[static_cast<std::size_t>(method)];
  b.gl.UseProgram(program.id());
  const int region = std::min(kCheckRegion, b.target.size);
  const int k = static_cast<int>(offsets.size());
  long differFromExact = 0;
  for (int index : {0, k / 2, k - 1}) {
    b.gl.Uniform1i(program.uniform("uCheckIndex"), index);
    draw(b.gl, region, region);
    const std::vector<std::uint32_t> out = readRegion(b.gl, region, region);
    for (int py = 0; py < region; ++py)
      for (int px = 0; px < region; ++px) {
        const std::uint32_t* p = out.data() + 4 * (static_cast<std::size_t>(py) * region + px);
        const Point x = lookupPoint(s, fragmentBase(s, px, py), offsets[static_cast<std::size_t>(index)]);
        const auto where = [&] {
          return std::string(methodName(method)) + ", n = " + std::to_string(s.n) + ", pixel (" + std::to_string(px) +
                 ", " + std::to_string(py) + "), lookup " + std::to_string(index);
        };
        for (std::size_t a = 0; a < 3; ++a) {
          float gx;
          std::memcpy(&gx, &p[a], sizeof gx);
          if (gx != x[a])
            fail("check: " + where() + ": the shader's point differs from the CPU's on axis " + std::to_string(a));
          const int cell = static_cast<int>((p[3] >> (8 * a)) & 0xFFu);
          const int expected = referenceCell(s, method, a, x[a]);
          if (cell != expected)
            fail("check: " + where() + ": axis " + std::to_string(a) + " cell " + std::to_string(cell) +
                 ", the CPU's is " + std::to_string(expected));
          if (method == Method::kHeuristic && cell != referenceCell(s, Method::kExact, a, x[a])) ++differFromExact;
        }
      }
  }
  return differFromExact;
}

// The sums the timed program wrote over the lower-left kSumRegion^2 pixels, against the CPU.
void checkSums(const Bench& b, const LookupScene& s, const std::vector<Point>& offsets, Method method) {
  const int region = std::min(kSumRegion, b.target.size);
  const std::vector<std::uint32_t> out = readRegion(b.gl, region, region);
  for (int py = 0; py < region; ++py)
    for (int px = 0; px < region; ++px) {
      const Point base = fragmentBase(s, px, py);
      std::array<std::uint32_t, 4> sum{};
      for (const Point& offset : offsets) {
        const Point x = lookupPoint(s, base, offset);
        std::array<int, 3> c{};
        for (std::size_t a = 0; a < 3; ++a) c[a] = referenceCell(s, method, a, x[a]);
        const std::uint32_t texel = fetchTexel(s.data.data(), s.n * s.n, c[0] + c[2] * s.n, c[1]);
        for (std::size_t ch = 0; ch < 4; ++ch) sum[ch] += (texel >> (8 * ch)) & 0xFFu;
      }
      for (std::size_t ch = 0; ch < 4; ++ch)
        if (out[4 * (static_cast<std::size_t>(py) * region + px) + ch] != sum[ch])
          fail(std::string("check: ") + methodName(method) + ", n = " + std::to_string(s.n) + ", pixel (" +
               std::to_string(px) + ", " + std::to_string(py) + "): the timed program's sum differs from the CPU's");
    }
}

// ---- Timing -----------------------------------------------------------------------------------

struct Sample {
  double queryNs = -1;  // GL_TIME_ELAPSED; -1 without timer queries
  double wallNs = 0;    // glFinish to glFinish
};

// `draws` draws over the whole target, timed both ways.
Sample timeDraws(const Bench& b, int draws) {
  const viewer::Gl& gl = b.gl;
  const int size = b.target.size;
  GLuint query = 0;
  if (b.queries.available()) b.queries.GenQueries(1, &query);
  gl.Finish();
  const auto start = std::chrono::steady_clock::now();
  if (query != 0) b.queries.BeginQuery(GL_TIME_ELAPSED, query);
  for (int d = 0; d < draws; ++d) draw(gl, size, size);
  if (query != 0) b.queries.EndQuery(GL_TIME_ELAPSED);
  gl.Finish();
  const auto end = std::chrono::steady_clock::now();
  Sample out;
  out.wallNs = std::chrono::duration<double, std::nano>(end - start).count();
  if (query != 0) {
    GLuint64 elapsed = 0;
    b.queries.GetQueryObjectui64v(query, GL_QUERY_RESULT, &elapsed);
    b.queries.DeleteQueries(1, &query);
    out.queryNs = static_cast<double>(elapsed);
  }
  checkGl(gl, "timed draws");
  return out;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t m = v.size() / 2;
  return v.size() % 2 ? v[m] : 0.5 * (v[m - 1] + v[m]);
}

struct Timing {
  double nsPerLookup = 0;   // median sample, by the chosen timer
  double spread = 0;        // (max - min) / median over the samples
  double wallOverQuery = 0; // median wall clock / median query time; 0 without queries
  int draws = 0;            // per sample
};

// Calibrates the draws per sample for each method, then takes the samples in turns, so that a
// slow drift of the clock or of the machine's load affects every method alike.
std::array<Timing, kMethodCount> timeMethods(const Bench& b) {
  const double lookupsPerDraw = static_cast<double>(b.target.size) * b.target.size * b.options.lookups;
  const auto chosen = [&b](const Sample& t) { return b.useQuery ? t.queryNs : t.wallNs; };
  std::array<int, kMethodCount> draws{};
  for (std::size_t m = 0; m < kMethodCount; ++m) {
    b.gl.UseProgram(b.timed[m].id());
    timeDraws(b, 1);  // warm-up
    const double oneDrawMs = chosen(timeDraws(b, 1)) * 1e-6;
    draws[m] = std::clamp(static_cast<int>(std::ceil(b.options.minMs / std::max(oneDrawMs, 1e-3))), 1, 10000);
  }
  std::array<std::vector<double>, kMethodCount> ns, wall, query;
  for (int sample = 0; sample < b.options.samples; ++sample)
    for (std::size_t m = 0; m < kMethodCount; ++m) {
      b.gl.UseProgram(b.timed[m].id());
      const Sample t = timeDraws(b, draws[m]);
      const double lookups = draws[m] * lookupsPerDraw;
      ns[m].push_back(chosen(t) / lookups);
      wall[m].push_back(t.wallNs / lookups);
      query[m].push_back(t.queryNs / lookups);
    }
  std::array<Timing, kMethodCount> out;
  for (std::size_t m = 0; m < kMethodCount; ++m) {
    const auto [lo, hi] = std::minmax_element(ns[m].begin(), ns[m].end());
    out[m].nsPerLookup = median(ns[m]);
    out[m].spread = (*hi - *lo) / out[m].nsPerLookup;
    out[m].wallOverQuery = b.queries.available() ? median(wall[m]) / median(query[m]) : 0;
    out[m].draws = draws[m];
  }
  return out;
}

// ---- Report -----------------------------------------------------------------------------------

struct SizeReport {
  int n = 0;
  double meanPixels = 0;           // M, mean over the axes
  double heuristicWrong = 0;       // fraction of checked per-axis heuristic cells not the exact one
  std::array<Timing, kMethodCount> results{};
};

std::string formatNs(double ns) {
  char text[32];
  std::snprintf(text, sizeof text, ns < 0.1 ? "%.4f" : ns < 10 ? "%.3f" : "%.2f", ns);
  return text;
}

void printTables(const std::vector<SizeReport>& reports) {
  const auto header = [&](const char* first) {
    std::printf("| %s |", first);
    for (const SizeReport& r : reports) std::printf(" n = %d |", r.n);
    std::printf("\n|---|");
    for (std::size_t i = 0; i < reports.size(); ++i) std::printf("---|");
    std::printf("\n");
  };
  std::printf("\nns per lookup (median of the samples; spread = (max - min) / median, worst over the methods):\n\n");
  header("method");
  for (std::size_t m = 0; m < kMethodCount; ++m) {
    std::printf("| %s |", methodName(kMethods[m]));
    for (const SizeReport& r : reports) std::printf(" %s |", formatNs(r.results[m].nsPerLookup).c_str());
    std::printf("\n");
  }
  std::printf("| spread |");
  for (const SizeReport& r : reports) {
    double worst = 0;
    for (const Timing& res : r.results) worst = std::max(worst, res.spread);
    std::printf(" %.1f %% |", 100 * worst);
  }
  std::printf("\n\n");
  header("ratio");
  for (std::size_t m = 1; m < kMethodCount; ++m) {
    std::printf("| %s / native |", methodName(kMethods[m]));
    for (const SizeReport& r : reports) std::printf(" %.2f |", r.results[m].nsPerLookup / r.results[0].nsPerLookup);
    std::printf("\n");
  }
  std::printf("\n| per size |");
  for (const SizeReport& r : reports) std::printf(" n = %d |", r.n);
  std::printf("\n|---|");
  for (std::size_t i = 0; i < reports.size(); ++i) std::printf("---|");
  std::printf("\n| mean M |");
  for (const SizeReport& r : reports) std::printf(" %.1f |", r.meanPixels);
  std::printf("\n| heuristic != exact (checked cells) |");
  for (const SizeReport& r : reports) std::printf(" %.3f %% |", 100 * r.heuristicWrong);
  std::printf("\n| draws per sample (native, heuristic, exact, binary) |");
  for (const SizeReport& r : reports)
    std::printf(" %d, %d, %d, %d |", r.results[0].draws, r.results[1].draws, r.results[2].draws, r.results[3].draws);
  if (reports.front().results[0].wallOverQuery > 0) {
    std::printf("\n| wall clock / GL_TIME_ELAPSED (medians; min-max over the methods) |");
    for (const SizeReport& r : reports) {
      double lo = 1e30, hi = 0;
      for (const Timing& t : r.results) lo = std::min(lo, t.wallOverQuery), hi = std::max(hi, t.wallOverQuery);
      std::printf(" %.2f-%.2f |", lo, hi);
    }
  }
  std::printf("\n");
}

// Scene n's textures and uniforms, the checks, then the timing.
SizeReport measureSize(const Bench& b, int n) {
  const viewer::Gl& gl = b.gl;
  LookupScene scene;
  if (nut::Status built = buildLookupScene(n, scene); !built) fail("n = " + std::to_string(n) + ": " + built.error().message);
  const std::vector<std::uint8_t> hni = hniRows(scene);
  const viewer::GlObject hniTexture = makeIntegerTexture(gl, GL_RGBA8UI, GL_UNSIGNED_BYTE, kRegionWidth, kHniRows, hni.data());
  const viewer::GlObject dataTexture = makeIntegerTexture(gl, GL_RGBA8UI, GL_UNSIGNED_BYTE, n * n, n, scene.data.data());
  gl.ActiveTexture(GL_TEXTURE0);  // uHni
  gl.BindTexture(GL_TEXTURE_2D, hniTexture.get());
  gl.ActiveTexture(GL_TEXTURE1);  // uData
  gl.BindTexture(GL_TEXTURE_2D, dataTexture.get());
  gl.ActiveTexture(GL_TEXTURE0);
  const std::vector<Point> offsets = lookupOffsets(scene, b.options.lookups);
  for (std::size_t m = 0; m < kMethodCount; ++m) {
    setSceneUniforms(gl, b.timed[m], scene, offsets);
    setSceneUniforms(gl, b.check[m], scene, offsets);
  }

  SizeReport report;
  report.n = n;
  report.meanPixels = (scene.pixels[0] + scene.pixels[1] + scene.pixels[2]) / 3.0;
  const int checkRegion = std::min(kCheckRegion, b.target.size);
  for (Method method : kMethods) {
    const long wrong = checkCells(b, scene, offsets, method);
    if (method == Method::kHeuristic) report.heuristicWrong = static_cast<double>(wrong) / (9.0 * checkRegion * checkRegion);
    gl.UseProgram(b.timed[static_cast<std::size_t>(method)].id());
    draw(gl, b.target.size, b.target.size);
    checkSums(b, scene, offsets, method);
  }
  std::fprintf(stderr, "n = %d: check passed (cells: %d x %d pixels x 3 lookups; sums: %d x %d pixels); timing\n", n,
               checkRegion, checkRegion, kSumRegion, kSumRegion);
  report.results = timeMethods(b);
  return report;
}

std::array<viewer::Program, kMethodCount> buildPrograms(const viewer::Context& context, int lookups, bool checkPass) {
  const viewer::ShaderLibrary library = viewer::ShaderLibrary::fromEnvironment();
  return {buildProgram(context, library, kMethods[0], lookups, checkPass),
          buildProgram(context, library, kMethods[1], lookups, checkPass),
          buildProgram(context, library, kMethods[2], lookups, checkPass),
          buildProgram(context, library, kMethods[3], lookups, checkPass)};
}

}  // namespace

int main(int argc, char** argv) {
  Options options = parseOptions(argc, argv);
  const std::unique_ptr<viewer::Context> context = openContext(options.backend);
  const viewer::Gl& gl = context->gl();
  const bool software = isSoftwareRenderer(*context);
  if (options.size == 0) options.size = software ? 256 : 2048;
  const TimerQueries queries = loadTimerQueries(*context);
  if (options.timer == "query" && !queries.available()) fail("--timer query: the context has no GL_TIME_ELAPSED query");
  const bool useQuery = options.timer == "query" || (options.timer == "auto" && queries.available() && !software);

  std::string command = argv[0];
  for (int i = 1; i < argc; ++i) command += std::string(" ") + argv[i];
  std::printf("command: %s\n", command.c_str());
  std::printf("back-end: %s; GL_RENDERER, GL_VERSION: %s\n", viewer::backendName(context->backend()),
              context->description().c_str());
  std::printf("target %d x %d fragments, %d lookups per fragment, %d samples of >= %g ms; timer: %s\n", options.size,
              options.size, options.lookups, options.samples, options.minMs,
              useQuery ? "GL_TIME_ELAPSED" : "glFinish + steady_clock");
  std::fflush(stdout);

  std::array<viewer::Program, kMethodCount> timed = buildPrograms(*context, options.lookups, false);
  std::array<viewer::Program, kMethodCount> check = buildPrograms(*context, options.lookups, true);
  const Target target = makeTarget(gl, options.size);
  const viewer::GlObject vertexArray = viewer::makeVertexArray(gl);
  gl.BindVertexArray(vertexArray.get());
  gl.Disable(GL_DEPTH_TEST);
  gl.Disable(GL_BLEND);
  const Bench bench{gl, options, queries, timed, check, target, useQuery};

  std::vector<SizeReport> reports;
  for (int n : kSizes) reports.push_back(measureSize(bench, n));
  printTables(reports);
  return 0;
}
