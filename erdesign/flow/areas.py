"""Areas of an annular damper head: SI kernels shared by the flow laws, the quasi-steady force and
:class:`~erdesign.geometry.Geometry`."""

from __future__ import annotations

import numpy as np

from ._checks import check_flow_args

__all__ = ["piston_area"]


def piston_area(Dp, dr):
    r"""Area that displaces fluid, a piston of diameter ``Dp`` on a through rod of diameter ``dr``.

    .. math:: A_p = \frac{\pi}{4}\left(D_p^2 - d_r^2\right)

    Parameters
    ----------
    Dp, dr : float or array
        Piston (head) and rod diameters, [m].

    Returns
    -------
    float or array
        A_p, [m^2].

    Examples
    --------
    >>> round(piston_area(0.0334, 0.01125) * 1e4, 4)   # cm^2, Makris et al. (1996)
    7.7676
    """
    check_flow_args(Dp=Dp, dr=dr)
    return np.pi / 4.0 * (Dp**2 - dr**2)
