// The page of stewart.view (docs/view.md): the machine in 3D (three.js), a time slider and
// playback, the legs coloured by their margin to the nearest limit, plots of the lengths and
// forces with a cursor, and window.stewartView for scripts and tests. Its data is the JSON of
// #stewart-data, whose keys docs/view.md ("The page's data") defines: stewart.view (Python) and
// the command lines' --view (csrc/cli/view_page.cpp) write it.
import * as THREE from "three";
import { OrbitControls } from "three/addons/controls/OrbitControls.js";

const startedAt = performance.now();  // ms since the page's navigation began
const data = JSON.parse(document.getElementById("stewart-data").textContent);
const M = data.machine;
const LEGS = 6;
const NO_CLASS = 255;

// Arrays travel as little-endian base64 (stewart.view._packed).
function unpack(b64, Type) {
  if (b64 === null) return null;
  let bytes;
  if (typeof Uint8Array.fromBase64 === "function") {
    bytes = Uint8Array.fromBase64(b64);
  } else {
    const bin = atob(b64);
    bytes = new Uint8Array(bin.length);
    for (let i = 0; i < bin.length; i++) bytes[i] = bin.charCodeAt(i);
  }
  return new Type(bytes.buffer, bytes.byteOffset, bytes.byteLength / Type.BYTES_PER_ELEMENT);
}
const N = data.frames;
const time = unpack(data.t, Float64Array);
const pose = unpack(data.pose, Float64Array);
const force = unpack(data.force, Float32Array);
const legClass = unpack(data.leg_class, Uint8Array);
const legMargin = unpack(data.leg_margin, Float32Array);
const first = unpack(data.first, Uint8Array);
const firstMargin = unpack(data.first_margin, Float32Array);
const condition = unpack(data.condition, Float32Array);
const ranges = unpack(data.ranges, Float32Array);  // per frame and axis: min - q, max - q

// ---- Kinematics (docs/model.md §3, docs/api.md "Tool and user frames") ----
// R = Rz(yaw) Ry(pitch) Rx(roll), row-major 3x3.
function rotation(roll, pitch, yaw) {
  const cr = Math.cos(roll), sr = Math.sin(roll), cp = Math.cos(pitch), sp = Math.sin(pitch);
  const cy = Math.cos(yaw), sy = Math.sin(yaw);
  return [cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr,
          sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr,
          -sp, cp * sr, cp * cr];
}
function mul(A, B) {  // A B
  const C = new Array(9);
  for (let i = 0; i < 3; i++)
    for (let j = 0; j < 3; j++)
      C[3 * i + j] = A[3 * i] * B[j] + A[3 * i + 1] * B[3 + j] + A[3 * i + 2] * B[6 + j];
  return C;
}
function mulT(A, B) {  // A B^T
  const C = new Array(9);
  for (let i = 0; i < 3; i++)
    for (let j = 0; j < 3; j++)
      C[3 * i + j] = A[3 * i] * B[3 * j] + A[3 * i + 1] * B[3 * j + 1] + A[3 * i + 2] * B[3 * j + 2];
  return C;
}
function apply(A, v) {
  return [A[0] * v[0] + A[1] * v[1] + A[2] * v[2], A[3] * v[0] + A[4] * v[1] + A[5] * v[2],
          A[6] * v[0] + A[7] * v[1] + A[8] * v[2]];
}
const joint = (list, k) => [list[3 * k], list[3 * k + 1], list[3 * k + 2]];
const baseJoint = [...Array(LEGS).keys()].map(k => joint(M.base_joint, k));
const platformJoint = [...Array(LEGS).keys()].map(k => joint(M.platform_joint, k));
const userOrigin = M.user_frame.slice(0, 3), userR = rotation(...M.user_frame.slice(3));
const toolOrigin = M.tool_frame.slice(0, 3), toolR = rotation(...M.tool_frame.slice(3));

