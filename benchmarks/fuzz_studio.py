"""Fuzz the studio's endpoints on loopback: ``python benchmarks/fuzz_studio.py [--cases 300] [--seed 0]``.

Starts ``text2anim studio`` on 127.0.0.1 (a free port, a private temporary folder) and sends, in a bounded
number and time:

- ``malformed``: bodies no page sends (a list for a format, 20,000 nested brackets, wrong types, bad
  UTF-8, random bytes and mutations of valid requests) to ``/api/animate`` and ``/api/export``;
- ``cross-site``: what another site could make a browser send: a JSON body as ``text/plain`` (a "simple"
  request, with and without an Origin), no or a wrong session token, a foreign ``Host`` or ``Origin``;
- ``rigs``: a GLB that reads but is no human rig (kept, it made every later request a 500), then a text;
- ``load``: 200 animate requests of distinct texts, 140 from 20 clients at once (beyond ``MAX_PENDING``
  waiting: 429; the result cache's budget) then 60 from one client, as the page sends them, 8 dropped
  files of 30 MB at once (the upload cap), a client that sends its body a byte at a time (the body timeout);
- ``stop``: SIGTERM, after which the private folder must be gone.

Every answer is checked: a 4xx or 2xx (never 5xx), one line of error, never a traceback; every cross-site
request refused (403/415); every answer with ``X-Frame-Options: DENY`` and ``frame-ancestors 'none'``; the
server's peak resident memory (``VmHWM``) under 1 GB and every answer within 10 s of wall time (but those
of the 20 clients at once, which wait for each other's animations: the studio animates one text at a time). Prints a table of classes; exits 1 on any failure.
"""
from __future__ import annotations

import argparse
import http.client
import json
import os
import random
import re
import signal
import socket
import subprocess
import sys
import tempfile
import threading
import time
from collections import defaultdict
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
LIMIT_S = 10.0
LIMIT_MB = 1024.0
TEXTS = ["太郎は歩く。", "太郎は走って、ボールを蹴る。", "花子は座る。", "太郎は跳ぶ。", "太郎は手を振る。"]


class Studio:
    """``text2anim studio`` in a child process on a free loopback port."""

    def __init__(self, tmp: Path):
        with socket.socket() as s:
            s.bind(("127.0.0.1", 0))
            self.port = s.getsockname()[1]
        self.tmp = tmp
        env = {**os.environ, "TMPDIR": str(tmp), "PYTHONPATH": str(REPO)}
        self.proc = subprocess.Popen([sys.executable, "-m", "text2anim.cli.main", "studio", "--no-browser",
                                      "--port", str(self.port)], env=env, stdout=subprocess.DEVNULL,
                                     stderr=subprocess.DEVNULL)
        deadline = time.monotonic() + 60
        while True:
            try:
                page = self.request("GET", "/")[2]
                break
            except OSError:
                if time.monotonic() > deadline or self.proc.poll() is not None:
                    raise RuntimeError("the studio did not start")
                time.sleep(0.2)
        self.token = re.search(rb'<meta name="t2a-token" content="([^"]+)">', page).group(1).decode()

    def request(self, method: str, path: str, body: bytes = b"", headers: dict | None = None,
                timeout: float = 120.0) -> tuple[int, dict, bytes]:
        conn = http.client.HTTPConnection("127.0.0.1", self.port, timeout=timeout)
        try:
            hdrs = {"Host": f"127.0.0.1:{self.port}", **(headers or {})}
            conn.request(method, path, body=body or None, headers=hdrs)
            r = conn.getresponse()
            return r.status, {k.lower(): v for k, v in r.getheaders()}, r.read()
        finally:
            conn.close()

    def post(self, path: str, body: bytes, **headers) -> tuple[int, dict, bytes]:
        return self.request("POST", path, body, {"Content-Type": "application/json", "X-Studio-Token": self.token,
                                                 **headers})

    def peak_mb(self) -> float:
        status = Path(f"/proc/{self.proc.pid}/status").read_text()
        return int(re.search(r"VmHWM:\s+(\d+)", status).group(1)) / 1024


def _glb(gl: dict) -> bytes:
    j = json.dumps(gl).encode()
    j += b" " * (-len(j) % 4)
    body = len(j).to_bytes(4, "little") + b"JSON" + j
    return b"glTF" + (2).to_bytes(4, "little") + (12 + len(body)).to_bytes(4, "little") + body


