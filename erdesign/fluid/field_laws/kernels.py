r"""The field-law kernels: yield stress [Pa] as a plain function of the control (SI floats or arrays).

See :mod:`erdesign.fluid.field_laws` for the laws and where each holds.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from ..._util import scalar_or_array
from ...errors import UnitError
from ...units import parse_quantity, ureg

__all__ = [
    "power_law_yield_stress",
    "saturating_yield_stress",
    "carlson_yield_stress",
    "CARLSON_STRESS_COEFFICIENT",
    "CARLSON_VOLUME_EXPONENT",
    "CARLSON_FIELD_COEFFICIENT",
    "control_unit_of",
    "CONTROL_SI",
]

#: Constants of Carlson's yield-stress law for LORD MR fluids (:func:`carlson_yield_stress`): stress coefficient
#: [Pa], exponent of the iron volume fraction [-], field coefficient [m/A].
CARLSON_STRESS_COEFFICIENT = 271700.0
CARLSON_VOLUME_EXPONENT = 1.5239
CARLSON_FIELD_COEFFICIENT = 6.33e-6

#: SI unit of each kind of control (the same table as erdesign.fluid.CONTROL_UNITS, which imports this package).
CONTROL_SI = ("V/m", "A/m", "T", "A", "V")


def control_unit_of(value: Any, name: str) -> str:
    """SI unit (``"V/m"``, ``"A/m"``, ``"T"``, ``"A"`` or ``"V"``) of a control given as a quantity or string."""
    q = parse_quantity(value, name) if isinstance(value, str) else value
    dim = getattr(q, "dimensionality", None)
    for unit in CONTROL_SI:
        if dim == ureg.Unit(unit).dimensionality:
            return unit
    raise UnitError(
        f"{name}: expected an electric field (V/m), a magnetic field (A/m, T), a current (A) or a "
        f"voltage (V) with its unit, got {value!r}"
    )


def power_law_yield_stress(E, tau_ref, E_ref, n):
    r"""Yield stress of the power law of the field.

    .. math:: \tau_y = \tau_\text{ref}\left(\frac{|E|}{E_\text{ref}}\right)^n

    Parameters
    ----------
    E : float or array
        Control (field, current or voltage), SI unit of its kind (V/m, A/m, T, A or V).
    tau_ref : float or array
        Yield stress at the reference control, [Pa].
    E_ref : float or array
        Reference control, same unit as ``E``; > 0.
    n : float or array
        Exponent, [-]; > 0.

    Returns
    -------
    float or array
        Yield stress, [Pa].

    Notes
    -----
    Butz and von Stryk (2002, section 2) reports n from 1.2 to 2.5 for ER fluids; Kamath and Wereley (1997,
    section I) call the ER law nominally quadratic.  The law does not saturate: for MR fluids use it only inside the
    range it was fitted on (:func:`fit_power_law`).

    Examples
    --------
    >>> power_law_yield_stress(E=1.5e6, tau_ref=1800.0, E_ref=3e6, n=2.0)   # Makris fluid at half field
    450.0

    References
    ----------
    Butz and von Stryk (2002), section 2: tau_y ~ E^n, n = 1.2 to 2.5.
    """
    return scalar_or_array(tau_ref * (np.abs(E) / E_ref) ** n)


def saturating_yield_stress(E, tau_sat, E_sat):
    r"""Yield stress of the saturating (hyperbolic-tangent) law of the field.

    .. math:: \tau_y = \tau_\text{sat}\tanh\frac{|E|}{E_\text{sat}}

    Parameters
    ----------
    E : float or array
        Control, SI unit of its kind (A/m for a magnetic field).
    tau_sat : float or array
        Saturation yield stress, [Pa].
    E_sat : float or array
        Saturation scale of the control, same unit as ``E``: the slope at zero field is ``tau_sat / E_sat``.

    Returns
    -------
    float or array
        Yield stress, [Pa].

    Notes
    -----
    Linear at small field (:math:`\tau_y \approx \tau_\text{sat}|E|/E_\text{sat}`), within 1 % of saturation
    above :math:`2.65\,E_\text{sat}`.  The linear start is the form of Carlson's law; measured MR curves start
    somewhat more steeply than linearly, so tabulate a datasheet curve (:class:`TabulatedLaw`) when the low-field
    part matters.

    Examples
    --------
    >>> round(saturating_yield_stress(E=158e3, tau_sat=47.9e3, E_sat=158e3))   # tanh(1) of saturation
    36480

    References
    ----------
    Carlson, "MR fluids and devices in the real world", Int. J. Mod. Phys. B 19 (2005) 1463-1470: the tanh form
    of the yield stress of LORD MR fluids.
    """
    return scalar_or_array(tau_sat * np.tanh(np.abs(E) / E_sat))


def carlson_yield_stress(H, phi, carrier_factor=1.0):
    r"""Carlson's yield stress of an MR fluid of iron volume fraction ``phi`` in a magnetic field ``H``.

    .. math:: \tau_y = C \cdot 271700\,\phi^{1.5239}\tanh\left(6.33\times 10^{-6}\,|H|\right)

    Parameters
    ----------
    H : float or array
        Magnetic field strength, [A/m].
    phi : float or array
        Volume fraction of iron, [-]; LORD name their hydrocarbon fluids by it (MRF-132DG: 0.32).
    carrier_factor : float or array
        C, [-]: 1.0 for hydrocarbon carriers, 1.16 for water, 0.95 for silicone oil (Carlson 2005).

    Returns
    -------
    float or array
        Yield stress, [Pa].

    Notes
    -----
    The law is quoted in several places with "kPa" beside it; with the constants above the result is in **Pa**
    (for phi = 0.32 it saturates at 47.9 kPa, the level of the MRF-132DG datasheet curve; read in kPa it would be
    48 MPa).  erdesign reads it in Pa.  It is a fit for LORD's fluids up to magnetic saturation of the iron; it is a
    saturating law (:func:`saturating_yield_stress`) with :math:`\tau_\text{sat} = C\,271700\,\phi^{1.5239}` and
    :math:`E_\text{sat} = 1/(6.33\times10^{-6})` = 158 kA/m.

    Examples
    --------
    >>> round(carlson_yield_stress(H=1e9, phi=0.32))   # saturation of an MRF-132DG-like fluid, Pa
    47862

    References
    ----------
    Carlson, "MR fluids and devices in the real world", Int. J. Mod. Phys. B 19 (2005) 1463-1470.
    """
    tau_sat = carrier_factor * CARLSON_STRESS_COEFFICIENT * np.asarray(phi, dtype=float) ** CARLSON_VOLUME_EXPONENT
    return saturating_yield_stress(H, tau_sat, 1.0 / CARLSON_FIELD_COEFFICIENT)
