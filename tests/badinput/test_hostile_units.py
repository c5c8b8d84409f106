"""Issue 27: values with units that pint reads silently wrong are read as meant or refused naming the argument; and
every message shown to a user is one printable line of readable length (:func:`erdesign.errors.one_line`)."""

from __future__ import annotations

import pytest

from erdesign.errors import MESSAGE_LIMIT, UnitError, one_line
from erdesign.units import clean_value_text, parse_quantity, parse_unit, positive_si, to_si

#: (text, SI unit, SI value): look-alike signs, digits and spaces read as meant
READ_AS_MEANT = [
    ("\u22120.8 mm", "m", -0.8e-3),  # U+2212 MINUS SIGN (pint read it as +0.8 mm)
    ("\ufe630.8 mm", "m", -0.8e-3),  # SMALL HYPHEN-MINUS
    ("\uff0d0.8 mm", "m", -0.8e-3),  # FULLWIDTH HYPHEN-MINUS
    ("\uff10.8 mm", "m", 0.8e-3),  # FULLWIDTH DIGIT ZERO
    ("0.8\u00a0mm", "m", 0.8e-3),  # NO-BREAK SPACE
    ("0.8\u202fmm", "m", 0.8e-3),  # NARROW NO-BREAK SPACE (French typesetting)
    ("0.8\u200b mm", "m", 0.8e-3),  # ZERO WIDTH SPACE: invisible, dropped
    ("\ufeff0.8 mm", "m", 0.8e-3),  # a BOM pasted with the value
    (" 0.8 mm\n", "m", 0.8e-3),  # a line break from a text field
    ("0.8\tmm", "m", 0.8e-3),
    ("0.8 \u00b5m", "m", 0.8e-6),  # MICRO SIGN
    ("0.8 \u03bcm", "m", 0.8e-6),  # GREEK SMALL LETTER MU
    ("120 kN\u00b7s/m", "N*s/m", 1.2e5),  # erdesign's own pretty output reads back
    ("2 m\u00b2", "m^2", 2.0),
    ("-40 degC", "K", 233.15),
    ("-40 \u00b0C", "K", 233.15),
    ("\u221240 degC", "K", 233.15),
    (".5 mm", "m", 0.5e-3),
    ("5. mm", "m", 5e-3),
    ("1e-3 m", "m", 1e-3),
    ("1 kV / mm", "V/m", 1e6),
]


@pytest.mark.parametrize("text, unit, expected", READ_AS_MEANT, ids=[repr(c[0]) for c in READ_AS_MEANT])
def test_look_alikes_are_read_as_meant(text, unit, expected):
    assert to_si(text, unit, "gap") == pytest.approx(expected, rel=1e-12)


#: (text, unit, what the message must say besides the argument's name).  Each of these pint reads silently wrong
#: (value after the arrow) or fails with an unhelpful exception.
REFUSED = [
    ("\u20130.8 mm", "m", "en dash"),  # -> +0.8 mm
    ("\u20140.8 mm", "m", "em dash"),  # -> +0.8 mm
    ("\u20100.8 mm", "m", "hyphen"),
    ("1\u20132 mm", "m", "not a minus sign"),  # a range
    ("4_446.6 N", "N", "'4446.6 N'"),  # -> 4446.6 N: the fix is shown
    ("4'446.6 N", "N", "digit separator"),
    ("1_000_000 N", "N", "'1000000 N'"),
    ("0,8 mm", "m", "'0.8 mm'"),  # -> 0 mm
    ("1,2 A", "A", "decimal comma"),  # -> 12 A
    ("1,2, A", "A", "','"),  # -> 12 A
    ("1 A,", "A", "','"),  # -> 1 A
    ("--0.8 mm", "m", "two signs"),  # -> +0.8 mm
    ("+-0.8 mm", "m", "two signs"),
    ("1.5.2 mm", "m", "two decimal points"),  # -> 0.3 mm
    ("1 mm # c", "m", "'#'"),
    ("mm", "m", "no number"),  # -> 1 mm
    ("kV/mm", "V/m", "no number"),
    ("(", "m", "cannot read"),
    ("3 kV/mm/", "V/m", "the unit ends in '/'"),  # a bare AssertionError from pint
    ("", "m", "cannot read"),
    ("1\x00 mm", "m", "control character"),
    ("1\x1b[31m mm", "m", "control character"),
    ("\u00bd mm", "m", "VULGAR FRACTION"),
    ("\u0663 mm", "m", "ARABIC-INDIC DIGIT"),  # float() would read 3
    ("x" * 300, "m", "too long"),
    ("1/0 mm", "m", "cannot read"),
    ("1e309 mm", "m", "finite"),
    ("nan mm", "m", "finite"),
    ("0.8 kg", "m", "a length"),
    # hostile round 3: pint evaluates expressions, so these were read silently wrong (value after the arrow) or hung
    ("0.8 mm 2", "m", "after the unit"),  # -> 1.6 mm
    ("0.8 mm * 2", "m", "after the unit"),  # -> 1.6 mm
    ("1 m/s; 2", "m/s", "after the unit"),  # -> 2 m/s
    ("1 in/s * 0", "m/s", "after the unit"),  # -> 0 m/s
    ("1/2 mm", "m", "a fraction as a decimal"),  # -> 0.5 mm
    ("2**-10 m", "m", "an expression"),  # -> 0.98 mm
    ("2**1000 m/s", "m/s", "an expression"),  # -> 1.07e301 m/s, then NaN in the results
    ("[1] m/s", "m/s", "one number, then its unit"),  # -> 1 m/s
    ("(0.8 mm)", "m", "one number, then its unit"),
    ("mm 0.8", "m", "one number, then its unit"),  # -> 0.8 mm
    ("nanometer", "m", "one number, then its unit"),  # 'nan' was taken for a number: -> 1 nm
    ("10**10**10 m/s", "m/s", "an expression"),  # pint computed the 10-billion-digit integer (a hang)
    ("1 m^2^3", "m", "power of a power"),
]


