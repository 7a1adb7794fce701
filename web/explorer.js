// The page: controls, state in the URL, calls into the WebAssembly module (polbrdf's task
// layer) and drawing. No physics here: every number shown is the module's.
import init, * as pb from "./pkg/polbrdf_wasm.js";
import * as draw from "./draw.js";

const $ = (id) => document.getElementById(id);
const MATERIAL_INPUTS = [
  "target-index", "target-n", "target-k", "target-rough", "target-rough-value", "target-form",
  "target-shadowing", "target-tau", "target-omega", "target-azimuth", "target-rho-d",
  "target-rho-v",
];
const STATE_INPUTS = [
  "wavelength", "sun-zenith", "sun-azimuth", "s0", "s1", "s2", "s3", "grid", "rank-by", "top",
  "min-sep", "max-zenith", "refine", "spectrum-mode", "band-lo", "band-hi", "band-step",
  "scene-on", "sun-irradiance", "sky-model", "sky-radiance", "sky-temperature", "sky-irradiance",
  "sky-dop-max", "target-temperature", "background-temperature", "transmittance", "path-radiance",
];
// The band file of the preset with edges: examples/lwir-8-12um.csv.
const LWIR_EDGES = "wavelength_um,response\n7.8,0\n8.0,1\n12.0,1\n12.2,0\n";

const view = { map: null, contrast: null, columns: {}, curves: null, best: [], grid: null, cursor: -1 };
let tables = {};
let targetName = null;

// ---- material form ↔ material file text -------------------------------------------------
// The form writes the text (the user's raw entries, so the file reader judges them); the text
// is what the module parses. Editing the text updates the form.
function tomlString(s) {
  return JSON.stringify(s); // a TOML basic string: JSON's escapes are TOML's
}

// n and k are the index's own with a library index: their fields are then disabled.
function syncIndexFields() {
  $("target-n").disabled = $("target-k").disabled = !!$("target-index").value;
}

function formToText() {
  syncIndexFields();
  const v = (id) => $(id).value.trim();
  const lines = [];
  if (targetName) lines.push(`name = ${tomlString(targetName)}`);
  if (v("target-index")) lines.push(`index = ${tomlString("library:" + v("target-index"))}`);
  else lines.push(`n = ${v("target-n")}`, `k = ${v("target-k")}`);
  lines.push(`${v("target-rough")} = ${v("target-rough-value")}`);
  lines.push(`form = ${tomlString(v("target-form"))}`);
  lines.push(`shadowing = ${$("target-shadowing").checked}`);
  lines.push(`tau_deg = ${v("target-tau")}`, `omega_deg = ${v("target-omega")}`);
  lines.push(`azimuth_term = ${tomlString(v("target-azimuth"))}`);
  lines.push(`rho_d = ${v("target-rho-d")}`, `rho_v = ${v("target-rho-v")}`);
  return lines.join("\n") + "\n";
}

function textToForm(text) {
  let e;
  try {
    e = JSON.parse(pb.material_entries(text, "target.toml"));
  } catch {
    return; // the message is shown by the recomputation
  }
  targetName = e.name ?? null;
  const set = (id, x) => { if (x !== undefined) $(id).value = String(x); };
  $("target-index").value = e.index?.startsWith("library:") ? e.index.slice(8) : "";
  set("target-n", e.n); set("target-k", e.k);
  if (e.b !== undefined) { $("target-rough").value = "b"; set("target-rough-value", e.b); }
  else { $("target-rough").value = "sigma_deg"; set("target-rough-value", e.sigma_deg); }
  set("target-form", e.form); $("target-shadowing").checked = !!e.shadowing;
  set("target-tau", e.tau_deg); set("target-omega", e.omega_deg);
  set("target-azimuth", e.azimuth_term); set("target-rho-d", e.rho_d); set("target-rho-v", e.rho_v);
  syncIndexFields();
}

// ---- state in the URL ----------------------------------------------------------------------
function saveState() {
  const p = new URLSearchParams();
  p.set("target", $("target-text").value);
  p.set("background", $("background-text").value);
  p.set("band", $("band-text").value);
  for (const id of STATE_INPUTS) {
    const el = $(id);
    p.set(id, el.type === "checkbox" ? String(el.checked) : el.value);
  }
  history.replaceState(null, "", "#" + p.toString());
}

