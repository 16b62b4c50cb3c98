// The ray panel's derivation as selectable text, written from /trace.json: Lode's numbers in
// his names, one line each (the setup, every step's comparison, the hit), and the sentence for
// the part being stepped through. Numbers print as halfcast prints them (render/derivation.rs).

// A number with `d` decimals as Rust's `{:.d}` writes it (an exact tie rounds to even), 1e30
// for the huge values a zero ray component gives, and never "-0.00".
export function num(v, d = 2) {
  if (Math.abs(v) >= 1e6) {
    const [m, e] = v.toExponential(0).split('e');
    return `${m}e${Number(e)}`;
  }
  let s = v.toFixed(d);
  const twice = v * 2 * 10 ** d;
  if (Number.isInteger(twice) && Math.abs(twice) % 2 === 1) {
    const k = Math.trunc(Math.abs(v) * 10 ** d);
    s = (v < 0 ? '-' : '') + ((k % 2 === 0 ? k : k + 1) / 10 ** d).toFixed(d);
  }
  return s.startsWith('-') && /^[0.]+$/.test(s.slice(1)) ? s.slice(1) : s;
}

// Two sideDists printed so their order shows (more decimals while two would print them equal).
export function compared(a, b) {
  const sign = a < b ? '<' : a > b ? '>' : '=';
  let d = 2;
  while (sign !== '=' && d < 6 && num(a, d) === num(b, d)) d++;
  return [num(a, d), sign, num(b, d)];
}

const pair = (v) => `(${num(v[0])}, ${num(v[1])})`;
const cell = (c) => `(${c[0]},${c[1]})`;
const signed = (s) => (s < 0 ? '−1' : '+1');
const axis = (side) => side.toUpperCase();
const height = (z) => String(Math.round(z * 100) / 100);

// One line of text: parts are strings or [class, text] pairs.
function line(part, ...chunks) {
  const div = document.createElement('div');
  div.className = 'line';
  div.dataset.part = part;
  for (const c of chunks) {
    if (typeof c === 'string') div.append(c);
    else {
      const span = document.createElement('span');
      span.className = c[0];
      span.textContent = c[1];
      div.append(span);
    }
  }
  return div;
}

function setupLines(t) {
  const [w, x] = [t.size[0], t.column];
  const gap = (i) => {
    const n = 'XY'[i];
    const f = t.step[i] < 0 ? `(pos${n} − map${n})` : `(map${n} + 1 − pos${n})`;
    return line(0, ['name', `sideDist${n}`], ` = ${f}·deltaDist${n} = ${num(t.gap[i])}·${num(t.delta_dist[i])} = `,
      ['value', num(t.side_dist[i])]);
  };
  return [
    line(0, ['name', 'cameraX'], ` = 2·x/w − 1 = 2·${x}/${w} − 1 = `, ['value', num(t.camera_x)]),
    line(0, ['name', 'rayDir'], ` = dir + plane·cameraX = ${pair(t.dir)} + ${pair(t.plane)}·${num(t.camera_x)} = `,
      ['value', pair(t.ray_dir)]),
    line(0, ['name', 'deltaDist'], ` = |1/rayDir| = `, ['value', pair(t.delta_dist)]),
    line(0, ['name', 'pos'], ` ${pair(t.pos)} in map ${cell(t.start_cell)}, `, ['name', 'step'],
      ` = (${signed(t.step[0])}, ${signed(t.step[1])})`),
    gap(0),
    gap(1),
  ];
}

function faceLines(t, part, c) {
  if (!t.heights) return [];
  return t.heights.faces.filter((f) => f.cell[0] === c[0] && f.cell[1] === c[1]).map((f) =>
    line(part, ['face', `    ${f.kind}`], ` z ${height(f.z[0])}..${height(f.z[1])} rows ${f.rows[0]}..${f.rows[1]}`,
      ` window ${f.before[0]}..${f.before[1]} → ${f.after[0]}..${f.after[1]}`));
}

function stepLines(t, s) {
  const [a, sign, b] = compared(s.before[0], s.before[1]);
  const n = axis(s.side);
  const grown = s.side === 'x' ? s.after[0] : s.after[1];
  const delta = s.side === 'x' ? t.delta_dist[0] : t.delta_dist[1];
  return [
    line(s.index, `${String(s.index).padStart(3)} `, ['x', 'sideDistX'], ` ${a} ${sign} `, ['y', 'sideDistY'], ` ${b} → `,
      [s.side, `step ${s.side}`], `   map ${cell(s.cell)}  `, [s.side, `sideDist${n}`], ` += ${num(delta)} → ${num(grown)}`),
    ...faceLines(t, s.index, s.cell),
  ];
}

