// The ray debugger's panel: one column's ray, drawn by the page from /trace.json (ray_figure.js)
// beside Lode's derivation as selectable text (ray_text.js), stepped through with buttons and
// keys, exported as the SVG and PNG `halfcast trace` writes. The game page mounts it when the
// player clicks a column (`mountRayPanel`); the address carries the ray as `trace` takes it, so
// `/ray?pos=…` (and, wired by main.js, `/?pos=…`) shows it again in any browser without playing.

import { drawFigure } from './ray_figure.js';
import { derivationLines, explain } from './ray_text.js';

// The address's keys that make a ray, in `halfcast trace`'s order.
const KEYS = ['pos', 'angle', 'column', 'size', 'fov', 'map'];
const NEEDED = ['pos', 'angle', 'column', 'size'];

// A query string from [key, value] pairs, commas left readable.
function queryOf(pairs) {
  return pairs.map(([k, v]) => `${k}=${encodeURIComponent(v).replace(/%2C/gi, ',')}`).join('&');
}

// The ray an address carries, as the trace routes' query, or null when it carries none.
export function rayFromAddress(location) {
  const q = new URLSearchParams(location.search);
  if (!NEEDED.every((k) => q.has(k))) return null;
  return queryOf(KEYS.filter((k) => q.has(k)).map((k) => [k, q.get(k)]));
}

// The same ray's query for another column of the view.
export function withColumn(query, column) {
  const q = new URLSearchParams(query);
  q.set('column', String(column));
  return queryOf(KEYS.filter((k) => q.has(k)).map((k) => [k, q.get(k)]));
}

// The trace routes' query for the server's `{"ray":{pos,angle,column,size,fov,map}}` message.
export function queryFromRay(r) {
  const pairs = [['pos', `${r.pos[0]},${r.pos[1]}`], ['angle', r.angle], ['column', r.column], ['size', `${r.size[0]}x${r.size[1]}`]];
  if (r.fov !== undefined && r.fov !== null) pairs.push(['fov', r.fov]);
  if (r.map) pairs.push(['map', r.map]);
  return queryOf(pairs.map(([k, v]) => [k, String(v)]));
}

function make(parent, tag, attrs = {}, text) {
  const e = document.createElement(tag);
  for (const [k, v] of Object.entries(attrs)) e.setAttribute(k, v);
  if (text !== undefined) e.textContent = text;
  parent.append(e);
  return e;
}

function skeleton(container) {
  const root = make(container, 'section', { class: 'ray-panel', 'aria-label': 'ray debugger' });
  const bar = make(root, 'header', { class: 'ray-bar' });
  const title = make(bar, 'h2', { class: 'ray-title' }, 'ray');
  const nav = make(bar, 'span', { class: 'ray-nav' });
  const button = (cls, label, text) => make(nav, 'button', { type: 'button', class: cls, title: label, 'aria-label': label }, text);
  const first = button('ray-first', 'the start (Home)', '« start');
  const prev = button('ray-prev', 'previous step (←)', '◀ prev');
  const part = make(nav, 'span', { class: 'ray-part' });
  const next = button('ray-next', 'next step (→)', 'next ▶');
  const last = button('ray-last', 'the hit (End)', 'hit »');
  const out = make(bar, 'span', { class: 'ray-out' });
  const svgLink = make(out, 'a', { class: 'ray-export-svg', download: 'ray.svg' }, 'SVG');
  const pngLink = make(out, 'a', { class: 'ray-export-png', download: 'ray.png' }, 'PNG');
  const link = make(out, 'a', { class: 'ray-link', title: 'this ray as a link' }, 'link');
  const close = make(bar, 'button', { type: 'button', class: 'ray-close', title: 'leave the debugger (Esc)', 'aria-label': 'close' }, '✕');
  const now = make(root, 'p', { class: 'ray-now' });
  const error = make(root, 'p', { class: 'ray-error' });
  const body = make(root, 'div', { class: 'ray-body' });
  const fig = make(body, 'figure', { class: 'ray-figure' });
  const svg = document.createElementNS('http://www.w3.org/2000/svg', 'svg');
  svg.setAttribute('class', 'ray-svg');
  fig.append(svg);
  const hover = make(fig, 'figcaption', { class: 'ray-hover' });
  const text = make(body, 'div', { class: 'ray-text', tabindex: '0' });
  return { root, title, first, prev, part, next, last, svgLink, pngLink, link, close, now, error, svg, hover, text };
}

