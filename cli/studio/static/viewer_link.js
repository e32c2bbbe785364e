/* The studio page's side of its bridge to the viewer (viewer_bridge.js, inlined into the framed viewer page, is
 * the other side). The frame is sandboxed without allow-same-origin (an opaque origin: the viewer's page cannot
 * lift its own sandbox, nor reach the studio's page, its storage or its token), so the page cannot touch the
 * viewer's window.__t2a: it sends commands and mirrors what the viewer reports.
 *
 * window.__viewerLink:
 *   state                 the viewer's last report: ready, failed, time (s), frame, playing, duration (s), body,
 *                         errors (the viewer page's error messages); the page's tests and the top view read it
 *   open(html)            a new viewer page in the frame (srcdoc); a promise, resolved once it has drawn
 *   load(data, options)   viewer_data()'s document in place, options {home: frame it as a new page does, at:
 *                         then seek there (s), play}; a promise, resolved once it is on screen with {before,
 *                         after, drawnAt} (s: the playing time just before and after the swap), rejected with
 *                         the viewer's error
 *   play(), pause(), seek(t), set({body, maxFps, words})
 *   drawn()               a promise of {drawnAt}, resolved at the viewer's next animation frame (what it drew is
 *                         on screen)
 * drawnAt: when the viewer's frame came, on this page's performance.now() clock (ms), not when the page heard of
 * it (a process hop later: the frame has its own renderer process).
 * Messages are taken only from the frame's window (event.source) with the opaque origin ("null") and the number
 * of the page now in it: a report of a page replaced since is dropped. */
window.__viewerLink = (function () {
  "use strict";
  var FONT_URL = "/static/font/jp.woff";  // the Japanese face (cli/studio/page.py), handed to each viewer page
  var frame = document.getElementById("view");
  var state = { ready: false, failed: false, time: 0, frame: 0, playing: false, duration: 0, body: false, errors: [] };
  var doc = 0, ids = 0, waiting = {}, opening = null, font = null;

  function tell(msg) {
    // The frame's origin is opaque: its serialization is "null", which no targetOrigin can name, so the only
    // target that reaches it is "*". What goes there is no secret (the animation, the page's words, the font;
    // never the session's token) and it goes to this frame's window only. The viewer answers to this page's
    // own origin, which it reads from these messages (event.origin).
    var w = frame.contentWindow;
    if (w) w.postMessage(msg, "*");
  }

  function ask(msg) {
    return new Promise(function (resolve, reject) {
      msg.id = ++ids;
      waiting[msg.id] = { resolve: resolve, reject: reject };
      tell(msg);
    });
  }

  function replaced() {
    // the page in the frame is going: what it was asked stays unanswered
    var why = new Error("the viewer page was replaced");
    why.name = "Replaced";
    Object.keys(waiting).forEach(function (id) { waiting[id].reject(why); });
    waiting = {};
    if (opening) opening.reject(why);
    opening = null;
  }

  function open(html) {
    replaced();
    doc++; state.ready = false; state.failed = false;
    var mine = doc;
    return new Promise(function (resolve, reject) {
      opening = { resolve: resolve, reject: reject };
      frame.onload = function () { if (mine === doc) tell({ type: "hello", doc: mine }); };
      frame.srcdoc = html;
    });
  }

  function fontBytes() {
    // the studio's own face, fetched once (same origin; the browser's cache holds it too)
    if (!font) {
      font = fetch(FONT_URL).then(function (r) {
        if (!r.ok) throw new Error("HTTP " + r.status);
        return r.arrayBuffer();
      });
    }
    return font;
  }

  function reported(m) {
    if (m.type === "state") {
      ["time", "frame", "playing", "duration", "body"].forEach(function (k) { state[k] = m[k]; });
      state.failed = !!m.failed;
      if (m.ready && !state.ready) {
        state.ready = true;
        var mine = doc;
        fontBytes().then(function (bytes) { if (mine === doc) tell({ type: "font", bytes: bytes }); })
          .catch(function () { /* the viewer keeps its own faces */ });
        if (opening) { opening.resolve(); opening = null; }
      } else if (state.failed && opening) {
        opening.reject(new Error(state.errors[state.errors.length - 1] || "the viewer cannot show the animation"));
        opening = null;
      }
    } else if (m.type === "loaded" || m.type === "drawn") {
      var w = waiting[m.id];
      if (!w) return;
      delete waiting[m.id];
      if (m.error) { w.reject(new Error(m.error)); return; }
      var now = performance.now(), at = typeof m.drawnAt === "number" ? m.drawnAt - performance.timeOrigin : now;
      w.resolve({ before: m.before, after: m.after, drawnAt: Math.min(at, now) });
    } else if (m.type === "error" && typeof m.message === "string") {
      state.errors.push(m.message);
    }
  }

  window.addEventListener("message", function (e) {
    if (e.source !== frame.contentWindow || e.origin !== "null") return;
    var m = e.data;
    if (m && typeof m === "object" && m.doc === doc) reported(m);
  });

  return {
    state: state,
    open: open,
    load: function (data, options) {
      var o = options || {};
      return ask({ type: "load", data: data, home: !!o.home, at: typeof o.at === "number" ? o.at : null, play: !!o.play });
    },
    play: function () { tell({ type: "play" }); },
    pause: function () { tell({ type: "pause" }); },
    seek: function (t) { tell({ type: "seek", time: t }); },
    set: function (options) { var m = { type: "set" }; for (var k in options) m[k] = options[k]; tell(m); },
    drawn: function () { return ask({ type: "drawn" }); }
  };
})();
