"""Time-domain stress laws of the fluid (SI kernels): the Makris elastic-viscoplastic law and its limits.

* :func:`makris_stress` - Makris et al. eq 8 for any sampled strain history (exact step, vectorised scan).
* :func:`maxwell_stress` - its a -> 0 limit, the Maxwell model (eq 13).
* :func:`elastic_plastic_stress` - its a -> infinity limit, rate-independent elastic-plastic loops.
* :func:`integration_factor_exponent` - the integrating-factor exponent of eq 11 (all three cases of a).

The unit-aware versions are in the top-level ``erdesign`` namespace.
"""

from .makris import elastic_plastic_stress, integration_factor_exponent, makris_stress, maxwell_stress

__all__ = ["elastic_plastic_stress", "integration_factor_exponent", "makris_stress", "maxwell_stress"]