function loadState() {
  const p = new URLSearchParams(location.hash.slice(1));
  $("target-text").value = p.get("target") ?? pb.preset_toml("paint");
  $("background-text").value = p.get("background") ?? pb.preset_toml("glass");
  for (const id of STATE_INPUTS) {
    if (!p.has(id)) continue;
    const el = $(id);
    if (el.type === "checkbox") el.checked = p.get(id) === "true";
    else el.value = p.get(id);
  }
  $("band-text").value = p.get("band") ?? flatBand();
  textToForm($("target-text").value);
  showSpectrumAndSky();
}

// ---- spectrum and scene: the band file and the scene file the controls write ----------------
// A flat band from λ_min to λ_max as a band file (the user's raw entries: the band reader
// judges them).
function flatBand() {
  return `wavelength_um,response\n${$("band-lo").value.trim()},1\n${$("band-hi").value.trim()},1\n`;
}

function showSpectrumAndSky() {
  const band = $("spectrum-mode").value === "band";
  $("wavelength-set").hidden = band;
  $("band-set").hidden = !band;
  for (const l of document.querySelectorAll("label[data-sky]")) {
    l.hidden = l.dataset.sky !== $("sky-model").value;
  }
}

// The scene file of the controls, as `polbrdf contrast --scene` reads it: its files are the
// page's target.toml, background.toml and band.csv. Values are the raw entries (the scene
// reader judges them); an empty field leaves its key out (a temperature: no emission; a
// required key: the reader says it is missing).
function sceneText() {
  const v = (id) => $(id).value.trim();
  const lines = ["# The polbrdf explorer's scene: polbrdf contrast --scene scene.toml"];
  const kv = (key, id) => { if (v(id)) lines.push(`${key} = ${v(id)}`); };
  if ($("spectrum-mode").value === "band") {
    lines.push("[band]", 'response = "band.csv"');
    kv("step_um", "band-step");
  } else if (v("wavelength")) {
    lines.splice(1, 0, `wavelength_um = ${v("wavelength")}`);
  }
  lines.push("[sun]", `zenith_deg = ${v("sun-zenith")}`, `azimuth_deg = ${v("sun-azimuth")}`);
  kv("irradiance", "sun-irradiance");
  lines.push(`stokes = [${["s0", "s1", "s2", "s3"].map(v).join(", ")}]`);
  const sky = v("sky-model");
  lines.push("[sky]", `model = ${tomlString(sky)}`);
  if (sky === "uniform") kv("radiance", "sky-radiance");
  if (sky === "thermal") kv("temperature_k", "sky-temperature");
  if (sky === "cie-clear") { kv("irradiance", "sky-irradiance"); kv("dop_max", "sky-dop-max"); }
  lines.push("[atmosphere]");
  kv("transmittance", "transmittance"); kv("path_radiance", "path-radiance");
  for (const side of ["target", "background"]) {
    lines.push(`[${side}]`, `material = "${side}.toml"`);
    kv("temperature_k", `${side}-temperature`);
  }
  return lines.join("\n") + "\n";
}

// ---- inputs --------------------------------------------------------------------------------
// A number field as the module's argument: JavaScript's own reading of the text (an
// unreadable entry becomes NaN, which the task layer refuses with its message).
const num = (id) => Number($(id).value.trim() === "" ? NaN : $(id).value);

function request() {
  const wl = $("wavelength").value.trim();
  const band = $("spectrum-mode").value === "band";
  const step = $("band-step").value.trim();
  const [dt, dp] = $("grid").value.split(",").map((s) => Number(s));
  const scene = $("scene-on").checked ? sceneText() : null;
  $("scene-text").value = sceneText();
  return {
    target: $("target-text").value,
    background: $("background-text").value,
    zenith: num("sun-zenith"),
    azimuth: num("sun-azimuth"),
    stokes: new Float64Array(["s0", "s1", "s2", "s3"].map(num)),
    wavelength: band || wl === "" ? undefined : Number(wl),
    bandCsv: band ? $("band-text").value : undefined,
    bandStep: band && step !== "" ? Number(step) : undefined,
    scene,
    grid: [dt, dp ?? dt],
  };
}

