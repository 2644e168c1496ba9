// fxaa.frag — optional anti-aliasing post-process: fast approximate anti-aliasing after Lottes
// (NVIDIA, 2009), in its compact form: where the luma contrast of the four diagonal neighbours
// marks an edge, blend along the edge's direction with two or four filtered taps, keeping the
// four-tap result unless it leaves the local luma range.
//
// References: not the paper, which renders one ray per pixel (section 6); T. Lottes, "FXAA",
// NVIDIA white paper, 2009. docs/GL.md says when to use it: never for comparisons with the CPU
// renderers, which do not anti-alias. Assembled after format_constants.glsl, common.glsl.

uniform sampler2D uColour;  // the frame, bilinear filtering
uniform vec2 uTexelSize;    // 1 / (width, height)

in vec2 vUv;
out vec4 fragColour;

const float kEdgeThreshold = 1.0 / 8.0;      // relative luma contrast that counts as an edge
const float kEdgeThresholdMin = 1.0 / 24.0;  // below this absolute contrast (dark areas) never
const float kReduceMultiplier = 1.0 / 8.0;
const float kReduceMinimum = 1.0 / 128.0;
const float kSpanMaximum = 8.0;              // pixels

float luma(vec3 c) { return dot(c, vec3(0.299, 0.587, 0.114)); }

vec3 tap(vec2 offsetPixels) { return texture(uColour, vUv + offsetPixels * uTexelSize).rgb; }

void main() {
  vec3 centre = tap(vec2(0.0));
  float lumaCentre = luma(centre);
  // The diagonal neighbours, in texture space (y up): lower left, lower right, upper left, upper right.
  float ll = luma(tap(vec2(-1.0, -1.0))), lr = luma(tap(vec2(1.0, -1.0)));
  float ul = luma(tap(vec2(-1.0, 1.0))), ur = luma(tap(vec2(1.0, 1.0)));
  float lumaMin = min(lumaCentre, min(min(ll, lr), min(ul, ur)));
  float lumaMax = max(lumaCentre, max(max(ll, lr), max(ul, ur)));
  if (lumaMax - lumaMin < max(kEdgeThresholdMin, lumaMax * kEdgeThreshold)) {
    fragColour = vec4(centre, 1.0);
    return;
  }
  // The luma gradient turned by 90 degrees points along the edge.
  vec2 along = vec2(-((ul + ur) - (ll + lr)), (ur + lr) - (ul + ll));
  float reduce = max((ll + lr + ul + ur) * 0.25 * kReduceMultiplier, kReduceMinimum);
  along = clamp(along / (min(abs(along.x), abs(along.y)) + reduce), -kSpanMaximum, kSpanMaximum);
  vec3 twoTaps = 0.5 * (tap(along * (1.0 / 3.0 - 0.5)) + tap(along * (2.0 / 3.0 - 0.5)));
  vec3 fourTaps = 0.5 * twoTaps + 0.25 * (tap(along * -0.5) + tap(along * 0.5));
  float lumaFour = luma(fourTaps);
  fragColour = vec4(lumaFour < lumaMin || lumaFour > lumaMax ? twoTaps : fourTaps, 1.0);
}
