// hni_raycast.frag — the HNI ray caster: a step-for-step port of the CPU reference caster
// nut::HniRayCaster::traceWith (nut/src/raycast.cpp), in float like it, writing the colour of
// docs/RENDERING.md and gl_FragDepth so that HNIs and meshes share one depth-tested image. The
// same cells are visited in the same order; where the CPU caster takes a step's new boundary from
// a table it read once per block, this shader fetches the metadata pixel the j numbers lead to.
//
// References: Kuang et al. 2013, section 6 and Algorithm 1 (ray casting: NUT traversal with one
// next-boundary query per step using the j numbers, Figure 14a; redirection landing: fetch the
// record, transform the ray, load the lower header, locate the cell, Figure 14b; a small stack to
// return to parents; wrapping of sub-blocks), section 4.2 (solids), section 7.3 and Figure 7
// (level of detail from visual summaries). Assembled after format_constants.glsl, common.glsl,
// hni_access.glsl and solids.glsl.
//
// Output: premultiplied colour and the transmittance left in alpha, blended with
// glBlendFunc(GL_ONE, GL_SRC_ALPHA) over what is behind (the background or meshes drawn first):
// an opaque hit writes alpha 0 and replaces it, a ray that ends behind translucent cells only
// lets it through tinted. Rays that hit nothing are discarded.

flat in vec3 vEyeUnits;
flat in mat3 vWorldFromRoot;
flat in ivec2 vAtlasOrigin;

// The camera (nut::RayGenerator): unit basis, tan of the half fields of view, image size.
uniform vec3 uForward;
uniform vec3 uRight;
uniform vec3 uUp;
uniform vec2 uTanHalf;
uniform vec2 uViewportSize;
// Window depth of eye-space depth z: 0.5 + 0.5 (x - y / z), x = (f + n) / (f - n), y = 2 f n / (f - n).
uniform vec2 uDepthFromEyeZ;
uniform float uPixelAngle;   // the angle one pixel subtends, radians
uniform float uLodPx;        // level of detail: 0 = full detail
uniform bool uLodAuto;       // level of detail from the footprints records carry (--lod auto)
uniform int uMaxIterations;  // cell visits and landings per ray
uniform bool uHeatMap;       // draw opaque hits in the colour of their iterations (nut/heat_map.hpp)
// Exact metadata lookup (two fetches) instead of the heuristic (one): NUT_EXACT_LOOKUP is defined
// by the program's builder (nut::viewer::HniRenderer), one program per mode.
const bool kExactLookup = NUT_EXACT_LOOKUP != 0;

out vec4 fragColour;

// One block instance on the traversal stack (nut/src/raycast.cpp Level).
struct Level {
  ivec2 header;
  vec3 o, d;         // the ray in this block's frame, units (mm)
  vec3 invD;         // 1 / d
  mat3 toWorld;      // rotation from this frame to the world
  int wrap;
  float tExit;       // the level ends here (box or parent cell exit)
  float tStepLimit;  // a step crossing at or after this leaves the level instead (see land)
  ivec3 cell;
  vec3 lo, hi;       // the cell's boundaries along each axis, within the tile
  ivec3 kLo, kHi;    // metadata pixels holding them (-1 / M for the block faces)
  vec3 tile;         // start of the current tile (multiple of D) on wrapped axes
  vec3 tNext;        // ray parameter where the ray leaves the cell, per axis
  vec3 entryNormal;  // world normal of the face through which the ray entered the cell's visible part
};

bool wraps(Level L, int a) { return (L.wrap & (1 << a)) != 0; }

// The face normal, in the level's frame, of a boundary perpendicular to axis a met by the ray.
vec3 faceNormal(vec3 d, int a) {
  vec3 n = vec3(0.0);
  n[a] = d[a] > 0.0 ? -1.0 : 1.0;
  return n;
}

float boundaryAt(BlockInfo b, int a, int k) {
  if (k < 0) return 0.0;
  if (k >= b.pixels[a]) return b.size[a];
  return kExactLookup ? boundaryExact(b, a, k) : boundaryHeuristic(b, a, k);
}

float exitParameter(Level L, int a) {
  if (L.d[a] > 0.0) return (L.tile[a] + L.hi[a] - L.o[a]) * L.invD[a];
  if (L.d[a] < 0.0) return (L.tile[a] + L.lo[a] - L.o[a]) * L.invD[a];
  return kInfinity;
}

