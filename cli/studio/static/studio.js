/* text2anim studio: the text box drives /api/animate (after a pause in typing; the latest text wins,
 * a stale request is aborted); the answer's viewer page plays in the iframe and its time table is
 * drawn below. Dragging a bar moves the motion, dragging its right end stretches it, clicking it picks
 * how it joins the one before; the edits are kept by verb and occurrence (text2anim.edits) and sent with
 * every text, so editing the text keeps those that still apply. "add" appends a sentence and resumes
 * playback at the time on screen. State for tests and the benchmark: window.__studio. */
(function () {
  "use strict";
  var $ = function (id) { return document.getElementById(id); };
  var DEBOUNCE_MS = 250;
  var S = { text: null, note: "", seq: 0, shown: 0, controller: null, timer: 0, firedAt: 0, resumeAt: null,
            renders: 0, lastLatencyMs: null, latencies: [], table: [], error: "", busy: false,
            edits: {}, sent: "" };
  window.__studio = S;

  function status(msg) { $("status").textContent = msg; }

  // the session's token, from the page the studio served: every state-changing request carries it
  var TOKEN = (document.querySelector('meta[name="t2a-token"]') || {}).content || "";
  function sends(headers) {
    var out = { "X-Studio-Token": TOKEN };
    Object.keys(headers).forEach(function (k) { out[k] = headers[k]; });
    return out;
  }

  function schedule() {
    clearTimeout(S.timer);
    S.timer = setTimeout(animate, DEBOUNCE_MS);
  }

  function editList() {
    return Object.keys(S.edits).sort().map(function (k) { return S.edits[k]; });
  }

  function animate() {
    var text = $("text").value, edits = editList(), sent = text + "\u0000" + JSON.stringify(edits);
    if (sent === S.sent && !S.error) return;
    S.sent = sent;
    if (S.controller) S.controller.abort();
    var ctl = new AbortController(), seq = ++S.seq;
    S.controller = ctl; S.firedAt = performance.now(); S.busy = true;
    status("animating…");
    fetch("/api/animate", { method: "POST", headers: sends({ "Content-Type": "application/json" }),
                            body: JSON.stringify({ text: text, edits: edits }), signal: ctl.signal })
      .then(function (r) { return r.json(); })
      .then(function (data) { if (seq === S.seq) show(data, text, seq); })
      .catch(function (e) { if (e.name !== "AbortError" && seq === S.seq) fail(String(e)); });
  }

  function fail(msg) {
    S.error = msg; S.busy = false;
    $("error").textContent = msg;
    status("");
  }

  function marks(text, data) {
    // unknown verbs underlined where they are written, with what may stand in (each previewable);
    // the analyser's notes (a typo read as meant) on hover; what the animation could not show (a manner
    // no modifier does, an element that did not fit) in words
    var box = $("marks"), unknown = (data && data.unknown) || [], notes = (data && data.notes) || [];
    var warnings = (data && data.warnings) || [];
    while (box.firstChild) box.removeChild(box.firstChild);
    S.unknown = unknown;
    if (!unknown.length && !notes.length && !warnings.length) return;
    var spans = unknown.filter(function (u) { return u.span; }).sort(function (a, b) { return a.span[0] - b.span[0]; });
    var at = 0;
    spans.forEach(function (u) {
      if (u.span[0] < at) return;
      box.appendChild(document.createTextNode(text.slice(at, u.span[0])));
      var mark = document.createElement("u");
      mark.className = "unknown"; mark.title = u.why; mark.textContent = text.slice(u.span[0], u.span[1]);
      box.appendChild(mark);
      at = u.span[1];
    });
    if (spans.length) box.appendChild(document.createTextNode(text.slice(at)));
    unknown.forEach(function (u) {
      var row = document.createElement("div");
      row.appendChild(document.createTextNode(u.written + ": "));
      (u.standin ? [u.standin] : []).concat(u.nearest).forEach(function (v, i) {
        var b = document.createElement("button");
        b.type = "button"; b.className = i === 0 && u.standin ? "standin" : "nearest";
        b.textContent = (i === 0 && u.standin ? "stand-in " : "preview ") + v;
        b.title = i === 0 && u.standin ? u.why : "the database's " + v + ", nearest by meaning (not a stand-in)";
        b.addEventListener("click", function () { preview(v); });
        row.appendChild(b);
      });
      box.appendChild(row);
    });
    if (notes.length) {
      var n = document.createElement("span");
      n.className = "note"; n.textContent = "read differently from how it is written"; n.title = notes.join("\n");
      box.appendChild(n);
    }
    warnings.forEach(function (w) {
      var row = document.createElement("div");
      row.className = "warning"; row.textContent = w;
      box.appendChild(row);
    });
  }

  function preview(verb) {
    // the verb's clip in the view, the text left as it is
    fetch("/api/animate", { method: "POST", headers: sends({ "Content-Type": "application/json" }),
                            body: JSON.stringify({ text: verb + "。" }) })
      .then(function (r) { return r.json(); })
      .then(function (data) {
        if (!data.ok) { fail(data.error); return; }
        S.previewing = verb;
        $("view").onload = null;  // a preview is no render of the text
        $("view3d").hidden = true; $("view").hidden = false;
        $("view").srcdoc = data.html;
        status("preview: " + verb + " (" + data.table.map(function (e) { return e.clip; }).join(", ") + ")");
      });
  }

  function show(data, text, seq) {
    marks(text, data);
    if (!data.ok) { S.text = text; fail(data.error); return; }
    S.error = ""; S.text = text; S.table = data.table;
    $("error").textContent = "";
    $("share").href = "/?text=" + encodeURIComponent(text);
    var view = $("view");
    timeline(data);
    window.__studioTop.show(data.top);
    // the skinned view draws one character; with several (a partner, a person only spoken to) the export
    // holds one file each, and the page draws them as figures
    var actors = new Set(data.table.map(function (e) { return e.actor; })).size;
    if (data.rig && actors === 1) { skinned(text, seq, data); return; }
    S.note = data.rig ? " (" + actors + " characters: the figures here, each on your character in the export)" : "";
    if (data.rig) $("builtin").hidden = false;  // the dropped character is still what the export animates
    $("view3d").hidden = true; view.hidden = false;
    view.onload = function () { ready(view, seq, data); };
    view.srcdoc = data.html;
  }

  function ready(view, seq, data) {
    var w = view.contentWindow, tries = 0;
    (function wait() {
      var api = w.__t2a;
      if (!api || !api.ready) { if (tries++ < 500) setTimeout(wait, 2); return; }
      if (S.resumeAt !== null) { api.seek(Math.min(S.resumeAt, api.duration)); api.play(); S.resumeAt = null; }
      w.requestAnimationFrame(function () {  // the first frame of the new animation is on screen
        var ms = performance.now() - S.firedAt;
        S.lastLatencyMs = ms; S.latencies.push(ms); S.renders++; S.shown = seq; S.busy = false;
        status(data.duration.toFixed(2) + " s of animation, on screen " + Math.round(ms) + " ms after the pause"
               + (S.note || ""));
      });
    })();
  }

  function skinned(text, seq, data) {
    // the dropped character, skinned: the GLB the studio exports for it, drawn by three.js (studio3d.js)
    if (!window.__studio3dApi) { setTimeout(function () { skinned(text, seq, data); }, 20); return; }  // module loading
    var api3d = window.__studio3dApi, s3 = window.__studio3d;
    var at = S.resumeAt !== null ? S.resumeAt : (s3 && s3.ready ? s3.time : 0);
    $("builtin").hidden = false;
    S.resumeAt = null;
    fetch("/api/export", { method: "POST", headers: sends({ "Content-Type": "application/json" }),
                           body: JSON.stringify({ text: text, edits: editList(), format: "glb" }) })
      .then(function (r) { if (!r.ok) throw new Error("cannot draw the character"); return r.arrayBuffer(); })
      .then(function (buffer) {
        var hidden = $("view").contentWindow && $("view").contentWindow.__t2a;
        if (hidden && hidden.ready) hidden.pause();  // a hidden viewer drawing every frame slows the skinned one
        $("view").hidden = true; $("view3d").hidden = false;
        return api3d.show(buffer, at);
      })
      .then(function () {
        if (seq !== S.seq) return;
        var ms = performance.now() - S.firedAt;
        S.lastLatencyMs = ms; S.latencies.push(ms); S.renders++; S.shown = seq; S.busy = false;
        status(data.duration.toFixed(2) + " s of animation on your character, on screen " + Math.round(ms) + " ms after the pause");
      })
      .catch(function (e) { fail(String(e)); });
  }

  function svg(tag, attrs, text) {
    var el = document.createElementNS("http://www.w3.org/2000/svg", tag);
    for (var k in attrs) el.setAttribute(k, attrs[k]);
    if (text !== undefined) el.textContent = text;
    return el;
  }

  function lanes(rows) {
    // each bar in the first lane where it overlaps nothing (a transition starts before the last one ends)
    var ends = [];
    return rows.map(function (e) {
      var k = 0;
      while (k < ends.length && ends[k] > e.start + 1e-6) k++;
      ends[k] = e.end;
      return k;
    });
  }

  function timeline(data) {
    var g = $("timeline"), W = g.clientWidth || 900, LEFT = 90, ROW = 28, BLEND = 8, y = 8;
    while (g.firstChild) g.removeChild(g.firstChild);
    var actors = [];
    data.table.forEach(function (e) { if (actors.indexOf(e.actor) < 0) actors.push(e.actor); });
    var T = Math.max(data.duration, 0.1), x = function (t) { return LEFT + (W - LEFT - 10) * t / T; };
    actors.forEach(function (a) {
      var rows = data.table.filter(function (e) { return e.actor === a; }), lane = lanes(rows);
      var n = Math.max.apply(null, lane.concat([0])) + 1;
      g.appendChild(svg("text", { x: 8, y: y + 18, "class": "actor" }, a));
      rows.forEach(function (e, i) {
        var top = y + lane[i] * ROW;
        var bar = svg("rect", { x: x(e.start), y: top + 2, width: Math.max(2, x(e.end) - x(e.start)), height: ROW - 6,
                                rx: 4, "class": "bar " + e.method + (e.key ? " editable" : ""), "data-id": e.id,
                                "data-verb": e.verb });
        if (e.key) draggable(bar, e, (W - LEFT - 10) / T);
        var how = e.manner ? " · " + e.manner.word + (e.manner.style ? " (" + e.manner.style + ")" : "") : "";
        bar.appendChild(svg("title", {}, e.id + " " + e.verb + " (" + e.clip + ", " + e.method + ") " +
                            e.start.toFixed(2) + "–" + e.end.toFixed(2) + " s" + how));
        g.appendChild(bar);
        g.appendChild(svg("text", { x: x(e.start) + 6, y: top + 18 }, e.id + " " + e.verb + how + " · " + e.method));
      });
      y += n * ROW;
      data.blends.filter(function (b) { return b.actor === a; }).forEach(function (b) {
        var blend = svg("rect", { x: x(b.start), y: y, width: Math.max(1, x(b.end) - x(b.start)), height: BLEND,
                                  "class": "blend" });
        blend.appendChild(svg("title", {}, b.label + " " + (b.part || "") + " " + b.start.toFixed(2) + "–" +
                              b.end.toFixed(2) + " s"));
        g.appendChild(blend);
      });
      y += BLEND + 10;
    });
    g.appendChild(svg("text", { x: LEFT, y: y + 12, "class": "actor" }, "0 s"));
    g.appendChild(svg("text", { x: W - 60, y: y + 12, "class": "actor" }, T.toFixed(2) + " s"));
    g.setAttribute("height", String(y + 20));
  }

  function edit(e) {
    var k = e.key[0] + "#" + e.key[1];
    return S.edits[k] || (S.edits[k] = { verb: e.key[0], nth: e.key[1] });
  }

  function draggable(bar, e, pxPerS) {
    // drag the body: move (shift); drag the right end: stretch (duration); a click: the join method menu
    bar.addEventListener("pointerdown", function (ev) {
      var r = bar.getBoundingClientRect(), stretch = ev.clientX > r.right - 10, x0 = ev.clientX;
      var x = parseFloat(bar.getAttribute("x")), w = parseFloat(bar.getAttribute("width"));
      bar.setPointerCapture(ev.pointerId);
      function move(mv) {
        var dx = mv.clientX - x0;
        if (stretch) bar.setAttribute("width", String(Math.max(4, w + dx)));
        else bar.setAttribute("x", String(x + dx));
      }
      function up(uv) {
        bar.removeEventListener("pointermove", move);
        bar.removeEventListener("pointerup", up);
        var dt = (uv.clientX - x0) / pxPerS;
        if (Math.abs(uv.clientX - x0) < 3) { menu(e, uv); return; }
        var ed = edit(e);
        if (stretch) ed.duration = Math.max(0.2, Math.round((e.end - e.start + dt) * 100) / 100);
        else ed.shift = Math.round(((ed.shift || 0) + dt) * 100) / 100;
        animate();
      }
      bar.addEventListener("pointermove", move);
      bar.addEventListener("pointerup", up);
    });
  }

  function menu(e, ev) {
    var m = $("method");
    m.value = e.method === "composition" || e.method === "transition" ? e.method : "connection";
    m.style.left = ev.pageX + "px"; m.style.top = ev.pageY + "px"; m.style.display = "block";
    m.onchange = function () { edit(e).method = m.value; m.style.display = "none"; animate(); };
    m.onblur = function () { m.style.display = "none"; };
    m.focus();
  }

  function append() {
    var more = $("add").value.trim();
    if (!more) return;
    var api = $("view").contentWindow && $("view").contentWindow.__t2a, s3 = window.__studio3d;
    if (!$("view3d").hidden && s3 && s3.ready) S.resumeAt = s3.time;  // playback goes on from the frame on screen
    else S.resumeAt = api && api.ready ? api.time : 0;
    var text = $("text").value.trim();
    $("text").value = text + (/[。！？!?]$/.test(text) || !text ? "" : "。") + more;
    $("add").value = "";
    clearTimeout(S.timer);
    animate();
  }

  function exportBvh() {
    var text = $("text").value;
    fetch("/api/export", { method: "POST", headers: sends({ "Content-Type": "application/json" }),
                           body: JSON.stringify({ text: text, edits: editList(), format: $("format").value }) })
      .then(function (r) {
        if (!r.ok) return r.json().then(function (d) { fail(d.error || "cannot export"); });
        var name = /filename="([^"]+)"/.exec(r.headers.get("Content-Disposition") || "");
        return r.blob().then(function (blob) {
          var a = document.createElement("a");
          a.href = URL.createObjectURL(blob); a.download = name ? name[1] : "animation.bvh";
          document.body.appendChild(a); a.click(); a.remove();
        });
      })
      .catch(function (e) { fail(String(e)); });
  }

  function search() {
    fetch("/api/verbs?q=" + encodeURIComponent($("search").value))
      .then(function (r) { return r.json(); })
      .then(function (data) {
        var box = $("verbs");
        while (box.firstChild) box.removeChild(box.firstChild);
        data.verbs.forEach(function (v) {
          var b = document.createElement("button");
          b.type = "button"; b.textContent = v.verb + " (" + v.clips + ")"; b.title = v.reading + ": preview";
          b.addEventListener("click", function () { preview(v.verb); });
          box.appendChild(b);
        });
      });
  }

  function dropped(file) {
    var name = file.name || "", lower = name.toLowerCase(), headers = sends({ "X-Filename": encodeURIComponent(name) });
    var url;
    if (/\.bvh$/.test(lower)) {
      var verb = window.prompt("Which verb does " + name + " show? (e.g. 歩く)", "");
      if (!verb) return;
      headers["X-Verb"] = encodeURIComponent(verb);
      url = "/api/import";
    } else if (/\.(glb|vrm)$/.test(lower)) {
      url = "/api/rig";
    } else { fail(name + ": drop a .bvh clip or a .glb/.vrm character"); return; }
    $("dropped").textContent = name + ": reading…";
    fetch(url, { method: "POST", headers: headers, body: file })
      .then(function (r) { return r.json(); })
      .then(function (d) {
        if (!d.ok) { $("dropped").textContent = ""; fail(d.error); return; }
        $("dropped").textContent = url === "/api/import"
          ? name + ": stored as clip " + d.clip + " (" + d.verbs.join("/") + ", " + d.seconds + " s)"
          : name + ": the animation is shown and exported on this character (" + d.joints + " joints)";
        S.sent = ""; animate();  // what plays may have changed
      })
      .catch(function (e) { fail(String(e)); });
  }

  document.addEventListener("dragover", function (e) { e.preventDefault(); document.body.classList.add("dragging"); });
  document.addEventListener("dragleave", function () { document.body.classList.remove("dragging"); });
  document.addEventListener("drop", function (e) {
    e.preventDefault(); document.body.classList.remove("dragging");
    if (e.dataTransfer && e.dataTransfer.files.length) dropped(e.dataTransfer.files[0]);
  });
  window.__studio.drop = dropped;  // tests hand it a File, as a drop does
  $("search").addEventListener("input", search);
  $("builtin").addEventListener("click", function () {
    fetch("/api/rig", { method: "DELETE", headers: sends({}) }).then(function () {
      $("builtin").hidden = true; $("dropped").textContent = ""; S.sent = ""; animate();
    });
  });
  $("text").addEventListener("input", schedule);
  $("add-btn").addEventListener("click", append);
  $("add").addEventListener("keydown", function (e) { if (e.key === "Enter") append(); });
  $("export").addEventListener("click", exportBvh);
  $("reset-edits").addEventListener("click", function () { S.edits = {}; animate(); });
  var start = new URLSearchParams(location.search).get("text");
  $("text").value = start !== null ? start : "太郎は走って、ボールを蹴る。そして喜ぶ。";
  animate();
})();