// ---- computation ---------------------------------------------------------------------------
function computeMap(r) {
  return pb.hemisphere(r.target, "target.toml", r.zenith, r.azimuth, r.stokes, r.wavelength,
    r.bandCsv, r.bandStep, r.grid[0], r.grid[1]);
}

// Under the collimated sun, or in the scene (the scene file and the files it names).
function computeContrast(r) {
  const rank = [$("rank-by").value, Math.max(0, Math.floor(num("top"))), num("min-sep"),
    num("max-zenith"), $("refine").checked];
  if (r.scene !== null) {
    return pb.scene_contrast(r.scene, r.target, r.background, r.bandCsv, r.grid[0], r.grid[1],
      ...rank);
  }
  return pb.contrast(r.target, r.background, r.zenith, r.azimuth, r.stokes, r.wavelength,
    r.bandCsv, r.bandStep, r.grid[0], r.grid[1], ...rank);
}

// Which box shows a message: the material's, the spectrum's or the light's.
function errorBox(m) {
  if (m.startsWith("material:")) return "target-error";
  if (/^(wavelength_um|band_step_um|band\.csv)/.test(m)) return "spectrum-error";
  return "light-error";
}

function showError(id, e) { $(id).textContent = e ? String(e.message ?? e) : ""; }

function recompute() {
  pending = false;
  const r = request();
  saveState();
  $("sun-zenith-out").textContent = $("sun-zenith").value;
  $("sun-azimuth-out").textContent = $("sun-azimuth").value;
  const times = {};
  let t0 = performance.now();
  for (const id of ["target-error", "spectrum-error", "light-error"]) showError(id, null);
  view.mapError = null;
  try {
    const map = computeMap(r);
    times.map = performance.now() - t0;
    view.map?.free(); view.map = map;
  } catch (e) {
    view.mapError = String(e.message ?? e);
    showError(errorBox(view.mapError), e);
    view.map?.free(); view.map = null;
  }
  showCaptions(r);
  t0 = performance.now();
  try {
    const curves = pb.in_plane(r.target, "target.toml", r.zenith, r.azimuth, r.stokes, r.wavelength,
      r.bandCsv, r.bandStep);
    times.curves = performance.now() - t0;
    view.curves?.free(); view.curves = curves;
  } catch { view.curves?.free(); view.curves = null; }
  // Without a map (an error above), the drawings left are of an earlier state: dimmed.
  $("views").classList.toggle("stale", !view.map);
  render(r);
  showTiming(times);
  // The contrast (two materials and the ranking's refinement: the slow part) after the maps
  // are painted, so that dragging a control stays live.
  contrastPending = true;
  if (r.scene !== null) {
    // A scene takes longer (emission and sky integrals): say so, and let the page paint first.
    $("timing").textContent += " · scene: computing…";
    requestAnimationFrame(() => setTimeout(() => recomputeContrast(r, times), 0));
  } else setTimeout(() => recomputeContrast(r, times), 0);
}

function recomputeContrast(r, times) {
  if (pending) { contrastPending = false; return; } // a newer state is on its way
  const t0 = performance.now();
  showError("background-error", null); showError("scene-error", null);
  $("scene-warnings").textContent = "";
  try {
    const c = computeContrast(r);
    times[r.scene === null ? "contrast" : "scene"] = performance.now() - t0;
    view.contrast?.free(); view.contrast = c; view.columns = {};
    view.best = JSON.parse(c.best_json()).top;
    $("scene-warnings").textContent = c.warnings().map((w) => `warning: ${w}`).join("\n");
  } catch (e) {
    const m = String(e.message ?? e);
    // In a scene, the scene reader's message; else the background's (the target's and the
    // spectrum's are shown above, by the map).
    if (r.scene !== null) showError("scene-error", e);
    else if (!m.startsWith("target:") && m !== view.mapError) showError("background-error", e);
    // Nothing to show on the contrast maps (and in a scene on the DoLP and AoLP maps): blank.
    const blank = ["map-delta", "map-pc", ...(r.scene !== null ? ["map-dolp", "map-aolp"] : [])];
    for (const id of blank) $(id).getContext("2d").clearRect(0, 0, $(id).width, $(id).height);
    view.contrast?.free(); view.contrast = null; view.best = [];
  }
  contrastPending = false;
  render(r);
  showTiming(times);
  document.body.dataset.computed = String(Number(document.body.dataset.computed ?? 0) + 1);
}

