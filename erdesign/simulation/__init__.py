"""Virtual measurements and simulations of a damper in use.

* :mod:`~erdesign.simulation.rig` - motions (sine, stepped sine, control steps, random, earthquake-like) and the
  virtual rig: the physics model driven by a motion, with hidden effects and noise;
* :mod:`~erdesign.simulation.truthrig` - the truth rig: an independent simulator (its own flow laws and time
  stepping) that makes the test records of the diagnosis benchmark;
* :mod:`~erdesign.simulation.vehicle` - a quarter-vehicle suspension with a damper model.

Submodules are imported on use; this package imports nothing.
"""
