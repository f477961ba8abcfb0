// grassbench report.html: builds the page from the JSON in #grassbench-data. Plain
// JavaScript, no network. Data is only ever inserted with textContent, setAttribute or
// properties, never as markup.
(function () {
  'use strict';

  // Errors are collected for ?selftest=1, which writes them into the DOM.
  const errors = [];
  const consoleError = console.error.bind(console);
  console.error = function (...args) {
    errors.push('console.error: ' + args.map(String).join(' '));
    consoleError(...args);
  };
  window.addEventListener('error', (e) => {
    const t = e.target;
    if (t && t !== window && t.tagName) {
      errors.push('failed to load ' + t.tagName.toLowerCase() + ' ' + (t.getAttribute('src') || ''));
    } else {
      errors.push('error: ' + e.message + ' at ' + e.filename + ':' + e.lineno);
    }
  }, true);
  window.addEventListener('unhandledrejection', (e) => errors.push('unhandled rejection: ' + e.reason));

  const SVGNS = 'http://www.w3.org/2000/svg';
  const data = JSON.parse(document.getElementById('grassbench-data').textContent);
  const main = document.getElementById('main');
  const tooltip = document.getElementById('tooltip');
  const viewers = [];
  let activeViewer = null;

  // An element with attributes (`text` sets textContent, `class` the class) and children
  // (nodes or strings, which become text nodes).
  function el(tag, attrs, ...children) {
    const e = document.createElement(tag);
    for (const [k, v] of Object.entries(attrs || {})) {
      if (v === undefined || v === null) continue;
      if (k === 'text') e.textContent = String(v);
      else if (k === 'class') e.className = v;
      else e.setAttribute(k, String(v));
    }
    for (const c of children) if (c !== null && c !== undefined) e.append(c);
    return e;
  }
  function svgEl(tag, attrs) {
    const e = document.createElementNS(SVGNS, tag);
    for (const [k, v] of Object.entries(attrs || {})) {
      if (k === 'text') e.textContent = String(v);
      else e.setAttribute(k, String(v));
    }
    return e;
  }
  function num(text) {
    if (text === '' || text === null || text === undefined) return null;
    const v = Number(text);
    return Number.isFinite(v) ? v : null;
  }
  function fmt(v) {
    if (v === null || v === undefined) return '–';
    const a = Math.abs(v);
    if (a === 0) return '0';
    if (Number.isInteger(v)) return String(v);
    if (a >= 1000) return v.toFixed(0);
    if (a >= 100) return v.toFixed(1);
    if (a >= 1) return v.toFixed(2);
    return v.toPrecision(3);
  }
  function anchor(name) {
    return 'scene-' + Array.from(name).map((c) => (/[A-Za-z0-9_-]/.test(c) ? c : '-')).join('');
  }
  function colorOf(technique) {
    return data.colors[technique] || '#7f7f7f';
  }

  // ---------------------------------------------------------------- image viewer
  function Viewer(scene) {
    this.scene = scene;
    this.images = scene.images;
    const ref = this.images.findIndex((i) => i.technique === 'reference');
    this.a = ref >= 0 ? ref : 0;
    const other = this.images.findIndex((i, k) => k !== this.a && i.technique !== 'reference' && i.technique !== 'none');
    this.b = other >= 0 ? other : Math.min(1, this.images.length - 1);
    this.mode = 'flip';
    this.showing = 'a';
    this.zoom = 1;
    this.x = 0;
    this.y = 0;
    this.swipe = 50;
    this.heat = false;
    this.heatOpacity = 0.85;
    this.aspect = null;
    this.build();
  }

  Viewer.prototype.entryA = function () { return this.images[this.a]; };
  Viewer.prototype.entryB = function () { return this.images[this.b]; };

  Viewer.prototype.heatmap = function () {
    const a = this.entryA(), b = this.entryB();
    if (!a || !b) return null;
    return this.scene.heatmaps.find((h) => (h.a === a.id && h.b === b.id) || (h.a === b.id && h.b === a.id)) || null;
  };

  Viewer.prototype.build = function () {
    const v = this;
    v.root = el('div', { class: 'viewer', tabindex: '0' });
    v.root.dataset.showing = v.showing;
    v.root.addEventListener('pointerdown', () => v.activate());
    v.root.addEventListener('focus', () => v.activate());
    const options = (sel, chosen) => {
      v.images.forEach((img, k) => {
        const o = el('option', { value: String(k), text: img.label });
        if (k === chosen) o.selected = true;
        sel.append(o);
      });
    };
    v.selA = el('select', { 'aria-label': 'image A' });
    options(v.selA, v.a);
    v.selB = el('select', { 'aria-label': 'image B' });
    options(v.selB, v.b);
    v.selA.addEventListener('change', () => v.setPair(Number(v.selA.value), v.b));
    v.selB.addEventListener('change', () => v.setPair(v.a, Number(v.selB.value)));
    v.modeButtons = {};
    const modes = el('span', { class: 'modes' });
    for (const [mode, name] of [['flip', 'flip'], ['swipe', 'swipe'], ['side', 'side by side']]) {
      const b = el('button', { type: 'button', text: name });
      b.addEventListener('click', () => v.setMode(mode));
      v.modeButtons[mode] = b;
      modes.append(b);
    }
    const swap = el('button', { type: 'button', text: 'swap A/B' });
    swap.addEventListener('click', () => v.setPair(v.b, v.a));
    v.heatBox = el('input', { type: 'checkbox' });
    v.heatBox.addEventListener('change', () => { v.heat = v.heatBox.checked; v.apply(); });
    v.heatLabel = el('label', {}, v.heatBox, 'FLIP heat map');
    v.heatRange = el('input', { type: 'range', min: '0', max: '100', value: String(v.heatOpacity * 100), 'aria-label': 'heat map opacity' });
    v.heatRange.addEventListener('input', () => { v.heatOpacity = Number(v.heatRange.value) / 100; v.apply(); });
    v.swipeRange = el('input', { type: 'range', min: '0', max: '100', value: String(v.swipe), 'aria-label': 'swipe position' });
    v.swipeRange.addEventListener('input', () => { v.swipe = Number(v.swipeRange.value); v.apply(); });
    v.swipeLabel = el('label', {}, 'swipe', v.swipeRange);
    const reset = el('button', { type: 'button', text: 'fit' });
    reset.addEventListener('click', () => v.resetZoom());
    v.root.append(
      el('div', { class: 'controls' },
        el('label', {}, 'A', v.selA), el('label', {}, 'B', v.selB), swap),
      el('div', { class: 'controls' }, modes, v.swipeLabel, v.heatLabel, v.heatRange, reset));
    v.stage = el('div', { class: 'stage' });
    v.root.append(v.stage);
    v.colorbar = el('div', { class: 'colorbar' }, 'FLIP error 0', el('span', { class: 'bar' }), '1 (magma)');
    v.heatNote = el('div', { class: 'heat-note' });
    v.statusLeft = el('span');
    const help = el('span', {}, el('kbd', { text: 'f' }), ' flip A/B · ', el('kbd', { text: '1' }), el('kbd', { text: '2' }), el('kbd', { text: '3' }),
      ' flip / swipe / side by side · ', el('kbd', { text: 'h' }), ' heat map · ', el('kbd', { text: '0' }), ' fit · wheel zooms, drag pans');
    v.root.append(v.colorbar, v.heatNote, el('div', { class: 'status' }, v.statusLeft, help));
    v.layout();
  };

  // Rebuilds the panes for the mode and the pair.
  Viewer.prototype.layout = function () {
    const v = this;
    v.stage.replaceChildren();
    v.panes = [];
    const a = v.entryA(), b = v.entryB();
    const heat = v.heatmap();
    const pane = (entries) => {
      const p = el('div', { class: 'pane' });
      if (v.aspect) p.style.aspectRatio = String(v.aspect);
      const layer = el('div', { class: 'layer' });
      const imgs = {};
      for (const [slot, entry] of entries) {
        if (!entry) continue;
        const img = el('img', { class: slot, alt: entry.label, src: entry.src, draggable: 'false' });
        img.addEventListener('load', () => {
          if (!v.aspect && img.naturalWidth > 0) {
            v.aspect = img.naturalWidth / img.naturalHeight;
            v.panes.forEach((q) => { q.el.style.aspectRatio = String(v.aspect); });
          }
        });
        imgs[slot] = img;
        layer.append(img);
      }
      p.append(layer);
      v.attachZoom(p);
      v.stage.append(p);
      const rec = { el: p, layer: layer, imgs: imgs };
      v.panes.push(rec);
      return rec;
    };
    if (v.mode === 'side') {
      const left = pane([['a', a]]);
      left.el.append(el('span', { class: 'caption', text: 'A: ' + (a ? a.label : '') }));
      const right = pane([['b', b], ['heat', heat ? { src: heat.src, label: 'FLIP heat map' } : null]]);
      right.el.append(el('span', { class: 'caption', text: 'B: ' + (b ? b.label : '') }));
    } else {
      const p = pane([['a', a], ['b', b], ['heat', heat ? { src: heat.src, label: 'FLIP heat map' } : null]]);
      p.captionA = el('span', { class: 'caption', text: 'A: ' + (a ? a.label : '') });
      p.captionB = el('span', { class: 'caption right', text: 'B: ' + (b ? b.label : '') });
      p.el.append(p.captionA, p.captionB);
      if (v.mode === 'swipe') {
        p.divider = el('div', { class: 'divider' });
        p.el.append(p.divider);
      }
    }
    for (const [mode, button] of Object.entries(v.modeButtons)) button.classList.toggle('on', mode === v.mode);
    v.swipeLabel.hidden = v.mode !== 'swipe';
    v.heatBox.disabled = !heat;
    v.heatRange.hidden = !heat;
    if (!heat) v.heat = false;
    v.heatBox.checked = v.heat;
    if (heat) {
      v.heatNote.textContent = '';
    } else {
      v.heatNote.textContent = 'No FLIP heat map for ' + (a ? a.label : '?') + ' against ' + (b ? b.label : '?') +
        ' in this folder (grassbench compare writes them, as SCENE/diff_A_B.png; run and sweep do not).';
    }
    v.apply();
  };

  // Applies the state without rebuilding: visibility, clip, heat map, zoom and pan.
  Viewer.prototype.apply = function () {
    const v = this;
    v.root.dataset.showing = v.showing;
    v.root.dataset.mode = v.mode;
    const t = 'translate(' + v.x + 'px,' + v.y + 'px) scale(' + v.zoom + ')';
    for (const p of v.panes) {
      p.layer.style.transform = t;
      const { a, b, heat } = p.imgs;
      if (v.mode === 'flip') {
        if (a) a.style.visibility = v.showing === 'a' ? 'visible' : 'hidden';
        if (b) b.style.visibility = v.showing === 'b' ? 'visible' : 'hidden';
        if (p.captionA) p.captionA.hidden = v.showing !== 'a';
        if (p.captionB) p.captionB.hidden = v.showing !== 'b';
      } else if (v.mode === 'swipe') {
        if (a) a.style.visibility = 'visible';
        if (b) {
          b.style.visibility = 'visible';
          // The clip is in the pane's frame, so the layer's transform is undone.
          const w = p.el.clientWidth || 1;
          const cut = ((v.swipe / 100) * w - v.x) / v.zoom;
          b.style.clipPath = 'inset(0 0 0 ' + Math.max(0, cut) + 'px)';
        }
        if (p.divider) p.divider.style.left = v.swipe + '%';
        if (p.captionA) p.captionA.hidden = false;
        if (p.captionB) p.captionB.hidden = false;
      } else {
        if (a) a.style.visibility = 'visible';
        if (b) b.style.visibility = 'visible';
      }
      if (b && v.mode !== 'swipe') b.style.clipPath = '';
      if (heat) {
        heat.style.visibility = v.heat ? 'visible' : 'hidden';
        heat.style.opacity = String(v.heatOpacity);
      }
    }
    v.colorbar.hidden = !v.heat;
    const a = v.entryA(), b = v.entryB();
    v.statusLeft.textContent = 'showing ' + (v.mode === 'flip' ? (v.showing === 'a' ? 'A: ' + (a ? a.label : '') : 'B: ' + (b ? b.label : '')) : 'A and B') +
      ' · zoom ' + v.zoom.toFixed(v.zoom < 10 ? 1 : 0) + 'x';
  };

  Viewer.prototype.attachZoom = function (pane) {
    const v = this;
    pane.addEventListener('wheel', (e) => {
      e.preventDefault();
      const r = pane.getBoundingClientRect();
      const px = e.clientX - r.left, py = e.clientY - r.top;
      const z = Math.min(64, Math.max(1, v.zoom * (e.deltaY < 0 ? 1.25 : 0.8)));
      v.x = px - ((px - v.x) * z) / v.zoom;
      v.y = py - ((py - v.y) * z) / v.zoom;
      v.zoom = z;
      v.clampPan(r.width, r.height);
      v.apply();
    }, { passive: false });
    let drag = null;
    pane.addEventListener('pointerdown', (e) => {
      drag = { x: e.clientX, y: e.clientY, ox: v.x, oy: v.y };
      pane.classList.add('dragging');
      if (pane.setPointerCapture) pane.setPointerCapture(e.pointerId);
    });
    pane.addEventListener('pointermove', (e) => {
      if (!drag) return;
      v.x = drag.ox + e.clientX - drag.x;
      v.y = drag.oy + e.clientY - drag.y;
      const r = pane.getBoundingClientRect();
      v.clampPan(r.width, r.height);
      v.apply();
    });
    const end = () => { drag = null; pane.classList.remove('dragging'); };
    pane.addEventListener('pointerup', end);
    pane.addEventListener('pointercancel', end);
  };

  Viewer.prototype.clampPan = function (w, h) {
    this.x = Math.min(0, Math.max(w - w * this.zoom, this.x));
    this.y = Math.min(0, Math.max(h - h * this.zoom, this.y));
  };
  Viewer.prototype.resetZoom = function () { this.zoom = 1; this.x = 0; this.y = 0; this.apply(); };
  Viewer.prototype.setMode = function (mode) {
    if (this.mode === mode) return;
    this.mode = mode;
    this.layout();
  };
  Viewer.prototype.setPair = function (a, b) {
    if (a < 0 || b < 0 || a >= this.images.length || b >= this.images.length) return;
    this.a = a;
    this.b = b;
    this.selA.value = String(a);
    this.selB.value = String(b);
    this.layout();
  };
  // Flips between A and B (switching to flip mode first where another mode is on).
  Viewer.prototype.flip = function () {
    if (this.mode !== 'flip') this.setMode('flip');
    this.showing = this.showing === 'a' ? 'b' : 'a';
    this.apply();
  };
  Viewer.prototype.activate = function () {
    if (activeViewer && activeViewer !== this) activeViewer.root.classList.remove('active');
    activeViewer = this;
    this.root.classList.add('active');
  };
  // The source of the image a reader sees in flip mode.
  Viewer.prototype.visibleSrc = function () {
    const p = this.panes[0];
    if (!p) return null;
    for (const slot of ['a', 'b']) {
      const img = p.imgs[slot];
      if (img && getComputedStyle(img).visibility === 'visible') return img.getAttribute('src');
    }
    return null;
  };
  // Shows a run from the chart: the run as B, the scene's reference as A.
  Viewer.prototype.showImage = function (id) {
    const k = this.images.findIndex((i) => i.id === id);
    if (k < 0) return;
    const ref = this.images.findIndex((i) => i.technique === 'reference');
    if (ref >= 0 && ref !== k) this.setPair(ref, k);
    else this.setPair(k, this.b === k ? this.a : this.b);
    this.showing = 'b';
    this.apply();
    this.activate();
  };

  document.addEventListener('keydown', (e) => {
    const tag = e.target && e.target.tagName;
    if (tag === 'INPUT' || tag === 'SELECT' || tag === 'TEXTAREA') return;
    if (e.ctrlKey || e.metaKey || e.altKey) return;
    const v = activeViewer || viewers[0];
    if (!v) return;
    switch (e.key) {
      case 'f': case 'F': v.flip(); break;
      case '1': v.setMode('flip'); break;
      case '2': v.setMode('swipe'); break;
      case '3': v.setMode('side'); break;
      case 'h': case 'H':
        if (v.heatmap()) { v.heat = !v.heat; v.heatBox.checked = v.heat; v.apply(); }
        break;
      case '0': v.resetZoom(); break;
      default: return;
    }
    e.preventDefault();
  });

  // ---------------------------------------------------------------- quality against cost
  function niceLogTicks(lo, hi) {
    const ticks = [];
    for (let e = Math.floor(Math.log10(lo)); e <= Math.ceil(Math.log10(hi)); e++) {
      for (const m of [1, 2, 5]) {
        const t = m * Math.pow(10, e);
        if (t >= lo && t <= hi) ticks.push(t);
      }
    }
    return ticks;
  }
  function niceLinearTicks(max) {
    const raw = max / 5;
    const p = Math.pow(10, Math.floor(Math.log10(raw)));
    const step = [1, 2, 2.5, 5, 10].map((m) => m * p).find((s) => s >= raw) || raw;
    const ticks = [];
    for (let t = 0; t <= max + 1e-12; t += step) ticks.push(t);
    return ticks;
  }

  function chart(scene, viewer) {
    const box = el('div', { class: 'chart-box' });
    const points = scene.points;
    if (points.length === 0) {
      box.append(el('p', { class: 'note', text: 'No run with a measured GPU time in this scene.' }));
      return box;
    }
    const W = 620, H = 380, L = 62, R = 16, T = 26, B = 46;
    const s = svgEl('svg', { class: 'chart', viewBox: '0 0 ' + W + ' ' + H, role: 'img' });
    s.append(svgEl('title', { text: 'Quality against cost: ' + scene.name }));
    const costs = points.map((p) => p.cost).filter((c) => c > 0);
    let lo = Math.min(...costs) / 1.4, hi = Math.max(...costs) * 1.4;
    if (!(lo > 0)) lo = 0.1;
    if (hi <= lo * 2) hi = lo * 2;
    const qs = points.map((p) => p.quality).filter((q) => q !== null);
    const qmax = Math.max(0.02, ...qs) * 1.15;
    const missing = points.some((p) => p.quality === null);
    const top = T + (missing ? 22 : 0);
    const X = (c) => L + ((Math.log(c) - Math.log(lo)) / (Math.log(hi) - Math.log(lo))) * (W - L - R);
    const Y = (q) => (q === null ? T + 6 : top + (1 - q / qmax) * (H - top - B));
    const axis = svgEl('g', { class: 'axis' });
    for (const t of niceLogTicks(lo, hi)) {
      const x = X(t);
      s.append(svgEl('line', { class: 'grid', x1: x, x2: x, y1: top, y2: H - B }));
      axis.append(svgEl('line', { x1: x, x2: x, y1: H - B, y2: H - B + 4 }));
      axis.append(svgEl('text', { x: x, y: H - B + 16, 'text-anchor': 'middle', text: t >= 1 ? String(Math.round(t)) : String(Number(t.toPrecision(1))) }));
    }
    for (const t of niceLinearTicks(qmax)) {
      const y = Y(t);
      s.append(svgEl('line', { class: 'grid', x1: L, x2: W - R, y1: y, y2: y }));
      axis.append(svgEl('text', { x: L - 6, y: y + 4, 'text-anchor': 'end', text: t === 0 ? '0' : t.toPrecision(2) }));
    }
    axis.append(svgEl('line', { x1: L, x2: W - R, y1: H - B, y2: H - B }));
    axis.append(svgEl('line', { x1: L, x2: L, y1: top, y2: H - B }));
    axis.append(svgEl('text', { x: (L + W - R) / 2, y: H - 8, 'text-anchor': 'middle', text: 'median GPU wall time per frame, ms (log scale) — cheaper to the left' }));
    axis.append(svgEl('text', { x: 14, y: (top + H - B) / 2, 'text-anchor': 'middle', transform: 'rotate(-90 14 ' + (top + H - B) / 2 + ')', text: 'FLIP 1/4 vs reference — better below' }));
    if (missing) axis.append(svgEl('text', { x: L - 6, y: T + 10, 'text-anchor': 'end', text: 'no FLIP' }));
    s.append(axis);
    if (scene.frontier.length > 1) {
      const pts = scene.frontier.map((k) => X(points[k].cost).toFixed(1) + ',' + Y(points[k].quality).toFixed(1)).join(' ');
      s.append(svgEl('polyline', { class: 'frontier', points: pts }));
    }
    const circles = [];
    points.forEach((p, k) => {
      const c = svgEl('circle', {
        class: 'point' + (p.quality === null ? ' no-quality' : ''),
        cx: X(p.cost).toFixed(1), cy: Y(p.quality).toFixed(1), r: scene.frontier.includes(k) ? 7 : 6,
        fill: colorOf(p.technique), 'data-row': p.row,
      });
      c.addEventListener('mouseenter', (e) => showTooltip(e, p));
      c.addEventListener('mousemove', (e) => placeTooltip(e));
      c.addEventListener('mouseleave', () => { tooltip.hidden = true; });
      c.addEventListener('click', () => {
        circles.forEach((o) => o.classList.remove('selected'));
        c.classList.add('selected');
        if (viewer && p.image) viewer.showImage(p.image);
      });
      circles.push(c);
      s.append(c);
    });
    box.append(s);
    const legend = el('div', { class: 'legend' });
    const seen = new Set();
    for (const p of points) {
      if (seen.has(p.technique)) continue;
      seen.add(p.technique);
      const sw = el('span', { class: 'swatch' });
      sw.style.background = colorOf(p.technique);
      legend.append(el('span', {}, sw, p.technique));
    }
    legend.append(el('span', { text: '- - frontier (nothing cheaper is better)' }));
    box.append(legend);
    box.append(el('p', { class: 'note', text: 'Hover a point for its parameters and figures; click it to load its image into the viewer (against the reference). Quality: ' + data.quality + '.' }));
    return box;
  }

  function showTooltip(e, p) {
    tooltip.replaceChildren(el('b', { text: p.label }));
    for (const [k, v] of p.figures) tooltip.append(el('div', { text: k + ': ' + v }));
    tooltip.hidden = false;
    placeTooltip(e);
  }
  function placeTooltip(e) {
    const w = tooltip.offsetWidth, h = tooltip.offsetHeight;
    let x = e.clientX + 14, y = e.clientY + 14;
    if (x + w > window.innerWidth - 4) x = e.clientX - w - 14;
    if (y + h > window.innerHeight - 4) y = Math.max(4, e.clientY - h - 14);
    tooltip.style.left = x + 'px';
    tooltip.style.top = y + 'px';
  }

  // ---------------------------------------------------------------- tables
  // A sortable table; `columns` limits the columns shown (all when null).
  function table(t, columns) {
    const shown = columns ? columns.map((c) => t.columns.indexOf(c)).filter((k) => k >= 0) : t.columns.map((_, k) => k);
    const numeric = shown.map((k) => t.rows.every((r) => r[k] === undefined || r[k] === '' || num(r[k]) !== null) && t.rows.some((r) => num(r[k]) !== null));
    const statusCol = t.columns.indexOf('status');
    const tb = el('table', { class: 'data' });
    const head = el('tr');
    const body = el('tbody');
    let sortCol = -1, asc = true;
    const rows = t.rows.map((r, k) => ({ r: r, k: k }));
    const render = () => {
      const ordered = rows.slice();
      if (sortCol >= 0) {
        const k = shown[sortCol];
        ordered.sort((x, y) => {
          let c;
          if (numeric[sortCol]) {
            const a = num(x.r[k]), b = num(y.r[k]);
            c = a === null ? (b === null ? 0 : 1) : b === null ? -1 : asc ? a - b : b - a;
            return c !== 0 ? c : x.k - y.k;
          }
          c = String(x.r[k] || '').localeCompare(String(y.r[k] || ''));
          return (asc ? c : -c) || x.k - y.k;
        });
      }
      body.replaceChildren(...ordered.map(({ r }) => {
        const tr = el('tr');
        if (statusCol >= 0 && r[statusCol] && r[statusCol] !== 'ok') tr.className = 'failed-row';
        shown.forEach((k, j) => {
          const raw = r[k] === undefined ? '' : r[k];
          const td = el('td', { class: numeric[j] ? '' : raw.length > 48 ? 'text long' : 'text', title: raw.length > 12 ? raw : null });
          td.textContent = numeric[j] && raw !== '' ? fmt(num(raw)) : raw;
          tr.append(td);
        });
        return tr;
      }));
    };
    shown.forEach((k, j) => {
      const th = el('th', { class: numeric[j] ? '' : 'text', text: t.columns[k], title: 'sort by ' + t.columns[k] });
      th.addEventListener('click', () => {
        if (sortCol === j) asc = !asc; else { sortCol = j; asc = true; }
        head.querySelectorAll('th').forEach((h) => h.classList.remove('sorted-asc', 'sorted-desc'));
        th.classList.add(asc ? 'sorted-asc' : 'sorted-desc');
        render();
      });
      head.append(th);
    });
    tb.append(el('thead', {}, head), body);
    render();
    return el('div', { class: 'table-wrap' }, tb);
  }

  const KEY_COLUMNS = ['run_id', 'repetition', 'status', 'scene', 'scene_variant', 'technique', 'width', 'height', 'msaa',
    'gpu_wall_ms_median', 'gpu_wall_ms_p5', 'gpu_wall_ms_p95', 'frame_ms_median', 'speedup', 'speedup_ci_low', 'speedup_ci_high',
    'flip_vs_reference', 'flip_vs_reference_quarter', 'model_ms', 'model_ratio', 'blades_drawn', 'blades_represented',
    'triangles', 'draw_calls', 'overdraw', 'host_other_cores', 'params', 'error'];

  function runsSection() {
    const t = data.runs;
    const sec = el('section', { id: 'runs' }, el('h2', { text: 'Runs (' + t.name + ')' }));
    sec.append(el('p', { class: 'note', text: t.rows.length + ' rows, ' + t.columns.length + ' columns. Click a header to sort (again to reverse); numbers are rounded for display, hover a long cell for its full text.' }));
    const all = el('input', { type: 'checkbox' });
    const holder = el('div');
    // The key columns that hold something (a run folder's rows have no run id, for one).
    const filled = (c) => { const k = t.columns.indexOf(c); return k >= 0 && t.rows.some((r) => r[k] !== undefined && r[k] !== ''); };
    const draw = () => holder.replaceChildren(table(t, all.checked ? null : KEY_COLUMNS.filter(filled)));
    all.addEventListener('change', draw);
    sec.append(el('div', { class: 'table-tools' }, el('label', {}, all, 'all ' + t.columns.length + ' columns')), holder);
    draw();
    return sec;
  }

  // ---------------------------------------------------------------- where the time goes
  const SEGMENT_COLORS = ['#1f77b4', '#ff7f0e', '#2ca02c', '#d62728', '#9467bd', '#8c564b', '#e377c2', '#7f7f7f', '#bcbd22', '#17becf', '#5a5a5a', '#c8c8c8', '#ffbb78', '#98df8a', '#c5b0d5', '#c49c94', '#f7b6d2', '#dbdb8d', '#9edae5', '#393b79', '#637939', '#8c6d31'];

  function splitSection() {
    const sec = el('section', { id: 'time' }, el('h2', { text: 'Where the time goes' }));
    sec.append(el('p', { class: 'note', text: 'Per configuration with a cost model: its median CPU stages and the GPU terms the model predicts from its measured work (unit cost × work), stacked, ms per frame; the black tick is the measured frame (CPU stages + measured GPU wall time). The gap between the bar and the tick is what the model does not explain. The same figures as REPORT.md.' }));
    const legend = el('div', { class: 'legend' });
    data.segments.forEach((name, k) => {
      const sw = el('span', { class: 'box' });
      sw.style.background = SEGMENT_COLORS[k % SEGMENT_COLORS.length];
      legend.append(el('span', {}, sw, name));
    });
    sec.append(legend);
    const measured = (r) => r.values.slice(0, 3).reduce((a, b) => a + b, 0) + (r.measured_gpu_ms || 0);
    const max = Math.max(1e-9, ...data.split.map((r) => Math.max(r.values.reduce((a, b) => a + b, 0), measured(r)))) * 1.02;
    for (const r of data.split) {
      const bar = el('div', { class: 'split-bar' });
      let base = 0;
      const total = r.values.reduce((a, b) => a + b, 0);
      r.values.forEach((v, k) => {
        const seg = el('div', { class: 'seg', title: data.segments[k] + ': ' + fmt(v) + ' ms (' + (100 * v / Math.max(total, 1e-12)).toFixed(0) + ' %)' });
        seg.style.left = (100 * base / max) + '%';
        seg.style.width = (100 * v / max) + '%';
        seg.style.background = SEGMENT_COLORS[k % SEGMENT_COLORS.length];
        bar.append(seg);
        base += v;
      });
      if (r.measured_gpu_ms !== null) {
        const tick = el('div', { class: 'tick', title: 'measured ' + fmt(measured(r)) + ' ms' });
        tick.style.left = 'calc(' + (100 * measured(r) / max) + '% - 1px)';
        bar.append(tick);
      }
      sec.append(el('div', { class: 'split-row' },
        el('span', { class: 'name', title: r.scene + ' ' + r.size + ' ' + r.label, text: r.scene + ' ' + r.size + ' · ' + r.label }),
        bar,
        el('span', { text: 'model ' + fmt(r.model_ms) + ' ms, measured / model ' + fmt(r.ratio) })));
    }
    const t = {
      name: 'where the time goes',
      columns: ['scene', 'size', 'configuration', 'measured GPU ms', 'model ms', 'measured / model'].concat(data.segments.map((s) => s + ' ms')),
      rows: data.split.map((r) => [r.scene, r.size, r.label, String(r.measured_gpu_ms === null ? '' : r.measured_gpu_ms), String(r.model_ms), String(r.ratio === null ? '' : r.ratio)].concat(r.values.map(String))),
    };
    sec.append(el('h3', { text: 'As a table' }), table(t, null));
    if (data.checks) {
      sec.append(el('h3', { text: 'Coverage checks of the calibration' }),
        el('p', { class: 'note', text: 'Timed with the calibration and not fitted: blades on screen (1.5 pixels wide), slivers (0.3) and layers hidden behind an opaque one, each opaque, alpha-tested and blended, at two sizes; measured over what the unit costs predict from their counted work. Near 1 where the prices, fitted on full-screen layers and sub-pixel triangles, hold for fragments like a technique\'s (results/cost_model/coverage/).' }),
        table(data.checks, null));
    }
    return sec;
  }

  // ---------------------------------------------------------------- temporal change
  // compare's temporal.csv as bars: per technique (its first operating point) and motion,
  // the spurious and the missing change against the reference's, at 1/4 scale.
  function temporalBars(t) {
    const col = (name) => t.columns.indexOf(name);
    const [ct, cv, cm, cb, cs, csp, cmi] = ['technique', 'variant', 'motion', 'baseline', 'scale', 'spurious_mean', 'missing_mean'].map(col);
    if ([ct, cv, cm, cb, cs, csp, cmi].some((k) => k < 0)) return null;
    const firstVariant = {};
    for (const r of t.rows) if (!(r[ct] in firstVariant)) firstVariant[r[ct]] = r[cv];
    const rows = t.rows.filter((r) => r[cb] === 'reference' && r[cs] === 'quarter' && r[cv] === firstVariant[r[ct]] && r[ct] !== 'reference');
    if (rows.length === 0) return null;
    const max = Math.max(1, ...rows.flatMap((r) => [num(r[csp]) || 0, num(r[cmi]) || 0]));
    const box = el('div');
    const legend = el('div', { class: 'legend' });
    for (const [name, color] of [['spurious change (shows what the reference does not)', '#d62728'], ['missing change (lacks what the reference shows)', '#1f77b4']]) {
      const sw = el('span', { class: 'box' });
      sw.style.background = color;
      legend.append(el('span', {}, sw, name));
    }
    box.append(legend);
    for (const r of rows) {
      const bars = el('div');
      for (const [k, color] of [[csp, '#d62728'], [cmi, '#1f77b4']]) {
        const v = num(r[k]) || 0;
        const bar = el('div', { class: 'split-bar thin' });
        const seg = el('div', { class: 'seg', title: t.columns[k] + ': ' + fmt(v) });
        seg.style.left = '0';
        seg.style.width = (100 * v / max) + '%';
        seg.style.background = color;
        bar.append(seg);
        bars.append(bar);
      }
      box.append(el('div', { class: 'split-row' },
        el('span', { class: 'name', text: r[ct] + ' (' + r[cv] + ') · ' + r[cm] }),
        bars,
        el('span', { text: 'spurious ' + fmt(num(r[csp])) + ', missing ' + fmt(num(r[cmi])) })));
    }
    return box;
  }

  // ---------------------------------------------------------------- the page
  const toc = document.getElementById('toc');
  data.scenes.forEach((scene) => {
    const id = anchor(scene.name);
    toc.append(el('a', { href: '#' + id, text: scene.name }));
    const sec = el('section', { id: id }, el('h2', { text: scene.name }));
    const grid = el('div', { class: scene.points.length > 0 ? 'scene-grid' : 'scene-grid single' });
    let viewer = null;
    const left = el('div');
    if (scene.images.length > 0) {
      viewer = new Viewer(scene);
      viewers.push(viewer);
      left.append(viewer.root);
    } else {
      left.append(el('p', { class: 'note', text: 'No saved images for this scene.' }));
    }
    grid.append(left);
    const right = el('div');
    if (scene.points.length > 0 || data.runs) right.append(el('h3', { text: 'Quality against cost' }), chart(scene, viewer));
    if (scene.failed.length > 0) {
      const ul = el('ul', { class: 'failed' });
      for (const [label, error] of scene.failed) ul.append(el('li', { text: 'failed: ' + label + ' — ' + error }));
      right.append(ul);
    }
    grid.append(right);
    sec.append(grid);
    for (const t of scene.tables) {
      const title = t.name.endsWith('temporal.csv') ? 'Temporal change along camera motions (' + t.name + ')' : t.name;
      sec.append(el('h3', { text: title }));
      if (t.name.endsWith('temporal.csv')) {
        sec.append(el('p', { class: 'note', text: 'Spurious change: change the technique shows where its baseline does not (popping, shimmer); missing change: the baseline\'s change it lacks; both in units of the baseline\'s mean change per step. Bars: against the reference, at 1/4 scale; the table holds every baseline and scale.' }));
        const bars = temporalBars(t);
        if (bars) sec.append(bars);
      }
      sec.append(table(t, null));
    }
    main.append(sec);
  });
  if (data.split.length > 0) {
    toc.append(el('a', { href: '#time', text: 'where the time goes' }));
    main.append(splitSection());
  }
  if (data.plots.length > 0) {
    toc.append(el('a', { href: '#plots', text: 'REPORT.md\'s plots' }));
    const sec = el('section', { id: 'plots' }, el('h2', { text: 'REPORT.md\'s plots' }));
    for (const [src, title] of data.plots) {
      sec.append(el('figure', {}, el('img', { src: src, alt: title }), el('figcaption', { text: title })));
    }
    main.append(sec);
  }
  if (data.runs) {
    toc.append(el('a', { href: '#runs', text: 'runs.csv' }));
    main.append(runsSection());
  }
  if (viewers.length > 0) viewers[0].activate();
  // ?mode=flip|swipe|side, ?heat=1 and ?zoom=N set every viewer (links and screenshots).
  const query = new URLSearchParams(window.location.search);
  for (const v of viewers) {
    const mode = query.get('mode');
    if (mode === 'flip' || mode === 'swipe' || mode === 'side') v.setMode(mode);
    if (query.get('heat') === '1' && v.heatmap()) { v.heat = true; v.heatBox.checked = true; }
    const zoom = Number(query.get('zoom'));
    if (zoom > 1 && zoom <= 64) {
      // About the middle of the picture.
      const pane = v.panes[0].el;
      v.zoom = zoom;
      v.x = (-pane.clientWidth * (zoom - 1)) / 2;
      v.y = (-pane.clientHeight * (zoom - 1)) / 2;
    }
    v.apply();
  }
  // The sections are built here, after the browser looked for the address's #anchor.
  if (window.location.hash.length > 1) {
    const target = document.getElementById(decodeURIComponent(window.location.hash.slice(1)));
    if (target) target.scrollIntoView();
  }
  // ?only=ID shows one section alone (for screenshots of a part of the page).
  const only = new URLSearchParams(window.location.search).get('only');
  if (only && document.getElementById(only)) {
    for (const sec of main.children) sec.hidden = sec.id !== only;
    toc.hidden = true;
  }

  // ---------------------------------------------------------------- ?selftest=1
  // Checks the page in a real browser: the first viewer flips on a keystroke, the charts hold
  // one point per run with a GPU time, a header click sorts; then writes the outcome and any
  // error seen into the data-selftest attribute of <html> ("ok: " or "fail: " and why).
  function selftest() {
    const fails = [];
    const notes = [];
    const v = viewers[0];
    if (!v) {
      fails.push('no image viewer');
    } else if (v.images.length < 2) {
      fails.push('the first viewer has fewer than two images');
    } else {
      v.setMode('flip');
      const before = v.root.dataset.showing, seenBefore = v.visibleSrc();
      document.body.dispatchEvent(new KeyboardEvent('keydown', { key: 'f', bubbles: true }));
      const after = v.root.dataset.showing, seenAfter = v.visibleSrc();
      if (before === after) fails.push('key f did not flip the viewer (showing ' + before + ' before and after)');
      if (seenBefore === seenAfter) fails.push('key f did not change the visible image (' + seenAfter + ')');
      else if (seenAfter !== v.entryB().src) fails.push('after key f the visible image is ' + seenAfter + ', not B ' + v.entryB().src);
      notes.push('key f flipped ' + before + ' -> ' + after);
      // Where the pair has a FLIP heat map, key h lays it over the images with its colour bar.
      if (v.heatmap()) {
        document.body.dispatchEvent(new KeyboardEvent('keydown', { key: 'h', bubbles: true }));
        const heat = v.panes[0].imgs.heat;
        if (!heat || getComputedStyle(heat).visibility !== 'visible' || v.colorbar.hidden) fails.push('key h did not show the FLIP heat map');
        else notes.push('key h shows the heat map');
      }
    }
    // Hovering a point shows its figures; clicking one loads its image into the viewer.
    const scene = data.scenes.find((sc) => sc.points.some((p) => p.image && p.technique !== 'reference'));
    if (scene) {
      const k = scene.points.findIndex((p) => p.image && p.technique !== 'reference');
      const circle = document.getElementById(anchor(scene.name)).querySelectorAll('circle.point')[k];
      const viewer = viewers.find((w) => w.scene === scene);
      if (!circle || !viewer) {
        fails.push('no chart point or viewer for ' + scene.name);
      } else {
        circle.dispatchEvent(new MouseEvent('mouseenter', { clientX: 20, clientY: 20 }));
        if (tooltip.hidden || !tooltip.textContent.includes(scene.points[k].label)) fails.push('hovering a point shows no tooltip with its label');
        else notes.push('tooltip');
        circle.dispatchEvent(new MouseEvent('mouseleave'));
        circle.dispatchEvent(new MouseEvent('click', { bubbles: true }));
        if (viewer.entryB().id !== scene.points[k].image || viewer.visibleSrc() !== viewer.entryB().src) {
          fails.push('clicking a point did not show its image (' + scene.points[k].image + ') in the viewer');
        } else {
          notes.push('click loads ' + scene.points[k].label);
        }
      }
    }
    const points = document.querySelectorAll('svg.chart circle.point').length;
    document.documentElement.setAttribute('data-points', String(points));
    if (data.runs) {
      const k = data.runs.columns.indexOf('gpu_wall_ms_median');
      const expected = data.runs.rows.filter((r) => num(r[k]) !== null).length;
      if (points !== expected) fails.push('the charts hold ' + points + ' points for ' + expected + ' runs with a GPU time');
      notes.push(points + ' points');
      const th = Array.from(document.querySelectorAll('#runs th')).find((h) => h.textContent === 'gpu_wall_ms_median');
      if (th) {
        th.click();
        const col = Array.from(th.parentNode.children).indexOf(th);
        const cells = Array.from(document.querySelectorAll('#runs tbody tr')).map((tr) => num(tr.children[col].getAttribute('title') || tr.children[col].textContent));
        const vals = cells.filter((c) => c !== null);
        if (vals.some((c, i) => i > 0 && c < vals[i - 1])) fails.push('a click on gpu_wall_ms_median did not sort the runs table');
        else notes.push('sorted');
      }
    }
    // The images the checks brought in load before the outcome is written.
    afterImages(() => {
      const pending = Array.from(document.images).filter((i) => !i.complete);
      if (pending.length > 0) fails.push(pending.length + ' images still loading');
      const broken = Array.from(document.images).filter((i) => i.complete && i.naturalWidth === 0 && i.getAttribute('src'));
      for (const b of broken) fails.push('image did not load: ' + b.getAttribute('src'));
      for (const e of errors) fails.push(e);
      document.documentElement.setAttribute('data-selftest', fails.length > 0 ? 'fail: ' + fails.join(' | ') : 'ok: ' + notes.join('; '));
    });
  }
  // Calls `then` once every image has loaded or failed (at most 3 s later).
  function afterImages(then) {
    let waited = 0;
    const wait = () => {
      const loading = Array.from(document.images).some((i) => !i.complete);
      if (loading && waited < 3000) { waited += 50; setTimeout(wait, 50); } else then();
    };
    wait();
  }
  if (new URLSearchParams(window.location.search).get('selftest') === '1') {
    // After the page's images have loaded (or failed), so their errors are counted.
    const start = () => afterImages(selftest);
    if (document.readyState === 'complete') start(); else window.addEventListener('load', start);
  }
})();
