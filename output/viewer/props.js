  // -------------------------------------------------------------------- props
  // The things of the scene (DATA.props). render_html inlines this file into viewer.js only when the
  // page has some. Each thing is made of solid parts (box, cylinder, ellipsoid: output/shapes.py) in its
  // own frame, moved and turned per frame; a part is drawn face by face (the faces turned away culled,
  // lit from above) at its depth among the actors' bones (draw); a soft shadow under each thing, its name
  // above it, a round chip in the legend.
  Props = (function () {
    var list = [], LIGHT = unit([0.35, 0.85, 0.45]), SEGMENTS = 18, FRAME_NEAR = 3;
    var CORNERS = [[-1, -1], [1, -1], [1, 1], [-1, 1]];
    var FRAMES = [[1, 2, 0], [2, 0, 1], [0, 1, 2]];  // a cylinder's (a, b, axis): a x b = axis

    function unit(v) { var n = Math.hypot(v[0], v[1], v[2]) || 1; return [v[0] / n, v[1] / n, v[2] / n]; }
    function dot(a, b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

    // per coordinate, running sums of int32 differences (k rows of T) into frame-major values / scale
    function sums(u8, k, T, scale, name) {
      var v = new DataView(u8.buffer, u8.byteOffset, u8.byteLength), out = new Float64Array(T * k);
      if (v.byteLength !== k * T * 4) throw new Error("thing " + name + ": data has the wrong size");
      for (var c = 0; c < k; c++) {
        var acc = 0;
        for (var t = 0; t < T; t++) { acc += v.getInt32((c * T + t) * 4, true); out[t * k + c] = acc / scale; }
      }
      return out;
    }

    // the things of a viewer_data() document, decoded (use() shows them)
    function decode(props, encoding) {
      return Promise.all(props.map(function (p) {
        return Promise.all([bytesOf(p.pos, encoding), bytesOf(p.rot, encoding)]).then(function (b) {
          return { meta: p, T: p.frames, pos: sums(b[0], 3, p.frames, 1000, p.name),
            rot: sums(b[1], 4, p.frames, 32767, p.name), base: hexRgb(p.color), at: [0, 0, 0], R: null };
        });
      }));
    }
    function use(decoded) { list = decoded; }

    function sampleOne(P, t) {
      var f = Math.max(0, Math.min(t * P.meta.fps, P.T - 1)), i0 = Math.floor(f), i1 = Math.min(i0 + 1, P.T - 1);
      var w = f - i0, q = [0, 0, 0, 0], k;
      for (k = 0; k < 3; k++) P.at[k] = P.pos[i0 * 3 + k] * (1 - w) + P.pos[i1 * 3 + k] * w;
      for (k = 0; k < 4; k++) q[k] = P.rot[i0 * 4 + k] * (1 - w) + P.rot[i1 * 4 + k] * w;
      var n = Math.hypot(q[0], q[1], q[2], q[3]) || 1, x = q[0] / n, y = q[1] / n, z = q[2] / n, s = q[3] / n;
      P.R = [1 - 2 * (y * y + z * z), 2 * (x * y - z * s), 2 * (x * z + y * s),
        2 * (x * y + z * s), 1 - 2 * (x * x + z * z), 2 * (y * z - x * s),
        2 * (x * z - y * s), 2 * (y * z + x * s), 1 - 2 * (x * x + y * y)];
    }
    function sample(t) { list.forEach(function (P) { sampleOne(P, t); }); }

    function turn(P, v) {
      var R = P.R;
      return [R[0] * v[0] + R[1] * v[1] + R[2] * v[2], R[3] * v[0] + R[4] * v[1] + R[5] * v[2],
        R[6] * v[0] + R[7] * v[1] + R[8] * v[2]];
    }
    function world(P, v) { var d = turn(P, v); return [P.at[0] + d[0], P.at[1] + d[1], P.at[2] + d[2]]; }

    // the faces of a part, in the prop's frame: {pts, n, edge}
    function faces(part) {
      var c = [part[1], part[2], part[3]], h = [part[4] / 2, part[5] / 2, part[6] / 2], out = [];
      function at(v) { return [c[0] + v[0] * h[0], c[1] + v[1] * h[1], c[2] + v[2] * h[2]]; }
      if (part[0] === 0) {  // box
        for (var ax = 0; ax < 3; ax++) {
          for (var sg = -1; sg <= 1; sg += 2) {
            var u = (ax + 1) % 3, v = (ax + 2) % 3, n = [0, 0, 0];
            n[ax] = sg;
            out.push({ n: n, edge: true, pts: CORNERS.map(function (cv) {
              var p = [0, 0, 0]; p[ax] = sg; p[u] = cv[0]; p[v] = cv[1]; return at(p);
            }) });
          }
        }
      } else if (part[0] === 1) {  // cylinder: side strips and two caps
        var fr = FRAMES[part[7]], a = fr[0], b = fr[1], x = fr[2], ring = [];
        for (var i = 0; i < SEGMENTS; i++) {
          var ang = i * 2 * Math.PI / SEGMENTS, r = [0, 0, 0];
          r[a] = Math.cos(ang); r[b] = Math.sin(ang);
          ring.push(r);
        }
        var lift = function (r, s) { var p = r.slice(); p[x] = s; return at(p); };
        for (i = 0; i < SEGMENTS; i++) {
          var r0 = ring[i], r1 = ring[(i + 1) % SEGMENTS], nn = [0, 0, 0];
          nn[a] = (r0[a] + r1[a]) / h[a]; nn[b] = (r0[b] + r1[b]) / h[b];
          out.push({ n: unit(nn), edge: false, pts: [lift(r0, -1), lift(r1, -1), lift(r1, 1), lift(r0, 1)] });
        }
        [-1, 1].forEach(function (s) {
          var n = [0, 0, 0];
          n[x] = s;
          out.push({ n: n, edge: true, pts: ring.map(function (r) { return lift(r, s); }) });
        });
      }
      return out;
    }

    function shade(P, n) {
      var lit = Math.max(0, dot(n, LIGHT));
      return mix(mix(P.base, BLACK, 0.5), mix(P.base, WHITE, 0.22), lit);
    }

    function drawPart(ctx, P, part) {
      if (part[0] === 2) { drawBall(ctx, P, part); return; }
      var eye = basis.eye;
      faces(part).forEach(function (f) {
        var n = turn(P, f.n), pts = f.pts.map(function (p) { return world(P, p); });
        var mid = [0, 0, 0];
        pts.forEach(function (p) { mid[0] += p[0] / pts.length; mid[1] += p[1] / pts.length; mid[2] += p[2] / pts.length; });
        if (dot(n, [mid[0] - eye[0], mid[1] - eye[1], mid[2] - eye[2]]) >= 0) return;  // turned away
        var sc = [];
        for (var i = 0; i < pts.length; i++) {
          var q = toCam(pts[i][0], pts[i][1], pts[i][2]);
          if (q[2] <= NEAR) return;
          sc.push(toScreen(q));
        }
        ctx.beginPath();
        sc.forEach(function (s, k) { if (k) ctx.lineTo(s[0], s[1]); else ctx.moveTo(s[0], s[1]); });
        ctx.closePath();
        var col = css(shade(P, n));
        ctx.fillStyle = col; ctx.fill();
        ctx.lineJoin = "round";
        ctx.strokeStyle = f.edge ? css(mix(P.base, BLACK, 0.7), 0.9) : col;  // a strip's own colour hides its seams
        ctx.lineWidth = f.edge ? 1 : 0.6;
        ctx.stroke();
      });
    }

    function drawBall(ctx, P, part) {
      var c = world(P, [part[1], part[2], part[3]]), q = toCam(c[0], c[1], c[2]);
      if (q[2] <= NEAR) return;
      var s = toScreen(q), r = Math.max(1.5, (part[4] + part[5] + part[6]) / 6 * F / q[2]);
      var g = ctx.createRadialGradient(s[0] - r * 0.35, s[1] - r * 0.4, r * 0.1, s[0], s[1], r);
      g.addColorStop(0, css(mix(P.base, WHITE, 0.45))); g.addColorStop(0.55, css(P.base));
      g.addColorStop(1, css(mix(P.base, BLACK, 0.35)));
      ctx.beginPath(); ctx.arc(s[0], s[1], r, 0, Math.PI * 2);
      ctx.fillStyle = g; ctx.fill();
      ctx.strokeStyle = css(mix(P.base, BLACK, 0.7), 0.9); ctx.lineWidth = 1; ctx.stroke();
    }

    // Each part at its depth with its box on screen ([x0, y0, x1, y1], from its corners).
    function pieces() {
      var out = [];
      list.forEach(function (P) {
        P.meta.parts.forEach(function (part) {
          var c = world(P, [part[1], part[2], part[3]]), box = [Infinity, Infinity, -Infinity, -Infinity];
          for (var k = 0; k < 8; k++) {
            var w = world(P, [part[1] + (k & 1 ? 0.5 : -0.5) * part[4], part[2] + (k & 2 ? 0.5 : -0.5) * part[5],
              part[3] + (k & 4 ? 0.5 : -0.5) * part[6]]), q = toCam(w[0], w[1], w[2]);
            if (q[2] <= NEAR) continue;
            var s = toScreen(q);
            box = [Math.min(box[0], s[0]), Math.min(box[1], s[1]), Math.max(box[2], s[0]), Math.max(box[3], s[1])];
          }
          out.push({ z: toCam(c[0], c[1], c[2])[2], box: box, P: P, part: part });
        });
      });
      return out.sort(function (a, b) { return b.z - a.z; });
    }

    function itemsBox(items) {
      var b = [Infinity, Infinity, -Infinity, -Infinity];
      items.forEach(function (it) {
        var pts = it.kind === 0 ? it.s : [[it.s[0] - it.r, it.s[1] - it.r], [it.s[0] + it.r, it.s[1] + it.r]];
        var pad = it.kind === 0 ? it.w / 2 + 2 : 2;
        pts.forEach(function (p) {
          b = [Math.min(b[0], p[0] - pad), Math.min(b[1], p[1] - pad), Math.max(b[2], p[0] + pad), Math.max(b[3], p[1] + pad)];
        });
      });
      return b;
    }
    function overlap(a, b) { return a[0] <= b[2] && b[0] <= a[2] && a[1] <= b[3] && b[1] <= a[3]; }

    // The painter's algorithm over the actors (in `order`, far to near) and the things' parts: before a part
    // is drawn, every actor it overlaps on screen draws its bones farther than the part (outline, then
    // fills), so a sitter's shins cover the chair's front legs and the chair's back covers nothing of the
    // sitter; an actor the part does not overlap is not cut. Names go on top.
    function draw(ctx, order, zMin, zMax) {
      var bodies = order.map(function (o) {
        var got = actorItems(o.A);
        return { A: o.A, cams: got.cams, items: got.items, box: itemsBox(got.items), next: 0 };
      });
      function upTo(u, z) {
        var k = u.next;
        while (k < u.items.length && u.items[k].z > z) k++;
        if (k > u.next) paintItems(ctx, u.A, u.cams, u.items.slice(u.next, k), zMin, zMax);
        u.next = k;
      }
      pieces().forEach(function (pc) {
        bodies.forEach(function (u) { if (overlap(u.box, pc.box)) upTo(u, pc.z); });
        drawPart(ctx, pc.P, pc.part);
      });
      bodies.forEach(function (u) { upTo(u, -Infinity); });
      bodies.forEach(function (u) { drawName(ctx, u.A); });
      labels(ctx);
    }

    function shadows(ctx) {
      list.forEach(function (P) {
        var sz = P.meta.size, low = P.at[1] - sz[1] / 2;
        groundBlob(ctx, P.at[0], P.at[2], 0.55 * Math.max(sz[0], sz[2]) + 0.03, 0.4 * Math.max(0, 1 - low / 1.2));
      });
    }

    function labels(ctx) {
      ctx.font = "600 12px " + getComputedStyle(document.documentElement).fontFamily;
      ctx.textAlign = "center"; ctx.textBaseline = "bottom";
      list.forEach(function (P) {
        var sz = P.meta.size, up = Math.hypot(sz[0], sz[1], sz[2]) / 2 + 0.05;
        var q = toCam(P.at[0], P.at[1] + up, P.at[2]);
        if (q[2] <= NEAR) return;
        var s = toScreen(q), w = ctx.measureText(P.meta.name).width;
        ctx.fillStyle = "rgba(13,15,19,0.66)";
        roundRect(ctx, s[0] - w / 2 - 6, s[1] - 18, w + 12, 17, 5); ctx.fill();
        ctx.fillStyle = css(mix(P.base, WHITE, 0.35)); ctx.fillText(P.meta.name, s[0], s[1] - 3.5);
      });
    }

    // for the camera's framing, the corners of the box of every thing within FRAME_NEAR metres of an actor at
    // time t (the actors sampled there): a kicked ball rolling 30 m away leaves the picture, as a camera that
    // follows the actors would let it
    function points(t, pts) {
      list.forEach(function (P) {
        sampleOne(P, t);
        var near = actors.some(function (A) { return Math.hypot(A.cur[0] - P.at[0], A.cur[2] - P.at[2]) < FRAME_NEAR; });
        if (!near) return;
        var h = P.meta.size;
        for (var k = 0; k < 8; k++) {
          pts.push(world(P, [(k & 1 ? 0.5 : -0.5) * h[0], (k & 2 ? 0.5 : -0.5) * h[1], (k & 4 ? 0.5 : -0.5) * h[2]]));
        }
      });
    }

    function legend(lg) {
      list.forEach(function (P) {
        var row = document.createElement("div"), chip = document.createElement("span"), name = document.createElement("span");
        row.className = "actor"; chip.className = "chip"; chip.style.background = P.meta.color; chip.style.borderRadius = "50%";
        name.textContent = P.meta.name;
        row.appendChild(chip); row.appendChild(name); lg.appendChild(row);
      });
    }

    return { decode: decode, use: use, sample: sample, draw: draw, shadows: shadows, points: points, legend: legend };
  })();
