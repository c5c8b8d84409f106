"""Studies of measured dampers that use the library end to end, one module per data set.

* :mod:`~erdesign.case_studies.quiroz` - the Quiroz (2022) UTFSM MR damper at five coil currents
  (docs/case_studies/quiroz.md).

Submodules are imported on use; this package imports nothing.
"""
