"""The characterization-and-customization method of Vivas-López et al. (n.d.): docs/characterize.md.

* :mod:`~erdesign.characterization.diagrams` - the FD, FV and FM diagrams and their 2D densities;
* :mod:`~erdesign.characterization.split` - the passive / semi-active split (eq 1) and the feature dictionaries;
* :mod:`~erdesign.characterization.detectors` - the characteristics of Table 2, each with its evidence;
* :mod:`~erdesign.characterization.method` - the workflow: characteristics -> model terms -> customized model ->
  identification -> cross-validation against the Eyring-plastic model (:func:`characterize`).

Submodules are imported on use; this package imports nothing.
"""
