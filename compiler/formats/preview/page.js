// The car's state at t ms: the last change at or before t (the board applies each packet when
// it arrives), and its pose between the path's 20 ms samples.
function carState(p, t) {
  let lo = 0, hi = p.changes.length - 1;
  while (lo < hi) {
    const mid = (lo + hi + 1) >> 1;
    if (p.changes[mid][0] <= t) lo = mid; else hi = mid - 1;
  }
  const c = p.changes[lo];
  const values = { pan: c[1], tilt: c[2], servo1: c[3], servo2: c[4], servo3: c[5], servo4: c[6] };
  const path = p.path;
  let i = 0;
  while (i + 1 < path.length && path[i + 1][0] <= t) ++i;
  let pose = path[i];
  if (i + 1 < path.length) {
    const a = path[i], b = path[i + 1];
    const f = (t - a[0]) / (b[0] - a[0]);
    pose = [t, a[1] + (b[1] - a[1]) * f, a[2] + (b[2] - a[2]) * f, a[3] + (b[3] - a[3]) * f];
  }
  return { values, pose: { x: pose[1], y: pose[2], heading: pose[3] } };
}

// ---- drawing: each part's robot is built once as SVG text, then only attributes change.
const SIDE = { w: 400, h: 400, scale: 0.4, r0: 200, z0: 300 };
const sideX = (r) => SIDE.r0 + r * SIDE.scale;
const sideY = (z) => SIDE.z0 - z * SIDE.scale;
const TOP = { c: 200, scale: 0.4 };

function dialsSvg(prefix, names, columns, left) {
  const rows = Math.ceil(names.length / columns);
  let out = `<svg width="${columns * 88}" height="${rows * 120}" style="left:${left}px">`;
  names.forEach((name, i) => {
    const x = (i % columns) * 88 + 44, y = Math.floor(i / columns) * 120 + 46;
    out += `<circle cx="${x}" cy="${y}" r="34" fill="#f3f4f6" stroke="#9ca3af"/>` +
      `<path d="M ${x - 24} ${y + 24} A 34 34 0 1 1 ${x + 24} ${y + 24}" fill="none" ` +
      `stroke="#d1d5db" stroke-width="3"/>` +
      `<line id="${prefix}-needle-${i}" x1="${x}" y1="${y}" x2="${x}" y2="${y - 30}" ` +
      `stroke="#1f2937" stroke-width="3" stroke-linecap="round"/>` +
      `<text x="${x}" y="${y + 52}" text-anchor="middle" font-size="11">${name}</text>` +
      `<text id="${prefix}-value-${i}" x="${x}" y="${y + 66}" text-anchor="middle" ` +
      `font-size="10" fill="#6b7280"></text>`;
  });
  return out + "</svg>";
}

// A dial's needle sweeps 270 degrees from the low end of the servo's limits to the high end.
function setDial(prefix, i, value, lo, hi) {
  const needle = $(`${prefix}-needle-${i}`);
  const label = $(`${prefix}-value-${i}`);
  if (value === null || value === undefined) {
    needle.setAttribute("visibility", "hidden");
    label.textContent = "unknown";
    return;
  }
  const f = Math.min(Math.max((value - lo) / Math.max(hi - lo, 1), 0), 1);
  const a = (-135 + 270 * f) * Math.PI / 180;
  const x = +needle.getAttribute("x1"), y = +needle.getAttribute("y1");
  needle.setAttribute("visibility", "visible");
  needle.setAttribute("x2", x + 30 * Math.sin(a));
  needle.setAttribute("y2", y - 30 * Math.cos(a));
  label.textContent = fmt(value);
}

