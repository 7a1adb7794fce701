// Drawing only: polar hemisphere maps, colour bars and line charts on canvases. Every number
// drawn comes from the WebAssembly module (polbrdf's task layer); the colour tables are
// polbrdf-plot's, exported through it. θ runs radially from 0° (centre) to 90° (rim), φ
// counterclockwise from the right (+x), as in the command line's polar figures.

const RIM = 4; // pixels between the 90° circle and the canvas edge

// The grid of a map: zenith angles (deg, ascending from 0) and the number of azimuths.
export function gridOf(thetas, nPhi) {
  const dTheta = thetas.length > 1 ? thetas[1] - thetas[0] : 90;
  return { nTheta: thetas.length, nPhi, dTheta, dPhi: 360 / nPhi };
}

const indexCache = new Map();

// For each pixel of a size × size canvas, the grid node it shows (zenith-major index), or −1
// outside the hemisphere: the nearest node in θ and in φ.
export function pixelNodes(size, grid) {
  const key = `${size}|${grid.nTheta}|${grid.nPhi}|${grid.dTheta}`;
  let idx = indexCache.get(key);
  if (idx) return idx;
  idx = new Int32Array(size * size);
  const c = size / 2, R = size / 2 - RIM;
  for (let y = 0; y < size; y++) {
    for (let x = 0; x < size; x++) {
      const dx = x + 0.5 - c, dy = c - (y + 0.5);
      const r = Math.hypot(dx, dy);
      if (r > R) { idx[y * size + x] = -1; continue; }
      const theta = (r / R) * 90;
      const k = Math.min(Math.round(theta / grid.dTheta), grid.nTheta - 1);
      let phi = (Math.atan2(dy, dx) * 180) / Math.PI;
      if (phi < 0) phi += 360;
      const j = Math.round(phi / grid.dPhi) % grid.nPhi;
      idx[y * size + x] = k * grid.nPhi + j;
    }
  }
  indexCache.set(key, idx);
  return idx;
}

// The canvas pixel (x, y) of direction (θ, φ) in degrees.
export function pixelOf(canvas, theta, phi) {
  const c = canvas.width / 2, R = canvas.width / 2 - RIM;
  const r = (theta / 90) * R, a = (phi * Math.PI) / 180;
  return [c + r * Math.cos(a), c - r * Math.sin(a)];
}

// The grid node under canvas pixel (x, y) (CSS pixels scaled to the canvas), or −1.
export function nodeAt(canvas, grid, x, y) {
  const size = canvas.width;
  const px = Math.floor((x * size) / canvas.clientWidth);
  const py = Math.floor((y * size) / canvas.clientHeight);
  if (px < 0 || py < 0 || px >= size || py >= size) return -1;
  return pixelNodes(size, grid)[py * size + px];
}

// A colour table: `n` RGB triplets then the colour of undefined values (the module's
// `colormap`).
export function lut(bytes) {
  const n = (bytes.length - 3) / 3;
  return { bytes, n, undefined: [bytes[3 * n], bytes[3 * n + 1], bytes[3 * n + 2]] };
}

// The colour of t ∈ [0, 1] (clamped; wrapped when `cyclic`); undefined grey for NaN.
export function colourOf(table, t, cyclic) {
  if (!Number.isFinite(t)) return table.undefined;
  if (cyclic) t -= Math.floor(t);
  const k = Math.round(Math.min(Math.max(t, 0), 1) * (table.n - 1));
  return [table.bytes[3 * k], table.bytes[3 * k + 1], table.bytes[3 * k + 2]];
}

// Paints `values` (one per grid node) through `scale` (value → t) and `table`.
export function drawMap(canvas, grid, values, table, scale, cyclic = false) {
  const size = canvas.width;
  const ctx = canvas.getContext("2d");
  const img = ctx.createImageData(size, size);
  const idx = pixelNodes(size, grid);
  const d = img.data;
  for (let p = 0; p < idx.length; p++) {
    const i = idx[p];
    let rgb;
    if (i < 0) rgb = [255, 255, 255];
    else rgb = colourOf(table, scale(values[i]), cyclic);
    d[4 * p] = rgb[0]; d[4 * p + 1] = rgb[1]; d[4 * p + 2] = rgb[2]; d[4 * p + 3] = 255;
  }
  ctx.putImageData(img, 0, 0);
  drawGuides(canvas);
}

// Zenith circles every 30° and azimuth spokes every 45°.
function drawGuides(canvas) {
  const ctx = canvas.getContext("2d");
  const c = canvas.width / 2, R = canvas.width / 2 - RIM;
  ctx.save();
  ctx.strokeStyle = "rgba(255,255,255,0.45)";
  ctx.lineWidth = 0.7;
  for (const t of [30, 60, 90]) {
    ctx.beginPath(); ctx.arc(c, c, (t / 90) * R, 0, 2 * Math.PI); ctx.stroke();
  }
  for (let a = 0; a < 360; a += 45) {
    const [x, y] = pixelOf(canvas, 90, a);
    ctx.beginPath(); ctx.moveTo(c, c); ctx.lineTo(x, y); ctx.stroke();
  }
  ctx.restore();
}

