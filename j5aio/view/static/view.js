"use strict";
// j5aio live view. TOKEN is set by the page. Everything shown comes over one WebSocket;
// controls are POSTed to /control. Values are drawn by component kind; unknown kinds
// show their fields as text, so new boards appear without new code here.

const WINDOW_S = 30;
const BOARD_ORDER = ["PowerBoard", "PowerBoardFw4", "MotorBoard", "MotorBoardFw4", "ServoBoard",
  "ServoBoardFw4", "SBServoBoard", "SBArduinoBoard", "SBArduino2024Board", "Ruggeduino",
  "SRArduinoBoard", "KCHBoard", "CameraBoard"];
const KIND_TITLES = { motor: "Motors", monitoredmotor: "Motors",
  protectedpoweroutput: "Power outputs", markercamera: "Camera", poweroutput: "Power outputs", led: "LEDs", rgbled: "RGB LEDs",
  servo: "Servos", pulseservo: "Servos", gpiopin: "GPIO pins", batterysensor: "Battery",
  piezo: "Piezo", button: "Start button", ultrasoundsensor: "Ultrasound", supplysensor: "Supply",
  flashingled: "Flashing LEDs", flag: "Flags" };
const KIND_ORDER = ["batterysensor", "button", "poweroutput", "protectedpoweroutput", "motor",
  "monitoredmotor", "servo", "pulseservo",
  "led", "rgbled", "flashingled", "piezo", "gpiopin", "ultrasoundsensor"];
const PRIMARY = { motor: "motor_state", monitoredmotor: "motor_state",
  protectedpoweroutput: "power_output_enabled", led: "led_state", poweroutput: "power_output_enabled",
  batterysensor: "battery_sensor_voltage", servo: "servo_position", button: "button_state",
  ultrasoundsensor: "ultrasound_distance", piezo: "note", pulseservo: "servo_pulse_width",
  flashingled: "led_mode", flag: "flag_state", supplysensor: "supply_voltage" };
const COLOURS = ["#206bc4", "#d63939", "#2fb344", "#f59f00", "#ae3ec9", "#0ca678", "#4263eb",
  "#e8590c", "#74b816", "#1098ad", "#c2255c", "#495057"];

const values = new Map();      // component id -> {fields: {field: value}, last: field}
const tiles = new Map();       // component id -> element
const boardsShown = new Map(); // serial -> {section, items, controls, log}
const series = new Map();      // "power"|"analogue" -> Map(key -> {label, colour, points})
series.set("power", new Map());
series.set("analogue", new Map());
let colourIndex = 0;

function el(tag, attrs = {}, ...children) {
  const node = document.createElement(tag);
  for (const [k, v] of Object.entries(attrs)) {
    if (k === "class") node.className = v; else if (k === "text") node.textContent = v;
    else node.setAttribute(k, v);
  }
  for (const child of children) node.append(child);
  return node;
}

function valueText(v) {
  if (v === null || v === undefined) return "none";
  if (typeof v === "object") return v.pitch !== undefined ? String(v.pitch) : JSON.stringify(v);
  return String(v);
}

function fmt(v, digits = 2, unit = "") {
  return typeof v === "number" ? v.toFixed(digits) + unit : valueText(v);
}

// ---------------------------------------------------------------- the connection
let socket = null;
function connect() {
  const url = `ws://${location.host}/ws?token=${encodeURIComponent(TOKEN)}`;
  socket = new WebSocket(url);
  socket.onopen = () => setStatus("live", "live");
  socket.onmessage = (event) => receive(JSON.parse(event.data));
  socket.onclose = () => { setStatus("stopped", "robot stopped (reconnecting…)"); setTimeout(connect, 1000); };
}
function setStatus(code, text) {
  const status = document.getElementById("status");
  status.dataset.status = code;
  status.textContent = text;
}

function receive(message) {
  const now = performance.now() / 1000;
  if (message.boards) showBoards(message.boards);
  for (const [cid, field, value] of message.values || []) setValue(cid, field, value, now);
  for (const [port, line] of message.log || []) addLogLine(port, line);
  if (message.arena) showArena(message.arena);
  if (message.pose) showPose(message.pose);
}

// ---------------------------------------------------------------- boards
function boardRank(board) {
  const i = BOARD_ORDER.indexOf(board.type);
  return i < 0 ? BOARD_ORDER.length : i;
}