function buildPart(p, index) {
  const prefix = "p" + index;
  const div = document.createElement("div");
  div.className = "robot";
  let html = `<div class="caption">${escapeText(p.name ? p.name + ": " + p.title : p.title)}</div>`;
  if (p.kind === "servo" && p.arm) {
    const reach = p.arm.upper_arm + p.arm.forearm + p.arm.hand;
    html += `<svg id="${prefix}-side" width="400" height="400" style="left:0px">` +
      `<rect width="400" height="400" fill="#f9fafb" stroke="#d1d5db"/>` +
      `<text x="8" y="16" font-size="11" fill="#6b7280">side (the arm's plane), mm</text>` +
      `<line x1="0" y1="${sideY(0)}" x2="400" y2="${sideY(0)}" stroke="#9ca3af"/>` +
      `<rect x="${sideX(-30)}" y="${sideY(p.arm.base_height)}" width="${60 * SIDE.scale}" ` +
      `height="${p.arm.base_height * SIDE.scale}" fill="#d1d5db"/>` +
      `<polyline id="${prefix}-links" fill="none" stroke="#1f2937" stroke-width="6" ` +
      `stroke-linejoin="round" stroke-linecap="round"/>` +
      `<polyline id="${prefix}-claw" fill="none" stroke="#4b5563" stroke-width="3"/>` +
      `<g id="${prefix}-joints"></g>` +
      `<circle id="${prefix}-tip" r="5" fill="#ff00ff"/></svg>` +
      `<svg id="${prefix}-top" width="400" height="400" style="left:408px">` +
      `<rect width="400" height="400" fill="#f9fafb" stroke="#d1d5db"/>` +
      `<text x="8" y="16" font-size="11" fill="#6b7280">from above: x right, y up, mm</text>` +
      `<circle cx="${TOP.c}" cy="${TOP.c}" r="${reach * TOP.scale}" fill="none" ` +
      `stroke="#e5e7eb" stroke-dasharray="4 3"/>` +
      `<line x1="${TOP.c}" y1="${TOP.c}" x2="${TOP.c + 40}" y2="${TOP.c}" stroke="#9ca3af"/>` +
      `<circle cx="${TOP.c}" cy="${TOP.c}" r="12" fill="#d1d5db"/>` +
      `<polyline id="${prefix}-plan" fill="none" stroke="#1f2937" stroke-width="6" ` +
      `stroke-linecap="round"/><circle id="${prefix}-plan-tip" r="5" fill="#2563eb"/></svg>`;
    div.style.width = "808px";
  } else if (p.kind === "servo") {
    html += dialsSvg(prefix, p.columns, Math.max(p.columns.length, 1), 0);
    div.className = "robot dials";
    div.style.width = Math.max(400, p.columns.length * 88) + "px";
  } else {
    let xs = p.path.map((q) => q[1]), ys = p.path.map((q) => q[2]);
    const minX = Math.min(0, ...xs), maxX = Math.max(0, ...xs);
    const minY = Math.min(0, ...ys), maxY = Math.max(0, ...ys);
    const span = Math.max(maxX - minX, maxY - minY, 200);
    p.view = { scale: 320 / span, mx: (minX + maxX) / 2, my: (minY + maxY) / 2 };
    const X = (x) => 200 + (x - p.view.mx) * p.view.scale;
    const Y = (y) => 200 - (y - p.view.my) * p.view.scale;
    const points = p.path.map((q) => `${X(q[1]).toFixed(1)},${Y(q[2]).toFixed(1)}`).join(" ");
    html += `<svg id="${prefix}-car" width="400" height="400" style="left:0px">` +
      `<rect width="400" height="400" fill="#f9fafb" stroke="#d1d5db"/>` +
      `<text x="8" y="16" font-size="11" fill="#6b7280">from above (nominal scale)</text>` +
      `<polyline points="${points}" fill="none" stroke="#9ca3af" stroke-width="1.5"/>` +
      `<circle cx="${X(0)}" cy="${Y(0)}" r="4" fill="#16a34a"/>` +
      `<g id="${prefix}-body"><rect x="-12" y="-18" width="24" height="36" rx="4" ` +
      `fill="#1f2937"/><line x1="0" y1="0" x2="0" y2="-16" stroke="#f9fafb" stroke-width="2"/>` +
      `<line id="${prefix}-gimbal" x1="0" y1="0" x2="0" y2="-34" stroke="#f59e0b" ` +
      `stroke-width="3" stroke-linecap="round"/></g></svg>` +
      dialsSvg(prefix, p.outputs, 2, 408);
    div.style.width = "584px";
  }
  div.innerHTML = html;
  $("stage").appendChild(div);
}

