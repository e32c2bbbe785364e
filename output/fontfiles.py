"""CJK font files on this machine, found without matplotlib's font cache.

matplotlib lists the installed fonts once and caches the list (``fontlist-*.json`` in its cache
folder); a font installed later (``apt install fonts-noto-cjk``) stays unknown to it until that cache
is deleted. :func:`cjk_font_files` looks for the CJK fonts :mod:`.fonts` wants in the folders fonts
are installed in, by file name, so a figure can load one by path (``FontManager.addfont``).
"""
from __future__ import annotations

import fnmatch
import os
from collections.abc import Iterable
from pathlib import Path

#: Folders fonts are installed in: Linux (fontconfig's defaults), macOS, Windows.
FONT_DIRS = ("~/.local/share/fonts", "~/.fonts", "/usr/local/share/fonts", "/usr/share/fonts",
             "~/Library/Fonts", "/Library/Fonts", "/System/Library/Fonts", "/System/Library/Fonts/Supplemental",
             os.path.join(os.environ.get("WINDIR", r"C:\Windows"), "Fonts"),
             os.path.join(os.environ.get("LOCALAPPDATA", "~"), "Microsoft", "Windows", "Fonts"))

#: File names of regular-weight Japanese-capable fonts, most wanted first (the order of
#: :data:`.fonts.CJK_FAMILIES`): Noto Sans CJK (Debian's ``fonts-noto-cjk``), IPAex/IPA Gothic,
#: Takao, VL Gothic, Source Han Sans, Hiragino, Yu Gothic, Meiryo, MS Gothic, WenQuanYi, Droid.
CJK_FILES = ("NotoSansCJK-Regular.ttc", "NotoSansCJKjp-Regular.otf", "NotoSansCJK*-Regular.*",
             "NotoSansJP-Regular.*", "NotoSansJP*.ttf", "ipaexg.ttf", "ipagp.ttf", "ipag.ttf", "TakaoPGothic.ttf",
             "TakaoGothic.ttf", "VL-PGothic-Regular.ttf", "VL-Gothic-Regular.ttf", "SourceHanSans*-Regular.*",
             "ヒラギノ角ゴシック W3.ttc", "Hiragino Sans GB.ttc", "YuGothR.ttc", "YuGothM.ttc", "meiryo.ttc",
             "msgothic.ttc", "wqy-zenhei.ttc", "DroidSansFallbackFull.ttf", "DroidSansFallback.ttf")


def cjk_font_files(dirs: Iterable[str] | None = None) -> list[Path]:
    """The CJK font files under ``dirs`` (default :data:`FONT_DIRS`; searched recursively), most wanted
    first (:data:`CJK_FILES`)."""
    found: dict[Path, int] = {}
    for folder in dict.fromkeys(Path(os.path.expanduser(d)) for d in (FONT_DIRS if dirs is None else dirs)):
        if not folder.is_dir():
            continue
        for root, _, names in os.walk(folder):
            for name in names:
                rank = next((k for k, pattern in enumerate(CJK_FILES) if fnmatch.fnmatch(name, pattern)), None)
                if rank is not None:
                    found.setdefault(Path(root) / name, rank)
    return sorted(found, key=lambda p: (found[p], str(p)))


def weights_of(path: Path) -> list[Path]:
    """``path`` and the other weights of its family beside it (``NotoSansCJK-Regular.ttc`` ->
    ``NotoSansCJK-Bold.ttc``, ...), ``path`` first."""
    stem, dash, _ = path.stem.rpartition("-")
    others = sorted(path.parent.glob(f"{stem}-*{path.suffix}")) if dash else []
    return [path] + [p for p in others if p != path]