// The platform's position p and rotation R in the base frame at frame i, from the tool's pose q
// in the user frame: R = R_u R_q R_d^T, p = u + R_u p_q - R d.
function platformPose(i) {
  const q = pose.subarray(6 * i, 6 * i + 6);
  const R = mulT(mul(userR, rotation(q[3], q[4], q[5])), toolR);
  const r = apply(R, toolOrigin), pu = apply(userR, [q[0], q[1], q[2]]);
  return { p: [userOrigin[0] + pu[0] - r[0], userOrigin[1] + pu[1] - r[1], userOrigin[2] + pu[2] - r[2]], R };
}
// Each leg's platform joint (base frame), unit vector base to platform, joint-to-joint length.
function legGeometry(i) {
  const { p, R } = platformPose(i);
  return baseJoint.map((a, k) => {
    const Rb = apply(R, platformJoint[k]);
    const top = [p[0] + Rb[0], p[1] + Rb[1], p[2] + Rb[2]];
    const v = [top[0] - a[0], top[1] - a[1], top[2] - a[2]];
    const L = Math.sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    return { a, top, n: L > 0 ? v.map(x => x / L) : [0, 0, 1], L };
  });
}
// The sensors' readings: joint-to-joint length minus length_offset (what the library returns).
function legLengths(i) {
  return legGeometry(i).map((g, k) => g.L - M.length_offset[k]);
}

// ---- Colours: a leg's margin to its nearest class over that class's scale ----
function legState(i, k) {
  const c = legClass[LEGS * i + k], margin = legMargin[LEGS * i + k];
  if (c === NO_CLASS || !Number.isFinite(margin))
    return { leg: k + 1, class: "none", margin: null, unit: "", fraction: null, beyond: false, colour: "#9e9e9e" };
  const fraction = margin / data.scale[c][k];
  return { leg: k + 1, class: data.classes[c], margin, unit: data.class_units[c], fraction,
           beyond: fraction <= 0, colour: marginColour(fraction) };
}
// <= 0: red (at or beyond the limit); up to half the scale: orange to yellow-green; above: green.
function marginColour(fraction) {
  if (fraction <= 0) return "#d62728";
  const s = Math.min(fraction / 0.5, 1);
  const c = new THREE.Color().setHSL((30 + 95 * s) / 360, 0.75, 0.42);
  return "#" + c.getHexString();
}

// ---- The scene ----
const canvas = document.getElementById("view3d");
const renderer = new THREE.WebGLRenderer({ canvas, antialias: true, preserveDrawingBuffer: true });
renderer.setPixelRatio(1);
const scene = new THREE.Scene();
scene.background = new THREE.Color(0xf2f4f7);
scene.add(new THREE.HemisphereLight(0xffffff, 0x8090a0, 2.2));
const sun = new THREE.DirectionalLight(0xffffff, 1.6);
sun.position.set(2, -3, 5);
scene.add(sun);

const radius = v => Math.hypot(v[0], v[1]);
const baseRadius = Math.max(...baseJoint.map(radius));
const topRadius = Math.max(...platformJoint.map(radius));
const size = Math.max(baseRadius, topRadius, M.home_height);
// A leg_diameter of 0 turns the interference check off; the legs are then drawn 1.5 % of the size.
const legDiameter = M.leg_diameter > 0 ? M.leg_diameter : 0.015 * size;
const plateThickness = 0.04 * size;
const jointRadius = Math.max(0.8 * legDiameter, 0.012 * size);