// Mounts the ray panel for `query` (the trace routes' query) in `container`. `onClose()` runs
// when the player leaves it; `onShow(address)` whenever a ray is shown (the address to put in
// the page's location). Returns { previewColumn(c), show(query), close(), element }.
export function mountRayPanel(container, { query, onClose = () => {}, onShow = () => {} }) {
  const ui = skeleton(container);
  const state = { query, data: null, shown: null, k: 0, seq: 0, preview: null };
  const parts = () => (state.shown ? state.shown.steps.length + 2 : 1);

  function render() {
    const t = state.shown;
    if (!t) return;
    const n = t.steps.length;
    drawFigure(ui.svg, t, state.k, (name) => { ui.hover.textContent = name ?? ''; });
    ui.text.replaceChildren(...derivationLines(t));
    for (const l of ui.text.querySelectorAll('.line')) {
      l.classList.toggle('current', Number(l.dataset.part) === state.k);
      l.classList.toggle('later', Number(l.dataset.part) > state.k && state.k <= n);
    }
    ui.now.textContent = explain(t, state.k);
    ui.part.textContent = state.k === 0 ? 'setup' : state.k > n ? `hit (${n} steps)` : `step ${state.k} of ${n}`;
    ui.prev.disabled = state.k === 0;
    ui.first.disabled = state.k === 0;
    ui.next.disabled = state.k > n;
    ui.last.disabled = state.k > n;
    const preview = state.preview === null ? '' : ' (preview: click to keep)';
    ui.title.textContent = `ray of column ${t.column} of ${t.size[0]}${preview}`;
    ui.root.classList.toggle('previewing', state.preview !== null);
    ui.svgLink.href = `/trace.svg?${t.address}`;
    ui.pngLink.href = `/trace.png?${t.address}`;
    ui.svgLink.download = `ray-${t.column}.svg`;
    ui.pngLink.download = `ray-${t.column}.png`;
    ui.link.href = `/ray?${t.address}`;
    ui.hover.textContent = '';
  }

  async function load(q, preview) {
    const seq = ++state.seq;
    let res;
    let body;
    try {
      res = await fetch(`/trace.json?${q}`);
      body = res.ok ? await res.json() : await res.text();
    } catch (e) {
      body = `the server did not answer: ${e.message}`;
    }
    if (seq !== state.seq) return; // a later ray was asked for meanwhile
    if (!res || !res.ok) {
      ui.error.textContent = String(body).trim();
      return;
    }
    ui.error.textContent = '';
    state.shown = body;
    state.preview = preview;
    if (preview === null) {
      state.data = body;
      state.query = q;
      onShow(body.address);
    }
    state.k = body.steps.length + 1;
    render();
  }

  function go(k) {
    state.k = Math.max(0, Math.min(parts() - 1, k));
    render();
  }

  function close() {
    if (!ui.root.isConnected) return;
    document.removeEventListener('keydown', onKey, true);
    ui.root.remove();
    onClose();
  }

  function onKey(e) {
    if (e.ctrlKey || e.altKey || e.metaKey) return;
    const to = { ArrowRight: state.k + 1, ArrowDown: state.k + 1, n: state.k + 1, ArrowLeft: state.k - 1,
      ArrowUp: state.k - 1, p: state.k - 1, Home: 0, End: parts() - 1 }[e.key];
    if (to !== undefined) go(to);
    else if (e.key === 'Escape') close();
    else return;
    e.preventDefault();
    e.stopPropagation();
  }

  ui.first.addEventListener('click', () => go(0));
  ui.prev.addEventListener('click', () => go(state.k - 1));
  ui.next.addEventListener('click', () => go(state.k + 1));
  ui.last.addEventListener('click', () => go(parts() - 1));
  ui.close.addEventListener('click', close);
  document.addEventListener('keydown', onKey, true);
  load(query, null);

  return {
    element: ui.root,
    // Shows column `c`'s ray of the same view for a moment (the mouse over the view); null,
    // or the debugged column, goes back to the debugged ray.
    previewColumn(c) {
      if (!state.data) return;
      if (c === null || c === state.data.column) {
        if (state.preview === null) return;
        state.seq++;
        ui.error.textContent = '';
        state.shown = state.data;
        state.preview = null;
        state.k = state.data.steps.length + 1;
        render();
      } else if (c !== state.preview) {
        load(withColumn(state.query, c), c);
      }
    },
    // Debugs another ray (a new click, or the server's {"ray":…} answer).
    show(q) { load(q, null); },
    close,
  };
}

// `/ray?…`: the panel alone, for a link opened in any browser.
function standalone() {
  const main = document.getElementById('ray');
  const query = rayFromAddress(location);
  if (!query) {
    make(main, 'p', { class: 'ray-error' },
      'This page shows one ray: open it as /ray?pos=X,Y&angle=A&column=C&size=COLSxROWS (as halfcast trace takes them).');
    return;
  }
  // The panel, for the console (and the browser test): previewColumn(c), show(query).
  window.halfcastRay = mountRayPanel(main, {
    query,
    onShow: (address) => history.replaceState(null, '', `${location.pathname}?${address}`),
    onClose: () => { location.href = '/'; },
  });
}

if (document.body && document.body.classList.contains('ray-page')) standalone();
