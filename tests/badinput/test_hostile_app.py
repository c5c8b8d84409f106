"""Issue 27 in the app: hostile uploads and typed values show one message naming the file, line or field (never
"Internal error", a traceback or binary) and leave the last good design in place (Streamlit's AppTest)."""

from __future__ import annotations

import io
import zipfile

import pytest

from erdesign.errors import MESSAGE_LIMIT

from .corpus import GOOD_RECORD, MAKRIS
from .test_app_corpus import _clean, app  # noqa: F401  (app: the module's AppTest fixture)


def _xlsx() -> bytes:
    buffer = io.BytesIO()
    with zipfile.ZipFile(buffer, "w") as z:
        z.writestr("xl/worksheets/sheet1.xml", "<row><c>1.0</c></row>" * 2000)
    return buffer.getvalue()


COMPARE_UPLOADS = [
    (
        "1 MB header cell",
        "big.csv",
        "time [s],displacement [mm],force [N]" + "x" * 1_000_000 + "\n" + "\n".join(GOOD_RECORD.splitlines()[1:]),
        "line 1",
    ),
    ("renamed xlsx", "data.csv", _xlsx(), "spreadsheet"),
    ("decimal comma", "comma.csv", GOOD_RECORD.replace("\n0.02,", '\n"0,02",', 1), "line 12"),
]
SIZE_UPLOADS = [
    (
        "deeply nested",
        "n.toml",
        MAKRIS.replace("[fluid]", "[fluid]\nx = " + "[" * 5000 + "]" * 5000, 1),
        "nested too deeply",
    ),
    ("unicode minus gap", "m.toml", MAKRIS.replace('"0.8 mm"', '"\u22120.8 mm"'), "geometry.gap"),
    ("Latin-1 file", "l.toml", MAKRIS.replace("makris-1996", "D\u00e4mpfer").encode("latin-1"), "line 4"),
    ("UTF-16 file", "u.toml", MAKRIS.encode("utf-16"), "UTF-16"),
]
SIZE_INPUTS = [
    ("gap unicode minus", "size.geo.gap", "\u22120.8 mm", "geometry.gap"),
    ("gap decimal comma", "size.geo.gap", "0,8 mm", "geometry.gap"),
    ("viscosity digit separator", "size.fluid.viscosity", "7_000 mPa*s", "fluid.viscosity"),
    ("gap expression", "size.geo.gap", "0.8 mm * 2", "geometry.gap"),  # read as 1.6 mm before (round 3)
    ("gap fraction", "size.geo.gap", "1/2 mm", "geometry.gap"),
]


def _short(at):
    for e in at.error:
        assert len(e.value) <= MESSAGE_LIMIT + 200 and e.value.isprintable(), e.value[:300]


@pytest.mark.parametrize("case", SIZE_INPUTS, ids=[c[0] for c in SIZE_INPUTS])
def test_size_input(app, case):  # noqa: F811
    _, key, value, field = case
    good = app.text_input(key=key).value
    app.text_input(key=key).set_value(value).run()
    _clean(app, field)
    _short(app)
    app.text_input(key=key).set_value(good).run()
    assert not app.exception and not app.error


@pytest.mark.parametrize("case", COMPARE_UPLOADS, ids=[c[0] for c in COMPARE_UPLOADS])
def test_compare_upload(app, case):  # noqa: F811
    _, name, content, field = case
    data = content if isinstance(content, bytes) else content.encode()
    app.switch_page("compare.py").run()
    app.radio(key="cmp.source").set_value("upload a measurement CSV").run()
    app.file_uploader(key="cmp.upload").set_value((name, data, "text/csv")).run()
    _clean(app, field)
    _short(app)
    app.switch_page("size.py").run()
    assert not app.exception


@pytest.mark.parametrize("case", SIZE_UPLOADS, ids=[c[0] for c in SIZE_UPLOADS])
def test_size_upload(app, case):  # noqa: F811
    _, name, content, field = case
    before = app.text_input(key="size.geo.gap").value
    data = content if isinstance(content, bytes) else content.encode()
    app.file_uploader(key="size.upload").set_value((name, data, "application/toml")).run()
    _clean(app, field)
    _short(app)
    assert app.text_input(key="size.geo.gap").value == before


def test_size_upload_with_a_bom_is_taken(app):  # noqa: F811
    """A damper file saved by Notepad (a BOM first) was 'invalid TOML' in the app too."""
    text = MAKRIS.replace('gap = "0.8 mm"', 'gap = "0.9 mm"')
    app.file_uploader(key="size.upload").set_value(("bom.toml", b"\xef\xbb\xbf" + text.encode(), "x")).run()
    assert not app.exception and not app.error
    assert app.text_input(key="size.geo.gap").value == "0.9 mm"
