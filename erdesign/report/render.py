"""Render a :class:`~erdesign.report.builder.Report` to HTML or Markdown with jinja2 (strict undefined).

The HTML is one self-contained file: plotly's JavaScript is embedded once, with the first figure
(``include_plotlyjs=True``), and the other figures reuse it; nothing is fetched from a network.  The Markdown
report tabulates each figure's values instead of drawing it.  A template that names a value the report does not
have is an error (:class:`jinja2.StrictUndefined`), never an empty cell.
"""

from __future__ import annotations

import re
from pathlib import Path
from typing import Any

import jinja2
from markupsafe import Markup

from ..errors import ErdesignError
from ..formatting import esr_shown
from .builder import Report

__all__ = ["render_html", "render_markdown", "write_report", "FORMATS"]

FORMATS = ("html", "md")


def _environment(autoescape: bool) -> jinja2.Environment:
    return jinja2.Environment(
        loader=jinja2.PackageLoader("erdesign.report", "templates"),
        undefined=jinja2.StrictUndefined,
        autoescape=autoescape,
        keep_trailing_newline=True,
    )


def _history(report: Report) -> list[dict[str, Any]]:
    return [{"step": h.step, "effect": h.effect, "esr": esr_shown(h.esr, name=f"history[{i}].esr")}
            for i, h in enumerate(report.history)]


def _stem(report: Report) -> str:
    """The start of the file names of the report's figure images: the design's name (``makris-1996``)."""
    name = report.title.removeprefix("Damper report: ")
    return re.sub(r"[^A-Za-z0-9_-]+", "-", name).strip("-.") or "erdesign"


def render_html(report: Report, image_format: str = "png") -> str:
    """The report as one self-contained HTML page (plotly's JavaScript embedded once).

    The camera button of each figure's toolbar saves it as ``<design>-<figure>.png`` (or ``.svg`` with
    ``image_format="svg"``), drawn by the reader's browser.
    """
    from .plots import export_config

    figures = []
    for i, f in enumerate(report.figures):
        config = {**export_config(f"{_stem(report)}-{f.key}", image_format), "responsive": True}
        html = f.figure.to_html(full_html=False, include_plotlyjs=(i == 0), include_mathjax=False,
                                config=config, div_id=f"plot-{f.key}")
        figures.append({"key": f.key, "title": f.title, "caption": f.caption, "html": Markup(html)})
    template = _environment(autoescape=True).get_template("report.html.j2")
    return template.render(r=report, figures=figures, history=_history(report), image_format=image_format)


def render_markdown(report: Report) -> str:
    """The report as Markdown (figures as tables of their values)."""
    template = _environment(autoescape=False).get_template("report.md.j2")
    return template.render(r=report, history=_history(report))


def write_report(report: Report, path: str | Path, format: str | None = None) -> Path:
    """Write the report to ``path``: ``format`` ``"html"`` or ``"md"``, default from the suffix (``.md`` -> md)."""
    path = Path(path)
    fmt = format or ("md" if path.suffix.lower() in (".md", ".markdown") else "html")
    if fmt not in FORMATS:
        raise ErdesignError(f"format: expected one of {', '.join(FORMATS)}, got {fmt!r}")
    text = render_html(report) if fmt == "html" else render_markdown(report)
    path.write_text(text, encoding="utf-8")
    return path
