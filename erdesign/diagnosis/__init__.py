"""Diagnosis: calibrate the physics model of a damper to a measurement, see where it fails, rank the effects that
could be missing, add one and refit (:mod:`erdesign.diagnosis.diagnose`; ``erdesign fit`` and
``erdesign diagnose``; docs/diagnosis.md).

Submodules are imported on use; this package imports nothing.
"""
