/* text2anim viewer: plays world joint positions precomputed in Python.
 * Canvas 2D, perspective camera, painter's algorithm; no dependencies.
 * State for tests: window.__t2a (frame, time, playing, ready) and the body element's data-frame, data-time, data-ready. */
(function () {
  "use strict";

  var $ = function (id) { return document.getElementById(id); };
  var DATA = JSON.parse($("t2a-data").textContent);
  var BG_TOP = [24, 28, 36], BG_BOTTOM = [14, 16, 21];
  var UPPER = "#f2c94c", LOWER = "#4cc38a";
  var FOV = 40 * Math.PI / 180;
  var HOLD_AT_END = 0.6; // seconds the last frame stays before a loop restarts

  var state = {
    t: 0, playing: true, speed: 1, loop: true, follow: true, frame: 0, ready: false,
    scrubbing: false, dirty: true, last: 0,
    every: 0, drawn: 0  // ms at least between two drawings (0: every animation frame), the last one's clock
  };
  var actors = [];
  // The things of the scene (balls, chairs): props.js sets this; render_html inlines it here only when
  // the page has some, so a page without them carries none of its code.
  var Props = null;
  /* props.js */
  var cam = { yaw: 0, pitch: 0.3, dist: 5, target: [0, 0.9, 0], home: null };

  // ------------------------------------------------------------------ colours
  function hexRgb(h) {
    h = h.replace("#", "");
    return [parseInt(h.slice(0, 2), 16), parseInt(h.slice(2, 4), 16), parseInt(h.slice(4, 6), 16)];
  }
  function mix(a, b, t) { return [a[0] + (b[0] - a[0]) * t, a[1] + (b[1] - a[1]) * t, a[2] + (b[2] - a[2]) * t]; }
  function css(c, alpha) {
    var r = Math.round(c[0]), g = Math.round(c[1]), b = Math.round(c[2]);
    return alpha === undefined ? "rgb(" + r + "," + g + "," + b + ")" : "rgba(" + r + "," + g + "," + b + "," + alpha + ")";
  }
  var WHITE = [255, 255, 255], BLACK = [0, 0, 0];

  // --------------------------------------------------------------- decoding
  function b64bytes(s) {
    var bin = atob(s), n = bin.length, u8 = new Uint8Array(n);
    for (var i = 0; i < n; i++) u8[i] = bin.charCodeAt(i);
    return u8;
  }
  function inflate(u8) {
    if (typeof DecompressionStream === "undefined") {
      return Promise.reject(new Error("this browser cannot read compressed data (no DecompressionStream); " +
        "write the page with compress=False"));
    }
    var stream = new Blob([u8]).stream().pipeThrough(new DecompressionStream("deflate"));
    return new Response(stream).arrayBuffer().then(function (b) { return new Uint8Array(b); });
  }
  function bytesOf(s, encoding) {
    var u8 = b64bytes(s);
    return (encoding || DATA.encoding) === "deflate" ? inflate(u8) : Promise.resolve(u8);
  }

  function sideOf(name) {
    if (/left/i.test(name) || /^L(?=[A-Z_.\-])/.test(name) || /[_.\-][Ll](_end)?$/.test(name)) return 1;
    if (/right/i.test(name) || /^R(?=[A-Z_.\-])/.test(name) || /[_.\-][Rr](_end)?$/.test(name)) return -1;
    return 0;
  }

  function decodeActor(a, encoding) {
    return Promise.all([bytesOf(a.rel, encoding), bytesOf(a.root, encoding)]).then(function (parts) {
      var T = a.frames, N = a.points;
      var relV = new DataView(parts[0].buffer, parts[0].byteOffset, parts[0].byteLength);
      var rootV = new DataView(parts[1].buffer, parts[1].byteOffset, parts[1].byteLength);
      if (relV.byteLength !== N * 3 * T * 2 || rootV.byteLength !== 3 * T * 4) {
        throw new Error("actor " + a.name + ": motion data has the wrong size");
      }
      var root = new Float64Array(T * 3);
      for (var k = 0; k < 3; k++) {
        var acc = 0;
        for (var t = 0; t < T; t++) { acc += rootV.getInt32((k * T + t) * 4, true); root[t * 3 + k] = acc; }
      }
      var pos = new Float32Array(T * N * 3);
      for (var n = 0; n < N; n++) {
        for (var kk = 0; kk < 3; kk++) {
          var s = 0, base = (n * 3 + kk) * T;
          for (var f = 0; f < T; f++) {
            s += relV.getInt16((base + f) * 2, true);
            pos[(f * N + n) * 3 + kk] = (s + root[f * 3 + kk]) / 1000;
          }
        }
      }
      var base = hexRgb(a.color);
      var sides = a.names.map(function (nm, i) {
        var sd = sideOf(nm), p = a.parents[i];
        while (sd === 0 && p > 0) { sd = sideOf(a.names[p]); p = a.parents[p]; }
        return sd;
      });
      var bones = [];
      for (var i = 0; i < N; i++) if (a.parents[i] >= 0) bones.push(i);
      var contact = a.contact || "";
      return {
        meta: a, T: T, N: N, fps: a.fps, pos: pos, cur: new Float32Array(N * 3), bones: bones,
        duration: (T - 1) / a.fps, sides: sides, contact: contact,
        base: base, left: mix(base, WHITE, 0.28), right: mix(base, BLACK, 0.12),
        outline: mix(base, BLACK, 0.65), frame: 0
      };
    });
  }

  // --------------------------------------------------------------- sampling
  function sample(A, t) {
    var f = Math.max(0, Math.min(t * A.fps, A.T - 1));
    var i0 = Math.floor(f), i1 = Math.min(i0 + 1, A.T - 1), w = f - i0, M = A.N * 3;
    var p = A.pos, c = A.cur, o0 = i0 * M, o1 = i1 * M;
    for (var k = 0; k < M; k++) c[k] = p[o0 + k] * (1 - w) + p[o1 + k] * w;
    A.frame = Math.round(f);
  }

  function centre() {
    var x = 0, z = 0;
    actors.forEach(function (A) { x += A.cur[0]; z += A.cur[2]; });
    return [x / actors.length, z / actors.length];
  }

  // ----------------------------------------------------------------- camera
  var view = $("view"), vctx = view.getContext("2d");
  var W = 1, H = 1, DPR = 1, F = 1;
  var basis = { eye: [0, 0, 0], r: [1, 0, 0], u: [0, 1, 0], f: [0, 0, -1] };

  function updateBasis() {
    var cp = Math.cos(cam.pitch), sp = Math.sin(cam.pitch);
    var dir = [cp * Math.sin(cam.yaw), sp, cp * Math.cos(cam.yaw)];
    var eye = [cam.target[0] + dir[0] * cam.dist, cam.target[1] + dir[1] * cam.dist, cam.target[2] + dir[2] * cam.dist];
    var f = [-dir[0], -dir[1], -dir[2]];
    var r = [f[1] * 0 - f[2] * 1, f[2] * 0 - f[0] * 0, f[0] * 1 - f[1] * 0]; // f × up
    var rl = Math.hypot(r[0], r[1], r[2]) || 1;
    r = [r[0] / rl, r[1] / rl, r[2] / rl];
    var u = [r[1] * f[2] - r[2] * f[1], r[2] * f[0] - r[0] * f[2], r[0] * f[1] - r[1] * f[0]];
    basis = { eye: eye, r: r, u: u, f: f };
    F = (H / 2) / Math.tan(FOV / 2);
  }
  // camera coordinates of a world point: [x right, y up, z depth]
  function toCam(x, y, z) {
    var b = basis, dx = x - b.eye[0], dy = y - b.eye[1], dz = z - b.eye[2];
    return [dx * b.r[0] + dy * b.r[1] + dz * b.r[2], dx * b.u[0] + dy * b.u[1] + dz * b.u[2],
      dx * b.f[0] + dy * b.f[1] + dz * b.f[2]];
  }
  var NEAR = 0.05;
  function toScreen(c) { return [W / 2 + F * c[0] / c[2], H / 2 - F * c[1] / c[2], c[2]]; }
  // a segment in camera coordinates clipped to the near plane; null when wholly behind
  function clipSeg(a, b) {
    if (a[2] < NEAR && b[2] < NEAR) return null;
    if (a[2] < NEAR || b[2] < NEAR) {
      var t = (NEAR - a[2]) / (b[2] - a[2]);
      var m = [a[0] + (b[0] - a[0]) * t, a[1] + (b[1] - a[1]) * t, NEAR];
      if (a[2] < NEAR) a = m; else b = m;
    }
    return [toScreen(a), toScreen(b)];
  }

  function resetCamera() {
    cam.yaw = cam.home.yaw; cam.pitch = cam.home.pitch; cam.dist = cam.home.dist;
    cam.target = cam.home.target.slice();
    if (cam.home.follow !== state.follow) { state.follow = cam.home.follow; $("follow").checked = state.follow; }
    state.dirty = true;
  }

  // The home view: three-quarter front of the first actor, slightly from above. Actors that
  // stay within 1.5 m are framed as a whole with a still camera; travelling ones are followed.
  // The distance is the smallest at which every joint (and the name tags) of sampled frames
  // falls inside the view with a margin.
  function initCamera() {
    var h = 0, facing = actors[0].meta.facing || 0;
    actors.forEach(function (A) { h = Math.max(h, A.meta.height || 1.7); });
    var lo = [Infinity, Infinity], hi = [-Infinity, -Infinity];
    actors.forEach(function (A) {
      for (var f = 0; f < A.T; f++) {
        var x = A.pos[f * A.N * 3], z = A.pos[f * A.N * 3 + 2];
        lo[0] = Math.min(lo[0], x); hi[0] = Math.max(hi[0], x); lo[1] = Math.min(lo[1], z); hi[1] = Math.max(hi[1], z);
      }
    });
    var follow = Math.hypot(hi[0] - lo[0], hi[1] - lo[1]) > 1.5;
    var fixed = [(lo[0] + hi[0]) / 2, h * 0.5, (lo[1] + hi[1]) / 2];
    var samples = [], steps = Math.min(24, Math.max(1, Math.round(DATA.duration * 4)));
    for (var s = 0; s <= steps; s++) {
      var t = DATA.duration * s / steps;
      actors.forEach(function (A) { sample(A, t); });
      var c = centre(), pts = [];
      actors.forEach(function (A) {
        for (var i = 0; i < A.N; i++) pts.push([A.cur[i * 3], A.cur[i * 3 + 1], A.cur[i * 3 + 2]]);
        var top = A.meta.head >= 0 ? A.meta.head : 0;
        pts.push([A.cur[top * 3], A.cur[top * 3 + 1] + 0.3 * A.meta.height / 1.7, A.cur[top * 3 + 2]]);
      });
      if (Props) Props.points(t, pts);
      samples.push({ target: follow ? [c[0], h * 0.5, c[1]] : fixed, pts: pts });
    }
    cam.yaw = facing + 0.62; cam.pitch = 0.24;
    function fits(dist) {
      cam.dist = dist;
      for (var k = 0; k < samples.length; k++) {
        cam.target = samples[k].target; updateBasis();
        var pts = samples[k].pts;
        for (var i = 0; i < pts.length; i++) {
          var q = toCam(pts[i][0], pts[i][1], pts[i][2]);
          if (q[2] < 0.3) return false;
          var sc = toScreen(q);
          if (sc[0] < 0.06 * W || sc[0] > 0.94 * W || sc[1] < 0.07 * H || sc[1] > 0.95 * H) return false;
        }
      }
      return true;
    }
    var dist = 1.5;
    while (dist < 200 && !fits(dist)) dist *= 1.06;
    actors.forEach(function (A) { sample(A, 0); });
    if (Props) Props.sample(0);
    var c0 = centre();
    cam.home = {
      yaw: facing + 0.62, pitch: 0.24, dist: dist,
      target: follow ? [c0[0], h * 0.5, c0[1]] : fixed, follow: follow
    };
    resetCamera();
    $("follow").checked = state.follow;
  }

  function followStep(dt) {
    if (!state.follow) return;
    var c = centre(), tx = cam.target;
    var d = Math.hypot(c[0] - tx[0], c[1] - tx[2]);
    var k = (d > 3 || dt <= 0) ? 1 : 1 - Math.exp(-dt * 5);
    tx[0] += (c[0] - tx[0]) * k; tx[2] += (c[1] - tx[2]) * k;
  }

  // ------------------------------------------------------------------ drawing
  // The timeline's height decides the 3D view's, so it is laid out first; a ResizeObserver
  // catches every later change of the view's size (window, fonts, devtools).
  function resize() {
    DPR = window.devicePixelRatio || 1;
    layoutTimeline();
    var r = view.getBoundingClientRect();
    W = Math.max(1, r.width); H = Math.max(1, r.height);
    var bw = Math.round(W * DPR), bh = Math.round(H * DPR);
    if (view.width !== bw || view.height !== bh) { view.width = bw; view.height = bh; }
    state.dirty = true;
  }

  function drawBackground(ctx) {
    var g = ctx.createLinearGradient(0, 0, 0, H);
    g.addColorStop(0, css(BG_TOP)); g.addColorStop(1, css(BG_BOTTOM));
    ctx.fillStyle = g; ctx.fillRect(0, 0, W, H);
  }

  function drawGrid(ctx) {
    var step = 0.5, R = Math.max(8, cam.dist * 2.2);
    while (R / step > 60) step *= 2;  // far out, whole metres and then coarser: a few thousand lines at most
    var cx = Math.round(cam.target[0] / step) * step, cz = Math.round(cam.target[2] / step) * step;
    var n = Math.ceil(R / step);
    var buckets = [];
    for (var b = 0; b < 6; b++) buckets.push([[], []]);
    function seg(x0, z0, x1, z1, major) {
      var mx = (x0 + x1) / 2 - cam.target[0], mz = (z0 + z1) / 2 - cam.target[2];
      var fade = 1 - Math.min(1, Math.hypot(mx, mz) / R);
      if (fade <= 0.02) return;
      var s = clipSeg(toCam(x0, 0, z0), toCam(x1, 0, z1));
      if (!s) return;
      buckets[Math.min(5, Math.floor(fade * 6))][major ? 1 : 0].push(s);
    }
    for (var i = -n; i <= n; i++) {
      var x = cx + i * step, z = cz + i * step;
      var majX = Math.abs(Math.round(x) - x) < 1e-6, majZ = Math.abs(Math.round(z) - z) < 1e-6;
      for (var j = -n; j < n; j++) {
        seg(x, cz + j * step, x, cz + (j + 1) * step, majX);
        seg(cx + j * step, z, cx + (j + 1) * step, z, majZ);
      }
    }
    ctx.lineCap = "butt";
    for (var q = 0; q < 6; q++) {
      for (var m = 0; m < 2; m++) {
        var list = buckets[q][m];
        if (!list.length) continue;
        ctx.beginPath();
        for (var L = 0; L < list.length; L++) { ctx.moveTo(list[L][0][0], list[L][0][1]); ctx.lineTo(list[L][1][0], list[L][1][1]); }
        var a = (q + 0.5) / 6;
        ctx.strokeStyle = m ? "rgba(150,160,178," + (0.42 * a).toFixed(3) + ")" : "rgba(130,140,160," + (0.18 * a).toFixed(3) + ")";
        ctx.lineWidth = m ? 1.1 : 0.8;
        ctx.stroke();
      }
    }
    // world axes at the origin: x red, z blue
    [[1, 0, "rgba(235,87,87,0.75)"], [0, 1, "rgba(79,156,249,0.75)"]].forEach(function (ax) {
      var s = clipSeg(toCam(0, 0, 0), toCam(ax[0] * 0.5, 0, ax[1] * 0.5));
      if (!s) return;
      ctx.beginPath(); ctx.moveTo(s[0][0], s[0][1]); ctx.lineTo(s[1][0], s[1][1]);
      ctx.strokeStyle = ax[2]; ctx.lineWidth = 2; ctx.stroke();
    });
  }

  function px(c) { return c[2] > NEAR ? F / c[2] : 0; }

  // A soft shadow on the floor: an ellipse under the body and one under each foot,
  // fading as the foot rises (overhead light; reads as contact without hard edges).
  function groundBlob(ctx, x, z, r, alpha) {
    var c = toCam(x, 0, z), cx = toCam(x + r, 0, z), cz = toCam(x, 0, z + r);
    if (c[2] <= NEAR || cx[2] <= NEAR || cz[2] <= NEAR || alpha <= 0.01) return;
    var s0 = toScreen(c), sx = toScreen(cx), sz = toScreen(cz);
    ctx.save();
    ctx.transform(sx[0] - s0[0], sx[1] - s0[1], sz[0] - s0[0], sz[1] - s0[1], s0[0], s0[1]);
    var g = ctx.createRadialGradient(0, 0, 0, 0, 0, 1);
    g.addColorStop(0, "rgba(0,0,0," + alpha.toFixed(3) + ")");
    g.addColorStop(0.6, "rgba(0,0,0," + (alpha * 0.55).toFixed(3) + ")");
    g.addColorStop(1, "rgba(0,0,0,0)");
    ctx.fillStyle = g;
    ctx.beginPath(); ctx.arc(0, 0, 1, 0, Math.PI * 2); ctx.fill();
    ctx.restore();
  }

  function drawShadow(ctx, A) {
    var c = A.cur, N = A.N, x = 0, z = 0, hs = A.meta.height / 1.7;
    for (var i = 0; i < N; i++) { x += c[i * 3]; z += c[i * 3 + 2]; }
    groundBlob(ctx, x / N, z / N, 0.42 * hs, 0.42);
    (A.meta.feet || []).forEach(function (ft) {
      ft.forEach(function (j) {
        var y = c[j * 3 + 1];
        groundBlob(ctx, c[j * 3], c[j * 3 + 2], 0.11 * hs, 0.45 * Math.max(0, 1 - y / (0.45 * hs)));
      });
    });
  }

  function drawContacts(ctx, A) {
    var ch = A.contact.charCodeAt(A.frame) - 48;
    if (!(ch > 0) || !A.meta.feet || A.meta.feet.length !== 2) return;
    var c = A.cur;
    for (var s = 0; s < 2; s++) {
      if (!(ch & (1 << s))) continue;
      var ft = A.meta.feet[s], ja = ft[0], jt = ft[1];
      var low = c[ja * 3 + 1] < c[jt * 3 + 1] ? ja : jt;
      var x = c[low * 3], z = c[low * 3 + 2], rad = 0.09 * (A.meta.height / 1.7);
      ctx.beginPath();
      for (var k = 0; k <= 24; k++) {
        var a = k / 24 * Math.PI * 2, q = toCam(x + Math.cos(a) * rad, 0.002, z + Math.sin(a) * rad);
        if (q[2] <= NEAR) return;
        var sc = toScreen(q);
        if (k === 0) ctx.moveTo(sc[0], sc[1]); else ctx.lineTo(sc[0], sc[1]);
      }
      ctx.fillStyle = css(A.left, 0.18); ctx.fill();
      ctx.strokeStyle = css(A.left, 0.85); ctx.lineWidth = 1.5; ctx.stroke();
    }
  }

  // The figure drawn: a body (capsules as thick as a person's: meta.body) or the stick figure (meta.radius).
  var BODY = { on: false };

  // An actor's bones (capsules) and head (a ball) in camera space, sorted far to near.
  function actorItems(A) {
    var c = A.cur, meta = A.meta, cams = new Array(A.N);
    for (var i = 0; i < A.N; i++) cams[i] = toCam(c[i * 3], c[i * 3 + 1], c[i * 3 + 2]);
    var items = [];
    for (var bi = 0; bi < A.bones.length; bi++) {
      var j = A.bones[bi], p = meta.parents[j];
      var s = clipSeg(cams[p], cams[j]);
      if (!s) continue;
      var z = (s[0][2] + s[1][2]) / 2;
      var rad = BODY.on && meta.body ? meta.body[j] : meta.radius[j];
      items.push({ kind: 0, j: j, s: s, z: z, w: Math.max(1.5, 2 * rad * F / z) });
    }
    var head = meta.head >= 0 ? meta.head : -1, hb = meta.headBase;
    if (head >= 0) {
      var hc = hb !== head ? [(cams[hb][0] + cams[head][0]) / 2, (cams[hb][1] + cams[head][1]) / 2, (cams[hb][2] + cams[head][2]) / 2] : cams[head];
      if (hc[2] > NEAR) {
        var hs = toScreen(hc);
        items.push({ kind: 1, s: hs, z: hc[2], r: meta.headRadius * (BODY.on ? 1.25 : 1) * F / hc[2] });
      }
    }
    items.sort(function (a, b) { return b.z - a.z; });
    return { cams: cams, items: items };
  }

  // Paints items of an actor: their silhouette outline first, then the fills far to near, then the joints' dots.
  function paintItems(ctx, A, cams, items, zMin, zMax) {
    var meta = A.meta;
    ctx.lineCap = "round"; ctx.lineJoin = "round";
    ctx.strokeStyle = css(A.outline, 0.9);
    items.forEach(function (it) {
      if (it.kind === 0) {
        ctx.beginPath(); ctx.moveTo(it.s[0][0], it.s[0][1]); ctx.lineTo(it.s[1][0], it.s[1][1]);
        ctx.lineWidth = it.w + 2.5; ctx.stroke();
      } else {
        ctx.beginPath(); ctx.arc(it.s[0], it.s[1], it.r + 1.25, 0, Math.PI * 2);
        ctx.fillStyle = css(A.outline, 0.9); ctx.fill();
      }
    });
    var span = Math.max(1e-6, zMax - zMin);
    items.forEach(function (it) {
      var fog = Math.min(1, Math.max(0, (it.z - zMin) / span)) * 0.28;
      if (it.kind === 0) {
        var sd = A.sides[it.j], col = sd > 0 ? A.left : sd < 0 ? A.right : A.base;
        col = mix(col, BG_TOP, fog);
        var x0 = it.s[0][0], y0 = it.s[0][1], x1 = it.s[1][0], y1 = it.s[1][1];
        ctx.beginPath(); ctx.moveTo(x0, y0); ctx.lineTo(x1, y1);
        ctx.lineWidth = it.w; ctx.strokeStyle = css(col); ctx.stroke();
        // a highlight along the lit side makes the capsule read as round
        var o = it.w * 0.18;
        ctx.beginPath(); ctx.moveTo(x0 - o, y0 - o); ctx.lineTo(x1 - o, y1 - o);
        ctx.lineWidth = Math.max(0.8, it.w * 0.3); ctx.strokeStyle = css(mix(col, WHITE, 0.35), 0.55); ctx.stroke();
      } else {
        var hcol = mix(A.base, BG_TOP, fog);
        var g = ctx.createRadialGradient(it.s[0] - it.r * 0.35, it.s[1] - it.r * 0.4, it.r * 0.1, it.s[0], it.s[1], it.r);
        g.addColorStop(0, css(mix(hcol, WHITE, 0.45))); g.addColorStop(1, css(hcol));
        ctx.beginPath(); ctx.arc(it.s[0], it.s[1], it.r, 0, Math.PI * 2); ctx.fillStyle = g; ctx.fill();
      }
    });
    // joints as dots (not the end sites), on the stick figure
    if (BODY.on) return;
    ctx.fillStyle = css(mix(A.base, WHITE, 0.7), 0.95);
    items.forEach(function (it) {
      var jn = it.j, q = cams[jn];
      if (it.kind !== 0 || jn >= meta.joints || q[2] <= NEAR || jn === meta.headBase) return;
      var sc = toScreen(q), r = Math.max(1.2, Math.min(4, meta.radius[jn] * 0.45 * F / q[2]));
      ctx.beginPath(); ctx.arc(sc[0], sc[1], r, 0, Math.PI * 2); ctx.fill();
    });
  }

  // The actor's name above its head.
  function drawName(ctx, A) {
    var c = A.cur, meta = A.meta;
    if (!meta.name) return;
    var top = meta.head >= 0 ? meta.head : 0, tc = toCam(c[top * 3], c[top * 3 + 1] + 0.28 * meta.height / 1.7, c[top * 3 + 2]);
    if (tc[2] <= NEAR) return;
    var ts = toScreen(tc);
    ctx.font = "600 13px " + getComputedStyle(document.documentElement).fontFamily;
    ctx.textAlign = "center"; ctx.textBaseline = "bottom";
    var tw = ctx.measureText(meta.name).width;
    ctx.fillStyle = "rgba(13,15,19,0.72)";
    roundRect(ctx, ts[0] - tw / 2 - 7, ts[1] - 20, tw + 14, 19, 5); ctx.fill();
    ctx.fillStyle = css(A.left); ctx.fillText(meta.name, ts[0], ts[1] - 4);
  }

  function drawActor(ctx, A, zMin, zMax) {
    var got = actorItems(A);
    paintItems(ctx, A, got.cams, got.items, zMin, zMax);
    drawName(ctx, A);
  }

  function roundRect(ctx, x, y, w, h, r) {
    r = Math.max(0, Math.min(r, w / 2, h / 2));
    ctx.beginPath();
    ctx.moveTo(x + r, y); ctx.lineTo(x + w - r, y); ctx.quadraticCurveTo(x + w, y, x + w, y + r);
    ctx.lineTo(x + w, y + h - r); ctx.quadraticCurveTo(x + w, y + h, x + w - r, y + h);
    ctx.lineTo(x + r, y + h); ctx.quadraticCurveTo(x, y + h, x, y + h - r);
    ctx.lineTo(x, y + r); ctx.quadraticCurveTo(x, y, x + r, y); ctx.closePath();
  }

  function render() {
    var ctx = vctx;
    ctx.setTransform(DPR, 0, 0, DPR, 0, 0);
    updateBasis();
    drawBackground(ctx);
    drawGrid(ctx);
    var order = actors.map(function (A) {
      var q = toCam(A.cur[0], A.cur[1], A.cur[2]);
      return { A: A, z: q[2] };
    });
    order.sort(function (a, b) { return b.z - a.z; });
    var zMin = cam.dist - 1.2, zMax = cam.dist + 1.2;
    if (Props) Props.shadows(ctx);
    order.forEach(function (o) { drawShadow(ctx, o.A); });
    order.forEach(function (o) { drawContacts(ctx, o.A); });
    if (Props) Props.draw(ctx, order, zMin, zMax);  // the things' parts sorted in among the actors' bones
    else order.forEach(function (o) { drawActor(ctx, o.A, zMin, zMax); });
    drawTimeline();
  }

  // ----------------------------------------------------------------- timeline
  var tl = $("timeline"), tctx = tl.getContext("2d"), tip = $("tip");
  var TL = { gutter: 118, axis: 24, lane: 22, blend: 22, pad: 8, rows: [], width: 1, height: 1 };

  function packLanes(items) {
    var ends = [];
    items.sort(function (a, b) { return a.start - b.start || b.end - a.end; });
    items.forEach(function (it) {
      var k = 0;
      while (k < ends.length && ends[k] > it.start + 1e-6) k++;
      ends[k] = it.end; it.laneIndex = k;
    });
    return Math.max(1, ends.length);
  }

  function buildRows() {
    TL.rows = DATA.rows.map(function (name, idx) {
      var els = DATA.spans.filter(function (s) { return s.actor === name && s.kind === "element"; });
      var bls = DATA.spans.filter(function (s) { return s.actor === name && s.kind === "blend"; });
      var A = actors.filter(function (a) { return a.meta.name === name; })[0];
      return { name: name, actor: A, color: A ? A.base : hexRgb("#8b93a1"), elements: els, blends: bls,
        lanes: packLanes(els), blendH: bls.length ? TL.blend : 0 };
    });
  }

  function layoutTimeline() {
    var y = TL.axis;
    TL.rows.forEach(function (r) {
      r.y = y; r.h = r.lanes * TL.lane + r.blendH + 6; y += r.h + TL.pad;
    });
    TL.height = y + 2;  // the wrapper scrolls when there are more rows than fit (max-height in the CSS)
    TL.width = Math.max(1, tl.getBoundingClientRect().width || window.innerWidth);
    tl.style.height = TL.height + "px";
    tl.width = Math.round(TL.width * DPR); tl.height = Math.round(TL.height * DPR);
  }

  function tx(t) { return TL.gutter + (TL.width - TL.gutter - 14) * (DATA.duration > 0 ? t / DATA.duration : 0); }
  function xt(x) { return Math.max(0, Math.min(DATA.duration, (x - TL.gutter) / (TL.width - TL.gutter - 14) * DATA.duration)); }

  function niceStep(px_per_s) {
    var steps = [0.1, 0.2, 0.5, 1, 2, 5, 10, 15, 30, 60, 120, 300];
    for (var i = 0; i < steps.length; i++) if (steps[i] * px_per_s >= 64) return steps[i];
    return 600;
  }

  function fitText(ctx, text, maxw) {
    if (ctx.measureText(text).width <= maxw) return text;
    var lo = 0, hi = text.length;
    while (lo < hi) {
      var mid = (lo + hi + 1) >> 1;
      if (ctx.measureText(text.slice(0, mid) + "…").width <= maxw) lo = mid; else hi = mid - 1;
    }
    return lo > 0 ? text.slice(0, lo) + "…" : "";
  }

  function drawTimeline() {
    var ctx = tctx, Wt = TL.width, Ht = TL.height;
    var font = getComputedStyle(document.documentElement).fontFamily;
    ctx.setTransform(DPR, 0, 0, DPR, 0, 0);
    ctx.fillStyle = "#1e222a"; ctx.fillRect(0, 0, Wt, Ht);
    var x0 = tx(0), x1 = tx(DATA.duration);
    // axis
    var step = niceStep((x1 - x0) / Math.max(DATA.duration, 1e-6));
    ctx.font = "11px " + font; ctx.textBaseline = "middle"; ctx.textAlign = "center";
    for (var t = 0; t <= DATA.duration + 1e-9; t += step) {
      var x = Math.round(tx(t)) + 0.5;
      ctx.strokeStyle = "rgba(139,147,161,0.16)"; ctx.lineWidth = 1;
      ctx.beginPath(); ctx.moveTo(x, TL.axis - 4); ctx.lineTo(x, Ht); ctx.stroke();
      ctx.fillStyle = "#8b93a1";
      ctx.fillText((step < 1 ? t.toFixed(1) : Math.round(t)) + " s", x, 11);
    }
    ctx.textAlign = "left";
    TL.rows.forEach(function (r, ri) {
      var y = r.y;
      ctx.fillStyle = ri % 2 ? "rgba(255,255,255,0.015)" : "rgba(255,255,255,0.035)";
      ctx.fillRect(0, y - 3, Wt, r.h + 6);
      // name
      ctx.fillStyle = css(r.color); roundRect(ctx, 10, y + 4, 10, 10, 2.5); ctx.fill();
      ctx.fillStyle = "#e4e7ec"; ctx.font = "600 12px " + font; ctx.textBaseline = "middle";
      ctx.fillText(fitText(ctx, r.name || "actor", TL.gutter - 34), 26, y + 9.5);
      // the blend lane: upper body above, lower body below
      var ly = y + r.lanes * TL.lane + 2;
      ctx.font = "10px " + font; ctx.textBaseline = "middle";
      if (r.blendH) {
      ctx.fillStyle = UPPER; ctx.fillText("upper blend", 26, ly + TL.blend / 4 + 0.5);
      ctx.fillStyle = LOWER; ctx.fillText("lower blend", 26, ly + 3 * TL.blend / 4 + 0.5);
      }
      // the motion's extent
      if (r.actor) {
        ctx.fillStyle = css(r.color, 0.22);
        ctx.fillRect(tx(0), y + r.lanes * TL.lane - 2, tx(r.actor.duration) - tx(0), 2);
      }
      // blend bands behind the elements
      r.blends.forEach(function (b) {
        ctx.fillStyle = css(hexRgb(b.lane === "lower" ? LOWER : UPPER), 0.08);
        ctx.fillRect(tx(b.start), y, Math.max(1, tx(b.end) - tx(b.start)), r.lanes * TL.lane);
      });
      ctx.font = "12px " + font;
      r.elements.forEach(function (e, k) {
        var ex = tx(e.start), ew = Math.max(2, tx(e.end) - ex), ey = y + e.laneIndex * TL.lane + 1;
        var col = mix(r.color, BLACK, (k % 2) * 0.18);
        ctx.fillStyle = css(col, 0.88); roundRect(ctx, ex, ey, ew, TL.lane - 4, 4); ctx.fill();
        ctx.strokeStyle = css(mix(r.color, WHITE, 0.35), 0.8); ctx.lineWidth = 1; ctx.stroke();
        var label = fitText(ctx, e.label, ew - 10);
        if (label) { ctx.fillStyle = "#0e1116"; ctx.fillText(label, ex + 5, ey + (TL.lane - 4) / 2 + 0.5); }
      });
      var by = y + r.lanes * TL.lane + 2, bh = TL.blend;
      if (r.blendH) { ctx.fillStyle = "rgba(255,255,255,0.04)"; ctx.fillRect(tx(0), by, x1 - x0, bh); }
      r.blends.forEach(function (b) {
        var bx = tx(b.start), bw = Math.max(2, tx(b.end) - bx);
        var parts = b.lane === "both" ? [[UPPER, by, bh / 2], [LOWER, by + bh / 2, bh / 2]]
          : b.lane === "lower" ? [[LOWER, by + bh / 2, bh / 2]] : [[UPPER, by, bh / 2]];
        parts.forEach(function (p) {
          ctx.fillStyle = css(hexRgb(p[0]), 0.7); ctx.fillRect(bx, p[1] + 0.5, bw, p[2] - 1);
        });
      });
    });
    // playhead
    var px_ = Math.round(tx(Math.min(state.t, DATA.duration))) + 0.5;
    ctx.strokeStyle = "#ff5c5c"; ctx.lineWidth = 1.5;
    ctx.beginPath(); ctx.moveTo(px_, TL.axis - 6); ctx.lineTo(px_, Ht); ctx.stroke();
    ctx.fillStyle = "#ff5c5c";
    ctx.beginPath(); ctx.moveTo(px_ - 5, TL.axis - 10); ctx.lineTo(px_ + 5, TL.axis - 10); ctx.lineTo(px_, TL.axis - 3); ctx.fill();
  }

  function spanAt(x, y) {
    for (var i = 0; i < TL.rows.length; i++) {
      var r = TL.rows[i];
      if (y < r.y || y > r.y + r.h) continue;
      var t = xt(x), by = r.y + r.lanes * TL.lane + 2;
      if (y >= by && r.blendH) {
        var half = y < by + TL.blend / 2 ? "upper" : "lower";
        var hits = r.blends.filter(function (b) { return t >= b.start && t <= b.end && (b.lane === "both" || b.lane === half); });
        return hits[0] || null;
      }
      var lane = Math.floor((y - r.y) / TL.lane);
      return r.elements.filter(function (e) { return e.laneIndex === lane && t >= e.start && t <= e.end; })[0] || null;
    }
    return null;
  }

  // ------------------------------------------------------------------ control
  function setTime(t) {
    state.t = Math.max(0, Math.min(t, DATA.duration));
    state.dirty = true;
  }

  function updateUi() {
    var t = Math.min(state.t, DATA.duration);
    actors.forEach(function (A) { sample(A, t); });
    if (Props) Props.sample(t);
    state.frame = actors[0].frame;
    $("time").innerHTML = t.toFixed(2) + " / " + DATA.duration.toFixed(2) + " s<span class=\"frame\">#" + state.frame + "</span>";
    if (!state.scrubbing) $("scrub").value = String(t);
    document.body.setAttribute("data-frame", String(state.frame));
    document.body.setAttribute("data-time", t.toFixed(3));
    $("play").innerHTML = state.playing
      ? '<svg viewBox="0 0 16 16"><path d="M3 2h3.5v12H3zM9.5 2H13v12H9.5z"/></svg>'
      : '<svg viewBox="0 0 16 16"><path d="M4 2l10 6-10 6z"/></svg>';
  }

  function togglePlay() {
    if (!state.playing && state.t >= DATA.duration) state.t = 0;
    state.playing = !state.playing; state.dirty = true;
  }

  // One step of the clock. Driven by requestAnimationFrame, plus a slow heartbeat for when
  // animation frames do not come (a headless browser's virtual time, a hidden tab).
  function step() {
    var now = performance.now();
    var dt = state.last ? Math.min(0.25, (now - state.last) / 1000) : 0;
    state.last = now;
    if (state.playing && !state.scrubbing && DATA.duration > 0) {
      state.t += dt * state.speed;
      if (state.t > DATA.duration) {
        if (!state.loop) { state.t = DATA.duration; state.playing = false; }
        else if (state.t > DATA.duration + HOLD_AT_END) { state.t = 0; }
      }
      state.dirty = true;
    }
    if (state.dirty && now - state.drawn >= state.every) {
      updateUi();
      followStep(state.drawn ? Math.min(0.25, (now - state.drawn) / 1000) : dt);
      render();
      state.drawn = now;
      state.dirty = state.follow && state.playing;
    }
  }
  function tick() { step(); requestAnimationFrame(tick); }
  function heartbeat() { if (performance.now() - state.last > 80) step(); }

  function bindEvents() {
    $("play").addEventListener("click", function () { togglePlay(); this.blur(); });
    $("start").addEventListener("click", function () { setTime(0); this.blur(); });
    var scrub = $("scrub");
    scrub.max = String(DATA.duration); scrub.step = "0.001";
    scrub.addEventListener("input", function () { setTime(parseFloat(scrub.value)); });
    scrub.addEventListener("pointerdown", function () { state.scrubbing = true; });
    window.addEventListener("pointerup", function () { state.scrubbing = false; });
    $("speed").addEventListener("change", function () { state.speed = parseFloat(this.value); this.blur(); });
    $("follow").addEventListener("change", function () { state.follow = this.checked; state.dirty = true; });
    $("loop").addEventListener("change", function () { state.loop = this.checked; });

    window.addEventListener("keydown", function (e) {
      var tag = e.target && e.target.tagName;
      if (e.key === " " || e.code === "Space") { e.preventDefault(); togglePlay(); return; }
      if (tag === "SELECT" || (tag === "INPUT" && e.target.type === "range")) return;
      var A = actors[0];
      if (e.key === "ArrowRight" || e.key === "ArrowLeft") {
        e.preventDefault(); state.playing = false;
        setTime((Math.round(state.t * A.fps) + (e.key === "ArrowRight" ? 1 : -1)) / A.fps);
      } else if (e.key === "Home") { setTime(0); }
      else if (e.key === "End") { setTime(DATA.duration); }
    });

    var drag = null;
    view.addEventListener("contextmenu", function (e) { e.preventDefault(); });
    view.addEventListener("pointerdown", function (e) {
      drag = { x: e.clientX, y: e.clientY, pan: e.shiftKey || e.button === 2 };
      view.setPointerCapture(e.pointerId); view.classList.add("dragging");
    });
    view.addEventListener("pointermove", function (e) {
      if (!drag) return;
      var dx = e.clientX - drag.x, dy = e.clientY - drag.y;
      drag.x = e.clientX; drag.y = e.clientY;
      if (drag.pan) {
        var s = cam.dist / F;
        var r = basis.r, fw = [-Math.sin(cam.yaw), 0, -Math.cos(cam.yaw)];
        cam.target[0] -= (r[0] * dx - fw[0] * dy) * s; cam.target[2] -= (r[2] * dx - fw[2] * dy) * s;
        if (state.follow) { state.follow = false; $("follow").checked = false; }
      } else {
        cam.yaw -= dx * 0.008;
        cam.pitch = Math.max(-0.15, Math.min(1.45, cam.pitch + dy * 0.006));
      }
      state.dirty = true;
    });
    var endDrag = function () { drag = null; view.classList.remove("dragging"); };
    view.addEventListener("pointerup", endDrag); view.addEventListener("pointercancel", endDrag);
    view.addEventListener("wheel", function (e) {
      e.preventDefault();
      cam.dist = Math.max(0.6, Math.min(300, cam.dist * Math.exp(e.deltaY * 0.0012)));
      state.dirty = true;
    }, { passive: false });
    view.addEventListener("dblclick", resetCamera);

    var seeking = false;
    function seekAt(e) {
      var r = tl.getBoundingClientRect();
      setTime(xt(e.clientX - r.left));
    }
    tl.addEventListener("pointerdown", function (e) { seeking = true; state.scrubbing = true; tl.setPointerCapture(e.pointerId); seekAt(e); });
    tl.addEventListener("pointermove", function (e) {
      var r = tl.getBoundingClientRect(), x = e.clientX - r.left, y = e.clientY - r.top;
      if (seeking) seekAt(e);
      var s = spanAt(x, y);
      if (s) {
        tip.style.display = "block";
        tip.textContent = s.label + "  " + s.start.toFixed(2) + "–" + s.end.toFixed(2) + " s" +
          (s.kind === "blend" ? "  (" + (s.part || "whole body") + " blend)" : "");
        var left = Math.min(x + 12, r.width - tip.offsetWidth - 4);
        tip.style.left = Math.max(4, left) + "px"; tip.style.top = Math.max(0, y - 30) + "px";
      } else { tip.style.display = "none"; }
    });
    tl.addEventListener("pointerleave", function () { tip.style.display = "none"; });
    var endSeek = function () { seeking = false; state.scrubbing = false; };
    tl.addEventListener("pointerup", endSeek); tl.addEventListener("pointercancel", endSeek);
    window.addEventListener("resize", resize);
    if (typeof ResizeObserver !== "undefined") {
      new ResizeObserver(function () {
        var r = view.getBoundingClientRect();
        if (Math.abs(r.width - W) > 0.5 || Math.abs(r.height - H) > 0.5) { resize(); if (state.ready) { updateUi(); render(); } }
      }).observe(view);
    }
  }

  function buildLegend() {
    var lg = $("legend");
    while (lg.firstChild) lg.removeChild(lg.firstChild);
    actors.forEach(function (A) {
      if (!A.meta.name) return;
      var row = document.createElement("div"); row.className = "actor";
      var chip = document.createElement("span"); chip.className = "chip"; chip.style.background = A.meta.color;
      var name = document.createElement("span"); name.textContent = A.meta.name;
      row.appendChild(chip); row.appendChild(name); lg.appendChild(row);
    });
    if (Props) Props.legend(lg);
  }

  var api = {
    get frame() { return actors.length ? Math.round(Math.min(state.t, actors[0].duration) * actors[0].fps) : 0; },
    get time() { return state.t; },
    // the page's clock (performance.now(), ms) at the step that set `time`: rates of play are measured on it
    get clock() { return state.last; },
    get playing() { return state.playing; },
    get ready() { return state.ready; },
    get duration() { return DATA.duration; },
    get speed() { return state.speed; },
    get follow() { return state.follow; },
    get camera() { return { yaw: cam.yaw, pitch: cam.pitch, dist: cam.dist, target: cam.target.slice() }; },
    // page coordinates of time t on the timeline's first row (for tests driving the mouse)
    timelinePoint: function (t) {
      var r = tl.getBoundingClientRect(), row = TL.rows[0];
      return { x: r.left + tx(t), y: r.top + (row ? row.y + TL.lane / 2 : TL.axis + 5) };
    },
    play: function () { state.playing = true; state.dirty = true; },
    pause: function () { state.playing = false; state.dirty = true; },
    seek: setTime,
    load: load,
    // the document playing (viewer_data()'s: the page's own, or the latest load()ed)
    get data() { return DATA; },
    // draw at most this many frames a second while playing (0: at every animation frame, the default): a page
    // that shares the machine with the work it shows (the studio) draws at the motion's own rate
    get maxFps() { return state.every ? Math.round(1000 / (state.every + 2)) : 0; },
    set maxFps(fps) { state.every = fps > 0 ? 1000 / fps - 2 : 0; },
    // draw a body (true) or the stick figure (false, the default)
    get body() { return BODY.on; },
    set body(on) { BODY.on = !!on; state.dirty = true; },
    errors: window.__t2aErrors || []
  };
  window.__t2a = api;

  // Another animation in place of the one playing (a front end that updates its view, the studio): ``data`` is
  // viewer_data()'s document; it is decoded first, then swapped in at once, the playing time kept (within the
  // new length), the camera too unless ``home`` (then framed as a new page frames it). A promise, resolved once
  // the new animation is drawn. Of two loads in flight the later one wins, whichever is decoded first.
  var loads = 0;
  function load(data, home) {
    if (data.props && !Props) return Promise.reject(new Error("this page was written without things (props.js)"));
    var mine = ++loads;
    return Promise.all([Promise.all(data.actors.map(function (a) { return decodeActor(a, data.encoding); })),
                        Props ? Props.decode(data.props || [], data.encoding) : null]).then(function (got) {
      if (mine !== loads) return;
      DATA = data; actors = got[0];
      if (Props) Props.use(got[1]);
      state.t = Math.min(state.t, DATA.duration);
      $("title").textContent = DATA.title || "text2anim"; document.title = DATA.title || "text2anim";
      $("scrub").max = String(DATA.duration);
      buildRows(); buildLegend(); resize();
      if (home) initCamera();
      updateUi(); render();
      state.dirty = true;
    });
  }

  // the page's own Japanese font (a subset embedded by render_html), loaded before the canvas draws names
  var fontLoaded = document.fonts && document.fonts.load ?
    document.fonts.load('13px "t2a-jp"').catch(function () { return null; }) : null;
  Promise.all([Promise.all(DATA.actors.map(function (a) { return decodeActor(a); })),
               Props ? Props.decode(DATA.props || []) : null, fontLoaded]).then(function (got) {
    actors = got[0];
    if (Props) Props.use(got[1]);
    $("message").style.display = "none";
    buildRows();
    buildLegend();
    bindEvents();
    resize();
    initCamera();
    state.ready = true;
    document.body.setAttribute("data-ready", "1");
    updateUi();
    render();
    state.last = performance.now();
    requestAnimationFrame(tick);
    setInterval(heartbeat, 100);
  }).catch(function (err) {
    $("message").textContent = "cannot show the animation: " + (err && err.message ? err.message : err);
    document.body.setAttribute("data-ready", "error");
    throw err;
  });
})();
