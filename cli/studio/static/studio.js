/* text2anim studio: the text box drives /api/animate (after a pause in typing, counted from the end of an
 * input method's composition: nothing is sent while one is open; the latest text wins, a stale request is
 * aborted as soon as the text changes). A new text is answered first with a draft (crossfaded joins, marked
 * 下書き), then with the finished animation, which replaces it in place at the same playing time. The viewer
 * page is loaded into the iframe once; every later answer's data is handed to it in place (its load()), and
 * its time table is drawn below it. The frame is sandboxed (an opaque origin): the page drives the viewer and
 * hears from it through viewer_link.js only (window.__viewerLink; its state is window.__studio.view). Dragging a
 * bar moves the motion, dragging its right end stretches it, clicking it picks how it joins the one before;
 * the edits are kept by verb and occurrence (text2anim.edits) and sent with every text, so editing the text
 * keeps those that still apply. "add" appends a sentence and resumes playback at the time on screen.
 *
 * The work is a project (text, edits, stand-ins: project() / restore()), kept in localStorage, saved and
 * opened as a .t2a.json file (docs/project.md), with an undo history step by step. The page's words come
 * from one catalogue (messages.json, in the page): Japanese, or English by the browser's language or the
 * switch. State for tests and the benchmark: window.__studio. */
