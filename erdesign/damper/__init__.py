"""The damper: :class:`Damper` (geometry + fluid + seal friction), its one quasi-steady force kernel, damper files,
the validity checks of a design and the force-velocity curves.

* :mod:`~erdesign.damper.quasi_steady` - the quasi-steady force of a damper, the one place it is written down;
* :mod:`~erdesign.damper.damper` - :class:`Damper`, its pint edge and design figures;
* :mod:`~erdesign.damper.files` - damper files (TOML) and the example dampers;
* :mod:`~erdesign.damper.validity` - the validity checks of a design (laminar flow, thin gap, control range ...);
* :mod:`~erdesign.damper.curves` - force-velocity curves over controls and sine loops, as SI arrays.
"""

from .damper import CRITICAL_REYNOLDS, FLOW_MODELS, Damper, QuasiSteadyState, SineResponse, SizingResult

__all__ = ["Damper", "QuasiSteadyState", "SizingResult", "SineResponse", "CRITICAL_REYNOLDS", "FLOW_MODELS"]