function showTiming(times) {
  const ms = (x) => (x === undefined ? "–" : x.toFixed(1));
  const n = view.map ? view.map.n_theta() * view.map.n_phi() : 0;
  const last = times.scene === undefined ? `contrast ${ms(times.contrast)} ms` : `scene ${ms(times.scene)} ms`;
  $("timing").textContent =
    `map ${n} directions (full Mueller) ${ms(times.map)} ms · curves ${ms(times.curves)} ms · ${last}`;
  $("timing").dataset.mapMs = times.map ?? "";
}

let pending = false, contrastPending = false;
function schedule() {
  if (pending) return;
  pending = true;
  requestAnimationFrame(recompute);
}

// A column of the contrast study (contrast.csv's), fetched once per computation.
function ccol(name) {
  view.columns[name] ??= view.contrast.column(name);
  return view.columns[name];
}

// ---- rendering -----------------------------------------------------------------------------
const finite = (a) => a.filter(Number.isFinite);
const maxOf = (a) => finite(a).reduce((m, v) => Math.max(m, v), -Infinity);
const fmt = (v) => (Number.isFinite(v) ? Number(v.toPrecision(4)).toString() : String(v));

function logScale(values) {
  const hi = Math.log10(maxOf(values));
  const lo = hi - 4;
  return { lo, hi, f: (v) => (v > 0 ? (Math.log10(v) - lo) / (hi - lo) : 0) };
}

function marks(r) {
  const m = [];
  if (Number.isFinite(r.zenith)) {
    m.push({ theta: r.zenith, phi: r.azimuth, shape: "sun" });
    m.push({ theta: r.zenith, phi: r.azimuth + 180, shape: "specular" });
  }
  return m;
}

// In a scene the DoLP and AoLP maps are the target's observed radiance's (the contrast
// study's), else the reflected beam's F·S_in.
const inScene = (r) => r.scene !== null;

function showCaptions(r) {
  $("caption-dolp").textContent = inScene(r)
    ? "DoLP, observed radiance (target)" : "DoLP of the reflected beam";
  $("caption-aolp").textContent = inScene(r)
    ? "AoLP, observed radiance (deg)" : "AoLP (deg, cyclic)";
}

