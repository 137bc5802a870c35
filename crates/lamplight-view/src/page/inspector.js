// lamplight view: the pixel inspector. It shows the ray tree of a clicked
// pixel beside the image and draws one sample's rays over it.
//
// This script runs before app.js and defines functions only: what they use of
// app.js (camera, state, svg, send, hooks, ...) exists by the time a click or
// a message calls them, and app.js's messages never reach a page whose
// inspector is not defined yet.
"use strict";

const fmt = (v) => (Array.isArray(v) ? "(" + v.map((x) => (x === null ? "inf" : (+x).toPrecision(4))).join(", ") + ")" : typeof v === "number" ? (+v).toPrecision(4) : String(v));
const el = (tag, cls, text) => { const e = document.createElement(tag); if (cls) e.className = cls; if (text !== undefined) e.textContent = text; return e; };

// What the inspector shows: the latest explanation, the rays of each of its
// samples, the sample drawn, and whether the view has moved on since.
const inspector = { explained: null, segments: [], selected: 0, stale: false, pending: null };

// Asks for pixel (x, y) of the frame shown. `again`: the same pixel for a new
// view (the stale tree stays until the new one comes, and the sample chosen
// is kept).
function explainPixel(x, y, again) {
  inspector.pending = { x, y, again: !!again };
  if (!again) {
    inspector.explained = null; hooks.explain = null; svg.textContent = "";
    $("tree").textContent = `explaining pixel (${x}, ${y})...`;
  }
  send({ type: "explain", x, y });
}

