"""User text written into files (issue 27): damper files (TOML) with every string escaped, so that any name loads
again, and Markdown reports that escape user text, so that a name neither injects HTML nor breaks a table."""

from __future__ import annotations

import re

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from erdesign.damper.files import damper_from_dict, damper_spec, load_damper, load_example, tomllib
from erdesign.damper.writer import damper_toml, save_damper, toml_key, toml_string
from erdesign.errors import ErdesignError, OutputPathError

MAKRIS = load_example("makris")
#: Any text a user can type or paste (every code point UTF-8 can encode: not the surrogates, which are not characters
#: and are refused with their own message, test_a_lone_surrogate_...; hypothesis' default alphabet drew U+D800 once),
#: with the ones that broke the writer before made likely.
TEXT = st.text(alphabet=st.one_of(st.characters(codec="utf-8"), st.sampled_from('\x00\x7f\x85"\\\n\r\t\u2028#[]=')))


@settings(max_examples=100, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(name=TEXT)
def test_any_damper_name_is_written_so_that_it_loads_again(name):
    spec = {**damper_spec(MAKRIS), "name": name}
    back = damper_from_dict(tomllib.loads(damper_toml(spec, comment=f"design {name}")))
    assert back.name == name
    assert (back.geometry, back.fluid, back.seal_friction) == (MAKRIS.geometry, MAKRIS.fluid, MAKRIS.seal_friction)


@settings(max_examples=300, deadline=None)
@given(value=TEXT, key=TEXT.filter(bool), comment=TEXT)
def test_every_string_key_and_comment_round_trips_through_tomllib(value, key, comment):
    text = damper_toml({"name": value, "fluid": {key: value}}, comment=comment)
    data = tomllib.loads(text)
    assert data == {"name": value, "fluid": {key: value}}
    assert tomllib.loads(f"{toml_key(key)} = {toml_string(value)}") == {key: value}


def test_the_del_name_of_the_issue_is_escaped_and_saved_from_the_api_loads(tmp_path):
    """A damper named with DEL, saved through the API, loads again (the raw byte 0x7f made the file invalid)."""
    damper = damper_from_dict({**damper_spec(MAKRIS), "name": "valve\x7f v2"})
    path = save_damper(damper, tmp_path / "d.toml")
    raw = path.read_bytes()
    assert b"\x7f" not in raw and b"\\u007F" in raw
    assert load_damper(path).name == "valve\x7f v2"
    assert load_damper(path).geometry == MAKRIS.geometry
    with pytest.raises(OutputPathError, match="d.toml: exists; pass overwrite=True"):
        save_damper(damper, path)
    save_damper(damper_spec(MAKRIS), path, overwrite=True)
    assert load_damper(path).name == MAKRIS.name


def test_a_lone_surrogate_is_a_one_line_error_naming_the_field():
    with pytest.raises(ErdesignError, match=r"^name: holds the lone surrogate U\+D800") as info:
        damper_toml({**damper_spec(MAKRIS), "name": "bad \ud800"})
    assert "\n" not in str(info.value)
    with pytest.raises(ErdesignError, match=r"^fluid.viscosity: holds the lone surrogate"):
        damper_toml({"fluid": {"viscosity": "7 Pa*s\udc00"}})


def test_the_app_download_of_a_design_with_a_hostile_name_loads_again():
    from erdesign.app.size import design_comment

    design = {
        "spec": {**damper_spec(MAKRIS), "name": 'x"\x7f\n[fluid]\nviscosity = "1 Pa*s"'},
        "velocity": "25 mm/s",
        "field": "3 kV/mm",
        "v_top": "50 mm/s",
    }
    data = tomllib.loads(damper_toml(design["spec"], comment=design_comment(design)))
    assert damper_from_dict(data).name == design["spec"]["name"]
    assert data["fluid"]["viscosity"] == damper_spec(MAKRIS)["fluid"]["viscosity"]  # nothing injected


# ----------------------------------------------------------------------------------------------- Markdown
HOSTILE = "<script>alert(1)</script> | *bold* `tick` _u_ [link](http://x) # h\nnew line"


@pytest.fixture(scope="module")
def hostile_markdown(tmp_path_factory):
    from erdesign.report.builder import build_report
    from erdesign.report.render import render_html, render_markdown

    path = save_damper({**damper_spec(MAKRIS), "name": HOSTILE}, tmp_path_factory.mktemp("md") / "hostile.toml")
    report = build_report(str(path))
    return render_markdown(report), render_html(report)


def _cells(line: str) -> list[str]:
    """The cells of a Markdown table row, split at unescaped pipes only (GitHub-flavoured Markdown)."""
    return re.split(r"(?<!\\)\|", line.strip())[1:-1]


def test_a_hostile_name_injects_no_html_into_the_markdown_report(hostile_markdown):
    md, html = hostile_markdown
    assert not re.search(r"(?<!\\)</?script", md)  # every "<" of the name is escaped: "\<script"
    assert "<script>alert" not in html  # the HTML report escaped it already
    title = md.splitlines()[0]
    assert title == (
        "# Damper report: \\<script>alert(1)\\</script> \\| \\*bold\\* \\`tick\\` \\_u\\_ "
        "[link\\](http://x) \\# h new line"
    )


def test_a_hostile_name_breaks_no_table_of_the_markdown_report(hostile_markdown):
    md, _ = hostile_markdown
    lines = md.splitlines()
    tables = 0
    for i, line in enumerate(lines[:-1]):
        if line.startswith("|") and re.match(r"^\|( ?-+:? ?\|)+$", lines[i + 1].replace(" ", "")):
            width, tables = len(_cells(line)), tables + 1
            j = i + 2
            while j < len(lines) and lines[j].startswith("|"):
                assert len(_cells(lines[j])) == width, (line, lines[j])
                j += 1
    assert tables >= 5
    assert HOSTILE.split("\n")[0] not in md  # the name is never printed raw


def test_markdown_code_spans_hold_any_backticks():
    from erdesign.report.render import markdown_code

    assert markdown_code("0.8 mm") == "`0.8 mm`"
    assert markdown_code("a``b") == "``` a``b ```"
    assert markdown_code("x | y", table=True) == "`x \\| y`"


@settings(max_examples=200, deadline=None)
@given(text=TEXT)
def test_any_user_text_is_one_markdown_line_with_every_active_character_escaped(text):
    from erdesign.report.render import markdown_text

    out = markdown_text(text)
    assert "\n" not in out and "\r" not in out and "\u2028" not in out
    # every backslash escapes the character after it, and every active character is escaped
    i, shown = 0, []
    while i < len(out):
        if out[i] == "\\":
            assert out[i + 1] in "\\`*<|#_]", (text, out)
            shown.append(out[i + 1])
            i += 2
            continue
        assert out[i] not in "\\`*<|#", (text, out)
        shown.append(out[i])
        i += 1
    one_line = re.sub(r"[\x00-\x1f\x7f-\x9f\u2028\u2029]+", " ", text)
    assert "".join(shown) == one_line  # what the reader sees is what the user wrote