function showBoards(boards) {
  boards = [...boards].sort((a, b) => boardRank(a) - boardRank(b) || a.serial.localeCompare(b.serial));
  const main = document.getElementById("boards");
  for (const board of boards) {
    let shown = boardsShown.get(board.serial);
    if (!shown) {
      shown = makeBoard(board);
      boardsShown.set(board.serial, shown);
    }
    main.append(shown.section);  // keeps the kit's order
    shown.section.dataset.state = board.state;
    shown.state.dataset.state = board.state;
    shown.state.textContent = board.state;
    shown.state.title = board.error || "";
    shown.firmware.textContent = `serial ${board.serial} · firmware ${board.firmware ?? "none"}`;
    for (const c of board.components) ensureTile(shown, c);
    showControls(shown, board);
  }
}

function makeBoard(board) {
  const state = el("span", { class: "state", "data-board-state": board.serial });
  const firmware = el("span", { class: "meta" });
  const section = el("section", { class: "board", "data-board": board.serial },
    el("h2", {}, el("span", { text: board.name }), firmware, state));
  const groups = el("div", { class: "groups" });
  const controls = el("div", { class: "controls", hidden: "" });
  const pre = el("pre", { "data-wire-log": board.serial });
  const log = el("details", {}, el("summary", { text: "Wire log" }), pre);
  section.append(groups, controls, log);
  return { type: board.type, section, state, firmware, groups, groupOf: new Map(), controls, controlOf: new Map(), log: pre };
}

function ensureTile(shown, c) {
  if (tiles.has(c.id)) return;
  let group = shown.groupOf.get(c.kind);
  if (!group) {
    group = el("div", { class: "items" });
    const box = el("div", { class: "group", "data-kind": c.kind },
      el("h3", { text: KIND_TITLES[c.kind] || c.kind }), group);
    box.dataset.rank = String(KIND_ORDER.includes(c.kind) ? KIND_ORDER.indexOf(c.kind) : 99);
    const after = [...shown.groups.children].find((g) => Number(g.dataset.rank) > Number(box.dataset.rank));
    shown.groups.insertBefore(box, after || null);
    shown.groupOf.set(c.kind, group);
  }
  const tile = el("div", { class: `comp kind-${c.kind} unknown`, "data-component": c.id, "data-value": "" });
  tile.kind = c.kind;
  tile.identifier = c.identifier;
  tile.name = c.name || (shown.type === "KCHBoard" && c.kind === "rgbled" ? `LED ${"ABC"[c.identifier] ?? c.identifier}` : null);
  tiles.set(c.id, tile);
  group.append(tile);
  draw(tile, { fields: {}, last: null });
}

// ---------------------------------------------------------------- values
function setValue(cid, field, value, now) {
  let entry = values.get(cid);
  if (!entry) { entry = { fields: {}, last: null }; values.set(cid, entry); }
  entry.fields[field] = value;
  if (!field.endsWith("_mode") || entry.last === null) entry.last = field;  // a reading, not a mode
  let tile = tiles.get(cid);
  if (!tile) {  // a component first seen in a call (an ultrasound sensor): show it now
    const [serial, kind, identifier] = cid.split(":");
    const shown = boardsShown.get(serial);
    if (!shown) return;
    ensureTile(shown, { id: cid, kind, identifier });
    tile = tiles.get(cid);
  }
  tile.classList.remove("unknown");
  draw(tile, entry);
  record(cid, tile, field, value, now);
  if (field === "note") playNote(value);
}

function label(tile) {
  if (tile.name) return tile.name[0].toUpperCase() + tile.name.slice(1);
  const titles = { batterysensor: "Battery", button: "Start", piezo: "Piezo", ultrasoundsensor: "Sensor" };
  const name = titles[tile.kind] || (KIND_TITLES[tile.kind] || tile.kind).replace(/s$/, "");
  return `${name} ${tile.identifier}`;
}

function draw(tile, entry) {
  const f = entry.fields;
  const primary = PRIMARY[tile.kind] && PRIMARY[tile.kind] in f ? PRIMARY[tile.kind] : entry.last;
  const text = VALUE_TEXT[tile.kind];
  tile.dataset.value = text ? text(f) : primary === null ? "" : valueText(f[primary]);
  const body = [el("span", { class: "label", text: label(tile) })];
  const renderer = RENDERERS[tile.kind] || renderFields;
  body.push(...renderer(f, tile));
  tile.replaceChildren(...body);
}

