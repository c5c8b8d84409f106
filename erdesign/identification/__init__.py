"""Identification: fit the parameters of a model (:mod:`erdesign.models`) to records.

* :mod:`~erdesign.identification.fit` - bounded least squares with uncertainties (:func:`erdesign.fit`);
* :mod:`~erdesign.identification.identify` - identification from measured records: several starts, variable
  projection, joint fits over records, cross-validation, reports, and running a model with given parameters
  (``erdesign identify`` and ``erdesign simulate``);
* :mod:`~erdesign.identification.inverse` - the control that makes a model give a desired force.

Submodules are imported on use; this package imports nothing.
"""
