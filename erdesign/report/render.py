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
from ..output import write_output
from .builder import Report

__all__ = ["render_html", "render_markdown", "write_report", "markdown_text", "markdown_code", "FORMATS"]

FORMATS = ("html", "md")


#: Characters that mean something in (GitHub-flavoured) Markdown text and are escaped with a backslash in user text:
#: inline HTML and autolinks (``<``), emphasis (``*``, ``_`` at a word's edge), code (backtick), links (a ``]``
#: followed by ``(``, ``[`` or ``:``; a lone ``[unit]`` is plain text), table cells (``|``), headings (``#``) and the
#: backslash itself.
_MARKDOWN_SPECIAL = re.compile(r"[\\`*<|#]|\](?=[(\[:])|(?<!\w)_|_(?!\w)")
#: Line breaks (a table row or a heading ends at one) and other control characters.
_MARKDOWN_BREAKS = re.compile(r"[\x00-\x1f\x7f-\x9f\u2028\u2029]+")


def markdown_text(value: Any) -> str:
    """``value`` as Markdown text that shows as written: one line, every Markdown-active character escaped.

    Every value the Markdown template prints goes through this (the environment's ``finalize``) unless the template
    marks it as its own Markdown (``| safe``: the library's equations); a damper named ``<script>`` or ``a | b``
    neither injects HTML nor breaks a table.

    >>> print(markdown_text("<script>alert(1)</script> | *x* `y` _z_ seal_friction [a](b) [kN]"))
    \\<script>alert(1)\\</script> \\| \\*x\\* \\`y\\` \\_z\\_ seal_friction [a\\](b) [kN]
    """
    if isinstance(value, Markup):
        return value
    return _MARKDOWN_SPECIAL.sub(lambda m: "\\" + m.group(0), _MARKDOWN_BREAKS.sub(" ", str(value)))


def markdown_code(value: Any, table: bool = False) -> Markup:
    """``value`` as one Markdown code span, whatever backticks it holds (a fence longer than its longest run);
    ``table=True`` in a table cell, where GitHub-flavoured Markdown needs ``|`` escaped even inside code.

    >>> print(markdown_code("a ` b | c", table=True))
    `` a ` b \\| c ``
    """
    text = _MARKDOWN_BREAKS.sub(" ", str(value))
    if table:
        text = text.replace("|", "\\|")
    fence = "`" * (max((len(run) for run in re.findall("`+", text)), default=0) + 1)
    pad = " " if text.startswith("`") or text.endswith("`") or len(fence) > 1 else ""
    return Markup(f"{fence}{pad}{text}{pad}{fence}")


def _environment(autoescape: bool) -> jinja2.Environment:
    if autoescape:
        env = jinja2.Environment(
            loader=jinja2.PackageLoader("erdesign.report", "templates"),
            undefined=jinja2.StrictUndefined,
            autoescape=True,
            keep_trailing_newline=True,
        )
    else:  # Markdown: user text escaped as Markdown (the counterpart of the HTML's autoescape)
        env = jinja2.Environment(
            loader=jinja2.PackageLoader("erdesign.report", "templates"),
            undefined=jinja2.StrictUndefined,
            autoescape=False,
            keep_trailing_newline=True,
            finalize=markdown_text,
        )
        env.filters["code"] = markdown_code
        env.filters["md"] = markdown_text
    return env


def _history(report: Report) -> list[dict[str, Any]]:
    return [
        {"step": h.step, "effect": h.effect, "esr": esr_shown(h.esr, name=f"history[{i}].esr")}
        for i, h in enumerate(report.history)
    ]


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
        html = f.figure.to_html(
            full_html=False, include_plotlyjs=(i == 0), include_mathjax=False, config=config, div_id=f"plot-{f.key}"
        )
        figures.append({"key": f.key, "title": f.title, "caption": f.caption, "html": Markup(html)})
    template = _environment(autoescape=True).get_template("report.html.j2")
    return template.render(r=report, figures=figures, history=_history(report), image_format=image_format)


def render_markdown(report: Report) -> str:
    """The report as Markdown (figures as tables of their values)."""
    template = _environment(autoescape=False).get_template("report.md.j2")
    return template.render(r=report, history=_history(report))


def write_report(
    report: Report, path: str | Path, format: str | None = None, *, overwrite: bool = False, option: str = "path"
) -> Path:
    """Write the report to ``path``: ``format`` ``"html"`` or ``"md"``, default from the suffix (``.md`` -> md).

    Written whole or not at all, and an existing ``path`` only with ``overwrite`` (:mod:`erdesign.output`; ``option``
    names the output in messages, e.g. ``--out``)."""
    path = Path(path)
    fmt = format or ("md" if path.suffix.lower() in (".md", ".markdown") else "html")
    if fmt not in FORMATS:
        raise ErdesignError(f"format: expected one of {', '.join(FORMATS)}, got {fmt!r}")
    text = render_html(report) if fmt == "html" else render_markdown(report)
    return write_output(path, text, overwrite=overwrite, option=option)
