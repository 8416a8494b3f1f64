// Mesh geometry on the page. Two layers, as the server sends them: the faces the fields and
// constraints refer to (triangles, or polygons of any size) and the display triangles they are
// drawn and picked with. Per face: the field frame of tvf (e1 = the first side projected onto the
// plane normal to the face's vector area, e2 = n x e1), area, corner average; per display
// triangle: its face, its normal and the P1 hat gradients of the colour map's divergence and
// curl. A point of a face is a set of weights over its corners (a SurfacePoint): a pick on a
// display triangle pushes the triangle's barycentric coordinates to the face's corners (a
// corner's weight to that corner, the corner average's weight evenly to all corners).

export const MESH_MAGIC = 0x4d465654; // "TVFM" little-endian

function sub(a, b) { return [a[0] - b[0], a[1] - b[1], a[2] - b[2]]; }
function cross(a, b) { return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]; }
function dot(a, b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
function norm(a) { return Math.sqrt(dot(a, a)); }

// Marks the corner average among a display triangle's sources.
const CORNER_AVERAGE = -1;

export class MeshData {
  // buffer: the body of GET /api/mesh (tvf_editor::payload): u32 magic, u32 V, u32 T,
  // f32 positions[3V], u32 triangles[3T], u32 F, u32 C, u32 cornerCounts[F], u32 corners[C],
  // u32 faceOfTriangle[T].
  constructor(buffer) {
    if (buffer.byteLength < 12) throw new Error('mesh payload: truncated');
    const head = new Uint32Array(buffer, 0, 3);
    if (head[0] !== MESH_MAGIC) throw new Error('mesh payload: bad magic number');
    const V = head[1], T = head[2];
    let at = 12 + 12 * V + 12 * T;
    if (buffer.byteLength < at + 8) throw new Error(`mesh payload: ${buffer.byteLength} bytes, truncated before the faces`);
    const [F, C] = new Uint32Array(buffer, at, 2);
    const expected = at + 8 + 4 * F + 4 * C + 4 * T;
    if (buffer.byteLength !== expected) throw new Error(`mesh payload: ${buffer.byteLength} bytes, expected ${expected}`);
    this.vertexCount = V;
    this.triangleCount = T;
    this.faceCount = F;
    this.positions = new Float32Array(buffer, 12, 3 * V);
    this.triangles = new Uint32Array(buffer, 12 + 12 * V, 3 * T);
    at += 8;
    const counts = new Uint32Array(buffer, at, F);
    this.corners = new Uint32Array(buffer, at + 4 * F, C);
    this.faceOfTriangle = new Uint32Array(buffer, at + 4 * F + 4 * C, T);
    this.cornerStart = new Uint32Array(F + 1);
    for (let f = 0; f < F; f++) this.cornerStart[f + 1] = this.cornerStart[f] + counts[f];
    if (this.cornerStart[F] !== C) throw new Error('mesh payload: corner counts do not add up');
    this.isTriangleMesh = counts.every((n) => n === 3);
    this.computeFaces();
    this.computeTriangles();
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

  // Per face: unit normal along the vector area, frame, area, corner average.
  computeFaces() {
    const F = this.faceCount;
    this.normals = new Float32Array(3 * F);
    this.e1 = new Float32Array(3 * F);
    this.e2 = new Float32Array(3 * F);
    this.areas = new Float64Array(F);
    this.centroids = new Float32Array(3 * F);
    let edgeSum = 0;
    for (let f = 0; f < F; f++) {
      const p = Array.from(this.faceCorners(f), (i) => this.vertex(i));
      const n = p.length;
      let area = [0, 0, 0];
      const middle = [0, 0, 0];
      for (let c = 0; c < n; c++) {
        const s = cross(p[c], p[(c + 1) % n]);
        area = area.map((x, k) => x + 0.5 * s[k]);
        for (let k = 0; k < 3; k++) middle[k] += p[c][k] / n;
      }
      const length = norm(area);
      const normal = length > 0 ? area.map((x) => x / length) : [0, 0, 1];
      const side = sub(p[1], p[0]);
      const inPlane = sub(side, normal.map((x) => x * dot(normal, side)));
      const l = norm(inPlane) || 1;
      const e1 = inPlane.map((x) => x / l);
      const e2 = cross(normal, e1);
      for (let k = 0; k < 3; k++) {
        this.normals[3 * f + k] = normal[k];
        this.e1[3 * f + k] = e1[k];
        this.e2[3 * f + k] = e2[k];
        this.centroids[3 * f + k] = middle[k];
      }
      this.areas[f] = length;
      edgeSum += norm(side);
    }
    this.meanEdge = F > 0 ? edgeSum / F : 1;
  }

  // Per display triangle: normal, the corner of its face at each of its vertices (or the corner
  // average), the gradients of its three P1 hat functions (9 floats) and the vertex masses.
  computeTriangles() {
    const T = this.triangleCount;
    this.triangleNormals = new Float32Array(3 * T);
    this.triangleAreas = new Float64Array(T);
    this.triangleSources = new Int32Array(3 * T);
    this.hatGradients = new Float64Array(9 * T);
    this.vertexMass = new Float64Array(this.vertexCount);
    for (let t = 0; t < T; t++) {
      const ids = [0, 1, 2].map((c) => this.triangles[3 * t + c]);
      const corners = this.faceCorners(this.faceOfTriangle[t]);
      for (let c = 0; c < 3; c++) {
        const at = corners.indexOf(ids[c]);
        this.triangleSources[3 * t + c] = at >= 0 ? at : CORNER_AVERAGE;
      }
      const p = ids.map((i) => this.vertex(i));
      const n2 = cross(sub(p[1], p[0]), sub(p[2], p[0]));
      const twiceArea = norm(n2);
      const n = twiceArea > 0 ? n2.map((x) => x / twiceArea) : [0, 0, 1];
      for (let k = 0; k < 3; k++) this.triangleNormals[3 * t + k] = n[k];
      const area = twiceArea / 2;
      this.triangleAreas[t] = area;
      for (let c = 0; c < 3; c++) {
        const g = twiceArea > 0 ? cross(n, sub(p[(c + 2) % 3], p[(c + 1) % 3])).map((x) => x / twiceArea) : [0, 0, 0];
        for (let k = 0; k < 3; k++) this.hatGradients[9 * t + 3 * c + k] = g[k];
        this.vertexMass[ids[c]] += area / 3;
      }
    }
  }

  faceCorners(f) { return this.corners.subarray(this.cornerStart[f], this.cornerStart[f + 1]); }
  vertex(i) { return [this.positions[3 * i], this.positions[3 * i + 1], this.positions[3 * i + 2]]; }
  normal(f) { return [this.normals[3 * f], this.normals[3 * f + 1], this.normals[3 * f + 2]]; }

  // The weights of face f's corner average.
  centroidWeights(f) {
    const n = this.cornerStart[f + 1] - this.cornerStart[f];
    return new Array(n).fill(1 / n);
  }

  // The point of face f with weights w over its corners (the corner average if w does not fit).
  pointAt(f, w) {
    const corners = this.faceCorners(f);
    const weights = w && w.length === corners.length ? w : this.centroidWeights(f);
    const out = [0, 0, 0];
    corners.forEach((i, c) => { for (let k = 0; k < 3; k++) out[k] += weights[c] * this.positions[3 * i + k]; });
    return out;
  }

  // The tangential part of v in face f (normal to its vector area).
  tangential(f, v) {
    const n = this.normal(f);
    const s = dot(v, n);
    return [v[0] - s * n[0], v[1] - s * n[1], v[2] - s * n[2]];
  }

  // Frame coordinates (2 per face, as sent by the server) -> 3D vectors (3 per face).
  vectorsFromFrames(coords) {
    const F = this.faceCount;
    const out = new Float32Array(3 * F);
    for (let f = 0; f < F; f++) {
      const a = coords[2 * f], b = coords[2 * f + 1];
      for (let k = 0; k < 3; k++) out[3 * f + k] = a * this.e1[3 * f + k] + b * this.e2[3 * f + k];
    }
    return out;
  }

  // Per display triangle scalar for the colour map from per-face vectors: 'magnitude' |u|, or the
  // conforming pointwise divergence -M^-1 G^T M_X u / curl M^-1 G^T J M_X u at the display
  // triangulation's vertices (each triangle carrying its face's vector), averaged over each
  // triangle.
  triangleScalar(mode, vectors) {
    const T = this.triangleCount;
    const out = new Float32Array(T);
    const faceVector = (t) => { const f = this.faceOfTriangle[t]; return [vectors[3 * f], vectors[3 * f + 1], vectors[3 * f + 2]]; };
    if (mode === 'magnitude') {
      for (let t = 0; t < T; t++) out[t] = norm(faceVector(t));
      return out;
    }
    const perVertex = new Float64Array(this.vertexCount);
    for (let t = 0; t < T; t++) {
      let u = faceVector(t);
      const n = [this.triangleNormals[3 * t], this.triangleNormals[3 * t + 1], this.triangleNormals[3 * t + 2]];
      if (mode === 'curl') u = cross(n, u);
      const sign = mode === 'curl' ? 1 : -1;
      for (let c = 0; c < 3; c++) {
        const g = 9 * t + 3 * c;
        const s = this.hatGradients[g] * u[0] + this.hatGradients[g + 1] * u[1] + this.hatGradients[g + 2] * u[2];
        perVertex[this.triangles[3 * t + c]] += sign * this.triangleAreas[t] * s;
      }
    }
    for (let i = 0; i < this.vertexCount; i++) perVertex[i] = this.vertexMass[i] > 0 ? perVertex[i] / this.vertexMass[i] : 0;
    for (let t = 0; t < T; t++) {
      out[t] = (perVertex[this.triangles[3 * t]] + perVertex[this.triangles[3 * t + 1]] + perVertex[this.triangles[3 * t + 2]]) / 3;
    }
    return out;
  }

  // The weights over its face's corners of the point of display triangle t with barycentric
  // coordinates b (non-negative, summing to 1).
  cornerWeights(t, b) {
    const f = this.faceOfTriangle[t];
    const n = this.cornerStart[f + 1] - this.cornerStart[f];
    const w = new Array(n).fill(0);
    for (let c = 0; c < 3; c++) {
      const source = this.triangleSources[3 * t + c];
      if (source === CORNER_AVERAGE) for (let k = 0; k < n; k++) w[k] += b[c] / n;
      else w[source] += b[c];
    }
    return w;
  }

  // Nearest intersection of the ray origin + s dir (s > 0) with the display triangles
  // (Moller-Trumbore), or null: {face, barycentric (weights over the face's corners), triangle,
  // point, distance}.
  pick(origin, dir) {
    let best = null;
    const P = this.positions, Tr = this.triangles;
    for (let t = 0; t < this.triangleCount; t++) {
      const i0 = 3 * Tr[3 * t], i1 = 3 * Tr[3 * t + 1], i2 = 3 * Tr[3 * t + 2];
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
      best = { triangle: t, distance: s, local: [Math.max(0, 1 - u - v), u, v] };
    }
    if (!best) return null;
    best.face = this.faceOfTriangle[best.triangle];
    best.barycentric = this.cornerWeights(best.triangle, best.local);
    best.point = this.pointAt(best.face, best.barycentric);
    return best;
  }

  // Intersection of a ray with the plane of face f (through its corner average, normal to its
  // vector area; for dragging a vector), or null.
  rayPlane(f, origin, dir) {
    const n = this.normal(f);
    const p0 = [this.centroids[3 * f], this.centroids[3 * f + 1], this.centroids[3 * f + 2]];
    const denom = dot(n, dir);
    if (Math.abs(denom) < 1e-12) return null;
    const s = dot(n, sub(p0, origin)) / denom;
    if (s <= 0) return null;
    return [origin[0] + s * dir[0], origin[1] + s * dir[1], origin[2] + s * dir[2]];
  }

  // The sides of every face as line segments (pairs of points), each lifted by `lift` along its
  // face's normal so that it shows over the surface.
  outlineSegments(lift) {
    const out = [];
    for (let f = 0; f < this.faceCount; f++) {
      const corners = this.faceCorners(f);
      const n = this.normal(f).map((x) => x * lift);
      for (let c = 0; c < corners.length; c++) {
        const a = this.vertex(corners[c]), b = this.vertex(corners[(c + 1) % corners.length]);
        out.push(...a.map((x, k) => x + n[k]), ...b.map((x, k) => x + n[k]));
      }
    }
    return new Float32Array(out);
  }
}

export const vec = { sub, cross, dot, norm };
