// report.js: the renderer of the clr run report (src/report/mod.rs). The page carries the
// `Report` as JSON in <script id="clr-data">; this script builds the page from it: the
// mechanism on a canvas with playback beside the run's description, metrics, impacts and
// figures. Plain ES2017, no libraries, no network: the page must work opened from disk.
//
// Data conventions (src/report/scene.rs, frames.rs): `frames.pose[part]` is [x, y, θ] of the
// part's centre of mass per frame, flattened; an anchor {part, at} is in the part's body frame
// (part −1: the world); an anchor {beam, node} is a beam node; `frames.nodes[beam]` holds the
// node displacements [u, v] (world axes) from the undeformed nodes, frame-major. A contact
// shape {at, angle, outlines} has its outlines in its own frame, whose origin is the anchor
// `at` and whose x axis is turned by `angle` from its part's.
//
// A headless test reads `window.clrReport` ({time, journal(name), errors}) and waits for the
// title to end with " [ready]"; `#t=<seconds>` in the URL sets the initial time (paused).
'use strict';
(() => {
  // ===== errors and the test handle ============================================================

  const clrReport = { time: 0, ready: false, errors: [], journal: () => null, seek: () => {} };
  window.clrReport = clrReport;

  let errorBox = null;
  /** Record an error for the test handle and show it in a red box (fixed, always visible). */
  function reportError(message) {
    const text = String(message);
    clrReport.errors.push(text);
    if (!errorBox) {
      errorBox = document.createElement('div');
      errorBox.className = 'clr-errors';
      errorBox.setAttribute('role', 'alert');
      const title = document.createElement('strong');
      title.textContent = 'report script error';
      errorBox.appendChild(title);
      document.body.appendChild(errorBox);
    }
    const line = document.createElement('div');
    line.textContent = text;
    errorBox.appendChild(line);
  }
  window.onerror = (msg, _src, line, col, err) => {
    reportError(err && err.stack ? err.stack : line ? `${msg} (line ${line}:${col})` : msg);
  };
  window.addEventListener('unhandledrejection', (e) => reportError(`unhandled rejection: ${e.reason}`));

  // ===== small helpers ==========================================================================

  const clamp = (v, lo, hi) => Math.min(hi, Math.max(lo, v));
  const isNum = (v) => typeof v === 'number' && isFinite(v);
  const TAU = 2 * Math.PI;

  /** Create an element: props (class, text, on<event>, attributes) and children. */
  function h(tag, props, ...children) {
    const e = document.createElement(tag);
    for (const [k, v] of Object.entries(props || {})) {
      if (v === undefined || v === null || v === false) continue;
      if (k === 'class') e.className = v;
      else if (k === 'text') e.textContent = v;
      else if (k.startsWith('on')) e.addEventListener(k.slice(2), v);
      else e.setAttribute(k, v === true ? '' : v);
    }
    for (const c of children.flat()) {
      if (c === null || c === undefined || c === false) continue;
      e.appendChild(typeof c === 'string' ? document.createTextNode(c) : c);
    }
    return e;
  }

  /** A 16×16 inline SVG icon (fonts differ between systems; paths do not). */
  function icon(d, stroke) {
    const ns = 'http://www.w3.org/2000/svg';
    const svg = document.createElementNS(ns, 'svg');
    svg.setAttribute('viewBox', '0 0 16 16');
    svg.setAttribute('width', '16');
    svg.setAttribute('height', '16');
    svg.setAttribute('aria-hidden', 'true');
    const p = document.createElementNS(ns, 'path');
    p.setAttribute('d', d);
    if (stroke) {
      p.setAttribute('fill', 'none');
      p.setAttribute('stroke', 'currentColor');
      p.setAttribute('stroke-width', '1.8');
    } else {
      p.setAttribute('fill', 'currentColor');
    }
    svg.appendChild(p);
    return svg;
  }
  const ICONS = {
    play: 'M4 2L14 8L4 14Z',
    pause: 'M3 2h4v12H3zM9 2h4v12H9z',
    back: 'M2 2h2v12H2zM14 2L5 8L14 14Z',
    forward: 'M12 2h2v12h-2zM2 2L11 8L2 14Z',
    fit: 'M1 5V1h4M11 1h4v4M15 11v4h-4M5 15H1v-4',
  };

  // ===== number formatting ======================================================================

  /** `v.toFixed(d)` without a "-0". */
  function fixed(v, d) {
    const s = v.toFixed(d);
    return /^-0(\.0*)?$/.test(s) ? s.slice(1) : s;
  }

  /** Engineering notation (exponent a multiple of 3, `sig` ≥ 3 significant digits, trailing
   * zeros dropped, always a "." decimal point): 54224.5 → "54.22e3", 0.0123 → "12.3e-3". */
  function eng(x, sig = 4) {
    if (typeof x !== 'number') return x === null || x === undefined ? '' : String(x);
    if (!isFinite(x)) return String(x);
    if (x === 0) return '0';
    let e3 = Math.floor(Math.log10(Math.abs(x)) / 3) * 3;
    let s = (x / 10 ** e3).toPrecision(sig);
    if (Math.abs(parseFloat(s)) >= 1000) {
      // rounding carried into the next group (999.96 → 1000)
      e3 += 3;
      s = (x / 10 ** e3).toPrecision(sig);
    }
    if (s.includes('.')) s = s.replace(/\.?0+$/, '');
    return e3 === 0 ? s : `${s}e${e3}`;
  }

  /** A 1-2-5 step giving about `count` intervals over `span`. */
  function niceStep(span, count) {
    if (!(span > 0)) return 1;
    const raw = span / Math.max(1, count);
    const p = 10 ** Math.floor(Math.log10(raw));
    const f = raw / p;
    return (f < 1.5 ? 1 : f < 3 ? 2 : f < 7 ? 5 : 10) * p;
  }

  /** Tick values in [lo, hi] at a nice step. */
  function ticks(lo, hi, count) {
    const step = niceStep(hi - lo, count);
    const values = [];
    for (let k = Math.ceil(lo / step - 1e-9); k * step <= hi + step * 1e-9; k++) {
      values.push(k === 0 ? 0 : k * step);
    }
    return { values, step };
  }

  /** Tick label format for ticks of `step` within ±`big`: plain decimals for ordinary
   * magnitudes, engineering notation with a common exponent for large or small ones. */
  function tickFormat(big, step) {
    if (big >= 1e-2 && big < 1e4) {
      const d = clamp(Math.ceil(-Math.log10(step) - 1e-9), 0, 10);
      return (v) => fixed(v, d);
    }
    const e3 = big > 0 ? Math.floor(Math.log10(big) / 3) * 3 : 0;
    const d = clamp(Math.ceil(-Math.log10(step / 10 ** e3) - 1e-9), 0, 10);
    return (v) => (v === 0 ? '0' : `${fixed(v / 10 ** e3, d)}e${e3}`);
  }

  /** Time format of a run: one exponent for the whole run (the digits do not jump while
   * playing) and decimals down to about the frame spacing. */
  function timeFormat(t0, t1, n) {
    const big = Math.max(Math.abs(t0), Math.abs(t1));
    const e3 = big > 0 ? Math.floor(Math.log10(big) / 3) * 3 : 0;
    const dt = n > 1 ? (t1 - t0) / (n - 1) : big || 1;
    const d = clamp(Math.ceil(-Math.log10(dt / 10 ** e3) - 1e-9), 0, 6);
    return (t) => `${fixed(t / 10 ** e3, d)}${e3 ? `e${e3}` : ''} s`;
  }

  /** A length with an SI prefix, for the scale bar. */
  function lengthLabel(m) {
    for (const [f, u] of [[1e3, 'km'], [1, 'm'], [1e-3, 'mm'], [1e-6, 'µm'], [1e-9, 'nm']]) {
      if (m >= f * 0.999) return `${+(m / f).toPrecision(3)} ${u}`;
    }
    return `${eng(m)} m`;
  }

  /** Colours of part k: pale fill, mid tone and dark outline at a golden-angle hue step. */
  function partColours(k) {
    const hue = Math.round((k * 137.508 + 205) % 360);
    return {
      fill: `hsl(${hue}, 48%, 86%)`,
      mid: `hsl(${hue}, 45%, 66%)`,
      stroke: `hsl(${hue}, 40%, 30%)`,
    };
  }
  const GROUND = { fill: '#c9d3df', mid: '#9aabbf', stroke: '#3b4a5e' };
  const INK = '#1d2330';
  const CONTACT = '#d62728';
  const FRICTION = '#e07b00';
  const DRIVE = '#7b3fb5';
  const LOAD = '#0f8a8a';
  const SPRING = '#2f7d4f';
  const PALETTE = ['#1f77b4', '#d62728', '#2ca02c', '#ff7f0e', '#9467bd', '#8c564b', '#e377c2',
    '#7f7f7f', '#bcbd22', '#17becf'];

  // ===== kinematics: the state at any time ======================================================

  /** The recorded motion, interpolated linearly between frames into one reused state
   * {t, i, f, pose, disp, contact} (no allocation per frame). */
  function makeMotion(rep) {
    const scene = rep.scene;
    const fr = rep.frames && rep.frames.t && rep.frames.t.length ? rep.frames : null;
    const t = fr ? fr.t : [0];
    const n = t.length;
    const parts = scene.parts;
    const beams = scene.beams;
    // without frames (or with a short pose array) the initial pose of the description is drawn
    const pose = parts.map((p, k) => {
      const a = fr && fr.pose && fr.pose[k];
      if (a && a.length >= 3 * n) return a;
      const [x, y, th] = p.pose0 || [0, 0, 0];
      const c = Math.cos(th);
      const s = Math.sin(th);
      return Array(n).fill([x + c * p.com[0] - s * p.com[1], y + s * p.com[0] + c * p.com[1], th]).flat();
    });
    const nodes = beams.map((b, k) => {
      const a = fr && fr.nodes && fr.nodes[k];
      return a && a.length >= 2 * b.nodes.length * n ? a : null;
    });
    const contact = (fr && fr.contact) || {};
    const st = {
      t: t[0],
      i: 0,
      f: 0,
      pose: new Float64Array(3 * parts.length),
      disp: beams.map((b) => new Float64Array(2 * b.nodes.length)),
      contact: {},
    };
    for (const name of Object.keys(contact)) st.contact[name] = {};

    /** Frame i and weight f of time tq (t[i] ≤ tq ≤ t[i+1]). */
    function locate(tq) {
      if (n < 2 || !(tq > t[0])) return [0, 0];
      if (tq >= t[n - 1]) return [n - 2, 1];
      let lo = 0;
      let hi = n - 1;
      while (hi - lo > 1) {
        const mid = (lo + hi) >> 1;
        if (t[mid] <= tq) lo = mid;
        else hi = mid;
      }
      const span = t[hi] - t[lo];
      return [lo, span > 0 ? (tq - t[lo]) / span : 0];
    }

    function fill(i, f) {
      const i1 = Math.min(i + 1, n - 1);
      const g = 1 - f;
      st.i = i;
      st.f = f;
      st.t = t[i] * g + t[i1] * f;
      for (let k = 0; k < parts.length; k++) {
        const a = pose[k];
        for (let c = 0; c < 3; c++) st.pose[3 * k + c] = a[3 * i + c] * g + a[3 * i1 + c] * f;
      }
      for (let k = 0; k < beams.length; k++) {
        const a = nodes[k];
        const d = st.disp[k];
        const w = d.length;
        if (!a) continue;
        for (let j = 0; j < w; j++) d[j] = (a[i * w + j] || 0) * g + (a[i1 * w + j] || 0) * f;
      }
      for (const [name, cols] of Object.entries(contact)) {
        const out = st.contact[name];
        for (const [col, a] of Object.entries(cols)) {
          out[col] = (a[i] || 0) * g + (a[i1] || 0) * f;
        }
      }
      return st;
    }

    return {
      t,
      n,
      t0: t[0],
      t1: t[n - 1],
      pose,
      nodes,
      contact,
      locate,
      at: (tq) => {
        const [i, f] = locate(tq);
        fill(i, f);
        st.t = n > 1 ? clamp(tq, t[0], t[n - 1]) : t[0];
        return st;
      },
      atIndex: (i) => fill(i, 0),
    };
  }

  /** World positions of anchors in a state. */
  function makeGeometry(scene) {
    const parts = scene.parts;
    const beams = scene.beams;
    /** World position of point `at` of part k (k < 0: the world). */
    function partPoint(st, k, at) {
      if (k < 0 || !parts[k]) return [at[0], at[1]];
      const com = parts[k].com;
      const x = st.pose[3 * k];
      const y = st.pose[3 * k + 1];
      const th = st.pose[3 * k + 2];
      const c = Math.cos(th);
      const s = Math.sin(th);
      const dx = at[0] - com[0];
      const dy = at[1] - com[1];
      return [x + c * dx - s * dy, y + s * dx + c * dy];
    }
    /** World position of node j of beam b, its displacement magnified `mag` times. */
    function nodePoint(st, b, j, mag) {
      const beam = beams[b];
      const q = beam.nodes[j] || beam.nodes[beam.nodes.length - 1];
      const d = st.disp[b];
      const u = (d[2 * j] || 0) * mag;
      const v = (d[2 * j + 1] || 0) * mag;
      const p = beam.part >= 0 ? partPoint(st, beam.part, q) : q;
      return [p[0] + u, p[1] + v];
    }
    const isNode = (a) => a && a.beam !== undefined;
    /** World position of an anchor (beam displacements magnified `mag` times). */
    function anchorPoint(st, a, mag) {
      return isNode(a) ? nodePoint(st, a.beam, a.node, mag) : partPoint(st, a.part, a.at);
    }
    /** Part index an anchor moves with (−1: the ground or a ground beam). */
    function anchorPart(a) {
      return isNode(a) ? (beams[a.beam] ? beams[a.beam].part : -1) : a.part;
    }
    /** Angle of the frame an anchor is given in (node rotations are not recorded). */
    function anchorAngle(st, a) {
      const k = anchorPart(a);
      return k >= 0 ? st.pose[3 * k + 2] : 0;
    }
    function partAngle(st, k) {
      return k >= 0 ? st.pose[3 * k + 2] : 0;
    }
    function com(st, k) {
      return k >= 0 ? [st.pose[3 * k], st.pose[3 * k + 1]] : null;
    }
    return { partPoint, nodePoint, anchorPoint, anchorPart, anchorAngle, partAngle, com, isNode };
  }

  /** World geometry of the contact shapes (`scene.shapes`): each moves with the part (or beam
   * node) it is attached to, by the same transform as the part's own points. */
  function makeShapes(scene, geo) {
    const list = scene.shapes || [];
    /** Origin (world; beam displacements magnified `mag` times) and angle of shape i's frame,
     * null for a shape without one (a beam face: drawn as its beam). */
    function frame(st, i, mag) {
      const sh = list[i];
      if (!sh || !sh.at) return null;
      return { o: geo.anchorPoint(st, sh.at, mag), a: geo.anchorAngle(st, sh.at) + num(sh.angle, 0) };
    }
    /** The outlines of shape i in the world: [{pts, closed}] (none without a frame). */
    function world(st, i, mag) {
      const f = frame(st, i, mag);
      if (!f) return [];
      const c = Math.cos(f.a);
      const s = Math.sin(f.a);
      return list[i].outlines.map((ol) => ({
        closed: ol.closed,
        pts: ol.points.map((q) => [f.o[0] + c * q[0] - s * q[1], f.o[1] + s * q[0] + c * q[1]]),
      }));
    }
    /** Part index shape i moves with (−1: the ground or a ground beam). */
    const part = (i) => (list[i] && list[i].at ? geo.anchorPart(list[i].at) : -1);
    // the convex hull of each outline's points (shape frame), at most 96 of them: the bounds
    const hulls = list.map((sh) => {
      const hull = convexHull([].concat(...sh.outlines.map((ol) => ol.points)));
      const step = Math.ceil(hull.length / 96);
      return step > 1 ? hull.filter((_, k) => k % step === 0) : hull;
    });
    /** Points of shape i (world) whose box holds its outline. */
    function extent(st, i) {
      const f = frame(st, i, 1);
      if (!f) return [];
      const c = Math.cos(f.a);
      const s = Math.sin(f.a);
      return hulls[i].map((q) => [f.o[0] + c * q[0] - s * q[1], f.o[1] + s * q[0] + c * q[1]]);
    }
    return { list, frame, world, part, extent };
  }

  const rot = (th, v) => {
    const c = Math.cos(th);
    const s = Math.sin(th);
    return [c * v[0] - s * v[1], s * v[0] + c * v[1]];
  };
  const unit = (v) => {
    const l = Math.hypot(v[0], v[1]);
    return l > 0 ? [v[0] / l, v[1] / l] : [1, 0];
  };
  const wrapAngle = (a) => a - TAU * Math.round(a / TAU);
  const num = (v, dflt) => (isNum(v) ? v : dflt);

  /** One pass over all frames: the bounds of everything drawn (for the fit), the travel of
   * every slider along its guide, the peak contact force (force scale) and the default
   * magnifications. */
  function analyse(scene, motion, geo) {
    const b = [Infinity, Infinity, -Infinity, -Infinity];
    const add = (p) => {
      if (!isNum(p[0]) || !isNum(p[1])) return;
      b[0] = Math.min(b[0], p[0]);
      b[1] = Math.min(b[1], p[1]);
      b[2] = Math.max(b[2], p[0]);
      b[3] = Math.max(b[3], p[1]);
    };
    const travel = new Map();
    const beamMax = scene.beams.map(() => 0);
    const moving = scene.beams.map((bm) => bm.nodes.map(() => false));
    for (let k = 0; k < motion.n; k++) {
      const st = motion.atIndex(k);
      scene.parts.forEach((p, i) => {
        add(geo.com(st, i));
        if (p.kind !== 'flexible') for (const q of p.points) add(geo.partPoint(st, i, q));
      });
      scene.beams.forEach((bm, i) => {
        const d = st.disp[i];
        for (let j = 0; j < bm.nodes.length; j++) {
          add(geo.nodePoint(st, i, j, 1));
          const m = Math.hypot(d[2 * j], d[2 * j + 1]);
          if (m > 0) moving[i][j] = true;
          beamMax[i] = Math.max(beamMax[i], m);
        }
      });
      for (let i = 0; i < geo.shapes.list.length; i++) for (const p of geo.shapes.extent(st, i)) add(p);
      for (const it of scene.items) {
        for (const a of Object.values(it.anchors)) add(geo.anchorPoint(st, a, 1));
        const s = sliderCoordinate(it, st, geo);
        if (s !== null) {
          const r = travel.get(it) || [Infinity, -Infinity];
          travel.set(it, [Math.min(r[0], s), Math.max(r[1], s)]);
        }
      }
    }
    for (const g of scene.ground) add(g);
    if (!(b[2] >= b[0])) b.splice(0, 4, -0.5, -0.5, 0.5, 0.5);
    // sizes beyond the anchors: bearing housings, slider rectangles, beam depths
    let pad = 0;
    for (const it of scene.items) {
      const P = it.params;
      pad = Math.max(pad, 1.35 * num(P.bearing_radius, 0), 0.6 * num(P.slider_length, 0),
        num(P.guide_width, 0), num(P.slider_height, 0));
    }
    for (const bm of scene.beams) pad = Math.max(pad, num(bm.depth, 0));
    const bounds = [b[0] - pad, b[1] - pad, b[2] + pad, b[3] + pad];

    // peak contact force over the run (normal or friction) for the default force scale
    let fmax = 0;
    for (const cols of Object.values(motion.contact)) {
      for (const key of ['normal_force', 'friction_force']) {
        for (const v of cols[key] || []) if (isNum(v)) fmax = Math.max(fmax, Math.abs(v));
      }
    }

    // deformation magnification: the largest displacement of the run ~5 % of its beam length
    let magD = Infinity;
    scene.beams.forEach((bm, i) => {
      let len = 0;
      for (let j = 1; j < bm.nodes.length; j++) {
        len += Math.hypot(bm.nodes[j][0] - bm.nodes[j - 1][0], bm.nodes[j][1] - bm.nodes[j - 1][1]);
      }
      if (beamMax[i] > 0 && len > 0) magD = Math.min(magD, (0.05 * len) / beamMax[i]);
    });
    magD = isFinite(magD) ? Math.max(1, magD) : 1;

    // clearance magnification (one for all): the radial clearance ~8 % of the bearing radius,
    // from the revolute clearances when there are any (translational ones: of the half guide
    // width); the smallest, so that no clearance is drawn too wide
    let magC = Infinity;
    let magCMax = 1;
    const sized = scene.items.map((it) => [it, clearanceSize(it)]).filter(([, cl]) => cl);
    const ruling = sized.some(([it]) => it.kind === 'revolute') ? sized.filter(([it]) => it.kind === 'revolute') : sized;
    for (const [, cl] of ruling) magC = Math.min(magC, (0.08 * cl.r) / cl.c);
    for (const [, cl] of sized) magCMax = Math.max(magCMax, (0.85 * cl.r) / cl.c);
    magC = isFinite(magC) ? Math.max(1, magC) : 1;

    return { bounds, travel, fmax, magD, magC, magCMax, beamMax, moving, contact: motion.contact };
  }

  /** Radial clearance c and reference radius r of a clearance element (null without one). */
  function clearanceSize(it) {
    if (it.section !== 'clearance') return null;
    const P = it.params;
    if (it.kind === 'revolute' && isNum(P.bearing_radius) && isNum(P.journal_radius)) {
      const c = P.bearing_radius - P.journal_radius;
      return c > 0 ? { c, r: P.bearing_radius } : null;
    }
    if (it.kind === 'translational' && isNum(P.guide_width) && isNum(P.slider_height)) {
      const c = (P.guide_width - P.slider_height) / 2;
      return c > 0 ? { c, r: P.guide_width / 2 } : null;
    }
    return null;
  }

  /** Position of a slider along its guide axis (translational joints and clearances), from the
   * guide anchor, in the guide frame; null for other items. */
  function sliderCoordinate(it, st, geo) {
    let a;
    let b;
    let u;
    if (it.section === 'joint' && it.kind === 'translational' && it.anchors.a && it.anchors.b) {
      a = it.anchors.a;
      b = it.anchors.b;
      u = rot(geo.anchorAngle(st, a), unit(it.params.axis || [1, 0]));
    } else if (it.section === 'clearance' && it.kind === 'translational' && it.anchors.guide && it.anchors.slider) {
      a = it.anchors.guide;
      b = it.anchors.slider;
      u = rot(geo.anchorAngle(st, a) + num(it.params.guide_angle, 0), [1, 0]);
    } else {
      return null;
    }
    const pa = geo.anchorPoint(st, a, 1);
    const pb = geo.anchorPoint(st, b, 1);
    return (pb[0] - pa[0]) * u[0] + (pb[1] - pa[1]) * u[1];
  }

  // ===== canvas primitives (screen pixels, y down) ==============================================

  function circlePath(ctx, x, y, r) {
    ctx.beginPath();
    ctx.arc(x, y, Math.max(r, 0.1), 0, TAU);
  }

  /** Arrow from (x0, y0) to (x1, y1) with a filled head at the end. */
  function arrow(ctx, x0, y0, x1, y1, colour, width = 2, head = 9) {
    const dx = x1 - x0;
    const dy = y1 - y0;
    const l = Math.hypot(dx, dy);
    if (!(l > 1)) return;
    const ux = dx / l;
    const uy = dy / l;
    const hl = Math.min(head, 0.6 * l);
    ctx.strokeStyle = colour;
    ctx.fillStyle = colour;
    ctx.lineWidth = width;
    ctx.lineCap = 'round';
    ctx.beginPath();
    ctx.moveTo(x0, y0);
    ctx.lineTo(x1 - ux * hl * 0.8, y1 - uy * hl * 0.8);
    ctx.stroke();
    ctx.beginPath();
    ctx.moveTo(x1, y1);
    ctx.lineTo(x1 - ux * hl - uy * hl * 0.45, y1 - uy * hl + ux * hl * 0.45);
    ctx.lineTo(x1 - ux * hl + uy * hl * 0.45, y1 - uy * hl - ux * hl * 0.45);
    ctx.closePath();
    ctx.fill();
  }

  /** A curved arrow around (x, y) turning counter-clockwise on screen (positive rotation in
   * the y-up world): three quarters of a circle with the head at its end. */
  function curvedArrow(ctx, x, y, r, colour, width = 1.8) {
    const a0 = 0.25 * Math.PI;
    const a1 = -1.25 * Math.PI;
    ctx.strokeStyle = colour;
    ctx.fillStyle = colour;
    ctx.lineWidth = width;
    ctx.beginPath();
    ctx.arc(x, y, r, a0, a1 + 0.25, true);
    ctx.stroke();
    const ex = x + r * Math.cos(a1);
    const ey = y + r * Math.sin(a1);
    // direction of travel at the end (the angle decreases)
    const dx = Math.sin(a1);
    const dy = -Math.cos(a1);
    const hl = 7;
    ctx.beginPath();
    ctx.moveTo(ex + dx * 2, ey + dy * 2);
    ctx.lineTo(ex - dx * hl - dy * hl * 0.5, ey - dy * hl + dx * hl * 0.5);
    ctx.lineTo(ex - dx * hl + dy * hl * 0.5, ey - dy * hl - dx * hl * 0.5);
    ctx.closePath();
    ctx.fill();
  }

  /** Spring zigzag between two screen points. */
  function zigzag(ctx, x0, y0, x1, y1, colour, coils = 6, amp = 5) {
    const l = Math.hypot(x1 - x0, y1 - y0);
    ctx.strokeStyle = colour;
    ctx.lineWidth = 1.5;
    ctx.lineJoin = 'round';
    ctx.beginPath();
    ctx.moveTo(x0, y0);
    if (l > 4) {
      const ux = (x1 - x0) / l;
      const uy = (y1 - y0) / l;
      const lead = Math.min(8, 0.15 * l);
      const body = l - 2 * lead;
      ctx.lineTo(x0 + ux * lead, y0 + uy * lead);
      for (let k = 0; k < 2 * coils; k++) {
        const s = lead + (body * (k + 0.5)) / (2 * coils);
        const side = k % 2 ? -amp : amp;
        ctx.lineTo(x0 + ux * s - uy * side, y0 + uy * s + ux * side);
      }
      ctx.lineTo(x1 - ux * lead, y1 - uy * lead);
    }
    ctx.lineTo(x1, y1);
    ctx.stroke();
  }

  /** Ground symbol under a point: a triangle on a hatched base. */
  function groundSymbol(ctx, x, y) {
    ctx.strokeStyle = GROUND.stroke;
    ctx.fillStyle = GROUND.fill;
    ctx.lineWidth = 1.3;
    ctx.beginPath();
    ctx.moveTo(x, y);
    ctx.lineTo(x - 8, y + 13);
    ctx.lineTo(x + 8, y + 13);
    ctx.closePath();
    ctx.fill();
    ctx.stroke();
    hatchedBase(ctx, x, y + 13, 0);
  }

  /** A hatched wall line of half length 12 px through (x, y) at screen angle `a` (hatch on
   * the side of +normal). */
  function hatchedBase(ctx, x, y, a) {
    const ux = Math.cos(a);
    const uy = Math.sin(a);
    const nx = -uy;
    const ny = ux;
    ctx.strokeStyle = GROUND.stroke;
    ctx.lineWidth = 1.3;
    ctx.beginPath();
    ctx.moveTo(x - 12 * ux, y - 12 * uy);
    ctx.lineTo(x + 12 * ux, y + 12 * uy);
    for (let k = -2; k <= 3; k++) {
      const px = x + (k * 4.8 - 1) * ux;
      const py = y + (k * 4.8 - 1) * uy;
      ctx.moveTo(px, py);
      ctx.lineTo(px - 5 * ux - 6 * nx, py - 5 * uy - 6 * ny);
    }
    ctx.stroke();
  }

  /** Pin (revolute joint): a small white circle. */
  function pin(ctx, x, y, r = 4.5) {
    circlePath(ctx, x, y, r);
    ctx.fillStyle = '#fff';
    ctx.fill();
    ctx.strokeStyle = INK;
    ctx.lineWidth = 1.5;
    ctx.stroke();
  }

  /** Centre-of-mass mark: a circle with two filled quadrants. */
  function comMark(ctx, x, y, r = 4) {
    circlePath(ctx, x, y, r);
    ctx.fillStyle = '#fff';
    ctx.fill();
    ctx.fillStyle = INK;
    ctx.beginPath();
    ctx.moveTo(x, y);
    ctx.arc(x, y, r, 0, Math.PI / 2);
    ctx.closePath();
    ctx.moveTo(x, y);
    ctx.arc(x, y, r, Math.PI, 1.5 * Math.PI);
    ctx.closePath();
    ctx.fill();
    circlePath(ctx, x, y, r);
    ctx.strokeStyle = INK;
    ctx.lineWidth = 1;
    ctx.stroke();
  }

  /** Rectangle centred at (x, y), half sizes (hx, hy), rotated by screen angle a. */
  function rectPath(ctx, x, y, hx, hy, a) {
    const c = Math.cos(a);
    const s = Math.sin(a);
    ctx.beginPath();
    for (const [px, py] of [[-hx, -hy], [hx, -hy], [hx, hy], [-hx, hy]]) {
      ctx.lineTo(x + c * px - s * py, y + s * px + c * py);
    }
    ctx.closePath();
  }

  /** A rounded convex outline: the hull widened by r px, with an outline (a stroke with round
   * joins draws the Minkowski sum with a disc; the fill colour must be opaque). */
  function roundedHull(ctx, pts, r, colours) {
    ctx.lineJoin = 'round';
    ctx.lineCap = 'round';
    ctx.beginPath();
    pts.forEach(([x, y], k) => (k ? ctx.lineTo(x, y) : ctx.moveTo(x, y)));
    if (pts.length > 2) ctx.closePath();
    ctx.strokeStyle = colours.stroke;
    ctx.lineWidth = 2 * r + 2.5;
    ctx.stroke();
    ctx.strokeStyle = colours.fill;
    ctx.lineWidth = 2 * r;
    ctx.stroke();
    if (pts.length > 2) {
      ctx.fillStyle = colours.fill;
      ctx.fill();
    }
  }

  /** Text with a white halo (readable over drawings). */
  function label(ctx, text, x, y, colour = INK) {
    ctx.font = '11px system-ui, sans-serif';
    ctx.textBaseline = 'middle';
    ctx.textAlign = 'left';
    ctx.lineJoin = 'round';
    ctx.lineWidth = 3;
    ctx.strokeStyle = 'rgba(255,255,255,0.9)';
    ctx.strokeText(text, x, y);
    ctx.fillStyle = colour;
    ctx.fillText(text, x, y);
  }

  /** Convex hull (Andrew's monotone chain), counter-clockwise. */
  function convexHull(points) {
    const p = points.slice().sort((a, b) => a[0] - b[0] || a[1] - b[1]);
    if (p.length < 3) return p;
    const cross = (o, a, b) => (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
    const lower = [];
    for (const q of p) {
      while (lower.length >= 2 && cross(lower[lower.length - 2], lower[lower.length - 1], q) <= 0) lower.pop();
      lower.push(q);
    }
    const upper = [];
    for (let k = p.length - 1; k >= 0; k--) {
      const q = p[k];
      while (upper.length >= 2 && cross(upper[upper.length - 2], upper[upper.length - 1], q) <= 0) upper.pop();
      upper.push(q);
    }
    return lower.slice(0, -1).concat(upper.slice(0, -1));
  }

  /** Points without near duplicates (tolerance a millionth of their extent). */
  function uniquePoints(points) {
    let ext = 0;
    for (const p of points) ext = Math.max(ext, Math.abs(p[0]), Math.abs(p[1]));
    const tol = Math.max(ext, 1e-9) * 1e-6;
    const out = [];
    for (const p of points) {
      if (!out.some((q) => Math.abs(q[0] - p[0]) <= tol && Math.abs(q[1] - p[1]) <= tol)) out.push(p);
    }
    return out;
  }

  // ===== the drawable elements ==================================================================

  // Drawing passes in order; every element draws in the passes it has a function for.
  const PASSES = ['under', 'body', 'over', 'joint', 'symbol', 'force', 'label'];
  // Bearings smaller than this on screen are drawn at this radius (symbol, not to scale).
  const MIN_BEARING_PX = 6;
  const BAR_PX = 7; // half width of a part's outline bar

  /** The elements of a scene with their drawing functions. Each function gets the drawing
   * context `D` = {ctx, st, s, S(p) → screen, magC, magD, forcePx (px per N), names}. */
  function makeElements(scene, geo, info) {
    const els = [];
    const parts = scene.parts;
    const colours = parts.map((_, k) => partColours(k));
    const colourOf = (k) => (k >= 0 && colours[k] ? colours[k] : GROUND);

    // largest bearing radius on each part (a one-point part is drawn as a block around it)
    const bearingOn = parts.map(() => 0);
    // parts drawn by a clearance as a slider rectangle (no block of their own)
    const sliderPart = parts.map(() => false);
    for (const it of scene.items) {
      if (it.section !== 'clearance') continue;
      if (it.kind === 'revolute' && it.anchors.bearing) {
        const k = geo.anchorPart(it.anchors.bearing);
        if (k >= 0 && !geo.isNode(it.anchors.bearing)) {
          bearingOn[k] = Math.max(bearingOn[k], num(it.params.bearing_radius, 0));
        }
      }
      if ((it.kind === 'translational' || it.kind === 'slider_on_beam') && it.anchors.slider) {
        const k = geo.anchorPart(it.anchors.slider);
        if (k >= 0) sliderPart[k] = true;
      }
    }
    // parts that carry a contact shape: the shape is their drawing (no block of their own)
    const shapes = geo.shapes;
    const shaped = parts.map(() => false);
    shapes.list.forEach((sh, i) => {
      const k = shapes.part(i);
      if (k >= 0 && sh.outlines.length) shaped[k] = true;
    });
    const hulls = parts.map((p) => convexHull(uniquePoints(p.points.concat([p.com]))));
    const isBlock = (k) => k >= 0 && parts[k].kind === 'rigid' && hulls[k].length === 1 && !sliderPart[k] && !shaped[k];
    /** Half sizes (px) of the block drawn for a one-point part. */
    const blockSize = (D, k) => {
      const r = bearingOn[k] > 0 ? Math.max(bearingOn[k] * D.s, MIN_BEARING_PX) : 0;
      return [Math.max(14, 1.55 * r), Math.max(9, 1.3 * r)];
    };

    // ---- rigid parts: rounded outline through their attachment points, com marked
    parts.forEach((p, k) => {
      if (p.kind === 'flexible') return;
      const hull = hulls[k];
      els.push({
        body(D) {
          if (hull.length === 1) {
            if (sliderPart[k] || shaped[k]) return;
            const [x, y] = D.S(geo.com(D.st, k));
            const [hx, hy] = blockSize(D, k);
            rectPath(D.ctx, x, y, hx, hy, -geo.partAngle(D.st, k));
            D.ctx.fillStyle = colours[k].fill;
            D.ctx.fill();
            D.ctx.strokeStyle = colours[k].stroke;
            D.ctx.lineWidth = 1.5;
            D.ctx.stroke();
            return;
          }
          roundedHull(D.ctx, hull.map((q) => D.S(geo.partPoint(D.st, k, q))), BAR_PX, colours[k]);
        },
        symbol(D) {
          const [x, y] = D.S(geo.com(D.st, k));
          comMark(D.ctx, x, y);
        },
        label(D) {
          if (!D.names) return;
          const [x, y] = D.S(geo.com(D.st, k));
          label(D.ctx, p.name, x + 7, y - 10, colours[k].stroke);
        },
      });
    });

    // ---- beams: a band of the section depth along the deformed centre line
    scene.beams.forEach((bm, b) => {
      const c = bm.part >= 0 ? colourOf(bm.part) : GROUND;
      const line = (D, mag) => bm.nodes.map((_, j) => D.S(geo.nodePoint(D.st, b, j, mag)));
      const mid = Math.floor(bm.nodes.length / 2);
      els.push({
        // the undeformed shape of a flexible body moves with its frame (ground beams: background)
        under(D) {
          if (bm.part < 0) return;
          dashedLine(D.ctx, line(D, 0));
        },
        body(D) {
          const pts = line(D, D.magD);
          const w = Math.max(num(bm.depth, 0) * D.s, 3);
          const ctx = D.ctx;
          ctx.lineJoin = 'round';
          ctx.lineCap = 'butt';
          ctx.beginPath();
          pts.forEach(([x, y], j) => (j ? ctx.lineTo(x, y) : ctx.moveTo(x, y)));
          ctx.strokeStyle = c.stroke;
          ctx.lineWidth = w + 2;
          ctx.stroke();
          ctx.strokeStyle = c.mid;
          ctx.lineWidth = w;
          ctx.stroke();
        },
        label(D) {
          if (!D.names) return;
          const [x, y] = D.S(geo.nodePoint(D.st, b, mid, D.magD));
          label(D.ctx, bm.name, x + 4, y - Math.max(num(bm.depth, 0) * D.s, 3) / 2 - 8, c.stroke);
        },
      });
    });

    // ---- contact shapes: their outlines with their part, filled lightly (ground shapes grey
    // and hatched, under everything), outlined in the contact colour while in contact
    shapes.list.forEach((sh, i) => {
      if (!sh.at || !sh.outlines.length) return;
      const k = shapes.part(i);
      const c = colourOf(k);
      const contacts = scene.items.filter((it) => it.section === 'clearance' && (it.shapes || []).includes(i)).map((it) => it.name);
      // a shape fixed to the ground is filled on the background canvas (under the scale bar)
      const fixed = k < 0 && !geo.isNode(sh.at);
      const draw = (D, fill, stroke) => {
        const outlines = shapes.world(D.st, i, D.magD).map((ol) => ({ closed: ol.closed, pts: ol.pts.map(D.S) }));
        const on = stroke && contacts.some((name) => {
          const con = contactOf(D, name);
          return con && con.on;
        });
        shapeOutline(D.ctx, outlines, c, k < 0, on, fill, stroke);
      };
      const el = {
        label(D) {
          const f = shapes.frame(D.st, i, D.magD);
          if (!D.names || !f) return;
          const [x, y] = D.S(f.o);
          label(D.ctx, sh.name, x + 6, y + 12, c.stroke);
        },
      };
      if (fixed) {
        el.background = (D) => draw(D, true, false);
        el.under = (D) => draw(D, false, true);
      } else {
        el[k < 0 ? 'under' : 'body'] = (D) => draw(D, true, true);
      }
      els.push(el);
    });

    // ground points: drawn over the parts that hinge on them (static, but cheap)
    const ground = uniquePoints(scene.ground);
    els.push({
      over(D) {
        for (const g of ground) {
          const [x, y] = D.S(g);
          groundSymbol(D.ctx, x, y);
        }
      },
    });

    for (const it of scene.items) {
      const el = itemElement(it, geo, info, { colourOf, isBlock, blockSize, shapes });
      if (el) els.push(el);
    }
    return els;
  }

  function dashedLine(ctx, pts) {
    ctx.save();
    ctx.setLineDash([5, 4]);
    ctx.strokeStyle = 'rgba(60,74,94,0.55)';
    ctx.lineWidth = 1.2;
    ctx.beginPath();
    pts.forEach(([x, y], j) => (j ? ctx.lineTo(x, y) : ctx.moveTo(x, y)));
    ctx.stroke();
    ctx.restore();
  }

  /** Screen direction of a world vector (y flipped), unit length. */
  const screenDir = (v) => unit([v[0], -v[1]]);

  /** The drawing of one joint, driver, force or clearance. */
  function itemElement(it, geo, info, shared) {
    const A = it.anchors;
    const P = it.params;
    const B = it.bodies;
    const at = (D, a) => D.S(geo.anchorPoint(D.st, a, D.magD));
    const nameLabel = (D, p, dx = 8, dy = -10, colour = INK) => {
      if (D.names && p) label(D.ctx, it.name, p[0] + dx, p[1] + dy, colour);
    };
    const firstAnchor = A.a || A.at || A.b || Object.values(A)[0];
    const bodyCom = (D, k) => (k >= 0 ? D.S(geo.com(D.st, k)) : null);
    const key = `${it.section}:${it.kind}`;

    switch (key) {
      case 'joint:revolute':
        return {
          joint(D) {
            const p = at(D, A.a || A.b);
            pin(D.ctx, p[0], p[1]);
          },
          label: (D) => nameLabel(D, at(D, A.a || A.b), 7, 10),
        };
      case 'joint:fixed':
        return {
          joint(D) {
            const [x, y] = at(D, A.a || A.b);
            D.ctx.fillStyle = INK;
            D.ctx.fillRect(x - 4, y - 4, 8, 8);
          },
          label: (D) => nameLabel(D, at(D, A.a || A.b), 7, 10),
        };
      case 'joint:translational':
        return translationalJoint(it, geo, info, shared);
      case 'driver:angle':
      case 'driver:relative_angle': {
        const k = key === 'driver:angle' ? B.body : B.body_j;
        return {
          symbol(D) {
            const p = bodyCom(D, k);
            if (p) curvedArrow(D.ctx, p[0], p[1], 15, DRIVE);
          },
          label: (D) => nameLabel(D, bodyCom(D, k), 14, 14, DRIVE),
        };
      }
      case 'driver:displacement':
        return {
          symbol(D) {
            if (!A.a || !A.b) return;
            const u = screenDir(rot(geo.anchorAngle(D.st, A.a), unit(P.axis || [1, 0])));
            const [x, y] = at(D, A.b);
            arrow(D.ctx, x + u[0] * 8, y + u[1] * 8, x + u[0] * 38, y + u[1] * 38, DRIVE, 2);
          },
          label: (D) => A.b && nameLabel(D, at(D, A.b), 8, 14, DRIVE),
        };
      case 'force:spring_damper':
        return {
          symbol(D) {
            const p = at(D, A.a);
            const q = at(D, A.b);
            zigzag(D.ctx, p[0], p[1], q[0], q[1], SPRING);
          },
          label: (D) => {
            const p = at(D, A.a);
            const q = at(D, A.b);
            nameLabel(D, [(p[0] + q[0]) / 2, (p[1] + q[1]) / 2], 6, -12, SPRING);
          },
        };
      case 'force:actuator':
        return {
          symbol(D) {
            const p = at(D, A.a);
            const q = at(D, A.b);
            doubleLine(D.ctx, p, q, LOAD);
          },
          label: (D) => {
            const p = at(D, A.a);
            const q = at(D, A.b);
            nameLabel(D, [(p[0] + q[0]) / 2, (p[1] + q[1]) / 2], 6, -12, LOAD);
          },
        };
      case 'force:bushing':
        return {
          symbol(D) {
            const p = at(D, A.a);
            const q = at(D, A.b);
            const ctx = D.ctx;
            ctx.strokeStyle = SPRING;
            ctx.lineWidth = 1.3;
            ctx.beginPath();
            ctx.moveTo(p[0], p[1]);
            ctx.lineTo(q[0], q[1]);
            ctx.stroke();
            circlePath(ctx, q[0], q[1], 5);
            ctx.lineWidth = 1.8;
            ctx.stroke();
            ctx.save();
            ctx.setLineDash([3, 2]);
            circlePath(ctx, q[0], q[1], 9);
            ctx.lineWidth = 1.3;
            ctx.stroke();
            ctx.restore();
          },
          label: (D) => nameLabel(D, at(D, A.b), 10, 12, SPRING),
        };
      case 'force:force':
      case 'force:nodal_load': {
        // the load's time function is not in the scene: fx, fy drawn when constant numbers,
        // otherwise a symbol pointing at the point (down and to the right)
        const dir = isNum(P.fx) || isNum(P.fy) ? screenDir([num(P.fx, 0), num(P.fy, 0)]) : unit([1, 1]);
        const where = (D) =>
          key === 'force:force'
            ? A.at && at(D, A.at)
            : B.beam >= 0 && isNum(P.node) && D.S(geo.nodePoint(D.st, B.beam, P.node, D.magD));
        return {
          symbol(D) {
            const p = where(D);
            if (p) arrow(D.ctx, p[0] - dir[0] * 34, p[1] - dir[1] * 34, p[0] - dir[0] * 3, p[1] - dir[1] * 3, LOAD, 2.2);
          },
          label: (D) => {
            const p = where(D);
            if (p) nameLabel(D, [p[0] - dir[0] * 34, p[1] - dir[1] * 34], -4, -9, LOAD);
          },
        };
      }
      case 'force:torque':
      case 'force:torque_between': {
        const k = key === 'force:torque' ? B.body : B.body_j;
        return {
          symbol(D) {
            const p = bodyCom(D, k);
            if (p) curvedArrow(D.ctx, p[0], p[1], 11, LOAD, 1.6);
          },
          label: (D) => nameLabel(D, bodyCom(D, k), 12, 16, LOAD),
        };
      }
      case 'force:rotational_spring_damper': {
        const k = B.body_j >= 0 ? B.body_j : B.body_i;
        return {
          symbol(D) {
            const p = bodyCom(D, k);
            if (p) spiral(D.ctx, p[0], p[1], SPRING);
          },
          label: (D) => nameLabel(D, bodyCom(D, k), 12, 16, SPRING),
        };
      }
      case 'clearance:revolute':
        return A.bearing && A.journal ? revoluteClearance(it, geo, shared) : genericItem(it, geo);
      case 'clearance:translational':
        return A.guide && A.slider ? translationalClearance(it, geo, info, shared) : genericItem(it, geo);
      case 'clearance:slider_on_beam':
        return A.slider && B.beam >= 0 ? sliderOnBeam(it, geo, shared) : genericItem(it, geo);
      case 'clearance:contact':
        return (it.shapes || []).length === 2 ? shapeContact(it, info, shared) : null;
      default:
        return firstAnchor ? genericItem(it, geo) : null;
    }
  }

  /** A kind without its own symbol: dashed links between its anchors. */
  function genericItem(it, geo) {
    const anchors = Object.values(it.anchors);
    return {
      symbol(D) {
        const pts = anchors.map((a) => D.S(geo.anchorPoint(D.st, a, D.magD)));
        const ctx = D.ctx;
        ctx.save();
        ctx.setLineDash([4, 3]);
        ctx.strokeStyle = '#667';
        ctx.lineWidth = 1.3;
        ctx.beginPath();
        pts.forEach(([x, y], j) => (j ? ctx.lineTo(x, y) : ctx.moveTo(x, y)));
        ctx.stroke();
        ctx.restore();
        for (const [x, y] of pts) {
          circlePath(ctx, x, y, 2.5);
          ctx.fillStyle = '#667';
          ctx.fill();
        }
      },
      label(D) {
        if (!D.names || !anchors.length) return;
        const [x, y] = D.S(geo.anchorPoint(D.st, anchors[0], D.magD));
        label(D.ctx, `${it.name} (${it.kind})`, x + 6, y + 10, '#556');
      },
    };
  }

  function doubleLine(ctx, p, q, colour) {
    const l = Math.hypot(q[0] - p[0], q[1] - p[1]);
    if (!(l > 1)) return;
    const nx = -(q[1] - p[1]) / l;
    const ny = (q[0] - p[0]) / l;
    ctx.strokeStyle = colour;
    ctx.lineWidth = 1.6;
    ctx.lineCap = 'butt';
    ctx.beginPath();
    for (const s of [-3, 3]) {
      ctx.moveTo(p[0] + nx * s, p[1] + ny * s);
      ctx.lineTo(q[0] + nx * s, q[1] + ny * s);
    }
    // end caps
    for (const e of [p, q]) {
      ctx.moveTo(e[0] + nx * 5, e[1] + ny * 5);
      ctx.lineTo(e[0] - nx * 5, e[1] - ny * 5);
    }
    ctx.stroke();
  }

  function spiral(ctx, x, y, colour) {
    ctx.strokeStyle = colour;
    ctx.lineWidth = 1.5;
    ctx.beginPath();
    for (let k = 0; k <= 60; k++) {
      const a = (k / 60) * 2.5 * TAU;
      const r = 2 + (k / 60) * 9;
      const px = x + r * Math.cos(a);
      const py = y - r * Math.sin(a);
      if (k) ctx.lineTo(px, py);
      else ctx.moveTo(px, py);
    }
    ctx.stroke();
  }

  /** Extent of a slider's travel along its guide, with a margin (world units). */
  function guideSpan(info, it, D, extra) {
    const r = info.travel.get(it) || [0, 0];
    const margin = Math.max(0.12 * (r[1] - r[0]), 28 / D.s) + extra;
    return [r[0] - margin, r[1] + margin];
  }

  /** Ideal translational joint: a guide line along the axis through anchor a, a block at b
   * (a one-point slider part is its own block: then the guide is a slot around it). */
  function translationalJoint(it, geo, info, shared) {
    const A = it.anchors;
    const axis = unit(it.params.axis || [1, 0]);
    const kb = geo.anchorPart(A.b);
    const frame = (D) => {
      const p = geo.anchorPoint(D.st, A.a, D.magD);
      const u = rot(geo.anchorAngle(D.st, A.a), axis);
      return { p, u, su: screenDir(u) };
    };
    return {
      under(D) {
        const { p, u, su } = frame(D);
        const [s0, s1] = guideSpan(info, it, D, 0);
        const a = D.S([p[0] + u[0] * s0, p[1] + u[1] * s0]);
        const b = D.S([p[0] + u[0] * s1, p[1] + u[1] * s1]);
        const ctx = D.ctx;
        ctx.strokeStyle = GROUND.stroke;
        ctx.lineCap = 'butt';
        const offsets = shared.isBlock(kb) ? [-1, 1].map((s) => s * (shared.blockSize(D, kb)[1] + 2)) : [0];
        ctx.lineWidth = offsets.length > 1 ? 1.6 : 2;
        ctx.beginPath();
        for (const o of offsets) {
          ctx.moveTo(a[0] - su[1] * o, a[1] + su[0] * o);
          ctx.lineTo(b[0] - su[1] * o, b[1] + su[0] * o);
        }
        ctx.stroke();
        // the axis passes through anchor a, which may lie off the slider's travel
        if (s0 > 0 || s1 < 0) {
          const o = D.S(p);
          dashedLine(ctx, [o, s0 > 0 ? a : b]);
        }
      },
      joint(D) {
        if (shared.isBlock(kb)) return;
        const { su } = frame(D);
        const [x, y] = D.S(geo.anchorPoint(D.st, A.b, D.magD));
        rectPath(D.ctx, x, y, 12, 6, Math.atan2(su[1], su[0]));
        D.ctx.fillStyle = '#fff';
        D.ctx.fill();
        D.ctx.strokeStyle = INK;
        D.ctx.lineWidth = 1.5;
        D.ctx.stroke();
      },
      label(D) {
        if (!D.names) return;
        const [x, y] = D.S(geo.anchorPoint(D.st, A.b, D.magD));
        label(D.ctx, it.name, x + 8, y + 14);
      },
    };
  }

  /** Contact state of a clearance element in the current state: {on, fn, ft} or null. */
  function contactOf(D, name) {
    const c = D.st.contact[name];
    if (!c) return null;
    const fn = num(c.normal_force, 0);
    return { on: num(c.contact, 0) > 0 || fn > 0, fn, ft: num(c.friction_force, 0) };
  }

  /** Normal and friction force arrows (screen) at point p: normal along screen direction n,
   * friction along screen direction t (signed force). */
  function forceArrows(D, p, n, fn, t, ft) {
    const ln = fn * D.forcePx;
    if (ln >= 2) arrow(D.ctx, p[0], p[1], p[0] + n[0] * ln, p[1] + n[1] * ln, CONTACT, 2.2);
    const lt = ft * D.forcePx;
    if (Math.abs(lt) >= 2) arrow(D.ctx, p[0], p[1], p[0] + t[0] * lt, p[1] + t[1] * lt, FRICTION, 2);
  }

  /** Revolute clearance joint: bearing circle at the bearing anchor, journal circle at the
   * bearing centre + m·e with the clearance drawn m times larger (journal radius R − m·c). */
  function revoluteClearance(it, geo, shared) {
    const A = it.anchors;
    const R = num(it.params.bearing_radius, 0);
    const r = num(it.params.journal_radius, R);
    const c = Math.max(R - r, 0);
    const kb = geo.anchorPart(A.bearing);
    const kj = geo.anchorPart(A.journal);
    /** Eccentricity e = journal − bearing centre (world, m): the recorded ex, ey are in the
     * bearing frame (clr-mbd ContactReport), else from the anchors. */
    const ecc = (st, mag) => {
      const cc = st.contact[it.name];
      if (cc && isNum(cc.ex) && isNum(cc.ey)) return rot(geo.anchorAngle(st, A.bearing), [cc.ex, cc.ey]);
      const b = geo.anchorPoint(st, A.bearing, mag);
      const j = geo.anchorPoint(st, A.journal, mag);
      return [j[0] - b[0], j[1] - b[1]];
    };
    /** Screen geometry: bearing centre and radius, journal centre and radius, e (world). */
    const shape = (D) => {
      const b = D.S(geo.anchorPoint(D.st, A.bearing, D.magD));
      const e = ecc(D.st, D.magD);
      // too small to see: drawn at a minimum size, offsets scaled alike
      const k = R > 0 ? Math.max(1, MIN_BEARING_PX / (R * D.s)) : 1;
      const m = c > 0 ? D.magC : 1;
      const Rpx = R * D.s * k;
      const rpx = Math.max((R - m * c) * D.s * k, 0.15 * Rpx);
      const j = [b[0] + m * k * e[0] * D.s, b[1] - m * k * e[1] * D.s];
      return { b, Rpx, j, rpx, e };
    };
    journals.set(it.name, (st) => {
      const b = geo.anchorPoint(st, A.bearing, 1);
      const e = ecc(st, 1);
      return [b[0] + e[0], b[1] + e[1]];
    });
    return {
      over(D) {
        const { b, Rpx, j, rpx } = shape(D);
        const ctx = D.ctx;
        const cb = shared.colourOf(kb);
        // bearing housing: a ring around the hole
        ctx.beginPath();
        ctx.arc(b[0], b[1], Rpx * 1.32, 0, TAU);
        ctx.arc(b[0], b[1], Rpx, 0, TAU, true);
        ctx.fillStyle = cb.mid;
        ctx.fill();
        circlePath(ctx, b[0], b[1], Rpx * 1.32);
        ctx.strokeStyle = cb.stroke;
        ctx.lineWidth = 1;
        ctx.stroke();
        circlePath(ctx, b[0], b[1], Rpx);
        ctx.fillStyle = '#fff';
        ctx.fill();
        ctx.lineWidth = 1.4;
        ctx.stroke();
        // journal
        const con = contactOf(D, it.name);
        circlePath(ctx, j[0], j[1], rpx);
        ctx.fillStyle = shared.colourOf(kj).fill;
        ctx.fill();
        ctx.strokeStyle = con && con.on ? CONTACT : shared.colourOf(kj).stroke;
        ctx.lineWidth = con && con.on ? 2 : 1.4;
        ctx.stroke();
        circlePath(ctx, j[0], j[1], 1.6);
        ctx.fillStyle = INK;
        ctx.fill();
      },
      force(D) {
        const con = contactOf(D, it.name);
        if (!con || !con.on) return;
        const { j, rpx, e } = shape(D);
        const le = Math.hypot(e[0], e[1]);
        if (!(le > 0)) return;
        // force on the journal: −F_N n + F_T t, n = e/|e|, t = k × n (clr-contact revolute)
        const n = [e[0] / le, e[1] / le];
        const sn = [n[0], -n[1]];
        const st = screenDir([-n[1], n[0]]);
        const p = [j[0] + sn[0] * rpx, j[1] + sn[1] * rpx];
        forceArrows(D, p, [-sn[0], -sn[1]], con.fn, st, con.ft);
      },
      label(D) {
        if (!D.names) return;
        const { b, Rpx } = shape(D);
        label(D.ctx, it.name, b[0] + Rpx * 1.32 + 3, b[1] - Rpx - 6, CONTACT);
      },
    };
  }

  /** Translational clearance joint: guide walls ±W/2 about the centre line through the guide
   * anchor, slider rectangle L × h; the lateral offset, the tilt and the clearance are drawn
   * m times larger. */
  function translationalClearance(it, geo, info, shared) {
    const A = it.anchors;
    const P = it.params;
    const W = num(P.guide_width, 0);
    const L = num(P.slider_length, 0);
    const hS = num(P.slider_height, 0);
    const c = Math.max((W - hS) / 2, 0);
    const ks = geo.anchorPart(A.slider);
    const frame = (D) => {
      const o = geo.anchorPoint(D.st, A.guide, D.magD);
      const tg = geo.anchorAngle(D.st, A.guide) + num(P.guide_angle, 0);
      const s = geo.anchorPoint(D.st, A.slider, D.magD);
      const ts = geo.anchorAngle(D.st, A.slider) + num(P.slider_angle, 0);
      const ax = [Math.cos(tg), Math.sin(tg)];
      const ay = [-ax[1], ax[0]];
      const d = [s[0] - o[0], s[1] - o[1]];
      const x = d[0] * ax[0] + d[1] * ax[1];
      const y = d[0] * ay[0] + d[1] * ay[1];
      const m = c > 0 ? D.magC : 1;
      const centre = [o[0] + ax[0] * x + ay[0] * m * y, o[1] + ax[1] * x + ay[1] * m * y];
      return { o, ax, ay, tg, y, m, centre, angle: tg + m * wrapAngle(ts - tg), hw: hS / 2 + m * c };
    };
    return {
      under(D) {
        const f = frame(D);
        const [s0, s1] = guideSpan(info, it, D, L / 2);
        const ctx = D.ctx;
        const sa = Math.atan2(-f.ax[1], f.ax[0]);
        for (const side of [-1, 1]) {
          const p = (s) => D.S([f.o[0] + f.ax[0] * s + f.ay[0] * side * f.hw, f.o[1] + f.ax[1] * s + f.ay[1] * side * f.hw]);
          const a = p(s0);
          const b = p(s1);
          wall(ctx, a, b, side > 0 ? sa : sa + Math.PI);
        }
      },
      over(D) {
        const f = frame(D);
        drawSlider(D, it.name, f.centre, f.angle, L, hS, shared.colourOf(ks), 1.4);
      },
      force(D) {
        const con = contactOf(D, it.name);
        if (!con || !con.on) return;
        const f = frame(D);
        // the loaded side is the one the slider is off-centre towards; on it the force on
        // the slider is −F_N n + F_T t with n = ±a_y (outwards), t = k × n
        const side = f.y >= 0 ? 1 : -1;
        const n = [f.ay[0] * side, f.ay[1] * side];
        const t = [-n[1], n[0]];
        const p = D.S([f.centre[0] + n[0] * hS / 2, f.centre[1] + n[1] * hS / 2]);
        forceArrows(D, p, screenDir([-n[0], -n[1]]), con.fn, screenDir(t), con.ft);
      },
      label(D) {
        if (!D.names) return;
        const [x, y] = D.S(frame(D).centre);
        label(D.ctx, it.name, x + (L / 2) * D.s + 4, y - 10, CONTACT);
      },
    };
  }

  /** A guide wall from a to b (screen) hatched on the outer side (screen angle `a` of the
   * wall's direction, hatch to its left). */
  function wall(ctx, p, q, a) {
    const l = Math.hypot(q[0] - p[0], q[1] - p[1]);
    if (!(l > 1)) return;
    const ux = (q[0] - p[0]) / l;
    const uy = (q[1] - p[1]) / l;
    // outward normal: rotate the direction by −90° on screen (left of the wall seen along a)
    const nx = Math.sin(a);
    const ny = -Math.cos(a);
    ctx.strokeStyle = GROUND.stroke;
    ctx.lineWidth = 1.6;
    ctx.beginPath();
    ctx.moveTo(p[0], p[1]);
    ctx.lineTo(q[0], q[1]);
    ctx.stroke();
    ctx.lineWidth = 1;
    ctx.beginPath();
    for (let s = 4; s < l; s += 8) {
      const x = p[0] + ux * s;
      const y = p[1] + uy * s;
      ctx.moveTo(x, y);
      ctx.lineTo(x + nx * 6 - ux * 4, y + ny * 6 - uy * 4);
    }
    ctx.stroke();
  }

  /** A contact shape's outlines (screen points): with `fill`, the closed ones filled lightly in
   * the part's colour as one path (the parts of a compound overlap without darkening), grey
   * and hatched for the ground; with `stroke`, every outline stroked, in the contact colour
   * while `on`. */
  function shapeOutline(ctx, outlines, colour, ground, on, fill, stroke) {
    const path = (closedOnly) => {
      ctx.beginPath();
      for (const ol of outlines) {
        if (closedOnly && !ol.closed) continue;
        ol.pts.forEach(([x, y], j) => (j ? ctx.lineTo(x, y) : ctx.moveTo(x, y)));
        if (ol.closed) ctx.closePath();
      }
    };
    ctx.lineJoin = 'round';
    ctx.lineCap = 'round';
    if (fill && outlines.some((ol) => ol.closed)) {
      path(true);
      ctx.save();
      ctx.globalAlpha = ground ? 0.8 : 0.7;
      ctx.fillStyle = colour.fill;
      ctx.fill();
      ctx.restore();
      if (ground) {
        // hatch: lines at 45° every 7 px across the outlines' box, clipped to them
        let [x0, y0, x1, y1] = [Infinity, Infinity, -Infinity, -Infinity];
        for (const ol of outlines) {
          if (!ol.closed) continue;
          for (const [x, y] of ol.pts) {
            x0 = Math.min(x0, x);
            y0 = Math.min(y0, y);
            x1 = Math.max(x1, x);
            y1 = Math.max(y1, y);
          }
        }
        // only the part on the canvas (a long floor may reach far beyond it)
        x0 = Math.max(x0, -10);
        y0 = Math.max(y0, -10);
        x1 = Math.min(x1, ctx.canvas.width + 10);
        y1 = Math.min(y1, ctx.canvas.height + 10);
        if (x1 > x0 && y1 > y0) {
          ctx.save();
          path(true);
          ctx.clip();
          ctx.strokeStyle = colour.mid;
          ctx.lineWidth = 1;
          ctx.beginPath();
          for (let d = x0 - (y1 - y0); d < x1; d += 7) {
            ctx.moveTo(d, y1);
            ctx.lineTo(d + (y1 - y0), y0);
          }
          ctx.stroke();
          ctx.restore();
        }
      }
    }
    if (!stroke) return;
    ctx.strokeStyle = on ? CONTACT : colour.stroke;
    for (const ol of outlines) {
      ctx.lineWidth = on ? 1.8 : ol.closed ? 1.3 : 2;
      ctx.beginPath();
      ol.pts.forEach(([x, y], j) => (j ? ctx.lineTo(x, y) : ctx.moveTo(x, y)));
      if (ol.closed) ctx.closePath();
      ctx.stroke();
    }
  }

  /** The edge of `outlines` (world) nearest to p: {d, n, corner, closed} with n the edge's
   * unit normal to its right (outwards for a counter-clockwise polygon; at a vertex where the
   * outline turns by less than 25°, a curve drawn by chords, the mean of the two edges'), and
   * `corner` true when p is at a sharper vertex or an open outline's end. Null without edges. */
  function nearestEdge(outlines, p) {
    let best = null;
    for (const ol of outlines) {
      const P = ol.pts;
      const m = P.length;
      for (let j = 0; j < (ol.closed ? m : m - 1); j++) {
        const a = P[j];
        const b = P[(j + 1) % m];
        const v = [b[0] - a[0], b[1] - a[1]];
        const vv = v[0] * v[0] + v[1] * v[1];
        if (!(vv > 0)) continue;
        const u = clamp(((p[0] - a[0]) * v[0] + (p[1] - a[1]) * v[1]) / vv, 0, 1);
        const d = Math.hypot(a[0] + u * v[0] - p[0], a[1] + u * v[1] - p[1]);
        if (!best || d < best.d) best = { d, ol, j, u };
      }
    }
    if (!best) return null;
    const { ol, j, u } = best;
    const P = ol.pts;
    const m = P.length;
    const normal = (k) => {
      const a = P[(k + m) % m];
      const b = P[(k + 1 + m) % m];
      return unit([b[1] - a[1], a[0] - b[0]]);
    };
    const n = normal(j);
    const out = { d: best.d, n, corner: false, closed: ol.closed };
    if (u > 1e-4 && u < 1 - 1e-4) return out;
    // at a vertex: the edge before it (u = 0) or after it (u = 1)
    const other = u <= 1e-4 ? j - 1 : j + 1;
    if (!ol.closed && (other < 0 || other > m - 2)) {
      out.corner = true;
      return out;
    }
    const n2 = normal(other);
    if (n[0] * n2[0] + n[1] * n2[1] < Math.cos((25 * Math.PI) / 180)) out.corner = true;
    out.n = unit([n[0] + n2[0], n[1] + n2[1]]);
    return out;
  }

  /** Mean of the outlines' points (world), null without any. */
  function outlineCentre(outlines) {
    let x = 0;
    let y = 0;
    let k = 0;
    for (const ol of outlines) {
      for (const q of ol.pts) {
        x += q[0];
        y += q[1];
        k++;
      }
    }
    return k ? [x / k, y / k] : null;
  }

  /** Unit normal from shape A to shape B at the contact point p on A (world; the normal is not
   * recorded): the outline normal of A at p, or where p is at a corner of A (or A has no
   * outline: a beam face) minus the normal of B's nearest edge. Open outlines (polylines) are
   * two-sided: their normal is turned towards B (from A). Null without outlines. */
  function contactNormal(wa, wb, p) {
    const ea = nearestEdge(wa, p);
    const eb = nearestEdge(wb, p);
    const towards = (n, from, to) => {
      if (!from || !to) return n;
      return (to[0] - from[0]) * n[0] + (to[1] - from[1]) * n[1] < 0 ? [-n[0], -n[1]] : n;
    };
    if (ea && (!ea.corner || !eb)) return ea.closed ? ea.n : towards(ea.n, p, outlineCentre(wb));
    if (eb) {
      const n = [-eb.n[0], -eb.n[1]];
      return eb.closed ? n : towards(n, outlineCentre(wa), p);
    }
    return null;
  }

  /** Shape contact (`type = "contact"`, shapes [A, B]): at the deepest point on A (the recorded
   * ex, ey, world), a dot and the contact force on B, F_N along the normal n from A to B and
   * F_T along k × n (clr-mbd shape pairs; the normal force summed over the contact points is
   * drawn at the deepest one). */
  function shapeContact(it, info, shared) {
    const [ia, ib] = it.shapes;
    const shapes = shared.shapes;
    const raw = info.contact[it.name] || {};
    /** The contact point in a state, or null: between a frame with contact and one without
     * (whose ex, ey may be 0, 0: no point within the prediction distance) the frame with. */
    const point = (st) => {
      const c = st.contact[it.name];
      if (!c || !isNum(c.ex) || !isNum(c.ey)) return null;
      const on = (j) => raw.contact && raw.contact[j] > 0;
      if (raw.ex && raw.ey && raw.contact) {
        const i1 = Math.min(st.i + 1, raw.ex.length - 1);
        if (on(st.i) !== on(i1)) {
          const j = on(st.i) ? st.i : i1;
          return [raw.ex[j], raw.ey[j]];
        }
      }
      return [c.ex, c.ey];
    };
    /** {p, n} of the contact in a state (world, unmagnified), null when not in contact. */
    const mark = (st) => {
      const c = st.contact[it.name];
      if (!c || !(num(c.contact, 0) > 0 || num(c.normal_force, 0) > 0)) return null;
      const p = point(st);
      if (!p) return null;
      return { p, n: contactNormal(shapes.world(st, ia, 1), shapes.world(st, ib, 1), p) };
    };
    contactMarks.set(it.name, mark);
    return {
      force(D) {
        const con = contactOf(D, it.name);
        const m = con && con.on ? mark(D.st) : null;
        if (!m) return;
        const [x, y] = D.S(m.p);
        if (m.n) forceArrows(D, [x, y], screenDir(m.n), con.fn, screenDir([-m.n[1], m.n[0]]), con.ft);
        circlePath(D.ctx, x, y, 3);
        D.ctx.fillStyle = CONTACT;
        D.ctx.fill();
      },
      label(D) {
        if (!D.names) return;
        const m = mark(D.st);
        const f = shapes.frame(D.st, ia, D.magD) || shapes.frame(D.st, ib, D.magD);
        const p = m ? m.p : f && f.o;
        if (!p) return;
        const [x, y] = D.S(p);
        // above the shapes' names (at their origins, below)
        label(D.ctx, it.name, x + 8, y - 24, CONTACT);
      },
    };
  }

  /** Slider on a flexible beam's face. The slider is drawn where it is, moved with the
   * magnified beam deflection so that it stays on the drawn face. */
  function sliderOnBeam(it, geo, shared) {
    const A = it.anchors;
    const P = it.params;
    const b = it.bodies.beam;
    const L = num(P.slider_length, 0);
    const hS = num(P.slider_height, 0);
    const upper = P.face !== 'lower';
    const ks = geo.anchorPart(A.slider);
    const place = (D) => {
      const st = D.st;
      const s = geo.anchorPoint(st, A.slider, 1);
      const nodes = geo.nodesOf(st, b);
      // nearest segment of the deformed (true) centre line
      let best = { d: Infinity, j: 0, lam: 0 };
      for (let j = 0; j + 1 < nodes.length; j++) {
        const p = nodes[j];
        const q = nodes[j + 1];
        const v = [q[0] - p[0], q[1] - p[1]];
        const vv = v[0] * v[0] + v[1] * v[1];
        const lam = vv > 0 ? clamp(((s[0] - p[0]) * v[0] + (s[1] - p[1]) * v[1]) / vv, 0, 1) : 0;
        const d = Math.hypot(p[0] + v[0] * lam - s[0], p[1] + v[1] * lam - s[1]);
        if (d < best.d) best = { d, j, lam };
      }
      const { j, lam } = best;
      const j1 = Math.min(j + 1, nodes.length - 1);
      const disp = st.disp[b];
      const du = (1 - lam) * disp[2 * j] + lam * disp[2 * j1];
      const dv = (1 - lam) * disp[2 * j + 1] + lam * disp[2 * j1 + 1];
      const k = D.magD - 1;
      const tau = unit([nodes[j1][0] - nodes[j][0], nodes[j1][1] - nodes[j][1]]);
      // rotation of the segment by its deformation, magnified like the deflection
      const p0 = geo.nodePoint(st, b, j, 0);
      const p1 = geo.nodePoint(st, b, j1, 0);
      const a0 = Math.atan2(p1[1] - p0[1], p1[0] - p0[0]);
      const dRot = wrapAngle(Math.atan2(tau[1], tau[0]) - a0);
      const angle = geo.anchorAngle(st, A.slider) + num(P.slider_angle, 0) + k * dRot;
      const centre = [s[0] + k * du, s[1] + k * dv];
      return { centre, angle, tau: rot(k * dRot, tau) };
    };
    return {
      over(D) {
        const f = place(D);
        drawSlider(D, it.name, f.centre, f.angle, L, hS, shared.colourOf(ks), 1.2);
      },
      force(D) {
        const con = contactOf(D, it.name);
        if (!con || !con.on) return;
        const f = place(D);
        // n (the direction the slider penetrates the face) is −ν on the upper face, +ν on the
        // lower (ν the beam's left normal); force on the slider −F_N n + F_T t, t = k × n
        const nu = [-f.tau[1], f.tau[0]];
        const n = upper ? [-nu[0], -nu[1]] : nu;
        const t = [-n[1], n[0]];
        const p = D.S([f.centre[0] + n[0] * hS / 2, f.centre[1] + n[1] * hS / 2]);
        forceArrows(D, p, screenDir([-n[0], -n[1]]), con.fn, screenDir(t), con.ft);
      },
      label(D) {
        if (!D.names) return;
        const [x, y] = D.S(place(D).centre);
        label(D.ctx, it.name, x + (L / 2) * D.s + 3, y, CONTACT);
      },
    };
  }

  // journal centres (unmagnified, world) of the revolute clearances, for window.clrReport
  const journals = new Map();
  // contact point and normal ({p, n}, world) of the shape contacts in a state, null when apart
  const contactMarks = new Map();

  // ===== the stage: canvas, view, playback ======================================================

  function createStage(rep) {
    const scene = rep.scene;
    const motion = makeMotion(rep);
    const geo = makeGeometry(scene);
    geo.nodesOf = (st, b) => scene.beams[b].nodes.map((_, j) => geo.nodePoint(st, b, j, 1));
    geo.shapes = makeShapes(scene, geo);
    const info = analyse(scene, motion, geo);
    const els = makeElements(scene, geo, info);
    const isRun = rep.kind !== 'view' && motion.n > 1;
    const fmtTime = timeFormat(motion.t0, motion.t1, motion.n);

    const view = { s: 1, ox: 0, oy: 0, w: 1, h: 1, user: false };
    const opt = { magC: info.magC, magD: info.magD, force: 1, names: false };
    const pb = { t: motion.t0, playing: false, last: 0, mode: 'dur:10', listeners: [] };

    // ---- DOM
    const bg = h('canvas', { class: 'clr-bg' });
    const fg = h('canvas', { class: 'clr-fg' });
    const hud = h('div', { class: 'clr-hud' });
    const fitButton = h('button', { class: 'clr-btn clr-fit', type: 'button', title: 'fit the mechanism in view (double-click)', onclick: () => fit(true) }, icon(ICONS.fit, true), ' fit');
    const box = h('div', { class: 'clr-stage', tabindex: '0' }, bg, fg, hud, fitButton);
    const col = h('section', { class: 'clr-stage-col' }, box);

    let slider = null;
    let timeText = null;
    let playButton = null;
    if (isRun) col.appendChild(playbar());
    col.appendChild(controls());

    // ---- view
    function fit(redraw) {
      const [x0, y0, x1, y1] = info.bounds;
      const bw = Math.max(x1 - x0, 1e-12);
      const bh = Math.max(y1 - y0, 1e-12);
      const ref = Math.max(bw, bh);
      // a flat mechanism (all on a line) gets the other direction from its length
      view.s = Math.min((view.w * 0.9) / Math.max(bw, ref * 0.02), (view.h * 0.86) / Math.max(bh, ref * 0.02));
      view.ox = view.w / 2 - view.s * (x0 + x1) / 2;
      view.oy = view.h / 2 + view.s * (y0 + y1) / 2;
      view.user = false;
      if (redraw) redrawAll();
    }

    function resize() {
      const r = box.getBoundingClientRect();
      const w = Math.max(1, Math.round(r.width));
      const hgt = Math.max(1, Math.round(r.height));
      if (w === view.w && hgt === view.h && bg.width) return;
      // keep the centre of the view when the user has moved it, else fit again
      const cx = (view.w / 2 - view.ox) / view.s;
      const cy = (view.oy - view.h / 2) / view.s;
      view.w = w;
      view.h = hgt;
      for (const c of [bg, fg]) sizeCanvas(c, w, hgt);
      if (view.user) {
        view.ox = w / 2 - view.s * cx;
        view.oy = hgt / 2 + view.s * cy;
      } else {
        fit(false);
      }
      redrawAll();
    }

    const S = (p) => [view.ox + view.s * p[0], view.oy - view.s * p[1]];

    function drawContext(ctx, st) {
      return {
        ctx,
        st,
        s: view.s,
        S,
        magC: opt.magC,
        magD: opt.magD,
        forcePx: info.fmax > 0 ? ((0.15 * Math.min(view.w, view.h)) / info.fmax) * opt.force : 0,
        names: opt.names,
      };
    }

    // ---- background: what does not move (ground beams undeformed, their supports, the fills
    // of ground shapes, the scale)
    function drawBackground() {
      const ctx = bg.getContext('2d');
      ctx.clearRect(0, 0, view.w, view.h);
      const D = drawContext(ctx, motion.at(pb.t));
      for (const el of els) if (el.background) el.background(D);
      scene.beams.forEach((bm, b) => {
        if (bm.part >= 0) return;
        dashedLine(ctx, bm.nodes.map((q) => S(q)));
        drawSupports(ctx, bm, b);
      });
      scaleBar(ctx);
    }

    /** Supports of a ground beam are not in the scene: a node that never moves in a run where
     * the beam does is taken as supported (hatched wall across the beam). */
    function drawSupports(ctx, bm, b) {
      if (!(info.beamMax[b] > 0) || motion.n < 2) return;
      const last = bm.nodes.length - 1;
      info.moving[b].forEach((mv, j) => {
        if (mv) return;
        const p = S(bm.nodes[j]);
        const q = S(bm.nodes[j === last ? j - 1 : j + 1] || bm.nodes[j]);
        const a = Math.atan2(q[1] - p[1], q[0] - p[0]);
        const half = Math.max(num(bm.depth, 0) * view.s, 3) / 2 + 5;
        // a wall across the beam on the side away from it
        const ax = Math.cos(a + Math.PI / 2);
        const ay = Math.sin(a + Math.PI / 2);
        ctx.strokeStyle = GROUND.stroke;
        ctx.lineWidth = 2;
        ctx.beginPath();
        ctx.moveTo(p[0] - ax * half, p[1] - ay * half);
        ctx.lineTo(p[0] + ax * half, p[1] + ay * half);
        ctx.stroke();
        ctx.lineWidth = 1;
        ctx.beginPath();
        for (let s = -half; s <= half; s += 5) {
          const x = p[0] + ax * s;
          const y = p[1] + ay * s;
          ctx.moveTo(x, y);
          ctx.lineTo(x - Math.cos(a) * 6 - ax * 4, y - Math.sin(a) * 6 - ay * 4);
        }
        ctx.stroke();
      });
    }

    function scaleBar(ctx) {
      const len = niceStep(110 / view.s, 1);
      const px = len * view.s;
      const x = 14;
      const y = view.h - 16;
      ctx.strokeStyle = INK;
      ctx.lineWidth = 1.5;
      ctx.beginPath();
      ctx.moveTo(x, y - 4);
      ctx.lineTo(x, y);
      ctx.lineTo(x + px, y);
      ctx.lineTo(x + px, y - 4);
      ctx.stroke();
      label(ctx, lengthLabel(len), x + px + 6, y - 2);
    }

    // ---- foreground: everything that moves, per animation frame
    function drawForeground() {
      const ctx = fg.getContext('2d');
      ctx.clearRect(0, 0, view.w, view.h);
      const st = motion.at(pb.t);
      const D = drawContext(ctx, st);
      for (const pass of PASSES) {
        for (const el of els) if (el[pass]) el[pass](D);
      }
    }

    function redrawAll() {
      drawBackground();
      drawForeground();
      showTime();
    }

    function showTime() {
      clrReport.time = pb.t;
      const k = nearestFrame(pb.t);
      hud.textContent = isRun ? `t = ${fmtTime(pb.t)}` : `t0 = ${fmtTime(motion.t0)}`;
      if (timeText) timeText.textContent = `${fmtTime(pb.t)}  ·  frame ${k + 1}/${motion.n}`;
      if (slider && document.activeElement !== slider) slider.value = String(pb.t);
      for (const f of pb.listeners) f(pb.t);
      publishState(k);
    }

    /**
     * The drawn state in the DOM (a JSON script element with the id clr-state), for a headless browser that can
     * only dump the DOM (`chromium --dump-dom`, cargo xtask report-check): time, journal
     * centres (world, unmagnified), part poses of the nearest frame, the frame of every contact
     * shape ({origin, angle, outlines}: world, unmagnified, and how many outlines it has), the
     * point and normal of every shape contact ({p, n}, world; null when apart), script errors.
     */
    function publishState(k) {
      const state = { time: pb.t, journals: {}, parts: {}, shapes: {}, contacts: {}, errors: clrReport.errors };
      const st = motion.at(pb.t);
      for (const it of scene.items) {
        if (it.section === 'clearance' && it.kind === 'revolute') {
          const f = journals.get(it.name);
          state.journals[it.name] = f ? f(st) : null;
        }
        const mark = contactMarks.get(it.name);
        if (it.section === 'clearance' && mark) state.contacts[it.name] = mark(st);
      }
      geo.shapes.list.forEach((sh, i) => {
        const f = geo.shapes.frame(st, i, 1);
        if (f) state.shapes[sh.name] = { origin: f.o, angle: f.a, outlines: sh.outlines.length };
      });
      scene.parts.forEach((p, i) => {
        const pose = rep.frames.pose[i];
        state.parts[p.name] = [pose[3 * k], pose[3 * k + 1], pose[3 * k + 2]];
      });
      let el = document.getElementById('clr-state');
      if (!el) {
        el = document.createElement('script');
        el.id = 'clr-state';
        el.type = 'application/json';
        document.body.appendChild(el);
      }
      el.textContent = JSON.stringify(state);
    }

    function nearestFrame(t) {
      const [i, f] = motion.locate(t);
      return Math.min(f > 0.5 ? i + 1 : i, motion.n - 1);
    }

    let pending = false;
    function requestDraw() {
      if (pending) return;
      pending = true;
      requestAnimationFrame(() => {
        pending = false;
        drawForeground();
        showTime();
      });
    }

    function seek(t) {
      pb.t = clamp(isNum(t) ? t : motion.t0, motion.t0, motion.t1);
      clrReport.time = pb.t;
      requestDraw();
    }

    // ---- playback
    /** Advance of the playback per wall-clock second in the chosen mode. */
    function advance(dt) {
      const [kind, v] = pb.mode.split(':');
      const value = parseFloat(v);
      const span = motion.t1 - motion.t0;
      if (kind === 'fps') {
        // frames per second: step through the frame index
        const [i, f] = motion.locate(pb.t);
        const x = i + f + value * dt;
        if (x >= motion.n - 1) return null;
        const k = Math.floor(x);
        return motion.t[k] + (motion.t[Math.min(k + 1, motion.n - 1)] - motion.t[k]) * (x - k);
      }
      const rate = kind === 'dur' ? span / value : value;
      const t = pb.t + rate * dt;
      return t > motion.t1 ? null : t;
    }

    function tick(now) {
      if (!pb.playing) return;
      const dt = Math.min((now - pb.last) / 1000, 0.1);
      pb.last = now;
      const t = advance(dt);
      // the run loops
      pb.t = t === null ? motion.t0 : t;
      drawForeground();
      showTime();
      requestAnimationFrame(tick);
    }

    function setPlaying(on) {
      pb.playing = on && isRun;
      if (playButton) {
        playButton.replaceChildren(icon(pb.playing ? ICONS.pause : ICONS.play));
        playButton.title = pb.playing ? 'pause (space)' : 'play (space)';
      }
      if (pb.playing) {
        if (pb.t >= motion.t1) pb.t = motion.t0;
        pb.last = performance.now();
        requestAnimationFrame(tick);
      }
    }

    function step(dir) {
      setPlaying(false);
      const t = motion.t;
      const eps = 1e-9 * Math.max(motion.t1 - motion.t0, 1e-300);
      const [i] = motion.locate(pb.t);
      let k;
      if (dir > 0) {
        k = i;
        while (k < motion.n - 1 && t[k] <= pb.t + eps) k++;
      } else {
        k = Math.min(i + 1, motion.n - 1);
        while (k > 0 && t[k] >= pb.t - eps) k--;
      }
      seek(t[k]);
    }

    function playbar() {
      playButton = h('button', { class: 'clr-btn clr-play', type: 'button', onclick: () => setPlaying(!pb.playing) });
      slider = h('input', {
        class: 'clr-time', type: 'range', min: String(motion.t0), max: String(motion.t1), step: 'any',
        value: String(pb.t), 'aria-label': 'time',
        oninput: () => seek(parseFloat(slider.value)),
      });
      timeText = h('span', { class: 'clr-time-text' });
      const modes = [
        ['dur:5', 'whole run in 5 s'], ['dur:10', 'whole run in 10 s'], ['dur:30', 'whole run in 30 s'],
        ['dur:60', 'whole run in 60 s'], ['rt:1', '1× real time'], ['rt:0.1', '0.1× real time'],
        ['rt:0.01', '0.01× real time'], ['rt:0.001', '0.001× real time'], ['fps:10', '10 frames/s'],
        ['fps:30', '30 frames/s'], ['fps:60', '60 frames/s'],
      ];
      const speed = h('select', {
        class: 'clr-speed', title: 'playback speed', 'aria-label': 'playback speed',
        onchange: () => { pb.mode = speed.value; },
      }, modes.map(([v, t]) => h('option', { value: v, selected: v === pb.mode }, t)));
      return h('div', { class: 'clr-playbar' },
        h('button', { class: 'clr-btn', type: 'button', title: 'previous frame (←)', onclick: () => step(-1) }, icon(ICONS.back)),
        playButton,
        h('button', { class: 'clr-btn', type: 'button', title: 'next frame (→)', onclick: () => step(1) }, icon(ICONS.forward)),
        slider, timeText, speed);
    }

    function controls() {
      const items = [];
      const mag = (v) => `×${v < 10 ? v.toFixed(2) : v < 100 ? v.toFixed(1) : v.toFixed(0)}`;
      if (scene.items.some((it) => clearanceSize(it))) {
        const hi = Math.max(info.magCMax, info.magC * 2, 2);
        items.push(logControl('clearance magnification', 'the clearance (and the journal or slider offset in it) drawn this many times larger', 1, hi, opt.magC,
          (v) => { opt.magC = v; redrawAll(); }, mag));
      }
      if (scene.beams.length) {
        const hi = Math.max(info.magD * 10, 100);
        items.push(logControl('deformation magnification', 'beam deflections drawn this many times larger (undeformed shape dashed)', 1, hi, opt.magD,
          (v) => { opt.magD = v; redrawAll(); }, mag));
      }
      if (info.fmax > 0) {
        items.push(logControl('force scale', `contact force arrows (normal red, friction orange); at ×1 the largest force of the run, ${eng(info.fmax)} N, is 15 % of the view`, 0.05, 20, 1,
          (v) => { opt.force = v; requestDraw(); }, mag));
      }
      const names = h('input', { type: 'checkbox', class: 'clr-names', onchange: () => { opt.names = names.checked; requestDraw(); } });
      items.push(h('label', { class: 'clr-control clr-check' }, names, ' names'));
      const legend = h('div', { class: 'clr-legend' },
        info.fmax > 0 ? [h('span', { class: 'clr-key clr-key-normal' }, 'normal force'), h('span', { class: 'clr-key clr-key-friction' }, 'friction force')] : [],
        h('span', { class: 'clr-key clr-key-contact' }, 'in contact'),
        h('span', { class: 'clr-hint' }, 'drag to pan · wheel to zoom'));
      return h('div', { class: 'clr-controls' }, items, legend);
    }

    // ---- pan and zoom
    let drag = null;
    box.addEventListener('pointerdown', (e) => {
      if (e.button !== 0 || e.target !== fg) return;
      drag = { x: e.clientX, y: e.clientY };
      capture(box, e);
      box.classList.add('clr-dragging');
    });
    box.addEventListener('pointermove', (e) => {
      if (!drag) return;
      view.ox += e.clientX - drag.x;
      view.oy += e.clientY - drag.y;
      drag = { x: e.clientX, y: e.clientY };
      view.user = true;
      redrawAll();
    });
    const endDrag = () => {
      drag = null;
      box.classList.remove('clr-dragging');
    };
    box.addEventListener('pointerup', endDrag);
    box.addEventListener('pointercancel', endDrag);
    box.addEventListener('wheel', (e) => {
      e.preventDefault();
      const r = fg.getBoundingClientRect();
      const mx = e.clientX - r.left;
      const my = e.clientY - r.top;
      const dy = e.deltaMode === 1 ? e.deltaY * 16 : e.deltaMode === 2 ? e.deltaY * 400 : e.deltaY;
      const f = Math.exp(-clamp(dy, -300, 300) * 0.0015);
      view.s *= f;
      view.ox = mx - (mx - view.ox) * f;
      view.oy = my - (my - view.oy) * f;
      view.user = true;
      redrawAll();
    }, { passive: false });
    fg.addEventListener('dblclick', () => fit(true));

    // ---- keys: space plays, arrows step (not while typing in another control)
    document.addEventListener('keydown', (e) => {
      const tag = e.target && e.target.tagName;
      const other = (tag === 'INPUT' && e.target !== slider) || tag === 'SELECT' || tag === 'TEXTAREA' || tag === 'BUTTON';
      if (!isRun || other || e.ctrlKey || e.metaKey || e.altKey) return;
      if (e.key === ' ') {
        e.preventDefault();
        setPlaying(!pb.playing);
      } else if (e.key === 'ArrowRight' || e.key === 'ArrowLeft') {
        e.preventDefault();
        step(e.key === 'ArrowRight' ? 1 : -1);
      }
    });

    /** Hash parameters: `#t=0.012` starts at that time, paused; `zoom=8&at=0.35,0` shows the
     * view zoomed 8 times about a world point (links to a detail). */
    function hashParam(name) {
      const m = new RegExp(`(?:^#|&)${name}=([^&]+)`).exec(location.hash);
      return m ? decodeURIComponent(m[1]) : null;
    }
    function fromHash() {
      const t = parseFloat(hashParam('t'));
      if (!isNum(t)) return false;
      setPlaying(false);
      pb.t = clamp(t, motion.t0, motion.t1);
      return true;
    }
    function viewFromHash() {
      if (hashParam('names') === '1') {
        opt.names = true;
        const box = col.querySelector('.clr-names');
        if (box) box.checked = true;
      }
      const z = parseFloat(hashParam('zoom'));
      const at = (hashParam('at') || '').split(',').map(parseFloat);
      if (!isNum(z) && !(at.length === 2 && at.every(isNum))) return;
      fit(false);
      const c = at.length === 2 && at.every(isNum) ? at : [(view.w / 2 - view.ox) / view.s, (view.oy - view.h / 2) / view.s];
      if (isNum(z) && z > 0) view.s *= z;
      view.ox = view.w / 2 - view.s * c[0];
      view.oy = view.h / 2 + view.s * c[1];
      view.user = true;
    }
    window.addEventListener('hashchange', () => {
      if (fromHash()) requestDraw();
    });

    return {
      root: col,
      motion,
      fmtTime,
      onTime: (f) => pb.listeners.push(f),
      seek,
      /** Seek and draw at once (paused): for scripts and tests. */
      seekNow(t) {
        setPlaying(false);
        pb.t = clamp(isNum(t) ? t : motion.t0, motion.t0, motion.t1);
        drawForeground();
        showTime();
        return pb.t;
      },
      /** First layout and drawing (synchronous, so that the page is drawn when it loads). */
      start() {
        const hashed = fromHash();
        resize();
        viewFromHash();
        redrawAll();
        if (typeof ResizeObserver !== 'undefined') new ResizeObserver(() => resize()).observe(box);
        else window.addEventListener('resize', resize);
        setPlaying(isRun && !hashed);
      },
      journal(name) {
        const f = journals.get(name);
        return f ? f(motion.at(pb.t)) : null;
      },
    };
  }

  /** A logarithmic slider from lo to hi (value shown as ×v). */
  function logControl(name, title, lo, hi, value, onChange, fmt) {
    const steps = 1000;
    const toPos = (v) => String(Math.round((Math.log(v / lo) / Math.log(hi / lo)) * steps));
    const out = h('output', { class: 'clr-val' }, fmt(value));
    const input = h('input', {
      type: 'range', min: '0', max: String(steps), step: '1', value: toPos(value), 'aria-label': name,
      oninput: () => {
        const v = lo * (hi / lo) ** (parseFloat(input.value) / steps);
        out.textContent = fmt(v);
        onChange(v);
      },
    });
    const reset = h('button', {
      class: 'clr-link', type: 'button', title: 'back to the default',
      onclick: () => {
        input.value = toPos(value);
        out.textContent = fmt(value);
        onChange(value);
      },
    }, 'reset');
    return h('label', { class: 'clr-control', title }, h('span', { class: 'clr-control-name' }, name), input, out, reset);
  }

  /**
   * A slider rectangle L × h (m) at `centre` turned by `angle`, outlined in the contact colour
   * while its element `name` is in contact (translational clearances and sliders on beams).
   */
  function drawSlider(D, name, centre, angle, L, h, colour, lineWidth) {
    const [x, y] = D.S(centre);
    const con = contactOf(D, name);
    rectPath(D.ctx, x, y, (L / 2) * D.s, Math.max((h / 2) * D.s, 1.5), -angle);
    D.ctx.fillStyle = colour.fill;
    D.ctx.fill();
    D.ctx.strokeStyle = con && con.on ? CONTACT : colour.stroke;
    D.ctx.lineWidth = con && con.on ? 2 : lineWidth;
    D.ctx.stroke();
  }

  /** Keep receiving a pointer's events while it is dragged outside (not for every pointer:
   * synthetic ones cannot be captured, which is harmless). */
  function capture(el, e) {
    try {
      el.setPointerCapture(e.pointerId);
    } catch (_) {
      // dragging still works inside the element
    }
  }

  /** Size a canvas to w × h CSS px at the device pixel ratio; drawing is then in CSS px. */
  function sizeCanvas(canvas, w, hgt) {
    const d = window.devicePixelRatio || 1;
    canvas.width = Math.max(1, Math.round(w * d));
    canvas.height = Math.max(1, Math.round(hgt * d));
    canvas.style.width = `${w}px`;
    canvas.style.height = `${hgt}px`;
    canvas.getContext('2d').setTransform(d, 0, 0, d, 0, 0);
  }

  // ===== figures ================================================================================

  /** One figure of `plots`: the lines drawn once on a base canvas, the time cursor on an
   * overlay redrawn per frame. Time plots seek on click. */
  function makeFigure(plot, seek) {
    const lines = (plot.lines || []).filter((l) => l.x && l.y && l.x.length);
    const orbit = plot.cursor === 'orbit';
    const base = h('canvas', { class: 'clr-fig-base' });
    const over = h('canvas', { class: 'clr-fig-over' });
    const holder = h('div', { class: `clr-fig-canvas${seek ? ' clr-seekable' : ''}` }, base, over);
    const legend = h('div', { class: 'clr-fig-legend' }, lines.map((l, k) =>
      h('span', { class: 'clr-key' }, h('i', { style: `background:${PALETTE[k % PALETTE.length]}` }), l.label)));
    const el = h('figure', { class: 'clr-fig' }, h('figcaption', { text: plot.title }), holder, legend);
    const M = { l: 58, r: 10, t: 8, b: 36 };

    // data ranges (fixed); orbits keep the unit circle (the clearance) in view
    let [x0, x1, y0, y1] = [Infinity, -Infinity, Infinity, -Infinity];
    for (const l of lines) {
      for (let k = 0; k < l.x.length; k++) {
        const x = l.x[k];
        const y = l.y[k];
        if (!isNum(x) || !isNum(y)) continue;
        x0 = Math.min(x0, x); x1 = Math.max(x1, x);
        y0 = Math.min(y0, y); y1 = Math.max(y1, y);
      }
    }
    if (orbit) {
      x0 = Math.min(x0, -1.1); x1 = Math.max(x1, 1.1);
      y0 = Math.min(y0, -1.1); y1 = Math.max(y1, 1.1);
    }
    if (!(x1 >= x0)) [x0, x1] = [0, 1];
    if (!(y1 >= y0)) [y0, y1] = [0, 1];
    const widen = (a, b) => (b > a ? [a, b] : [a - (Math.abs(a) * 0.1 || 1), b + (Math.abs(b) * 0.1 || 1)]);
    [x0, x1] = widen(x0, x1);
    [y0, y1] = widen(y0, y1);
    if (!orbit) {
      const pad = 0.05 * (y1 - y0);
      y0 -= pad;
      y1 += pad;
    }

    let map = null; // {X, Y, invX, w, h}
    let lastT = null;

    function render(width) {
      const w = Math.max(160, Math.floor(width));
      const hgt = plot.equal ? Math.min(Math.round(w * 0.85), 380) : 190;
      sizeCanvas(base, w, hgt);
      sizeCanvas(over, w, hgt);
      holder.style.height = `${hgt}px`;
      const pw = w - M.l - M.r;
      const ph = hgt - M.t - M.b;
      let [a0, a1, b0, b1] = [x0, x1, y0, y1];
      if (plot.equal) {
        // one scale for both axes: widen the range that has fewer units per pixel
        const u = Math.max((a1 - a0) / pw, (b1 - b0) / ph);
        const cx = (a0 + a1) / 2;
        const cy = (b0 + b1) / 2;
        [a0, a1] = [cx - (u * pw) / 2, cx + (u * pw) / 2];
        [b0, b1] = [cy - (u * ph) / 2, cy + (u * ph) / 2];
      }
      const X = (x) => M.l + ((x - a0) / (a1 - a0)) * pw;
      const Y = (y) => M.t + ph - ((y - b0) / (b1 - b0)) * ph;
      map = { X, Y, invX: (px) => a0 + ((px - M.l) / pw) * (a1 - a0), w, h: hgt, a0, a1 };
      const ctx = base.getContext('2d');
      ctx.clearRect(0, 0, w, hgt);
      axes(ctx, a0, a1, b0, b1, X, Y, pw, ph);
      ctx.save();
      ctx.beginPath();
      ctx.rect(M.l, M.t, pw, ph);
      ctx.clip();
      if (orbit) {
        ctx.save();
        ctx.setLineDash([4, 3]);
        ctx.strokeStyle = '#888';
        ctx.lineWidth = 1;
        ctx.beginPath();
        ctx.ellipse(X(0), Y(0), Math.abs(X(1) - X(0)), Math.abs(Y(1) - Y(0)), 0, 0, TAU);
        ctx.stroke();
        ctx.restore();
      }
      lines.forEach((l, k) => {
        ctx.strokeStyle = PALETTE[k % PALETTE.length];
        ctx.lineWidth = 1.2;
        ctx.lineJoin = 'round';
        ctx.beginPath();
        let pen = false;
        for (let j = 0; j < l.x.length; j++) {
          if (!isNum(l.x[j]) || !isNum(l.y[j])) {
            pen = false;
            continue;
          }
          const px = X(l.x[j]);
          const py = Y(l.y[j]);
          if (pen) ctx.lineTo(px, py);
          else ctx.moveTo(px, py);
          pen = true;
        }
        ctx.stroke();
      });
      ctx.restore();
      if (lastT !== null) cursor(lastT);
    }

    function axes(ctx, a0, a1, b0, b1, X, Y, pw, ph) {
      ctx.strokeStyle = '#aab';
      ctx.lineWidth = 1;
      ctx.strokeRect(M.l + 0.5, M.t + 0.5, pw, ph);
      ctx.font = '10px system-ui, sans-serif';
      ctx.fillStyle = '#445';
      // as many x ticks as their labels leave room for
      let tx = ticks(a0, a1, clamp(Math.floor(pw / 70), 2, 10));
      let fx = tickFormat(Math.max(Math.abs(a0), Math.abs(a1)), tx.step);
      const widest = Math.max(...tx.values.map((v) => ctx.measureText(fx(v)).width));
      if ((widest + 14) * tx.values.length > pw) {
        tx = ticks(a0, a1, Math.max(2, Math.floor(pw / (widest + 14)) - 1));
        fx = tickFormat(Math.max(Math.abs(a0), Math.abs(a1)), tx.step);
      }
      ctx.textAlign = 'center';
      ctx.textBaseline = 'top';
      ctx.beginPath();
      for (const v of tx.values) {
        const x = Math.round(X(v)) + 0.5;
        const text = fx(v);
        const half = ctx.measureText(text).width / 2;
        ctx.moveTo(x, M.t + ph);
        ctx.lineTo(x, M.t + ph + 4);
        // the last label stays inside the canvas
        ctx.fillText(text, Math.min(x, M.l + pw + M.r - half - 1), M.t + ph + 6);
      }
      const ty = ticks(b0, b1, Math.max(2, Math.floor(ph / 34)));
      const fy = tickFormat(Math.max(Math.abs(b0), Math.abs(b1)), ty.step);
      ctx.textAlign = 'right';
      ctx.textBaseline = 'middle';
      for (const v of ty.values) {
        const y = Math.round(Y(v)) + 0.5;
        ctx.moveTo(M.l - 4, y);
        ctx.lineTo(M.l, y);
        ctx.fillText(fy(v), M.l - 6, y);
      }
      ctx.stroke();
      // light grid at the ticks, and the zero lines a little darker
      ctx.save();
      ctx.strokeStyle = 'rgba(0,0,40,0.07)';
      ctx.beginPath();
      for (const v of tx.values) {
        ctx.moveTo(Math.round(X(v)) + 0.5, M.t);
        ctx.lineTo(Math.round(X(v)) + 0.5, M.t + ph);
      }
      for (const v of ty.values) {
        ctx.moveTo(M.l, Math.round(Y(v)) + 0.5);
        ctx.lineTo(M.l + pw, Math.round(Y(v)) + 0.5);
      }
      ctx.stroke();
      ctx.restore();
      ctx.fillStyle = '#223';
      ctx.font = '11px system-ui, sans-serif';
      ctx.textAlign = 'center';
      ctx.textBaseline = 'bottom';
      ctx.fillText(plot.x_label || '', M.l + pw / 2, M.t + ph + M.b - 1);
      ctx.save();
      ctx.translate(11, M.t + ph / 2);
      ctx.rotate(-Math.PI / 2);
      ctx.textBaseline = 'middle';
      // a long label gets a smaller font rather than running off the plot
      const yl = plot.y_label || '';
      const size = clamp(Math.floor((11 * ph) / Math.max(ctx.measureText(yl).width, 1)), 8, 11);
      ctx.font = `${size}px system-ui, sans-serif`;
      ctx.fillText(yl, 0, 0, ph + M.b);
      ctx.restore();
    }

    /** Mark time t: a vertical line with the value of each line (time plots), or the point of
     * each orbit nearest in time. */
    function cursor(t) {
      lastT = t;
      if (!map) return;
      const ctx = over.getContext('2d');
      ctx.clearRect(0, 0, map.w, map.h);
      if (orbit) {
        const k = nearestIndex(plot.t || [], t);
        if (k < 0) return;
        lines.forEach((l, j) => {
          if (!isNum(l.x[k]) || !isNum(l.y[k])) return;
          dot(ctx, map.X(l.x[k]), map.Y(l.y[k]), PALETTE[j % PALETTE.length]);
        });
        return;
      }
      if (plot.cursor !== 'time') return;
      const x = map.X(t);
      if (x < M.l - 1 || x > map.w - M.r + 1) return;
      ctx.strokeStyle = 'rgba(20,20,40,0.7)';
      ctx.lineWidth = 1;
      ctx.beginPath();
      ctx.moveTo(Math.round(x) + 0.5, M.t);
      ctx.lineTo(Math.round(x) + 0.5, map.h - M.b);
      ctx.stroke();
      lines.forEach((l, j) => {
        const y = valueAt(l, t);
        if (isNum(y)) dot(ctx, x, map.Y(y), PALETTE[j % PALETTE.length], 3);
      });
    }

    function dot(ctx, x, y, colour, r = 4) {
      circlePath(ctx, x, y, r);
      ctx.fillStyle = colour;
      ctx.fill();
      ctx.strokeStyle = '#fff';
      ctx.lineWidth = 1.5;
      ctx.stroke();
    }

    // seeking: a time plot maps x to t; an orbit seeks to the time of the nearest point
    if (seek) {
      let down = false;
      const seekAt = (e) => {
        if (!map) return;
        const r = over.getBoundingClientRect();
        const px = e.clientX - r.left;
        const py = e.clientY - r.top;
        if (!orbit) {
          seek(map.invX(px));
          return;
        }
        let best = [Infinity, -1];
        for (const l of lines) {
          for (let k = 0; k < l.x.length; k++) {
            const d = (map.X(l.x[k]) - px) ** 2 + (map.Y(l.y[k]) - py) ** 2;
            if (d < best[0]) best = [d, k];
          }
        }
        if (best[1] >= 0 && plot.t && isNum(plot.t[best[1]])) seek(plot.t[best[1]]);
      };
      over.addEventListener('pointerdown', (e) => {
        down = true;
        capture(over, e);
        seekAt(e);
      });
      over.addEventListener('pointermove', (e) => {
        if (down && !orbit) seekAt(e);
      });
      over.addEventListener('pointerup', () => { down = false; });
      over.addEventListener('pointercancel', () => { down = false; });
    }

    return { el, render, cursor, holder };
  }

  /** Index of the value of sorted `t` nearest to `x` (−1 when empty). */
  function nearestIndex(t, x) {
    const n = t.length;
    if (!n) return -1;
    let lo = 0;
    let hi = n - 1;
    if (x <= t[0]) return 0;
    if (x >= t[n - 1]) return n - 1;
    while (hi - lo > 1) {
      const mid = (lo + hi) >> 1;
      if (t[mid] <= x) lo = mid;
      else hi = mid;
    }
    return x - t[lo] <= t[hi] - x ? lo : hi;
  }

  /** Value of a time line at t (linear between points; null outside). */
  function valueAt(line, t) {
    const x = line.x;
    const n = x.length;
    if (!n || t < x[0] || t > x[n - 1]) return null;
    const k = nearestIndex(x, t);
    const j = x[k] <= t ? k : k - 1;
    if (j < 0 || j + 1 >= n) return line.y[k];
    const span = x[j + 1] - x[j];
    const f = span > 0 ? (t - x[j]) / span : 0;
    return line.y[j] + (line.y[j + 1] - line.y[j]) * f;
  }

  // ===== the side panel =========================================================================

  function card(title, ...content) {
    return h('section', { class: 'clr-card' }, title ? h('h2', { text: title }) : null, ...content);
  }

  /** "peak_force_N" → "peak force [N]" (the column names of impacts.csv carry their unit). */
  function columnTitle(key) {
    const units = [['_m_per_s', 'm/s'], ['_N', 'N'], ['_s', 's'], ['_m', 'm'], ['_J', 'J']];
    for (const [suffix, u] of units) {
      if (key.endsWith(suffix)) return `${key.slice(0, -suffix.length).replace(/_/g, ' ')} [${u}]`;
    }
    return key.replace(/_/g, ' ');
  }

  function cell(v) {
    if (typeof v === 'number') return h('td', { class: 'clr-num', title: String(v) }, eng(v));
    if (v === null || v === undefined) return h('td');
    if (typeof v === 'object') return h('td', { text: JSON.stringify(v) });
    const s = String(v);
    if (/\.html?(#.*)?$/i.test(s)) return h('td', {}, h('a', { href: s }, s));
    return h('td', { text: s });
  }

  function metricsTable(metrics) {
    return h('table', { class: 'clr-table' },
      h('thead', {}, h('tr', {}, h('th', { text: 'metric' }), h('th', { class: 'clr-num', text: 'value' }), h('th', { text: 'unit' }))),
      h('tbody', {}, metrics.map((m) => h('tr', { title: m.description || '' },
        h('td', {}, h('span', { class: 'clr-metric-name', text: m.name })),
        h('td', { class: 'clr-num', title: `${m.value}` }, eng(m.value)),
        h('td', { text: m.unit || '' })))));
  }

  function impactsTable(impacts, seek) {
    const order = ['joint', 'onset_s', 'impact_velocity_m_per_s', 'peak_force_N', 'peak_force_time_s',
      'max_penetration_m', 'max_penetration_time_s', 'separation_s', 'duration_s'];
    const keys = [];
    for (const k of order) if (impacts.some((r) => k in r)) keys.push(k);
    for (const r of impacts) for (const k of Object.keys(r)) if (!keys.includes(k)) keys.push(k);
    const rows = impacts.slice(0, 200);
    const table = h('table', { class: 'clr-table clr-impacts' },
      h('thead', {}, h('tr', {}, keys.map((k) => h('th', { class: k === 'joint' ? '' : 'clr-num', text: columnTitle(k) })))),
      h('tbody', {}, rows.map((r) => h('tr', {
        class: seek && isNum(r.onset_s) ? 'clr-seekable' : '',
        title: seek && isNum(r.onset_s) ? 'show the onset' : '',
        onclick: seek && isNum(r.onset_s) ? () => seek(r.onset_s) : null,
      }, keys.map((k) => cell(r[k]))))));
    const note = impacts.length > rows.length
      ? h('p', { class: 'clr-note', text: `first ${rows.length} of ${impacts.length} impacts (all in impacts.csv)` })
      : h('p', { class: 'clr-note', text: `${impacts.length} impact${impacts.length === 1 ? '' : 's'}${seek ? ' · click a row to show its onset' : ''}` });
    return [note, h('div', { class: 'clr-scroll' }, table)];
  }

  /** The coordinates the assembly solved or corrected (initial_conditions of summary.json). */
  function initialConditions(ic) {
    if (!ic || typeof ic !== 'object') return null;
    const rows = [];
    for (const [body, coords] of Object.entries(ic.bodies || {})) {
      for (const [coord, c] of Object.entries(coords || {})) {
        if (c && c.status && c.status !== 'given') rows.push({ body, coord, ...c });
      }
    }
    const summary = [];
    if (isNum(ic.solved)) summary.push(`${ic.solved} solved`);
    if (isNum(ic.corrected)) summary.push(`${ic.corrected} corrected`);
    if (isNum(ic.position_newton_iterations)) summary.push(`${ic.position_newton_iterations} position Newton iterations`);
    const text = `${summary.join(', ')}${rows.length ? '' : ' — every coordinate as given'}`;
    const table = rows.length
      ? h('div', { class: 'clr-scroll' }, h('table', { class: 'clr-table' },
        h('thead', {}, h('tr', {}, ['body', 'coordinate', 'status', 'given', 'assembled', 'unit'].map((k) =>
          h('th', { class: k === 'given' || k === 'assembled' ? 'clr-num' : '', text: k })))),
        h('tbody', {}, rows.map((r) => h('tr', { class: `clr-ic-${r.status}` },
          h('td', { text: r.body }), h('td', { text: r.coord }), h('td', { text: r.status }),
          cell(r.given), cell(r.assembled), h('td', { text: r.unit || '' }))))))
      : null;
    return { rows, text, table };
  }

  function sweepSection(sweep) {
    const out = [];
    const table = Array.isArray(sweep.table) ? sweep.table.filter((r) => r && typeof r === 'object') : [];
    const links = Array.isArray(sweep.links) ? sweep.links.filter((l) => l && l.href) : [];
    if (table.length) {
      // the point's report linked from its row (by its `point` index, else by row order)
      const linkOf = (r, i) => (isNum(r.point) && links[r.point]) || (links.length === table.length && links[i]) || null;
      const rows = table.map((r, i) => {
        const l = linkOf(r, i);
        return l && !('report' in r) ? { ...r, report: l.href } : r;
      });
      // the swept parameters first, then the point, its status and the results
      const names = Array.isArray(sweep.names) ? sweep.names.filter((n) => typeof n === 'string') : [];
      const keys = [];
      for (const k of ['point', ...names, 'status']) if (rows.some((r) => k in r)) keys.push(k);
      for (const r of rows) for (const k of Object.keys(r)) if (!keys.includes(k) && k !== 'report') keys.push(k);
      if (rows.some((r) => 'report' in r)) keys.push('report');
      table.splice(0, table.length, ...rows);
      out.push(h('div', { class: 'clr-scroll' }, h('table', { class: 'clr-table' },
        h('thead', {}, h('tr', {}, keys.map((k) => h('th', {
          class: table.every((r) => typeof r[k] === 'number' || r[k] === undefined) ? 'clr-num' : '', text: k,
        })))),
        h('tbody', {}, table.map((r) => h('tr', {}, keys.map((k) =>
          (k === 'report' && typeof r[k] === 'string' ? h('td', {}, h('a', { href: r[k] }, 'open')) : cell(r[k])))))))));
    }
    if (links.length) {
      out.push(h('ul', { class: 'clr-links' }, links.map((l) => h('li', {}, h('a', { href: l.href }, l.label || l.href)))));
    }
    if (!out.length) out.push(h('p', { class: 'clr-note', text: 'the sweep has no table' }));
    return card('sweep', ...out);
  }

  function buildPanel(rep, stage) {
    const seek = stage ? stage.seek : null;
    const panel = h('aside', { class: 'clr-panel' });
    const view = rep.kind === 'view';

    // ---- the run
    const motion = stage && stage.motion;
    const status = rep.error
      ? h('p', { class: 'clr-status clr-status-error' }, h('strong', { text: 'stopped early: ' }), rep.error)
      : view
        ? h('p', { class: 'clr-status', text: 'initial state assembled at t0 (not simulated)' })
        : rep.kind === 'sweep'
          ? null
          : h('p', { class: 'clr-status clr-status-ok', text: motion
            ? `completed: t = ${eng(motion.t0)} … ${eng(motion.t1)} s, ${motion.n} frames drawn`
            : 'completed' });
    panel.appendChild(card(null,
      h('h2', { class: 'clr-model', text: rep.model || '(unnamed model)' }),
      h('p', { class: 'clr-source' }, h('span', { class: 'clr-badge', text: rep.kind || 'run' }), ' ', rep.source || ''),
      rep.description ? h('p', { class: 'clr-description', text: rep.description }) : null,
      status,
      rep.scene_note ? h('p', { class: 'clr-note', text: rep.scene_note }) : null));

    // ---- notes (a view lists them in its banner, up front)
    const notes = Array.isArray(rep.notes) ? rep.notes : [];
    if (notes.length && !view) {
      panel.appendChild(card('notes', h('ul', { class: 'clr-notes' }, notes.map((n) => h('li', { text: n })))));
    } else if (view && !notes.length) {
      panel.appendChild(card('initial-condition notes', h('p', { class: 'clr-note', text: 'none: the initial state was assembled as given' })));
    }

    const ic = initialConditions(rep.initial_conditions);
    if (ic && (view || ic.rows.length)) {
      const body = [h('p', { class: 'clr-note', text: ic.text }), ic.table];
      if (view) panel.appendChild(card('initial conditions', ...body));
      else panel.appendChild(h('details', { class: 'clr-card' }, h('summary', { text: `initial conditions (${ic.rows.length} solved or corrected)` }), ...body));
    }

    if (rep.sweep && typeof rep.sweep === 'object') panel.appendChild(sweepSection(rep.sweep));

    const metrics = Array.isArray(rep.metrics) ? rep.metrics : [];
    if (metrics.length) panel.appendChild(card('metrics', h('p', { class: 'clr-note', text: 'hover a row for its description' }), metricsTable(metrics)));

    const impacts = Array.isArray(rep.impacts) ? rep.impacts : [];
    if (!view && (impacts.length || rep.kind === 'run')) {
      panel.appendChild(card('impacts', ...(impacts.length ? impactsTable(impacts, seek) : [h('p', { class: 'clr-note', text: 'no impacts located' })])));
    }

    // ---- figures (a view has one point per line: nothing to plot)
    const plots = (Array.isArray(rep.plots) ? rep.plots : []).filter((p) =>
      (p.lines || []).some((l) => l.x && l.x.length > 1));
    const figures = plots.map((p) => makeFigure(p, p.cursor === 'time' || p.cursor === 'orbit' ? seek : null));
    if (figures.length) {
      const box = h('div', { class: 'clr-figures' }, figures.map((f) => f.el));
      panel.appendChild(card('figures', box));
      const layout = () => {
        for (const f of figures) f.render(f.holder.clientWidth || box.clientWidth || 400);
      };
      if (stage) stage.onTime((t) => figures.forEach((f) => f.cursor(t)));
      return { root: panel, layout, observe: box };
    }
    return { root: panel, layout: () => {}, observe: null };
  }

  // ===== the page ===============================================================================

  function main() {
    const rep = JSON.parse(document.getElementById('clr-data').textContent);
    const app = h('div', { class: `clr-app clr-kind-${rep.kind || 'run'}` });
    document.body.appendChild(app);
    app.appendChild(h('header', { class: 'clr-head' },
      h('h1', {}, h('span', { class: 'clr-logo', text: 'clr' }), ' ', rep.model || ''),
      h('span', { class: 'clr-badge', text: rep.kind || 'run' }),
      h('span', { class: 'clr-head-source', text: rep.source || '' })));
    if (rep.kind === 'view') {
      // a view is about the initial conditions: their notes go up front
      const notes = Array.isArray(rep.notes) ? rep.notes : [];
      app.appendChild(h('div', { class: 'clr-banner' }, h('strong', { text: 'initial state at t0 (not simulated)' }),
        ' — the model as assembled from its description; `clr run` simulates it.',
        notes.length ? h('ul', { class: 'clr-notes clr-notes-strong' }, notes.map((n) => h('li', { text: n }))) : null));
    }
    if (rep.error) app.appendChild(h('div', { class: 'clr-banner clr-banner-error', text: `the run stopped early: ${rep.error}` }));

    // a spatial page carries report3d.js, which draws the 3-D stage with the same helpers
    const kit = { h, icon, ICONS, eng, timeFormat, clamp, isNum, logControl, clrReport };
    const stage = rep.scene ? createStage(rep) : rep.spatial && window.clrSpatialStage ? window.clrSpatialStage(rep, kit) : null;
    const layout = h('main', { class: `clr-layout${stage ? '' : ' clr-no-stage'}` });
    app.appendChild(layout);
    if (stage) layout.appendChild(stage.root);
    const panel = buildPanel(rep, stage);
    layout.appendChild(panel.root);

    // journals for the headless test: world centre, without magnification
    clrReport.journal = (name) => (stage ? stage.journal(name) : null);
    clrReport.seek = (t) => (stage ? stage.seekNow(t) : null);

    panel.layout();
    if (panel.observe && typeof ResizeObserver !== 'undefined') {
      let width = 0;
      new ResizeObserver(() => {
        const w = panel.observe.clientWidth;
        if (w !== width) {
          width = w;
          panel.layout();
        }
      }).observe(panel.observe);
    }
    if (stage) stage.start();
  }

  try {
    main();
  } catch (e) {
    reportError(e && e.stack ? e.stack : e);
  } finally {
    clrReport.ready = true;
    document.title = `${document.title} [ready]`;
  }
})();