void setDirection(inout Level L, vec3 d) {
  L.d = d;
  L.invD = 1.0 / d;  // +-infinity on zero components, which exitParameter never multiplies
}

int argMin(vec3 v) { return v.x <= v.y ? (v.x <= v.z ? 0 : 2) : (v.y <= v.z ? 1 : 2); }

// Redirection landing (paper Figure 14b): clips [tStart, tLimit] by the block's box (axes without
// wrapping) and finds the landing cell. Returns the landing parameter, or -1 when the ray misses
// the block in that interval. The cell is looked up a few float ulps past the entry, as on the CPU
// (raycast.cpp explains why), and the ray is processed from the entry.
float land(inout Level L, BlockInfo b, float tStart, float tLimit, vec3 entryNormal) {
  float t0 = tStart, t1 = tLimit;
  L.entryNormal = entryNormal;
  for (int a = 0; a < 3; ++a) {
    if (wraps(L, a)) continue;
    if (L.d[a] == 0.0) {
      if (L.o[a] < 0.0 || L.o[a] > b.size[a]) return -1.0;
      continue;
    }
    float ta = -L.o[a] * L.invD[a], tb = (b.size[a] - L.o[a]) * L.invD[a];
    if (ta > tb) {
      float swap = ta;
      ta = tb;
      tb = swap;
    }
    if (ta > t0) {
      t0 = ta;
      L.entryNormal = L.toWorld * faceNormal(L.d, a);
    }
    t1 = min(t1, tb);
  }
  if (!(t0 < t1)) return -1.0;
  L.tExit = t1;
  // As the CPU caster (nut/src/raycast.cpp, land): the landing cell is looked up a few ulps past
  // t0, and a boundary crossed that close before t1 is not crossed.
  float reach = max(abs(L.o.x), max(abs(L.o.y), abs(L.o.z)));
  float tProbe = t0 + min(4.0 * kFloatEpsilon * (abs(t0) + reach), 0.5 * (t1 - t0));
  L.tStepLimit = t1 - min(4.0 * kFloatEpsilon * (abs(t1) + reach), 0.5 * (t1 - t0));
  for (int a = 0; a < 3; ++a) {
    float x = L.o[a] + tProbe * L.d[a];
    L.tile[a] = wraps(L, a) ? floor(x / b.size[a]) * b.size[a] : 0.0;
    x -= L.tile[a];
    // The cell lookup and both traversal queries read the same metadata pixel: fetch it once.
    int q = kExactLookup ? 0 : stepOf(b, a, x);
    int k = kExactLookup ? pixelOf(b, a, x) : q >> 8;
    uvec4 p = metaTexel(b, a, k);
    int c = kExactLookup ? cellExact(b, a, x, k, p) : cellHeuristic(p, q);
    L.cell[a] = c;
    L.kLo[a] = c > 0 ? boundaryPixelAhead(p, k, c, -1) : -1;
    L.kHi[a] = c + 1 < b.cells[a] ? boundaryPixelAhead(p, k, c, +1) : b.pixels[a];
    L.lo[a] = boundaryAt(b, a, L.kLo[a]);
    L.hi[a] = boundaryAt(b, a, L.kHi[a]);
    L.tNext[a] = exitParameter(L, a);
  }
  return t0;
}

