// lamplight view: the page. It shows the frames the server streams (linear
// radiance, exposed and sRGB-encoded here), moves the camera with the mouse,
// and draws the ray tree of a clicked pixel over the image (inspector.js).
"use strict";

const token = new URLSearchParams(location.search).get("token") || "";
const $ = (id) => document.getElementById(id);
const canvas = $("image"), ctx = canvas.getContext("2d"), svg = $("rays");

// What tests and benchmarks read (window.lamplight).
const hooks = { frames: 0, info: null, state: null, explain: null, errors: [], saved: [], pixels: null };
window.lamplight = hooks;

let state = null;       // the server's latest `state` message
let camera = null;      // the camera shown (ahead of the server while dragging)
let frameInfo = null;   // the `frame` message the next binary message belongs to
let frame = null;       // { info, data: Float32Array }
let exposure = 0;

// ---- vectors
const add = (a, b) => [a[0] + b[0], a[1] + b[1], a[2] + b[2]];
const sub = (a, b) => [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
const mul = (a, s) => [a[0] * s, a[1] * s, a[2] * s];
const dot = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
const cross = (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
const len = (a) => Math.sqrt(dot(a, a));
const norm = (a) => mul(a, 1 / (len(a) || 1));
// Rodrigues' rotation of v about the unit axis k by angle t.
const rotate = (v, k, t) => add(add(mul(v, Math.cos(t)), mul(cross(k, v), Math.sin(t))), mul(k, dot(k, v) * (1 - Math.cos(t))));

// ---- the connection
const ws = new WebSocket(`ws://${location.host}/ws?token=${encodeURIComponent(token)}`);
ws.binaryType = "arraybuffer";
const send = (m) => { if (ws.readyState === 1) ws.send(JSON.stringify(m)); };
ws.onclose = () => { $("status").textContent = "disconnected (the viewer stopped?)"; };
ws.onmessage = (e) => {
  if (typeof e.data !== "string") {
    if (frameInfo) { frame = { info: frameInfo, data: new Float32Array(e.data) }; frameInfo = null; showFrame(); }
    return;
  }
  const m = JSON.parse(e.data);
  if (m.type === "state") applyState(m);
  else if (m.type === "frame") frameInfo = m;
  else if (m.type === "explain") showExplain(m);
  else if (m.type === "saved") { hooks.saved.push(m); say(`saved ${m.name} (${m.spp} spp${m.last ? "" : ", still refining"})`); }
  else if (m.type === "error" && m.exists && lastSave && lastSave.name === m.exists && window.confirm(`${m.exists} exists and this viewer did not write it. Replace it?`)) send({ ...lastSave, replace: m.exists });
  else if (m.type === "error") { hooks.errors.push(m.message); say(m.message); explainFailed(); }
};

function say(text) { $("message").textContent = text; }

function applyState(m) {
  state = m; hooks.state = m;
  $("scene").textContent = m.scene_file || m.scene;
  if (!dragging) camera = m.camera;
  $("camera_toml").value = m.camera_toml;
  $("vfov").value = camera.vfov; $("vfov_value").textContent = (+camera.vfov).toFixed(1) + "°";
  const sel = $("integrator");
  if (sel.options.length === 1) for (const name of m.integrators) sel.add(new Option(name, name));
  sel.value = m.settings.integrator || "";
  if (document.activeElement !== $("spp")) $("spp").value = m.settings.spp ?? "";
  if (document.activeElement !== $("max_depth")) $("max_depth").value = m.settings.max_depth ?? "";
  $("denoise").checked = !!m.settings.denoise;
  const overlay = $("overlay");
  overlay.hidden = !m.error;
  overlay.textContent = m.error || "";
  // The scene's warnings (its files', and a light shut in or reaching nothing), as `lamplight render` prints them.
  const list = $("warnings"), warnings = m.warnings || [];
  if (list.dataset.shown !== JSON.stringify(warnings)) {
    list.dataset.shown = JSON.stringify(warnings);
    list.replaceChildren(...warnings.map((w) => { const li = document.createElement("li"); li.textContent = "warning: " + w; return li; }));
  }
  list.hidden = warnings.length === 0;
  showTimeline(m);
  if (canvas.width !== m.settings.width || canvas.height !== m.settings.height) {
    canvas.width = m.settings.width; canvas.height = m.settings.height;
  }
  // Drawn in image pixels, shown over the canvas's box and clipped to it (app.css).
  svg.setAttribute("viewBox", `0 0 ${canvas.width} ${canvas.height}`);
  const shown = inspector.explained;
  if (shown && m.generation > shown.generation) markStale("the camera, the settings or the scene changed");
}

// ---- frames: linear radiance -> exposure -> sRGB bytes (a table of 2^16 steps)
const SRGB = new Uint8ClampedArray(65536);
for (let i = 0; i < 65536; i++) {
  const v = i / 65535;
  SRGB[i] = Math.round(255 * (v <= 0.0031308 ? 12.92 * v : 1.055 * Math.pow(v, 1 / 2.4) - 0.055));
}
const scratch = document.createElement("canvas");

function showFrame() {
  const { info, data } = frame;
  hooks.frames++; hooks.info = info;
  // Milliseconds from the page's navigation to its first image.
  if (hooks.frames === 1) { hooks.firstFrameMs = performance.now(); hooks.firstInfo = info; }
  if (info.width === info.full_width && info.height === info.full_height) hooks.pixels = { info, data };
  const scale = Math.pow(2, exposure) * 65535;
  const image = new ImageData(info.width, info.height);
  const out = image.data;
  for (let i = 0, j = 0; i < data.length; i += 3, j += 4) {
    out[j] = SRGB[Math.min(65535, Math.max(0, data[i] * scale)) | 0];
    out[j + 1] = SRGB[Math.min(65535, Math.max(0, data[i + 1] * scale)) | 0];
    out[j + 2] = SRGB[Math.min(65535, Math.max(0, data[i + 2] * scale)) | 0];
    out[j + 3] = 255;
  }
  scratch.width = info.width; scratch.height = info.height;
  scratch.getContext("2d").putImageData(image, 0, 0);
  ctx.imageSmoothingEnabled = info.width !== info.full_width;
  ctx.drawImage(scratch, 0, 0, canvas.width, canvas.height);
  const rate = info.samples_per_second >= 1e6 ? (info.samples_per_second / 1e6).toFixed(2) + " M" : (info.samples_per_second / 1e3).toFixed(1) + " k";
  const target = info.adaptive ? "adaptive" : info.target_spp;
  $("status").textContent = `${info.frame != null ? `frame ${info.frame} · ` : ""}${info.width}x${info.height} · spp ${info.spp}/${target} · ${rate} samples/s · ${info.latency_ms.toFixed(0)} ms${info.denoise_ms != null ? ` · denoise +${info.denoise_ms.toFixed(0)} ms` : ""}${info.last ? " · done" : ""}${info.preview ? " · playing (preview)" : ""}`;
  for (const w of waiters.splice(0)) w();
  reexplainIfStale(info, dragging);
}

// A checksum of the pixels shown (tests compare images by it).
hooks.checksum = () => {
  const d = ctx.getImageData(0, 0, canvas.width, canvas.height).data;
  let h = 0;
  for (let i = 0; i < d.length; i++) h = (h * 31 + d[i]) >>> 0;
  return h;
};

// The linear value of full-image pixel (x, y) of the latest full-size frame.
hooks.pixel = (x, y) => {
  const p = hooks.pixels; if (!p) return null;
  const i = 3 * (y * p.info.width + x);
  return [p.data[i], p.data[i + 1], p.data[i + 2]];
};

// ---- camera controls
let dragging = false, dragStart = null, last = null, moved = false, queued = false;
function sendCamera() {
  if (queued) return;
  queued = true;
  requestAnimationFrame(() => { queued = false; send({ type: "camera", camera }); hooks.sentAt = performance.now(); });
}
function basis(c) {
  const w = norm(sub(c.look_at, c.eye));
  const r = norm(cross(w, c.up));
  return { w, r, u: cross(r, w), d: len(sub(c.look_at, c.eye)) };
}
function orbit(dx, dy) {
  const { r } = basis(camera);
  let offset = sub(camera.eye, camera.look_at);
  offset = rotate(offset, norm(camera.up), -dx * 0.008);
  const r2 = norm(cross(mul(offset, -1), camera.up));
  const tilted = rotate(offset, r2.every((x) => isFinite(x)) ? r2 : r, -dy * 0.008);
  // Stop short of looking straight along up.
  if (Math.abs(dot(norm(tilted), norm(camera.up))) < 0.995) offset = tilted;
  camera = { ...camera, eye: add(camera.look_at, offset) };
}
function pan(dx, dy) {
  const { r, u, d } = basis(camera);
  const perPixel = (2 * d * Math.tan((camera.vfov * Math.PI) / 360)) / canvas.clientHeight;
  const shift = add(mul(r, -dx * perPixel), mul(u, dy * perPixel));
  camera = { ...camera, eye: add(camera.eye, shift), look_at: add(camera.look_at, shift) };
}
function zoom(steps) {
  const { w, d } = basis(camera);
  camera = { ...camera, eye: sub(camera.look_at, mul(w, Math.max(1e-4, d * Math.exp(steps * 0.0015)))) };
}
function setFov(vfov) {
  camera = { ...camera, vfov: Math.min(150, Math.max(5, vfov)) };
  $("vfov").value = camera.vfov; $("vfov_value").textContent = camera.vfov.toFixed(1) + "°";
}

canvas.addEventListener("contextmenu", (e) => e.preventDefault());
canvas.addEventListener("mousedown", (e) => {
  if (!camera) return;
  dragging = true; moved = false; dragStart = last = [e.clientX, e.clientY];
  e.preventDefault();
});
window.addEventListener("mousemove", (e) => {
  if (!dragging) return;
  const dx = e.clientX - last[0], dy = e.clientY - last[1];
  last = [e.clientX, e.clientY];
  if (Math.abs(e.clientX - dragStart[0]) + Math.abs(e.clientY - dragStart[1]) > 3) moved = true;
  if (!moved) return;
  markStale("the camera moved");
  if (e.shiftKey || e.buttons === 2) pan(dx, dy); else orbit(dx, dy);
  sendCamera();
});
window.addEventListener("mouseup", (e) => {
  if (!dragging) return;
  dragging = false;
  if (!moved && e.target === canvas) {
    const rect = canvas.getBoundingClientRect();
    const x = Math.floor(((e.clientX - rect.left) * canvas.width) / rect.width);
    const y = Math.floor(((e.clientY - rect.top) * canvas.height) / rect.height);
    explainPixel(x, y);
  }
  reexplainIfStale(hooks.info, dragging);
});
canvas.addEventListener("wheel", (e) => {
  if (!camera) return;
  e.preventDefault();
  if (e.altKey || e.ctrlKey) setFov(camera.vfov * Math.exp(e.deltaY * 0.001)); else zoom(e.deltaY);
  sendCamera();
}, { passive: false });
$("vfov").addEventListener("input", (e) => { if (camera) { setFov(+e.target.value); sendCamera(); } });
$("reset").onclick = () => send({ type: "reset" });
$("copy").onclick = async () => {
  const text = state ? state.camera_toml : "";
  try { await navigator.clipboard.writeText(text); say("camera copied as TOML"); }
  catch { $("camera_toml").select(); document.execCommand("copy"); say("camera copied as TOML"); }
};
const settings = () => {
  const count = (id) => ($(id).value === "" ? null : Math.max(0, Math.floor(+$(id).value)));
  send({ type: "settings", integrator: $("integrator").value || null, spp: count("spp"), max_depth: count("max_depth"), denoise: $("denoise").checked || null });
};
$("integrator").onchange = settings; $("spp").onchange = settings; $("max_depth").onchange = settings; $("denoise").onchange = settings;
$("exposure").addEventListener("input", (e) => {
  exposure = +e.target.value; $("exposure_value").textContent = exposure;
  if (frame) showFrame();
});
// The last save asked for: replacing a file the viewer did not write is asked again, naming it.
let lastSave = null;
const save = (m) => { lastSave = m; send(m); };
$("save").onclick = () => save({ type: "save", name: $("save_name").value, exposure });
$("save_camera").onclick = () => save({ type: "save_camera", name: $("camera_name").value });

// ---- the timeline of an animated scene: a slider over its frames, play/pause
let scrubbing = false, frameQueued = false;
function showTimeline(m) {
  const a = m.animation, slider = $("frame");
  $("timeline").hidden = !a;
  if (!a) return;
  slider.min = a.start; slider.max = a.end;
  // The server's frame, unless the slider is in the user's hand.
  if (!scrubbing) slider.value = m.frame;
  $("frame_value").textContent = `frame ${scrubbing ? slider.value : m.frame} of ${a.start}-${a.end} · ${a.fps} fps`;
  $("play").textContent = m.playing ? "pause" : "play";
}
// The newest frame wins on the server too; one message per animation frame of the page is plenty.
function sendFrame() {
  if (frameQueued) return;
  frameQueued = true;
  requestAnimationFrame(() => { frameQueued = false; send({ type: "frame", frame: +$("frame").value }); });
}
$("frame").addEventListener("pointerdown", () => { scrubbing = true; });
window.addEventListener("pointerup", () => { scrubbing = false; });
$("frame").addEventListener("input", () => {
  if (state && state.animation) $("frame_value").textContent = `frame ${$("frame").value} of ${state.animation.start}-${state.animation.end} · ${state.animation.fps} fps`;
  sendFrame();
});
$("play").onclick = () => send({ type: state && state.playing ? "pause" : "play" });

// ---- the pixel inspector (inspector.js)
hooks.explainPixel = (x, y) => explainPixel(x, y);
hooks.selectSample = (i) => selectSample(i, "button");

// ---- for tests and benchmarks: resolves when the next frame arrives.
const waiters = [];
hooks.nextFrame = () => new Promise((resolve) => waiters.push(resolve));
// Sends `c` and times the first frame of it (the preview) and its first full-size frame.
hooks.timeCamera = async (c) => {
  const g0 = hooks.state ? hooks.state.generation : 0;
  const t0 = performance.now();
  camera = c; send({ type: "camera", camera: c });
  let first = null;
  for (;;) {
    await hooks.nextFrame();
    if (hooks.info.generation <= g0) continue;
    const t = performance.now() - t0;
    if (first === null) first = t;
    if (hooks.info.width === hooks.info.full_width) return { first_ms: first, full_ms: t };
  }
};
