// rigsim live view (docs/control-api.md#the-live-view): the rig as the control API reports it,
// kept current from its event stream. Served by rigsimd itself; no external asset, no build step.
"use strict";

const SVG = "http://www.w3.org/2000/svg";
const FAULT_KINDS = ["stall", "slip", "sensor_failure", "reference_lost", "limit_switch", "unplugged",
  "drop_bytes", "corrupt_bytes", "latency", "slicer", "bandwidth", "reset", "slow_close", "hang_close",
  "cut_after", "garbage_close", "overrun", "baud_mismatch", "power_cycle"];
const CHANNEL_FAULTS = new Set(["stall", "slip", "sensor_failure", "reference_lost", "limit_switch"]);
const WIRE_KEPT = 60;          // wire entries shown
const TRAJECTORY_KEPT = 240;   // samples per channel's trajectory
const ALARM_WORDS = /limit|error|fault|stall|overcurrent|interlock|lost|fail/i;

const state = {
  token: sessionStorage.getItem("rigsim-token") || "",
  rig: null,
  devices: new Map(),        // name -> GET /api/devices/{name}
  trajectories: new Map(),   // "device/channel" -> [[time_ms, position_si], ...]
  luts: new Map(),           // "device/channel" -> trace samples
  traceReads: new Map(),     // "device/channel" -> {next_from, at}: where the next trace read starts
  following: false,          // the event stream and the poll loop run (once)
  clock: null,
  refreshing: new Set(),
  moving: false,
};

// ---- the control API ----

function $(id) { return document.getElementById(id); }

function say(text) { $("message").textContent = text || ""; }

async function api(method, path, body) {
  const headers = {};
  if (state.token) headers.Authorization = "Bearer " + state.token;
  const init = { method, headers };
  if (body !== undefined) {
    headers["Content-Type"] = "application/json";
    init.body = JSON.stringify(body);
  }
  const response = await fetch(path, init);
  if (response.status === 401) {
    $("token-box").hidden = false;
    throw new Error("the control API asks for its token (--control-token)");
  }
  const answer = await response.json();
  if (!response.ok) throw new Error(`${method} ${path}: ${response.status} ${answer.error || ""}`);
  return answer;
}

// ---- formatting ----

function el(tag, attrs, ...children) {
  const node = document.createElement(tag);
  for (const [k, v] of Object.entries(attrs || {})) {
    if (k === "class") node.className = v;
    else if (k === "text") node.textContent = v;
    else node.setAttribute(k, v);
  }
  for (const child of children) if (child != null) node.append(child);
  return node;
}

function svgEl(tag, attrs) {
  const node = document.createElementNS(SVG, tag);
  for (const [k, v] of Object.entries(attrs || {})) node.setAttribute(k, v);
  return node;
}

function position_text(value, unit) {
  if (value === null || value === undefined) return "–";
  if (unit === "rad") return (value * 180 / Math.PI).toFixed(4) + " °";
  const abs = Math.abs(value);
  if (abs !== 0 && abs < 1e-3) return (value * 1e6).toFixed(3) + " µm";
  return (value * 1e3).toFixed(6) + " mm";
}

function status_words(ch) {
  const status = ch.status;
  if (Array.isArray(ch.status_set)) return ch.status_set.length ? ch.status_set : ["(no bit set)"];
  if (status === undefined || status === null) return [];
  if (Array.isArray(status.set)) return status.set.length ? status.set : ["(no bit set)"];
  if (status.name) return [status.name];
  return [typeof status === "number" ? "0x" + status.toString(16) : JSON.stringify(status)];
}

function svgText(text, attrs) {
  const node = svgEl("text", attrs);
  node.textContent = text;
  return node;
}

// ---- plots ----

function polyline(svg, points, w, h, colour) {
  if (points.length < 2) return;
  const xs = points.map((p) => p[0]), ys = points.map((p) => p[1]);
  const x0 = Math.min(...xs), x1 = Math.max(...xs);
  let y0 = Math.min(...ys), y1 = Math.max(...ys);
  if (y1 - y0 < 1e-12) { y0 -= 1e-9; y1 += 1e-9; }
  const sx = (x) => 2 + (w - 4) * (x1 > x0 ? (x - x0) / (x1 - x0) : 1);
  const sy = (y) => h - 3 - (h - 6) * (y - y0) / (y1 - y0);
  svg.append(svgEl("polyline", {
    points: points.map((p) => `${sx(p[0]).toFixed(1)},${sy(p[1]).toFixed(1)}`).join(" "),
    fill: "none", stroke: colour, "stroke-width": "1.5",
  }));
}