// Steps into the neighbouring cell along axis a (one metadata fetch: the boundary crossed is the
// new cell's other one). Returns false when the ray leaves the block along an axis without
// wrapping.
bool stepCell(inout Level L, BlockInfo b, int a) {
  L.entryNormal = L.toWorld * faceNormal(L.d, a);
  if (L.d[a] > 0.0) {
    if (++L.cell[a] == b.cells[a]) {
      if (!wraps(L, a)) return false;
      L.cell[a] = 0;
      L.tile[a] += b.size[a];
      L.kLo[a] = -1;  // the new cell starts at the block face
      L.lo[a] = 0.0;
    } else {
      L.kLo[a] = L.kHi[a];
      L.lo[a] = L.hi[a];
    }
    L.kHi[a] = L.cell[a] + 1 == b.cells[a] ? b.pixels[a]
               : L.kLo[a] < 0             ? boundaryPixelAhead(metaTexel(b, a, 0), 0, 0, +1)
                                          : nextBoundaryPixel(b, a, L.kLo[a], +1);
    L.hi[a] = boundaryAt(b, a, L.kHi[a]);
  } else {
    if (--L.cell[a] < 0) {
      if (!wraps(L, a)) return false;
      L.cell[a] = b.cells[a] - 1;
      L.tile[a] -= b.size[a];
      L.kHi[a] = b.pixels[a];  // the new cell ends at the block face
      L.hi[a] = b.size[a];
    } else {
      L.kHi[a] = L.kLo[a];
      L.hi[a] = L.lo[a];
    }
    L.kLo[a] = L.cell[a] == 0             ? -1
               : L.kHi[a] >= b.pixels[a] ? boundaryPixelAhead(metaTexel(b, a, b.pixels[a] - 1), b.pixels[a] - 1,
                                                              b.cells[a] - 1, -1)
                                         : nextBoundaryPixel(b, a, L.kHi[a], -1);
    L.lo[a] = boundaryAt(b, a, L.kLo[a]);
  }
  L.tNext[a] = exitParameter(L, a);
  return true;
}

// Front-to-back compositing of translucent cells.
vec3 gComposite = vec3(0.0);
float gTransmittance = 1.0;

void composite(vec3 colour, float alpha) {
  gComposite += gTransmittance * alpha * colour;
  gTransmittance *= 1.0 - alpha;
}

// Window depth (OpenGL convention, nut::RayGenerator::windowDepth) of the point at t units.
float windowDepth(float t, vec3 direction) {
  float eyeZ = t * kMetresPerUnit * dot(direction, uForward);
  return clamp(0.5 + 0.5 * (uDepthFromEyeZ.x - uDepthFromEyeZ.y / eyeZ), 0.0, 1.0);
}

// An opaque surface at tHit: the composited colour, rounded as on the CPU, replaces what is behind.
// In the heat-map, the colour of the iterations taken instead, untinted.
void finishHit(float tHit, vec3 colour, vec3 direction, int iterations) {
  vec3 c = uHeatMap ? heatColour(iterations, uMaxIterations)
                    : floor(min(vec3(255.0), gComposite + gTransmittance * colour) + 0.5);
  fragColour = vec4(c / 255.0, 0.0);
  gl_FragDepth = windowDepth(tHit, direction);
}

