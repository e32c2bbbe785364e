"""Who may talk to the studio: only its own page, on the addresses that reach it.

A web page elsewhere must not drive a local tool (DNS rebinding, cross-site POSTs, framing):

- a request whose ``Host`` is not one of the studio's own addresses, or whose ``Origin`` (sent by
  browsers on cross-origin requests and on every POST) is not ``http://`` + one of them, is refused (403);
- every state-changing request (POST, DELETE) carries the session's token in ``X-Studio-Token``, as
  Jupyter does: the page gets it from the HTML the studio serves (a ``<meta>``), which another site
  cannot read; without it, 403. A cross-site form or "simple" request cannot set that header, and
  cannot send ``application/json`` either, which the JSON endpoints require (415 otherwise);
- every answer says ``X-Frame-Options: DENY`` and ``Content-Security-Policy: frame-ancestors 'none'``:
  no other page may frame the studio and click for the user.
"""
from __future__ import annotations

import secrets
import socket

from starlette.responses import PlainTextResponse
from starlette.types import ASGIApp, Message, Receive, Scope, Send

LOOPBACK = ("127.0.0.1", "localhost", "::1")
WILDCARD = ("0.0.0.0", "::", "")
#: Headers every answer carries.
FRAMING = [(b"x-frame-options", b"DENY"), (b"content-security-policy", b"frame-ancestors 'none'"),
           (b"x-content-type-options", b"nosniff")]
#: Methods that change the studio's state and so need the session's token.
UNSAFE = ("POST", "PUT", "PATCH", "DELETE")


def _bracketed(name: str) -> str:
    return f"[{name}]" if ":" in name else name


def reaching_names(host: str) -> set[str]:
    """The names a browser may use for the studio listening on ``host``: loopback names for a loopback
    address; for every interface (``0.0.0.0``, ``::``) this machine's name, its full name, its addresses
    and the loopback names (``--host 0.0.0.0`` refused every name but ``0.0.0.0``)."""
    names = {host}
    if host in LOOPBACK or host in WILDCARD:
        names |= set(LOOPBACK)
    if host in WILDCARD:
        names.discard(host)
        for name in {socket.gethostname(), socket.getfqdn()}:
            names.add(name)
            try:
                names |= {str(info[4][0]) for info in socket.getaddrinfo(name, None)}
            except OSError:
                pass
    return {n for n in names if n}


def own_hosts(host: str, port: int) -> frozenset[str]:
    """The ``Host`` values of the studio listening on ``host``:``port`` (:func:`reaching_names`)."""
    return frozenset(f"{_bracketed(n)}:{port}" for n in reaching_names(host))


def new_token() -> str:
    """A session's token: 256 random bits, URL-safe."""
    return secrets.token_urlsafe(32)


class SameOrigin:
    """ASGI middleware refusing requests from anywhere but the studio's own page (module docstring)."""

    def __init__(self, app: ASGIApp, hosts: frozenset[str], token: str):
        self.app, self.hosts, self.token = app, hosts, token

    def _refusal(self, scope: Scope) -> PlainTextResponse | None:
        headers = {k.decode("latin-1"): v.decode("latin-1") for k, v in scope["headers"]}
        host, origin = headers.get("host", ""), headers.get("origin")
        if host not in self.hosts:
            shown = ", ".join(sorted(self.hosts)[:6]) + (", …" if len(self.hosts) > 6 else "")
            return PlainTextResponse(f"refused: this studio answers on {shown} only", status_code=403)
        if origin is not None and origin not in {f"http://{h}" for h in self.hosts}:
            return PlainTextResponse("refused: a page of another origin may not drive the studio", status_code=403)
        if scope["method"] in UNSAFE and not secrets.compare_digest(headers.get("x-studio-token", ""), self.token):
            return PlainTextResponse("refused: this request does not carry the studio's session token "
                                     "(reload the studio's page)", status_code=403)
        return None

    async def __call__(self, scope: Scope, receive: Receive, send: Send) -> None:
        if scope["type"] != "http":
            await self.app(scope, receive, send)
            return

        async def framed(message: Message) -> None:
            if message["type"] == "http.response.start":
                message = {**message, "headers": [*message.get("headers", []), *FRAMING]}
            await send(message)

        refused = self._refusal(scope)
        if refused is not None:
            await refused(scope, receive, framed)
            return
        await self.app(scope, receive, framed)
