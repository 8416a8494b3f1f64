// WebGL2 drawing: the shaded surface (the display triangles) with a colour per triangle, line
// sets (arrows, fur, polygon outlines, constraint glyphs) and point markers.

const SURFACE_VS = `#version 300 es
in vec3 position; in vec3 normal; in vec3 color;
uniform mat4 viewProjection;
out vec3 vNormal; out vec3 vColor;
void main() { vNormal = normal; vColor = color; gl_Position = viewProjection * vec4(position, 1.0); }`;
const SURFACE_FS = `#version 300 es
precision highp float;
in vec3 vNormal; in vec3 vColor;
uniform vec3 lightDir;
out vec4 fragColor;
void main() {
  vec3 n = normalize(vNormal);
  float d = abs(dot(n, lightDir));
  fragColor = vec4(vColor * (0.35 + 0.65 * d), 1.0);
}`;
const LINE_VS = `#version 300 es
in vec3 position; in vec3 color;
uniform mat4 viewProjection; uniform float pointSize;
out vec3 vColor;
void main() { vColor = color; gl_PointSize = pointSize; gl_Position = viewProjection * vec4(position, 1.0); }`;
const LINE_FS = `#version 300 es
precision highp float;
in vec3 vColor; uniform float roundPoints;
out vec4 fragColor;
void main() {
  if (roundPoints > 0.5) { vec2 q = gl_PointCoord - vec2(0.5); if (dot(q, q) > 0.25) discard; }
  fragColor = vec4(vColor, 1.0);
}`;

function compile(gl, vs, fs) {
  const program = gl.createProgram();
  for (const [type, src] of [[gl.VERTEX_SHADER, vs], [gl.FRAGMENT_SHADER, fs]]) {
    const s = gl.createShader(type);
    gl.shaderSource(s, src);
    gl.compileShader(s);
    if (!gl.getShaderParameter(s, gl.COMPILE_STATUS)) throw new Error('shader: ' + gl.getShaderInfoLog(s));
    gl.attachShader(program, s);
  }
  gl.linkProgram(program);
  if (!gl.getProgramParameter(program, gl.LINK_STATUS)) throw new Error('program: ' + gl.getProgramInfoLog(program));
  return program;
}

export class Renderer {
  constructor(canvas) {
    const gl = canvas.getContext('webgl2', { antialias: true, preserveDrawingBuffer: true });
    if (!gl) throw new Error('WebGL2 is not available in this browser');
    this.gl = gl;
    this.canvas = canvas;
    this.surface = compile(gl, SURFACE_VS, SURFACE_FS);
    this.lines = compile(gl, LINE_VS, LINE_FS);
    this.layers = new Map(); // name -> {vao, buffers, count, mode, size}
    gl.enable(gl.DEPTH_TEST);
    gl.clearColor(0.96, 0.96, 0.97, 1);
  }

  buffer(data) {
    const gl = this.gl;
    const b = gl.createBuffer();
    gl.bindBuffer(gl.ARRAY_BUFFER, b);
    gl.bufferData(gl.ARRAY_BUFFER, data, gl.DYNAMIC_DRAW);
    return b;
  }

  attribute(program, name, buffer) {
    const gl = this.gl;
    const loc = gl.getAttribLocation(program, name);
    gl.bindBuffer(gl.ARRAY_BUFFER, buffer);
    gl.enableVertexAttribArray(loc);
    gl.vertexAttribPointer(loc, 3, gl.FLOAT, false, 0, 0);
  }

  // Uploads the mesh's display triangles as unindexed flat-shaded triangles (3 vertices each).
  setMesh(mesh) {
    const gl = this.gl;
    const F = mesh.triangleCount;
    const pos = new Float32Array(9 * F), nor = new Float32Array(9 * F);
    for (let t = 0; t < F; t++) {
      for (let c = 0; c < 3; c++) {
        const i = mesh.triangles[3 * t + c];
        for (let k = 0; k < 3; k++) {
          pos[9 * t + 3 * c + k] = mesh.positions[3 * i + k];
          nor[9 * t + 3 * c + k] = mesh.triangleNormals[3 * t + k];
        }
      }
    }
    this.triangleCount = F;
    this.surfaceVao = gl.createVertexArray();
    gl.bindVertexArray(this.surfaceVao);
    this.attribute(this.surface, 'position', this.buffer(pos));
    this.attribute(this.surface, 'normal', this.buffer(nor));
    this.colorBuffer = this.buffer(new Float32Array(9 * F).fill(0.8));
    this.attribute(this.surface, 'color', this.colorBuffer);
    gl.bindVertexArray(null);
  }

  // triangleColors: Float32Array of 3 floats (rgb in [0, 1]) per display triangle.
  setTriangleColors(triangleColors) {
    const gl = this.gl;
    const F = this.triangleCount;
    const data = new Float32Array(9 * F);
    for (let t = 0; t < F; t++) {
      for (let c = 0; c < 3; c++) for (let k = 0; k < 3; k++) data[9 * t + 3 * c + k] = triangleColors[3 * t + k];
    }
    gl.bindBuffer(gl.ARRAY_BUFFER, this.colorBuffer);
    gl.bufferData(gl.ARRAY_BUFFER, data, gl.DYNAMIC_DRAW);
  }

