// The ray panel's figure, drawn by the page from /trace.json as SVG: the cells around the ray
// (walls, doors, the cells visited, the hit cell; on maps with heights each cell's
// floor..ceiling), the camera with dir and the plane, the ray, every x- and y-crossing numbered
// with its sideDist, the hit face and perp. The region and the cell size follow `halfcast
// trace`'s figure (output/figure/frame.rs), so the two drawings of one ray place everything
// alike. Part `k` of the stepping (0 the setup, 1..n a step, n+1 the hit) is highlighted:
// later crossings and cells are faint.

import { num } from './ray_text.js';

const NS = 'http://www.w3.org/2000/svg';
// The figure's colours (output/figure/palette.rs).
const C = {
  paper: '#fafaf6', grid: '#c4c6ce', wall: '#545864', visited: '#ffeca8', later: '#fff8df',
  hit: '#f6b0a8', x: '#de7010', y: '#1c68d6', ray: '#7630a0', camera: '#18181c', plane: '#228c48',
  perp: '#d42028', text: '#1e1e24',
};
const ORIGIN = [40, 30];

function el(parent, name, attrs, text) {
  const e = document.createElementNS(NS, name);
  for (const [k, v] of Object.entries(attrs)) e.setAttribute(k, v);
  if (text !== undefined) e.textContent = text;
  parent.append(e);
  return e;
}

// Where map point p is drawn, in the figure's pixels.
function placer(t, cell) {
  return (p) => [ORIGIN[0] + (p[0] - t.grid.x0) * cell, ORIGIN[1] + (p[1] - t.grid.y0) * cell];
}

// trace's cell size: smaller as the region grows, 36 to 72 pixels.
export function cellSize(t) {
  const span = Math.max(t.grid.width, t.grid.height);
  return Math.floor(Math.min(72, Math.max(36, 720 / span)));
}

const add = (a, b, s = 1) => [a[0] + b[0] * s, a[1] + b[1] * s];
const unit = (v) => { const l = Math.hypot(v[0], v[1]) || 1; return [v[0] / l, v[1] / l]; };

function cells(g, t, k, at, cell) {
  const order = new Map([[`${t.start_cell}`, 0]]);
  t.steps.forEach((s) => order.set(`${s.cell}`, s.index));
  const n = t.steps.length;
  for (let j = 0; j < t.grid.height; j++) {
    for (let i = 0; i < t.grid.width; i++) {
      const c = [t.grid.x0 + i, t.grid.y0 + j];
      const what = t.grid.rows[j][i];
      const [x, y] = at(c);
      const step = order.get(`${c}`);
      const isHit = c[0] === t.hit.cell[0] && c[1] === t.hit.cell[1];
      let fill = null;
      if (isHit) fill = k >= n ? C.hit : C.later;
      else if (what === '#' || what === ' ') fill = C.wall;
      else if (step !== undefined) fill = step <= k ? C.visited : C.later;
      if (fill) {
        const r = el(g, 'rect', { x, y, width: cell, height: cell, fill });
        if (isHit) r.setAttribute('class', 'hit-cell');
        if (step !== undefined) r.dataset.cell = `${c[0]},${c[1]}`;
      }
      // On a map with heights, each open cell's floor..ceiling where it is not 0..1.
      const span = t.grid.spans && t.grid.spans[j][i];
      if (span && (span[0] !== 0 || span[1] !== 1)) {
        el(g, 'text', { x: x + cell - 3, y: y + cell - 4, 'text-anchor': 'end', fill: '#6a6e7a', class: 'tiny' },
          `${+span[0].toFixed(2)}..${+span[1].toFixed(2)}`);
      }
      if (what === 'D') {
        el(g, 'rect', { x: x + cell * 0.2, y: y + cell * 0.2, width: cell * 0.6, height: cell * 0.6,
          fill: 'none', stroke: C.wall, 'stroke-dasharray': '4 3' });
      }
    }
  }
}

