// The player of kinetology.viewer, inlined into every page it writes (no network, no library).
// `script` is this script's element, `id` the player's: the player is the script's parent (the
// same player shown twice in a notebook has its id twice), or found by id where a notebook runs
// the script detached from the page. The data is the JSON script inside the player. The page's
// state is readable by a test or a user: root.dataset.tick, each canvas's dataset.frame,
// root.viewer.
"use strict";
const parent = script ? script.parentElement : null;
const root = parent && parent.classList.contains("kinetology-view") ? parent
  : document.getElementById(id);
const data = JSON.parse(root.querySelector("script.data").textContent);
const slider = root.querySelector("input.time");
const button = root.querySelector("button.play");
const clock = root.querySelector("span.clock");
const holder = root.querySelector("div.panels");
const WIDTH = Math.max(200, Math.min(420, Math.floor((860 - 12 * (data.panels.length - 1)) / data.panels.length)));
const HEIGHT = 420;
let yaw = data.yaw * Math.PI / 180;
const pitch = data.pitch * Math.PI / 180;

// positions are integer differences from the frame before, in units of the panel's quantum
const panels = data.panels.map(function (p) {
  const n = p.joints.length, pos = new Float32Array(p.pos.length);
  for (let i = 0; i < p.pos.length; i++) {
    pos[i] = (i < 3 * n ? p.pos[i] : pos[i - 3 * n] + p.pos[i]);
  }
  const canvas = document.createElement("canvas");
  canvas.width = WIDTH;
  canvas.height = HEIGHT;
  canvas.title = p.label;
  canvas.style.border = "1px solid #ccc";
  canvas.style.cursor = "grab";
  const box = document.createElement("figure");
  box.style.margin = "0";
  const caption = document.createElement("figcaption");
  caption.textContent = p.label;
  caption.style.textAlign = "center";
  box.appendChild(canvas);
  box.appendChild(caption);
  holder.appendChild(box);
  // the whole motion fits at any yaw: a circle of `radius` around the centre, `height` tall
  const tall = p.height * Math.cos(pitch) + 2 * p.radius * Math.sin(pitch);
  const scale = 0.9 * Math.min(WIDTH / (2 * p.radius), (HEIGHT - 30) / tall);
  const base = HEIGHT - 0.05 * HEIGHT - scale * p.radius * Math.sin(pitch);
  const anchors = [];
  for (let f = 0; f < p.frames; f++) {
    let x = 0, z = 0;
    if (p.follow) {
      let count = 0;
      for (let j = 0; j < n; j++) {
        if (!p.body[j]) continue;
        x += pos[3 * (f * n + j)];
        z += pos[3 * (f * n + j) + 2];
        count++;
      }
      x /= count;
      z /= count;
    }
    anchors.push([x, z]);
  }
  return {p: p, n: n, pos: pos, anchors: anchors, canvas: canvas, ctx: canvas.getContext("2d"),
          scale: scale, base: base};
});

function frameOf(q, tick) {
  return Math.min(Math.floor(tick * q.p.rate / data.rate + 1e-9), q.p.frames - 1);
}

// the floor point the camera looks at: below the mean of the joints (following) or the middle
// of the path (0, 0), as Panel._anchors
function anchor(q, f) {
  return q.anchors[f];
}

// a point (x, y, z) seen from the camera at floor point `a`, as kinetology.viewer.Panel.pose
function screen(q, a, x, y, z) {
  x -= a[0];
  z -= a[1];
  const across = x * Math.cos(yaw) - z * Math.sin(yaw);
  const depth = x * Math.sin(yaw) + z * Math.cos(yaw);
  const up = y * Math.cos(pitch) + depth * Math.sin(pitch);
  return [WIDTH / 2 + q.scale * across, q.base - q.scale * up];
}

function project(q, f, j) {
  const i = 3 * (f * q.n + j);
  return screen(q, anchor(q, f), q.pos[i], q.pos[i + 1], q.pos[i + 2]);
}

