/* text2anim studio: the scene seen from above (the numbers of text2anim.output.topview, as the
 * --top-view picture draws them): +z up the page, +x to the left (a person looking down), a grid of 1 m
 * (coarser when the scene is large);
 * each actor's hips path in its colour, a dot where it starts and arrows where it faces at the start
 * and the end, a dot per time-table element where it starts; each thing's footprint at the start (and,
 * dashed, at the end) and its path. A marker per actor and thing follows the time on screen (the viewer
 * page's clock, or the skinned view's). window.__studioTop: show(top), and the last drawn state for tests. */
(function () {
  "use strict";
  var NS = "http://www.w3.org/2000/svg", PAD = 18;
  var T = { top: null, markers: [], shown: 0, time: 0 };
  window.__studioTop = T;

  function el(tag, attrs, text) {
    var e = document.createElementNS(NS, tag);
    for (var k in attrs) e.setAttribute(k, attrs[k]);
    if (text !== undefined) e.textContent = text;
    return e;
  }

  function footPoints(f) {
    if (f.circle) { var c = f.circle; return [[c[0] - c[2], c[1] - c[2]], [c[0] + c[2], c[1] + c[2]]]; }
    return f.polygon;
  }

  function bounds(top) {
    var pts = [];
    top.actors.forEach(function (a) { pts = pts.concat(a.path); });
    top.props.forEach(function (p) { pts = pts.concat(footPoints(p.start), footPoints(p.end), p.path || []); });
    var b = [Infinity, Infinity, -Infinity, -Infinity];
    pts.forEach(function (p) { b = [Math.min(b[0], p[0]), Math.min(b[1], p[1]), Math.max(b[2], p[0]), Math.max(b[3], p[1])]; });
    return b;
  }

  function show(top) {
    var svg = document.getElementById("topview");
    while (svg.firstChild) svg.removeChild(svg.firstChild);
    T.top = top; T.markers = [];
    if (!top || !top.actors.length) return;
    var W = svg.clientWidth || 600, H = svg.clientHeight || 240, b = bounds(top);
    var wx = Math.max(b[2] - b[0], 1) + 1, wz = Math.max(b[3] - b[1], 1) + 1;
    var k = Math.min((W - 2 * PAD) / wx, (H - 2 * PAD) / wz), cx = (b[0] + b[2]) / 2, cz = (b[1] + b[3]) / 2;
    var X = function (x) { return W / 2 - (x - cx) * k; }, Y = function (z) { return H / 2 - (z - cz) * k; };
    var pts = function (list) { return list.map(function (p) { return X(p[0]).toFixed(1) + "," + Y(p[1]).toFixed(1); }).join(" "); };
    var step = [1, 2, 5, 10, 20, 50, 100].filter(function (s) { return s * k >= 20; })[0] || 200;  // metres a line
    for (var gx = Math.ceil((cx - W / 2 / k) / step) * step; gx <= cx + W / 2 / k; gx += step) {
      svg.appendChild(el("line", { x1: X(gx), x2: X(gx), y1: 0, y2: H, "class": gx === 0 ? "axis" : "grid" }));
    }
    for (var gz = Math.ceil((cz - H / 2 / k) / step) * step; gz <= cz + H / 2 / k; gz += step) {
      svg.appendChild(el("line", { x1: 0, x2: W, y1: Y(gz), y2: Y(gz), "class": gz === 0 ? "axis" : "grid" }));
    }
    top.props.forEach(function (p) {
      [[p.start, ""], [p.path ? p.end : null, "end"]].forEach(function (fe) {
        var f = fe[0];
        if (!f) return;
        var shape = f.circle ? el("circle", { cx: X(f.circle[0]), cy: Y(f.circle[1]), r: Math.max(2, f.circle[2] * k) })
          : el("polygon", { points: pts(f.polygon) });
        shape.setAttribute("class", "foot " + fe[1]);
        shape.setAttribute("fill", p.color); shape.setAttribute("stroke", p.color);
        shape.appendChild(el("title", {}, p.name + (fe[1] ? " (end)" : "")));
        svg.appendChild(shape);
      });
      if (p.path) svg.appendChild(el("polyline", { points: pts(p.path), stroke: p.color, "class": "thing-path" }));
      var s = footPoints(p.start)[0];
      svg.appendChild(el("text", { x: X((footPoints(p.start)[0][0] + footPoints(p.start)[1][0]) / 2), y: Y(s[1]) + 12,
        "class": "name", style: "fill:" + p.color, "text-anchor": "middle" }, p.name));
    });
    top.actors.forEach(function (a) {
      svg.appendChild(el("polyline", { points: pts(a.path), stroke: a.color, "class": "path" }));
      var s = a.path[0], e = a.path[a.path.length - 1];
      svg.appendChild(el("circle", { cx: X(s[0]), cy: Y(s[1]), r: 5, fill: a.color, "class": "start" }));
      [[s, a.facing[0]], [e, a.facing[1]]].forEach(function (sf) {
        var f = sf[1];
        if (!f) return;
        var L = Math.max(14, 0.35 * k), x0 = X(sf[0][0]), y0 = Y(sf[0][1]), x1 = x0 - f[0] * L, y1 = y0 - f[1] * L;
        var ux = (x1 - x0) / L, uy = (y1 - y0) / L;
        svg.appendChild(el("line", { x1: x0, y1: y0, x2: x1, y2: y1, stroke: a.color, "class": "facing" }));
        svg.appendChild(el("polygon", { fill: a.color, points: [[x1 + ux * 6, y1 + uy * 6], [x1 - uy * 4, y1 + ux * 4],
          [x1 + uy * 4, y1 - ux * 4]].map(function (p) { return p[0].toFixed(1) + "," + p[1].toFixed(1); }).join(" ") }));
      });
      a.marks.forEach(function (m) {
        svg.appendChild(el("circle", { cx: X(m[1]), cy: Y(m[2]), r: 2.5, fill: a.color, "class": "mark" }));
        svg.appendChild(el("text", { x: X(m[1]) + 5, y: Y(m[2]) + 3, "class": "mark" }, m[0]));
      });
      svg.appendChild(el("text", { x: X(s[0]), y: Y(s[1]) + 18, style: "fill:" + a.color, "class": "name", "text-anchor": "middle" }, a.name));
    });
    top.actors.concat(top.props.filter(function (p) { return p.path; })).forEach(function (it) {
      var m = el("circle", { r: it.marks ? 6 : 4, fill: it.color, "class": "now" });
      svg.appendChild(m);
      T.markers.push({ el: m, path: it.path, step: it.step, X: X, Y: Y });
    });
    svg.appendChild(el("text", { x: 8, y: 14, "class": "legend" }, window.__t2aWord ? window.__t2aWord("topview", { m: step }) : "seen from above: +z ↑, +x ←, " + step + " m grid"));
    T.shown++;
    place(T.time);
  }

  function place(t) {
    T.markers.forEach(function (m) {
      var f = Math.max(0, Math.min(t / m.step, m.path.length - 1)), i = Math.floor(f), j = Math.min(i + 1, m.path.length - 1), w = f - i;
      var x = m.path[i][0] * (1 - w) + m.path[j][0] * w, z = m.path[i][1] * (1 - w) + m.path[j][1] * w;
      m.el.setAttribute("cx", m.X(x).toFixed(1)); m.el.setAttribute("cy", m.Y(z).toFixed(1));
    });
  }

  function clock() {
    var s3 = window.__studio3d, seen = window.__viewerLink && window.__viewerLink.state;  // the framed viewer's last report
    var t = !document.getElementById("view3d").hidden && s3 && s3.ready ? s3.time : seen && seen.ready ? seen.time : 0;
    if (t !== T.time) { T.time = t; place(t); }
    requestAnimationFrame(clock);
  }
  T.show = show;
  requestAnimationFrame(clock);
})();
