r"""Design scaling law of the valve damper: the active fluid volume that a force and a dynamic range cost.

For a valve damper in the thin-gap Bingham model (Makris eq 7 with :math:`h^3`), with no seal friction and a
plastic viscosity :math:`\eta` that does not depend on the field, every design that gives the force :math:`F` at
the piston velocity :math:`v` with the dynamic range :math:`D = F/F_0` has the same active fluid volume

.. math::
    V = n\pi d h L = 3\,\frac{\eta}{\tau_y^2}\,F v\,D\,\phi^2, \qquad (1 - \phi)^2 (2 + \phi) = \frac{2}{D},

whatever its gap, length, diameters and number of ducts; :math:`\phi` is the plug fraction at the design point.

Derivation (docs/design.md): with :math:`N = \Delta p_N/\Delta p_y = 6\eta Q/(\pi d h^2 \tau_y)`, the plug fraction
solves :math:`\phi^3 - (3 + 2N)\phi + 2 = 0` and :math:`\Delta p = \Delta p_y/\phi`, so :math:`D = \Delta p/\Delta
p_N = 1/(\phi N)`; eliminating :math:`N` gives the cubic in :math:`\phi` above.  The power :math:`W = F v = \Delta p
\, v A_p` and :math:`L = W h \phi/(2 \tau_y v A_p)` then give :math:`V`.  Since :math:`V` grows with both :math:`F`
and :math:`D`, the designs that meet ``min_force`` and ``min_dynamic_range`` at one point need at least
:math:`V(F_\text{min}, D_\text{min})`: a lower bound that a design search must reach and never beat.

This is the exact thin-gap form of the rule of thumb that the fluid volume scales with the material figure
:math:`\eta/\tau_y^2` (Butz and von Stryk 2002, Table 1 and section 2: MR devices need a comparatively small amount
of fluid
because their :math:`\eta/\tau_y^2` is two to three orders of magnitude below that of ER fluids).
"""

from __future__ import annotations

import numpy as np

__all__ = ["plug_fraction_at_dynamic_range", "valve_minimum_active_volume"]


def plug_fraction_at_dynamic_range(D):
    r"""Plug fraction of valve (slit) Bingham flow whose pressure drop is ``D`` times the Newtonian one.

    .. math::
        (1 - \phi)^2(2 + \phi) = \frac{2}{D} \quad\Longleftrightarrow\quad
        \phi = 2\sin\!\left(\tfrac13\arcsin\frac{D - 1}{D}\right)

    Parameters
    ----------
    D : float or array
        Dynamic range :math:`\Delta p / \Delta p_N` (same viscosity, no friction), [-], >= 1.

    Returns
    -------
    float or array
        Plug fraction in [0, 1): 0 at D = 1 (Newtonian), tending to 1 as D grows (blocked gap); NaN for D < 1.

    Notes
    -----
    The trigonometric root of the depressed cubic :math:`\phi^3 - 3\phi + 2 - 2/D = 0` that lies in [0, 1], in
    the sine form, which keeps full relative precision as :math:`D \to 1` (:math:`\phi \approx \sqrt{2(D-1)/3}`).

    Examples
    --------
    >>> plug_fraction_at_dynamic_range(1.0), round(plug_fraction_at_dynamic_range(2.0), 6)
    (0.0, 0.347296)
    """
    D = np.asarray(D, dtype=float)
    with np.errstate(invalid="ignore", divide="ignore"):
        s = np.where(D >= 1.0, (D - 1.0) / D, np.nan)
        phi = 2.0 * np.sin(np.arcsin(s) / 3.0)
    return float(phi) if phi.ndim == 0 else phi


def valve_minimum_active_volume(force, velocity, dynamic_range, tau_y, eta):
    r"""Active fluid volume of any valve damper that gives ``force`` at ``velocity`` with ``dynamic_range``.

    .. math:: V = 3\,\frac{\eta}{\tau_y^2}\,F\,v\,D\,\phi(D)^2

    Parameters
    ----------
    force : float or array
        Force at the design point, [N] (no seal friction).
    velocity : float or array
        Piston velocity, [m/s].
    dynamic_range : float or array
        F / F(zero field), [-], >= 1.
    tau_y : float or array
        Yield stress at the field, [Pa].
    eta : float or array
        Plastic viscosity, [Pa s], the same at the field and at zero field.

    Returns
    -------
    float or array
        Volume between the electrodes, :math:`n\pi d h L`, [m^3]; the least volume of the designs that meet
        ``force`` and ``dynamic_range`` (V grows with both).

    Notes
    -----
    Thin-gap valve (Makris eq 7 with :math:`h^3`), laminar, no seal friction, viscosity independent of the field.
    Envelope limits, bounds and other constraints can only raise the volume a search finds.

    Examples
    --------
    Makris's duct with a field-independent viscosity of 13 Pa s and no friction: the formula returns the
    duct's own volume :math:`\pi d h L`.

    >>> from math import pi
    >>> from erdesign.design.evaluate import valve_point_figures
    >>> Ap = pi / 4 * (0.0334**2 - 0.01125**2)
    >>> r = valve_point_figures(0.0254, 1800.0, 13.0, 13.0, 1290.0, 0.0, 0.0008, 0.0546, 0.0143, Ap, 1)
    >>> V = valve_minimum_active_volume(r.force, 0.0254, r.force / r.zero_field_force, 1800.0, 13.0)
    >>> round(V * 1e6, 4), round(pi * 0.0143 * 0.0008 * 0.0546 * 1e6, 4)      # cm^3
    (1.9623, 1.9623)

    References
    ----------
    Makris et al. (1996), eqs 4 and 7 (corrected); Butz and von Stryk (2002), Table 1 (the figure eta / tau_y^2);
    derivation in docs/design.md.
    """
    phi = plug_fraction_at_dynamic_range(dynamic_range)
    return 3.0 * eta / tau_y**2 * force * velocity * dynamic_range * phi**2