function disc(r, thickness, colour, opacity) {
  const g = new THREE.CylinderGeometry(r, r, thickness, 64);
  g.rotateX(Math.PI / 2);  // three's cylinders run along y; the machine's plates lie in x-y
  const m = new THREE.MeshStandardMaterial({ color: colour, roughness: 0.7, metalness: 0.1,
                                             transparent: opacity < 1, opacity });
  return new THREE.Mesh(g, m);
}
function sphere(r, colour) {
  return new THREE.Mesh(new THREE.SphereGeometry(r, 20, 12),
                        new THREE.MeshStandardMaterial({ color: colour, roughness: 0.5 }));
}
function frameMatrix(origin, R) {
  return new THREE.Matrix4().set(R[0], R[1], R[2], origin[0], R[3], R[4], R[5], origin[1],
                                 R[6], R[7], R[8], origin[2], 0, 0, 0, 1);
}
function axes(length, origin, R) {
  const helper = new THREE.AxesHelper(length);
  helper.matrixAutoUpdate = false;
  helper.matrix.copy(frameMatrix(origin, R));
  return helper;
}

const base = disc(1.12 * baseRadius, plateThickness, 0x6d7b8d, 1);
base.position.z = Math.min(...baseJoint.map(a => a[2])) - plateThickness / 2 - jointRadius;
scene.add(base);
baseJoint.forEach(a => { const s = sphere(jointRadius, 0x37474f); s.position.set(...a); scene.add(s); });
scene.add(axes(0.45 * size, [0, 0, 0], rotation(0, 0, 0)));
scene.add(axes(0.3 * size, userOrigin, userR));

const platform = new THREE.Group();
platform.matrixAutoUpdate = false;
scene.add(platform);
const plate = disc(1.12 * topRadius, plateThickness, 0x90a4ae, 0.55);
plate.position.z = platformJoint.reduce((s, b) => s + b[2], 0) / LEGS + plateThickness / 2 + jointRadius;
platform.add(plate);
platformJoint.forEach(b => { const s = sphere(jointRadius, 0x37474f); s.position.set(...b); platform.add(s); });
platform.add(axes(0.2 * size, toolOrigin, toolR));
const payload = sphere(1.6 * jointRadius, 0xff8c00);
payload.position.set(...M.payload_com);
payload.visible = M.payload_mass > 0;
platform.add(payload);

// Each leg: the cylinder from the base joint over stroke_min (the shortest leg), and the rod out
// of it to the platform joint, so the rod that shows is the extension over the shortest length.
const unitY = new THREE.Vector3(0, 1, 0);
const legs = [...Array(LEGS).keys()].map(k => {
  const tube = new THREE.Mesh(new THREE.CylinderGeometry(legDiameter / 2, legDiameter / 2, 1, 20),
                              new THREE.MeshStandardMaterial({ color: 0x888888, roughness: 0.45 }));
  const rod = new THREE.Mesh(new THREE.CylinderGeometry(0.3 * legDiameter, 0.3 * legDiameter, 1, 16),
                             new THREE.MeshStandardMaterial({ color: 0xcccccc, roughness: 0.3, metalness: 0.4 }));
  tube.userData.leg = rod.userData.leg = k;
  scene.add(tube, rod);
  return { tube, rod };
});
function place(mesh, from, n, length) {
  const d = new THREE.Vector3(...n);
  mesh.quaternion.setFromUnitVectors(unitY, d);
  mesh.scale.set(1, Math.max(length, 1e-9), 1);
  mesh.position.set(from[0] + n[0] * length / 2, from[1] + n[1] * length / 2, from[2] + n[2] * length / 2);
  mesh.visible = length > 0;
}

