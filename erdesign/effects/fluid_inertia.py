r"""Fluid inertia: the slug of fluid accelerated through the ducts.

The fluid in a duct moves :math:`A_p/(n\,\pi d h)` times faster than the piston, so its kinetic energy is that of
a mass

.. math:: m_f = \frac{\rho\,L\,A_p^2}{n\,\pi\,d\,h}

moving with the piston; the force is :math:`F_i = m_f\,a`.  Kamath and Wereley (1997, eq 10) add the same term
(their :math:`R\ddot X`) to the post-yield branch of their damper model.
"""

from __future__ import annotations

import math

import numpy as np

from ..parameters import Parameter
from .base import Effect

__all__ = ["FluidInertia", "slug_mass"]


def slug_mass(rho, L, Ap, d, h, ducts=1):
    r"""Equivalent mass of the fluid slug in the ducts, referred to the piston.

    .. math:: m_f = \frac{\rho L A_p^2}{n \pi d h}

    Parameters
    ----------
    rho : float
        Fluid density, [kg/m^3].
    L : float
        Duct length, [m].
    Ap : float
        Piston area, [m^2].
    d : float
        Mean diameter of the annulus, [m].
    h : float
        Gap, [m].
    ducts : int
        Number of ducts in parallel, n.

    Returns
    -------
    float
        m_f, [kg].

    Notes
    -----
    Kinetic energy of plug flow at the mean duct speed :math:`U = v A_p/(n\pi d h)`; a parabolic profile has 6/5
    of it (momentum-flux factor of laminar slit flow).  The fluid in the chambers moves at the piston speed and
    adds less than :math:`\rho A_p \ell` (tens of grams), which is left out.

    Examples
    --------
    Makris's duct (L = 54.6 mm, d = 14.3 mm, h = 0.8 mm, A_p = 7.77 cm^2) with 1290 kg/m^3:

    >>> round(slug_mass(1290.0, 0.0546, 7.7676e-4, 0.0143, 0.0008), 3)
    1.182

    References
    ----------
    Kamath and Wereley (1997), eq 10 (inertial term R X''); geometry of Makris et al. (1996).
    """
    return rho * L * Ap**2 / (ducts * math.pi * d * h)


class FluidInertia(Effect):
    name = "fluid_inertia"
    title = "Fluid inertia"
    mechanism = (
        "The fluid in the ducts moves A_p/(pi d h) times faster than the piston; accelerating it takes a "
        "force m_f a with m_f = rho L A_p^2 / (n pi d h)."
    )
    signature = (
        "residual in phase with the acceleration (against the displacement for a sine), growing with the "
        "square of the frequency, the same at every field"
    )
    stage = "additive"
    neutral = {"slug_mass": "lower"}
    # the chamber fluid, fittings and the moving parts between load cell and piston add to the duct slug
    plausible_ratio = {"slug_mass": (0.2, 10.0)}
    source = "Kamath and Wereley (1997) eq 10"

    def parameters(self, damper):
        m = self.prior(damper)["slug_mass"]
        return (Parameter("slug_mass", "kg", m, 0.0, 1e4 * max(m, 1e-3), "fluid mass referred to the piston"),)

    def prior(self, damper):
        g = damper.geometry
        return {
            "slug_mass": slug_mass(
                damper.fluid.density, g.duct_length, g.piston_area, g.duct_mean_diameter, g.gap, g.ducts
            )
        }

    def check(self, record, damper):
        if np.ptp(record.acceleration) == 0:
            return "the piston does not accelerate"
        return None

    @staticmethod
    def force(acceleration, slug_mass):
        """F_i = m_f a, [N]."""
        return slug_mass * np.asarray(acceleration, dtype=float)

    def additive_forces(self, record, sign, damper, values):
        return {"inertia": self.force(record.acceleration, values["slug_mass"])}