function gauge(v) {
  const fill = el("div", { class: "fill" });
  if (typeof v === "number") {
    const x = Math.max(-1, Math.min(1, v));
    fill.style.left = `${50 + Math.min(0, x) * 50}%`;
    fill.style.width = `${Math.abs(x) * 50}%`;
  }
  return el("div", { class: "gauge" }, el("div", { class: "mid" }), fill);
}

function dot(lit, colour, flashing = false) {
  const d = el("span", { class: (lit ? "dot lit" : "dot") + (flashing ? " flash" : "") });
  if (lit && colour) { d.style.background = colour; d.style.boxShadow = `0 0 6px ${colour}`; }
  return d;
}

function renderFields(f) {
  const keys = Object.keys(f);
  if (!keys.length) return [el("span", { class: "text", text: "—" })];
  return keys.map((k) => el("div", { class: "text", "data-field": k, text: `${k.replace(/_/g, " ")}: ${fmt(f[k])}` }));
}

// An RGB LED's channels as 0-255 (a channel not yet set or read is dark).
function rgbOf(f) {
  return ["red", "green", "blue"].map((name) => Math.round(255 * (f[`rgb_led_channel_duty_cycle.${name}`] || 0)));
}
const COLOUR_NAMES = { "0,0,0": "off", "255,0,0": "red", "255,255,0": "yellow", "0,255,0": "green",
  "0,255,255": "cyan", "0,0,255": "blue", "255,0,255": "magenta", "255,255,255": "white" };
// A flashing LED's mode: ON, OFF or FLASH (from whether it is lit, before any mode was set).
function ledMode(f) {
  if (f.led_mode !== undefined) return f.led_mode;
  return f.led_state === undefined ? undefined : f.led_state ? "ON" : "OFF";
}
// data-value of the kinds whose value is made of several fields.
const VALUE_TEXT = {
  rgbled(f) {
    const rgb = rgbOf(f);
    return COLOUR_NAMES[rgb.join(",")] || `rgb(${rgb.join(", ")})`;
  },
  flashingled(f) {
    return ledMode(f) ?? "";
  },
};

const RENDERERS = {
  motor(f) {
    const v = f.motor_state;
    if (typeof v === "string") return [gauge(0), el("span", { class: "text special", text: v })];
    return [gauge(v), el("span", { class: "text", text: v === undefined ? "—" : `${Math.round(v * 100)} %` })];
  },
  servo(f) {
    const v = f.servo_position;
    return [gauge(v), el("span", { class: "text", text: v === undefined ? "—" : v === null ? "off" : fmt(v) })];
  },
  led(f) {
    const v = f.led_state;
    return [dot(v === true), el("span", { class: "text", text: v === undefined ? "—" : v ? "on" : "off" })];
  },
  rgbled(f) {
    const [r, g, b] = rgbOf(f);
    const lit = r + g + b > 0;
    return [dot(lit, `rgb(${r}, ${g}, ${b})`), el("span", { class: "text", text: VALUE_TEXT.rgbled(f) })];
  },
  flashingled(f, tile) {
    const mode = ledMode(f);
    const colour = /error/.test(tile.name || "") ? "#d63939" : /run/.test(tile.name || "") ? "#2fb344" : "#f59f00";
    const text = { FLASH: "flashing", ON: "on", OFF: "off" }[mode] || "—";
    return [dot(mode === "ON" || mode === "FLASH", colour, mode === "FLASH"), el("span", { class: "text", text })];
  },
  poweroutput(f) {
    const on = f.power_output_enabled;
    const amps = f.power_output_current;
    return [dot(on === true), el("span", { class: "text", text: `${on === undefined ? "—" : on ? "on" : "off"}${amps === undefined ? "" : " · " + fmt(amps, 2, " A")}` })];
  },
  batterysensor(f) {
    return [el("span", { class: "text", text: `${fmt(f.battery_sensor_voltage ?? "—", 2, " V")} · ${fmt(f.battery_sensor_current ?? "—", 2, " A")}` })];
  },
  supplysensor(f) {
    return [el("span", { class: "text", text: `${fmt(f.supply_voltage ?? "—", 2, " V")} · ${fmt(f.supply_current ?? "—", 2, " A")}` })];
  },
  button(f) {
    const v = f.button_state;
    return [dot(v === true, "#f59f00"), el("span", { class: "text", text: v === undefined ? "—" : v ? "pressed" : "released" })];
  },
  piezo(f) {
    const n = f.note;
    return [el("span", { class: "text", text: n ? `♪ ${fmt(n.pitch, 0, " Hz")} for ${fmt(n.seconds, 2, " s")}` : "quiet" })];
  },
  ultrasoundsensor(f) {
    const v = f.ultrasound_distance;
    return [el("span", { class: "text", text: v === undefined ? "—" : v === null ? "no echo" : fmt(v, 3, " m") })];
  },
  gpiopin(f) {
    const mode = f.gpio_pin_mode;
    const parts = [];
    if ("gpio_pin_digital_state" in f) parts.push(f.gpio_pin_digital_state ? "HIGH" : "LOW");
    if ("gpio_pin_analogue_value" in f) parts.push(fmt(f.gpio_pin_analogue_value, 2, " V"));
    if ("gpio_pin_pwm_value" in f) parts.push(`PWM ${fmt(f.gpio_pin_pwm_value)}`);
    return [el("span", { class: "text", text: `${mode ? String(mode).replace(/_/g, " ").toLowerCase() : "—"}${parts.length ? " · " + parts.join(" ") : ""}` })];
  },
};