// The axis ranges at the pose: arrows from the tool origin along the user frame's x, y, z to the
// first limit each way (the angles' ranges are in the status line).
const AXIS_COLOURS = [0xd62728, 0x2ca02c, 0x1f77b4];
const rangeArrows = [0, 1, 2].flatMap(axis => [0, 1].map(() => {
  const arrow = new THREE.ArrowHelper(new THREE.Vector3(1, 0, 0), new THREE.Vector3(), 1,
                                      AXIS_COLOURS[axis], 0.04 * size, 0.025 * size);
  scene.add(arrow);
  return arrow;
}));
const rangesBox = document.getElementById("ranges");
function showRanges(i) {
  const shown = ranges !== null && rangesBox.checked;
  const { p, R } = platformPose(i), d = apply(R, toolOrigin);
  const origin = new THREE.Vector3(p[0] + d[0], p[1] + d[1], p[2] + d[2]);
  rangeArrows.forEach((arrow, j) => {
    const axis = j >> 1, end = shown ? ranges[12 * i + 2 * axis + (j & 1)] : 0;
    const length = Math.abs(end);
    arrow.visible = shown && length > 1e-6;
    arrow.userData.length = arrow.visible ? length : 0;
    if (!arrow.visible) return;
    const u = [userR[axis], userR[3 + axis], userR[6 + axis]].map(x => x * Math.sign(end));
    arrow.position.copy(origin);
    arrow.setDirection(new THREE.Vector3(...u));
    arrow.setLength(length, Math.min(0.04 * size, 0.5 * length), Math.min(0.025 * size, 0.3 * length));
  });
}
function rangeText(i) {
  if (ranges === null) return "";
  const deg = 180 / Math.PI, names = ["roll", "pitch", "yaw"];
  return " · ranges " + names.map((n, j) => {
    const lo = ranges[12 * i + 2 * (3 + j)] * deg, hi = ranges[12 * i + 2 * (3 + j) + 1] * deg;
    return `${n} ${lo.toFixed(1)}/+${hi.toFixed(1)}`;
  }).join(" ") + " deg";
}

// The constant-orientation workspace (stewart.view.workspace_columns): the top and bottom of its
// columns as two surfaces over the grid of the tool origin's (x, y), in the user frame.
function workspaceMesh(w) {
  const nx = w.x.length, ny = w.y.length, positions = [], index = [];
  for (const ends of [w.z_min, w.z_max]) {
    const first = positions.length / 3;
    for (let i = 0; i < nx; i++)
      for (let j = 0; j < ny; j++) {
        const z = ends[i][j] === null ? 0 : ends[i][j];
        positions.push(...[0, 1, 2].map(r => userOrigin[r] + userR[3 * r] * w.x[i] + userR[3 * r + 1] * w.y[j] + userR[3 * r + 2] * z));
      }
    const at = (i, j) => first + i * ny + j, has = (i, j) => ends[i][j] !== null;
    for (let i = 0; i + 1 < nx; i++)
      for (let j = 0; j + 1 < ny; j++)
        if (has(i, j) && has(i + 1, j) && has(i, j + 1) && has(i + 1, j + 1))
          index.push(at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j), at(i + 1, j + 1), at(i, j + 1));
  }
  const geometry = new THREE.BufferGeometry();
  geometry.setAttribute("position", new THREE.Float32BufferAttribute(positions, 3));
  geometry.setIndex(index);
  geometry.computeVertexNormals();
  const group = new THREE.Group();
  group.add(new THREE.Mesh(geometry, new THREE.MeshLambertMaterial({
    color: 0x3f7fbf, transparent: true, opacity: 0.18, side: THREE.DoubleSide, depthWrite: false })));
  group.add(new THREE.LineSegments(new THREE.WireframeGeometry(geometry),
    new THREE.LineBasicMaterial({ color: 0x3f7fbf, transparent: true, opacity: 0.25 })));
  group.userData.triangles = index.length / 3;
  return group;
}
const workspace = data.workspace && data.workspace.x.length ? workspaceMesh(data.workspace) : null;
const workspaceBox = document.getElementById("workspace");
if (workspace) scene.add(workspace);
workspaceBox.disabled = workspace === null;
workspaceBox.checked = workspace !== null;
workspaceBox.addEventListener("change", () => { if (workspace) workspace.visible = workspaceBox.checked; render(); });