// Marks: {theta, phi, shape: "sun" | "specular" | "rank" | "cursor", label}.
export function drawMarks(canvas, marks) {
  const ctx = canvas.getContext("2d");
  ctx.save();
  for (const m of marks) {
    const [x, y] = pixelOf(canvas, m.theta, m.phi);
    ctx.lineWidth = 1.5;
    if (m.shape === "specular") {
      ctx.strokeStyle = "#fff";
      ctx.beginPath(); ctx.moveTo(x - 5, y - 5); ctx.lineTo(x + 5, y + 5);
      ctx.moveTo(x - 5, y + 5); ctx.lineTo(x + 5, y - 5); ctx.stroke();
    } else if (m.shape === "sun") {
      ctx.fillStyle = "#ffd21f"; ctx.strokeStyle = "#000";
      ctx.beginPath(); ctx.arc(x, y, 4.5, 0, 2 * Math.PI); ctx.fill(); ctx.stroke();
    } else if (m.shape === "rank") {
      ctx.strokeStyle = "#fff"; ctx.fillStyle = "rgba(0,0,0,0.55)";
      ctx.beginPath(); ctx.arc(x, y, 7, 0, 2 * Math.PI); ctx.fill(); ctx.stroke();
      ctx.fillStyle = "#fff"; ctx.font = "bold 9px sans-serif";
      ctx.textAlign = "center"; ctx.textBaseline = "middle";
      ctx.fillText(m.label, x, y + 0.5);
    } else if (m.shape === "cursor") {
      ctx.strokeStyle = "#f0f"; ctx.lineWidth = 1.2;
      ctx.beginPath(); ctx.arc(x, y, 6, 0, 2 * Math.PI); ctx.stroke();
    }
  }
  ctx.restore();
}

// A horizontal colour bar from `lo` to `hi` with its label.
export function drawBar(canvas, table, cyclic, lo, hi, label) {
  const ctx = canvas.getContext("2d");
  const w = canvas.width, h = canvas.height;
  ctx.clearRect(0, 0, w, h);
  for (let x = 0; x < w; x++) {
    const [r, g, b] = colourOf(table, x / (w - 1), cyclic);
    ctx.fillStyle = `rgb(${r},${g},${b})`;
    ctx.fillRect(x, 0, 1, 10);
  }
  ctx.fillStyle = "#222"; ctx.font = "11px sans-serif"; ctx.textBaseline = "top";
  ctx.textAlign = "left"; ctx.fillText(lo, 0, 13);
  ctx.textAlign = "right"; ctx.fillText(hi, w, 13);
  ctx.textAlign = "center"; ctx.fillText(label, w / 2, 13);
}

// A line chart of ys against xs; `log`: log10 y axis; `mark`: x of a vertical line.
export function drawCurve(canvas, xs, ys, { log = false, xlabel = "", ylo, yhi, mark } = {}) {
  const ctx = canvas.getContext("2d");
  const w = canvas.width, h = canvas.height, L = 46, B = 26, T = 8, Rm = 8;
  ctx.clearRect(0, 0, w, h);
  ctx.fillStyle = "#fff"; ctx.fillRect(0, 0, w, h);
  const f = (y) => (log ? (y > 0 ? Math.log10(y) : NaN) : y);
  const fin = ys.map(f).filter(Number.isFinite);
  let lo = ylo ?? Math.min(...fin), hi = yhi ?? Math.max(...fin);
  if (log) lo = Math.max(lo, hi - 6);
  if (!(hi > lo)) { hi = lo + 1; }
  const x0 = xs[0], x1 = xs[xs.length - 1];
  const X = (x) => L + ((x - x0) / (x1 - x0)) * (w - L - Rm);
  const Y = (y) => h - B - ((y - lo) / (hi - lo)) * (h - B - T);
  ctx.strokeStyle = "#999"; ctx.lineWidth = 1;
  ctx.strokeRect(L, T, w - L - Rm, h - B - T);
  ctx.fillStyle = "#222"; ctx.font = "10px sans-serif";
  ctx.textAlign = "center"; ctx.textBaseline = "top";
  for (let k = 0; k <= 4; k++) {
    const x = x0 + ((x1 - x0) * k) / 4;
    ctx.fillText(x.toFixed(0), X(x), h - B + 3);
  }
  ctx.fillText(xlabel, (L + w) / 2, h - 12);
  ctx.textAlign = "right"; ctx.textBaseline = "middle";
  for (let k = 0; k <= 4; k++) {
    const y = lo + ((hi - lo) * k) / 4;
    ctx.fillText(log ? `1e${y.toFixed(1)}` : y.toFixed(2), L - 3, Y(y));
  }
  ctx.save();
  ctx.beginPath(); ctx.rect(L, T, w - L - Rm, h - B - T); ctx.clip();
  ctx.strokeStyle = "#1f5fbf"; ctx.lineWidth = 1.5; ctx.beginPath();
  let pen = false;
  for (let i = 0; i < xs.length; i++) {
    const y = f(ys[i]);
    if (!Number.isFinite(y)) { pen = false; continue; }
    if (pen) ctx.lineTo(X(xs[i]), Y(y)); else ctx.moveTo(X(xs[i]), Y(y));
    pen = true;
  }
  ctx.stroke();
  if (mark !== undefined && mark !== null) {
    ctx.strokeStyle = "#e0218a"; ctx.lineWidth = 1.2; ctx.setLineDash([4, 3]);
    ctx.beginPath(); ctx.moveTo(X(mark), T); ctx.lineTo(X(mark), h - B); ctx.stroke();
  }
  ctx.restore();
}