// The fw 4 boards' motors and outputs also report currents: drawn as the older ones are.
RENDERERS.monitoredmotor = RENDERERS.motor;
RENDERERS.protectedpoweroutput = RENDERERS.poweroutput;

// ---------------------------------------------------------------- plots
function record(cid, tile, field, value, now) {
  let plot = null;
  if (field === "motor_state" || field === "servo_position") plot = "power";
  else if (field === "gpio_pin_analogue_value") plot = "analogue";
  if (!plot) return;
  const v = typeof value === "number" ? value : field === "motor_state" ? 0 : null;
  const lines = series.get(plot);
  let line = lines.get(cid);
  if (!line) {
    const [serial] = cid.split(":");
    line = { label: `${serial} ${label(tile)}`, colour: COLOURS[colourIndex++ % COLOURS.length], points: [] };
    lines.set(cid, line);
    const legend = document.getElementById(`legend-${plot}`);
    legend.append(el("span", { "data-series": cid }, el("i", { style: `background:${line.colour}` }), line.label));
  }
  line.points.push([now, v]);
}

function drawPlot(name, low, high) {
  const canvas = document.getElementById(`plot-${name}`);
  const ctx = canvas.getContext("2d");
  const w = canvas.width = canvas.clientWidth * devicePixelRatio;
  const h = canvas.height = canvas.clientHeight * devicePixelRatio;
  const now = performance.now() / 1000;
  const x = (t) => w - ((now - t) / WINDOW_S) * w;
  const y = (v) => h - ((v - low) / (high - low)) * h;
  ctx.strokeStyle = "#d8dce4";
  ctx.beginPath(); ctx.moveTo(0, y((low + high) / 2)); ctx.lineTo(w, y((low + high) / 2)); ctx.stroke();
  ctx.lineWidth = 1.5 * devicePixelRatio;
  for (const line of series.get(name).values()) {
    while (line.points.length > 1 && line.points[1][0] < now - WINDOW_S) line.points.shift();
    ctx.strokeStyle = line.colour;
    ctx.beginPath();
    let last = null;
    for (const [t, v] of line.points) {
      if (v === null) { last = null; continue; }
      const px = Math.max(0, x(t));
      if (last === null) ctx.moveTo(px, y(v)); else ctx.lineTo(px, y(last));
      ctx.lineTo(px, y(v));
      last = v;
    }
    if (last !== null) ctx.lineTo(w, y(last));
    ctx.stroke();
  }
}
setInterval(() => { drawPlot("power", -1, 1); drawPlot("analogue", 0, 5); }, 100);

// ---------------------------------------------------------------- the simulated arena
// Drawn from above in the arena's own units (mm); the world's y points north, the SVG's down.
const SVG_NS = "http://www.w3.org/2000/svg";
let arena = null;  // {length, robot, fov, body, nose}

function svg(tag, attrs = {}, text = null) {
  const node = document.createElementNS(SVG_NS, tag);
  for (const [k, v] of Object.entries(attrs)) node.setAttribute(k, v);
  if (text !== null) node.textContent = text;
  return node;
}

