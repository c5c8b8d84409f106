"""Errors and warnings of erdesign.

Every error raised for bad input is an :class:`ErdesignError` whose message names the argument, the file key or
the line and column at fault, so that the command line can print it as one line and the app can show it in the
page.  They derive from :class:`ValueError` so that callers who do not know erdesign still catch them.
"""

__all__ = [
    "ErdesignError",
    "UnitError",
    "DamperFileError",
    "OutputPathError",
    "PlausibilityWarning",
    "ErdesignWarning",
    "ValidityWarning",
]


class ErdesignError(ValueError):
    """Bad input: the message says which argument, key or line is wrong and what was expected."""


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
