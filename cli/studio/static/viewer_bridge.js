/* The framed viewer's side of the studio's bridge: inlined by work.framed() after the viewer's own script into
 * the viewer page the studio frames (the page `text2anim TEXT` writes has none and works alone).
 *
 * The frame is sandboxed without allow-same-origin: its origin is opaque, so the studio cannot reach
 * window.__t2a and the two talk by postMessage only. Accepted: messages whose source is window.parent, all from
 * the one origin of the first (the studio's page: its event.origin is the portable way for an opaque-origin
 * frame to learn its parent's origin; location.ancestorOrigins is Chromium's only). Posted: only to
 * window.parent, to that origin, never "*"; nothing is posted before it is known.
 *
 * Commands (studio -> viewer), each {type, ...}:
 *   hello {doc}            the page's number for this document, echoed in every message; the state is sent back
 *   load {id, data, home, at, play}  viewer_data()'s document in place (window.__t2a.load), then sought to
 *                          `at` (s) and played when asked -> loaded {id, before, after, drawnAt} once it is on
 *                          screen (the next animation frame; before, after: the playing time just before and
 *                          after the swap), or loaded {id, error}: one round trip for what the studio waits for
 *                          at a keystroke
 *   play, pause, seek {time}
 *   set {body, maxFps, words: {help, speed, follow, loop}}  the figure, the drawing rate, the controls' words
 *   font {bytes}           the studio's Japanese face (WOFF): names loaded later are drawn with it
 *   drawn {id}             -> drawn {id, drawnAt} at the next animation frame (what the viewer drew is on screen)
 * drawnAt: when that frame came, on the clock every page shares (performance.timeOrigin + performance.now(), ms):
 * the message saying so reaches the studio a process hop later (the frame has its own renderer process).
 * Reports (viewer -> studio): state {time, frame, playing, duration, ready, failed, body} whenever the viewer
 * draws (and once it is ready or failed), error {message} for every error on the page. */
(function () {
  "use strict";
  var api = window.__t2a, up = window.parent, origin = null, doc = 0, sent = 0;
  if (!api || up === window) return;  // opened on its own: no one to talk to

  function post(msg) {
    if (origin === null) return;
    msg.doc = doc;
    up.postMessage(msg, origin);
  }

  function clock() { return performance.timeOrigin + performance.now(); }  // ms, the clock pages share

  function state() {
    post({ type: "state", time: api.time, frame: api.frame, playing: api.playing, duration: api.duration,
           ready: api.ready, failed: document.body.getAttribute("data-ready") === "error", body: api.body });
  }

  function errors() {
    // the errors the page recorded (viewer.html: window.__t2aErrors) that were not yet reported
    var all = api.errors || [];
    for (; sent < all.length; sent++) post({ type: "error", message: String(all[sent]).slice(0, 500) });
  }

  function label(id, word, before) {
    // the text beside a control inside its <label>: before it (speed) or after it (follow, loop)
    var input = document.getElementById(id), lab = input && input.parentNode;
    if (!lab || lab.tagName !== "LABEL" || typeof word !== "string") return;
    var node = before ? lab.firstChild : lab.lastChild;
    if (node && node.nodeType === 3) node.textContent = before ? word + " " : " " + word;
  }

  function set(msg) {
    if (typeof msg.body === "boolean") api.body = msg.body;
    if (typeof msg.maxFps === "number") api.maxFps = msg.maxFps;
    var w = msg.words;
    if (w && typeof w === "object") {
      var help = document.getElementById("help");
      if (help && typeof w.help === "string") help.textContent = w.help;
      label("speed", w.speed, true); label("follow", w.follow, false); label("loop", w.loop, false);
    }
  }

  function font(bytes) {
    if (!(bytes instanceof ArrayBuffer) || !document.fonts || typeof FontFace === "undefined") return;
    var face = new FontFace("t2a-studio", bytes, { unicodeRange: "U+2E80-FFFF" });
    face.load().then(function () { document.fonts.add(face); }).catch(function () { /* the system's font */ });
  }

  function load(msg) {
    var before = api.time;
    api.load(msg.data, !!msg.home).then(function () {
      var after = api.time;
      if (typeof msg.at === "number" && isFinite(msg.at)) api.seek(msg.at);
      if (msg.play) api.play();
      requestAnimationFrame(function () {
        post({ type: "loaded", id: msg.id, before: before, after: after, drawnAt: clock() });
      });
    }).catch(function (e) {
      post({ type: "loaded", id: msg.id, error: String(e && e.message ? e.message : e).slice(0, 500) });
    });
  }

  var COMMANDS = {
    hello: function (msg) { doc = typeof msg.doc === "number" ? msg.doc : 0; errors(); state(); },
    load: load,
    play: function () { api.play(); },
    pause: function () { api.pause(); },
    seek: function (msg) { if (typeof msg.time === "number" && isFinite(msg.time)) api.seek(msg.time); },
    set: set,
    font: function (msg) { font(msg.bytes); },
    drawn: function (msg) {
      requestAnimationFrame(function () { post({ type: "drawn", id: msg.id, drawnAt: clock() }); });
    }
  };

  window.addEventListener("message", function (e) {
    if (e.source !== up || (origin !== null && e.origin !== origin)) return;
    var msg = e.data;
    if (!msg || typeof msg !== "object" || !Object.prototype.hasOwnProperty.call(COMMANDS, msg.type)) return;
    if (origin === null) origin = e.origin;
    COMMANDS[msg.type](msg);
  });
  // the viewer sets these on <body> each time it draws (and once it is ready or failed); its errors first, so
  // that the studio has the reason when it hears of a failure
  new MutationObserver(function () { errors(); state(); })
    .observe(document.body, { attributes: true, attributeFilter: ["data-time", "data-ready"] });
  new MutationObserver(errors).observe(document.documentElement, { attributes: true, attributeFilter: ["data-errors"] });
})();