function render(r) {
  const base = marks(r);
  const cursor = cursorMark();
  if (view.map) {
    const grid = draw.gridOf(view.map.thetas_deg(), view.map.n_phi());
    view.grid = grid;
    const brdf = view.map.brdf();
    const ls = logScale(brdf);
    draw.drawMap($("map-brdf"), grid, brdf, tables.viridis, ls.f);
    draw.drawBar($("bar-brdf"), tables.viridis, false, `1e${ls.lo.toFixed(1)}`, `1e${ls.hi.toFixed(1)}`, "sr⁻¹");
    const scene = inScene(r) && view.contrast?.is_scene();
    if (!inScene(r) || scene) {
      draw.drawMap($("map-dolp"), grid, scene ? ccol("dolp_target") : view.map.dolp(), tables.viridis, (v) => v);
      draw.drawMap($("map-aolp"), grid, scene ? ccol("aolp_target_deg") : view.map.aolp_deg(), tables.cyclic,
        (v) => (v + 90) / 180, true);
    }
    draw.drawBar($("bar-dolp"), tables.viridis, false, "0", "1", "DoLP");
    draw.drawBar($("bar-aolp"), tables.cyclic, true, "−90°", "90°", "AoLP");
    for (const id of ["map-brdf", "map-dolp", "map-aolp"]) draw.drawMarks($(id), [...base, ...cursor]);
    const m00 = view.map.mueller(0);
    for (let e = 0; e < 16; e++) {
      const c = $(`mueller-${e >> 2}${e & 3}`);
      if (e === 0) draw.drawMap(c, grid, m00, tables.viridis, ls.f);
      else {
        const m = view.map.mueller(e);
        draw.drawMap(c, grid, m.map((v, i) => v / m00[i]), tables.diverging, (v) => (v + 1) / 2);
      }
      draw.drawMarks(c, cursor);
    }
    draw.drawBar($("bar-mueller"), tables.diverging, false, "−1", "1", "m_rc / m₀₀");
  }
  if (view.contrast && view.grid) {
    const d = ccol("delta_dolp");
    const M = Math.max(maxOf(d.map(Math.abs)), 1e-12);
    draw.drawMap($("map-delta"), view.grid, d, tables.diverging, (v) => (v / M + 1) / 2);
    draw.drawBar($("bar-delta"), tables.diverging, false, fmt(-M), fmt(M), "ΔDoLP");
    const pc = ccol("polarization_contrast");
    const P = Math.max(maxOf(pc), 1e-300);
    draw.drawMap($("map-pc"), view.grid, pc, tables.viridis, (v) => v / P);
    draw.drawBar($("bar-pc"), tables.viridis, false, "0", fmt(P), "|ΔS_lin| / mean S0");
    const ranks = view.best.map((b, k) => ({ theta: b.theta_r_deg, phi: b.phi_r_deg, shape: "rank", label: String(k + 1) }));
    for (const id of ["map-delta", "map-pc"]) draw.drawMarks($(id), [...base, ...ranks, ...cursor]);
  }
  renderBest();
  renderCurves(r);
  renderReadout();
}

function cell(name, v) {
  const td = document.createElement("td");
  td.dataset.name = name;
  td.dataset.value = String(v); // shortest round-trip text of the f64
  td.textContent = fmt(v);
  td.title = String(v);
  return td;
}

function renderBest() {
  const t = $("best");
  t.replaceChildren();
  const head = t.insertRow();
  for (const h of ["#", "θr", "φr", "ΔDoLP", "pol. contrast"]) {
    const th = document.createElement("th"); th.textContent = h; head.appendChild(th);
  }
  view.best.forEach((b, k) => {
    const tr = t.insertRow();
    tr.dataset.rank = String(k + 1);
    const th = document.createElement("th"); th.textContent = String(k + 1); tr.appendChild(th);
    tr.appendChild(cell("theta_r_deg", b.theta_r_deg));
    tr.appendChild(cell("phi_r_deg", b.phi_r_deg));
    tr.appendChild(cell("delta_dolp", b.delta_dolp));
    tr.appendChild(cell("polarization_contrast", b.polarization_contrast));
  });
}

// The in-plane position of the cursor: signed θr (positive on the specular side).
function cursorInPlane() {
  if (!view.map || view.cursor < 0) return null;
  const row = view.map.node(view.cursor);
  const side = Math.cos(((row[1] - num("sun-azimuth")) * Math.PI) / 180) <= 0 ? 1 : -1;
  return side * row[0];
}

function renderCurves(r) {
  if (!view.curves) return;
  const x = view.curves.theta_r_deg();
  const mark = cursorInPlane();
  draw.drawCurve($("curve-brdf"), x, view.curves.brdf(), { log: true, xlabel: "θr (deg)", mark });
  draw.drawCurve($("curve-dolp"), x, view.curves.dolp(), { ylo: 0, yhi: 1, xlabel: "θr (deg)", mark });
  draw.drawCurve($("curve-spec"), view.curves.theta_i_deg(), view.curves.specular_dolp(),
    { ylo: 0, yhi: 1, xlabel: "θi = θr (deg), specular", mark: r.zenith });
}