def malformed_bodies(rng: random.Random, n: int) -> list[bytes]:
    fixed = [b'{"text": "\xe8\xb5\xb0\xe3\x82\x8b", "format": []}', b"[" * 20_000, b"{" * 20_000, b'["text"]', b"7",
             b"null", b'{"text": 7}', b'{"text": null}', b'{"text": "x", "edits": [1]}', b'{"text": "x", "edits": "a"}',
             b'{"text": "x", "edits": [{"verb": []}]}', b'{"text": "x", "edits": [{"nth": -1e308}]}',
             b'{"text": "x", "format": {"a": 1}}', b'{"text": "x", "format": "exe"}', b"\xff\xfe\x00",
             b'{"text": "' + b"\\u0000" * 100 + b'"}', b'{"text": "\\ud800"}', b'{"text": "x"' + b" " * 70_000 + b"}",
             b'{"text": "\xe6\xad\xa9\xe3\x81\x8f\xe3\x80\x82", "edits": [' + b'{"verb":"x","nth":0},' * 300 + b'{}]}']
    valid = [json.dumps({"text": t, "edits": [{"verb": "走る", "nth": 0, "shift": 0.5}], "format": "bvh"},
                        ensure_ascii=False).encode() for t in TEXTS]
    out = list(fixed)
    while len(out) < n:
        b = bytearray(rng.choice(valid))
        for _ in range(rng.randint(1, 4)):
            k = rng.randrange(len(b))
            op = rng.random()
            if op < 0.4:
                b[k] = rng.randrange(256)
            elif op < 0.7:
                del b[k:k + rng.randint(1, 8)]
            else:
                b[k:k] = rng.choice([b"[", b"{", b'"', b"null", b"-1e999", b"\\u0000", b"[]", b'{"a":'])
        out.append(bytes(b))
    return out[:max(n, len(fixed))]


class Tally:
    def __init__(self):
        self.rows: dict[str, dict] = defaultdict(lambda: defaultdict(float))
        self.failures: list[str] = []

    def add(self, cls: str, case: str, status: int, headers: dict, body: bytes, wall: float,
            cross_site: bool = False, expect: tuple[int, ...] | None = None, timed: bool = True) -> None:
        r = self.rows[cls]
        r["cases"] += 1
        r[f"{status // 100}xx"] += 1
        r["wall"] = max(r["wall"], wall)
        why = []
        if status >= 500 or b"Traceback" in body:
            why.append(f"{status}")
        if cross_site and status not in (403, 415):
            why.append(f"cross-site request served ({status})")
            r["served"] += 1
        if expect and status not in expect:
            why.append(f"{status}, expected {expect}")
        if headers.get("x-frame-options") != "DENY" or headers.get("content-security-policy") != "frame-ancestors 'none'":
            why.append("no framing headers")
        if status >= 400 and headers.get("content-type", "").startswith("application/json"):
            error = json.loads(body).get("error", "")
            if "\n" in error or len(error) > 1100:  # cli.terminal.MESSAGE_WIDTH and its note
                why.append("error not one short line")
        if timed and wall > LIMIT_S:
            why.append(f"{wall:.1f} s")
        if why:
            r["failed"] += 1
            self.failures.append(f"{cls}: {case}: {'; '.join(why)}")


def timed(fn, *args, **kw):
    t0 = time.perf_counter()
    status, headers, body = fn(*args, **kw)
    return status, headers, body, time.perf_counter() - t0