function hitLines(t) {
  const part = t.steps.length + 1;
  const h = t.hit;
  const n = axis(h.side);
  const face = h.face === 'panel' ? 'the door panel' : `${h.face} face, texture ${h.texture}`;
  const out = [line(part, ['name', 'hit'], ' ', ['hit', cell(h.cell)], ` ${h.what}, side ${h.side} (${face})`)];
  const p = t.perp;
  if (p.from === 'grid') {
    out.push(line(part, ['name', 'perp'], ` = sideDist${n} − deltaDist${n} = ${num(p.side_dist)} − ${num(p.delta_dist)} = `,
      ['value perp', num(p.value)]));
  } else {
    const i = h.side === 'x' ? 0 : 1;
    out.push(line(part, ['name', 'perp'], ` = (map${n}+0.5 − pos${n})/rayDir${n} = (${num(p.line)} − ${num(t.pos[i])})/${num(t.ray_dir[i])} = `,
      ['value perp', num(p.value)]));
  }
  const hs = t.heights;
  if (!hs) out.push(line(part, ['name', 'line'], ` = focal/perp = ${num(t.focal)}/${num(p.value)} = ${num(t.line_height)} px`));
  else if (hs.closing_dz === null) out.push(line(part, ['name', 'line'], ' none (floors closed it)'));
  else out.push(line(part, ['name', 'line'], ` = Δz·focal/perp = ${height(hs.closing_dz)}·${num(t.focal)}/${num(p.value)} = ${num(t.line_height)} px`));
  if (h.face === 'panel') out.push(line(part, ['name', 'wall_x'], ` (along the open panel) = ${num(t.wall_x)}`));
  else {
    const [pn, rn, i] = h.side === 'x' ? ['posY', 'rayDirY', 1] : ['posX', 'rayDirX', 0];
    out.push(line(part, ['name', 'wall_x'], ` = ${pn} + perp·${rn} = ${num(t.pos[i])} + ${num(p.value)}·${num(t.ray_dir[i])} = ${num(t.wall_along)} → `,
      ['value', num(t.wall_x)]));
  }
  out.push(line(part, ['name', 'texture x'], ` ${t.texture_x} of ${t.texture_width}`));
  if (hs) out.push(line(part, ['name', 'window closed'], ' ', ['hit', cell(hs.closed)], ` at ${num(hs.closed_at)}`));
  return out;
}

// Every line of the derivation, in order.
export function derivationLines(t) {
  return [...setupLines(t), ...t.steps.flatMap((s) => stepLines(t, s)), ...hitLines(t)];
}

// What the part `k` (0 the setup, 1..n a step, n+1 the hit) does, in a sentence.
export function explain(t, k) {
  const n = t.steps.length;
  if (k === 0) {
    return `The ray starts at ${pair(t.pos)} in map ${cell(t.start_cell)} with sideDistX ${num(t.side_dist[0])} and ` +
      `sideDistY ${num(t.side_dist[1])}: the ray lengths to the first x and y grid lines. Each step goes to the nearer one.`;
  }
  if (k > n) {
    return `Map ${cell(t.hit.cell)} is ${t.hit.what.startsWith('wall') ? 'a wall' : `a ${t.hit.what}`}: the ray stops after ${n} ` +
      `steps. perp = ${num(t.perp.value)}, measured from the camera plane, not the eye, so walls do not bulge.`;
  }
  const s = t.steps[k - 1];
  const [a, sign, b] = compared(s.before[0], s.before[1]);
  const n2 = axis(s.side);
  const line2 = s.side === 'x' ? 'an x line (a vertical grid line)' : 'a y line (a horizontal grid line)';
  const grown = s.side === 'x' ? s.after[0] : s.after[1];
  return `Step ${k}: sideDistX ${a} ${sign} sideDistY ${b}, so the ray crosses ${line2} first, at ray length ` +
    `${num(s.crossing)}, point ${pair(s.point)}, into map ${cell(s.cell)}; sideDist${n2} grows by deltaDist${n2} to ${num(grown)}.`;
}
