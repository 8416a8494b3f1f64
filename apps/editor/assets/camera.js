// An orbit camera around the mesh: drag to orbit, wheel to zoom, shift-drag on the background to pan.

function normalize(a) { const l = Math.hypot(a[0], a[1], a[2]) || 1; return [a[0] / l, a[1] / l, a[2] / l]; }
function cross(a, b) { return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]; }

export class OrbitCamera {
  constructor(center, radius) {
    this.target = center.slice();
    this.radius = radius;
    this.distance = 2.8 * radius;
    this.yaw = 0.0;
    this.pitch = 0.25;
    this.fov = 40 * Math.PI / 180;
  }

  eye() {
    const c = Math.cos(this.pitch);
    return [
      this.target[0] + this.distance * c * Math.sin(this.yaw),
      this.target[1] + this.distance * Math.sin(this.pitch),
      this.target[2] + this.distance * c * Math.cos(this.yaw),
    ];
  }

  // Orthonormal camera axes: right, up, back (from target towards the eye).
  axes() {
    const eye = this.eye();
    const back = normalize([eye[0] - this.target[0], eye[1] - this.target[1], eye[2] - this.target[2]]);
    const right = normalize(cross([0, 1, 0], back));
    const up = cross(back, right);
    return { eye, right, up, back };
  }

  orbit(dx, dy) {
    this.yaw -= dx * 0.008;
    this.pitch = Math.max(-1.5, Math.min(1.5, this.pitch + dy * 0.008));
  }

  zoom(factor) {
    this.distance = Math.max(0.05 * this.radius, Math.min(50 * this.radius, this.distance * factor));
  }

  pan(dx, dy, height) {
    const { right, up } = this.axes();
    const s = 2 * this.distance * Math.tan(this.fov / 2) / height;
    for (let k = 0; k < 3; k++) this.target[k] += -dx * s * right[k] + dy * s * up[k];
  }

  // Column-major view-projection matrix for an aspect ratio.
  viewProjection(aspect) {
    const { eye, right, up, back } = this.axes();
    const near = Math.max(1e-4 * this.radius, this.distance - 2 * this.radius);
    const far = this.distance + 2 * this.radius;
    const f = 1 / Math.tan(this.fov / 2);
    const view = [
      right[0], up[0], back[0], 0,
      right[1], up[1], back[1], 0,
      right[2], up[2], back[2], 0,
      -(right[0] * eye[0] + right[1] * eye[1] + right[2] * eye[2]),
      -(up[0] * eye[0] + up[1] * eye[1] + up[2] * eye[2]),
      -(back[0] * eye[0] + back[1] * eye[1] + back[2] * eye[2]), 1,
    ];
    const proj = [f / aspect, 0, 0, 0, 0, f, 0, 0, 0, 0, (far + near) / (near - far), -1, 0, 0, 2 * far * near / (near - far), 0];
    const out = new Float32Array(16);
    for (let c = 0; c < 4; c++) {
      for (let r = 0; r < 4; r++) {
        let s = 0;
        for (let k = 0; k < 4; k++) s += proj[k * 4 + r] * view[c * 4 + k];
        out[c * 4 + r] = s;
      }
    }
    return out;
  }

  // The ray through a pixel (x, y in CSS pixels from the top-left of a width x height canvas).
  ray(x, y, width, height) {
    const { eye, right, up, back } = this.axes();
    const t = Math.tan(this.fov / 2);
    const px = (2 * x / width - 1) * t * (width / height);
    const py = (1 - 2 * y / height) * t;
    const dir = normalize([0, 1, 2].map((k) => px * right[k] + py * up[k] - back[k]));
    return { origin: eye, dir };
  }
}
