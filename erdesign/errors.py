"""Errors and warnings of erdesign.

Every error raised for bad input is an :class:`ErdesignError` whose message names the argument, the file key or
the line and column at fault, so that the command line can print it as one line and the app can show it in the
page.  They derive from :class:`ValueError` so that callers who do not know erdesign still catch them.
"""

from itertools import groupby

__all__ = [
    "ErdesignError",
    "UnitError",
    "DamperFileError",
    "OutputPathError",
    "PlausibilityWarning",
    "ErdesignWarning",
    "ValidityWarning",
    "one_line",
    "cut",
    "MESSAGE_LIMIT",
    "did_you_mean",
]


class ErdesignError(ValueError):
    """Bad input: the message says which argument, key or line is wrong and what was expected.

    The message is one line (a pandas object's repr in it ran over several) and one longer than
    :data:`MESSAGE_LIMIT` is cut as the command line cuts it (:func:`cut`): a 5,000-character file name made a
    5,000-character message for the API's caller.
    """

    def __init__(self, *args):
        if len(args) == 1 and isinstance(args[0], str):
            text = args[0]
            if "\n" in text or "\r" in text:
                text = " ".join(text.split())
            args = (cut(text),)
        super().__init__(*args)


class UnitError(ErdesignError):
    """A value has the wrong dimension, an unknown unit, or is not finite."""


class DamperFileError(ErdesignError):
    """A damper (TOML) file is malformed: unknown or missing key, wrong type or dimension."""


class OutputPathError(ErdesignError):
    """An output file that must not be written: an input of the same call, an existing file without --force, or a
    suffix whose format the command does not write."""


class ErdesignWarning(UserWarning):
    """Base class of the warnings erdesign issues."""


class ValidityWarning(ErdesignWarning):
    """A model is used outside the range where its assumptions hold (thin gap, laminar flow, field range...)."""


class PlausibilityWarning(ErdesignWarning):
    """A value is possible but implausible (outside the range real dampers, fluids or records take): often a unit
    mistake.  The message names the field and, where one is likely, the unit mistake."""


#: Most characters of a message shown to the user (the command line's error line, the app's error box).
MESSAGE_LIMIT = 400
_TAIL = 120


def one_line(message, limit: int = MESSAGE_LIMIT) -> str:
    """A message made safe to show: one line, printable, at most ``limit`` characters.

    The one place that makes a message safe, used by the command line's error path and the app's: whitespace runs
    (line breaks too) become one space; characters that are not printable (binary read as text, control
    characters, stray surrogates) are shown as ``\\xNN`` escapes, a run of more than three of them as its count
    only; a message longer than ``limit`` keeps its start (which names the argument, key or line) and its end (which
    says what to do) around a note of what was cut.

    >>> one_line("gap:\\n  must be\\tpositive")
    'gap: must be positive'
    >>> one_line("name: " + "x" * 1000 + " is too long", limit=60)
    'name: xxxxxxxxx [... 988 characters cut ...] xxx is too long'
    >>> one_line("cell 'PK\\x03\\x04\\x14\\x00\\x06': not a number")
    "cell 'PK[5 binary characters]': not a number"
    """
    parts = []
    for shown, run in groupby(str(message), key=lambda c: c.isprintable() or c.isspace()):
        run = "".join(run)
        if shown:
            parts.append(run)
        elif len(run) > 3:
            parts.append(f"[{len(run)} binary characters]")
        else:
            parts.append(run.encode("unicode_escape", "backslashreplace").decode("ascii"))
    return cut(" ".join("".join(parts).split()), limit)


def cut(text: str, limit: int = MESSAGE_LIMIT) -> str:
    """``text`` at most ``limit`` characters: a longer one keeps its start (which names the argument, key or line)
    and its end (which says what to do) around a note of what was cut; the one cutter of messages (the command
    line's and the app's through :func:`one_line`, the API's in :class:`ErdesignError`).

    >>> cut("name: " + "x" * 1000 + " is too long", limit=60)
    'name: xxxxxxxxx [... 988 characters cut ...] xxx is too long'
    """
    if len(text) <= limit:
        return text
    tail = min(_TAIL, limit // 4)
    note = f" [... {len(text) - limit + 40} characters cut ...] "  # 40: room for the note itself
    head = limit - tail - len(note)
    note = f" [... {len(text) - head - tail} characters cut ...] "
    return text[:head].rstrip() + note + text[len(text) - tail :].lstrip()


def did_you_mean(given, options) -> str:
    """``" (did you mean 'gap'?)"`` naming the option closest to ``given`` (a misspelt key, model, effect or
    material), or "" when none is close: the hint a user needs first when a long list of names follows.

    >>> did_you_mean("viscosty", ["viscosity", "yield_stress"])
    " (did you mean 'viscosity'?)"
    >>> did_you_mean("Gap", ["gap", "ducts"]), did_you_mean("colour", ["gap", "ducts"])
    (" (did you mean 'gap'?)", '')
    """
    import difflib

    if not isinstance(given, str) or not given.strip():
        return ""
    options = [str(o) for o in options]
    folded = {o.casefold().replace("-", "_"): o for o in options}
    key = given.strip().casefold().replace("-", "_")
    match = folded.get(key) or next(iter(difflib.get_close_matches(given, options, n=1, cutoff=0.75)), None)
    if match is None:
        close = difflib.get_close_matches(key, list(folded), n=1, cutoff=0.75)
        match = folded[close[0]] if close else None
    return f" (did you mean {match!r}?)" if match is not None and match != given else ""
