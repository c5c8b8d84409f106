"""Files a user takes away: the damper file (TOML) of a design and CSV tables with units in their headers.

:func:`damper_toml` (:mod:`erdesign.damper.writer`, every string escaped) writes the content of a damper file
(docs/file_formats.md: the plain data that :func:`erdesign.damper.files.damper_from_dict` reads) as TOML text that
``erdesign size`` and the app's upload read back; :func:`csv_text` writes columns of numbers with ``name [unit]`` headers, the form of a measurement file
(section 2), so that a time history written here can be read again as a measurement; :func:`rows_csv` writes a
table of text (a ranking, a list of parameters).

>>> text = damper_toml({"name": "d", "geometry": {"configuration": "valve", "gap": "0.8 mm", "ducts": 1},
...                     "fluid": {"yield_exponent": 2.0}})
>>> print(text.split("\\n\\n", 1)[1])
name = "d"
<BLANKLINE>
[geometry]
configuration = "valve"
gap = "0.8 mm"
ducts = 1
<BLANKLINE>
[fluid]
yield_exponent = 2.0
<BLANKLINE>
>>> print(csv_text([("time", "s", [0.0, 0.5]), ("force", "N", [1.25, -3.0])]), end="")
time [s],force [N]
0,1.25
0.5,-3
"""

from __future__ import annotations

import csv
import io
import math
from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np

from ..damper.writer import damper_toml  # the damper file's writer lives with the damper files
from ..errors import ErdesignError

__all__ = ["damper_toml", "csv_text", "rows_csv", "figure_images", "figure_pages", "images_zip", "IMAGES_NEED"]


def _number(x: float) -> str:
    return "" if not math.isfinite(x) else f"{x:.10g}"


def csv_text(columns: Sequence[tuple[str, str, Any]], *, comment: str = "") -> str:
    """Columns of numbers as CSV: first line ``name [unit]`` per column (``[1]`` for a ratio), then the rows.

    ``columns`` are ``(name, unit, values)``, all of one length; numbers get 10 significant figures, a missing
    (non-finite) value is an empty cell.  ``comment`` lines come first, each starting with ``#`` (a measurement
    file allows them).
    """
    arrays = [np.asarray(values, dtype=float).ravel() for _, _, values in columns]
    n = {a.size for a in arrays}
    if len(n) > 1:
        raise ErdesignError(f"csv: columns of different lengths {sorted(n)}")
    out = io.StringIO()
    for line in comment.splitlines():
        out.write(f"# {line}\n")
    writer = csv.writer(out, lineterminator="\n")
    writer.writerow([f"{name} [{unit or '1'}]" for name, unit, _ in columns])
    for row in zip(*arrays):
        writer.writerow([_number(float(x)) for x in row])
    return out.getvalue()


def rows_csv(rows: Sequence[Mapping[str, Any]], *, comment: str = "") -> str:
    """A table of rows (dicts with the same keys, values as text or numbers) as CSV with a header line."""
    out = io.StringIO()
    for line in comment.splitlines():
        out.write(f"# {line}\n")
    if not rows:
        return out.getvalue()
    writer = csv.DictWriter(out, fieldnames=list(rows[0]), lineterminator="\n", extrasaction="ignore")
    writer.writeheader()
    writer.writerows(rows)
    return out.getvalue()


#: What static figure images need, said when they cannot be made.
IMAGES_NEED = (
    'static figure images need the optional package kaleido (>= 1, `pip install "erdesign[docs]"`) '
    "and a Chrome or Chromium already on the machine (e.g. `apt-get install chromium`); erdesign never "
    "downloads a browser. Without them, save each figure with the camera button of its toolbar in the "
    "app or in the HTML report"
)


def figure_images(figures: Sequence[Any], image_format: str = "png", *, timeout: float = 120.0) -> dict[str, bytes]:
    """Static images of a report's figures (:class:`~erdesign.report.builder.FigureSpec`), ``{"<key>.png": bytes}``.

    Drawn by plotly.js in a headless Chrome or Chromium that kaleido (>= 1) drives: the browser must already be
    installed (found on the PATH, or named by the environment variable ``BROWSER_PATH``); nothing is downloaded,
    neither a browser nor a script (plotly.js comes with plotly; MathJax is not used).

    Raises
    ------
    ErdesignError
        kaleido is not installed, no browser is found, or the browser fails; the message says what to install
        (:data:`IMAGES_NEED`).
    """
    import asyncio
    import concurrent.futures

    if image_format not in ("png", "svg"):
        raise ErdesignError(f"image format: expected png or svg, got {image_format!r}")
    try:
        import kaleido
    except ImportError:
        raise ErdesignError(f"figure images: kaleido is not installed; {IMAGES_NEED}") from None

    opts = {"format": image_format, "scale": 2 if image_format == "png" else 1}

    async def draw() -> list[bytes]:
        # one browser for all the figures; mathjax=False: kaleido would otherwise load MathJax from a CDN
        async with kaleido.Kaleido(n=1, mathjax=False, timeout=timeout) as k:
            return [
                await k.calc_fig(
                    f.figure, opts=dict(opts, width=f.figure.layout.width or 900, height=f.figure.layout.height or 450)
                )
                for f in figures
            ]

    try:
        # a thread of its own: asyncio.run needs a thread without a running event loop (Streamlit, Jupyter)
        with concurrent.futures.ThreadPoolExecutor(max_workers=1) as pool:
            images = pool.submit(asyncio.run, draw()).result()
    except Exception as exc:  # ChromeNotFoundError, a browser that dies, a timeout: say what is needed
        first = " ".join(str(exc).split())[:200] or type(exc).__name__
        raise ErdesignError(f"figure images: {type(exc).__name__}: {first}; {IMAGES_NEED}") from None
    return {f"{f.key}.{image_format}": bytes(b) for f, b in zip(figures, images)}


def figure_pages(figures: Sequence[Any], image_format: str = "png") -> dict[str, bytes]:
    """The report's figures as interactive HTML pages, ``{"<key>.html": bytes, "plotly.min.js": bytes}``: the
    static fallback that needs nothing beyond plotly (no kaleido, no browser on the server).  Each page loads the
    one ``plotly.min.js`` beside it (plotly's own copy: nothing is fetched from the network); its camera button
    saves the figure as ``image_format`` (:func:`erdesign.report.plots.export_config`).
    """
    from plotly.offline import get_plotlyjs

    from .plots import export_config

    pages = {"plotly.min.js": get_plotlyjs().encode()}
    for f in figures:
        html = f.figure.to_html(
            include_plotlyjs="plotly.min.js", full_html=True, config=export_config(f.key, image_format)
        )
        pages[f"{f.key}.html"] = html.encode()
    return pages


def images_zip(images: Mapping[str, bytes]) -> bytes:
    """The images of :func:`figure_images` as one ZIP archive (a download)."""
    import zipfile

    buffer = io.BytesIO()
    with zipfile.ZipFile(buffer, "w", zipfile.ZIP_DEFLATED) as archive:
        for name, data in images.items():
            archive.writestr(name, data)
    return buffer.getvalue()