let current = 0;
function showFrame(i) {
  showRanges(i);
  const { p, R } = platformPose(i);
  platform.matrix.copy(frameMatrix(p, R));
  platform.matrixWorldNeedsUpdate = true;
  legGeometry(i).forEach((g, k) => {
    const tubeLength = Math.min(g.L, M.stroke_min[k]);
    place(legs[k].tube, g.a, g.n, tubeLength);
    const rodStart = g.a.map((x, j) => x + g.n[j] * tubeLength);
    place(legs[k].rod, rodStart, g.n, g.L - tubeLength);
    const colour = new THREE.Color(legState(i, k).colour);
    legs[k].tube.material.color.copy(colour);
    legs[k].rod.material.color.copy(colour).lerp(new THREE.Color(0xffffff), 0.45);
  });
}

// ---- Camera and rendering on demand ----
const camera = new THREE.PerspectiveCamera(38, 1, size / 200, size * 200);
camera.up.set(0, 0, 1);
camera.position.set(2.1 * size, -2.7 * size, 1.7 * size + M.home_height / 2);
const controls = new OrbitControls(camera, canvas);
controls.target.set(0, 0, 0.45 * M.home_height);
controls.update();
function resize() {
  const w = canvas.clientWidth, h = canvas.clientHeight;
  if (canvas.width !== w || canvas.height !== h) {
    renderer.setSize(w, h, false);
    camera.aspect = w / Math.max(h, 1);
    camera.updateProjectionMatrix();
  }
}
// The scene is drawn at most once per animation frame: moves that come faster than the screen
// shows them (a drag's input events, a held arrow key, a slow software renderer) each update the
// scene, and only the last state of a frame is drawn, not every one queued behind the others.
let drawQueued = false;
const drawWork = [];  // the last 1000 draws' work [ms] (docs/view.md, speed)
function render() {
  if (drawQueued) return;
  drawQueued = true;
  requestAnimationFrame(() => {
    drawQueued = false;
    const began = performance.now();
    resize();
    renderer.render(scene, camera);
    if (drawWork.push(performance.now() - began) > 1000) drawWork.shift();
  });
}
controls.addEventListener("change", render);
window.addEventListener("resize", () => { render(); drawPlots(); });