(function () {
  "use strict";
  var $ = function (id) { return document.getElementById(id); };
  // the viewer draws at the motion's own 30 fps: at every animation frame (60 a second) headless Chromium took
  // 63% of a core, which the studio's server, on the same machine, needs for the next text
  var DRAW_FPS = 30;
  // the pause after the last keystroke (or the end of a composition) before a text is sent: longer than the
  // gap between two keys of continuous typing; a text sent too early is only a draft, aborted by the next key
  var DEBOUNCE_MS = 120, PROJECT_VERSION = 1, STORE = "t2a-studio-project";
  var S = { text: null, note: "", seq: 0, shown: 0, controller: null, timer: 0, firedAt: 0, resumeAt: null,
            renders: 0, lastLatencyMs: null, latencies: [], table: [], error: "", busy: false,
            edits: {}, sent: "", fallback: "strict", composing: false, requests: 0,
            history: [], at: -1, session: [], lang: "ja", keyAt: 0, keyLatencies: [], character: "body",
            draft: false, drafts: 0, finishLatencies: [], phases: [] };
  window.__studio = S;
  var link = window.__viewerLink;  // the viewer in the frame: commands to it, its state (viewer_link.js)
  S.view = link.state;

  // ---- words: one catalogue, the page's language
  var M = JSON.parse(($("t2a-messages") || {}).textContent || "{}");
  function t(key, args) {
    var m = M[key], s = m ? (m[S.lang] || m.ja) : key.replace(/^m_/, "");
    return s.replace(/\{(\w+)\}/g, function (_, k) { return args && args[k] !== undefined ? String(args[k]) : ""; });
  }
  function words() {
    document.documentElement.lang = S.lang;
    document.querySelectorAll("[data-t]").forEach(function (el) { el.textContent = t(el.getAttribute("data-t")); });
    document.querySelectorAll("[data-title]").forEach(function (el) { el.title = t(el.getAttribute("data-title")); });
    document.querySelectorAll("[data-placeholder]").forEach(function (el) {
      el.placeholder = t(el.getAttribute("data-placeholder")); });
    document.querySelectorAll("[data-label]").forEach(function (el) {
      el.setAttribute("aria-label", t(el.getAttribute("data-label"))); });
    $("lang").value = S.lang;
    if (S.last) {
      marks(S.last.text, S.last.data);
      if (S.last.data.ok) { timeline(S.last.data); window.__studioTop.show(S.last.data.top); } else fail(S.last.data);
    }
    if (link.state.ready) dress();
    library();
  }
  window.__t2aWord = t;  // topview.js words its legend with it

  function dress() {
    // the viewer in the page's words (the studio's font draws them: work.FRAMED_CSS), with the chosen character,
    // drawing at the motion's own rate
    link.set({ body: S.character === "body", maxFps: DRAW_FPS,
               words: { help: t("viewer_help"), speed: t("viewer_speed"), follow: t("viewer_follow"),
                        loop: t("viewer_loop") } });
  }

  function language() {
    var chosen = null;
    try { chosen = localStorage.getItem("t2a-studio-lang"); } catch (e) { /* storage off: the browser's */ }
    if (chosen === "ja" || chosen === "en") return chosen;
    return /^ja\b/i.test(navigator.language || "ja") ? "ja" : (/^en\b/i.test(navigator.language) ? "en" : "ja");
  }

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
    if (S.composing) return;  // the pause counts from compositionend
    S.timer = setTimeout(function () { commit(); animate(); }, DEBOUNCE_MS);
  }

  function editList() {
    return Object.keys(S.edits).sort().map(function (k) { return S.edits[k]; });
  }

  function animate() {
    if (S.composing) return;  // a half-converted text is never sent
    var text = $("text").value, edits = editList();
    var sent = text + "\u0000" + JSON.stringify(edits) + "\u0000" + S.fallback;
    if (sent === S.sent && !S.error) return;
    S.sent = sent;
    var keyAt = S.keyAt;  // the last keystroke of the text sent (the benchmark's keystroke-to-frame); 0: no typing
    S.keyAt = 0; S.firedAt = performance.now();
    status(t("animating"));
    request(text, edits, S.fallback, true, keyAt);
  }

  function viewer() {
    // whether the viewer page in the frame can take an answer in place
    return link.state.ready;
  }

  function request(text, edits, fallback, draft, keyAt, page) {
    // one answer for the text: a draft may come first (draft), the finished one after it; ``page``: the
    // viewer page too, when there is none to load the answer into
    stop();
    var ctl = new AbortController(), seq = ++S.seq;
    S.controller = ctl; S.busy = true; S.requests++;
    fetch("/api/animate", { method: "POST", headers: sends({ "Content-Type": "application/json" }), signal: ctl.signal,
                            body: JSON.stringify({ text: text, edits: edits, fallback: fallback, draft: draft,
                                                   page: !!page || !viewer() }) })
      .then(answer)
      .then(function (data) {
        if (seq !== S.seq) return;
        S.answeredAt = performance.now();
        if (data.ok && !data.html && !viewer()) { request(text, edits, fallback, draft, keyAt, true); return; }
        S.sentKeyAt = keyAt; show(data, text, seq, { text: text, edits: edits, fallback: fallback });
      })
      .catch(function (e) { if (e.name !== "AbortError" && seq === S.seq) fail({ code: "network", error: String(e) }); });
  }

  function stop() {
    // the request in flight abandoned (the server drops its work too, between stages and joins)
    if (S.controller) { S.controller.abort(); S.controller = null; }
  }

  function answer(r) {
    // the JSON of a response; a refusal without one (a proxy, a crash) as the page's own error
    return r.json().catch(function () { return { ok: false, code: "other", error: "HTTP " + r.status }; })
      .then(function (data) {
        if (r.status === 429) data.code = "busy";
        return data;
      });
  }

  var CODES = { empty: "err_empty", too_long: "err_too_long", no_motion: "err_no_motion", limit: "err_limit",
                edit: "err_edit", busy: "err_busy", slow: "err_slow", network: "err_network" };

  function fail(data) {
    // an error in the page's words; what the server said (in the command's English) under "details"
    var box = $("error");
    S.error = data.error || data.code || "error"; S.busy = false; drafted(false);
    while (box.firstChild) box.removeChild(box.firstChild);
    status("");
    if (data.code === "unknown") return;  // said by marks(): the verb, its stand-in button, similar ones
    if (data.notice && noticeKey(data.notice)) {  // a refusal the page words itself (a limit, an edit)
      var row = document.createElement("div");
      said(row, data.notice);
      if (/^edit_/.test(data.notice.kind) && S.at > 0) row.appendChild(button(t("undo_edit"), "", function () { step(-1); }, "undo-edit"));
      box.appendChild(row);
      return;
    }
    var line = document.createElement("div");
    line.textContent = data.message || t(CODES[data.code] || "err_other", { n: data.max });
    box.appendChild(line);
    if (data.error && !data.message && data.code !== "empty" && data.code !== "busy" && data.code !== "network") {
      var more = document.createElement("details"), sum = document.createElement("summary"), pre = document.createElement("div");
      sum.textContent = t("details"); pre.textContent = data.error;
      more.appendChild(sum); more.appendChild(pre); box.appendChild(more);
    }
  }

  function button(label, title, onclick, cls) {
    var b = document.createElement("button");
    b.type = "button"; b.textContent = label; if (title) b.title = title; if (cls) b.className = cls;
    b.addEventListener("click", onclick);
    return b;
  }

  function marks(text, data) {
    // unknown verbs underlined where they are written, each with a button playing the text with its stand-in
    // and the similar verbs to preview; the analyser's notes (a typo read as meant) on hover; what the
    // animation could not show (a manner no modifier does, an element that did not fit) in words
    var box = $("marks"), unknown = (data && data.unknown) || [], notes = (data && data.notes) || [];
    var notices = (data && data.notices) || [], used = (data && data.fallbacks) || [];
    while (box.firstChild) box.removeChild(box.firstChild);
    S.unknown = unknown;
    var spans = unknown.filter(function (u) { return u.span; }).sort(function (a, b) { return a.span[0] - b.span[0]; });
    var at = 0;
    spans.forEach(function (u) {
      if (u.span[0] < at) return;
      box.appendChild(document.createTextNode(text.slice(at, u.span[0])));
      var mark = document.createElement("u");
      mark.className = "unknown"; mark.textContent = text.slice(u.span[0], u.span[1]);
      box.appendChild(mark);
      at = u.span[1];
    });
    if (spans.length) box.appendChild(document.createTextNode(text.slice(at)));
    unknown.forEach(function (u) {
      var row = document.createElement("div");
      row.className = "missing";
      row.appendChild(document.createTextNode(t("unknown", { v: u.written }) + " "));
      if (u.standin) {
        row.appendChild(button(t("unknown_standin", { v: u.standin }), "", function () {
          S.fallback = "nearest"; commit(); animate(); }, "standin"));
      } else row.appendChild(document.createTextNode(t("unknown_none") + " "));
      u.nearest.forEach(function (v) {
        row.appendChild(button(t("unknown_nearest", { v: v }), t("unknown_nearest_title"), function () { preview(v); },
                               "nearest"));
      });
      row.appendChild(button(t("unknown_library"), "", function () {
        $("search").value = u.written.slice(0, 1); search(); $("search").focus(); }, "open-library"));
      box.appendChild(row);
    });
    if (used.length) {
      var row = document.createElement("div");
      row.className = "standing-in";
      row.appendChild(document.createTextNode(used.map(function (f) {
        return t("standing_in", { w: f.written, v: f.used }); }).join("、") + " "));
      row.appendChild(button(t("strict_again"), "", function () { S.fallback = "strict"; commit(); animate(); }));
      box.appendChild(row);
    }
    if (notes.length) {
      var n = document.createElement("span");
      n.className = "note"; n.textContent = t("read_as"); n.title = notes.join("\n");
      box.appendChild(n);
    }
    notices.forEach(function (n) {
      var row = document.createElement("div");
      row.className = "warning"; row.setAttribute("data-kind", n.kind);
      said(row, n);
      if (n.kind === "manner_not_shown") row.appendChild(button(t("unknown_library"), "", function () {
        $("search").value = n.params.verb.slice(0, 1); search(); $("search").focus(); }, "open-library"));
      box.appendChild(row);
    });
  }

  function noticeKey(n) {
    // the catalogue's words for a notice (core/notice.py): n_<kind>, n_<kind>_<why> when it says why, or
    // n_<kind>_any when it names no row; null when the catalogue has none
    var p = n.params || {}, keys = ["n_" + n.kind + "_" + (p.why || ""), p.row === undefined ? "n_" + n.kind + "_any" : "",
                                    "n_" + n.kind];
    for (var i = 0; i < keys.length; i++) if (keys[i] && M[keys[i]]) return keys[i];
    return null;
  }

  function said(box, n) {
    // a notice in the page's words; one the catalogue lacks is a general line with its English under "details"
    var key = noticeKey(n), line = document.createElement("span");
    line.textContent = t(key || "n_other", n.params) + " ";
    box.appendChild(line);
    if (!key) {
      var more = document.createElement("details"), sum = document.createElement("summary"), pre = document.createElement("div");
      sum.textContent = t("details"); pre.textContent = n.text;
      more.appendChild(sum); more.appendChild(pre); box.appendChild(more);
    }
  }

  function preview(verb) {
    // the verb's clip in the view, the text left as it is
    fetch("/api/animate", { method: "POST", headers: sends({ "Content-Type": "application/json" }),
                            body: JSON.stringify({ text: verb + "。" }) })
      .then(answer)
      .then(function (data) {
        if (!data.ok) { fail(data); return; }
        S.previewing = verb;
        $("view3d").hidden = true; $("view").hidden = false;
        link.open(data.html).then(dress, quiet);  // a preview is no render of the text
        status(t("preview_of", { v: verb, clips: data.table.map(function (e) { return e.clip; }).join(", ") }));
      });
  }

  function show(data, text, seq, asked) {
    S.last = { text: text, data: data };
    marks(text, data);
    if (!data.ok) { S.text = text; fail(data); return; }
    var finishing = !data.draft && S.draft && S.text === text;  // the finished animation of the draft on screen
    S.error = ""; S.text = text; S.table = data.table;
    $("error").textContent = "";
    $("share").href = "/?text=" + encodeURIComponent(text);
    timeline(data);
    window.__studioTop.show(data.top);
    // the skinned view draws one character; with several (a partner, a person only spoken to) the export
    // holds one file each, and the page draws them as figures
    var actors = new Set(data.table.map(function (e) { return e.actor; })).size;
    if (data.rig && actors === 1) { drafted(false); skinned(text, seq, data); return; }
    S.note = data.rig ? t("many_actors", { n: actors }) : "";
    if (data.rig) $("builtin").hidden = false;  // the dropped character is still what the export animates
    $("view3d").hidden = true; $("view").hidden = false;
    if (data.html) {  // the first answer, or the viewer was replaced: the page itself, loaded once
      link.open(data.html).then(function () {
        dress();
        if (S.resumeAt !== null) { link.seek(S.resumeAt); link.play(); S.resumeAt = null; }  // kept within its length
        return link.drawn().then(function (drawn) { shown(seq, data, asked, drawn.drawnAt); });
      }).catch(function (e) {
        if (e.name !== "Replaced" && seq === S.seq) fail({ code: "other", error: String(e.message || e) });
      });
      return;
    }
    S.previewing = null;
    // a new animation plays from its start, as a new page did (or from where "add" asked); the finished one of
    // the draft on screen goes on at the same time
    var at = S.resumeAt !== null ? S.resumeAt : finishing ? null : 0;
    S.resumeAt = null;
    link.load(data.view, { home: !finishing, at: at, play: at !== null }).then(function (swap) {
      if (finishing) S.swap = { before: swap.before, after: swap.after };  // the playing time across the replacement
      shown(seq, data, asked, swap.drawnAt);
    }).catch(function (e) {
      if (e.name !== "Replaced" && seq === S.seq) request(asked.text, asked.edits, asked.fallback, data.draft, 0, true);
    });
  }

  function quiet(e) {
    // a viewer page replaced before it was ready: nothing to say; anything else in the page's words
    if (e.name !== "Replaced") fail({ code: "other", error: String(e.message || e) });
  }

  function shown(seq, data, asked, now) {
    // the first frame of the answer came on screen at ``now`` (performance.now(), ms): the figures, and the
    // finished animation asked for after a draft
    if (seq !== S.seq) return;
    var ms = now - S.firedAt;
    S.lastLatencyMs = ms; S.latencies.push(ms); S.renders++; S.shown = seq;
    if (S.sentKeyAt) {
      S.keyLatencies.push(now - S.sentKeyAt);
      // where the time went: the pause, the request (the server's work), the viewer's load and first frame
      S.phases.push({ pause: S.firedAt - S.sentKeyAt, request: S.answeredAt - S.firedAt, shown: now - S.answeredAt });
    }
    if (data.draft) {
      S.drafts++; S.draftKeyAt = S.sentKeyAt; S.draftMs = ms; drafted(true);
      status(t("shown_draft", { s: data.duration.toFixed(2), ms: Math.round(ms) }));
      request(asked.text, asked.edits, asked.fallback, false, 0);  // the finished one, in place when ready
      return;
    }
    if (S.draft && S.draftKeyAt) S.finishLatencies.push(now - S.draftKeyAt);
    status((S.draft ? t("shown_finished", { s: data.duration.toFixed(2), first: Math.round(S.draftMs), ms: Math.round(ms) })
                    : t("shown", { s: data.duration.toFixed(2), ms: Math.round(ms) })) + (S.note || ""));
    S.draftKeyAt = 0; S.busy = false; drafted(false);
  }

  function drafted(on) {
    // the draft's mark in the page: what plays is the quick draft, the finished animation is on its way
    S.draft = on; $("draft").hidden = !on;
  }

  function skinned(text, seq, data) {
    // the dropped character, skinned: the GLB the studio exports for it, drawn by three.js (studio3d.js)
    if (!window.__studio3dApi) { setTimeout(function () { skinned(text, seq, data); }, 20); return; }  // module loading
    var api3d = window.__studio3dApi, s3 = window.__studio3d;
    var at = S.resumeAt !== null ? S.resumeAt : (s3 && s3.ready ? s3.time : 0);
    $("builtin").hidden = false;
    S.resumeAt = null;
    fetch("/api/export", { method: "POST", headers: sends({ "Content-Type": "application/json" }),
                           body: JSON.stringify({ text: text, edits: editList(), format: "glb", fallback: S.fallback }) })
      .then(function (r) { if (!r.ok) throw new Error(t("err_character")); return r.arrayBuffer(); })
      .then(function (buffer) {
        if (link.state.ready) link.pause();  // a hidden viewer drawing every frame slows the skinned one
        $("view").hidden = true; $("view3d").hidden = false;
        return api3d.show(buffer, at);
      })
      .then(function () {
        if (seq !== S.seq) return;
        var ms = performance.now() - S.firedAt;
        S.lastLatencyMs = ms; S.latencies.push(ms); S.renders++; S.shown = seq; S.busy = false;
        if (S.sentKeyAt) S.keyLatencies.push(performance.now() - S.sentKeyAt);
        status(t("shown_skinned", { s: data.duration.toFixed(2), ms: Math.round(ms) }));
      })
      .catch(function (e) { fail({ code: "other", message: t("err_character"), error: String(e) }); });
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
        bar.appendChild(svg("title", {}, e.id + " " + e.verb + " (" + e.clip + ", " + t("m_" + e.method) + ") " +
                            e.start.toFixed(2) + "–" + e.end.toFixed(2) + " s" + how));
        g.appendChild(bar);
        g.appendChild(svg("text", { x: x(e.start) + 6, y: top + 18 }, e.id + " " + e.verb + how + " · " + t("m_" + e.method)));
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
    g.appendChild(svg("text", { x: LEFT, y: y + 12, "class": "actor" }, "0 " + t("seconds")));
    g.appendChild(svg("text", { x: W - 60, y: y + 12, "class": "actor" }, T.toFixed(2) + " " + t("seconds")));
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
        commit(); animate();
      }
      bar.addEventListener("pointermove", move);
      bar.addEventListener("pointerup", up);
    });
  }

  function menu(e, ev) {
    var m = $("method");
    m.value = e.method === "composition" || e.method === "transition" ? e.method : "connection";
    m.style.left = ev.pageX + "px"; m.style.top = ev.pageY + "px"; m.style.display = "block";
    m.onchange = function () { edit(e).method = m.value; m.style.display = "none"; commit(); animate(); };
    m.onblur = function () { m.style.display = "none"; };
    m.focus();
  }

  function append() {
    var more = $("add").value.trim();
    if (!more) return;
    var s3 = window.__studio3d;
    if (!$("view3d").hidden && s3 && s3.ready) S.resumeAt = s3.time;  // playback goes on from the frame on screen
    else S.resumeAt = link.state.ready ? link.state.time : 0;
    var text = $("text").value.trim();
    $("text").value = text + (/[。！？!?]$/.test(text) || !text ? "" : "。") + more;
    $("add").value = "";
    clearTimeout(S.timer);
    commit(); animate();
  }

  function exportBvh() {
    var text = $("text").value;
    fetch("/api/export", { method: "POST", headers: sends({ "Content-Type": "application/json" }),
                           body: JSON.stringify({ text: text, edits: editList(), format: $("format").value,
                                                  fallback: S.fallback }) })
      .then(function (r) {
        if (!r.ok) return answer(r).then(function (d) { fail(d.code === "other" ? { message: t("err_export"), error: d.error } : d); });
        var name = /filename="([^"]+)"/.exec(r.headers.get("Content-Disposition") || "");
        return r.blob().then(function (blob) {
          var a = document.createElement("a");
          a.href = URL.createObjectURL(blob); a.download = name ? name[1] : "animation.bvh";
          document.body.appendChild(a); a.click(); a.remove();
        });
      })
      .catch(function (e) { fail({ code: "network", error: String(e) }); });
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

  // ---- the project: what is kept, saved, opened, undone
  function project() {
    return { format: "text2anim-project", version: PROJECT_VERSION, text: $("text").value, edits: editList(),
             fallback: S.fallback, character: S.character };
  }

  function restore(p) {
    $("text").value = p.text || "";
    S.edits = {};
    (p.edits || []).forEach(function (e) { S.edits[e.verb + "#" + (e.nth || 0)] = JSON.parse(JSON.stringify(e)); });
    S.fallback = p.fallback === "nearest" ? "nearest" : "strict";
    S.character = p.character === "figure" ? "figure" : "body";
    figure();
  }

  function figure() {
    // the character drawn: a body (the default) or the stick figure, in the viewer on screen
    $("character").value = S.character;
    if (link.state.ready) link.set({ body: S.character === "body" });
  }

  function commit() {
    // one step of the history (a pause in typing, a bar moved, a join chosen, a stand-in taken), kept in storage
    var now = JSON.stringify(project());
    if (S.history[S.at] === now) return;
    S.history = S.history.slice(0, S.at + 1);
    S.history.push(now); S.at = S.history.length - 1;
    keep(now); buttons();
  }

  function keep(json) {
    try { localStorage.setItem(STORE, json); } catch (e) { /* storage off or full: the page still works */ }
  }

  function buttons() {
    $("undo").disabled = S.at <= 0;
    $("redo").disabled = S.at >= S.history.length - 1;
  }

  function step(by) {
    var to = S.at + by;
    if (to < 0 || to >= S.history.length) return;
    S.at = to; clearTimeout(S.timer);
    restore(JSON.parse(S.history[to]));
    keep(S.history[to]); buttons(); animate();
  }

  function checked(p, name) {
    // a parsed .t2a.json, or the page's message saying why it is none (the command line refuses it alike)
    if (!p || typeof p !== "object" || p.format !== "text2anim-project" || typeof p.text !== "string")
      return t("project_bad", { name: name });
    if (p.version !== PROJECT_VERSION) return t("project_version", { name: name, v: String(p.version) });
    if (!Array.isArray(p.edits || [])) return t("project_bad", { name: name });
    return "";
  }

  function openProject(file) {
    file.text().then(function (body) {
      var p = null;
      try { p = JSON.parse(body); } catch (e) { p = null; }
      var why = checked(p, file.name);
      if (why) { fail({ message: why }); return; }
      restore(p); commit(); animate();
      status(t("project_opened", { name: file.name }));
    });
  }

  function saveProject() {
    var blob = new Blob([JSON.stringify(project(), null, 2) + "\n"], { type: "application/json" });
    var a = document.createElement("a");
    a.href = URL.createObjectURL(blob); a.download = "project.t2a.json";
    document.body.appendChild(a); a.click(); a.remove();
  }

  // ---- dropped files: a BVH for this session (the library only when asked), a character
  function dropped(file) {
    var name = file.name || "", lower = name.toLowerCase(), headers = sends({ "X-Filename": encodeURIComponent(name) });
    var url;
    if (/\.t2a\.json$|\.json$/.test(lower)) { openProject(file); return; }
    if (/\.bvh$/.test(lower)) {
      var verb = window.prompt(t("drop_verb", { name: name }), "");
      if (!verb) return;
      headers["X-Verb"] = encodeURIComponent(verb);
      url = "/api/import";
    } else if (/\.(glb|vrm)$/.test(lower)) {
      url = "/api/rig";
    } else { fail({ message: t("drop_kind", { name: name }) }); return; }
    $("dropped").textContent = t("drop_reading", { name: name });
    fetch(url, { method: "POST", headers: headers, body: file })
      .then(answer)
      .then(function (d) {
        $("dropped").textContent = t("drop_hint");
        if (!d.ok) { fail({ message: t("drop_bad", { name: name }), error: d.error }); return; }
        if (url === "/api/import") { S.session.push({ file: name, clip: d.clip, verbs: d.verbs, seconds: d.seconds }); session(); }
        else $("dropped").textContent = t("drop_rig", { name: name, n: d.joints });
        S.sent = ""; animate();  // what plays may have changed
      })
      .catch(function (e) { fail({ code: "network", error: String(e) }); });
  }

  function session() {
    // the clips dropped in this session, each with the explicit step into the user's library
    var box = $("session");
    while (box.firstChild) box.removeChild(box.firstChild);
    S.session.forEach(function (c) {
      var row = document.createElement("div"), label = document.createElement("span");
      row.className = "clip"; label.className = "name";
      label.textContent = c.kept ? t("drop_kept", { name: c.file })
        : t("drop_session", { name: c.file, verbs: c.verbs.join("/"), s: c.seconds });
      row.appendChild(label);
      if (!c.kept) row.appendChild(button(t("drop_keep"), "", function () { keepClip(c); }, "keep"));
      box.appendChild(row);
    });
  }

  function post(url, body) {
    return fetch(url, { method: "POST", headers: sends({ "Content-Type": "application/json" }), body: JSON.stringify(body) })
      .then(answer);
  }

  function keepClip(c) {
    post("/api/library/keep", { clip: c.clip }).then(function (d) {
      if (!d.ok) { fail({ message: t("err_other"), error: d.error }); return; }
      c.kept = true; session(); library();
    });
  }

  function library() {
    // the user's own clips (not the built-in ones): preview, rename, remove
    fetch("/api/library").then(answer).then(function (d) {
      var box = $("mine");
      while (box.firstChild) box.removeChild(box.firstChild);
      S.mine = (d.clips || []).map(function (c) { return c.name; });
      if (!d.clips || !d.clips.length) {
        var p = document.createElement("p"); p.className = "empty"; p.textContent = t("library_empty"); box.appendChild(p);
        return;
      }
      d.clips.forEach(function (c) {
        var row = document.createElement("div"), label = document.createElement("span");
        row.className = "clip"; row.setAttribute("data-clip", c.name); label.className = "name";
        label.textContent = c.name + " — " + c.verbs.join("/") + " (" + c.seconds + " " + t("seconds") + ")";
        row.appendChild(label);
        row.appendChild(button(t("lib_preview"), "", function () { previewClip(c.name); }, "preview"));
        row.appendChild(button(t("lib_rename"), "", function () {
          var to = window.prompt(t("lib_rename_ask", { name: c.name }), c.name);
          if (to && to !== c.name) post("/api/library/rename", { clip: c.name, name: to }).then(done);
        }, "rename"));
        row.appendChild(button(t("lib_remove"), "", function () {
          if (window.confirm(t("lib_remove_ask", { name: c.name }))) post("/api/library/remove", { clip: c.name }).then(done);
        }, "remove"));
        box.appendChild(row);
      });
    });
    function done(d) {
      if (!d.ok) fail({ message: t("err_other"), error: d.error });
      library(); S.sent = ""; animate();
    }
  }

  function previewClip(name) {
    post("/api/clip", { clip: name }).then(function (data) {
      if (!data.ok) { fail({ message: t("err_other"), error: data.error }); return; }
      S.previewing = name;
      $("view3d").hidden = true; $("view").hidden = false;
      link.open(data.html).then(dress, quiet);
      status(t("preview_of", { v: name, clips: data.verbs.join("/") }));
    });
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
      $("builtin").hidden = true; $("dropped").textContent = t("drop_hint"); S.sent = ""; animate();
    });
  });
  // the input method: nothing is sent while a composition is open; the pause counts from its end
  var box = $("text");
  box.addEventListener("compositionstart", function () { S.composing = true; clearTimeout(S.timer); });
  box.addEventListener("compositionend", function () { S.composing = false; S.keyAt = performance.now(); schedule(); });
  box.addEventListener("input", function (e) {
    S.keyAt = performance.now();
    // the text changed: the animation in flight (and an answer not yet on screen) no longer matters, a new one is due
    stop(); S.seq++; S.busy = true; S.sent = "";
    if (!e.isComposing && !S.composing) schedule();
  });
  $("add-btn").addEventListener("click", append);
  $("add").addEventListener("keydown", function (e) { if (e.key === "Enter" && !e.isComposing) append(); });
  $("export").addEventListener("click", exportBvh);
  $("reset-edits").addEventListener("click", function () { S.edits = {}; commit(); animate(); });
  $("undo").addEventListener("click", function () { step(-1); });
  $("redo").addEventListener("click", function () { step(1); });
  $("save").addEventListener("click", saveProject);
  $("open").addEventListener("change", function () { if (this.files.length) openProject(this.files[0]); this.value = ""; });
  $("character").addEventListener("change", function () { S.character = this.value; figure(); commit(); });
  $("lang").addEventListener("change", function () {
    S.lang = this.value;
    try { localStorage.setItem("t2a-studio-lang", S.lang); } catch (e) { /* the switch holds for this page */ }
    words();
  });
  document.addEventListener("keydown", function (e) {
    if (!(e.ctrlKey || e.metaKey) || e.isComposing || (e.key !== "z" && e.key !== "Z" && e.key !== "y")) return;
    if (e.target && (e.target.id === "search" || e.target.id === "add")) return;  // their own undo
    e.preventDefault();
    step(e.key === "y" || e.shiftKey ? 1 : -1);
  });
  window.__studio.project = project;
  S.lang = language();
  words();
  var start = new URLSearchParams(location.search).get("text"), kept = null;
  try { kept = JSON.parse(localStorage.getItem(STORE) || "null"); } catch (e) { kept = null; }
  if (start !== null) $("text").value = start;
  else if (kept && !checked(kept, "")) { restore(kept); status(t("restored")); }
  else $("text").value = "太郎は走って、ボールを蹴る。そして喜ぶ。";
  commit();
  animate();
})();
