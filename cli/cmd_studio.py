"""``text2anim studio``: a local web page to type Japanese, watch it act and export it (cli/studio/).

Listens on 127.0.0.1 (a free port unless ``--port``), prints the address and opens it in the
default browser unless ``--no-browser``; ``--host`` listens elsewhere, with a warning, since
anyone who reaches that address can run the studio. Ctrl+C stops it.
"""
from __future__ import annotations

import signal
import socket
import sys

from .terminal import say

NAME = "studio"
HELP = "a local web page: type Japanese, watch it act as you type, add sentences while it plays, export BVH"


def add_arguments(p):
    p.add_argument("--port", type=int, default=0, help="the port to listen on (default: a free one, printed)")
    p.add_argument("--host", default="127.0.0.1",
                   help="the address to listen on (default 127.0.0.1: this machine only)")
    p.add_argument("--no-browser", action="store_true", help="do not open the page in the default browser")
    p.add_argument("--db", metavar="URL", default=None,
                   help="motion database URL or SQLite file (default: $TEXT2ANIM_DB, else the built-in library's)")


def free_port(host: str) -> int:
    """A port free on ``host`` now (the OS picks it)."""
    with socket.socket(socket.AF_INET6 if ":" in host else socket.AF_INET) as s:
        s.bind((host, 0))
        return int(s.getsockname()[1])


def run(args) -> int:
    import uvicorn

    from .studio.app import create_app
    from .studio.guard import LOOPBACK
    from .studio.slow import server_config

    if not 0 <= args.port <= 65535:
        say(f"text2anim studio: error: --port must be 0..65535, not {args.port}", file=sys.stderr)
        return 2
    port = args.port or free_port(args.host)
    if args.host not in LOOPBACK:
        say(f"text2anim studio: warning: listening on {args.host}: anyone who can reach it can use the studio",
            file=sys.stderr)
    app = create_app(args.db, args.host, port)
    url = f"http://{'[' + args.host + ']' if ':' in args.host else args.host}:{port}/"
    say(f"text2anim studio: {url}  (Ctrl+C stops it)", flush=True)
    if not args.no_browser:
        import webbrowser

        webbrowser.open(url)
    # uvicorn stops on SIGTERM, then raises it again with the handler it found: this one, so the process
    # ends through the ``finally`` below (with the default one it died there, the dropped character left behind)
    previous = signal.signal(signal.SIGTERM, _terminated)
    try:
        uvicorn.Server(server_config(app, args.host, port, log_level="warning")).run()
    finally:
        signal.signal(signal.SIGTERM, previous)
        app.state.studio.close()
    return 0


def _terminated(signum, frame) -> None:
    raise SystemExit(128 + signum)