function trajectory_plot(key) {
  const svg = svgEl("svg", { class: "plot", viewBox: "0 0 180 44", "data-key": key, role: "img",
    "aria-label": "trajectory of " + key });
  polyline(svg, state.trajectories.get(key) || [], 180, 44, "#1f6feb");
  return svg;
}

function lut_plot(key) {
  const samples = state.luts.get(key) || [];
  const svg = svgEl("svg", { class: "lut", viewBox: "0 0 400 120", role: "img", "aria-label": "LUT output of " + key });
  polyline(svg, samples.map((s) => [s[0], s[2]]), 400, 120, "#1f6feb");     // output, V
  polyline(svg, samples.map((s) => [s[0], s[3]]), 400, 120, "#e65100");     // extension, µm
  return svg;
}

// ---- rendering ----

function render_device(name) {
  const device = state.devices.get(name);
  if (!device) return;
  const id = "device-" + name;
  const old = $(id);
  const section = el("section", { class: "device", id });
  section.append(el("h2", {}, `${device.name} `, el("small", { text:
    `${device.protocol} ${device.model}, firmware ${device.firmware}` +
    (device.endpoints ? ` · tcp ${device.endpoints.tcp}` + (device.endpoints.pty ? ` · pty ${device.endpoints.pty}` : "") : "") })));
  const table = el("table");
  table.append(el("tr", {}, el("th", { text: "ch" }), el("th", { text: "kind" }), el("th", { text: "position" }),
    el("th", { text: "protocol" }), el("th", { text: "status" }), el("th", { text: "trajectory" })));
  const luts = [];
  for (const ch of device.channels || []) {
    const key = `${name}/${ch.index}`;
    const words = status_words(ch);
    if (ch.moving && !words.includes("moving")) words.unshift("moving");
    if (ch.referenced === false) words.push("not referenced");
    const statusCell = el("td", { id: `status-${name}-${ch.index}` });
    for (const w of words) statusCell.append(el("span", { class: "status-word" + (ALARM_WORDS.test(w) ? " alarm" : ""), text: w }));
    const positionCell = el("td", { class: "num" + (ch.moving ? " moving" : ""), id: `pos-${name}-${ch.index}`,
      "data-si": ch.position_si === undefined || ch.position_si === null ? "" : String(ch.position_si),
      // A strain gauge moves nothing: the extension it senses of the actuator it is mounted on.
      text: ch.position_si === undefined && typeof ch.position_um === "number"
        ? `${ch.position_um.toFixed(3)} µm sensed` : position_text(ch.position_si, ch.si_unit) });
    // What the protocol reports: a counter, a piezo's output, a gauge's reading.
    let protocolText = "–";
    if (ch.position_protocol !== undefined && ch.position_protocol !== null)
      protocolText = `${ch.position_protocol} ${ch.protocol_unit || ""}`;
    else if (typeof ch.output_voltage_v === "number")
      protocolText = `${ch.output_voltage_v.toFixed(2)} V out`;
    else if (ch.reading && typeof ch.reading.value === "number")
      protocolText = `${ch.reading.value.toFixed(3)} ${ch.reading.unit === "um" ? "µm" : ch.reading.unit} read`;
    table.append(el("tr", {}, el("td", { text: String(ch.index) }), el("td", { text: ch.kind || ch.unit || "–" }),
      positionCell, el("td", { class: "num", text: protocolText }), statusCell,
      el("td", {}, ch.position_si === undefined ? null : trajectory_plot(key))));
    if (ch.unit === "piezo") luts.push(key);
  }
  section.append(table);
  for (const key of luts) {
    section.append(el("p", { class: "note", text: `${key}: piezo output (blue, V) and extension (orange, µm), the newest trace samples` }));
    section.append(lut_plot(key));
  }
  if (device.faults && device.faults.length)
    section.append(el("p", { class: "note", text: "faults: " + device.faults.map((f) => `${f.kind}#${f.id}`).join(", ") }));
  if (old) old.replaceWith(section); else $("devices").append(section);
}

function render_clock() {
  const c = state.clock;
  if (!c) return;
  $("clock-now").textContent = c.now_ms.toFixed(0);
  $("clock-scale").textContent = String(c.time_scale);
  $("clock-mode").textContent = c.paused ? "paused" : "running";
}

