"""Build ``output/fontdata/NotoSansCJKjp-JIS0208.otf``: the Japanese font the package ships.

Noto Sans CJK JP Regular (SIL Open Font License 1.1), cut down to the characters of JIS X 0208
(the 6,355 kanji of levels 1 and 2, kana, full-width Latin and symbols: 6,879 characters) plus
ASCII, without hinting and layout features: 1.5 MB instead of the 19 MB collection. The viewer
page embeds a subset of it for the characters the page shows (:mod:`output.embedded_font`), and
contact sheets draw Japanese with it when the machine has no CJK font (:mod:`output.fonts`).

Source: Debian's ``fonts-noto-cjk`` (``apt-get download fonts-noto-cjk`` and ``dpkg-deb -x``, or the
installed package)::

    python tools/build_jp_font.py /usr/share/fonts/opentype/noto/NotoSansCJK-Regular.ttc

Needs fontTools (``pip install fonttools``). The same source gives the same bytes.
"""
from __future__ import annotations

import sys
from pathlib import Path

from fontTools import subset
from fontTools.ttLib import TTCollection

OUT = Path(__file__).resolve().parents[1] / "output" / "fontdata" / "NotoSansCJKjp-JIS0208.otf"
FAMILY = "Noto Sans CJK JP JIS0208"


def jis_x_0208() -> list[str]:
    """Every character of JIS X 0208, read off Python's EUC-JP codec (rows 1-84)."""
    out = []
    for hi in range(0xA1, 0xF5):
        for lo in range(0xA1, 0xFF):
            try:
                out.append(bytes([hi, lo]).decode("euc_jp"))
            except UnicodeDecodeError:
                continue
    return out


def main(src: str) -> None:
    font = next(f for f in TTCollection(src).fonts if f["name"].getDebugName(1) == "Noto Sans CJK JP")
    opts = subset.Options()
    opts.layout_features = []
    opts.hinting = False
    opts.name_IDs = [0, 1, 2, 3, 4, 5, 6, 13, 14]
    opts.notdef_outline = True
    sub = subset.Subsetter(opts)
    sub.populate(unicodes=sorted({ord(c) for c in jis_x_0208()} | set(range(0x20, 0x7F))))
    sub.subset(font)
    names = font["name"]
    for rec in list(names.names):  # a modified version says so in its name (OFL 1.1 §3 reserves only "Source")
        if rec.nameID in (1, 4):
            names.setName(FAMILY if rec.nameID == 1 else f"{FAMILY} Regular", rec.nameID, rec.platformID,
                          rec.platEncID, rec.langID)
        elif rec.nameID == 6:
            names.setName("NotoSansCJKjp-JIS0208-Regular", 6, rec.platformID, rec.platEncID, rec.langID)
    font.recalcTimestamp = False  # reproducible bytes: head.modified stays the source's
    font.save(OUT)
    print(f"wrote {OUT} ({OUT.stat().st_size:,} bytes)")


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "/usr/share/fonts/opentype/noto/NotoSansCJK-Regular.ttc")