function gridLines(g, t, at, cell) {
  const [w, h] = [t.grid.width * cell, t.grid.height * cell];
  for (let i = 0; i <= t.grid.width; i++) {
    const [x, y] = at([t.grid.x0 + i, t.grid.y0]);
    el(g, 'line', { x1: x, y1: y, x2: x, y2: y + h, stroke: C.grid });
    if (i < t.grid.width) el(g, 'text', { x: x + cell / 2, y: y - 8, 'text-anchor': 'middle', fill: C.text, class: 'small' }, t.grid.x0 + i);
  }
  for (let j = 0; j <= t.grid.height; j++) {
    const [x, y] = at([t.grid.x0, t.grid.y0 + j]);
    el(g, 'line', { x1: x, y1: y, x2: x + w, y2: y, stroke: C.grid });
    if (j < t.grid.height) el(g, 'text', { x: x - 8, y: y + cell / 2 + 4, 'text-anchor': 'end', fill: C.text, class: 'small' }, t.grid.y0 + j);
  }
}

// The hit face's two ends: a door's panel line, or the grid line crossed into the hit cell.
function hitFace(t) {
  const [hx, hy] = t.hit.cell;
  if (t.perp.from === 'door') {
    const l = t.perp.line;
    return t.hit.side === 'x' ? [[l, hy], [l, hy + 1]] : [[hx, l], [hx + 1, l]];
  }
  const gx = t.step[0] > 0 ? hx : hx + 1;
  const gy = t.step[1] > 0 ? hy : hy + 1;
  return t.hit.side === 'x' ? [[gx, hy], [gx, hy + 1]] : [[hx, gy], [hx + 1, gy]];
}

function line(g, a, b, stroke, width, dash) {
  const e = el(g, 'line', { x1: a[0], y1: a[1], x2: b[0], y2: b[1], stroke, 'stroke-width': width });
  if (dash) e.setAttribute('stroke-dasharray', dash);
  return e;
}

function crossings(g, t, k, at, onHover) {
  const marks = cameraMarks(t, at);
  const normal = unit([-t.ray_dir[1], t.ray_dir[0]]);
  const seen = { x: 0, y: 0 };
  for (const s of t.steps) {
    seen[s.side]++;
    const p = at(s.point);
    const name = s.side === 'x' ? 'sideDistX' : 'sideDistY';
    const cls = `crossing ${s.side}${s.index === k ? ' current' : ''}${s.index > k ? ' later' : ''}`;
    const grp = el(g, 'g', { class: cls });
    Object.assign(grp.dataset, { step: s.index, name, sideDist: s.crossing, x: s.point[0], y: s.point[1] });
    el(grp, 'circle', { cx: p[0], cy: p[1], r: s.index === k ? 8 : 5, fill: C[s.side],
      stroke: s.index === k ? C.camera : C.paper, 'stroke-width': s.index === k ? 2.5 : 1.5 });
    // x labels on one side of the ray, y on the other; close crossings alternate rows; a label
    // over the camera's marks moves further out.
    const sign = s.side === 'x' ? 1 : -1;
    const far = seen[s.side] % 2 === 0 ? 12 : 0;
    let out = sign * (18 + far);
    for (let push = 0; push < 4 && marks.some((m) => Math.hypot(m[0] - (p[0] + normal[0] * out), m[1] - (p[1] + normal[1] * out)) < 16); push++) {
      out += sign * 14;
    }
    const lp = add(p, normal, out);
    const anchor = normal[0] * out > 3 ? 'start' : normal[0] * out < -3 ? 'end' : 'middle';
    el(grp, 'text', { x: lp[0], y: lp[1] + 4, 'text-anchor': anchor, fill: C[s.side], class: 'label' },
      `${s.index}: ${num(s.crossing)}`);
    const title = `${s.side}-crossing ${s.index}: ${name} = ${num(s.crossing)} at (${num(s.point[0])}, ${num(s.point[1])}), into map (${s.cell})`;
    el(grp, 'title', {}, title);
    grp.addEventListener('mouseenter', () => onHover(title));
    grp.addEventListener('mouseleave', () => onHover(null));
  }
}

// Points along the eye's dir arrow and the plane, which labels keep clear of.
function cameraMarks(t, at) {
  const pts = [];
  const seg = (a, b) => { for (let i = 0; i <= 12; i++) pts.push(at(add(a, [b[0] - a[0], b[1] - a[1]], i / 12))); };
  seg(t.pos, add(t.pos, t.dir));
  seg(add(add(t.pos, t.dir), t.plane, -1), add(add(t.pos, t.dir), t.plane));
  return pts;
}