function render_wire(entry) {
  const list = $("wire");
  const d = entry.decoded || {};
  // MCS: the line's text; APT: the message's name and its id ("0x0453", a string in the log).
  const id = typeof d.id === "number" ? "0x" + d.id.toString(16).padStart(4, "0") : d.id;
  const text = d.text !== undefined ? d.text : (d.name ? `${d.name} (${id})` : entry.hex);
  const item = el("li", { class: entry.direction }, `${(entry.time_ms || 0).toFixed(1)} ms ${entry.device || ""} ${entry.direction === "in" ? "→" : "←"} ${text}`);
  for (const note of entry.notes || []) item.append(el("span", { class: "wire-note", text: "note: " + note }));
  list.prepend(item);
  while (list.children.length > WIRE_KEPT) list.lastChild.remove();
}

function render_faults(faults) {
  const list = $("fault-list");
  list.replaceChildren();
  for (const f of faults) {
    const remove = el("button", { type: "button", text: "remove" });
    remove.addEventListener("click", () => act(() => api("DELETE", `/api/faults/${f.id}`)));
    list.append(el("li", {}, `#${f.id} ${f.kind} on ${f.device}` + (f.channel === null ? " (wire) " : ` ch ${f.channel} `), remove));
  }
}

// The chain in two projections, side (x, z) and top (x, y), world millimetres, each frame's axes drawn.
function render_frames(answer) {
  const svg = $("chain");
  svg.replaceChildren();
  const all = [...(answer.frames || []), ...(answer.tools || [])];
  if (!all.length) {
    $("chain-note").textContent = "This rig has no kinematics (\"kinematics\" in the rig JSON).";
    return;
  }
  const colliding = new Set((answer.collisions || []).flatMap((c) => c.frames));
  const byName = new Map(all.map((f) => [f.name, f]));
  const pts = all.map((f) => f.world.position_mm);
  const views = [["x", "z", 0, "side (x, z)"], ["x", "y", 210, "top (x, y)"]];
  const axis = { x: 0, y: 1, z: 2 };
  for (const [h, v, left, title] of views) {
    // Each view fits the frames' extent in its two axes, one scale for both.
    const hs = pts.map((p) => p[axis[h]]), vs = pts.map((p) => p[axis[v]]);
    const [hmin, hmax, vmin, vmax] = [Math.min(...hs), Math.max(...hs), Math.min(...vs), Math.max(...vs)];
    const s = 150 / Math.max(hmax - hmin, vmax - vmin, 1);
    const cx = left + 105 - (hmin + hmax) / 2 * s, cy = 140 + (vmin + vmax) / 2 * s;
    const map = (p) => [cx + p[axis[h]] * s, cy - p[axis[v]] * s];
    svg.append(svgText(title, { x: left + 6, y: 14, "font-size": "11", fill: "#66707c" }));
    for (const f of all) {
      if (!f.parent || !byName.has(f.parent)) continue;
      const [x1, y1] = map(byName.get(f.parent).world.position_mm), [x2, y2] = map(f.world.position_mm);
      svg.append(svgEl("line", { x1, y1, x2, y2, stroke: "#46505c", "stroke-width": "2" }));
    }
    for (const f of all) {
      const [x, y] = map(f.world.position_mm);
      const q = f.world.quaternion;   // [w, x, y, z]: the frame's axes, 12 px long
      const rot = (vx, vy, vz) => {
        const [w, a, b, c] = q;
        const tx = 2 * (b * vz - c * vy), ty = 2 * (c * vx - a * vz), tz = 2 * (a * vy - b * vx);
        return [vx + w * tx + (b * tz - c * ty), vy + w * ty + (c * tx - a * tz), vz + w * tz + (a * ty - b * tx)];
      };
      [[1, 0, 0, "#c62828"], [0, 1, 0, "#2e7d32"], [0, 0, 1, "#1f6feb"]].forEach(([ax, ay, az, colour]) => {
        const d = rot(ax, ay, az);
        svg.append(svgEl("line", { x1: x, y1: y, x2: x + 12 * d[axis[h]], y2: y - 12 * d[axis[v]], stroke: colour, "stroke-width": "1" }));
      });
      svg.append(svgEl("circle", { cx: x, cy: y, r: f.tool ? 3 : 4, fill: colliding.has(f.name) ? "#c62828" : (f.tool ? "#e65100" : "#1d232b") }));
      svg.append(svgText(f.name, { x: x + 5, y: y - 5, "font-size": "10", fill: "#1d232b" }));
    }
  }
  const joints = (answer.frames || []).filter((f) => f.joint).map((f) =>
    `${f.name}: ${f.joint.type} ${f.joint.device}/${f.joint.channel} at ${f.joint.position.toFixed(3)} ${f.joint.type === "prismatic" ? "mm" : "°"}`);
  $("chain-note").textContent = joints.join(" · ") + (colliding.size ? ` · collision: ${[...colliding].join(", ")}` : "");
}

