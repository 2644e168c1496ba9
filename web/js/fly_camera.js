// fly_camera.js — a fly camera for the browser viewer: drag to look around, W A S D (or the
// arrows) to move, E and Q (or Space and Shift) to rise and sink, the wheel to change speed.
// The camera keeps its eye and a unit view direction; up is +y, as in every nut city.

import { cross, normalize } from './camera.js';

export class FlyCamera {
  // camera: { eye, target, ... }; speedMps: metres per second at the start.
  constructor(element, camera, speedMps) {
    this.eye = [...camera.eye];
    const d = normalize([0, 1, 2].map((a) => camera.target[a] - camera.eye[a]));
    this.yaw = Math.atan2(d[0], -d[2]);
    this.pitch = Math.asin(Math.max(-1, Math.min(1, d[1])));
    this.speed = speedMps;
    this.keys = new Set();
    this.changed = false;
    element.addEventListener('pointerdown', (e) => {
      element.setPointerCapture(e.pointerId);
      this.dragging = { x: e.clientX, y: e.clientY };
    });
    element.addEventListener('pointerup', () => (this.dragging = null));
    element.addEventListener('pointermove', (e) => {
      if (!this.dragging) return;
      this.yaw += 0.005 * (e.clientX - this.dragging.x);
      this.pitch = Math.max(-1.55, Math.min(1.55, this.pitch - 0.005 * (e.clientY - this.dragging.y)));
      this.dragging = { x: e.clientX, y: e.clientY };
      this.changed = true;
    });
    element.addEventListener('wheel', (e) => {
      e.preventDefault();
      this.speed *= e.deltaY < 0 ? 1.25 : 0.8;
    }, { passive: false });
    window.addEventListener('keydown', (e) => this.keys.add(e.code));
    window.addEventListener('keyup', (e) => this.keys.delete(e.code));
    window.addEventListener('blur', () => this.keys.clear());
  }

  direction() {
    return [Math.sin(this.yaw) * Math.cos(this.pitch), Math.sin(this.pitch), -Math.cos(this.yaw) * Math.cos(this.pitch)];
  }

  // Moves by the keys held over `seconds`; returns whether the view changed since the last call.
  update(seconds) {
    const forward = this.direction();
    const right = normalize(cross(forward, [0, 1, 0]));
    const axis = (plus, minus) => (plus.some((k) => this.keys.has(k)) ? 1 : 0) - (minus.some((k) => this.keys.has(k)) ? 1 : 0);
    const ahead = axis(['KeyW', 'ArrowUp'], ['KeyS', 'ArrowDown']);
    const side = axis(['KeyD', 'ArrowRight'], ['KeyA', 'ArrowLeft']);
    const rise = axis(['KeyE', 'Space'], ['KeyQ', 'ShiftLeft', 'ShiftRight']);
    if (ahead || side || rise) {
      const step = this.speed * seconds;
      for (let a = 0; a < 3; ++a) this.eye[a] += step * (ahead * forward[a] + side * right[a] + (a === 1 ? rise : 0));
      this.changed = true;
    }
    const changed = this.changed;
    this.changed = false;
    return changed;
  }

  target() {
    const d = this.direction();
    return this.eye.map((e, a) => e + d[a]);
  }
}
