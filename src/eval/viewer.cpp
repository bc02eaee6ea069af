// The stream viewer: one self-contained HTML page per stream.
#include "eval/viewer.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include "common/json.hpp"
#include "eval/report.hpp"

namespace actionstring {
namespace host {
namespace {

// Skeleton frames per second on the page, and the most coordinates it holds
// (2 bytes each before base64): long streams are thinned further.
constexpr double page_frame_rate_hz = 30.0;
constexpr std::size_t most_page_values = 1500000;

std::string base64(const std::vector<std::uint8_t>& bytes) {
    static const char alphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    out.reserve((bytes.size() + 2) / 3 * 4);
    for (std::size_t i = 0; i < bytes.size(); i += 3) {
        const std::uint32_t b0 = bytes[i];
        const std::uint32_t b1 = i + 1 < bytes.size() ? bytes[i + 1] : 0u;
        const std::uint32_t b2 = i + 2 < bytes.size() ? bytes[i + 2] : 0u;
        const std::uint32_t v = (b0 << 16) | (b1 << 8) | b2;
        out += alphabet[(v >> 18) & 63];
        out += alphabet[(v >> 12) & 63];
        out += i + 1 < bytes.size() ? alphabet[(v >> 6) & 63] : '=';
        out += i + 2 < bytes.size() ? alphabet[v & 63] : '=';
    }
    return out;
}

std::string number(double v, int decimals) {
    if (!std::isfinite(v)) return "null";
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, "%.*f", decimals, v);
    return buffer;
}

// Frames of the stream shown on the page: at most page_frame_rate_hz, and
// fewer when the stream would exceed most_page_values coordinates.
std::vector<std::size_t> page_frames(const StreamTimeline& s) {
    const std::size_t frames = s.times_s.size();
    std::vector<std::size_t> picked;
    if (frames == 0) return picked;
    const double duration = s.times_s.back() - s.times_s.front();
    const std::size_t values_per_frame = std::max<std::size_t>(1, s.joints * 3);
    double spacing = 1.0 / page_frame_rate_hz;
    // Ticks 0 … duration / spacing, each at most one frame: keep their count within budget.
    const double affordable = static_cast<double>(std::max<std::size_t>(2, most_page_values / values_per_frame));
    if (duration / spacing + 1 > affordable) spacing = duration / (affordable - 1);
    // The first frame nearest each tick of a `spacing` grid (rounding, so a
    // 30 Hz stream of times in whole milliseconds keeps every frame).
    long long last_tick = -1;
    for (std::size_t f = 0; f < frames; ++f) {
        const double offset = s.times_s[f] - s.times_s.front();
        const auto tick = static_cast<long long>(std::floor(offset / spacing + 0.5));
        if (tick > last_tick) {
            picked.push_back(f);
            last_tick = tick;
        }
    }
    return picked;
}

// One row of the timeline: runs of equal labels as [start, end, label].
std::string spans_json(const std::vector<int>& labels, const std::vector<double>& times) {
    std::string out = "[";
    const std::size_t n = std::min(labels.size(), times.size());
    for (std::size_t f = 0; f < n;) {
        std::size_t g = f;
        while (g < n && labels[g] == labels[f]) ++g;
        const double end = g < n ? times[g] : times[n - 1];
        if (out.size() > 1) out += ',';
        out += "[" + number(times[f], 4) + "," + number(end, 4) + "," + std::to_string(labels[f]) + "]";
        f = g;
    }
    return out + "]";
}

// JSON inside a <script> element must not contain "</" (it would end the element).
std::string script_safe(const std::string& json) {
    std::string out;
    out.reserve(json.size());
    for (std::size_t i = 0; i < json.size(); ++i) {
        if (json[i] == '<' && i + 1 < json.size() && json[i + 1] == '/') {
            out += "<\\/";
            ++i;
        } else {
            out += json[i];
        }
    }
    return out;
}

std::string page_data(const StreamTimeline& s, const std::vector<std::string>& labels, const std::string& title) {
    const std::vector<std::size_t> shown = page_frames(s);
    std::string d = "{";
    d += "\"title\":" + json_string(title);
    d += ",\"name\":" + json_string(s.name);
    d += ",\"labels\":[";
    for (std::size_t i = 0; i < labels.size(); ++i) d += (i ? "," : "") + json_string(labels[i]);
    d += "],\"colours\":[";
    for (std::size_t i = 0; i < labels.size(); ++i) d += (i ? "," : "") + json_string(label_colour(static_cast<int>(i)));
    d += "],\"unknownColour\":" + json_string(label_colour(unknown_frame));
    d += ",\"foreignColour\":" + json_string(label_colour(foreign_label));
    d += ",\"joints\":" + std::to_string(s.joints);
    d += ",\"parents\":[";
    for (std::size_t j = 0; j < s.parents.size(); ++j) d += (j ? "," : "") + std::to_string(s.parents[j]);
    d += "],\"up\":" + std::to_string(s.up_axis);
    d += ",\"start\":" + number(s.times_s.empty() ? 0.0 : s.times_s.front(), 4);
    d += ",\"end\":" + number(s.times_s.empty() ? 0.0 : s.times_s.back(), 4);
    d += ",\"streamFrames\":" + std::to_string(s.times_s.size());

    // Skeleton frames: times, then 16-bit millimetres (little-endian, base64).
    std::vector<std::uint8_t> bytes;
    const bool have_positions = s.joints > 0 && s.positions.size() >= s.times_s.size() * s.joints * 3;
    d += ",\"times\":[";
    for (std::size_t k = 0; k < shown.size(); ++k) {
        d += (k ? "," : "") + number(s.times_s[shown[k]], 4);
        if (!have_positions) continue;
        const float* p = s.positions.data() + shown[k] * s.joints * 3;
        for (std::size_t i = 0; i < s.joints * 3; ++i) {
            const double mm = std::isfinite(p[i]) ? std::round(static_cast<double>(p[i]) * 1000.0) : 0.0;
            const auto v = static_cast<std::int16_t>(std::clamp(mm, -32767.0, 32767.0));
            const auto u = static_cast<std::uint16_t>(v);
            bytes.push_back(static_cast<std::uint8_t>(u & 0xFF));
            bytes.push_back(static_cast<std::uint8_t>(u >> 8));
        }
    }
    d += "],\"positions\":\"" + (have_positions ? base64(bytes) : std::string()) + "\"";

    // The live label's margin at each shown frame (null: no other label could explain the stream).
    d += ",\"margin\":[";
    for (std::size_t k = 0; k < shown.size(); ++k) {
        const float m = shown[k] < s.labels.margin.size() ? s.labels.margin[shown[k]] : 0.0f;
        d += (k ? "," : "") + number(static_cast<double>(m), 3);
    }
    d += "]";

    d += ",\"rows\":[";
    bool first_row = true;
    auto row = [&](const char* name, const std::vector<int>& values) {
        if (values.empty()) return;
        d += std::string(first_row ? "" : ",") + "{\"name\":\"" + name + "\",\"spans\":" +
             spans_json(values, s.times_s) + "}";
        first_row = false;
    };
    row("truth", s.truth);
    row("settled", s.labels.settled);
    row("live", s.labels.live);
    row("window", s.labels.window);
    d += "]";

    d += ",\"events\":[";
    for (std::size_t i = 0; i < s.labels.events.size(); ++i) {
        const ReportedEvent& e = s.labels.events[i];
        d += std::string(i ? "," : "") + "{\"kind\":\"" +
             (e.event.kind == ActionEvent::Kind::started ? "started" : "ended") +
             "\",\"label\":" + std::to_string(frame_label(e.event.label)) +
             ",\"start\":" + number(static_cast<double>(e.event.start_time_us) * 1e-6, 3) +
             ",\"end\":" + number(static_cast<double>(e.event.end_time_us) * 1e-6, 3) +
             ",\"confidence\":" + number(static_cast<double>(e.event.confidence), 3) +
             ",\"at\":" + number(e.reported_s, 3) + "}";
    }
    d += "]}";
    return script_safe(d);
}

// The page. Plain canvas 2D drawing; everything it needs is in this file.
constexpr const char* page_head = R"HTML(<!DOCTYPE html>
<html lang="en">
<head>
<meta charset="utf-8">
<meta name="generator" content="actionstring view">
<title>actionstring</title>
<style>
body { font: 14px/1.4 sans-serif; margin: 16px; color: #222; background: #fff; }
h1 { font-size: 18px; margin: 0 0 4px; }
#sub { color: #666; margin-bottom: 8px; }
#top { display: flex; gap: 16px; align-items: flex-start; }
#skeleton { border: 1px solid #ccc; cursor: grab; }
#side { flex: 1; min-width: 240px; }
#now div { margin: 2px 0; }
.sw { display: inline-block; width: 12px; height: 12px; vertical-align: -1px; margin-right: 4px; border: 1px solid #888; }
#legend span { margin-right: 10px; white-space: nowrap; display: inline-block; }
#controls { margin: 8px 0; display: flex; gap: 8px; align-items: center; }
#slider { flex: 1; }
canvas.strip { display: block; width: 100%; margin-top: 6px; cursor: pointer; }
#events { max-height: 160px; overflow-y: auto; border: 1px solid #ddd; margin-top: 8px; font-size: 13px; }
#events div { padding: 1px 6px; cursor: pointer; }
#events div.near { background: #fff3c4; }
small { color: #666; }
</style>
<script>
window.viewerErrors = [];
window.addEventListener("error", function (e) {
  window.viewerErrors.push(String(e.message || e));
  document.documentElement.setAttribute("data-errors", JSON.stringify(window.viewerErrors));
});
</script>
</head>
<body>
<h1 id="title"></h1>
<div id="sub"></div>
<div id="top">
  <canvas id="skeleton" width="480" height="400" title="drag to turn the skeleton"></canvas>
  <div id="side">
    <div id="now"></div>
    <p id="legend"></p>
    <small>Rows: the truth (when known), the settled labels (final after the settle delay), the live
    labels (no delay, may change) and the paper's latest-window rule. The curve is the live label's
    margin over every other label (larger: more confident). Upper strip: the whole stream; lower
    strips: 20 s around the cursor. Space plays; arrows step; drag the skeleton to turn it.</small>
  </div>
</div>
<div id="controls">
  <button id="play">Play</button>
  <select id="speed"><option>0.25</option><option>0.5</option><option selected>1</option><option>2</option><option>4</option></select>
  <input id="slider" type="range" min="0" max="0" value="0">
  <span id="clock"></span>
</div>
<canvas id="overview" class="strip" height="90"></canvas>
<canvas id="detail" class="strip" height="90"></canvas>
<canvas id="margin" class="strip" height="70"></canvas>
<div id="events"></div>
<script id="data" type="application/json">)HTML";

constexpr const char* page_tail = R"HTML(</script>
<script>
"use strict";
(function () {
  const D = JSON.parse(document.getElementById("data").textContent);
  const BG = [255, 255, 255];
  const N = D.times.length, J = D.joints;
  const pos = decode(D.positions);
  const hasSkeleton = pos.length === N * J * 3 && J > 0;
  let frame = 0, playing = false, clock = 0, yaw = -0.5, pitch = 0.25;

  function decode(text) {
    if (!text) return new Int16Array(0);
    const bin = atob(text), out = new Int16Array(bin.length >> 1);
    for (let i = 0; i < out.length; i++) {
      const v = bin.charCodeAt(2 * i) | (bin.charCodeAt(2 * i + 1) << 8);
      out[i] = v > 32767 ? v - 65536 : v;
    }
    return out;
  }
  function labelName(l) { return l >= 0 ? D.labels[l] : (l === -1 ? "unknown / no action" : "a label the model lacks"); }
  function colour(l) { return l >= 0 ? D.colours[l] : (l === -1 ? D.unknownColour : D.foreignColour); }
  function fmt(t) { return t.toFixed(2) + " s"; }

  // Right-handed coordinates with Y up, whatever the file's up axis.
  function world(f, j) {
    const b = (f * J + j) * 3, p0 = pos[b] / 1000, p1 = pos[b + 1] / 1000, p2 = pos[b + 2] / 1000;
    if (D.up === 2) return [p0, p2, -p1];
    if (D.up === 0) return [p1, p0, -p2];
    return [p0, p1, p2];
  }
  function lost(f) {
    for (let i = (f * J) * 3; i < (f * J + J) * 3; i++) if (pos[i] !== 0) return false;
    return true;
  }
  const root = D.parents.indexOf(-1) >= 0 ? D.parents.indexOf(-1) : 0;

  // Scale and floor from the whole stream, so the body does not jump in size.
  let floor = 0, reach = 1;
  if (hasSkeleton) {
    let lo = Infinity, hi = -Infinity, far = 0;
    for (let f = 0; f < N; f++) {
      if (lost(f)) continue;
      const r = world(f, root);
      for (let j = 0; j < J; j++) {
        const p = world(f, j);
        lo = Math.min(lo, p[1]); hi = Math.max(hi, p[1]);
        far = Math.max(far, Math.hypot(p[0] - r[0], p[2] - r[2]));
      }
    }
    if (isFinite(lo)) { floor = lo; reach = Math.max(hi - lo, 2 * far, 0.5); }
  }

  function at(t) {  // the shown frame at or before time t
    let a = 0, b = N - 1;
    if (N === 0) return 0;
    while (a < b) { const m = (a + b + 1) >> 1; if (D.times[m] <= t) a = m; else b = m - 1; }
    return a;
  }
  function labelAt(row, t) {
    const s = row.spans;
    let a = 0, b = s.length - 1;
    while (a < b) { const m = (a + b + 1) >> 1; if (s[m][0] <= t) a = m; else b = m - 1; }
    return s.length ? s[a][2] : -1;
  }
  function fit(canvas) {
    const w = Math.max(200, Math.round(canvas.getBoundingClientRect().width));
    if (canvas.width !== w) canvas.width = w;
    const ctx = canvas.getContext("2d");
    ctx.fillStyle = "rgb(" + BG.join(",") + ")";
    ctx.fillRect(0, 0, canvas.width, canvas.height);
    return ctx;
  }

  function drawSkeleton() {
    const c = document.getElementById("skeleton"), ctx = fit(c);
    if (!hasSkeleton) { ctx.fillStyle = "#888"; ctx.fillText("no skeleton in this stream", 20, 30); return; }
    const f = frame, r = world(f, root);
    const cy = Math.cos(yaw), sy = Math.sin(yaw), cp = Math.cos(pitch), sp = Math.sin(pitch);
    const s = 0.8 * c.height / reach, ox = c.width / 2, oy = c.height * 0.88;
    function project(p) {
      const x = p[0] - r[0], y = p[1] - floor, z = p[2] - r[2];
      const x1 = cy * x + sy * z, z1 = -sy * x + cy * z;
      const y2 = cp * y - sp * z1;
      return [ox + s * x1, oy - s * y2];
    }
    // The floor: a grid every 0.5 m around the root, in world coordinates.
    ctx.strokeStyle = "#e3e3e3"; ctx.lineWidth = 1;
    const g0x = Math.round(r[0] * 2) / 2, g0z = Math.round(r[2] * 2) / 2;
    for (let k = -4; k <= 4; k++) {
      const a = project([g0x + k * 0.5, floor, g0z - 2]), b = project([g0x + k * 0.5, floor, g0z + 2]);
      const c1 = project([g0x - 2, floor, g0z + k * 0.5]), d1 = project([g0x + 2, floor, g0z + k * 0.5]);
      ctx.beginPath(); ctx.moveTo(a[0], a[1]); ctx.lineTo(b[0], b[1]); ctx.moveTo(c1[0], c1[1]); ctx.lineTo(d1[0], d1[1]); ctx.stroke();
    }
    if (lost(f)) { ctx.fillStyle = "#c00"; ctx.fillText("tracking lost at this frame", 20, 30); return; }
    const live = D.rows.find(function (row) { return row.name === "live"; });
    const tint = live ? colour(labelAt(live, D.times[f])) : "#333";
    const pts = [];
    for (let j = 0; j < J; j++) pts.push(project(world(f, j)));
    ctx.strokeStyle = "#333"; ctx.lineWidth = 3; ctx.lineCap = "round";
    ctx.beginPath();
    for (let j = 0; j < J; j++) {
      const p = D.parents[j];
      if (p === undefined || p < 0) continue;
      ctx.moveTo(pts[p][0], pts[p][1]); ctx.lineTo(pts[j][0], pts[j][1]);
    }
    ctx.stroke();
    ctx.fillStyle = tint;
    for (let j = 0; j < J; j++) { ctx.beginPath(); ctx.arc(pts[j][0], pts[j][1], j === root ? 5 : 3.5, 0, 2 * Math.PI); ctx.fill(); }
  }

  const ROW_H = 18, LEFT = 64;
  function drawStrip(id, t0, t1) {
    const c = document.getElementById(id);
    c.height = Math.max(30, D.rows.length * (ROW_H + 2) + 16);
    const ctx = fit(c), w = c.width - LEFT - 4, span = Math.max(t1 - t0, 1e-6);
    const x = function (t) { return LEFT + (t - t0) / span * w; };
    ctx.font = "12px sans-serif"; ctx.textBaseline = "middle";
    D.rows.forEach(function (row, i) {
      const y = 4 + i * (ROW_H + 2);
      ctx.fillStyle = "#444"; ctx.fillText(row.name, 4, y + ROW_H / 2);
      for (const s of row.spans) {
        if (s[1] < t0 || s[0] > t1) continue;
        const a = Math.max(x(s[0]), LEFT), b = Math.min(x(Math.max(s[1], s[0] + span / w)), LEFT + w);
        ctx.fillStyle = colour(s[2]); ctx.fillRect(a, y, Math.max(b - a, 1), ROW_H);
      }
    });
    const yAxis = 4 + D.rows.length * (ROW_H + 2) + 6;
    ctx.fillStyle = "#666";
    ctx.fillText(fmt(t0), LEFT, yAxis);
    const end = fmt(t1); ctx.fillText(end, LEFT + w - ctx.measureText(end).width, yAxis);
    const now = N ? D.times[frame] : 0;
    if (now >= t0 && now <= t1) {
      ctx.strokeStyle = "#000"; ctx.lineWidth = 2;
      ctx.beginPath(); ctx.moveTo(x(now), 0); ctx.lineTo(x(now), yAxis - 6); ctx.stroke();
    }
    c.onclick = function (e) {
      const bx = c.getBoundingClientRect();
      const t = t0 + (e.clientX - bx.left - LEFT) / w * span;
      seek(at(Math.min(Math.max(t, D.start), D.end)));
    };
  }

  // The margin curve's scale: the 95th percentile of the finite margins.
  const finite = D.margin.filter(function (m) { return m !== null; }).sort(function (a, b) { return a - b; });
  const top = Math.max(finite.length ? finite[Math.floor(0.95 * (finite.length - 1))] : 1, 1e-3);
  function drawMargin(t0, t1) {
    const c = document.getElementById("margin"), ctx = fit(c), w = c.width - LEFT - 4, h = c.height - 8;
    const span = Math.max(t1 - t0, 1e-6);
    ctx.font = "12px sans-serif"; ctx.textBaseline = "middle"; ctx.fillStyle = "#444";
    ctx.fillText("margin", 4, h / 2);
    ctx.strokeStyle = "#ddd"; ctx.beginPath(); ctx.moveTo(LEFT, h + 2); ctx.lineTo(LEFT + w, h + 2); ctx.stroke();
    ctx.save(); ctx.beginPath(); ctx.rect(LEFT, 0, w, c.height); ctx.clip();
    ctx.strokeStyle = "#1f5fa8"; ctx.lineWidth = 1.5; ctx.beginPath();
    let started = false;
    for (let k = at(t0); k < N && D.times[k] <= t1; k++) {
      const m = D.margin[k] === null ? top : Math.min(D.margin[k], top);
      const px = LEFT + (D.times[k] - t0) / span * w, py = h + 2 - m / top * (h - 4);
      if (!started) { ctx.moveTo(px, py); started = true; } else ctx.lineTo(px, py);
    }
    ctx.stroke(); ctx.restore();
    const now = N ? D.times[frame] : 0;
    ctx.strokeStyle = "#000"; ctx.lineWidth = 2;
    const nx = LEFT + (now - t0) / span * w;
    ctx.beginPath(); ctx.moveTo(nx, 0); ctx.lineTo(nx, h + 4); ctx.stroke();
  }

  function drawText() {
    const t = N ? D.times[frame] : 0;
    document.getElementById("clock").textContent = fmt(t) + " of " + fmt(D.end);
    const now = document.getElementById("now");
    now.textContent = "";
    D.rows.forEach(function (row) {
      const l = labelAt(row, t), div = document.createElement("div"), sw = document.createElement("span");
      sw.className = "sw"; sw.style.background = colour(l);
      div.appendChild(sw); div.appendChild(document.createTextNode(row.name + ": " + labelName(l)));
      now.appendChild(div);
    });
    const m = N ? D.margin[frame] : 0, div = document.createElement("div");
    div.textContent = "margin: " + (m === null ? "no rival" : m.toFixed(3));
    now.appendChild(div);
    const box = document.getElementById("events");
    let first = null;
    for (const e of box.children) {
      const near = Math.abs(Number(e.dataset.at) - t) < 2;
      e.classList.toggle("near", near);
      if (near && first === null) first = e;
    }
    if (first !== null) box.scrollTop = first.offsetTop - box.offsetTop;  // the list only, not the page
  }

  function draw() {
    const t = N ? D.times[frame] : 0;
    let t0 = Math.max(D.start, t - 10), t1 = Math.min(D.end, t0 + 20);
    t0 = Math.max(D.start, t1 - 20);
    drawSkeleton();
    drawStrip("overview", D.start, D.end);
    drawStrip("detail", t0, t1);
    drawMargin(t0, t1);
    drawText();
    document.getElementById("slider").value = frame;
  }
  function seek(f) { frame = Math.min(Math.max(f, 0), Math.max(N - 1, 0)); clock = N ? D.times[frame] : 0; draw(); }

  // Static parts: title, legend, events.
  document.title = D.title;
  document.getElementById("title").textContent = D.title;
  document.getElementById("sub").textContent = D.name + " \u00b7 " + D.streamFrames + " frames, " +
    fmt(D.end - D.start) + " \u00b7 skeleton of " + J + " joints shown at " + N + " frames";
  const used = new Set();
  D.rows.forEach(function (row) { row.spans.forEach(function (s) { used.add(s[2]); }); });
  const legend = document.getElementById("legend");
  Array.from(used).sort(function (a, b) { return a - b; }).forEach(function (l) {
    const item = document.createElement("span"), sw = document.createElement("span");
    sw.className = "sw"; sw.style.background = colour(l);
    item.appendChild(sw); item.appendChild(document.createTextNode(labelName(l)));
    legend.appendChild(item);
  });
  const events = document.getElementById("events");
  D.events.forEach(function (e) {
    const div = document.createElement("div");
    div.dataset.at = e.kind === "started" ? e.start : e.end;
    div.textContent = fmt(e.at) + ": " + labelName(e.label) + (e.kind === "started"
      ? " started at " + fmt(e.start)
      : " ended (" + fmt(e.start) + " \u2013 " + fmt(e.end) + ", confidence " + e.confidence.toFixed(2) + ")");
    div.onclick = function () { seek(at(Number(div.dataset.at))); };
    events.appendChild(div);
  });
  if (!D.events.length) events.textContent = "no action events";

  // Controls.
  const slider = document.getElementById("slider");
  slider.max = Math.max(N - 1, 0);
  slider.oninput = function () { seek(Number(slider.value)); };
  const play = document.getElementById("play");
  let last = null;
  function tick(ms) {
    if (!playing) return;
    if (last !== null) clock += (ms - last) / 1000 * Number(document.getElementById("speed").value);
    last = ms;
    if (clock >= D.end) { clock = D.end; playing = false; play.textContent = "Play"; }
    frame = at(clock); draw();
    if (playing) requestAnimationFrame(tick);
  }
  function toggle() {
    playing = !playing; play.textContent = playing ? "Pause" : "Play"; last = null;
    if (playing) { if (clock >= D.end) clock = D.start; requestAnimationFrame(tick); }
  }
  play.onclick = toggle;
  document.addEventListener("keydown", function (e) {
    if (e.target.tagName === "SELECT") return;
    if (e.key === " ") { e.preventDefault(); toggle(); }
    else if (e.key === "ArrowRight") seek(frame + 1);
    else if (e.key === "ArrowLeft") seek(frame - 1);
  });
  const sk = document.getElementById("skeleton");
  let drag = null;
  sk.onmousedown = function (e) { drag = [e.clientX, e.clientY, yaw, pitch]; };
  window.addEventListener("mouseup", function () { drag = null; });
  window.addEventListener("mousemove", function (e) {
    if (!drag) return;
    yaw = drag[2] + (e.clientX - drag[0]) * 0.01;
    pitch = Math.min(1.4, Math.max(-0.3, drag[3] + (e.clientY - drag[1]) * 0.01));
    drawSkeleton();
  });
  window.addEventListener("resize", draw);

  // Start at #t=SECONDS, else in the middle of the first predicted action.
  let startAt = D.start;
  const hash = /t=([0-9.]+)/.exec(location.hash);
  const settled = D.rows.find(function (row) { return row.name === "settled"; });
  const firstAction = settled ? settled.spans.find(function (s) { return s[2] >= 0; }) : null;
  if (hash) startAt = Number(hash[1]); else if (firstAction) startAt = (firstAction[0] + firstAction[1]) / 2;
  seek(at(startAt));

  // Self-check for the browser test: how many pixels each canvas drew.
  function inked(id) {
    const c = document.getElementById(id), d = c.getContext("2d").getImageData(0, 0, c.width, c.height).data;
    let n = 0;
    for (let i = 0; i < d.length; i += 4) if (d[i] !== BG[0] || d[i + 1] !== BG[1] || d[i + 2] !== BG[2]) n++;
    return n;
  }
  document.documentElement.setAttribute("data-check", JSON.stringify({
    skeleton: inked("skeleton"), overview: inked("overview"), detail: inked("detail"), margin: inked("margin"),
    frames: N, joints: J, rows: D.rows.length, events: D.events.length }));
})();
</script>
</body>
</html>
)HTML";

}  // namespace

std::string viewer_html(const StreamTimeline& stream, const std::vector<std::string>& labels,
                        const std::string& title) {
    return std::string(page_head) + page_data(stream, labels, title) + page_tail;
}

}  // namespace host
}  // namespace actionstring