// ---- Plots: joint-to-joint lengths with the stroke, and forces when given ----
// The plots are drawn once; the cursor on a canvas of its own above them, so a frame redraws a line.
const plotCanvas = document.getElementById("plot"), cursorCanvas = document.getElementById("cursor");
const LEG_COLOURS = ["#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd", "#8c564b"];
let allLengths = null;  // joint-to-joint, N x 6, computed once
let plotBoxes = [];
function lengthsTable() {  // legGeometry's lengths, without its per-leg arrays (10^5 rows)
  if (allLengths === null) {
    allLengths = new Float64Array(N * LEGS);
    for (let i = 0; i < N; i++) {
      const { p, R } = platformPose(i);
      for (let k = 0; k < LEGS; k++) {
        const a = baseJoint[k], b = platformJoint[k];
        const x = p[0] + (R[0] * b[0] + R[1] * b[1] + R[2] * b[2]) - a[0];
        const y = p[1] + (R[3] * b[0] + R[4] * b[1] + R[5] * b[2]) - a[1];
        const z = p[2] + (R[6] * b[0] + R[7] * b[1] + R[8] * b[2]) - a[2];
        allLengths[LEGS * i + k] = Math.sqrt(x * x + y * y + z * z);
      }
    }
  }
  return allLengths;
}
function drawSeries(ctx, box, values, lo, hi) {
  const x0 = time[0], span = Math.max(time[N - 1] - x0, 1e-300);
  const X = t => box.x + (t - x0) / span * box.w;
  const Y = v => box.y + box.h - (v - lo) / (hi - lo) * box.h;
  for (let k = 0; k < LEGS; k++) {
    ctx.strokeStyle = LEG_COLOURS[k];
    ctx.beginPath();
    if (N <= 4 * box.w) {
      for (let i = 0; i < N; i++) (i ? ctx.lineTo : ctx.moveTo).call(ctx, X(time[i]), Y(values[LEGS * i + k]));
    } else {  // many rows per pixel: each pixel column's min-max
      let column = -1, mn = 0, mx = 0;
      for (let i = 0; i <= N; i++) {
        const c = i < N ? Math.floor(X(time[i])) : -2;
        if (c !== column) {
          if (column >= 0) { ctx.moveTo(column + 0.5, Y(mn)); ctx.lineTo(column + 0.5, Y(mx) - 0.5); }
          if (i === N) break;
          column = c; mn = mx = values[LEGS * i + k];
        } else { const v = values[LEGS * i + k]; if (v < mn) mn = v; if (v > mx) mx = v; }
      }
    }
    ctx.stroke();
  }
}
function panel(ctx, box, values, limits, title) {
  let lo = Infinity, hi = -Infinity;
  for (const v of values) if (Number.isFinite(v)) { if (v < lo) lo = v; if (v > hi) hi = v; }
  for (const v of limits) { lo = Math.min(lo, v); hi = Math.max(hi, v); }
  if (!(hi > lo)) { lo -= 1; hi += 1; }
  const pad = 0.05 * (hi - lo); lo -= pad; hi += pad;
  ctx.strokeStyle = "#bbb"; ctx.strokeRect(box.x, box.y, box.w, box.h);
  ctx.fillStyle = "#222"; ctx.fillText(title, box.x, box.y - 5);
  ctx.fillText(hi.toPrecision(4), 2, box.y + 10); ctx.fillText(lo.toPrecision(4), 2, box.y + box.h);
  ctx.setLineDash([4, 3]); ctx.strokeStyle = "#d62728";
  for (const v of limits) {
    const y = box.y + box.h - (v - lo) / (hi - lo) * box.h;
    ctx.beginPath(); ctx.moveTo(box.x, y); ctx.lineTo(box.x + box.w, y); ctx.stroke();
  }
  ctx.setLineDash([]);
  ctx.save(); ctx.beginPath(); ctx.rect(box.x, box.y, box.w, box.h); ctx.clip();
  drawSeries(ctx, box, values, lo, hi);
  ctx.restore();
}
function drawPlots() {
  const w = plotCanvas.clientWidth, h = plotCanvas.clientHeight;
  plotCanvas.width = cursorCanvas.width = w; plotCanvas.height = cursorCanvas.height = h;
  const ctx = plotCanvas.getContext("2d");
  ctx.font = "11px system-ui, sans-serif";
  if (N < 2) {
    ctx.fillText("One pose: give a result (t and pose columns) for plots and playback.", 10, 20);
    plotBoxes = [];
    return;
  }
  const panels = force ? 2 : 1, left = 52, gap = 34, top = 22;
  const ph = (h - top - 22 - gap * (panels - 1)) / panels;
  plotBoxes = [...Array(panels).keys()].map(j => ({ x: left, y: top + j * (ph + gap), w: w - left - 8, h: ph }));
  const strokes = [...new Set([...M.stroke_min, ...M.stroke_max])];
  panel(ctx, plotBoxes[0], lengthsTable(), strokes, "leg length, joint to joint [m] (dashed: stroke)");
  if (force) panel(ctx, plotBoxes[1], force, [], "actuator force F [N]");
  const last = plotBoxes[panels - 1];
  ctx.fillStyle = "#222";
  ctx.fillText(`${time[0].toPrecision(4)} s`, last.x, last.y + last.h + 14);
  ctx.fillText(`${time[N - 1].toPrecision(4)} s`, last.x + last.w - 50, last.y + last.h + 14);
  LEG_COLOURS.forEach((c, k) => { ctx.fillStyle = c; ctx.fillText(`leg ${k + 1}`, last.x + 60 + 42 * k, last.y + last.h + 14); });
}
function drawCursor() {
  if (!plotBoxes.length) return;
  const ctx = cursorCanvas.getContext("2d");
  ctx.clearRect(0, 0, cursorCanvas.width, cursorCanvas.height);
  const box = plotBoxes[0], span = Math.max(time[N - 1] - time[0], 1e-300);
  const x = box.x + (time[current] - time[0]) / span * box.w;
  ctx.strokeStyle = "#000"; ctx.lineWidth = 1;
  ctx.beginPath();
  for (const b of plotBoxes) { ctx.moveTo(x, b.y); ctx.lineTo(x, b.y + b.h); }
  ctx.stroke();
}
function frameAtTime(t) {  // the last frame at or before t
  let lo = 0, hi = N - 1;
  while (lo < hi) { const mid = (lo + hi + 1) >> 1; if (time[mid] <= t) lo = mid; else hi = mid - 1; }
  return lo;
}
function seekPlot(event) {
  if (!plotBoxes.length || !(event.buttons & 1) && event.type !== "pointerdown") return;
  const box = plotBoxes[0], r = cursorCanvas.getBoundingClientRect();
  const f = Math.min(Math.max((event.clientX - r.left - box.x) / box.w, 0), 1);
  pause();
  setFrame(frameAtTime(time[0] + f * (time[N - 1] - time[0])));
}
cursorCanvas.addEventListener("pointerdown", seekPlot);
cursorCanvas.addEventListener("pointermove", seekPlot);

