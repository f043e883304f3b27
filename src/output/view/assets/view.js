// rapidvc view: replays a run (or follows a live one) in 3D with WebGL, beside the RAPID
// source, the TP output, the events and the EGM / path-correction curves. Plain JavaScript,
// no libraries. The data format is written by src/output/view/encode.rs.
'use strict';
(function () {
  const T0 = performance.now();
  const $ = (id) => document.getElementById(id);
  const DATA_VERSION = 1;
  const STATE_NAMES = ['DISCONNECTED', 'CONNECTED', 'RUNNING'];
  const STATE_COLORS = ['#59636e', '#4f8fe6', '#4cc27a'];

  // ---------------------------------------------------------------- the run model --------
  // Columns of plain numbers: rows (motion cycles), EGM samples, path-correction samples.
  const M = {
    scene: null, t: [], j: [[], [], [], [], [], []], p: [[], [], []], q: [[], [], [], []],
    v: [], i: [], instrs: [], log: [], egm: null, egmStates: [], path: null,
    endUs: 0, finished: false, live: false, maxSpeed: 1,
  };

  function emptyEgm() {
    return { t: [], axes: [], state: [], lim: [], hasRef: [], ref: [[], [], [], [], [], []],
      fb: [[], [], [], [], [], []] };
  }
  function emptyPath() {
    return { t: [], s: [], start: [], corr: [[], []], hasMeas: [], meas: [[], []], prog: [[], [], []],
      cor: [[], [], []] };
  }

  // A column stored as differences of quantised integers (see encode.rs).
  function decode(col, scale, out) {
    let acc = 0;
    for (let k = 0; k < col.length; k++) { acc += col[k]; out.push(acc / scale); }
    return out;
  }

  function decodeTime(col, out) {
    let acc = 0;
    for (let k = 0; k < col.d.length; k++) { acc += col.d[k]; out.push(acc * col.unit); }
    return out;
  }

  function load(data) {
    if (!data || data.version !== DATA_VERSION) {
      throw new Error('this page holds data of another rapidvc version');
    }
    M.scene = data.scene;
    M.live = !!data.live;
    M.t = []; M.j = [[], [], [], [], [], []]; M.p = [[], [], []]; M.q = [[], [], [], []];
    M.v = []; M.i = [];
    const r = data.rows;
    decodeTime(r.t, M.t);
    for (let a = 0; a < 6; a++) decode(r.j[a], 1e3, M.j[a]);
    for (let a = 0; a < 3; a++) decode(r.p[a], 1e2, M.p[a]);
    for (let a = 0; a < 4; a++) decode(r.q[a], 1e4, M.q[a]);
    decode(r.v, 1e1, M.v);
    decode(r.i, 1, M.i);
    M.instrs = data.instrs.slice();
    M.log = data.log.slice();
    M.egm = emptyEgm();
    const e = data.egm;
    decodeTime(e.t, M.egm.t); decode(e.axes, 1, M.egm.axes); decode(e.state, 1, M.egm.state);
    decode(e.lim, 1, M.egm.lim); decode(e.hasRef, 1, M.egm.hasRef);
    for (let a = 0; a < 6; a++) { decode(e.ref[a], 1e3, M.egm.ref[a]); decode(e.fb[a], 1e3, M.egm.fb[a]); }
    M.egmStates = data.egmStates.slice();
    M.path = emptyPath();
    const p = data.path;
    decodeTime(p.t, M.path.t); decode(p.s, 1e2, M.path.s); decode(p.start, 1, M.path.start); decode(p.hasMeas, 1, M.path.hasMeas);
    for (let a = 0; a < 2; a++) { decode(p.corr[a], 1e3, M.path.corr[a]); decode(p.meas[a], 1e3, M.path.meas[a]); }
    for (let a = 0; a < 3; a++) { decode(p.prog[a], 1e2, M.path.prog[a]); decode(p.cor[a], 1e2, M.path.cor[a]); }
    M.endUs = Math.max(data.endUs || 0, M.t.length ? M.t[M.t.length - 1] : 0);
    M.finished = !!data.finished;
    M.maxSpeed = speedScale();
  }

  // The speed the colour scale tops out at: the 99th percentile of the run (at least 1 mm/s).
  function speedScale() {
    const v = M.v.filter((x) => x > 0).sort((a, b) => a - b);
    if (!v.length) return 1;
    return Math.max(1, v[Math.min(v.length - 1, Math.floor(v.length * 0.99))]);
  }

  function appendRow(m) {
    const n = M.t.length;
    if (n && m.t <= M.t[n - 1]) return false;
    M.t.push(m.t);
    for (let a = 0; a < 6; a++) M.j[a].push(m.j[a]);
    for (let a = 0; a < 3; a++) M.p[a].push(m.p[a]);
    let q = m.q;
    if (n) {
      const d = q[0] * M.q[0][n - 1] + q[1] * M.q[1][n - 1] + q[2] * M.q[2][n - 1] + q[3] * M.q[3][n - 1];
      if (d < 0) q = q.map((c) => -c);
    }
    for (let a = 0; a < 4; a++) M.q[a].push(q[a]);
    M.v.push(m.v);
    M.i.push(m.i);
    M.endUs = Math.max(M.endUs, m.t);
    if (m.v > M.maxSpeed) M.maxSpeed = m.v;
    return true;
  }

  // Index of the last element of the sorted array `a` that is <= x (-1 when none).
  function floorIndex(a, x) {
    let lo = 0; let hi = a.length - 1; let k = -1;
    while (lo <= hi) {
      const mid = (lo + hi) >> 1;
      if (a[mid] <= x) { k = mid; lo = mid + 1; } else { hi = mid - 1; }
    }
    return k;
  }

  // The robot at time t (µs): joints and TCP interpolated linearly between the kept rows
  // (within the recording's tolerance of every motion cycle), the instruction of the row
  // at or before t.
  function sample(t) {
    const n = M.t.length;
    if (!n) return null;
    let k = floorIndex(M.t, t);
    if (k < 0) k = 0;
    const k2 = Math.min(k + 1, n - 1);
    const span = M.t[k2] - M.t[k];
    const f = span > 0 ? Math.min(1, Math.max(0, (t - M.t[k]) / span)) : 0;
    const lerp = (c) => c[k] + (c[k2] - c[k]) * f;
    const joints = M.j.map(lerp);
    const tcp = M.p.map(lerp);
    let q = M.q.map(lerp);
    const qn = Math.hypot(q[0], q[1], q[2], q[3]) || 1;
    q = q.map((c) => c / qn);
    return { t, k, joints, tcp, quat: q, speed: lerp(M.v), instr: M.i[k] };
  }

  // ---------------------------------------------------------------- matrices -------------
  // 4×4 matrices, column-major (as WebGL takes them), in plain arrays of doubles.
  function m4() { return [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]; }
  function mul(a, b) {
    const o = new Array(16);
    for (let c = 0; c < 4; c++) {
      for (let r = 0; r < 4; r++) {
        o[c * 4 + r] = a[r] * b[c * 4] + a[4 + r] * b[c * 4 + 1] + a[8 + r] * b[c * 4 + 2] + a[12 + r] * b[c * 4 + 3];
      }
    }
    return o;
  }
  function trans(x, y, z) { const m = m4(); m[12] = x; m[13] = y; m[14] = z; return m; }
  function rotY(a) { const c = Math.cos(a); const s = Math.sin(a); return [c, 0, -s, 0, 0, 1, 0, 0, s, 0, c, 0, 0, 0, 0, 1]; }
  function rotZ(a) { const c = Math.cos(a); const s = Math.sin(a); return [c, s, 0, 0, -s, c, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]; }
  // A pose [x, y, z, qw, qx, qy, qz] (mm, RAPID quaternion order).
  function pose(p) {
    const [x, y, z, w, i, j, k] = p;
    return [
      1 - 2 * (j * j + k * k), 2 * (i * j + w * k), 2 * (i * k - w * j), 0,
      2 * (i * j - w * k), 1 - 2 * (i * i + k * k), 2 * (j * k + w * i), 0,
      2 * (i * k + w * j), 2 * (j * k - w * i), 1 - 2 * (i * i + j * j), 0,
      x, y, z, 1,
    ];
  }
  function origin(m) { return [m[12], m[13], m[14]]; }
  function axis(m, c) { return [m[c * 4], m[c * 4 + 1], m[c * 4 + 2]]; }
  function sub3(a, b) { return [a[0] - b[0], a[1] - b[1], a[2] - b[2]]; }
  function add3(a, b) { return [a[0] + b[0], a[1] + b[1], a[2] + b[2]]; }
  function scale3(a, s) { return [a[0] * s, a[1] * s, a[2] * s]; }
  function dot3(a, b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
  function cross3(a, b) { return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]; }
  function len3(a) { return Math.hypot(a[0], a[1], a[2]); }
  function norm3(a) { const l = len3(a) || 1; return [a[0] / l, a[1] / l, a[2] / l]; }
  function perspective(fovy, aspect, near, far) {
    const f = 1 / Math.tan(fovy / 2); const nf = 1 / (near - far);
    return [f / aspect, 0, 0, 0, 0, f, 0, 0, 0, 0, (far + near) * nf, -1, 0, 0, 2 * far * near * nf, 0];
  }
  function lookAt(eye, target, up) {
    const z = norm3(sub3(eye, target));
    const x = norm3(cross3(up, z));
    const y = cross3(z, x);
    return [x[0], y[0], z[0], 0, x[1], y[1], z[1], 0, x[2], y[2], z[2], 0,
      -dot3(x, eye), -dot3(y, eye), -dot3(z, eye), 1];
  }
  function apply(m, p) {
    const w = m[3] * p[0] + m[7] * p[1] + m[11] * p[2] + m[15];
    return [(m[0] * p[0] + m[4] * p[1] + m[8] * p[2] + m[12]) / w,
      (m[1] * p[0] + m[5] * p[1] + m[9] * p[2] + m[13]) / w,
      (m[2] * p[0] + m[6] * p[1] + m[10] * p[2] + m[14]) / w, w];
  }

  // ---------------------------------------------------------------- kinematics -----------
  // The joint frames of the OPW chain (src/output/view/kinematics.rs, joint_frames): axis 1 at the
  // height of axis 2, axes 2, 3, 4, 5 and the flange. ABB's axis 3 is the OPW angle − 90°.
  function jointFrames(q) {
    const o = M.scene.robot.opw;
    const r = q.map((d) => d * Math.PI / 180);
    const f1 = mul(pose(M.scene.robot.base), mul(trans(0, 0, o.c1), rotZ(r[0])));
    const f2 = mul(f1, mul(trans(o.a1, o.b, 0), rotY(r[1])));
    const f3 = mul(f2, mul(trans(0, 0, o.c2), rotY(r[2] + Math.PI / 2)));
    const f4 = mul(f3, mul(trans(o.a2, 0, 0), rotZ(r[3])));
    const f5 = mul(f4, mul(trans(0, 0, o.c3), rotY(r[4])));
    const f6 = mul(f5, mul(trans(0, 0, o.c4), rotZ(r[5])));
    return [f1, f2, f3, f4, f5, f6];
  }

  // ---------------------------------------------------------------- WebGL ----------------
  const canvas = $('gl');
  const overlay = $('overlay');
  const ctx2d = overlay.getContext('2d');
  let gl = null;
  try {
    gl = canvas.getContext('webgl', { antialias: true, preserveDrawingBuffer: true });
  } catch (e) {
    gl = null;
  }
  let meshProg = null; let lineProg = null; let shapes = null;

  function compile(vs, fs) {
    const mk = (type, src) => {
      const s = gl.createShader(type);
      gl.shaderSource(s, src);
      gl.compileShader(s);
      if (!gl.getShaderParameter(s, gl.COMPILE_STATUS)) throw new Error(gl.getShaderInfoLog(s));
      return s;
    };
    const p = gl.createProgram();
    gl.attachShader(p, mk(gl.VERTEX_SHADER, vs));
    gl.attachShader(p, mk(gl.FRAGMENT_SHADER, fs));
    gl.linkProgram(p);
    if (!gl.getProgramParameter(p, gl.LINK_STATUS)) throw new Error(gl.getProgramInfoLog(p));
    const loc = {};
    const na = gl.getProgramParameter(p, gl.ACTIVE_ATTRIBUTES);
    for (let k = 0; k < na; k++) { const a = gl.getActiveAttrib(p, k); loc[a.name] = gl.getAttribLocation(p, a.name); }
    const nu = gl.getProgramParameter(p, gl.ACTIVE_UNIFORMS);
    for (let k = 0; k < nu; k++) { const u = gl.getActiveUniform(p, k); loc[u.name] = gl.getUniformLocation(p, u.name); }
    return { p, loc };
  }

  function initGl() {
    meshProg = compile(
      'attribute vec3 aPos; attribute vec3 aNor; uniform mat4 uMvp; uniform mat4 uModel; uniform mat3 uNm;' +
      'varying vec3 vN; void main(){ vN = normalize(uNm * aNor); gl_Position = uMvp * uModel * vec4(aPos, 1.0); }',
      'precision mediump float; varying vec3 vN; uniform vec3 uColor; uniform vec3 uLight;' +
      'void main(){ vec3 n = normalize(vN); float d = max(dot(n, uLight), 0.0);' +
      'float sky = 0.5 + 0.5 * n.z; vec3 c = uColor * (0.28 + 0.17 * sky + 0.62 * d);' +
      'gl_FragColor = vec4(c, 1.0); }');
    lineProg = compile(
      'attribute vec3 aPos; attribute vec3 aCol; uniform mat4 uMvp; uniform vec2 uShift; varying vec3 vC;' +
      'void main(){ vC = aCol; vec4 p = uMvp * vec4(aPos, 1.0); p.xy += uShift * p.w; gl_Position = p; }',
      'precision mediump float; varying vec3 vC; uniform float uDim;' +
      'void main(){ gl_FragColor = vec4(mix(vC, vec3(0.33, 0.37, 0.42), uDim), 1.0); }');
    shapes = { cyl: cylinder(28), box: box() };
    gl.enable(gl.DEPTH_TEST);
  }

  function meshBuffers(pos, nor, idx) {
    const b = { pos: gl.createBuffer(), nor: gl.createBuffer(), idx: gl.createBuffer(), n: idx.length };
    gl.bindBuffer(gl.ARRAY_BUFFER, b.pos); gl.bufferData(gl.ARRAY_BUFFER, new Float32Array(pos), gl.STATIC_DRAW);
    gl.bindBuffer(gl.ARRAY_BUFFER, b.nor); gl.bufferData(gl.ARRAY_BUFFER, new Float32Array(nor), gl.STATIC_DRAW);
    gl.bindBuffer(gl.ELEMENT_ARRAY_BUFFER, b.idx); gl.bufferData(gl.ELEMENT_ARRAY_BUFFER, new Uint16Array(idx), gl.STATIC_DRAW);
    return b;
  }

  // A cylinder of radius 1 along z from 0 to 1, with caps.
  function cylinder(seg) {
    const pos = []; const nor = []; const idx = [];
    for (let s = 0; s <= seg; s++) {
      const a = (s / seg) * 2 * Math.PI; const c = Math.cos(a); const n = Math.sin(a);
      pos.push(c, n, 0, c, n, 1); nor.push(c, n, 0, c, n, 0);
    }
    for (let s = 0; s < seg; s++) { const b = 2 * s; idx.push(b, b + 2, b + 1, b + 1, b + 2, b + 3); }
    for (const z of [0, 1]) {
      const centre = pos.length / 3; pos.push(0, 0, z); nor.push(0, 0, z ? 1 : -1);
      for (let s = 0; s <= seg; s++) {
        const a = (s / seg) * 2 * Math.PI; pos.push(Math.cos(a), Math.sin(a), z); nor.push(0, 0, z ? 1 : -1);
      }
      for (let s = 0; s < seg; s++) {
        if (z) idx.push(centre, centre + 1 + s, centre + 2 + s); else idx.push(centre, centre + 2 + s, centre + 1 + s);
      }
    }
    return meshBuffers(pos, nor, idx);
  }

  // A box from (−1, −1, 0) to (1, 1, 1).
  function box() {
    const pos = []; const nor = []; const idx = [];
    const faces = [[0, 0, 1], [0, 0, -1], [1, 0, 0], [-1, 0, 0], [0, 1, 0], [0, -1, 0]];
    for (const n of faces) {
      const u = Math.abs(n[2]) > 0 ? [1, 0, 0] : [0, 0, 1];
      const v = cross3(n, u);
      const b = pos.length / 3;
      for (const [su, sv] of [[-1, -1], [1, -1], [1, 1], [-1, 1]]) {
        const p = add3(n, add3(scale3(u, su), scale3(v, sv)));
        pos.push(p[0], p[1], (p[2] + 1) / 2); nor.push(n[0], n[1], n[2]);
      }
      idx.push(b, b + 1, b + 2, b, b + 2, b + 3);
    }
    return meshBuffers(pos, nor, idx);
  }

  // The model matrix of a solid from point a to point b, with its cross-section axes
  // scaled by r (and its first cross-section axis along `side` when given).
  function between(a, b, r, side) {
    const d = sub3(b, a); const l = len3(d);
    if (l < 1e-6) return null;
    const z = scale3(d, 1 / l);
    let x = side ? sub3(side, scale3(z, dot3(side, z))) : null;
    if (!x || len3(x) < 1e-6) x = cross3(Math.abs(z[0]) < 0.9 ? [1, 0, 0] : [0, 1, 0], z);
    x = norm3(x);
    const y = cross3(z, x);
    return [x[0] * r, x[1] * r, x[2] * r, 0, y[0] * r, y[1] * r, y[2] * r, 0, d[0], d[1], d[2], 0, a[0], a[1], a[2], 1];
  }

  function normalMatrix(m) {
    // Inverse transpose of the upper 3×3.
    const a = [m[0], m[1], m[2], m[4], m[5], m[6], m[8], m[9], m[10]];
    const [a00, a01, a02, a10, a11, a12, a20, a21, a22] = a;
    const b01 = a22 * a11 - a12 * a21; const b11 = -a22 * a10 + a12 * a20; const b21 = a21 * a10 - a11 * a20;
    const det = a00 * b01 + a01 * b11 + a02 * b21 || 1;
    const inv = [b01, -a22 * a01 + a02 * a21, a12 * a01 - a02 * a11,
      b11, a22 * a00 - a02 * a20, -a12 * a00 + a02 * a10,
      b21, -a21 * a00 + a01 * a20, a11 * a00 - a01 * a10].map((v) => v / det);
    // transpose
    return [inv[0], inv[3], inv[6], inv[1], inv[4], inv[7], inv[2], inv[5], inv[8]];
  }

  function hex(c) { return [parseInt(c.slice(1, 3), 16) / 255, parseInt(c.slice(3, 5), 16) / 255, parseInt(c.slice(5, 7), 16) / 255]; }
  const COL = { link: hex('#dfe3e8'), joint: hex('#ff8c3a'), base: hex('#5a626c'), dark: hex('#3a4048'),
    tool: hex('#7fb8ff') };

  let solids = [];
  function solid(shape, model, color) { if (model) solids.push({ shape, model, color }); }

  function drawSolids(mvp, light) {
    const P = meshProg; gl.useProgram(P.p);
    gl.uniformMatrix4fv(P.loc.uMvp, false, new Float32Array(mvp));
    gl.uniform3fv(P.loc.uLight, new Float32Array(light));
    for (const s of solids) {
      const b = s.shape;
      gl.bindBuffer(gl.ARRAY_BUFFER, b.pos); gl.enableVertexAttribArray(P.loc.aPos);
      gl.vertexAttribPointer(P.loc.aPos, 3, gl.FLOAT, false, 0, 0);
      gl.bindBuffer(gl.ARRAY_BUFFER, b.nor); gl.enableVertexAttribArray(P.loc.aNor);
      gl.vertexAttribPointer(P.loc.aNor, 3, gl.FLOAT, false, 0, 0);
      gl.bindBuffer(gl.ELEMENT_ARRAY_BUFFER, b.idx);
      gl.uniformMatrix4fv(P.loc.uModel, false, new Float32Array(s.model));
      gl.uniformMatrix3fv(P.loc.uNm, false, new Float32Array(normalMatrix(s.model)));
      gl.uniform3fv(P.loc.uColor, new Float32Array(s.color));
      gl.drawElements(gl.TRIANGLES, b.n, gl.UNSIGNED_SHORT, 0);
    }
  }

  // Line sets: {buf, n, mode} with interleaved position and colour.
  function lineSet(verts, old) {
    const b = old || { buf: gl.createBuffer(), n: 0 };
    gl.bindBuffer(gl.ARRAY_BUFFER, b.buf);
    gl.bufferData(gl.ARRAY_BUFFER, new Float32Array(verts), gl.DYNAMIC_DRAW);
    b.n = verts.length / 6;
    return b;
  }
  // Lines `width` pixels wide are drawn as copies shifted by a pixel (WebGL lines are one
  // pixel wide on most systems).
  let pixel = [0, 0];
  function drawLines(set, mvp, first, count, dim, width) {
    if (!set || count <= 0) return;
    const P = lineProg; gl.useProgram(P.p);
    gl.uniformMatrix4fv(P.loc.uMvp, false, new Float32Array(mvp));
    gl.uniform1f(P.loc.uDim, dim || 0);
    gl.bindBuffer(gl.ARRAY_BUFFER, set.buf);
    gl.enableVertexAttribArray(P.loc.aPos); gl.vertexAttribPointer(P.loc.aPos, 3, gl.FLOAT, false, 24, 0);
    gl.enableVertexAttribArray(P.loc.aCol); gl.vertexAttribPointer(P.loc.aCol, 3, gl.FLOAT, false, 24, 12);
    const shifts = width >= 2 ? [[0, 0], [1, 0], [0, 1], [1, 1]] : [[0, 0]];
    for (const [sx, sy] of shifts) {
      gl.uniform2f(P.loc.uShift, sx * pixel[0], sy * pixel[1]);
      gl.drawArrays(gl.LINES, first, count);
    }
  }

  // Speed colour: blue (slow) → cyan → green → yellow → red (the run's top speed).
  function speedColor(v) {
    const x = Math.min(1, Math.max(0, v / M.maxSpeed));
    const stops = [[0.16, 0.35, 0.95], [0.1, 0.8, 0.95], [0.2, 0.85, 0.35], [0.98, 0.85, 0.2], [0.95, 0.25, 0.2]];
    const f = x * (stops.length - 1); const k = Math.min(stops.length - 2, Math.floor(f)); const u = f - k;
    return stops[k].map((c, a) => c + (stops[k + 1][a] - c) * u);
  }

  // ---------------------------------------------------------------- scene geometry -------
  let grid = null; let frameLines = null; let pathLines = null; let pathRows = [];
  let corrLines = null; let liveLines = null;
  let R = 1850;

  function buildStatic() {
    R = M.scene.robot.reach || 1850;
    const v = [];
    const ext = Math.ceil((R * 1.4) / 500) * 500;
    for (let x = -ext; x <= ext + 1e-6; x += 100) {
      const major = Math.abs(x % 500) < 1e-6;
      const c = major ? [0.25, 0.28, 0.32] : [0.18, 0.2, 0.23];
      v.push(x, -ext, 0, ...c, x, ext, 0, ...c, -ext, x, 0, ...c, ext, x, 0, ...c);
    }
    grid = lineSet(v, grid);
    const f = [];
    frameAxes(f, m4(), R * 0.25);
    for (const fr of M.scene.frames) frameAxes(f, pose(fr.pose), R * 0.09);
    frameLines = lineSet(f, frameLines);
  }

  function frameAxes(out, m, l) {
    const o = origin(m);
    const cols = [[0.95, 0.3, 0.3], [0.35, 0.9, 0.4], [0.35, 0.55, 1]];
    for (let c = 0; c < 3; c++) {
      const e = add3(o, scale3(axis(m, c), l));
      out.push(...o, ...cols[c], ...e, ...cols[c]);
    }
  }

  // The TCP path as segments coloured by speed; no segment across a jump of the TCP (a
  // tool change between two motion cycles).
  function buildPath() {
    const v = []; pathRows = [];
    const period = M.scene.periodUs || 4000;
    for (let k = 1; k < M.t.length; k++) {
      const a = [M.p[0][k - 1], M.p[1][k - 1], M.p[2][k - 1]];
      const b = [M.p[0][k], M.p[1][k], M.p[2][k]];
      const jump = M.t[k] - M.t[k - 1] <= 1.5 * period && len3(sub3(b, a)) > 20;
      if (jump) continue;
      const ca = speedColor(M.v[k - 1]); const cb = speedColor(M.v[k]);
      v.push(...a, ...ca, ...b, ...cb);
      pathRows.push(k);
    }
    pathLines = lineSet(v, pathLines);
    const c = [];
    const P = M.path;
    const gain = $('exag').checked ? 20 : 1;
    const mag = (p, q) => add3(p, scale3(sub3(q, p), gain));
    for (let k = 1; k < P.t.length; k++) {
      if (P.start[k]) continue;
      const pa = [P.prog[0][k - 1], P.prog[1][k - 1], P.prog[2][k - 1]];
      const pb = [P.prog[0][k], P.prog[1][k], P.prog[2][k]];
      const ca = mag(pa, [P.cor[0][k - 1], P.cor[1][k - 1], P.cor[2][k - 1]]);
      const cb = mag(pb, [P.cor[0][k], P.cor[1][k], P.cor[2][k]]);
      c.push(...pa, 0.95, 0.95, 0.95, ...pb, 0.95, 0.95, 0.95);
      c.push(...ca, 1, 0.3, 0.85, ...cb, 1, 0.3, 0.85);
    }
    corrLines = lineSet(c, corrLines);
  }

  // The solids of the arm at `q` with the TCP at `tcp` (world, mm).
  function buildRobot(q, tcp) {
    solids = [];
    const F = jointFrames(q);
    const o = F.map(origin);
    const base = pose(M.scene.robot.base);
    const b0 = origin(base); const bz = axis(base, 2);
    const c1 = M.scene.robot.opw.c1;
    const at = (m, x, y, z) => add3(add3(add3(origin(m), scale3(axis(m, 0), x)), scale3(axis(m, 1), y)), scale3(axis(m, 2), z));
    // Base and the turning column of axis 1.
    solid(shapes.cyl, between(b0, add3(b0, scale3(bz, c1 * 0.42)), R * 0.105), COL.base);
    solid(shapes.cyl, between(add3(b0, scale3(bz, c1 * 0.42)), add3(b0, scale3(bz, c1 * 0.5)), R * 0.095), COL.dark);
    const shoulder = add3(b0, scale3(bz, c1));
    solid(shapes.cyl, between(add3(b0, scale3(bz, c1 * 0.5)), shoulder, R * 0.085), COL.link);
    solid(shapes.box, between(shoulder, o[1], R * 0.06, axis(F[1], 1)), COL.link);
    // Axis 2, the lower arm, axis 3.
    const w2 = R * 0.085;
    solid(shapes.cyl, between(at(F[1], 0, -w2, 0), at(F[1], 0, w2, 0), R * 0.07), COL.joint);
    solid(shapes.box, between(o[1], o[2], R * 0.045, axis(F[1], 1)), COL.link);
    const w3 = R * 0.07;
    solid(shapes.cyl, between(at(F[2], 0, -w3, 0), at(F[2], 0, w3, 0), R * 0.058), COL.joint);
    // The upper arm housing: behind axis 3, the elbow offset, the arm to the wrist.
    solid(shapes.cyl, between(at(F[3], 0, 0, -R * 0.09), o[3], R * 0.055), COL.link);
    solid(shapes.box, between(o[2], o[3], R * 0.05, axis(F[2], 1)), COL.link);
    solid(shapes.cyl, between(o[3], o[4], R * 0.036), COL.link);
    // Axis 5, the wrist, the flange.
    const w5 = R * 0.04;
    solid(shapes.cyl, between(at(F[4], 0, -w5, 0), at(F[4], 0, w5, 0), R * 0.033), COL.joint);
    solid(shapes.cyl, between(o[4], at(F[5], 0, 0, -R * 0.006), R * 0.022), COL.link);
    solid(shapes.cyl, between(at(F[5], 0, 0, -R * 0.006), o[5], R * 0.03), COL.dark);
    // The tool: flange to TCP.
    if (tcp && len3(sub3(tcp, o[5])) > 1) solid(shapes.cyl, between(o[5], tcp, R * 0.008), COL.tool);
    return F;
  }

  // ---------------------------------------------------------------- camera ---------------
  const cam = { yaw: -0.9, pitch: 0.42, dist: 4000, target: [600, 0, 700] };
  function resetCamera() {
    const xs = [0]; const ys = [0]; const zs = [0, M.scene.robot.opw.c1 + M.scene.robot.opw.c2];
    for (let k = 0; k < M.t.length; k += Math.max(1, Math.floor(M.t.length / 500))) {
      xs.push(M.p[0][k]); ys.push(M.p[1][k]); zs.push(M.p[2][k]);
    }
    // The arm where it starts and where it ends.
    for (const k of M.t.length ? [0, M.t.length - 1] : []) {
      for (const o of jointFrames(M.j.map((c) => c[k])).map(origin)) { xs.push(o[0]); ys.push(o[1]); zs.push(o[2]); }
    }
    const lo = [Math.min(...xs), Math.min(...ys), Math.min(...zs)];
    const hi = [Math.max(...xs), Math.max(...ys), Math.max(...zs)];
    cam.target = scale3(add3(lo, hi), 0.5);
    // Leave the read-out in the top left corner free: the scene a little to the right.
    const side = norm3(cross3([0, 0, 1], [Math.cos(-0.95), Math.sin(-0.95), 0]));
    cam.target = add3(cam.target, scale3(side, -R * 0.15));
    const size = Math.max(len3(sub3(hi, lo)), R * 1.1);
    cam.dist = size * 1.5;
    cam.yaw = -0.95; cam.pitch = 0.38;
  }
  function eye() {
    const c = Math.cos(cam.pitch);
    return add3(cam.target, scale3([c * Math.cos(cam.yaw), c * Math.sin(cam.yaw), Math.sin(cam.pitch)], cam.dist));
  }

  let dragging = null; let moved = false;
  canvas.addEventListener('contextmenu', (e) => e.preventDefault());
  canvas.addEventListener('mousedown', (e) => {
    dragging = { x: e.clientX, y: e.clientY, pan: e.button === 2 || e.shiftKey }; moved = true;
  });
  window.addEventListener('mouseup', () => { dragging = null; });
  window.addEventListener('mousemove', (e) => {
    if (!dragging) return;
    const dx = e.clientX - dragging.x; const dy = e.clientY - dragging.y;
    dragging.x = e.clientX; dragging.y = e.clientY;
    if (dragging.pan) {
      const ey = eye(); const fwd = norm3(sub3(cam.target, ey));
      const right = norm3(cross3(fwd, [0, 0, 1])); const up = cross3(right, fwd);
      const s = cam.dist / (canvas.clientHeight || 600) * 0.8;
      cam.target = add3(cam.target, add3(scale3(right, -dx * s), scale3(up, dy * s)));
    } else {
      cam.yaw -= dx * 0.008;
      cam.pitch = Math.max(-1.45, Math.min(1.5, cam.pitch + dy * 0.008));
    }
    requestDraw();
  });
  canvas.addEventListener('wheel', (e) => {
    e.preventDefault();
    cam.dist = Math.max(50, Math.min(1e6, cam.dist * Math.exp(e.deltaY * 0.0012)));
    requestDraw();
  }, { passive: false });
  canvas.addEventListener('dblclick', () => { resetCamera(); requestDraw(); });

  // ---------------------------------------------------------------- drawing --------------
  let nowUs = 0;
  let drawPending = false;
  const api = { ready: false, loadMs: null, drawn: null, frames: 0 };
  window.rapidvc = api;

  function requestDraw() {
    if (drawPending) return;
    drawPending = true;
    requestAnimationFrame(() => { drawPending = false; draw(); });
  }

  function fitCanvas(c) {
    const dpr = window.devicePixelRatio || 1;
    const w = Math.max(1, Math.round(c.clientWidth * dpr)); const h = Math.max(1, Math.round(c.clientHeight * dpr));
    if (c.width !== w || c.height !== h) { c.width = w; c.height = h; }
    return [w, h, dpr];
  }

  function draw() {
    const s = sample(nowUs);
    updatePanels(s);
    drawCharts();
    if (!gl || !s) { api.drawn = s && { t: s.t, joints: s.joints, origins: null, tcp: s.tcp }; return; }
    const [w, h, dpr] = fitCanvas(canvas);
    fitCanvas(overlay);
    gl.viewport(0, 0, w, h);
    pixel = [2 / w, 2 / h];
    gl.clearColor(0.102, 0.122, 0.145, 1);
    gl.clear(gl.COLOR_BUFFER_BIT | gl.DEPTH_BUFFER_BIT);
    const ey = eye();
    const view = lookAt(ey, cam.target, [0, 0, 1]);
    const proj = perspective(40 * Math.PI / 180, w / h, cam.dist / 200, cam.dist * 30);
    const mvp = mul(proj, view);
    const F = buildRobot(s.joints, s.tcp);
    const light = norm3(add3(norm3(sub3(ey, cam.target)), [0.3, -0.2, 0.9]));
    drawLines(grid, mvp, 0, grid.n);
    // The TCP path: dimmed ahead of the robot, coloured behind it.
    const done = floorIndex(pathRows, s.k) + 1;
    drawLines(pathLines, mvp, 0, done * 2, 0, 2);
    drawLines(pathLines, mvp, done * 2, pathLines.n - done * 2, 0.55, 2);
    if (corrLines) drawLines(corrLines, mvp, 0, corrLines.n, 0, 2);
    drawSolids(mvp, light);
    // Frames show through the arm.
    gl.disable(gl.DEPTH_TEST);
    drawLines(frameLines, mvp, 0, frameLines.n, 0, 2);
    const tcpFrame = [];
    frameAxes(tcpFrame, pose([...s.tcp, ...s.quat]), R * 0.07);
    liveLines = lineSet(tcpFrame, liveLines);
    drawLines(liveLines, mvp, 0, liveLines.n, 0, 2);
    gl.enable(gl.DEPTH_TEST);
    // Labels.
    ctx2d.setTransform(dpr, 0, 0, dpr, 0, 0);
    ctx2d.clearRect(0, 0, w, h);
    ctx2d.font = '12px system-ui, sans-serif';
    const label = (p, text, color) => {
      const c = apply(mvp, p);
      if (c[3] <= 0 || Math.abs(c[0]) > 1.05 || Math.abs(c[1]) > 1.05) return;
      const x = (c[0] + 1) / 2 * (w / dpr); const y = (1 - c[1]) / 2 * (h / dpr);
      ctx2d.fillStyle = 'rgba(20,24,29,0.7)';
      const tw = ctx2d.measureText(text).width;
      ctx2d.fillRect(x + 4, y - 14, tw + 6, 16);
      ctx2d.fillStyle = color; ctx2d.fillText(text, x + 7, y - 2);
    };
    label([0, 0, 0], 'world', '#9aa5b1');
    for (const fr of M.scene.frames) label(fr.pose.slice(0, 3), fr.name, '#c3ccd6');
    label(s.tcp, 'TCP', '#7fb8ff');
    api.frames += 1;
    api.drawn = { t: s.t, joints: s.joints, origins: F.map(origin), tcp: s.tcp };
  }

  // ---------------------------------------------------------------- panels ---------------
  const srcEl = $('source'); const tabsEl = $('tabs');
  let fileViews = []; let shownFile = -1; let curLineEl = null; let shownInstr = -2;

  function buildSource() {
    srcEl.textContent = ''; tabsEl.textContent = ''; fileViews = []; shownFile = -1; curLineEl = null;
    M.scene.files.forEach((f, k) => {
      const pre = document.createElement('div');
      pre.className = 'src'; pre.hidden = true;
      const lines = f.text.split(/\r\n|\r|\n/);
      const frag = document.createDocumentFragment();
      lines.forEach((l, n) => {
        const d = document.createElement('div');
        d.className = 'ln'; d.dataset.n = String(n + 1); d.textContent = l || ' ';
        frag.appendChild(d);
      });
      pre.appendChild(frag);
      srcEl.appendChild(pre);
      const b = document.createElement('button');
      b.textContent = f.name.split(/[\\/]/).pop();
      b.title = f.name;
      b.addEventListener('click', () => showFile(k));
      tabsEl.appendChild(b);
      fileViews.push({ pre, tab: b });
    });
    tabsEl.hidden = M.scene.files.length < 2;
    if (fileViews.length) showFile(0);
  }

  function showFile(k) {
    if (k === shownFile || !fileViews[k]) return;
    fileViews.forEach((v, n) => { v.pre.hidden = n !== k; v.tab.classList.toggle('on', n === k); });
    shownFile = k;
  }

  function highlight(instr) {
    if (instr === shownInstr) return;
    shownInstr = instr;
    if (curLineEl) curLineEl.classList.remove('cur');
    curLineEl = null;
    const info = M.instrs[instr];
    if (!info) return;
    const [, , file, line] = info;
    if (file < 0 || !fileViews[file]) return;
    showFile(file);
    const el = fileViews[file].pre.children[line - 1];
    if (!el) return;
    el.classList.add('cur'); curLineEl = el;
    const top = el.offsetTop - srcEl.offsetTop;
    if (top < srcEl.scrollTop + 20 || top > srcEl.scrollTop + srcEl.clientHeight - 40) {
      srcEl.scrollTop = Math.max(0, top - srcEl.clientHeight / 3);
    }
  }

  const tpEl = $('tp'); const evEl = $('events');
  let logEls = []; let logShown = 0;
  function fmtT(us) { return (us / 1e6).toFixed(3) + ' s'; }

  function addLogEntry(e) {
    const [t, kind, text] = e;
    const d = document.createElement('div');
    const ts = document.createElement('span'); ts.className = 'ts'; ts.textContent = fmtT(t);
    const tx = document.createElement('span'); tx.className = kind;
    tx.textContent = kind === 'erase' ? '(TPErase)' : text;
    d.append(ts, tx);
    d.hidden = true;
    d.addEventListener('click', () => seek(t));
    (kind === 'tp' || kind === 'erase' ? tpEl : evEl).appendChild(d);
    logEls.push({ el: d, t, kind });
  }

  function buildLog() {
    tpEl.textContent = ''; evEl.textContent = ''; logEls = []; logShown = 0;
    for (const e of M.log) addLogEntry(e);
  }

  function updateLog() {
    const n = floorIndex(M.log.map((e) => e[0]), nowUs) + 1;
    if (n === logShown) return;
    const from = logShown < 0 ? 0 : Math.min(n, logShown);
    const to = logShown < 0 ? logEls.length : Math.max(n, logShown);
    for (let k = from; k < to; k++) logEls[k].el.hidden = k >= n;
    let lastTp = null; let lastEv = null;
    logEls.forEach((x, k) => {
      x.el.classList.remove('last');
      if (k < n) { if (x.kind === 'tp' || x.kind === 'erase') lastTp = x; else lastEv = x; }
    });
    for (const x of [lastTp, lastEv]) {
      if (!x) continue;
      x.el.classList.add('last');
      const box = x.el.parentElement;
      box.scrollTop = Math.max(0, x.el.offsetTop - box.offsetTop - box.clientHeight + x.el.offsetHeight + 4);
    }
    logShown = n;
  }

  const readout = $('readout');
  function updatePanels(s) {
    const total = M.endUs;
    $('time').textContent = fmtT(nowUs) + ' / ' + fmtT(total);
    if (document.activeElement !== slider) slider.value = String(Math.round(nowUs / 1000));
    slider.max = String(Math.ceil(total / 1000));
    if (!s) { readout.textContent = 'no motion recorded'; updateLog(); return; }
    highlight(s.instr);
    const info = M.instrs[s.instr];
    const where = info ? info[1] + (info[3] ? ' (line ' + info[3] + ')' : '') : 'idle';
    const j = s.joints.map((x, a) => 'J' + (a + 1) + (x >= 0 ? '  ' : ' ') + x.toFixed(2).padStart(8)).join('\n');
    const egm = egmAt(nowUs);
    readout.textContent = where + '\n' + j + '\nTCP ' + s.tcp.map((x) => x.toFixed(1)).join(', ') +
      ' mm\nv   ' + s.speed.toFixed(1) + ' mm/s' + (egm !== null ? '\nEGM ' + STATE_NAMES[egm] : '');
    updateLog();
  }

  function egmAt(t) {
    const k = floorIndex(M.egmStates.map((e) => e[0]), t);
    return k < 0 ? null : M.egmStates[k][1];
  }

  function buildLegend() {
    const c = $('legendbar'); const g = c.getContext('2d');
    for (let x = 0; x < c.width; x++) {
      const col = speedColor((x / (c.width - 1)) * M.maxSpeed).map((v) => Math.round(v * 255));
      g.fillStyle = 'rgb(' + col.join(',') + ')'; g.fillRect(x, 0, 1, c.height);
    }
    $('legendtext').textContent = '0 – ' + M.maxSpeed.toFixed(0) + ' mm/s';
  }

  // ---------------------------------------------------------------- charts ---------------
  const chartEl = $('chart'); const chartG = chartEl.getContext('2d');
  let panels = []; let chartSpan = [0, 1];

  function buildCharts() {
    panels = [];
    const E = M.egm; const P = M.path;
    if (E.t.length || M.egmStates.length) {
      panels.push({ kind: 'state' });
      const pose = E.axes.some((a) => a === 1); const joint = E.axes.some((a) => a === 0);
      const names = ['J1 / x', 'J2 / y', 'J3 / z', 'J4 / rx', 'J5 / ry', 'J6 / rz'].map((n) => {
        const [jn, pn] = n.split(' / ');
        return pose && joint ? n : (pose ? pn : jn);
      });
      for (let a = 0; a < 6; a++) if (E.t.length) panels.push({ kind: 'egm', axis: a, label: names[a] });
    }
    if (P.t.length) panels.push({ kind: 'path' });
    $('charts').hidden = panels.length === 0;
    $('exagbox').hidden = P.t.length === 0;
    const ts = [];
    if (E.t.length) ts.push(E.t[0], E.t[E.t.length - 1]);
    if (P.t.length) ts.push(P.t[0], P.t[P.t.length - 1]);
    for (const s of M.egmStates) ts.push(s[0]);
    if (ts.length) {
      const lo = Math.min(...ts); const hi = Math.max(...ts, lo + 1e6);
      const m = (hi - lo) * 0.02;
      chartSpan = [Math.max(0, lo - m), hi + m];
    }
    $('charttitle').textContent = (E.t.length ? 'EGM: reference (orange) and feedback (blue) per axis; state: grey disconnected, blue connected, green running, red MaxSpeedDeviation limiting' : '') +
      (P.t.length ? (E.t.length ? ' · ' : '') + 'path correction applied: y (magenta), z (green), mm' : '');
  }

  function window2() {
    if ($('follow').checked) return [nowUs - 5e6, nowUs + 5e6];
    return chartSpan;
  }

  function drawCharts() {
    if (!panels.length) return;
    const egmPanels = panels.filter((p) => p.kind === 'egm');
    const hasState = panels.some((p) => p.kind === 'state'); const hasPath = panels.some((p) => p.kind === 'path');
    const rowH = 64; const cols = 3; const gap = 6; const left = 52;
    const cssH = (hasState ? 20 : 0) + Math.ceil(egmPanels.length / cols) * (rowH + gap) + (hasPath ? rowH + gap : 0) + 18;
    chartEl.style.height = cssH + 'px';
    const [w, h, dpr] = fitCanvas(chartEl);
    const g = chartG; g.setTransform(dpr, 0, 0, dpr, 0, 0);
    const W = w / dpr; g.clearRect(0, 0, W, h / dpr);
    g.font = '11px system-ui, sans-serif';
    const [t0, t1] = window2();
    const X = (t, x0, pw) => x0 + (t - t0) / (t1 - t0) * pw;
    let y = 2;
    const E = M.egm;
    if (hasState) {
      const pw = W - left - 8;
      g.fillStyle = '#8b97a4'; g.fillText('state', 2, y + 12);
      for (let k = 0; k < M.egmStates.length; k++) {
        const [ta, st] = M.egmStates[k];
        const tb = k + 1 < M.egmStates.length ? M.egmStates[k + 1][0] : M.endUs;
        const xa = Math.max(left, X(ta, left, pw)); const xb = Math.min(left + pw, X(tb, left, pw));
        if (xb > xa) { g.fillStyle = STATE_COLORS[st]; g.fillRect(xa, y + 2, xb - xa, 12); }
      }
      g.fillStyle = '#ff5a4f';
      for (let k = 0; k < E.t.length; k++) {
        if (!E.lim[k]) continue;
        const tb = k + 1 < E.t.length ? E.t[k + 1] : E.t[k] + 4000;
        const xa = X(E.t[k], left, pw); const xb = X(tb, left, pw);
        if (xb >= left && xa <= left + pw) g.fillRect(Math.max(left, xa), y + 12, Math.max(1, Math.min(left + pw, xb) - Math.max(left, xa)), 4);
      }
      y += 20;
    }
    const pwE = (W - left - 8 - (cols - 1) * (left + gap)) / cols;
    egmPanels.forEach((p, n) => {
      const x0 = left + (n % cols) * (pwE + left + gap); const y0 = y + Math.floor(n / cols) * (rowH + gap);
      const series = [
        { v: E.ref[p.axis], ok: E.hasRef, color: '#ff9f43' },
        { v: E.fb[p.axis], ok: null, color: '#54a0ff' },
      ];
      plotPanel(g, x0, y0, pwE, rowH, p.label, E.t, series, t0, t1);
    });
    if (egmPanels.length) y += Math.ceil(egmPanels.length / cols) * (rowH + gap);
    if (hasPath) {
      const P = M.path;
      plotPanel(g, left, y, W - left - 8, rowH, 'corr (mm)', P.t, [
        { v: P.corr[0], ok: null, color: '#ff5fd2' }, { v: P.corr[1], ok: null, color: '#4cc27a' },
      ], t0, t1, P.start);
      y += rowH + gap;
    }
    // Time axis and the cursor.
    const pw = W - left - 8;
    g.fillStyle = '#6e7b88';
    g.fillText(fmtT(t0), left, y + 11);
    const endText = fmtT(t1); g.fillText(endText, left + pw - g.measureText(endText).width, y + 11);
    if (nowUs >= t0 && nowUs <= t1) {
      g.strokeStyle = '#ffffff'; g.lineWidth = 1; g.beginPath();
      for (let n = 0; n < Math.max(1, egmPanels.length ? cols : 1); n++) {
        const x0 = egmPanels.length ? left + n * (pwE + left + gap) : left;
        const pw2 = egmPanels.length ? pwE : pw;
        const x = X(nowUs, x0, pw2);
        g.moveTo(x + 0.5, 2); g.lineTo(x + 0.5, y);
      }
      g.stroke();
    }
  }

  function plotPanel(g, x0, y0, pw, ph, label, ts, series, t0, t1, starts) {
    g.fillStyle = '#1d2228'; g.fillRect(x0, y0, pw, ph);
    let lo = Infinity; let hi = -Infinity;
    const k0 = Math.max(0, floorIndex(ts, t0)); const k1 = Math.min(ts.length - 1, floorIndex(ts, t1) + 1);
    for (const s of series) {
      for (let k = k0; k <= k1; k++) {
        if (s.ok && !s.ok[k]) continue;
        const v = s.v[k]; if (v < lo) lo = v; if (v > hi) hi = v;
      }
    }
    if (!(hi >= lo)) { lo = -1; hi = 1; }
    if (hi - lo < 1e-3) { lo -= 0.5; hi += 0.5; }
    const m = (hi - lo) * 0.08; lo -= m; hi += m;
    const Y = (v) => y0 + ph - (v - lo) / (hi - lo) * ph;
    g.fillStyle = '#8b97a4';
    g.fillText(label, x0 - 50, y0 + 11);
    g.fillStyle = '#6e7b88';
    g.fillText(hi.toFixed(Math.abs(hi) < 10 ? 2 : 1), x0 - 50, y0 + 24);
    g.fillText(lo.toFixed(Math.abs(lo) < 10 ? 2 : 1), x0 - 50, y0 + ph - 2);
    g.save(); g.beginPath(); g.rect(x0, y0, pw, ph); g.clip();
    for (const s of series) {
      g.strokeStyle = s.color; g.lineWidth = 1.3; g.beginPath();
      let pen = false;
      for (let k = k0; k <= k1; k++) {
        if (s.ok && !s.ok[k]) { pen = false; continue; }
        if (starts && starts[k]) pen = false;
        const x = x0 + (ts[k] - t0) / (t1 - t0) * pw; const yy = Y(s.v[k]);
        if (pen) g.lineTo(x, yy); else { g.moveTo(x, yy); pen = true; }
      }
      g.stroke();
    }
    g.restore();
  }

  chartEl.addEventListener('click', (e) => {
    const r = chartEl.getBoundingClientRect();
    const [t0, t1] = window2();
    const left = 52; const pw = r.width - left - 8;
    const f = (e.clientX - r.left - left) / pw;
    if (f >= 0 && f <= 1 && !panels.some((p) => p.kind === 'egm')) seek(t0 + f * (t1 - t0));
    else if (panels.some((p) => p.kind === 'egm')) {
      const cols = 3; const gap = 6;
      const pwE = (r.width - left - 8 - (cols - 1) * (left + gap)) / cols;
      for (let n = 0; n < cols; n++) {
        const x0 = left + n * (pwE + left + gap); const g = (e.clientX - r.left - x0) / pwE;
        if (g >= 0 && g <= 1) { seek(t0 + g * (t1 - t0)); break; }
      }
    }
  });
  $('follow').addEventListener('change', () => requestDraw());
  $('exag').addEventListener('change', () => { if (gl) buildPath(); requestDraw(); });

  // ---------------------------------------------------------------- transport ------------
  const slider = $('slider'); const playBtn = $('play'); const rateSel = $('rate');
  let playing = false; let lastWall = 0; let liveFollow = true;

  function seek(t) {
    nowUs = Math.max(0, Math.min(M.endUs, t));
    if (M.live && !M.finished) { liveFollow = nowUs >= M.endUs; $('livefollow').checked = liveFollow; }
    requestDraw();
  }
  function setPlaying(on) {
    playing = on; playBtn.textContent = on ? '❚❚' : '▶';
    if (on) {
      if (nowUs >= M.endUs) nowUs = 0;
      lastWall = performance.now(); requestAnimationFrame(tick);
    }
  }
  function tick(now) {
    if (!playing) return;
    const dt = (now - lastWall) * 1000 * Number(rateSel.value); lastWall = now;
    nowUs = Math.min(M.endUs, nowUs + dt);
    if (nowUs >= M.endUs && (!M.live || M.finished)) setPlaying(false);
    draw();
    if (playing) requestAnimationFrame(tick);
  }
  slider.addEventListener('input', () => { seek(Number(slider.value) * 1000); });
  playBtn.addEventListener('click', () => setPlaying(!playing));
  rateSel.addEventListener('change', () => { lastWall = performance.now(); });

  // Start times of the move instructions (a row whose instruction differs from the row
  // before it), and of the log entries.
  function instrStarts() {
    const s = [];
    for (let k = 0; k < M.t.length; k++) if (M.i[k] >= 0 && (k === 0 || M.i[k] !== M.i[k - 1])) s.push(M.t[k]);
    return s;
  }
  $('nextMove').addEventListener('click', () => {
    const s = instrStarts().find((t) => t > nowUs + 1);
    if (s !== undefined) seek(s);
  });
  $('prevMove').addEventListener('click', () => {
    const s = instrStarts().filter((t) => t < nowUs - 1);
    seek(s.length ? s[s.length - 1] : 0);
  });
  $('nextEvent').addEventListener('click', () => {
    const e = M.log.find((x) => x[0] > nowUs + 1 && x[1] !== 'erase');
    if (e) seek(e[0]);
  });
  window.addEventListener('keydown', (e) => {
    if (e.target && (e.target.tagName === 'INPUT' && e.target.type !== 'range')) return;
    if (e.key === ' ') { e.preventDefault(); setPlaying(!playing); }
  });
  if (window.ResizeObserver) new ResizeObserver(() => requestDraw()).observe($('stage'));
  else window.addEventListener('resize', requestDraw);

  // ---------------------------------------------------------------- live ------------------
  function status(text, cls) { const s = $('status'); s.textContent = text; s.className = cls || ''; }

  function rebuild() {
    buildStatic(); buildSource(); buildLog(); buildLegend(); buildCharts();
    if (gl) buildPath();
    shownInstr = -2;
  }

  function connect() {
    const base = location.pathname.endsWith('/') ? location.pathname : location.pathname + '/';
    const url = (location.protocol === 'https:' ? 'wss://' : 'ws://') + location.host + base + 'ws';
    let ws;
    try { ws = new WebSocket(url); } catch (e) { status('live: cannot connect', ''); return; }
    $('livebox').hidden = false;
    $('livefollow').addEventListener('change', (e) => { liveFollow = e.target.checked; if (liveFollow) seek(M.endUs); });
    let dirty = false; let lastPath = 0; let liveDrawPending = false;
    ws.onopen = () => status('live · connected', 'live');
    ws.onclose = () => status(M.finished ? 'live · run ended' : 'live · disconnected', '');
    ws.onerror = () => {};
    ws.onmessage = (ev) => {
      let m;
      try { m = JSON.parse(ev.data); } catch (e) { return; }
      switch (m.type) {
        case 'snapshot': load(m.data); M.live = true; rebuild(); if (!moved) resetCamera(); break;
        case 'row': if (appendRow(m)) dirty = true; break;
        case 'instr': if (m.index >= M.instrs.length) M.instrs[m.index] = m.instr; break;
        case 'log':
          if (m.index >= M.log.length) { M.log.push(m.entry); addLogEntry(m.entry); logShown = -1; }
          break;
        case 'egm': {
          const E = M.egm;
          if (E.t.length && m.t <= E.t[E.t.length - 1]) break;
          E.t.push(m.t); E.axes.push(m.axes); E.state.push(m.state); E.lim.push(m.lim ? 1 : 0);
          E.hasRef.push(m.ref ? 1 : 0);
          for (let a = 0; a < 6; a++) { E.ref[a].push(m.ref ? m.ref[a] : 0); E.fb[a].push(m.fb[a]); }
          if (!panels.some((p) => p.kind === 'egm')) buildCharts();
          break;
        }
        case 'egmState':
          if (!M.egmStates.length || M.egmStates[M.egmStates.length - 1][0] <= m.t) M.egmStates.push([m.t, m.state]);
          if (!panels.length) buildCharts();
          break;
        case 'path': {
          const P = M.path;
          if (P.t.length && m.t <= P.t[P.t.length - 1]) break;
          P.t.push(m.t); P.s.push(m.s); P.start.push(m.start ? 1 : 0); P.hasMeas.push(m.meas ? 1 : 0);
          for (let a = 0; a < 2; a++) { P.corr[a].push(m.corr[a]); P.meas[a].push(m.meas ? m.meas[a] : 0); }
          for (let a = 0; a < 3; a++) { P.prog[a].push(m.prog[a]); P.cor[a].push(m.cor[a]); }
          if (!panels.some((p) => p.kind === 'path')) buildCharts();
          break;
        }
        case 'lagged': status('live · ' + m.n + ' messages lost (the page fell behind)', 'live'); break;
        case 'end': M.finished = true; M.endUs = Math.max(M.endUs, m.t); status('live · run ended', ''); break;
        default: break;
      }
      if (liveFollow) nowUs = M.endUs;
      if (!liveDrawPending) {
        liveDrawPending = true;
        requestAnimationFrame(() => {
          liveDrawPending = false;
          if (dirty && gl && (M.finished || performance.now() - lastPath > 250)) {
            buildPath(); lastPath = performance.now(); dirty = false;
          }
          updateChartsSpan();
          draw();
        });
      }
    };
  }

  function updateChartsSpan() {
    if (!panels.length) return;
    const E = M.egm; const P = M.path;
    const ts = [];
    if (E.t.length) ts.push(E.t[0], E.t[E.t.length - 1]);
    if (P.t.length) ts.push(P.t[0], P.t[P.t.length - 1]);
    for (const s of M.egmStates) ts.push(s[0]);
    ts.push(M.endUs);
    const lo = Math.min(...ts); const hi = Math.max(...ts, lo + 1e6);
    chartSpan = [lo, hi];
  }

  // ---------------------------------------------------------------- start ----------------
  try {
    load(JSON.parse($('rapidvc-data').textContent));
    $('title').textContent = M.scene.title;
    document.title = 'rapidvc · ' + M.scene.title;
    if (gl) initGl(); else { $('nogl').hidden = false; $('help').hidden = true; }
    // `#exag` magnifies the path correction in 3D from the start.
    if (/[#&]exag\b/.test(location.hash)) $('exag').checked = true;
    rebuild();
    resetCamera();
    nowUs = M.live && !M.finished ? M.endUs : 0;
    // `#t=SECONDS` opens the replay at that time.
    const h = /[#&]t=([0-9.]+)/.exec(location.hash);
    if (h && !M.live) nowUs = Math.min(M.endUs, Number(h[1]) * 1e6);
    if (M.live) connect();
    else status('replay · ' + M.t.length + ' rows, ' + (M.scene.periodUs / 1000) + ' ms cycle', '');
    draw();
    api.loadMs = performance.now();
    api.initMs = performance.now() - T0;
    api.ready = true;
  } catch (e) {
    status('error: ' + e.message, '');
    api.error = String(e && e.message);
    throw e;
  }

  // For tests and the curious: seek and read what was drawn.
  api.duration = () => M.endUs / 1e6;
  api.seek = (sec) => { nowUs = Math.max(0, Math.min(M.endUs, sec * 1e6)); draw(); return api.drawn; };
  api.rows = () => M.t.length;
  api.instrStarts = () => instrStarts().map((t) => t / 1e6);
  api.jointFrames = (q) => jointFrames(q).map(origin);
  api.model = M;
})();
