"""The studio's page as served: its words in Japanese and English, and the Japanese font that draws them.

The page's words are one catalogue, ``static/messages.json`` (key -> ``{"ja", "en"}``; ``{name}`` marks what
the page fills in), served inside the page so that it is never drawn in another language first. A machine
without a Japanese font drew them as boxes, so the page carries two faces of the Noto Sans CJK JP the package
ships (:mod:`text2anim.output.embedded_font`):

- ``t2a-ui``: the catalogue's and the page's own characters, embedded in the page (about 31 KB for 200
  characters), drawn at once;
- ``t2a-jp``: every kana and JIS X 0208 kanji (levels 1 and 2), for what the user types, which cannot be known
  ahead: a WOFF of 1.3 MB served by the studio at :data:`FONT_URL` (cached by the browser), fetched only when
  a character the first face lacks is on screen. Measured: the whole set as WOFF 1,293,788 bytes (under the
  2 MB one could embed, but 1.7 MB more in every page load as base64), the catalogue's subset 31,164 bytes.
"""
from __future__ import annotations

import base64
import json
from functools import lru_cache
from importlib import resources

#: Where the page fetches the face for what the user types.
FONT_URL = "/static/font/jp.woff"
#: The page's languages, the first the default.
LANGUAGES = ("ja", "en")


def _static(name: str) -> str:
    return resources.files(__package__).joinpath("static").joinpath(name).read_text(encoding="utf-8")


@lru_cache(maxsize=1)
def messages() -> dict[str, dict[str, str]]:
    """The page's catalogue: key -> ``{"ja": ..., "en": ...}``."""
    catalogue: dict[str, dict[str, str]] = json.loads(_static("messages.json"))
    return catalogue


@lru_cache(maxsize=1)
def font_css() -> str:
    """The two ``@font-face`` rules (``t2a-ui`` embedded, ``t2a-jp`` fetched from :data:`FONT_URL`)."""
    from text2anim.output import embedded_font

    words = "".join(m[lang] for m in messages().values() for lang in LANGUAGES) + _static("studio.html")
    ui = base64.b64encode(embedded_font.subset_woff(embedded_font.page_chars(words))).decode("ascii")
    rng = f"U+{embedded_font.CJK_FROM:X}-FFFF"
    return (f'@font-face {{ font-family: "t2a-ui"; font-display: block; unicode-range: {rng}; '
            f'src: url(data:font/woff;base64,{ui}) format("woff"); }}\n'
            f'@font-face {{ font-family: "t2a-jp"; font-display: block; unicode-range: {rng}; '
            f'src: url({FONT_URL}) format("woff"); }}')


@lru_cache(maxsize=1)
def full_font() -> bytes:
    """The shipped font's every glyph as WOFF (what :data:`FONT_URL` answers)."""
    import io

    from fontTools.ttLib import TTFont

    from text2anim.output import embedded_font

    font = TTFont(embedded_font.font_path(), recalcTimestamp=False)
    font.flavor = "woff"
    buf = io.BytesIO()
    font.save(buf)
    return buf.getvalue()


def html(token: str) -> str:
    """The page, with the session's token, the catalogue and the fonts in its head."""
    head = (f'<meta name="t2a-token" content="{token}">\n<style>{font_css()}</style>\n'
            f'<script type="application/json" id="t2a-messages">{_script_json(messages())}</script>\n</head>')
    return _static("studio.html").replace("</head>", head, 1)


def _script_json(data: object) -> str:
    """JSON safe inside a ``<script>`` element (no ``</`` can end it)."""
    return json.dumps(data, ensure_ascii=False, separators=(",", ":")).replace("</", "<\\/")