function showArena(a) {
  const figure = document.getElementById("arena-figure");
  const root = document.getElementById("arena");
  const Y = (y) => a.length - y;
  const margin = 250;
  root.setAttribute("viewBox", `${-margin} ${-margin} ${a.width + 2 * margin} ${a.length + 2 * margin}`);
  root.dataset.width = String(a.width);
  root.dataset.length = String(a.length);
  const clip = svg("clipPath", { id: "arena-clip" }, null);
  clip.append(svg("rect", { x: 0, y: 0, width: a.width, height: a.length }));
  const parts = [svg("defs"), svg("rect", { class: "floor", x: 0, y: 0, width: a.width, height: a.length })];
  parts[0].append(clip);
  for (const m of a.markers) {
    // The marker lies along its wall: across the way it faces.
    const dx = -Math.sin(m.facing) * m.size / 2, dy = Math.cos(m.facing) * m.size / 2;
    const g = svg("g", { "data-marker": String(m.id) });
    g.append(svg("line", { class: "marker", x1: m.x - dx, y1: Y(m.y - dy), x2: m.x + dx, y2: Y(m.y + dy) }));
    g.append(svg("text", { x: m.x + Math.cos(m.facing) * 170, y: Y(m.y + Math.sin(m.facing) * 170) }, String(m.id)));
    parts.push(g);
  }
  for (const t of a.tokens) {
    const g = svg("g", { "data-token": String(t.id), transform: `translate(${t.x} ${Y(t.y)})` });
    g.append(svg("rect", { class: "token", x: -t.side / 2, y: -t.side / 2, width: t.side, height: t.side,
      transform: `rotate(${-t.heading * 180 / Math.PI})` }));
    g.append(svg("text", { class: "token-label", y: -t.side / 2 - 90 }, String(t.id)));
    parts.push(g);
  }
  const fov = svg("polygon", { class: "fov", "clip-path": "url(#arena-clip)" });
  const robot = svg("g", { "data-robot": "", "data-pose": "" });
  const body = svg("circle", { class: "body", cx: 0, cy: 0, r: a.robot.radius });
  const nose = svg("line", { class: "nose", x1: 0, y1: 0, x2: a.robot.radius, y2: 0 });
  robot.append(body, nose);
  // Where the program believes the robot is (a PositionTracker's estimate), when it says.
  const estimate = svg("g", { "data-estimate": "", class: "estimate", display: "none" });
  const spread = svg("circle", { class: "spread", cx: 0, cy: 0, r: 0 });
  estimate.append(spread, svg("circle", { class: "ghost", cx: 0, cy: 0, r: a.robot.radius }),
    svg("line", { class: "ghost-nose", x1: 0, y1: 0, x2: a.robot.radius, y2: 0 }));
  parts.push(fov, robot, estimate);
  root.replaceChildren(...parts);
  arena = { length: a.length, width: a.width, robot, fov, estimate, spread };
  figure.hidden = false;
}

function showPose(p) {
  if (!arena) return;
  const Y = (y) => arena.length - y;
  const degrees = p.heading * 180 / Math.PI;
  arena.robot.setAttribute("transform", `translate(${p.x} ${Y(p.y)}) rotate(${-degrees})`);
  arena.robot.dataset.pose = `${Math.round(p.x)},${Math.round(p.y)},${degrees.toFixed(1)}`;
  const c = p.camera;
  if (c) {
    const reach = 2 * Math.max(arena.width, arena.length);  // clipped at the walls
    const edge = (angle) => `${c.x + reach * Math.cos(angle)},${Y(c.y + reach * Math.sin(angle))}`;
    arena.fov.setAttribute("points", `${c.x},${Y(c.y)} ${edge(c.left)} ${edge(c.right)}`);
  }
  arena.fov.style.display = c ? "" : "none";
  let text = `robot at x ${(p.x / 1000).toFixed(2)} m, y ${(p.y / 1000).toFixed(2)} m, heading ${degrees.toFixed(0)}°`;
  const e = p.estimate;
  if (e) {
    const believed = e.heading * 180 / Math.PI;
    arena.estimate.setAttribute("transform", `translate(${e.x} ${Y(e.y)}) rotate(${-believed})`);
    arena.estimate.dataset.estimate = `${Math.round(e.x)},${Math.round(e.y)},${believed.toFixed(1)}`;
    arena.spread.setAttribute("r", String(Math.max(e.error, 20)));
    arena.estimate.setAttribute("display", "inline");
    text += `; believed at x ${(e.x / 1000).toFixed(2)} m, y ${(e.y / 1000).toFixed(2)} m` +
      ` ± ${Math.round(e.error)} mm, heading ${believed.toFixed(0)}° (${e.age.toFixed(1)} s since markers)`;
  } else {
    arena.estimate.setAttribute("display", "none");
  }
  document.getElementById("pose-text").textContent = text;
}