function renderReadout() {
  const t = $("readout");
  t.replaceChildren();
  if (!view.map || view.cursor < 0) {
    t.insertRow().insertCell().textContent = "hover a map";
    return;
  }
  const cols = view.map.columns();
  const row = view.map.node(view.cursor);
  const add = (label, names) => {
    const tr = t.insertRow();
    const th = document.createElement("th"); th.textContent = label; tr.appendChild(th);
    for (const n of names) tr.appendChild(cell(n, row[cols.indexOf(n)]));
  };
  const tr0 = t.insertRow();
  const th0 = document.createElement("th"); th0.textContent = "θi, φi (deg)"; tr0.appendChild(th0);
  tr0.appendChild(cell("theta_i_deg", num("sun-zenith")));
  tr0.appendChild(cell("phi_i_deg", num("sun-azimuth")));
  add("θr, φr (deg)", ["theta_r_deg", "phi_r_deg"]);
  for (let r = 0; r < 4; r++) add(r === 0 ? "F (sr⁻¹)" : "", [0, 1, 2, 3].map((c) => `m${r}${c}`));
  add("BRDF", ["brdf"]);
  add("S out", ["s0", "s1", "s2", "s3"]);
  add("DoLP, AoLP°", ["dolp", "aolp_deg"]);
  if (view.contrast) {
    const names = ["dolp_target", "dolp_background", "delta_dolp", "polarization_contrast"];
    // In a scene: the observed radiances (S0 and AoLP) of both, and their difference.
    if (view.contrast.is_scene()) {
      names.push("intensity_target", "aolp_target_deg", "intensity_background",
        "aolp_background_deg", "radiance_difference");
    }
    for (const n of names) {
      const tr = t.insertRow();
      const th = document.createElement("th"); th.textContent = n; tr.appendChild(th);
      tr.appendChild(cell(n, ccol(n)[view.cursor]));
    }
  }
}

function cursorMark() {
  if (!view.map || view.cursor < 0) return [];
  const row = view.map.node(view.cursor);
  return [{ theta: row[0], phi: row[1], shape: "cursor" }];
}

function hover(ev) {
  if (!view.grid) return;
  const rect = ev.target.getBoundingClientRect();
  const i = draw.nodeAt(ev.target, view.grid, ev.clientX - rect.left, ev.clientY - rect.top);
  if (i < 0 || i === view.cursor) return;
  view.cursor = i;
  render(request());
}

// ---- downloads -----------------------------------------------------------------------------
function save(name, data, type) {
  const a = document.createElement("a");
  a.href = URL.createObjectURL(new Blob([data], { type }));
  a.download = name;
  a.click();
  setTimeout(() => URL.revokeObjectURL(a.href), 1000);
}

function savePng(id) {
  let canvas = $(id);
  if (id === "mueller-all") {
    canvas = document.createElement("canvas");
    const s = $("mueller-00").width;
    canvas.width = canvas.height = 4 * s;
    for (let e = 0; e < 16; e++) {
      canvas.getContext("2d").drawImage($(`mueller-${e >> 2}${e & 3}`), (e & 3) * s, (e >> 2) * s);
    }
  }
  canvas.toBlob((b) => save(`${id}.png`, b, "image/png"), "image/png");
}

function wireDownloads() {
  $("download-scene").onclick = () => {
    // The scene file and the files it names, beside each other (a browser may ask once
    // whether the page may download several files).
    const r = request();
    const files = [["scene.toml", sceneText()], ["target.toml", r.target], ["background.toml", r.background]];
    if ($("spectrum-mode").value === "band") files.push(["band.csv", $("band-text").value]);
    files.forEach(([name, text], k) => setTimeout(() => save(name, text, "text/plain"), 150 * k));
  };
  $("download-toml").onclick = () => {
    try { save("target.toml", pb.material_toml($("target-text").value, "target.toml"), "application/toml"); }
    catch (e) { showError("target-error", e); }
  };
  $("download-map-csv").onclick = () => view.map && save("map.csv", view.map.csv(), "text/csv");
  $("download-contrast-csv").onclick = () => view.contrast && save("contrast.csv", view.contrast.csv(), "text/csv");
  $("download-best-json").onclick = () => view.contrast && save("best.json", view.contrast.best_json(), "application/json");
  for (const b of document.querySelectorAll("button[data-png]")) b.onclick = () => savePng(b.dataset.png);
}

// ---- start ---------------------------------------------------------------------------------
function fillSelect(select, options) {
  for (const [value, label] of options) {
    const o = document.createElement("option");
    o.value = value; o.textContent = label; select.appendChild(o);
  }
}