  // A named layer of lines (mode 'lines', pairs of points) or points (mode 'points').
  setLayer(name, positions, colors, mode = 'lines', size = 1) {
    const gl = this.gl;
    let layer = this.layers.get(name);
    if (!layer) {
      layer = { vao: gl.createVertexArray(), pos: gl.createBuffer(), col: gl.createBuffer() };
      gl.bindVertexArray(layer.vao);
      this.attribute(this.lines, 'position', layer.pos);
      this.attribute(this.lines, 'color', layer.col);
      gl.bindVertexArray(null);
      this.layers.set(name, layer);
    }
    gl.bindBuffer(gl.ARRAY_BUFFER, layer.pos);
    gl.bufferData(gl.ARRAY_BUFFER, positions, gl.DYNAMIC_DRAW);
    gl.bindBuffer(gl.ARRAY_BUFFER, layer.col);
    gl.bufferData(gl.ARRAY_BUFFER, colors, gl.DYNAMIC_DRAW);
    layer.count = positions.length / 3;
    layer.mode = mode;
    layer.size = size;
    layer.visible = true;
  }

  setVisible(name, visible) {
    const layer = this.layers.get(name);
    if (layer) layer.visible = visible;
  }

  draw(camera) {
    const gl = this.gl;
    const dpr = window.devicePixelRatio || 1;
    const w = Math.max(1, Math.round(this.canvas.clientWidth * dpr));
    const h = Math.max(1, Math.round(this.canvas.clientHeight * dpr));
    if (this.canvas.width !== w || this.canvas.height !== h) { this.canvas.width = w; this.canvas.height = h; }
    gl.viewport(0, 0, w, h);
    gl.clear(gl.COLOR_BUFFER_BIT | gl.DEPTH_BUFFER_BIT);
    const vp = camera.viewProjection(w / h);
    const { back } = camera.axes();
    if (this.surfaceVao) {
      gl.useProgram(this.surface);
      gl.uniformMatrix4fv(gl.getUniformLocation(this.surface, 'viewProjection'), false, vp);
      gl.uniform3fv(gl.getUniformLocation(this.surface, 'lightDir'), new Float32Array(back));
      gl.enable(gl.POLYGON_OFFSET_FILL);
      gl.polygonOffset(1, 1);
      gl.bindVertexArray(this.surfaceVao);
      gl.drawArrays(gl.TRIANGLES, 0, 3 * this.triangleCount);
      gl.disable(gl.POLYGON_OFFSET_FILL);
    }
    gl.useProgram(this.lines);
    gl.uniformMatrix4fv(gl.getUniformLocation(this.lines, 'viewProjection'), false, vp);
    for (const layer of this.layers.values()) {
      if (!layer.visible || !layer.count) continue;
      gl.uniform1f(gl.getUniformLocation(this.lines, 'pointSize'), layer.size * dpr);
      gl.uniform1f(gl.getUniformLocation(this.lines, 'roundPoints'), layer.mode === 'points' ? 1 : 0);
      gl.bindVertexArray(layer.vao);
      gl.drawArrays(layer.mode === 'points' ? gl.POINTS : gl.LINES, 0, layer.count);
    }
    gl.bindVertexArray(null);
  }
}

// Colour maps (the same control points as tvf-render): t in [0, 1] -> [r, g, b] in [0, 1].
const VIRIDIS = [[68, 1, 84], [71, 44, 122], [59, 81, 139], [44, 113, 142], [33, 144, 141], [39, 173, 129], [92, 200, 99], [170, 220, 50], [253, 231, 37]];
const BLUE_WHITE_RED = [[33, 72, 170], [120, 160, 220], [247, 247, 247], [230, 130, 100], [178, 24, 43]];

export function colorMap(diverging, t) {
  const table = diverging ? BLUE_WHITE_RED : VIRIDIS;
  const x = (Number.isFinite(t) ? Math.min(1, Math.max(0, t)) : 0) * (table.length - 1);
  const i = Math.min(table.length - 2, Math.floor(x));
  const f = x - i;
  return [0, 1, 2].map((k) => (table[i][k] * (1 - f) + table[i + 1][k] * f) / 255);
}

// Colours for a scalar per triangle, with the range fitted as tvf-render does ([min, max], or
// [-m, m] for a diverging map). Returns {colors, min, max}.
export function scalarColors(values, diverging) {
  let lo = Infinity, hi = -Infinity;
  for (const v of values) { if (Number.isFinite(v)) { lo = Math.min(lo, v); hi = Math.max(hi, v); } }
  if (lo > hi) { lo = diverging ? -1 : 0; hi = 1; }
  if (diverging) { const m = Math.max(Math.abs(lo), Math.abs(hi)) || 1; lo = -m; hi = m; } else if (hi <= lo) { hi = lo + 1; }
  const colors = new Float32Array(3 * values.length);
  for (let t = 0; t < values.length; t++) {
    const c = colorMap(diverging, (values[t] - lo) / (hi - lo));
    colors[3 * t] = c[0]; colors[3 * t + 1] = c[1]; colors[3 * t + 2] = c[2];
  }
  return { colors, min: lo, max: hi };
}