// ---------------------------------------------------------------- wire log
function addLogLine(port, line) {
  let pane = null;
  for (const [serial, shown] of boardsShown) if (port.includes(serial)) pane = shown.log;
  if (!pane) {
    const other = document.getElementById("other-logs");
    other.hidden = false;
    pane = other.querySelector(`pre[data-port="${CSS.escape(port)}"]`);
    if (!pane) {
      pane = el("pre", { "data-port": port });
      other.append(el("details", {}, el("summary", { text: port }), pane));
    }
  }
  pane.append(line + "\n");
  while (pane.childNodes.length > 300) pane.firstChild.remove();
  pane.scrollTop = pane.scrollHeight;
}

// ---------------------------------------------------------------- piezo sound
let audio = null;
function playNote(note) {
  if (!document.getElementById("sound").checked || !note || typeof note.pitch !== "number") return;
  audio = audio || new AudioContext();
  const osc = audio.createOscillator();
  const gain = audio.createGain();
  gain.gain.value = 0.05;
  osc.frequency.value = note.pitch;
  osc.connect(gain).connect(audio.destination);
  osc.start();
  osc.stop(audio.currentTime + Math.min(note.seconds || 0.2, 5));
}

// ---------------------------------------------------------------- simulator controls
async function send(control, value, shown) {
  const response = await fetch(`/control?token=${encodeURIComponent(TOKEN)}`, {
    method: "POST", headers: { "Content-Type": "application/json" },
    body: JSON.stringify({ control, value }),
  });
  const error = shown.controls.querySelector(".error");
  error.textContent = response.ok ? "" : (await response.json()).error;
}

function showControls(shown, board) {
  if (!board.controls.length) return;
  if (shown.controls.hidden) {
    shown.controls.hidden = false;
    shown.controls.append(el("h3", { text: "Simulator: play the world's part" }));
  }
  for (const c of board.controls) {
    const id = `${board.serial}:${c.name}`;
    let input = shown.controlOf.get(id);
    if (!input) {
      input = makeControl(id, c, shown);
      shown.controlOf.set(id, input);
    }
    input.dataset.value = valueText(c.value);
    if (document.activeElement !== input) {
      if (c.type === "number") input.value = c.value === null ? "" : String(c.value);
      else if (c.type === "level") input.value = c.value;
      else if (c.type === "plug") input.textContent = c.value ? "Unplug" : "Plug in";
    }
  }
  if (!shown.controls.querySelector(".error")) shown.controls.append(el("div", { class: "error" }));
}

function makeControl(id, c, shown) {
  const name = c.name;
  let input;
  if (c.type === "button") {
    input = el("button", { "data-control": id, text: "Press start" });
    input.onclick = () => send(id, true, shown);
    shown.controls.append(input);
  } else if (c.type === "plug") {
    input = el("button", { "data-control": id, text: "Unplug" });
    input.onclick = () => send(id, input.dataset.value !== "true", shown);
    shown.controls.append(input);
  } else if (c.type === "level") {
    input = el("select", { "data-control": id },
      el("option", { value: "float", text: "—" }), el("option", { value: "high", text: "high" }),
      el("option", { value: "low", text: "low" }));
    input.onchange = () => send(id, input.value, shown);
    shown.controls.append(el("label", {}, name, input));
  } else {
    input = el("input", { "data-control": id, type: "number", min: c.min, max: c.max, step: c.step });
    input.onchange = () => {
      if (input.value !== "" || name.startsWith("ultrasound")) {  // empty: no echo
        send(id, input.value === "" ? null : Number(input.value), shown);
      }
    };
    const unit = name.startsWith("ultrasound") ? "m" : "V";
    shown.controls.append(el("label", {}, name, input, unit));
  }
  return input;
}

connect();