// ---- keeping it current ----

// A piezo channel's newest samples: only those after the last read (next_from), at most 2,000 a
// read and 3 reads a second (a whole trace is 16,384 samples, 30-45 ms of the daemon's loop).
async function refresh_trace(name, index, key) {
  const last = state.traceReads.get(key) || { next_from: 0, at: 0 };
  if (Date.now() - last.at < 300) return;
  const trace = await api("GET", `/api/devices/${encodeURIComponent(name)}/channels/${index}/trace?from=${last.next_from}&max=2000`);
  const kept = (state.luts.get(key) || []).concat(trace.samples);
  state.luts.set(key, kept.slice(-2000));
  state.traceReads.set(key, { next_from: trace.next_from, at: Date.now() });
}

async function refresh_device(name) {
  if (state.refreshing.has(name)) return;
  state.refreshing.add(name);
  try {
    const device = await api("GET", `/api/devices/${encodeURIComponent(name)}`);
    const time = state.clock ? state.clock.now_ms : 0;
    for (const ch of device.channels || []) {
      if (ch.position_si === undefined || ch.position_si === null) continue;
      const key = `${name}/${ch.index}`;
      const t = state.trajectories.get(key) || [];
      if (!t.length || t[t.length - 1][1] !== ch.position_si || ch.moving) t.push([time, ch.position_si]);
      while (t.length > TRAJECTORY_KEPT) t.shift();
      state.trajectories.set(key, t);
      if (ch.unit === "piezo") await refresh_trace(name, ch.index, key);
    }
    state.devices.set(name, device);
    render_device(name);
  } finally {
    state.refreshing.delete(name);
  }
}

async function refresh_all() {
  state.clock = await api("GET", "/api/clock");
  render_clock();
  await Promise.all([...state.devices.keys()].map(refresh_device));
  render_faults((await api("GET", "/api/faults")).faults);
  render_frames(await api("GET", "/api/frames"));
}

function on_event(type, data) {
  if (type === "clock" || type === "reset") {
    if (type === "clock") { state.clock = data; render_clock(); }
    refresh_all().catch((e) => say(e.message));
    return;
  }
  if (type === "wire") { render_wire(data); return; }
  if (type === "frames" || type === "collision") {
    api("GET", "/api/frames").then(render_frames).catch((e) => say(e.message));
    return;
  }
  if (type === "fault_added" || type === "fault_removed")
    api("GET", "/api/faults").then((a) => render_faults(a.faults)).catch((e) => say(e.message));
  if (type === "move_started" || type === "lut_started") state.moving = true;
  if (data && data.device && state.devices.has(data.device)) refresh_device(data.device).catch((e) => say(e.message));
}

// Server-Sent Events through fetch (an EventSource cannot send the token).
async function follow_events() {
  for (;;) {
    try {
      const headers = state.token ? { Authorization: "Bearer " + state.token } : {};
      const response = await fetch("/api/events", { headers });
      if (!response.ok) throw new Error("event stream: " + response.status);
      $("connection").textContent = "live";
      $("connection").className = "badge live";
      const reader = response.body.getReader();
      const decoder = new TextDecoder();
      let buffer = "";
      for (;;) {
        const { value, done } = await reader.read();
        if (done) break;
        buffer += decoder.decode(value, { stream: true });
        let end;
        while ((end = buffer.indexOf("\n\n")) >= 0) {
          const block = buffer.slice(0, end);
          buffer = buffer.slice(end + 2);
          let type = "message", data = "";
          for (const line of block.split("\n")) {
            if (line.startsWith("event: ")) type = line.slice(7);
            else if (line.startsWith("data: ")) data += line.slice(6);
          }
          if (data) on_event(type, JSON.parse(data));
        }
      }
    } catch (e) {
      say(e.message);
    }
    $("connection").textContent = "reconnecting";
    $("connection").className = "badge down";
    await new Promise((r) => setTimeout(r, 2000));
  }
}

