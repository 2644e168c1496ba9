// camera.js — the camera as the programs take it, computed exactly as the desktop viewer computes
// it (nut/camera.hpp RayGenerator and fitCamera, viewer/frame_view.hpp FrameView): the ray basis
// the caster rebuilds per pixel, the projections of proxy boxes and meshes, the window-depth
// mapping, and the frustum test of culling. Everything the GPU sees is relative to the eye.

const sub = (a, b) => [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
const dot = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
const cross = (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
const length = (a) => Math.sqrt(dot(a, a));
const normalize = (a) => {
  const l = length(a);
  return [a[0] / l, a[1] / l, a[2] / l];
};
export { sub, dot, cross, length, normalize };

// The direction the default camera looks from (nut::kDefaultViewFrom).
const DEFAULT_VIEW_FROM = [0.55, 0.45, 1.0];

// A camera that sees the whole box: nut::fitCamera. { eye, target, up, fovYDeg, width, height }.
export function fitCamera(box, width, height, fovYDeg = 40) {
  const target = [0, 1, 2].map((a) => 0.5 * (box.min[a] + box.max[a]));
  const radius = Math.max(0.5 * length(sub(box.max, box.min)), 1e-3);
  const halfY = (0.5 * fovYDeg * Math.PI) / 180;
  const halfX = Math.atan((Math.tan(halfY) * width) / height);
  const distance = (1.05 * radius) / Math.sin(Math.min(halfX, halfY));
  const from = normalize(DEFAULT_VIEW_FROM);
  return { eye: target.map((t, a) => t + distance * from[a]), target, up: [0, 1, 0], fovYDeg, width, height };
}

// Near and far planes as nut-viewer sets them for a city of box `box`: far reaches past the whole
// city from the eye; near keeps depth precision over that range.
export function depthRange(eye, box) {
  const centre = [0, 1, 2].map((a) => 0.5 * (box.min[a] + box.max[a]));
  const farM = length(sub(eye, centre)) + length(sub(box.max, box.min)) + 1;
  return { nearM: Math.max(0.05, farM * 1e-5), farM };
}

// A perspective projection (column-major 4x4) with the camera's own tan of the half fields of
// view; farM = Infinity gives an infinitely distant far plane.
function projection(tanHalfX, tanHalfY, nearM, farM) {
  const p = new Float64Array(16);
  p[0] = 1 / tanHalfX;
  p[5] = 1 / tanHalfY;
  p[11] = -1;
  if (farM === Infinity) {
    p[10] = -1;
    p[14] = -2 * nearM;
  } else {
    p[10] = -(farM + nearM) / (farM - nearM);
    p[14] = (-2 * farM * nearM) / (farM - nearM);
  }
  return p;
}

function multiply(a, b) {
  const out = new Float64Array(16);
  for (let c = 0; c < 4; ++c)
    for (let r = 0; r < 4; ++r) {
      let s = 0;
      for (let k = 0; k < 4; ++k) s += a[k * 4 + r] * b[c * 4 + k];
      out[c * 4 + r] = s;
    }
  return out;
}

// camera: { eye, target, up, fovYDeg, width, height, nearM, farM }.
export class FrameView {
  constructor(camera) {
    this.camera = camera;
    this.forward = normalize(sub(camera.target, camera.eye));
    this.right = normalize(cross(this.forward, camera.up));
    this.up = cross(this.right, this.forward);
    this.tanHalfY = Math.tan((0.5 * camera.fovYDeg * Math.PI) / 180);
    this.tanHalfX = (this.tanHalfY * camera.width) / camera.height;
    this.pixelAngle = (2 * this.tanHalfY) / camera.height;
    // Rows of the rotation are the eye axes: right, up, backwards.
    const eyeFromWorld = new Float64Array(16);
    for (let i = 0; i < 3; ++i) {
      eyeFromWorld[i * 4 + 0] = this.right[i];
      eyeFromWorld[i * 4 + 1] = this.up[i];
      eyeFromWorld[i * 4 + 2] = -this.forward[i];
    }
    eyeFromWorld[15] = 1;
    const { nearM: n, farM: f } = camera;
    this.clipFromEye = new Float32Array(multiply(projection(this.tanHalfX, this.tanHalfY, n, f), eyeFromWorld));
    this.proxyClipFromEye = new Float32Array(multiply(projection(this.tanHalfX, this.tanHalfY, 1e-3, Infinity), eyeFromWorld));
    this.depthFromEyeZ = [(f + n) / (f - n), (2 * f * n) / (f - n)];
  }

  // Whether any part of the box may lie in the view (the four side planes, near and far): false
  // only when all eight corners are outside one plane (viewer::mayBeVisible).
  mayBeVisible(box) {
    const { eye, nearM, farM } = this.camera;
    const corners = [];
    for (let c = 0; c < 8; ++c)
      corners.push(sub([c & 1 ? box.max[0] : box.min[0], c & 2 ? box.max[1] : box.min[1], c & 4 ? box.max[2] : box.min[2]], eye));
    const allOutside = (value) => corners.every((p) => value(p) < 0);
    const tx = this.tanHalfX, ty = this.tanHalfY, f = this.forward, r = this.right, u = this.up;
    return !(
      allOutside((p) => tx * dot(p, f) - dot(p, r)) || allOutside((p) => tx * dot(p, f) + dot(p, r)) ||
      allOutside((p) => ty * dot(p, f) - dot(p, u)) || allOutside((p) => ty * dot(p, f) + dot(p, u)) ||
      allOutside((p) => dot(p, f) - nearM) || allOutside((p) => farM - dot(p, f))
    );
  }
}
