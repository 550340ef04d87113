// The operator's view (viewer/README.md): a Foxglove WebSocket client (foxglove.websocket.v1,
// JSON encoding) that draws the mine, the vehicle and the mission on a canvas. Plain
// JavaScript, no build step: the bridge serves this file as it is.
//
// View: x right, y up, metres; the URL's hash may set it: #center=X,Y&scale=PX_PER_M&follow=0.
// window.minenavViewer exposes the state, the view transform and the measured rates (tests).
"use strict";

(function () {
  const WANTED = ["CONTOUR_MAP", "SIM_WORLD", "LINE_MAP", "LADAR_SCAN", "POSE", "SIM_TRUTH", "PATH", "DRIVE_PATH",
                  "MISSION_STATUS", "/minenav/fleet", "/minenav/bridge", "/minenav/viewer_config", "/minenav/replay"];
  const MOTION = { FORWARD: 0, REVERSE: 1, ARC_LEFT: 2, ARC_RIGHT: 3, TURN_IN_PLACE: 4, ARC_LEFT_REVERSE: 5,
                   ARC_RIGHT_REVERSE: 6 };
  const MISSION_STATES = ["IDLE", "RUNNING", "PAUSED", "DONE", "FAILED", "ABORTED", "ESTOPPED", "WAITING"];
  const NODE_STATES = ["IDLE", "RUNNING", "SUCCESS", "FAILURE"];

  const canvas = document.getElementById("map");
  const ctx = canvas.getContext("2d");
  const $ = (id) => document.getElementById(id);

  const state = {
    map: null, walls: null, scan: null, pose: null, truth: null, path: null, drivePath: null,
    mission: null, fleet: null, bridge: null, config: { vehicle_width_m: 3.3, vehicle_length_m: 10 },
    track: [], connected: false, capabilities: [], commandTopic: null, replayTopic: null, replay: null,
  };
  const view = { cx: 0, cy: 0, scale: 10, follow: true, fitted: false };
  const stats = { frames: 0, redraws: 0, bytes: 0, messages: 0, fps: 0, redrawsPerS: 0, bytesPerS: 0,
                  messagesPerS: 0 };
  let dirty = true;

  // ---- view -------------------------------------------------------------------------------
  (function readHash() {
    const h = new URLSearchParams(location.hash.slice(1));
    if (h.has("center")) {
      const [x, y] = h.get("center").split(",").map(Number);
      if (isFinite(x) && isFinite(y)) { view.cx = x; view.cy = y; view.fitted = true; }
    }
    if (h.has("scale") && Number(h.get("scale")) > 0) view.scale = Number(h.get("scale"));
    if (h.get("follow") === "0") view.follow = false;
    $("follow").checked = view.follow;
  })();

  function size() { return { w: canvas.clientWidth, h: canvas.clientHeight }; }
  function worldToScreen(x, y) {
    const { w, h } = size();
    return [w / 2 + (x - view.cx) * view.scale, h / 2 - (y - view.cy) * view.scale];
  }
  function screenToWorld(px, py) {
    const { w, h } = size();
    return [view.cx + (px - w / 2) / view.scale, view.cy - (py - h / 2) / view.scale];
  }

  function fit() {
    const xs = [], ys = [];
    const add = (x, y) => { xs.push(x); ys.push(y); };
    if (state.map) for (const c of state.map.contours) for (let i = 0; i < c.xy.length; i += 2) add(c.xy[i], c.xy[i + 1]);
    if (state.walls) for (const s of state.walls.segments) { add(s.x1, s.y1); add(s.x2, s.y2); }
    if (state.pose) add(state.pose.pose.x, state.pose.pose.y);
    if (xs.length === 0) return;
    const x0 = Math.min(...xs), x1 = Math.max(...xs), y0 = Math.min(...ys), y1 = Math.max(...ys);
    const { w, h } = size();
    view.cx = (x0 + x1) / 2; view.cy = (y0 + y1) / 2;
    view.scale = Math.max(0.05, Math.min(200, 0.9 * Math.min(w / Math.max(1, x1 - x0), h / Math.max(1, y1 - y0))));
    view.fitted = true;
    dirty = true;
  }

  // ---- drawing ----------------------------------------------------------------------------
  function line(points, color, width, dash) {
    if (points.length < 2) return;
    ctx.strokeStyle = color; ctx.lineWidth = width; ctx.setLineDash(dash || []);
    ctx.beginPath();
    points.forEach(([x, y], i) => { const [sx, sy] = worldToScreen(x, y); i ? ctx.lineTo(sx, sy) : ctx.moveTo(sx, sy); });
    ctx.stroke();
    ctx.setLineDash([]);
  }

  function vehicleOutline(p) {
    const l = state.config.vehicle_length_m / 2, w = state.config.vehicle_width_m / 2;
    const c = Math.cos(p.theta), s = Math.sin(p.theta);
    return [[l, w], [-l, w], [-l, -w], [l, -w], [l, w]].map(([x, y]) => [p.x + c * x - s * y, p.y + s * x + c * y]);
  }

  function drawVehicle(p, fill, stroke, dash) {
    const pts = vehicleOutline(p).map(([x, y]) => worldToScreen(x, y));
    ctx.beginPath();
    pts.forEach(([x, y], i) => (i ? ctx.lineTo(x, y) : ctx.moveTo(x, y)));
    if (fill) { ctx.fillStyle = fill; ctx.fill(); }
    ctx.strokeStyle = stroke; ctx.lineWidth = 2; ctx.setLineDash(dash || []); ctx.stroke(); ctx.setLineDash([]);
    // Heading: a line from the reference point to the front.
    const [ax, ay] = worldToScreen(p.x, p.y);
    const [bx, by] = worldToScreen(p.x + Math.cos(p.theta) * state.config.vehicle_length_m / 2,
                                   p.y + Math.sin(p.theta) * state.config.vehicle_length_m / 2);
    ctx.beginPath(); ctx.moveTo(ax, ay); ctx.lineTo(bx, by); ctx.stroke();
  }

  // The 2-sigma ellipse of the (x, y) covariance.
  function drawEllipse(p, cov) {
    const a = cov[0], b = cov[1], d = cov[4];
    if (!(a >= 0 && d >= 0) || !isFinite(b)) return;
    const tr = (a + d) / 2, det = Math.sqrt(Math.max(0, ((a - d) / 2) ** 2 + b * b));
    const l1 = tr + det, l2 = Math.max(0, tr - det);
    const angle = Math.atan2(l1 - a, b || 1e-12);
    const [sx, sy] = worldToScreen(p.x, p.y);
    ctx.strokeStyle = "#e07b00"; ctx.lineWidth = 1.5;
    ctx.beginPath();
    ctx.ellipse(sx, sy, Math.max(1, 2 * Math.sqrt(l1) * view.scale), Math.max(1, 2 * Math.sqrt(l2) * view.scale),
                -(b === 0 ? (a >= d ? 0 : Math.PI / 2) : angle), 0, 2 * Math.PI);
    ctx.stroke();
  }

  // A path_t as points: straight pieces, arcs at their radius, turns in place.
  function pathPoints(path) {
    let p = path.start;
    const out = [[p.x, p.y]];
    for (const seg of path.segments) {
      const e = seg.end;
      const arc = [MOTION.ARC_LEFT, MOTION.ARC_RIGHT, MOTION.ARC_LEFT_REVERSE, MOTION.ARC_RIGHT_REVERSE].includes(seg.motion);
      const chord = Math.hypot(e.x - p.x, e.y - p.y);
      if (arc && seg.radius > 0 && chord > 1e-6 && chord <= 2 * seg.radius) {
        const left = seg.motion === MOTION.ARC_LEFT || seg.motion === MOTION.ARC_LEFT_REVERSE;
        const side = left ? 1 : -1;
        const cx = p.x - side * Math.sin(p.theta) * seg.radius, cy = p.y + side * Math.cos(p.theta) * seg.radius;
        const a0 = Math.atan2(p.y - cy, p.x - cx);
        let da = Math.atan2(e.y - cy, e.x - cx) - a0;
        while (da > Math.PI) da -= 2 * Math.PI;
        while (da < -Math.PI) da += 2 * Math.PI;
        const n = Math.max(2, Math.ceil(Math.abs(da) / 0.05));
        for (let i = 1; i <= n; i++) {
          const a = a0 + (da * i) / n;
          out.push([cx + seg.radius * Math.cos(a), cy + seg.radius * Math.sin(a)]);
        }
      } else {
        out.push([e.x, e.y]);
      }
      p = e;
    }
    return out;
  }

  function drawScaleBar() {
    const { h } = size();
    const target = 120 / view.scale;  // m that 120 px show
    const pow = Math.pow(10, Math.floor(Math.log10(target)));
    const len = [1, 2, 5, 10].map((k) => k * pow).filter((v) => v <= target).pop() || pow;
    const px = len * view.scale;
    const x = 16, y = h - 20;
    ctx.fillStyle = "rgba(255,255,255,.85)"; ctx.fillRect(x - 6, y - 22, px + 60, 34);
    ctx.strokeStyle = "#222"; ctx.lineWidth = 2;
    ctx.beginPath(); ctx.moveTo(x, y - 6); ctx.lineTo(x, y); ctx.lineTo(x + px, y); ctx.lineTo(x + px, y - 6); ctx.stroke();
    ctx.fillStyle = "#222"; ctx.font = "12px system-ui, sans-serif";
    ctx.fillText(len >= 1 ? `${len} m` : `${Math.round(len * 100)} cm`, x + px / 2 - 12, y - 9);
  }

  function draw() {
    const dpr = window.devicePixelRatio || 1;
    const { w, h } = size();
    if (canvas.width !== Math.round(w * dpr) || canvas.height !== Math.round(h * dpr)) {
      canvas.width = Math.round(w * dpr); canvas.height = Math.round(h * dpr);
    }
    ctx.setTransform(dpr, 0, 0, dpr, 0, 0);
    ctx.fillStyle = "#fff"; ctx.fillRect(0, 0, w, h);
    if (!view.fitted) fit();
    const pose = state.pose ? state.pose.pose : null;
    if (view.follow && pose) { view.cx = pose.x; view.cy = pose.y; }

    if (state.walls && $("show_walls").checked)
      for (const s of state.walls.segments) line([[s.x1, s.y1], [s.x2, s.y2]], "#9a9a9a", 1.5);
    if (state.map)
      for (const c of state.map.contours) {
        const pts = [];
        for (let i = 0; i < c.xy.length; i += 2) pts.push([c.xy[i], c.xy[i + 1]]);
        if (c.closed && pts.length > 2) pts.push(pts[0]);
        line(pts, "#1f5fbf", 2.5);
      }
    if (state.track.length > 1) line(state.track, "#8c564b", 1.5);
    if (state.path && state.path.feasible) line(pathPoints(state.path), "#2ca02c", 2, [6, 4]);
    if (state.drivePath && state.drivePath.feasible) line(pathPoints(state.drivePath), "#f2b705", 3);
    const scanPose = pose || (state.truth ? state.truth.pose : null);
    if (state.scan && scanPose && $("show_scan").checked) {
      const s = state.scan, o = s.sensor_offset;
      const c = Math.cos(scanPose.theta), sn = Math.sin(scanPose.theta);
      const sx0 = scanPose.x + c * o.x - sn * o.y, sy0 = scanPose.y + sn * o.x + c * o.y, st = scanPose.theta + o.theta;
      ctx.fillStyle = "#d6249f";
      s.ranges.forEach((r, i) => {
        if (r === null) return;
        const a = st + s.start_angle + i * s.angle_step;
        const [px, py] = worldToScreen(sx0 + r * Math.cos(a), sy0 + r * Math.sin(a));
        ctx.fillRect(px - 1, py - 1, 2, 2);
      });
    }
    if (state.truth) drawVehicle(state.truth.pose, null, "#222", [4, 3]);
    if (pose) {
      drawVehicle(pose, "rgba(224,123,0,.35)", "#e07b00");
      drawEllipse(pose, state.pose.covariance);
    }
    drawScaleBar();
    stats.redraws++;
  }

  function frame() {
    stats.frames++;
    if (dirty) { dirty = false; draw(); }
    requestAnimationFrame(frame);
  }
  requestAnimationFrame(frame);
  setInterval(() => {
    stats.fps = stats.frames; stats.redrawsPerS = stats.redraws; stats.bytesPerS = stats.bytes;
    stats.messagesPerS = stats.messages;
    stats.frames = stats.redraws = stats.bytes = stats.messages = 0;
    $("rates").textContent = `${stats.fps} frames/s (${stats.redrawsPerS} redraws/s) · ` +
        `${(stats.bytesPerS / 1000).toFixed(1)} kB/s · ${stats.messagesPerS} msg/s`;
  }, 1000);

  // ---- panels -----------------------------------------------------------------------------
  const deg = (r) => (r * 180 / Math.PI).toFixed(1);
  const esc = (s) => String(s).replace(/[&<>"]/g, (c) => ({ "&": "&amp;", "<": "&lt;", ">": "&gt;", '"': "&quot;" }[c]));

  function showVehicle() {
    if (!state.pose) return;
    const p = state.pose.pose, c = state.pose.covariance;
    const sigma = c.every((v) => v === 0) ? "covariance not given" :
        `σx ${Math.sqrt(Math.max(0, c[0])).toFixed(3)} m, σy ${Math.sqrt(Math.max(0, c[4])).toFixed(3)} m, ` +
        `σθ ${deg(Math.sqrt(Math.max(0, c[8])))}°`;
    let html = `x ${p.x.toFixed(2)} m, y ${p.y.toFixed(2)} m, θ ${deg(p.theta)}°<br>` +
        `${sigma} · ${esc(state.pose.source)} ${state.pose.converged ? "" : "(not converged)"}`;
    if (state.truth) {
      const t = state.truth.pose;
      html += `<br>true pose off by ${Math.hypot(t.x - p.x, t.y - p.y).toFixed(3)} m, ` +
          `${deg(Math.atan2(Math.sin(t.theta - p.theta), Math.cos(t.theta - p.theta)))}°`;
    }
    $("vehicle").innerHTML = html;
  }

  function showMission() {
    const m = state.mission;
    if (!m) return;
    $("mission").innerHTML = `<b>${MISSION_STATES[m.state] || m.state}</b> ${esc(m.mission_id)} · task ` +
        `${m.current_task_id >= 0 ? m.current_task_id : "—"} · ${m.tasks_done}/${m.tasks_total} tasks done · ` +
        `${Math.round((m.progress || 0) * 100)} %<br>${esc(m.message)}` +
        (m.waiting_for ? `<br>waiting for: ${esc(m.waiting_for)}` : "");
    const depth = {};
    const lines = m.nodes.map((n) => {
      depth[n.id] = n.parent >= 0 && depth[n.parent] !== undefined ? depth[n.parent] + 1 : 0;
      const current = n.task_id >= 0 && n.task_id === m.current_task_id;
      const mark = { 0: "○", 1: "▶", 2: "✓", 3: "✗" }[n.state] || "?";
      return `<div class="${current ? "current" : ""}" data-task="${n.task_id}">${"  ".repeat(depth[n.id])}${mark} ` +
          `${esc(n.name)} [${NODE_STATES[n.state] || n.state}]</div>`;
    });
    $("tree").innerHTML = lines.join("");
  }

  function showFleet() {
    const rows = (state.fleet.processes || []).map((p) => {
      const name = p.instance ? `${p.process}/${p.instance}` : p.process;
      const cls = p.stale ? "stale" : p.state;
      return `<tr title="${esc(p.message)}"><td>${esc(name)}</td><td class="${esc(cls)}">${p.stale ? "STALE" : esc(p.state)}</td>` +
          `<td class="num ${p.stale ? "stale" : ""}">${p.age_s.toFixed(1)}</td>` +
          `<td class="num">${p.in_rate_hz === null ? "—" : p.in_rate_hz.toFixed(1)}</td>` +
          `<td class="num">${p.messages_bad}</td></tr>`;
    });
    document.querySelector("#fleet tbody").innerHTML = rows.join("");
  }

  function showBridge() {
    const b = state.bridge, s = b.server || {};
    $("bridge").textContent = `${s.clients} client(s), ${(s.bytes_sent / 1e6).toFixed(2)} MB sent, ` +
        `${s.frames_dropped} frames dropped (slow clients), commands ${b.commands_allowed ? "allowed" : "refused"}`;
  }

  // ---- the connection -----------------------------------------------------------------------
  let ws = null;
  const channels = new Map();       // channel id -> topic
  const subscriptions = new Map();  // subscription id -> topic
  let nextSubscription = 1;
  const clientChannels = new Map();  // topic -> client channel id

  function onMessage(topic, msg) {
    switch (topic) {
      case "CONTOUR_MAP": state.map = msg; break;
      case "SIM_WORLD": state.walls = msg; break;
      case "LINE_MAP": if (!state.walls) state.walls = msg; break;
      case "LADAR_SCAN": state.scan = msg; break;
      case "POSE": {
        state.pose = msg;
        const last = state.track[state.track.length - 1];
        if (!last || Math.hypot(last[0] - msg.pose.x, last[1] - msg.pose.y) > 0.05) state.track.push([msg.pose.x, msg.pose.y]);
        if (state.track.length > 20000) state.track.splice(0, state.track.length - 20000);
        showVehicle();
        break;
      }
      case "SIM_TRUTH": state.truth = msg; showVehicle(); break;
      case "PATH": state.path = msg; break;
      case "DRIVE_PATH": state.drivePath = msg; break;
      case "MISSION_STATUS": state.mission = msg; showMission(); break;
      case "/minenav/fleet": state.fleet = msg; showFleet(); break;
      case "/minenav/bridge": state.bridge = msg; showBridge(); break;
      case "/minenav/viewer_config": state.config = msg; break;
      case "/minenav/replay": showReplay(msg); break;
    }
    dirty = true;
  }

  function connect() {
    ws = new WebSocket(`ws://${location.host}/`, ["foxglove.websocket.v1"]);
    ws.binaryType = "arraybuffer";
    ws.onopen = () => { state.connected = true; $("conn").textContent = `connected to ${location.host}`; };
    ws.onclose = () => {
      state.connected = false; channels.clear(); subscriptions.clear(); clientChannels.clear();
      $("conn").textContent = "disconnected: reconnecting in 2 s…";
      setButtons();
      setTimeout(connect, 2000);
    };
    ws.onmessage = (event) => {
      stats.messages++;
      if (typeof event.data === "string") {
        stats.bytes += event.data.length;
        const m = JSON.parse(event.data);
        if (m.op === "serverInfo") {
          state.capabilities = m.capabilities || [];
          state.commandTopic = (m.metadata || {}).command_topic || null;
          state.replayTopic = (m.metadata || {}).replay_control_topic || null;
          $("replay").hidden = !state.replayTopic;
          setButtons();
        } else if (m.op === "advertise") {
          const subs = [];
          for (const c of m.channels) {
            channels.set(c.id, c.topic);
            if (WANTED.includes(c.topic)) {
              const id = nextSubscription++;
              subscriptions.set(id, c.topic);
              subs.push({ id, channelId: c.id });
            }
          }
          if (subs.length) ws.send(JSON.stringify({ op: "subscribe", subscriptions: subs }));
        } else if (m.op === "status") {
          $("status").textContent = m.message;
          $("status").style.color = m.level >= 2 ? "#c4161c" : "#555";
        }
        return;
      }
      const bytes = new DataView(event.data);
      stats.bytes += event.data.byteLength;
      if (bytes.getUint8(0) !== 1) return;
      const topic = subscriptions.get(bytes.getUint32(1, true));
      if (!topic) return;
      const text = new TextDecoder().decode(new Uint8Array(event.data, 13));
      onMessage(topic, JSON.parse(text));
    };
  }

  // ---- operator commands ----------------------------------------------------------------------
  function setButtons() {
    const allowed = state.connected && state.capabilities.includes("clientPublish") && state.commandTopic;
    for (const b of document.querySelectorAll("#commands button")) b.disabled = !allowed;
    if (!allowed) $("status").textContent = state.connected ? "commands are off (bridge started without --allow-commands)" : "";
  }

  // A JSON message on one of the topics the server accepts (clientPublish).
  function publish(topic, message) {
    if (!ws || ws.readyState !== WebSocket.OPEN || !topic) return false;
    if (!clientChannels.has(topic)) {
      const id = clientChannels.size + 1;
      clientChannels.set(topic, id);
      ws.send(JSON.stringify({ op: "advertise", channels: [{ id, topic, encoding: "json", schemaName: "minenav.viewer.client" }] }));
    }
    const payload = new TextEncoder().encode(JSON.stringify(message));
    const frame = new Uint8Array(5 + payload.length);
    frame[0] = 1;
    new DataView(frame.buffer).setUint32(1, clientChannels.get(topic), true);
    frame.set(payload, 5);
    ws.send(frame);
    return true;
  }

  function sendCommand(name) {
    if (publish(state.commandTopic, { command: name })) $("status").textContent = `${name} sent…`;
  }

  // ---- replay of a log (viewer_bridge --replay) ----------------------------------------------
  let sliderHeld = false;
  function showReplay(r) {
    if (state.replay && r.generation !== state.replay.generation) {
      // A seek: what follows is the state at the new time, from nothing.
      Object.assign(state, { map: null, walls: null, scan: null, pose: null, truth: null, path: null, drivePath: null,
                             mission: null, track: [] });
      $("vehicle").textContent = "no pose yet"; $("mission").textContent = "no MISSION_STATUS yet"; $("tree").innerHTML = "";
    }
    state.replay = r;
    const slider = $("replay_slider");
    slider.max = r.duration_s.toFixed(1);
    if (!sliderHeld) slider.value = r.time_s.toFixed(1);
    $("replay_time").textContent = `${r.time_s.toFixed(1)} s / ${r.duration_s.toFixed(1)} s`;
    $("replay_play").textContent = r.paused ? "▶" : "⏸";
  }
  $("replay_slider").addEventListener("input", () => { sliderHeld = true; });
  $("replay_slider").addEventListener("change", (e) => {
    sliderHeld = false;
    publish(state.replayTopic, { seek_s: Number(e.target.value) });
  });
  $("replay_play").addEventListener("click", () => {
    if (!state.replay) return;
    const atEnd = state.replay.time_s >= state.replay.duration_s;
    publish(state.replayTopic, atEnd ? { seek_s: 0, paused: false } : { paused: !state.replay.paused });
  });
  $("replay_speed").addEventListener("change", (e) => publish(state.replayTopic, { speed: Number(e.target.value) }));

  for (const b of document.querySelectorAll("#commands button")) b.addEventListener("click", () => sendCommand(b.dataset.cmd));
  setButtons();

  // ---- pan, zoom, follow ------------------------------------------------------------------------
  let drag = null;
  canvas.addEventListener("mousedown", (e) => { drag = { x: e.clientX, y: e.clientY }; canvas.style.cursor = "grabbing"; });
  window.addEventListener("mouseup", () => { drag = null; canvas.style.cursor = "grab"; });
  canvas.addEventListener("mousemove", (e) => {
    const r = canvas.getBoundingClientRect();
    const [x, y] = screenToWorld(e.clientX - r.left, e.clientY - r.top);
    $("cursor").textContent = `x ${x.toFixed(2)} m, y ${y.toFixed(2)} m`;
    if (!drag) return;
    view.cx -= (e.clientX - drag.x) / view.scale; view.cy += (e.clientY - drag.y) / view.scale;
    drag = { x: e.clientX, y: e.clientY };
    view.follow = false; $("follow").checked = false; dirty = true;
  });
  canvas.addEventListener("wheel", (e) => {
    e.preventDefault();
    const r = canvas.getBoundingClientRect();
    const [x, y] = screenToWorld(e.clientX - r.left, e.clientY - r.top);
    view.scale = Math.max(0.05, Math.min(500, view.scale * Math.exp(-e.deltaY * 0.0015)));
    if (!view.follow) {
      const [x2, y2] = screenToWorld(e.clientX - r.left, e.clientY - r.top);
      view.cx += x - x2; view.cy += y - y2;
    }
    dirty = true;
  }, { passive: false });
  $("follow").addEventListener("change", (e) => { view.follow = e.target.checked; dirty = true; });
  $("fit").addEventListener("click", () => { view.follow = false; $("follow").checked = false; fit(); });
  $("zoomin").addEventListener("click", () => { view.scale *= 1.5; dirty = true; });
  $("zoomout").addEventListener("click", () => { view.scale /= 1.5; dirty = true; });
  for (const id of ["show_walls", "show_scan"]) $(id).addEventListener("change", () => { dirty = true; });
  window.addEventListener("resize", () => { dirty = true; });

  window.minenavViewer = { state, view, stats, worldToScreen, screenToWorld, sendCommand, publish, redraw: () => { dirty = true; } };
  connect();
})();