def run(cases: int, seed: int) -> int:
    rng = random.Random(seed)
    tally = Tally()
    t_start = time.perf_counter()
    with tempfile.TemporaryDirectory() as tmp_name:
        tmp = Path(tmp_name)
        s = Studio(tmp)
        # a client that sends its body a byte at a time, from the start (the body timeout ends it)
        slow: dict = {}

        def slow_client():
            t0 = time.perf_counter()
            conn = socket.create_connection(("127.0.0.1", s.port))
            conn.sendall((f"POST /api/animate HTTP/1.1\r\nHost: 127.0.0.1:{s.port}\r\nContent-Type: application/json\r\n"
                          f"X-Studio-Token: {s.token}\r\nContent-Length: 1000\r\n\r\n").encode())
            conn.settimeout(1.0)
            answer = b""
            for _ in range(120):
                try:
                    conn.sendall(b" ")
                    answer += conn.recv(4096)
                    if answer:
                        break
                except socket.timeout:
                    continue
                except OSError:
                    break
            conn.close()
            slow.update(answer=answer, wall=time.perf_counter() - t0)
        slow_thread = threading.Thread(target=slow_client)
        slow_thread.start()

        for k, body in enumerate(malformed_bodies(rng, cases)):
            endpoint = "/api/animate" if k % 2 == 0 else "/api/export"
            st, h, b, w = timed(s.post, endpoint, body)
            tally.add("malformed", f"{endpoint} {body[:40]!r}", st, h, b, w)

        good = json.dumps({"text": TEXTS[0]}, ensure_ascii=False).encode()
        for path in ("/api/animate", "/api/export"):  # the page's own token, but not JSON: refused all the same
            st, h, b, w = timed(s.post, path, good, **{"Content-Type": "text/plain"})
            tally.add("cross-site", f"{path} text/plain with the token", st, h, b, w, cross_site=True)
        # what another site can make a browser send: never the session's token (it cannot read the page)
        cross = [("text/plain, no Origin", {"Content-Type": "text/plain"}),
                 ("text/plain, a foreign Origin", {"Content-Type": "text/plain", "Origin": "http://evil.example"}),
                 ("form encoding", {"Content-Type": "application/x-www-form-urlencoded"}),
                 ("no token", {"X-Studio-Token": ""}), ("a wrong token", {"X-Studio-Token": "x" * 43}),
                 ("a foreign Origin", {"Origin": "http://evil.example"}),
                 ("a foreign Host (DNS rebinding)", {"Host": f"evil.example:{s.port}"})]
        for name, headers in cross:
            for path in ("/api/animate", "/api/export", "/api/import", "/api/rig"):
                st, h, b, w = timed(s.post, path, good, **{"X-Studio-Token": "", **headers})
                tally.add("cross-site", f"{path} {name}", st, h, b, w, cross_site=True)
            st, h, b, w = timed(s.request, "DELETE", "/api/rig", b"", {k: v for k, v in headers.items() if k != "Content-Type"})
            tally.add("cross-site", f"DELETE /api/rig {name}", st, h, b, w, cross_site=True)
        st, h, b, w = timed(s.request, "GET", "/", b"", {"Host": "evil.example"})
        tally.add("cross-site", "GET / with a foreign Host", st, h, b, w, cross_site=True)

        nodes = [{"name": f"j{i}", "children": [i + 1] if i < 7999 else [], "translation": [0, 0.01, 0]} for i in range(8000)]
        chain = _glb({"asset": {"version": "2.0"}, "nodes": nodes, "skins": [{"joints": list(range(8000))}]})
        for name, data in [("an 8,000-node chain GLB", chain), ("a GLB header alone", b"glTF\x02\x00\x00\x00"),
                           ("random bytes", bytes(rng.randrange(256) for _ in range(4096)))]:
            st, h, b, w = timed(s.post, "/api/rig", data, **{"X-Filename": "c.glb", "Content-Type": "model/gltf-binary"})
            tally.add("rigs", name, st, h, b, w, expect=(422,))
            st, h, b, w = timed(s.post, "/api/animate", good)
            tally.add("rigs", f"a text after {name}", st, h, b, w, expect=(200,))

        texts = [f"太郎は{k % 9 + 1}秒歩く。" + "そして走る。" * (k % 4) + "花子は座る。" * (k % 2) for k in range(200)]
        animate = lambda t: timed(s.post, "/api/animate", json.dumps({"text": t}, ensure_ascii=False).encode())  # noqa: E731
        with ThreadPoolExecutor(20) as pool:  # a burst: beyond MAX_PENDING, told the studio is busy; the
            for st, h, b, w in pool.map(animate, texts[:140]):  # time bound is not theirs (one animation at a time)
                tally.add("load", "140 texts from 20 clients", st, h, b, w, expect=(200, 422, 429), timed=False)
        for t in texts[140:]:  # then one client, as the page is: each answer within the time bound
            st, h, b, w = animate(t)
            tally.add("load", "60 texts from one client", st, h, b, w, expect=(200, 422))
        big = b"\x00" * (30 * 2**20)
        with ThreadPoolExecutor(8) as pool:
            for st, h, b, w in pool.map(lambda _: timed(s.post, "/api/import", big, **{"X-Filename": "a.bvh", "X-Verb": "x",
                                                                                       "Content-Type": "application/octet-stream"}), range(8)):
                tally.add("load", "8 dropped files of 30 MB at once", st, h, b, w, expect=(422, 429))
        slow_thread.join()
        answer = slow.get("answer", b"")
        status = int(answer.split(b" ")[1]) if answer.startswith(b"HTTP/1.1 ") else 0
        tally.add("load", "a body sent a byte a second", status, {"x-frame-options": "DENY",
                  "content-security-policy": "frame-ancestors 'none'"}, b"", 0.0, expect=(408,))
        peak = s.peak_mb()
        s.proc.send_signal(signal.SIGTERM)
        code = s.proc.wait(30)
        left = list(tmp.glob("t2a-studio-*"))
        tally.rows["stop"]["cases"] += 1
        if left or code != 128 + signal.SIGTERM:
            tally.failures.append(f"stop: SIGTERM left {left} (exit {code})")
            tally.rows["stop"]["failed"] += 1
    if peak > LIMIT_MB:
        tally.failures.append(f"the server's peak resident memory {peak:.0f} MB")
    head = f"| class | cases | 2xx | 4xx | 5xx | cross-site served | max wall s | failed |"
    print(f"studio fuzz: seed {seed}, {time.perf_counter() - t_start:.0f} s; server peak resident {peak:.0f} MB")
    print(head + "\n|" + " --- |" * 8)
    for cls, r in tally.rows.items():
        print(f"| {cls} | {int(r['cases'])} | {int(r['2xx'])} | {int(r['4xx'])} | {int(r['5xx'])} | {int(r['served'])} "
              f"| {r['wall']:.2f} | {int(r['failed'])} |")
    for f in tally.failures[:30]:
        print("FAIL", f)
    return 1 if tally.failures else 0


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--cases", type=int, default=300, help="malformed bodies sent")
    ap.add_argument("--seed", type=int, default=0)
    args = ap.parse_args(argv)
    return run(args.cases, args.seed)


if __name__ == "__main__":
    sys.exit(main())
