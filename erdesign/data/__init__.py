"""Records of a damper and what they say: measurement files, other readers, noise floors, figures of merit.

* :mod:`~erdesign.data.measurement` - :class:`~erdesign.data.measurement.Measurement`, measurement CSV files,
  derivatives of the displacement;
* :mod:`~erdesign.data.noise` - displacement, velocity and force noise, and the ESR noise alone would leave;
* :mod:`~erdesign.data.noise_floor` - the noise floor a record supports: the load cell's noise from a still
  segment, repeated cycles or the spectrum above the excited band, and what the motion channel adds;
* :mod:`~erdesign.data.findings` - data-quality findings made before any fit (clipped or saturated channels,
  smoothing, channel skew, time gaps, force drift, quantised displacement);
* :mod:`~erdesign.data.metrics` - energy per cycle, equivalent damping, ESR (used by the damper's design figures
  as well as by identification and diagnosis, hence here and not in :mod:`erdesign.identification`).

Submodules are imported on use (``from erdesign.data.measurement import Measurement``); this package imports
nothing, so that a module that needs one of them does not pay for the others.
"""