function escapeText(s) {
  return s.replace(/[&<>"]/g, (c) => ({ "&": "&amp;", "<": "&lt;", ">": "&gt;", '"': "&quot;" })[c]);
}

// Draws part p at t ms and returns its state for seqc-state.
function drawPart(p, index, t) {
  const prefix = "p" + index;
  const state = {};
  if (p.kind === "servo") {
    const now = servoPositions(p, t);
    const byName = {};
    p.servos.forEach((s, i) => { byName[s.name] = i; });
    state.servos = {};
    for (const name of p.columns) state.servos[name] = round2(now[byName[name]]);
    if (p.arm) {
      const position = (name) => now[byName[name]];
      const arm = armPoints(p.arm, position);
      state.tip = arm.tip.map(round2);
      $(`${prefix}-links`).setAttribute("points",
        arm.plane.map(([r, z]) => `${sideX(r)},${sideY(z)}`).join(" "));
      $(`${prefix}-joints`).innerHTML = arm.plane.slice(0, 3).map(([r, z]) =>
        `<circle cx="${sideX(r)}" cy="${sideY(z)}" r="5" fill="#f9fafb" stroke="#1f2937" ` +
        `stroke-width="2"/>`).join("");
      const [tr, tz] = arm.plane[3];
      // The claw: two fingers from 40 mm before the tip, opening with the claw servo across its
      // limits (0 to 35 degrees each side).
      let open = 0.5;
      if (p.arm.claw && byName[p.arm.claw] !== undefined) {
        const s = p.servos[byName[p.arm.claw]];
        open = (now[byName[p.arm.claw]] - s.min) / Math.max(s.max - s.min, 1);
      }
      const spread = Math.min(Math.max(open, 0), 1) * 35 * Math.PI / 180;
      const br = tr - 40 * Math.sin(arm.hand), bz = tz - 40 * Math.cos(arm.hand);
      const finger = (side) => [br + 45 * Math.sin(arm.hand + side * spread),
                                bz + 45 * Math.cos(arm.hand + side * spread)];
      const [ar, az] = finger(1), [cr, cz] = finger(-1);
      $(`${prefix}-claw`).setAttribute("points", `${sideX(ar)},${sideY(az)} ${sideX(br)},` +
        `${sideY(bz)} ${sideX(cr)},${sideY(cz)}`);
      $(`${prefix}-tip`).setAttribute("cx", sideX(tr));
      $(`${prefix}-tip`).setAttribute("cy", sideY(tz));
      const plan = arm.plane.map(([r]) => [TOP.c + r * Math.cos(arm.base) * TOP.scale,
                                           TOP.c - r * Math.sin(arm.base) * TOP.scale]);
      $(`${prefix}-plan`).setAttribute("points", plan.map(([x, y]) => `${x},${y}`).join(" "));
      $(`${prefix}-plan-tip`).setAttribute("cx", plan[3][0]);
      $(`${prefix}-plan-tip`).setAttribute("cy", plan[3][1]);
    } else {
      p.columns.forEach((name, i) => {
        const s = p.servos[byName[name]];
        setDial(prefix, i, now[byName[name]], s.min, s.max);
      });
    }
  } else {
    const car = carState(p, t);
    state.servos = {};
    p.outputs.forEach((name, i) => {
      const v = car.values[name];
      if (v !== null) state.servos[name] = v;
      setDial(prefix, i, v, 500, 2500);
    });
    state.car = { x: round2(car.pose.x), y: round2(car.pose.y), heading: round2(car.pose.heading) };
    const X = 200 + (car.pose.x - p.view.mx) * p.view.scale;
    const Y = 200 - (car.pose.y - p.view.my) * p.view.scale;
    $(`${prefix}-body`).setAttribute("transform",
      `translate(${X},${Y}) rotate(${car.pose.heading})`);
    // The gimbal's pan turns it from straight ahead: 1500 us ahead, 500 and 2500 us a quarter
    // turn either way (nominal, like the path's scale).
    const pan = car.values.pan === null ? 1500 : car.values.pan;
    const a = (pan - 1500) / 1000 * 90 * Math.PI / 180;
    $(`${prefix}-gimbal`).setAttribute("x2", 34 * Math.sin(a));
    $(`${prefix}-gimbal`).setAttribute("y2", -34 * Math.cos(a));
  }
  return state;
}

// ---- the page: bars, loop, controls, the frame loop.
// Loops count bars; a tempo without a meter counts beats; no tempo, seconds.
let barsPart = null, bars = [];
function findBars() {
  barsPart = page.parts.find((p) => p.bars.length > 0) ||
    page.parts.find((p) => p.beats.length > 0);
  bars = !barsPart ? [] : barsPart.bars.length > 0 ? barsPart.bars : barsPart.beats;
  $("loop-unit").textContent = !barsPart ? "seconds from" : barsPart.bars.length > 0 ? "bars" : "beats";
}
findBars();
$("loop-to").value = bars.length > 0 ? Math.min(bars.length, 4) : Math.ceil(endMs / 1000);
$("loop-from").value = bars.length > 0 ? 1 : 0;

// [from, to] in ms when looping, else null: bars A to B (both included) or seconds.
function loopRange() {
  if (!$("loop").checked) return null;
  const a = Math.floor(+$("loop-from").value), b = Math.floor(+$("loop-to").value);
  let from, to;
  if (bars.length > 0) {
    from = bars[Math.min(Math.max(a, 1), bars.length) - 1];
    to = b < bars.length ? bars[Math.max(b, 1)] : endMs;
  } else {
    from = Math.max(a, 0) * 1000;
    to = Math.min(b * 1000, endMs);
  }
  return to > from ? [from, to] : null;
}

function barText(t) {
  if (bars.length === 0) return "";
  let i = 0;
  while (i + 1 < bars.length && bars[i + 1] <= t) ++i;
  const unit = barsPart.bars.length > 0 ? "bar" : "beat";
  return t >= bars[0] ? `, ${unit} ${i + 1}` : "";
}

page.parts.forEach(buildPart);

// The studio (live.js) calls this once it has replaced the data and the lanes: the robots are
// built afresh and the new lanes scrub; the clock, the loop's inputs and the speed are kept.
function rebuild() {
  findBars();
  $("stage").textContent = "";
  page.parts.forEach(buildPart);
  document.querySelectorAll(".lanes svg").forEach(scrubbable);
}

function draw(seconds) {
  const t = seconds * 1000;
  const shown = { t: Math.round(seconds * 1000) / 1000 };
  const states = page.parts.map((p, i) => drawPart(p, i, t));
  if (page.show) {
    shown.performers = {};
    page.parts.forEach((p, i) => { shown.performers[p.name] = states[i]; });
  } else {
    Object.assign(shown, states[0]);
  }
  $("seqc-state").textContent = JSON.stringify(shown);
  $("now").textContent = `${seconds.toFixed(2)} s${barText(t)}`;
  $("scrub").value = t;
  document.querySelectorAll(".playhead").forEach((line) => {
    const x = 150 + t / endMs * (1100 - 150 - 24);
    line.setAttribute("x1", x);
    line.setAttribute("x2", x);
  });
  $("play").textContent = timeSource.playing ? "pause" : "play";
}

function frame() {
  let t = clock();
  const range = loopRange();
  if (timeSource.playing && range && (t * 1000 >= range[1] || t * 1000 < range[0] - 1)) {
    seek(range[0] / 1000);
    t = clock();
  } else if (timeSource.playing && t >= endMs / 1000) {
    seek(endMs / 1000);
    pause();
    t = clock();
  }
  draw(t);
  if (timeSource.playing) requestAnimationFrame(frame);
}

function start() {
  if (!timeSource.playing) {
    play();
    requestAnimationFrame(frame);
  }
}
function toggle() {
  if (timeSource.playing) pause(); else start();
  draw(clock());
}
$("play").addEventListener("click", toggle);
document.addEventListener("keydown", (e) => {
  if (e.key === " " && e.target.tagName !== "INPUT" && e.target.tagName !== "SELECT") {
    e.preventDefault();
    toggle();
  }
});
$("speed").addEventListener("change", () => setRate(+$("speed").value));
$("scrub").addEventListener("input", () => { seek(+$("scrub").value / 1000); draw(clock()); });
// Scrubbing on the lanes and their ruler: x maps to time as the plot's axis does.
function scrubbable(svg) {
  const to = (e) => {
    const box = svg.getBoundingClientRect();
    const x = (e.clientX - box.left) * 1100 / box.width;
    seek((x - 150) / (1100 - 150 - 24) * endMs / 1000);
    draw(clock());
  };
  svg.addEventListener("pointerdown", (e) => {
    svg.setPointerCapture(e.pointerId);
    to(e);
  });
  svg.addEventListener("pointermove", (e) => { if (e.buttons & 1) to(e); });
}
document.querySelectorAll(".lanes svg").forEach(scrubbable);

// #t=SECONDS shows that instant, paused.
function fromHash() {
  const m = /(?:^#|&)t=([0-9.]+)/.exec(location.hash);
  if (!m) return false;
  pause();
  seek(parseFloat(m[1]));
  draw(clock());
  return true;
}
window.addEventListener("hashchange", fromHash);
if (!fromHash()) draw(0);
