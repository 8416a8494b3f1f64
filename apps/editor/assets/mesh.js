// Mesh geometry on the page: per-face frames (the field convention of tvf: e1 = normalize(p1 - p0),
// e2 = n x e1), face areas, vertex masses, picking by ray-triangle intersection, and the
// per-face scalars of the colour map (magnitude, conforming divergence and curl).

export const MESH_MAGIC = 0x4d465654; // "TVFM" little-endian

function sub(a, b) { return [a[0] - b[0], a[1] - b[1], a[2] - b[2]]; }
function cross(a, b) { return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]; }
function dot(a, b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
function norm(a) { return Math.sqrt(dot(a, a)); }

export class MeshData {
  // buffer: the body of GET /api/mesh: u32 magic, u32 V, u32 F, f32 positions[3V], u32 faces[3F].
  constructor(buffer) {
    const head = new Uint32Array(buffer, 0, 3);
    if (head[0] !== MESH_MAGIC) throw new Error('mesh payload: bad magic number');
    this.vertexCount = head[1];
    this.faceCount = head[2];
    const V = this.vertexCount, F = this.faceCount;
    const expected = 12 + 12 * V + 12 * F;
    if (buffer.byteLength !== expected) throw new Error(`mesh payload: ${buffer.byteLength} bytes, expected ${expected}`);
    this.positions = new Float32Array(buffer, 12, 3 * V);
    this.faces = new Uint32Array(buffer, 12 + 12 * V, 3 * F);
    this.normals = new Float32Array(3 * F);
    this.e1 = new Float32Array(3 * F);
    this.e2 = new Float32Array(3 * F);
    this.areas = new Float64Array(F);
    this.centroids = new Float32Array(3 * F);
    // Gradients of the three P1 hat functions per face (9 floats per face), for div/curl.
    this.hatGradients = new Float64Array(9 * F);
    this.vertexMass = new Float64Array(V);
    let edgeSum = 0;
    for (let t = 0; t < F; t++) {
      const p = [0, 1, 2].map((c) => this.vertex(this.faces[3 * t + c]));
      const n2 = cross(sub(p[1], p[0]), sub(p[2], p[0]));
      const twiceArea = norm(n2);
      const n = twiceArea > 0 ? n2.map((x) => x / twiceArea) : [0, 0, 1];
      const d01 = sub(p[1], p[0]);
      const l01 = norm(d01) || 1;
      const e1 = d01.map((x) => x / l01);
      const e2 = cross(n, e1);
      for (let k = 0; k < 3; k++) {
        this.normals[3 * t + k] = n[k];
        this.e1[3 * t + k] = e1[k];
        this.e2[3 * t + k] = e2[k];
        this.centroids[3 * t + k] = (p[0][k] + p[1][k] + p[2][k]) / 3;
      }
      const area = twiceArea / 2;
      this.areas[t] = area;
      for (let c = 0; c < 3; c++) {
        const g = twiceArea > 0 ? cross(n, sub(p[(c + 2) % 3], p[(c + 1) % 3])).map((x) => x / twiceArea) : [0, 0, 0];
        for (let k = 0; k < 3; k++) this.hatGradients[9 * t + 3 * c + k] = g[k];
        this.vertexMass[this.faces[3 * t + c]] += area / 3;
      }
      edgeSum += l01;
    }
    this.meanEdge = F > 0 ? edgeSum / F : 1;
    const lo = [Infinity, Infinity, Infinity], hi = [-Infinity, -Infinity, -Infinity];
    for (let i = 0; i < V; i++) {
      for (let k = 0; k < 3; k++) {
        lo[k] = Math.min(lo[k], this.positions[3 * i + k]);
        hi[k] = Math.max(hi[k], this.positions[3 * i + k]);
      }
    }
    this.center = [0, 1, 2].map((k) => (lo[k] + hi[k]) / 2);
    this.radius = Math.max(1e-9, norm(sub(hi, lo)) / 2);
  }

  vertex(i) { return [this.positions[3 * i], this.positions[3 * i + 1], this.positions[3 * i + 2]]; }
  normal(t) { return [this.normals[3 * t], this.normals[3 * t + 1], this.normals[3 * t + 2]]; }

  // The point of face t with barycentric coordinates b.
  pointAt(t, b) {
    const p = [0, 1, 2].map((c) => this.vertex(this.faces[3 * t + c]));
    return [0, 1, 2].map((k) => b[0] * p[0][k] + b[1] * p[1][k] + b[2] * p[2][k]);
  }

  // The tangential part of v in face t.
  tangential(t, v) {
    const n = this.normal(t);
    const s = dot(v, n);
    return [v[0] - s * n[0], v[1] - s * n[1], v[2] - s * n[2]];
  }

  // Frame coordinates (2 per face, as sent by the server) -> 3D vectors (3 per face).
  vectorsFromFrames(coords) {
    const F = this.faceCount;
    const out = new Float32Array(3 * F);
    for (let t = 0; t < F; t++) {
      const a = coords[2 * t], b = coords[2 * t + 1];
      for (let k = 0; k < 3; k++) out[3 * t + k] = a * this.e1[3 * t + k] + b * this.e2[3 * t + k];
    }
    return out;
  }

  // Per-face scalar for the colour map: 'magnitude' |u|, or the conforming pointwise
  // divergence -M^-1 G^T M_X u / curl M^-1 G^T J M_X u at the vertices, averaged over each face.
  faceScalar(mode, vectors) {
    const F = this.faceCount;
    const out = new Float32Array(F);
    if (mode === 'magnitude') {
      for (let t = 0; t < F; t++) {
        const x = vectors[3 * t], y = vectors[3 * t + 1], z = vectors[3 * t + 2];
        out[t] = Math.sqrt(x * x + y * y + z * z);
      }
      return out;
    }
    const perVertex = new Float64Array(this.vertexCount);
    for (let t = 0; t < F; t++) {
      let u = [vectors[3 * t], vectors[3 * t + 1], vectors[3 * t + 2]];
      if (mode === 'curl') u = cross(this.normal(t), u);
      const sign = mode === 'curl' ? 1 : -1;
      for (let c = 0; c < 3; c++) {
        const g = 9 * t + 3 * c;
        const s = this.hatGradients[g] * u[0] + this.hatGradients[g + 1] * u[1] + this.hatGradients[g + 2] * u[2];
        perVertex[this.faces[3 * t + c]] += sign * this.areas[t] * s;
      }
    }
    for (let i = 0; i < this.vertexCount; i++) perVertex[i] = this.vertexMass[i] > 0 ? perVertex[i] / this.vertexMass[i] : 0;
    for (let t = 0; t < F; t++) {
      out[t] = (perVertex[this.faces[3 * t]] + perVertex[this.faces[3 * t + 1]] + perVertex[this.faces[3 * t + 2]]) / 3;
    }
    return out;
  }

  // Nearest intersection of the ray origin + s dir (s > 0) with the surface (Moller-Trumbore),
  // or null: {face, point, barycentric, distance}.
  pick(origin, dir) {
    let best = null;
    const P = this.positions, Fa = this.faces;
    for (let t = 0; t < this.faceCount; t++) {
      const i0 = 3 * Fa[3 * t], i1 = 3 * Fa[3 * t + 1], i2 = 3 * Fa[3 * t + 2];
      const e1x = P[i1] - P[i0], e1y = P[i1 + 1] - P[i0 + 1], e1z = P[i1 + 2] - P[i0 + 2];
      const e2x = P[i2] - P[i0], e2y = P[i2 + 1] - P[i0 + 1], e2z = P[i2 + 2] - P[i0 + 2];
      const px = dir[1] * e2z - dir[2] * e2y, py = dir[2] * e2x - dir[0] * e2z, pz = dir[0] * e2y - dir[1] * e2x;
      const det = e1x * px + e1y * py + e1z * pz;
      if (Math.abs(det) < 1e-20) continue;
      const inv = 1 / det;
      const sx = origin[0] - P[i0], sy = origin[1] - P[i0 + 1], sz = origin[2] - P[i0 + 2];
      const u = (sx * px + sy * py + sz * pz) * inv;
      if (u < 0 || u > 1) continue;
      const qx = sy * e1z - sz * e1y, qy = sz * e1x - sx * e1z, qz = sx * e1y - sy * e1x;
      const v = (dir[0] * qx + dir[1] * qy + dir[2] * qz) * inv;
      if (v < 0 || u + v > 1) continue;
      const s = (e2x * qx + e2y * qy + e2z * qz) * inv;
      if (s <= 0 || (best && s >= best.distance)) continue;
      best = { face: t, distance: s, barycentric: [1 - u - v, u, v] };
    }
    if (best) best.point = this.pointAt(best.face, best.barycentric);
    return best;
  }

  // Intersection of a ray with the plane of face t (for dragging a vector), or null.
  rayPlane(t, origin, dir) {
    const n = this.normal(t);
    const p0 = this.vertex(this.faces[3 * t]);
    const denom = dot(n, dir);
    if (Math.abs(denom) < 1e-12) return null;
    const s = dot(n, sub(p0, origin)) / denom;
    if (s <= 0) return null;
    return [origin[0] + s * dir[0], origin[1] + s * dir[1], origin[2] + s * dir[2]];
  }
}

export const vec = { sub, cross, dot, norm };
