"""Who may talk to the studio: only its own page, on the address it listens on.

A web page elsewhere must not drive a local tool (DNS rebinding, cross-site POSTs): a request
whose ``Host`` is not one of the studio's own addresses, or whose ``Origin`` (sent by browsers on
cross-origin requests and on every POST) is not ``http://`` + one of them, is refused with 403.
"""
from __future__ import annotations

from starlette.responses import PlainTextResponse
from starlette.types import ASGIApp, Receive, Scope, Send


def own_hosts(host: str, port: int) -> frozenset[str]:
    """The ``Host`` values of the studio listening on ``host``:``port`` (loopback names included)."""
    names = {host}
    if host in ("127.0.0.1", "localhost", "::1"):
        names |= {"127.0.0.1", "localhost", "[::1]"}
    return frozenset(f"{n}:{port}" for n in names)


class SameOrigin:
    """ASGI middleware refusing requests from anywhere but the studio's own page (module docstring)."""

    def __init__(self, app: ASGIApp, hosts: frozenset[str]):
        self.app, self.hosts = app, hosts

    async def __call__(self, scope: Scope, receive: Receive, send: Send) -> None:
        if scope["type"] == "http":
            headers = {k.decode("latin-1"): v.decode("latin-1") for k, v in scope["headers"]}
            host, origin = headers.get("host", ""), headers.get("origin")
            if host not in self.hosts:
                await PlainTextResponse(f"refused: this studio answers on {', '.join(sorted(self.hosts))} only",
                                        status_code=403)(scope, receive, send)
                return
            if origin is not None and origin not in {f"http://{h}" for h in self.hosts}:
                await PlainTextResponse("refused: a page of another origin may not drive the studio",
                                        status_code=403)(scope, receive, send)
                return
        await self.app(scope, receive, send)
