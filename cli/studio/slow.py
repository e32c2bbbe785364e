"""Slow clients cut off: a request's headers must arrive within :data:`HEADER_TIMEOUT` seconds of its first byte.

uvicorn times out an idle kept-alive connection, but a client that sends its headers a byte at a time keeps a
connection (and its memory) for ever: every byte restarts the keep-alive clock (issue 41: "headers and bodies
never time out"). Bodies have their own limit (``app.BODY_TIMEOUT``, read by the application). Headers are read
by the server before the application sees the request, so the guard is in two parts:

- :func:`guarded` wraps the server's HTTP protocol class: it notes when the bytes of a request start arriving on
  a connection and closes the connection if no request has reached the application :data:`HEADER_TIMEOUT` seconds
  later;
- :class:`Arrived`, the application's outermost middleware, tells the connection (found by the client's address
  and port, unique per connection) that its request's headers arrived, and when its answer is sent.
"""
from __future__ import annotations

import asyncio
import time
from typing import Any

#: Seconds a request's headers may take to arrive after its first byte.
HEADER_TIMEOUT = 10.0
#: Seconds between two looks at a connection's clock.
CHECK_EVERY = 1.0

#: Open connections by the client's (address, port): what :class:`Arrived` tells.
_OPEN: dict[tuple, Any] = {}


def guarded(protocol: type) -> type:
    """A subclass of the server's HTTP ``protocol`` (an :class:`asyncio.Protocol`) that closes a connection whose
    request headers take over :data:`HEADER_TIMEOUT` seconds."""

    class Guarded(protocol):
        def connection_made(self, transport) -> None:
            super().connection_made(transport)
            self._t2a_transport, self._t2a_answering = transport, False
            self._t2a_since: float | None = None
            self._t2a_peer = _peer(transport.get_extra_info("peername"))
            _OPEN[self._t2a_peer] = self
            self._t2a_timer = asyncio.get_running_loop().call_later(CHECK_EVERY, self._t2a_check)

        def data_received(self, data: bytes) -> None:
            if self._t2a_since is None and not self._t2a_answering:
                self._t2a_since = time.monotonic()  # a request's first bytes: its headers' clock starts
            super().data_received(data)

        def connection_lost(self, exc) -> None:
            self._t2a_timer.cancel()
            _OPEN.pop(self._t2a_peer, None)
            super().connection_lost(exc)

        def _t2a_check(self) -> None:
            since = self._t2a_since
            if since is not None and not self._t2a_answering and time.monotonic() - since > HEADER_TIMEOUT:
                self._t2a_transport.close()
                return
            self._t2a_timer = asyncio.get_running_loop().call_later(CHECK_EVERY, self._t2a_check)

    Guarded.__name__ = Guarded.__qualname__ = f"Guarded{protocol.__name__}"
    return Guarded


def _peer(address) -> tuple:
    return tuple(address[:2]) if isinstance(address, (tuple, list)) else (str(address),)


class Arrived:
    """ASGI middleware: a request reached the application (its headers arrived) and, later, was answered."""

    def __init__(self, app) -> None:
        self.app = app

    async def __call__(self, scope, receive, send) -> None:
        conn = _OPEN.get(_peer(scope.get("client") or ())) if scope["type"] == "http" else None
        if conn is None:
            await self.app(scope, receive, send)
            return
        conn._t2a_answering, conn._t2a_since = True, None
        try:
            await self.app(scope, receive, send)
        finally:
            conn._t2a_answering, conn._t2a_since = False, None


def server_config(app, host: str, port: int, **options):
    """A ``uvicorn.Config`` serving ``app`` with the header timeout (the protocol :func:`guarded`, the app
    wrapped in :class:`Arrived`)."""
    import uvicorn

    probe = uvicorn.Config(app, host=host, port=port, **options)
    probe.load()  # resolves "auto" to the installed protocol class
    return uvicorn.Config(Arrived(app), host=host, port=port, http=guarded(probe.http_protocol_class), **options)