// lines fixed on the floor, every half radius, around the camera's point: a body that
// travels passes over them (as Panel.floor draws them in a GIF)
function drawFloor(q, f) {
  const ctx = q.ctx, r = q.p.radius, s = r / 2, a = anchor(q, f);
  ctx.strokeStyle = "#e4e4e4";
  ctx.lineWidth = 1;
  for (let axis = 0; axis < 2; axis++) {
    const first = Math.ceil((a[axis] - r) / s);
    for (let k = first; k < first + 5; k++) {
      const c = k * s, lo = a[1 - axis] - r, hi = a[1 - axis] + r;
      const p0 = axis === 0 ? screen(q, a, c, 0, lo) : screen(q, a, lo, 0, c);
      const p1 = axis === 0 ? screen(q, a, c, 0, hi) : screen(q, a, hi, 0, c);
      ctx.beginPath();
      ctx.moveTo(p0[0], p0[1]);
      ctx.lineTo(p1[0], p1[1]);
      ctx.stroke();
    }
  }
}

function draw(q, tick) {
  const f = frameOf(q, tick), ctx = q.ctx, p = q.p;
  ctx.fillStyle = "#ffffff";
  ctx.fillRect(0, 0, WIDTH, HEIGHT);
  drawFloor(q, f);
  const xy = [];
  for (let j = 0; j < q.n; j++) xy.push(project(q, f, j));
  ctx.strokeStyle = "#444444";
  ctx.lineWidth = 3;
  ctx.lineCap = "round";
  for (let j = 0; j < q.n; j++) {
    const parent = p.parents[j];
    if (!p.bones[j]) continue;  // a root's translation, not a bone
    ctx.beginPath();
    ctx.moveTo(xy[parent][0], xy[parent][1]);
    ctx.lineTo(xy[j][0], xy[j][1]);
    ctx.stroke();
  }
  for (let j = 0; j < q.n; j++) {
    if (!p.body[j]) continue;
    if (!p.joints[j].endsWith(".end") || p.actuators[j]) {
      const state = p.states[j][f];
      ctx.fillStyle = data.colours[state] || data.colours["-"];
      ctx.beginPath();
      ctx.arc(xy[j][0], xy[j][1], state === "-" ? 3 : 5, 0, 2 * Math.PI);
      ctx.fill();
    }
    if (p.actuators[j]) {
      ctx.strokeStyle = "#000000";
      ctx.lineWidth = 2;
      ctx.beginPath();
      ctx.arc(xy[j][0], xy[j][1], 9, 0, 2 * Math.PI);
      ctx.stroke();
    }
  }
  ctx.fillStyle = "#333333";
  ctx.font = "12px sans-serif";
  ctx.fillText((f / p.rate).toFixed(2) + " s", 6, 16);
  q.canvas.dataset.frame = String(f);
}

let tick = 0, playing = false, last = null;

function show(t) {
  tick = Math.max(0, Math.min(data.ticks - 1, t));
  slider.value = String(Math.floor(tick));
  clock.textContent = (Math.floor(tick) / data.rate).toFixed(2) + " s";
  for (const q of panels) draw(q, Math.floor(tick));
  root.dataset.tick = String(Math.floor(tick));
}

function step(now) {
  if (!playing) return;
  if (last !== null) {
    let next = tick + (now - last) / 1000 * data.rate;
    if (next >= data.ticks) next = 0;  // loop
    show(next);
  }
  last = now;
  requestAnimationFrame(step);
}

function play(on) {
  playing = on;
  button.textContent = on ? "Pause" : "Play";
  root.dataset.playing = on ? "yes" : "no";
  last = null;
  if (on) requestAnimationFrame(step);
}

slider.addEventListener("input", function () { play(false); show(Number(slider.value)); });
button.addEventListener("click", function () { play(!playing); });
for (const q of panels) {
  let dragging = null;
  q.canvas.addEventListener("pointerdown", function (e) { dragging = e.clientX; });
  window.addEventListener("pointerup", function () { dragging = null; });
  q.canvas.addEventListener("pointermove", function (e) {
    if (dragging === null) return;
    yaw += (e.clientX - dragging) * 0.01;
    dragging = e.clientX;
    show(tick);
  });
}
root.viewer = {show: show, play: play, tick: function () { return Math.floor(tick); },
               frame: function (i) { return frameOf(panels[i], Math.floor(tick)); }};
root.dataset.playing = "no";
show(0);