async function main() {
  await init();
  tables = {
    viridis: draw.lut(pb.colormap("viridis", 256)),
    diverging: draw.lut(pb.colormap("diverging", 256)),
    cyclic: draw.lut(pb.colormap("cyclic", 256)),
  };
  const presets = pb.presets();
  fillSelect($("target-preset"), [["", "—"], ...presets.map((p) => [p, p])]);
  fillSelect($("background-preset"), [["", "—"], ...presets.map((p) => [p, p])]);
  const library = JSON.parse(pb.library_json());
  fillSelect($("target-index"), library.map((e) => [e.id, `${e.id} (${e.material})`]));
  const mu = $("mueller");
  for (let e = 0; e < 16; e++) {
    const c = document.createElement("canvas");
    c.id = `mueller-${e >> 2}${e & 3}`; c.width = c.height = 104; c.className = "map";
    c.title = `m${e >> 2}${e & 3}`;
    mu.appendChild(c);
  }
  loadState();
  $("target-preset").onchange = () => {
    if (!$("target-preset").value) return;
    $("target-text").value = pb.preset_toml($("target-preset").value);
    textToForm($("target-text").value); schedule();
  };
  $("background-preset").onchange = () => {
    if (!$("background-preset").value) return;
    $("background-text").value = pb.preset_toml($("background-preset").value); schedule();
  };
  // "change" as well as "input": a select or checkbox changed by a script or a driver may
  // fire only one of them.
  const fromForm = () => { $("target-text").value = formToText(); schedule(); };
  for (const id of MATERIAL_INPUTS) {
    $(id).addEventListener("input", fromForm);
    $(id).addEventListener("change", fromForm);
  }
  $("target-text").addEventListener("input", () => { textToForm($("target-text").value); schedule(); });
  $("background-text").addEventListener("input", schedule);
  $("band-text").addEventListener("input", schedule);
  const fromRange = () => { $("band-preset").value = ""; $("band-text").value = flatBand(); schedule(); };
  for (const id of ["band-lo", "band-hi"]) $(id).addEventListener("input", fromRange);
  $("band-preset").onchange = () => {
    const p = $("band-preset").value;
    if (!p) return;
    if (p === "edges") $("band-text").value = LWIR_EDGES;
    else {
      [$("band-lo").value, $("band-hi").value] = p.split(",");
      $("band-text").value = flatBand();
    }
    schedule();
  };
  for (const id of ["spectrum-mode", "sky-model"]) $(id).addEventListener("change", showSpectrumAndSky);
  for (const id of STATE_INPUTS) {
    $(id).addEventListener("input", schedule);
    $(id).addEventListener("change", schedule);
  }
  for (const b of document.querySelectorAll("button[data-stokes]")) {
    b.onclick = () => {
      b.dataset.stokes.split(",").forEach((v, k) => { $(`s${k}`).value = v; });
      schedule();
    };
  }
  for (const c of document.querySelectorAll("canvas.map")) c.addEventListener("mousemove", hover);
  wireDownloads();
  recompute();
  $("status").textContent = `polbrdf ${pb.version()} (WebAssembly)`;
  document.body.dataset.ready = "true";
}

// For the browser test and the curious: the module, the view, and a timing of the map alone.
window.explorer = {
  pb, view, draw,
  busy: () => pending || contrastPending,
  pixelOf: (id, theta, phi) => draw.pixelOf($(id), theta, phi),
  timeMap(reps) {
    const r = request(), out = [];
    for (let k = 0; k < reps; k++) {
      const t0 = performance.now();
      const m = computeMap(r);
      out.push(performance.now() - t0);
      m.free();
    }
    return out;
  },
  // The contrast in the page's scene (both observed radiances over the grid, sun + sky +
  // emission, and the ranking), as the page computes it after a control moves.
  timeScene(reps) {
    const r = { ...request(), scene: sceneText() }, out = [];
    for (let k = 0; k < reps; k++) {
      const t0 = performance.now();
      const c = computeContrast(r);
      out.push(performance.now() - t0);
      c.free();
    }
    return out;
  },
};

main().catch((e) => { $("status").textContent = `failed to start: ${e.message ?? e}`; });