let rayId = 0;
function showExplain(m) {
  const again = inspector.pending && inspector.pending.again && inspector.explained && inspector.explained.x === m.x && inspector.explained.y === m.y;
  inspector.pending = null;
  inspector.explained = m; inspector.stale = false;
  hooks.explain = m; hooks.stale = false; hooks.explained = (hooks.explained || 0) + 1;
  const t = m.tree, root = $("tree");
  root.textContent = "";
  root.classList.remove("stale");
  const samples = t.samples;
  const n = samples.length;
  const sum = [0, 0, 0];
  for (const s of samples) for (const c of s.contributions) for (let k = 0; k < 3; k++) sum[k] += c[k];
  root.append(el("p", "", `pixel (${m.x}, ${m.y}) of ${t.width}x${t.height}, ${t.integrator}, ${t.spp} sample${t.spp === 1 ? "" : "s"}, max depth ${t.max_depth}`));
  const u = t.unrecorded;
  if (u) {
    // Past the recorded samples: the film's sum of the others (docs/explain.md).
    const all = sum.map((x, k) => (x + u.film_sum[k]) / t.spp);
    root.append(el("p", "sum", `pixel value ${fmt(t.value)} = mean over ${t.spp} samples ${fmt(all)}: the first ${n} shown, the other ${u.count} traced but not recorded${u.why && u.why.memory_allowance !== undefined ? ` (their records would pass the explanation's memory allowance of ${(u.why.memory_allowance / 1048576).toFixed(1)} MiB)` : ""} (mean ${fmt(u.mean)}${u.brightest ? `, brightest sample ${u.brightest.index}: ${fmt(u.brightest.film_value)}` : ""})`));
  } else {
    root.append(el("p", "sum", `pixel value ${fmt(t.value)} = mean over ${n} sample${n === 1 ? "" : "s"} of the sum of their contributions ${fmt(sum.map((x) => x / n))}`));
  }
  // One sample's rays are drawn: 64 paths at once hide each other. The
  // others are a click away (the buttons, or a sample's own line).
  const nav = el("p", "samples");
  const prev = el("button", "", "◀"), next = el("button", "", "▶");
  prev.type = next.type = "button"; prev.id = "sample_prev"; next.id = "sample_next";
  prev.title = "the previous sample's rays"; next.title = "the next sample's rays";
  prev.onclick = () => selectSample(inspector.selected - 1, "button");
  next.onclick = () => selectSample(inspector.selected + 1, "button");
  const label = el("span", "", ""); label.id = "sample_label";
  nav.append(prev, " ", label, " ", next);
  if (n > 0) root.append(nav);
  rayId = 0;
  inspector.segments = [];
  samples.forEach((s, i) => {
    const segments = [];
    const d = el("details", "sample"); d.dataset.sample = i;
    const summary = el("summary", "", `sample ${s.index}: radiance ${fmt(s.radiance)} = sum of ${s.contributions.length} contributions`);
    summary.addEventListener("click", () => selectSample(i, "summary"));
    d.append(summary);
    if (s.ray) d.append(rayNode(s.ray, segments));
    if (s.path) d.append(pathNode(s.path, segments));
    root.append(d);
    inspector.segments.push(segments);
  });
  selectSample(again ? inspector.selected : 0, "tree");
  // Explained from a frame the view has already left (the camera moved while it ran).
  if (state && m.generation < state.generation) markStale("the view changed while the pixel was explained");
}

// Draws sample `i` (wrapping around). A new tree and the buttons open only
// that sample's part of the tree (the buttons also scroll to it); a click on
// its own line leaves the opening to the browser, which toggles it after this
// handler.
function selectSample(i, how) {
  const m = inspector.explained; if (!m) return;
  const n = inspector.segments.length;
  inspector.selected = n ? ((i % n) + n) % n : 0;
  hooks.sample = inspector.selected;
  for (const d of document.querySelectorAll("#tree details.sample")) {
    const on = +d.dataset.sample === inspector.selected;
    d.classList.toggle("selected", on);
    if (how !== "summary") d.open = on;
    if (on && how === "button") d.scrollIntoView({ block: "nearest" });
  }
  const s = m.tree.samples[inspector.selected];
  const label = $("sample_label");
  if (label && s) label.textContent = `sample ${s.index} drawn (${inspector.selected + 1} of ${n})`;
  // A stale tree's rays would point at the wrong things in the new image.
  if (inspector.stale) { svg.textContent = ""; return; }
  drawRays(n ? inspector.segments[inspector.selected] : [], m.camera, s ? s.index : null);
  markPixel(m);
}

// The pixel itself: the camera ray runs straight into the screen there.
function markPixel(m) {
  const mark = document.createElementNS("http://www.w3.org/2000/svg", "circle");
  mark.setAttribute("cx", m.x + 0.5); mark.setAttribute("cy", m.y + 0.5); mark.setAttribute("r", 5);
  mark.setAttribute("stroke", COLOURS.camera); mark.setAttribute("class", "ray");
  svg.append(mark);
}

// The view changed (camera, settings or scene): the tree describes the old
// one. Its rays are taken off the image, where they would point at the wrong
// things, and the tree says so until it is explained again for the new view.
function markStale(why) {
  const m = inspector.explained;
  if (!m || inspector.stale) return;
  inspector.stale = true; hooks.stale = true; hooks.staleMarks = (hooks.staleMarks || 0) + 1;
  svg.textContent = "";
  const root = $("tree");
  root.classList.add("stale");
  const note = el("p", "stale-note", `stale: ${why}; this tree is of the view before. Pixel (${m.x}, ${m.y}) is explained again when the new view's first frame comes.`);
  note.id = "stale_note";
  root.prepend(note);
}

// Explains the stale tree's pixel again once a frame of the current view is
// shown and the mouse is not dragging: one pixel's samples, cheap beside the
// frame itself. A pixel the new image size lacks stays stale.
function reexplainIfStale(info, dragging) {
  const m = inspector.explained;
  if (!m || !inspector.stale || dragging || inspector.pending || !state || !info) return;
  if (info.generation !== state.generation || info.generation <= m.generation) return;
  if (m.x >= info.full_width || m.y >= info.full_height) return;
  explainPixel(m.x, m.y, true);
}

// An explanation the server refused: nothing is pending any more.
function explainFailed() { inspector.pending = null; }

function segment(segments, kind, from, to, extra) {
  const id = "ray" + rayId++;
  segments.push({ id, kind, from, to, ...extra });
  return id;
}
function hover(node, id) {
  node.dataset.ray = id;
  node.addEventListener("mouseenter", () => { const p = document.getElementById(id); if (p) p.classList.add("hl"); });
  node.addEventListener("mouseleave", () => { const p = document.getElementById(id); if (p) p.classList.remove("hl"); });
}
function farPoint(origin, direction) {
  const c = camera || { eye: origin, look_at: origin };
  return add(origin, mul(norm(direction), 20 * (len(sub(c.look_at, c.eye)) || 1)));
}

function rayNode(r, segments) {
  const d = el("details"); d.open = true;
  const end = r.hit ? r.hit.point : farPoint(r.origin, r.direction);
  const id = segment(segments, r.kind, r.origin, end, {});
  const what = r.hit ? `hit ${r.hit.object_name ? "'" + r.hit.object_name + "' " : ""}${r.hit.object_kind} at t = ${fmt(r.hit.t)}` : r.miss ? `miss: sky ${fmt(r.miss.sky)}` : r.dropped || "";
  const s = el("summary", "k-" + r.kind, `${r.kind} ray, depth ${r.depth}${r.inside ? ", inside" : ""}: ${what}${r.contribution ? " · contribution " + fmt(r.contribution) : ""}`);
  hover(s, id);
  d.append(s);
  const ul = el("ul");
  const li = (text, cls) => { const e = el("li", cls, text); ul.append(e); return e; };
  li(`weight ${fmt(r.weight)}, origin ${fmt(r.origin)}, direction ${fmt(r.direction)}`);
  if (r.hit) {
    const h = r.hit;
    li(`material ${h.material_name ? "'" + h.material_name + "'" : h.material}, point ${fmt(h.point)}, normal ${fmt(h.shading_normal)}${h.normal_flipped ? " (flipped: back face)" : ""}`);
  }
  if (r.terms) {
    const t = r.terms;
    li(`colour C ${fmt(t.color)}, emission ${fmt(t.emission)}, ambient ka*C*La ${fmt(t.ambient)}`);
    // Point, spot and directional lights one line each; an area light's
    // samples folded into one entry per emitting object.
    const groups = new Map();
    for (const l of t.lights) {
      const key = l.light !== undefined ? `light ${l.light}` : `area light (object ${l.area_light_object})`;
      if (!groups.has(key)) groups.set(key, []);
      groups.get(key).push(l);
    }
    for (const [name, records] of groups) {
      let parent = ul;
      if (records.length > 1) {
        const lit = records.filter((l) => !l.unlit).length;
        const total = records.reduce((s, l) => add(s, l.radiance), [0, 0, 0]);
        const g = el("details");
        g.append(el("summary", "k-shadow", `${name} (${records[0].kind}): ${records.length} samples, ${lit} reach the point → ${fmt(total)}`));
        parent = el("ul");
        g.append(parent);
        const item = el("li"); item.append(g); ul.append(item);
      }
      for (const l of records) {
        if (l.unlit) { parent.append(el("li", "", `${name} (${l.kind}): unlit, ${l.unlit}`)); continue; }
        const sr = l.shadow_ray;
        const blocked = sr.blocked;
        const to = sr.length === null ? farPoint(sr.origin, sr.direction) : add(sr.origin, mul(norm(sr.direction), sr.length));
        const sid = segment(segments, blocked ? "blocked" : "shadow", sr.origin, to, {});
        const by = sr.blocked_by.map((b) => b.name || `${b.kind} ${b.object}`).join(", ");
        const e = el("li", blocked ? "light k-blocked" : "light k-shadow",
          `${name} (${l.kind}): L.N ${fmt(l["L.N"])}, H.N ${fmt(l["H.N"])}, kd C (L.N) ${fmt(l.diffuse)}, ks (H.N)^n ${fmt(l.specular)}; shadow ray ${blocked ? "blocked by " + by : "clear" + (by ? " (dimmed by " + by + ")" : "")} → ${fmt(l.radiance)}`);
        hover(e, sid);
        parent.append(e);
      }
    }
    li(`direct light ${fmt(t.direct)}`);
  }
  if (r.reflection) li(`reflection: ${r.reflection.how}${r.reflection.F !== undefined ? ", F = " + fmt(r.reflection.F) : ""}, weight ${fmt(r.reflection.weight)}`, "k-reflected");
  if (r.refraction) li(r.refraction.total_internal_reflection ? "refraction: total internal reflection" : `refraction: 1 - F = ${fmt(r.refraction.one_minus_F)}, weight ${fmt(r.refraction.weight)}`, "k-refracted");
  if (r.depth_cutoff) li("depth limit reached: the recursion stops here");
  d.append(ul);
  for (const c of r.children || []) d.append(rayNode(c, segments));
  return d;
}

function pathNode(p, segments) {
  const d = el("div");
  for (const v of p.vertices) {
    const end = v.hit ? v.hit.point : farPoint(v.origin, v.direction);
    const id = segment(segments, v.depth === 1 ? "camera" : "reflected", v.origin, end, {});
    const s = el("details"); s.open = true;
    const sum = el("summary", v.depth === 1 ? "k-camera" : "k-reflected", `vertex ${v.depth}: ${v.hit ? "hit " + (v.hit.object_name || v.hit.object_kind) : "escaped"}, throughput ${fmt(v.throughput)}`);
    hover(sum, id);
    s.append(sum);
    const ul = el("ul");
    for (const [k, val] of Object.entries(v)) {
      if (["origin", "direction", "hit", "depth", "throughput"].includes(k)) continue;
      ul.append(el("li", "", `${k}: ${JSON.stringify(val)}`));
    }
    s.append(ul);
    d.append(s);
  }
  if (p.end) d.append(el("p", "", `path ends: ${JSON.stringify(p.end)}`));
  return d;
}

// Projects world point p into the image of camera c (the renderer's pinhole
// camera: window one unit in front of the eye, tan(hfov/2) = aspect tan(vfov/2)).
function project(c, p) {
  const { w, r, u } = basis(c);
  const d = sub(p, c.eye);
  const z = dot(d, w);
  const tv = Math.tan((c.vfov * Math.PI) / 360), th = (tv * canvas.width) / canvas.height;
  const a = dot(d, r) / z / th, b = dot(d, u) / z / tv;
  return [((a + 1) / 2) * canvas.width, ((1 - b) / 2) * canvas.height];
}
// The part of segment a-b in front of the eye (z >= near), projected.
function clipProject(c, a, b) {
  const { w } = basis(c);
  const near = 1e-3 * (len(sub(c.look_at, c.eye)) || 1);
  const za = dot(sub(a, c.eye), w), zb = dot(sub(b, c.eye), w);
  if (za < near && zb < near) return null;
  if (za < near) a = add(a, mul(sub(b, a), (near - za) / (zb - za)));
  if (zb < near) b = add(b, mul(sub(a, b), (near - zb) / (za - zb)));
  return [project(c, a), project(c, b)];
}
// The part of the projected segment p-q inside the image (Liang and Barsky's
// clipping), or null. The stage also hides what overflows it; clipping here
// keeps every drawn line's end on the image, where tests can check it.
function clipToImage(p, q) {
  const dx = q[0] - p[0], dy = q[1] - p[1];
  let t0 = 0, t1 = 1;
  const edges = [[-dx, p[0]], [dx, canvas.width - p[0]], [-dy, p[1]], [dy, canvas.height - p[1]]];
  for (const [den, num] of edges) {
    if (den === 0) { if (num < 0) return null; continue; }
    const t = num / den;
    if (den < 0) { if (t > t1) return null; if (t > t0) t0 = t; } else { if (t < t0) return null; if (t < t1) t1 = t; }
  }
  if (!(t0 <= t1) || !isFinite(t0 + t1)) return null;
  return [[p[0] + t0 * dx, p[1] + t0 * dy], [p[0] + t1 * dx, p[1] + t1 * dy]];
}
const COLOURS = { camera: "#ffd400", reflected: "#00c8ff", refracted: "#ff4fd8", shadow: "#7cfc00", blocked: "#ff4040" };
function drawRays(segments, c, sample) {
  svg.textContent = "";
  for (const s of segments) {
    const projected = clipProject(c, s.from, s.to);
    const pts = projected && clipToImage(projected[0], projected[1]);
    if (!pts) continue;
    const line = document.createElementNS("http://www.w3.org/2000/svg", "line");
    line.setAttribute("x1", pts[0][0]); line.setAttribute("y1", pts[0][1]);
    line.setAttribute("x2", pts[1][0]); line.setAttribute("y2", pts[1][1]);
    line.setAttribute("stroke", COLOURS[s.kind]);
    line.setAttribute("class", "ray");
    line.dataset.sample = sample;
    line.id = s.id;
    if (s.kind === "blocked") line.setAttribute("stroke-dasharray", "5 3");
    svg.append(line);
  }
  hooks.rays = segments.map((s) => s.kind);
}