// ---- Status line, slider, playback ----
const statusLine = document.getElementById("status"), slider = document.getElementById("slider");
const timeLabel = document.getElementById("time"), playButton = document.getElementById("play");
const speed = document.getElementById("speed");
slider.max = String(N - 1);
function statusText(i) {
  const q = pose.subarray(6 * i, 6 * i + 6), deg = 180 / Math.PI;
  const where = `x ${q[0].toFixed(4)} y ${q[1].toFixed(4)} z ${q[2].toFixed(4)} m · roll ${(q[3] * deg).toFixed(2)} ` +
                `pitch ${(q[4] * deg).toFixed(2)} yaw ${(q[5] * deg).toFixed(2)} deg`;
  const c = first[i];
  const verdict = c === 0 ? "within every limit"
    : `<span class="beyond">beyond: ${data.pose_classes[c]} (margin ${firstMargin[i].toPrecision(3)} ${data.pose_class_units[c]})</span>`;
  return `${where} · ${verdict} · condition ${condition[i].toPrecision(4)}${rangeText(i)}`;
}
const frameWork = [];  // the last 1000 setFrame calls' work but the draw [ms] (docs/view.md)
function setFrame(i) {
  const began = performance.now();
  i = Math.min(Math.max(Math.round(Number(i)) || 0, 0), N - 1);
  current = i;
  showFrame(i);
  render();
  drawCursor();
  slider.value = String(i);
  timeLabel.textContent = `t = ${time[i].toFixed(3)} s (${i + 1}/${N})`;
  statusLine.innerHTML = statusText(i);
  if (frameWork.push(performance.now() - began) > 1000) frameWork.shift();
  return i;
}
slider.addEventListener("input", () => { pause(); setFrame(slider.value); });
rangesBox.disabled = ranges === null;
rangesBox.addEventListener("change", () => setFrame(current));

let playing = false, playClock = 0, playStart = 0;
function tick(now) {
  if (!playing) return;
  // An animation frame's timestamp is when the frame began, which can be before play() read
  // the clock: never earlier than the start, so the frames only move forward.
  const t = playStart + Math.max(0, now - playClock) / 1000 * Number(speed.value);
  const i = frameAtTime(t);
  if (i !== current) setFrame(i);
  if (t >= time[N - 1]) { pause(); return; }
  requestAnimationFrame(tick);
}
function play() {
  if (N < 2 || playing) return;
  if (current >= N - 1) setFrame(0);
  playing = true; playButton.textContent = "Pause";
  playStart = time[current]; playClock = performance.now();
  requestAnimationFrame(tick);
}
function pause() { playing = false; playButton.textContent = "Play"; }
playButton.addEventListener("click", () => (playing ? pause() : play()));
// Space plays and pauses, the arrow keys step a frame (the slider steps by itself when focused).
window.addEventListener("keydown", event => {
  if (event.target === slider || event.target === speed || event.target.type === "checkbox") return;
  if (event.key === " ") { event.preventDefault(); (playing ? pause : play)(); }
  else if (event.key === "ArrowRight" || event.key === "ArrowLeft") {
    pause();
    setFrame(current + (event.key === "ArrowRight" ? 1 : -1));
  }
});
speed.addEventListener("change", () => { if (playing) { playStart = time[current]; playClock = performance.now(); } });