@pytest.mark.parametrize("text, unit, expected", REFUSED, ids=[repr(c[0])[:30] for c in REFUSED])
def test_slips_are_refused_naming_the_argument(text, unit, expected):
    with pytest.raises(UnitError) as info:
        to_si(text, unit, "fluid.gap")
    message = str(info.value)
    assert message.startswith("fluid.gap: ") and expected in message, message
    assert "\n" not in message and len(message) < MESSAGE_LIMIT and message == one_line(message), message


def test_the_issue_example_a_unicode_minus_gap_is_negative():
    """`gap = "-0.8 mm"` typed with U+2212 was read as +0.8 mm; it is now -0.8 mm (and a damper refuses it)."""
    assert parse_quantity("\u22120.8 mm", "gap").to("mm").magnitude == -0.8
    assert clean_value_text("\u22120.8 mm", "gap") == "-0.8 mm"


def test_a_power_tower_is_refused_at_once():
    """``10**10**10`` in a value or a header's unit ran for ever (pint evaluates it exactly)."""
    import time

    start = time.perf_counter()
    for text in ("10**10**10 m/s", "1 m^(10**10**10)"):
        with pytest.raises(UnitError, match="power of a power|expression"):
            to_si(text, "m/s", "velocity")
    with pytest.raises(UnitError, match=r"^displacement \[unit\]: .*power of a power"):
        parse_unit("mm**10**10**10", "displacement [unit]")
    assert time.perf_counter() - start < 1.0


def test_units_alone():
    assert parse_unit("kN", "unit").to("N").magnitude == 1000.0
    assert parse_unit("degC", "unit", value=25.0).to("K").magnitude == pytest.approx(298.15)
    for bad, said in [
        ("", "empty"),
        ("furlong2", "unknown unit"),
        ("m\u2013s", "not a minus sign"),
        ("kV/mm/", "the unit ends in '/'"),
        ("2*mm", "holds a number"),  # pint read the header unit '2*mm' as 2 mm
        ("mm 2", "holds a number"),
    ]:
        with pytest.raises(UnitError, match=said):
            parse_unit(bad, "force [unit]")


@pytest.mark.parametrize("value", [None, 3.0, b"0.8 mm", ["0.8 mm"]])
def test_parse_quantity_names_a_value_that_is_not_text(value):
    with pytest.raises(UnitError, match="^gap: expected a value with a unit as a string"):
        parse_quantity(value, "gap")


@pytest.mark.parametrize(
    "value, said",
    [
        ("0 mm", "must be positive, got '0 mm'"),
        ("-1 mm", "must be positive"),
        ("\u22121 mm", "must be positive"),
        ("1 s", "expected a length"),
    ],
)
def test_positive_values_name_the_one_at_fault(value, said):
    with pytest.raises(UnitError, match=f"^amplitude: {said}"):
        positive_si(value, "m", "amplitude")
    assert positive_si("10 mm", "m", "amplitude") == pytest.approx(0.01)


# ------------------------------------------------------------------------------------------ one_line
def test_one_line_keeps_a_short_message_as_it_is():
    text = "gap: must be positive, got -0.8 mm"
    assert one_line(text) == text


def test_one_line_joins_lines_and_spaces():
    assert one_line("line 1:\n  bad\r\n\tcell ") == "line 1: bad cell"


def test_one_line_cuts_a_long_message_keeping_its_start_and_end():
    """The issue: a 200k-character damper name made a 200,052-character error line."""
    text = "name: " + "x" * 200_000 + " is too long; shorten it"
    out = one_line(text)
    assert len(out) == MESSAGE_LIMIT
    assert out.startswith("name: xxx") and out.endswith("is too long; shorten it")
    cut = int(out.split("[... ")[1].split(" characters cut")[0])
    assert len(out) - len(f" [... {cut} characters cut ...] ") + cut == len(text)  # the count is exact


def test_one_line_shows_binary_as_a_count_never_raw():
    """The issue: a renamed .xlsx gave 2,191 characters of binary."""
    blob = "PK\x03\x04\x14\x00\x06\x00\x08\x00" + "".join(chr(c) for c in range(0x80, 0xA0)) * 50
    out = one_line(f"line 1, column 1 ({blob!s}): not a name with a unit")
    assert out.isprintable() and len(out) <= MESSAGE_LIMIT
    assert "binary characters]" in out and out.endswith("not a name with a unit")
    assert one_line("a\x7fb") == "a\\x7fb"  # a lone control character is escaped, not dropped
    assert one_line("bad \udcff byte") == "bad \\udcff byte"  # a surrogate from a bad decode


@pytest.mark.parametrize("limit", [60, 100, 400, 1000])
def test_one_line_respects_any_limit(limit):
    assert len(one_line("k: " + "y" * 5000, limit=limit)) == limit