function camera(g, t, at) {
  // The plane through the eye, where perp is measured from.
  const pu = unit(t.plane);
  const reach = Math.abs(t.camera_x * t.perp.value) * Math.hypot(t.plane[0], t.plane[1]) + 1.5;
  line(g, at(add(t.pos, pu, -reach)), at(add(t.pos, pu, reach)), C.plane, 1, '5 4').setAttribute('clip-path', 'url(#ray-grid)');
  const pos = t.pos;
  line(g, at(add(add(pos, t.dir), t.plane, -1)), at(add(add(pos, t.dir), t.plane)), C.plane, 3);
  const pe = at(add(add(pos, t.dir), t.plane));
  el(g, 'text', { x: pe[0] + 6, y: pe[1] - 6, fill: C.plane, class: 'label' }, 'plane');
  const [a, b] = [at(pos), at(add(pos, t.dir))];
  line(g, a, b, C.camera, 2.5);
  const d = unit([b[0] - a[0], b[1] - a[1]]);
  const head = (s) => [b[0] - d[0] * 10 + s * d[1] * 5, b[1] - d[1] * 10 - s * d[0] * 5];
  el(g, 'polygon', { points: [b, head(1), head(-1)].map((q) => q.join(',')).join(' '), fill: C.camera });
  const lab = at(add(add(pos, t.dir, 0.45), unit(t.plane), -0.45));
  el(g, 'text', { x: lab[0], y: lab[1] + 5, 'text-anchor': 'middle', fill: C.camera, class: 'label' }, 'dir');
  el(g, 'circle', { cx: a[0], cy: a[1], r: 5, fill: C.camera, class: 'eye' });
}

// Draws ray data `t` into `svg` with part `k` highlighted; `onHover(text|null)` names crossings.
export function drawFigure(svg, t, k, onHover = () => {}) {
  const cell = cellSize(t);
  const at = placer(t, cell);
  const [w, h] = [ORIGIN[0] + t.grid.width * cell + 20, ORIGIN[1] + t.grid.height * cell + 20];
  svg.replaceChildren();
  svg.setAttribute('viewBox', `0 0 ${w} ${h}`);
  svg.setAttribute('width', w);
  svg.setAttribute('height', h);
  el(svg, 'rect', { width: w, height: h, fill: C.paper });
  const clip = el(el(svg, 'clipPath', { id: 'ray-grid' }), 'rect', {});
  const [gx, gy] = at([t.grid.x0, t.grid.y0]);
  Object.entries({ x: gx, y: gy, width: t.grid.width * cell, height: t.grid.height * cell })
    .forEach(([k2, v]) => clip.setAttribute(k2, v));
  const n = t.steps.length;
  cells(svg, t, k, at, cell);
  gridLines(svg, t, at, cell);
  const [fa, fb] = hitFace(t);
  const face = line(svg, at(fa), at(fb), C.perp, 4);
  face.setAttribute('class', 'hit-face');
  if (k < n) face.setAttribute('opacity', 0.3);
  const hit = t.hit.point;
  // The ray: faint to the hit, solid as far as the part shown.
  line(svg, at(t.pos), at(hit), C.ray, 2).setAttribute('opacity', k > n ? 1 : 0.3);
  const reach = k === 0 ? null : k > n ? hit : t.steps[k - 1].point;
  if (reach) line(svg, at(t.pos), at(reach), C.ray, 2.5);
  const eyeDot = at(add(t.pos, t.ray_dir));
  el(svg, 'circle', { cx: eyeDot[0], cy: eyeDot[1], r: 3.5, fill: C.ray });
  if (k >= n) {
    const foot = add(t.pos, t.plane, t.camera_x * t.perp.value);
    line(svg, at(foot), at(hit), C.perp, 2, '6 4');
    const mid = at(add(add(foot, [hit[0] - foot[0], hit[1] - foot[1]], 0.5), unit([-t.dir[1], t.dir[0]]), 0.3));
    el(svg, 'text', { x: mid[0], y: mid[1] + 4, 'text-anchor': 'middle', fill: C.perp, class: 'label perp' },
      `perp ${num(t.perp.value)}`).dataset.perp = t.perp.value;
  }
  crossings(svg, t, k, at, onHover);
  camera(svg, t, at);
  return { width: w, height: h, cell };
}