// ---- Hover: the leg's nearest limit class and margin ----
const tooltip = document.getElementById("tooltip");
const raycaster = new THREE.Raycaster(), pointer = new THREE.Vector2();
const legMeshes = legs.flatMap(l => [l.tube, l.rod]);
canvas.addEventListener("pointermove", event => {
  const r = canvas.getBoundingClientRect();
  pointer.set((event.clientX - r.left) / r.width * 2 - 1, -(event.clientY - r.top) / r.height * 2 + 1);
  raycaster.setFromCamera(pointer, camera);
  const hit = raycaster.intersectObjects(legMeshes, false)[0];
  if (!hit) { tooltip.style.display = "none"; return; }
  const k = hit.object.userData.leg, s = legState(current, k), L = legLengths(current)[k];
  tooltip.innerHTML = `leg ${k + 1}: length ${L.toFixed(5)} m<br>nearest limit: ${s.class}` +
    (s.margin === null ? "" : `, margin ${s.margin.toPrecision(4)} ${s.unit}`) +
    (s.beyond ? " (at or beyond it)" : "");
  tooltip.style.left = `${event.clientX - r.left + 12}px`;
  tooltip.style.top = `${event.clientY - r.top + 12}px`;
  tooltip.style.display = "block";
});
canvas.addEventListener("pointerleave", () => { tooltip.style.display = "none"; });

// ---- The documented API ----
function frameIndex(i) {
  if (i === undefined) return current;
  if (!Number.isInteger(i) || i < 0 || i >= N) throw new RangeError(`frame ${i} is not in 0..${N - 1}`);
  return i;
}
window.stewartView = {
  frames: N,
  frame: () => current,
  time: i => time[frameIndex(i)],
  setFrame,
  legLengths: i => legLengths(frameIndex(i)),
  legStates: i => [...Array(LEGS).keys()].map(k => legState(frameIndex(i), k)),
  legColours: () => legs.map(l => "#" + l.tube.material.color.getHexString()),
  axisRanges: i => ranges === null ? null : [...Array(6).keys()].map(
    a => [ranges[12 * frameIndex(i) + 2 * a], ranges[12 * frameIndex(i) + 2 * a + 1]]),
  rangeArrows: () => rangeArrows.map(a => a.userData.length),
  workspaceTriangles: () => (workspace ? workspace.userData.triangles : 0),
  play, pause,
  // Where leg k's middle is drawn now, in CSS pixels from the canvas's centre (to point at it).
  legPoint: k => {
    const g = legGeometry(current)[k], r = canvas.getBoundingClientRect();
    const v = new THREE.Vector3(...g.a.map((x, j) => (x + g.top[j]) / 2)).project(camera);
    return { x: v.x * r.width / 2, y: -v.y * r.height / 2 };
  },
  frameWork: () => frameWork.slice(),
  drawWork: () => drawWork.slice(),
  renderer: () => {
    const gl = renderer.getContext(), info = gl.getExtension("WEBGL_debug_renderer_info");
    return info ? gl.getParameter(info.UNMASKED_RENDERER_WEBGL) : gl.getParameter(gl.RENDERER);
  },
  ready: false,
};
const sceneBuilt = performance.now();
drawPlots();
const plotsDrawn = performance.now();
setFrame(0);
requestAnimationFrame(() => {  // after the first draw's (queued first by setFrame)
  window.stewartView.timings = { scriptStart: startedAt, sceneBuilt, plotsDrawn, ready: performance.now() };
  window.stewartView.ready = true;
});