void main() {
  gHniOrigin = vAtlasOrigin;
  // The ray through this pixel centre, as nut::RayGenerator::direction (row 0 at the top).
  vec2 ndc = 2.0 * gl_FragCoord.xy / uViewportSize - 1.0;
  vec3 direction = normalize(uForward + ndc.x * uTanHalf.x * uRight + ndc.y * uTanHalf.y * uUp);

  Level stack[kMaxStackDepth];  // the parents of the current level
  int top = 0;
  Level L;
  L.header = rootHeader();
  L.toWorld = vWorldFromRoot;
  L.wrap = 0;
  L.o = vEyeUnits;
  setDirection(L, transpose(vWorldFromRoot) * direction);
  BlockInfo B = loadBlock(L.header);
  // A camera inside the root box sees what is in front of it: the entry "face" faces the ray.
  float t = land(L, B, 0.0, kInfinity, -direction);
  if (t < 0.0) discard;  // misses the root box
  float firstTranslucent = -1.0;  // where the first translucent surface was met, for the depth
  int iterations = 0;
  bool advance = false;

  while (true) {
    if (advance) {
      // Leave the current cell through the nearest boundary, or leave the level.
      int a = argMin(L.tNext);
      float tCross = L.tNext[a];
      if (tCross >= L.tStepLimit || !stepCell(L, B, a)) {
        if (top == 0) break;
        t = L.tExit;
        L = stack[--top];
        B = loadBlock(L.header);
        continue;  // the parent advances past the cell that held this level
      }
      t = max(t, tCross);
      advance = false;
      continue;
    }
    if (++iterations > uMaxIterations) {
      // Capped: drawn in kCappedColour, never silently, and behind everything.
      fragColour = vec4(kCappedColour / 255.0, 0.0);
      gl_FragDepth = 1.0;
      return;
    }
    advance = true;
    float tCellExit = min(L.tNext[argMin(L.tNext)], L.tExit);
    if (!(tCellExit > t)) continue;  // touched, not entered (landing on a boundary moving away)
    uvec4 texel = cellTexel(B, L.cell);
    int g = int(texel.a);
    if (g >= kCellFirstSolid) {
      float tHit;
      vec3 normalWorld;  // a hit where the ray enters the cell's visible part lies on that face (raycast.cpp)
      uvec4 m;
      if (g == kCellPlane) {
        // A plane cell: its planes are in the block's frame of tile 0 (docs/FORMAT.md).
        PlaneCell cell = loadPlaneCell(unpackAddress(readU24(texel)));
        vec3 span = intersectPlaneCut(cell.normals[0], cell.offsets[0], cell.normals[1], cell.offsets[1], cell.combine,
                                      L.o - L.tile, L.d, t, tCellExit);
        if (!(span.x <= span.y)) continue;
        tHit = span.x;
        normalWorld = span.z < 0.0 ? L.entryNormal : normalize(L.toWorld * cell.normals[int(span.z)]);
        m = loadMaterial(span.z < 0.0 ? cell.material : cell.surfaceMaterials[int(span.z)]);
      } else {
        vec3 size = L.hi - L.lo;
        SolidHit hit = intersectSolid(g - kCellFirstSolid, (L.o - L.tile - L.lo) / size, L.d / size, t, tCellExit);
        if (!hit.hit) continue;
        tHit = hit.t;
        normalWorld = hit.t == t ? L.entryNormal : normalize(L.toWorld * normalize(hit.normal / size));
        m = loadMaterial(int(texel.r | (texel.g << 8)));
      }
      vec3 colour = shade(vec3(m.rgb), normalWorld, direction);
      if (m.a == 255u) {
        finishHit(tHit, colour, direction, iterations);
        return;
      }
      if (firstTranslucent < 0.0) firstTranslucent = tHit;
      composite(colour, float(m.a) / 255.0);
      continue;
    }
    if (g != kCellRedirection) continue;

    Redirect record = loadRedirect(ivec2(texel.rg));
    vec3 cellSize = L.hi - L.lo;
    float pixelSpan = max(t, 1.0) * uPixelAngle;
    float projectedPx = max(cellSize.x, max(cellSize.y, cellSize.z)) / pixelSpan;
    if (top + 1 == kMaxStackDepth || (uLodAuto && record.lodFootprint > 0.0 && pixelSpan > record.lodFootprint) ||
        (uLodPx > 0.0 && projectedPx < uLodPx)) {
      // Level of detail: the target's visual summary of the face the ray entered through.
      vec3 normalWorld = L.entryNormal;
      vec3 inTarget = transpose(L.toWorld * record.rotation) * normalWorld;
      int axis = argMin(-abs(inTarget));
      int side = 2 * axis + (inTarget[axis] > 0.0 ? 0 : 1);
      uvec4 s = hniTexel(record.target + ivec2(kHeaderSummary + side, 0));
      vec3 colour = shade(vec3(s.rgb), normalWorld, direction);
      if (s.a == 255u) {
        finishHit(t, colour, direction, iterations);
        return;
      }
      if (firstTranslucent < 0.0) firstTranslucent = t;
      composite(colour, float(s.a) / 255.0);
      continue;
    }
    Level child;
    child.header = record.target;
    mat3 toChild = transpose(record.rotation);
    child.o = toChild * (L.o - L.tile - L.lo - record.offset);
    setDirection(child, toChild * L.d);
    child.toWorld = L.toWorld * record.rotation;
    child.wrap = record.wrap;
    BlockInfo childBlock = loadBlock(child.header);
    float landed = land(child, childBlock, t, tCellExit, L.entryNormal);
    if (landed < 0.0) continue;  // the sub-block does not reach into this part of the cell
    t = landed;
    stack[top++] = L;
    L = child;
    B = childBlock;
    advance = false;
  }
  if (firstTranslucent < 0.0) discard;  // nothing but empty space: the background stays
  // Only translucent cells: their tint over what is behind, at the depth of the first of them.
  fragColour = vec4(gComposite / 255.0, gTransmittance);
  gl_FragDepth = windowDepth(firstTranslucent, direction);
}
