// report3d.js: the 3-D stage of a spatial clr report (src/report/spatial.rs), drawn with
// three.js (the vendored bundle defines the global THREE; assets/three/README.md). report.js
// calls window.clrSpatialStage(rep, kit) in place of its planar stage when the page carries
// `rep.spatial`, and builds the side panel (metrics, impacts, figures) around the returned stage
// as for a planar page; `kit` lends its helpers (h, icon, eng, logControl, …).
//
// Data (spatial.rs): scene.bodies[k].points are in the body's centre-of-mass frame;
// frames.pose[k] is [x, y, z, qw, qx, qy, qz] per frame (world, body → world); frames.sockets[s]
// is [ex, ey, ez, F_N, ftx, fty, ftz, contact] per frame (e = ball − socket centre, world; the
// normal force acts on the ball along −e/|e|); frames.journals[j] is [F_A, F_B, F_thrust−,
// F_thrust+] per frame (normal forces of the journal's radial regions at the bore's low and high
// ends and of its thrust faces, N); frames.trace is the traced point [x, y, z] per frame.
// World axes are three.js's: y up.
//
// A headless test reads window.clrReport.spatial ({webgl, renders, ball(name), journal(name), body(name)}).
'use strict';
(() => {
  const COLOURS = [0x4f7fc8, 0xd9822b, 0x3c9a5f, 0x9b59b6, 0xc0392b, 0x16a0a0, 0x8d6e63, 0x7f8c8d];
  const CONTACT = 0xd62728; // --contact of report.css
  const FRICTION = 0xe07b00; // --friction of report.css
  const JOINT = 0x343a40;
  /** Camera directions (towards the camera) and up vectors of the named views. */
  const VIEWS = {
    // z up, as gravity along −z in spatial model files
    iso: { dir: [1, 1, 1], up: [0, 0, 1] },
    front: { dir: [0, -1, 0], up: [0, 0, 1] },
    top: { dir: [0, 0, 1], up: [0, 1, 0] },
    side: { dir: [1, 0, 0], up: [0, 0, 1] },
  };

  /** Frame index i and weight f of time tq in the sorted times t (t[i] ≤ tq ≤ t[i+1]). */
  function frameAt(t, tq) {
    const n = t.length;
    if (n < 2 || !(tq > t[0])) return [0, 0];
    if (tq >= t[n - 1]) return [n - 2, 1];
    let a = 0;
    let b = n - 1;
    while (b - a > 1) {
      const m = (a + b) >> 1;
      [a, b] = t[m] <= tq ? [m, b] : [a, m];
    }
    return [a, (tq - t[a]) / (t[b] - t[a] || 1)];
  }

  /** Body poses, socket values and the trace between frames (positions linear, rotations
   * normalised linear: the frames are close). */
  function makeMotion(view) {
    const fr = view.frames;
    const t = fr.t.length ? fr.t : [0];
    const n = t.length;
    const mix = (a, w, i, j, f) => a[w * i + j] * (1 - f) + a[w * Math.min(i + 1, n - 1) + j] * f;
    return {
      t, n, t0: t[0], t1: t[n - 1],
      locate: (tq) => frameAt(t, tq),
      /** Pose {p: Vector3, q: Quaternion} of body k at (i, f). */
      pose(k, i, f) {
        const a = fr.pose[k];
        if (!a || a.length < 7 * n) return null;
        const q0 = [3, 4, 5, 6].map((j) => a[7 * i + j]);
        const q1 = [3, 4, 5, 6].map((j) => a[7 * Math.min(i + 1, n - 1) + j]);
        const sign = q0.reduce((s, v, j) => s + v * q1[j], 0) < 0 ? -1 : 1;
        const q = q0.map((v, j) => v * (1 - f) + sign * q1[j] * f);
        return {
          p: new THREE.Vector3(mix(a, 7, i, 0, f), mix(a, 7, i, 1, f), mix(a, 7, i, 2, f)),
          q: new THREE.Quaternion(q[1], q[2], q[3], q[0]).normalize(),
        };
      },
      /** The eight socket values of socket s at (i, f). */
      socket(s, i, f) {
        const a = fr.sockets[s];
        return a && a.length >= 8 * n ? [0, 1, 2, 3, 4, 5, 6, 7].map((j) => mix(a, 8, i, j, f)) : null;
      },
      /** The four journal forces of journal j at (i, f). */
      journal(j, i, f) {
        const a = (fr.journals || [])[j];
        return a && a.length >= 4 * n ? [0, 1, 2, 3].map((c) => mix(a, 4, i, c, f)) : null;
      },
      trace(i, f) {
        const a = fr.trace;
        return a && a.length >= 3 * n ? new THREE.Vector3(mix(a, 3, i, 0, f), mix(a, 3, i, 1, f), mix(a, 3, i, 2, f)) : null;
      },
    };
  }

  /** The box of every attachment point, joint, socket and traced point over all frames. */
  function bounds(view, motion) {
    const sc = view.scene;
    const box = new THREE.Box3();
    const v = new THREE.Vector3();
    const poseOf = (name, i) => motion.pose(sc.bodies.findIndex((b) => b.name === name), i, 0);
    /** Add the point `at` of body `name` (null: the ground) in frame i, grown by r. */
    const add = (name, at, i, r) => {
      const p = name == null ? null : poseOf(name, i);
      v.set(...at);
      if (p) v.applyQuaternion(p.q).add(p.p);
      box.expandByPoint(v.clone().addScalar(r));
      box.expandByPoint(v.addScalar(-r));
    };
    const shapes = (sc.shapes || []).map((s) => [s, shapeRadius(s)]); // once, not per frame
    for (let i = 0; i < motion.n; i++) {
      for (const b of sc.bodies) {
        add(b.name, [0, 0, 0], i, 0);
        for (const a of b.points) add(b.name, a, i, 0);
      }
      for (const j of sc.joints) add(j.body, j.at, i, 0);
      for (const s of sc.sockets) add(s.socket_body, s.socket_at, i, s.socket_radius);
      for (const j of sc.journals || []) add(j.bearing_body, j.bearing_at, i, j.bearing_radius + 0.5 * j.bearing_length);
      shapes.forEach(([s, r]) => add(s.body, s.at, i, r));
      const tr = motion.trace(i, 0);
      if (tr) box.expandByPoint(tr);
    }
    box.expandByPoint(new THREE.Vector3(0, 0, 0));
    return box;
  }

  /** The largest distance of a shape's vertices from its origin, m. */
  function shapeRadius(s) {
    let r = 0;
    for (let k = 0; k + 2 < s.vertices.length; k += 3) r = Math.max(r, Math.hypot(s.vertices[k], s.vertices[k + 1], s.vertices[k + 2]));
    return r;
  }

  function material(colour, opts) {
    return new THREE.MeshLambertMaterial({ color: colour, ...opts });
  }

  /** A cylinder of radius r from a to b (Vector3), or null when they coincide. */
  function tube(a, b, r, mat) {
    const d = new THREE.Vector3().subVectors(b, a);
    const L = d.length();
    if (!(L > 0)) return null;
    const m = new THREE.Mesh(new THREE.CylinderGeometry(r, r, L, 16), mat);
    m.position.copy(a).addScaledVector(d, 0.5);
    m.quaternion.setFromUnitVectors(new THREE.Vector3(0, 1, 0), d.divideScalar(L));
    return m;
  }

  function ball(r, mat) {
    return new THREE.Mesh(new THREE.SphereGeometry(r, 24, 16), mat);
  }

  /** A body: tubes through its points (a closed loop for three or more), a sphere at its centre
   * of mass; one point: a box there. A body that carries a contact shape gets only the tubes:
   * its shape shows the body, and a marker of 1–3 % of the scene would hide a small one. */
  function bodyGroup(b, colour, size, shaped) {
    const g = new THREE.Group();
    const mat = material(colour);
    const pts = b.points.map((p) => new THREE.Vector3(...p));
    const r = 0.012 * size;
    if (pts.length === 1 && !shaped) {
      const m = new THREE.Mesh(new THREE.BoxGeometry(6 * r, 6 * r, 6 * r), mat);
      m.position.copy(pts[0]);
      g.add(m);
    }
    const loop = pts.length >= 3 ? [...pts, pts[0]] : pts;
    for (let j = 0; j + 1 < loop.length; j++) {
      const m = tube(loop[j], loop[j + 1], r, mat);
      if (m) g.add(m);
    }
    if (shaped) return g;
    for (const p of pts) {
      const m = ball(1.3 * r, mat);
      m.position.copy(p);
      g.add(m);
    }
    g.add(ball(2.2 * r, material(0x212529)));
    return g;
  }

  /** A joint marker at its place, oriented by its axis (y of the marker), and the axis line. */
  function jointGroup(j, size) {
    const g = new THREE.Group();
    const r = 0.03 * size;
    const mat = material(JOINT, { transparent: true, opacity: 0.75 });
    const shapes = {
      revolute: () => new THREE.CylinderGeometry(r, r, 2.2 * r, 24),
      cylindrical: () => new THREE.CylinderGeometry(0.8 * r, 0.8 * r, 3.5 * r, 24),
      prismatic: () => new THREE.BoxGeometry(1.4 * r, 4 * r, 1.4 * r),
      planar: () => new THREE.CylinderGeometry(2 * r, 2 * r, 0.3 * r, 32),
      universal: () => new THREE.TorusGeometry(r, 0.3 * r, 12, 24),
      fixed: () => new THREE.BoxGeometry(1.5 * r, 1.5 * r, 1.5 * r),
    };
    const m = new THREE.Mesh((shapes[j.kind] || (() => new THREE.SphereGeometry(r, 20, 14)))(), mat);
    g.add(m);
    if (j.axis) {
      const a = new THREE.Vector3(...j.axis).normalize();
      g.quaternion.setFromUnitVectors(new THREE.Vector3(0, 1, 0), a);
      const line = new THREE.BufferGeometry().setFromPoints([new THREE.Vector3(0, -5 * r, 0), new THREE.Vector3(0, 5 * r, 0)]);
      g.add(new THREE.Line(line, new THREE.LineBasicMaterial({ color: JOINT })));
    }
    g.position.set(...j.at);
    return g;
  }

  window.clrSpatialStage = function clrSpatialStage(rep, kit) {
    const { h, icon, ICONS, eng, timeFormat, clamp, isNum, logControl, clrReport } = kit;
    const view = rep.spatial;
    const scene3 = view.scene;
    const motion = makeMotion(view);
    const isRun = rep.kind !== 'view' && motion.n > 1;
    const fmtTime = timeFormat(motion.t0, motion.t1, motion.n);
    const box3 = bounds(view, motion);
    const size = Math.max(box3.getSize(new THREE.Vector3()).length(), 1e-6);
    const handle = { webgl: 'pending', renders: 0, ball: () => null, journal: () => null, body: () => null };
    clrReport.spatial = handle;
    // three.js reports WebGL failures (shader compilation, lost context) on the console only
    const consoleError = console.error.bind(console);
    console.error = (...args) => {
      clrReport.errors.push(args.map(String).join(' '));
      consoleError(...args);
    };

    // clearance magnification as on the planar page: the clearance drawn as 8 % of the socket
    // radius by default, up to 85 %
    // (sockets and journal bores alike: [outer radius, inner radius])
    const journals3 = scene3.journals || [];
    const radii = [...scene3.sockets.map((s) => [s.socket_radius, s.ball_radius]), ...journals3.map((j) => [j.bearing_radius, j.journal_radius])];
    const sized = radii.filter(([R, r]) => R > r && R > 0);
    const magDefault = Math.max(1, Math.min(...sized.map(([R, r]) => (0.08 * R) / (R - r)), Infinity) || 1);
    const magMax = Math.max(2, magDefault * 2, ...sized.map(([R, r]) => (0.85 * R) / (R - r)));
    let fmax = 0;
    view.frames.sockets.forEach((a) => {
      for (let i = 0; i + 7 < a.length; i += 8) fmax = Math.max(fmax, Math.abs(a[i + 3]), Math.hypot(a[i + 4], a[i + 5], a[i + 6]));
    });
    (view.frames.journals || []).forEach((a) => {
      for (const v of a) fmax = Math.max(fmax, Math.abs(v));
    });
    const opt = { mag: isFinite(magDefault) ? magDefault : 1, force: 1 };
    const pb = { t: motion.t0, playing: false, last: 0, span: 10, listeners: [] };

    // ---- DOM
    const hud = h('div', { class: 'clr-hud' });
    const viewButtons = Object.keys(VIEWS).map((name) =>
      h('button', { class: 'clr-btn', type: 'button', title: `${name} view`, onclick: () => setView(name) }, name));
    const tools = h('div', { class: 'clr-view3d' }, viewButtons,
      h('button', { class: 'clr-btn', type: 'button', title: 'fit the model in view', onclick: () => setView(current) }, icon(ICONS.fit, true), ' fit'));
    const box = h('div', { class: 'clr-stage clr-stage3d', tabindex: '0' }, hud, tools);
    const col = h('section', { class: 'clr-stage-col' }, box);
    let slider = null;
    let timeText = null;
    let playButton = null;
    if (isRun) col.appendChild(playbar());
    col.appendChild(controls());

    // ---- three.js scene
    let renderer = null;
    try {
      renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
      handle.webgl = 'ok';
    } catch (e) {
      handle.webgl = `unavailable: ${e && e.message ? e.message : e}`;
      box.appendChild(h('p', { class: 'clr-note clr-no-webgl', text: `no 3-D view: this browser gives no WebGL (${handle.webgl})` }));
    }
    const world = new THREE.Scene();
    world.background = new THREE.Color(0xffffff);
    const camera = new THREE.PerspectiveCamera(35, 1, size * 1e-3, size * 100);
    world.add(new THREE.HemisphereLight(0xffffff, 0x8090a0, 1.6));
    const sun = new THREE.DirectionalLight(0xffffff, 1.6);
    sun.position.set(1, 2, 3);
    camera.add(sun);
    world.add(camera);
    world.add(new THREE.AxesHelper(0.15 * size));
    const bodies = scene3.bodies.map((b, k) => {
      const shaped = (scene3.shapes || []).some((s) => s.body === b.name);
      const g = bodyGroup(b, COLOURS[k % COLOURS.length], size, shaped);
      world.add(g);
      return g;
    });
    const bodyIndex = (name) => (name == null ? -1 : scene3.bodies.findIndex((b) => b.name === name));
    const parentOf = (name) => (bodyIndex(name) >= 0 ? bodies[bodyIndex(name)] : world);
    for (const j of scene3.joints) parentOf(j.body).add(jointGroup(j, size));
    const sockets = scene3.sockets.map((s, k) => makeSocket(s, k));
    const journals = journals3.map((j, k) => makeJournal(j, k));
    for (const s of scene3.shapes || []) parentOf(s.body).add(makeShape(s));
    const trace = makeTrace();

    /** A contact shape: its triangulated surface in its body's colour (translucent grey on the
     * ground, so that a floor or a guide hides nothing), at its place and rotation. */
    function makeShape(s) {
      // setFromPoints and setIndex build the attributes (the bundle exports no BufferAttribute)
      const pts = [];
      for (let k = 0; k + 2 < s.vertices.length; k += 3) pts.push(new THREE.Vector3(s.vertices[k], s.vertices[k + 1], s.vertices[k + 2]));
      const geo = new THREE.BufferGeometry().setFromPoints(pts);
      geo.setIndex(s.triangles);
      geo.computeVertexNormals();
      const k = bodyIndex(s.body);
      const mat = k >= 0
        ? material(COLOURS[k % COLOURS.length], { flatShading: true })
        : material(0x868e96, { transparent: true, opacity: 0.35, depthWrite: false, side: 2 });
      const m = new THREE.Mesh(geo, mat);
      m.position.set(...s.at);
      const [w, x, y, z] = s.rotation;
      m.quaternion.set(x, y, z, w);
      return m;
    }

    function makeSocket(s, k) {
      const shell = ball(s.socket_radius, material(0x868e96, { transparent: true, opacity: 0.25, depthWrite: false }));
      shell.position.set(...s.socket_at);
      parentOf(s.socket_body).add(shell);
      const colour = COLOURS[(bodyIndex(s.ball_body) + COLOURS.length) % COLOURS.length];
      const inner = ball(1, material(colour));
      world.add(inner);
      const arrowOf = (c) => {
        const a = new THREE.ArrowHelper(new THREE.Vector3(1, 0, 0), new THREE.Vector3(), 1, c);
        world.add(a);
        return a;
      };
      return { s, k, shell, inner, normal: arrowOf(CONTACT), friction: arrowOf(FRICTION) };
    }

    /** A bore (translucent, with its two rims) on the bearing body and a journal cylinder in
     * the world, placed per frame by placeJournal; markers and arrows for the four groups. */
    function makeJournal(j, k) {
      const shade = material(0x868e96, { transparent: true, opacity: 0.25, depthWrite: false, side: 2 }); // side 2 = THREE.DoubleSide (the bundle exports no constants)
      const bore = new THREE.Group();
      bore.add(new THREE.Mesh(new THREE.CylinderGeometry(j.bearing_radius, j.bearing_radius, j.bearing_length, 40, 1, true), shade));
      for (const y of [-0.5, 0.5]) {
        const rim = new THREE.Mesh(new THREE.TorusGeometry(j.bearing_radius, 0.03 * j.bearing_radius, 8, 48), material(0x495057));
        rim.rotation.x = Math.PI / 2;
        rim.position.y = y * j.bearing_length;
        bore.add(rim);
      }
      bore.position.set(...j.bearing_at);
      bore.quaternion.setFromUnitVectors(new THREE.Vector3(0, 1, 0), new THREE.Vector3(...j.bearing_axis).normalize());
      parentOf(j.bearing_body).add(bore);
      const colour = COLOURS[(bodyIndex(j.journal_body) + COLOURS.length) % COLOURS.length];
      const pin = new THREE.Mesh(new THREE.CylinderGeometry(1, 1, 1, 40), material(colour));
      world.add(pin);
      const marks = [0, 1, 2, 3].map(() => {
        const m = ball(0.12 * j.bearing_radius, material(CONTACT));
        world.add(m);
        return m;
      });
      const arrows = [0, 1, 2, 3].map(() => {
        const a = new THREE.ArrowHelper(new THREE.Vector3(1, 0, 0), new THREE.Vector3(), 1, CONTACT);
        world.add(a);
        return a;
      });
      return { j, k, bore, pin, marks, arrows };
    }

    /** World place and axis of point `at` / direction `axis` of body `name` at (i, f). */
    function onBody(name, at, axis, i, f) {
      const p = name == null ? null : motion.pose(bodyIndex(name), i, f);
      const x = new THREE.Vector3(...at);
      const u = new THREE.Vector3(...axis).normalize();
      if (p) {
        x.applyQuaternion(p.q).add(p.p);
        u.applyQuaternion(p.q);
      }
      return { x, u };
    }

    /** The journal's true state at (i, f): bore centre and axis, journal centre and axis (world),
     * and the four group forces. */
    function journalState(jr, i, f) {
      const j = jr.j;
      const b = onBody(j.bearing_body, j.bearing_at, j.bearing_axis, i, f);
      const p = onBody(j.journal_body, j.journal_at, j.journal_axis, i, f);
      if (p.u.dot(b.u) < 0) p.u.negate();
      return { ob: b.x, ub: b.u, oj: p.x, uj: p.u, forces: motion.journal(jr.k, i, f) || [0, 0, 0, 0] };
    }

    /** The clearance magnification m and the drawn inner radius R − m·c (at least 0.15 R) of
     * an outer radius R and inner radius r. */
    function magnified(R, r) {
      const c = Math.max(R - r, 0);
      const m = c > 0 ? opt.mag : 1;
      return { m, r: Math.max(R - m * c, 0.15 * R) };
    }

    function placeJournal(jr, i, f) {
      const j = jr.j;
      const { ob, ub, oj, uj, forces } = journalState(jr, i, f);
      const { m, r } = magnified(j.bearing_radius, j.journal_radius);
      // radial offset and tilt magnified m times, the axial offset as it is
      const e = oj.clone().sub(ob);
      const ax = ub.clone().multiplyScalar(e.dot(ub));
      const centre = ob.clone().add(ax).addScaledVector(e.sub(ax), m);
      const lean = uj.clone().addScaledVector(ub, -uj.dot(ub));
      const u = ub.clone().addScaledVector(lean, m).normalize();
      jr.pin.position.copy(centre);
      jr.pin.quaternion.setFromUnitVectors(new THREE.Vector3(0, 1, 0), u);
      jr.pin.scale.set(r, j.journal_length, r);
      const perN = fmax > 0 ? (0.15 * size * opt.force) / fmax : 0;
      [-1, 1].forEach((side, g) => {
        // region A at the journal's low end, B at its high end: the contact lies on the side
        // of that end's offset from the bore axis
        const end = centre.clone().addScaledVector(u, 0.5 * side * j.journal_length);
        const off = end.clone().sub(ob);
        off.addScaledVector(ub, -off.dot(ub));
        const on = forces[g] > 0 && off.lengthSq() > 0;
        const n = on ? off.normalize() : new THREE.Vector3(1, 0, 0);
        const at = end.clone().addScaledVector(n, r);
        jr.marks[g].visible = on;
        jr.marks[g].position.copy(at);
        arrowTo(jr.arrows[g], at, n.clone().negate(), on ? forces[g] * perN : 0);
      });
      [-1, 1].forEach((side, t) => {
        const g = 2 + t;
        const at = centre.clone().addScaledVector(u, 0.5 * side * j.journal_length);
        const on = forces[g] > 0;
        jr.marks[g].visible = on;
        jr.marks[g].position.copy(at);
        arrowTo(jr.arrows[g], at, u.clone().multiplyScalar(-side), on ? forces[g] * perN : 0);
      });
    }

    function makeTrace() {
      const a = view.frames.trace;
      if (!a || a.length < 3) return null;
      const pts = [];
      for (let i = 0; i + 2 < a.length; i += 3) pts.push(new THREE.Vector3(a[i], a[i + 1], a[i + 2]));
      world.add(new THREE.Line(new THREE.BufferGeometry().setFromPoints(pts), new THREE.LineBasicMaterial({ color: 0x6741d9 })));
      const dot = ball(0.01 * size, material(0x6741d9));
      world.add(dot);
      return dot;
    }

    // ---- the state at time t
    const tmp = new THREE.Vector3();
    function socketState(sk, i, f) {
      const v = motion.socket(sk.k, i, f) || [0, 0, 0, 0, 0, 0, 0, 0];
      sk.shell.updateWorldMatrix(true, false);
      const centre = new THREE.Vector3().setFromMatrixPosition(sk.shell.matrixWorld);
      const e = new THREE.Vector3(v[0], v[1], v[2]);
      return { centre, e, fn: v[3], ft: new THREE.Vector3(v[4], v[5], v[6]), on: v[7] > 0.5 || v[3] > 0 };
    }

    function place(sk, i, f) {
      const s = sk.s;
      const { centre, e, fn, ft, on } = socketState(sk, i, f);
      const { m, r } = magnified(s.socket_radius, s.ball_radius);
      sk.inner.position.copy(centre).addScaledVector(e, m);
      sk.inner.scale.setScalar(r);
      sk.inner.material.emissive.setHex(on ? 0x550000 : 0x000000);
      // arrows at the contact point on the ball: normal force along −e/|e|, friction as recorded
      const le = e.length();
      const n = le > 0 ? e.clone().divideScalar(le) : new THREE.Vector3(1, 0, 0);
      const at = sk.inner.position.clone().addScaledVector(n, r);
      const perN = fmax > 0 ? (0.15 * size * opt.force) / fmax : 0;
      arrowTo(sk.normal, at, n.clone().negate(), on ? fn * perN : 0);
      arrowTo(sk.friction, at, ft.clone(), on ? ft.length() * perN : 0);
    }

    function arrowTo(a, at, dir, length) {
      a.visible = length > 1e-3 * size && dir.lengthSq() > 0;
      if (!a.visible) return;
      a.position.copy(at);
      a.setDirection(dir.normalize());
      a.setLength(length, Math.min(0.3 * length, 0.04 * size), Math.min(0.15 * length, 0.02 * size));
    }

    function update() {
      const [i, f] = motion.locate(pb.t);
      bodies.forEach((g, k) => {
        const p = motion.pose(k, i, f);
        if (!p) return;
        g.position.copy(p.p);
        g.quaternion.copy(p.q);
      });
      for (const sk of sockets) place(sk, i, f);
      for (const jr of journals) placeJournal(jr, i, f);
      const tr = motion.trace(i, f);
      if (trace && tr) trace.position.copy(tr);
      render();
      showTime();
      if (!pb.playing) publishState();
    }

    function render() {
      if (!renderer) return;
      renderer.render(world, camera);
      handle.renders += 1;
    }

    /** Drawn pixels that are not the white background, of a 64 × 64 sample of the canvas. */
    function inkSample() {
      const gl = renderer && renderer.getContext();
      if (!gl) return 0;
      const w = gl.drawingBufferWidth;
      const hgt = gl.drawingBufferHeight;
      const px = new Uint8Array(w * hgt * 4);
      gl.readPixels(0, 0, w, hgt, gl.RGBA, gl.UNSIGNED_BYTE, px);
      let ink = 0;
      for (let y = 0; y < 64; y++) {
        for (let x = 0; x < 64; x++) {
          const k = 4 * (Math.floor((y * hgt) / 64) * w + Math.floor((x * w) / 64));
          if (px[k] < 240 || px[k + 1] < 240 || px[k + 2] < 240) ink++;
        }
      }
      return ink;
    }

    /** The drawn state in the DOM (<script id="clr-state">), for a headless browser that can
     * only dump the DOM (cargo xtask report-check): time, WebGL status, renders, the ink of the
     * canvas, ball centres (world, unmagnified), body poses, script errors. */
    function publishState() {
      const balls = {};
      for (const sk of sockets) balls[sk.s.name] = handle.ball(sk.s.name);
      const pins = {};
      for (const jr of journals) pins[jr.j.name] = handle.journal(jr.j.name);
      const poses = {};
      for (const b of scene3.bodies) poses[b.name] = handle.body(b.name);
      const state = {
        time: pb.t, webgl: handle.webgl, renders: handle.renders, ink: inkSample(), view: current,
        balls, journals: pins, bodies: poses, errors: clrReport.errors,
      };
      let el = document.getElementById('clr-state');
      if (!el) {
        el = h('script', { id: 'clr-state', type: 'application/json' });
        document.body.appendChild(el);
      }
      el.textContent = JSON.stringify(state);
    }

    handle.ball = (name) => {
      const sk = sockets.find((x) => x.s.name === name);
      if (!sk) return null;
      const [i, f] = motion.locate(pb.t);
      const { centre, e } = socketState(sk, i, f);
      return centre.add(e).toArray();
    };
    /** A journal's true centre and axis (world, unmagnified) and which groups touch. */
    handle.journal = (name) => {
      const jr = journals.find((x) => x.j.name === name);
      if (!jr) return null;
      const { oj, uj, forces } = journalState(jr, ...motion.locate(pb.t));
      return { centre: oj.toArray(), axis: uj.toArray(), touching: forces.map((v) => v > 0) };
    };
    handle.body = (name) => {
      const k = bodyIndex(name);
      const p = k >= 0 ? motion.pose(k, ...motion.locate(pb.t)) : null;
      return p ? { at: p.p.toArray(), q: [p.q.w, p.q.x, p.q.y, p.q.z] } : null;
    };

    // ---- camera
    let current = 'iso';
    let controlsOrbit = null;
    function setView(name) {
      current = name;
      const v = VIEWS[name];
      const centre = box3.getCenter(new THREE.Vector3());
      const radius = 0.5 * size;
      const aspect = camera.aspect || 1;
      const fit = radius / Math.sin((camera.fov * Math.PI) / 360) / Math.min(1, aspect);
      const dir = tmp.set(...v.dir).normalize();
      camera.up.set(...v.up);
      camera.position.copy(centre).addScaledVector(dir, 1.05 * fit);
      camera.lookAt(centre);
      if (controlsOrbit) {
        controlsOrbit.target.copy(centre);
        controlsOrbit.update();
      }
      viewButtons.forEach((b) => b.classList.toggle('clr-on', b.textContent === name));
      render();
    }

    function resize() {
      if (!renderer) return;
      const r = box.getBoundingClientRect();
      const w = Math.max(1, Math.round(r.width));
      const hgt = Math.max(1, Math.round(r.height));
      renderer.setPixelRatio(window.devicePixelRatio || 1);
      // the canvas fills the stage by its style (report3d.css): only its buffer is sized here
      renderer.setSize(w, hgt, false);
      camera.aspect = w / hgt;
      camera.updateProjectionMatrix();
      render();
    }

    // ---- playback
    function showTime() {
      clrReport.time = pb.t;
      const [i, f] = motion.locate(pb.t);
      const k = Math.min(f > 0.5 ? i + 1 : i, motion.n - 1);
      hud.textContent = isRun ? `t = ${fmtTime(pb.t)}` : `t0 = ${fmtTime(motion.t0)}`;
      if (timeText) timeText.textContent = `${fmtTime(pb.t)}  ·  frame ${k + 1}/${motion.n}`;
      if (slider && document.activeElement !== slider) slider.value = String(pb.t);
      for (const l of pb.listeners) l(pb.t);
    }

    function seek(t) {
      pb.t = clamp(isNum(t) ? t : motion.t0, motion.t0, motion.t1);
      update();
    }

    function tick(now) {
      if (!pb.playing) return;
      const dt = Math.min((now - pb.last) / 1000, 0.1);
      pb.last = now;
      const t = pb.t + ((motion.t1 - motion.t0) / pb.span) * dt;
      seek(t > motion.t1 ? motion.t0 : t);
      requestAnimationFrame(tick);
    }

    function setPlaying(on) {
      pb.playing = on && isRun;
      if (playButton) playButton.replaceChildren(icon(pb.playing ? ICONS.pause : ICONS.play));
      if (!pb.playing) return;
      pb.last = performance.now();
      requestAnimationFrame(tick);
    }

    function playbar() {
      playButton = h('button', { class: 'clr-btn clr-play', type: 'button', title: 'play / pause (space)', onclick: () => setPlaying(!pb.playing) });
      slider = h('input', {
        class: 'clr-time', type: 'range', min: String(motion.t0), max: String(motion.t1), step: 'any',
        value: String(pb.t), 'aria-label': 'time', oninput: () => seek(parseFloat(slider.value)),
      });
      timeText = h('span', { class: 'clr-time-text' });
      const speed = h('select', {
        class: 'clr-speed', title: 'playback speed', 'aria-label': 'playback speed',
        onchange: () => { pb.span = parseFloat(speed.value); },
      }, [5, 10, 30, 60].map((s) => h('option', { value: String(s), selected: s === pb.span }, `whole run in ${s} s`)));
      return h('div', { class: 'clr-playbar' }, playButton, slider, timeText, speed);
    }

    function controls() {
      const items = [];
      const fmt = (v) => `×${v < 10 ? v.toFixed(2) : v < 100 ? v.toFixed(1) : v.toFixed(0)}`;
      if (sized.length) {
        items.push(logControl('clearance magnification', 'the clearance (and the ball offset in the socket) drawn this many times larger', 1, magMax, opt.mag,
          (v) => { opt.mag = v; update(); }, fmt));
      }
      if (fmax > 0) {
        items.push(logControl('force scale', `contact force arrows (normal red, friction orange); at ×1 the largest force of the run, ${eng(fmax)} N, is 15 % of the model's size`, 0.05, 20, 1,
          (v) => { opt.force = v; update(); }, fmt));
      }
      const legend = h('div', { class: 'clr-legend' },
        fmax > 0 ? [h('span', { class: 'clr-key clr-key-normal' }, 'normal force'), h('span', { class: 'clr-key clr-key-friction' }, 'friction force')] : [],
        h('span', { class: 'clr-key clr-key-axes' }, 'axes x red · y green · z blue'),
        view.scene.trace ? h('span', { class: 'clr-key clr-key-trace' }, `trace of ${view.scene.trace.body}`) : null,
        h('span', { class: 'clr-hint' }, 'drag to orbit · right-drag to pan · wheel to zoom'));
      return h('div', { class: 'clr-controls' }, items, legend);
    }

    document.addEventListener('keydown', (e) => {
      const tag = e.target && e.target.tagName;
      if (!isRun || (tag === 'INPUT' && e.target !== slider) || tag === 'SELECT' || tag === 'BUTTON') return;
      if (e.key === ' ') {
        e.preventDefault();
        setPlaying(!pb.playing);
      }
    });

    return {
      root: col,
      motion,
      fmtTime,
      onTime: (f) => pb.listeners.push(f),
      seek,
      seekNow(t) {
        setPlaying(false);
        seek(t);
        return pb.t;
      },
      start() {
        if (renderer) {
          box.insertBefore(renderer.domElement, box.firstChild);
          controlsOrbit = new THREE.OrbitControls(camera, renderer.domElement);
          controlsOrbit.addEventListener('change', render);
          resize();
          if (typeof ResizeObserver !== 'undefined') new ResizeObserver(resize).observe(box);
        }
        const m = /(?:^#|&)t=([^&]+)/.exec(location.hash);
        const view0 = /(?:^#|&)view=([a-z]+)/.exec(location.hash);
        setView(view0 && VIEWS[view0[1]] ? view0[1] : 'iso');
        seek(m ? parseFloat(m[1]) : motion.t0);
        setPlaying(isRun && !m);
      },
      journal: (name) => handle.ball(name),
    };
  };
})();