// While something moves, positions change between events: the moving devices are read 10 times a
// second (the trajectories' samples), the others twice; the clock once a second otherwise.
async function poll() {
  let last_clock = 0, last_frames = 0, last_all = 0;
  for (;;) {
    await new Promise((r) => setTimeout(r, 100));
    const moving = [...state.devices.values()].filter((d) => (d.channels || []).some((c) => c.moving || (c.body && c.body.settling)));
    try {
      if (moving.length || Date.now() - last_clock > 1000) {
        state.clock = await api("GET", "/api/clock");
        render_clock();
        last_clock = Date.now();
      }
      // The moving devices at every turn; every device twice a second while something moves (a
      // gauge reads the stack another device drives).
      const all = moving.length && Date.now() - last_all > 500;
      await Promise.all((all ? [...state.devices.values()] : moving).map((d) => refresh_device(d.name)));
      if (all) last_all = Date.now();
      // The frames of moving joints: an event comes only when a motion ends.
      if (moving.length && Date.now() - last_frames > 300) {
        render_frames(await api("GET", "/api/frames"));
        last_frames = Date.now();
      }
    } catch (e) { say(e.message); }
  }
}

async function act(action) {
  try { say(""); await action(); } catch (e) { say(e.message); }
}

function wire_controls() {
  $("clock-pause").addEventListener("click", () => act(() => api("POST", "/api/clock", { pause: true })));
  $("clock-resume").addEventListener("click", () => act(() => api("POST", "/api/clock", { resume: true })));
  $("clock-step").addEventListener("click", () => act(() => api("POST", "/api/clock", { step_ms: Number($("clock-step-ms").value) })));
  $("clock-idle").addEventListener("click", () => act(async () => {
    const answer = await api("POST", "/api/clock", { run_until_idle: true, max_ms: Number($("clock-idle-ms").value) });
    say(answer.idle ? "" : `not idle after ${answer.reached_ms} ms`);
  }));
  $("token-use").addEventListener("click", () => {
    state.token = $("token").value.trim();
    sessionStorage.setItem("rigsim-token", state.token);
    $("token-box").hidden = true;
    start().catch((e) => say(e.message));
  });
  for (const kind of FAULT_KINDS) {
    const button = el("button", { type: "button", text: kind, "data-kind": kind });
    button.addEventListener("click", () => act(async () => {
      let params;
      try { params = JSON.parse($("fault-params").value || "{}"); } catch (e) { throw new Error("parameters: not JSON"); }
      if (params === null || typeof params !== "object" || Array.isArray(params)) throw new Error("parameters: not a JSON object");
      // POST /api/faults: the kind's parameters beside device and kind; a channel for the faults
      // of a channel's stage only (the others act on the whole device or its wire).
      const body = Object.assign({}, params, { device: $("fault-device").value, kind });
      if (CHANNEL_FAULTS.has(kind)) body.channel = Number($("fault-channel").value);
      await api("POST", "/api/faults", body);
    }));
    $("fault-kinds").append(button);
  }
}

async function start() {
  state.rig = await api("GET", "/api/rig");
  state.clock = state.rig.clock;
  render_clock();
  $("fault-device").replaceChildren(...state.rig.devices.map((d) => el("option", { value: d.name, text: d.name })));
  state.devices.clear();
  $("devices").replaceChildren();
  for (const d of state.rig.devices) state.devices.set(d.name, Object.assign({ channels: [] }, d));
  await refresh_all();
  $("wire").replaceChildren();
  for (const d of state.rig.devices) {
    const log = await api("GET", `/api/devices/${encodeURIComponent(d.name)}/log?last=10`);
    for (const entry of log.entries) render_wire(Object.assign({ device: d.name }, entry));
  }
  document.body.dataset.ready = "true";
  if (!state.following) {
    state.following = true;
    follow_events();
    poll();
  }
}

const fragment = new URLSearchParams(location.hash.slice(1));
if (fragment.get("token")) {
  state.token = fragment.get("token");
  sessionStorage.setItem("rigsim-token", state.token);
  history.replaceState(null, "", location.pathname);
}
wire_controls();
start().catch((e) => say(e.message));
