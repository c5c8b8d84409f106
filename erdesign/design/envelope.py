r"""Envelope model of a damper: outer diameter, body length and fluid volumes from the geometry (SI kernels).

The requirements file limits the *envelope* (``max_outer_diameter``, ``max_length``) while the flow kernels need
the *duct* geometry; this module is the bridge, with the assumptions written down.  Symbols as in
docs/glossary.md: gap ``h``, duct length ``L``, mean diameter ``d``, piston diameter ``Dp``, rod ``dr``, ``n``
ducts; envelope parameters: stroke ``s``, wall allowance ``t_w``, head length ``L_h`` (valve), end allowance
``L_e`` (each end cap with its seal and bearing).

Valve damper (Makris et al. 1996, Fig 1): a double-ended piston of diameter Dp (the bore) moves in the main
cylinder and pushes the fluid through ``n`` stationary annular ducts.  In Makris's damper the duct is an external
bypass tube that runs beside the cylinder from one end to the other (``duct_placement = "beside"``); the duct is
then outside the cylinder's diameter and must fit along its length.  The alternative (``"around"``) is one
concentric annulus outside the cylinder tube, whose inner electrode is the tube itself.

.. math::
    D_\text{out} = \begin{cases} D_p + 2t_w & \text{valve, ducts beside}\\
                                 d + h + 2t_w & \text{valve, duct around (needs } d - h \ge D_p + 2t_w)\\
                                 D_p + 2h + 2t_w & \text{mixed (bore } D_p + 2h) \end{cases}

.. math::
    \ell = \begin{cases} \max(s + L_h,\; L) + 2L_e & \text{valve}\\ s + L + 2L_e & \text{mixed} \end{cases}

The body length :math:`\ell` is the cylinder with its end caps; the rod ends (a double-ended rod sticks out by up
to the stroke at each end) and the mounting eyes are not included.  The defaults (:class:`~erdesign.design.
requirements.Envelope`) are a 5 mm wall (hoop stress :math:`p D/(2 t_w)` = 100 MPa at 20 MPa in a 50 mm bore),
a 20 mm piston head, 25 mm per end and a 50 mm stroke.
"""

from __future__ import annotations

import numpy as np

__all__ = ["outer_diameter", "body_length", "active_fluid_volume", "total_fluid_volume", "duct_clearance_ratio"]


def outer_diameter(Dp, h, d, wall, configuration, duct_placement="beside"):
    r"""Outer diameter of the damper body, [m].

    .. math:: D_\text{out} = D_p + 2t_w \;(\text{valve, beside}),\quad d + h + 2t_w \;(\text{valve, around}),
              \quad D_p + 2h + 2t_w \;(\text{mixed})

    Parameters
    ----------
    Dp : float or array
        Piston (bore) diameter, [m]; mixed: the head (inner electrode) diameter.
    h : float or array
        Gap, [m].
    d : float or array
        Mean diameter of the duct annulus, [m] (used for ``duct_placement = "around"`` only).
    wall : float
        Wall allowance of the cylinder and of an outer duct tube, [m].
    configuration : str
        ``"valve"`` or ``"mixed"``.
    duct_placement : str
        Valve only: ``"beside"`` (Makris Fig 1) or ``"around"`` the cylinder.

    Returns
    -------
    float or array
        Outer diameter, [m].

    Notes
    -----
    The wall allowance stands for the tube wall; it is not sized from the pressure here (check the hoop stress
    :math:`\Delta p\,D/(2t_w)` of the design's pressure drop against the tube material).  Ducts placed beside the
    cylinder do not count in the diameter, as in docs/file_formats.md ("piston diameter + 2 x wall allowance").

    Examples
    --------
    >>> round(outer_diameter(0.0334, 0.0008, 0.0143, 0.005, "valve") * 1e3, 2)   # Makris bore + 2 x 5 mm
    43.4

    References
    ----------
    Makris et al. (1996), Fig 1 (main cylinder with an external bypass); Kamath and Wereley (1997),
    section II (mixed mode: the head moves in the cylinder bore with the gap h around it).
    """
    if configuration == "mixed":
        return Dp + 2.0 * h + 2.0 * wall
    if duct_placement == "around":
        return np.maximum(Dp + 2.0 * wall, d + h + 2.0 * wall)
    return Dp + 2.0 * wall + 0.0 * h


def body_length(L, stroke, head_length, end_allowance, configuration):
    r"""Body length of the damper: the cylinder with its end caps, [m].

    .. math:: \ell = \max(s + L_h,\, L) + 2L_e \;(\text{valve}), \qquad \ell = s + L + 2L_e \;(\text{mixed})

    Parameters
    ----------
    L : float or array
        Duct length (mixed: length of the piston head, which is the electrode), [m].
    stroke : float
        Full stroke s, [m].
    head_length : float
        Length of the valve piston head, [m]; not used for mixed (the head length is L).
    end_allowance : float
        Length of each end cap with seal and bearing, [m].
    configuration : str
        ``"valve"`` or ``"mixed"``.

    Returns
    -------
    float or array
        Body length, [m]; rod ends and mounting eyes not included.

    Notes
    -----
    Valve: the bore must hold the stroke plus the head; the duct runs along the cylinder between ports at its two
    ends (Makris Fig 1), so a duct longer than the bore lengthens the body.

    Examples
    --------
    >>> round(body_length(0.0546, 0.05, 0.02, 0.025, "valve") * 1e3, 1)   # max(70, 54.6) + 50
    120.0
    """
    L = np.asarray(L, dtype=float)
    if configuration == "mixed":
        out = stroke + L + 2.0 * end_allowance
    else:
        out = np.maximum(stroke + head_length, L) + 2.0 * end_allowance
    return out if out.ndim else float(out)


def active_fluid_volume(h, L, d, n):
    r"""Volume of fluid between the electrodes (the controlled, "active" volume), [m^3].

    .. math:: V = n\,\pi\,d\,h\,L

    Parameters
    ----------
    h, L, d : float or array
        Gap, duct length, mean diameter, [m].
    n : int or array
        Number of ducts.

    Returns
    -------
    float or array
        Active volume, [m^3]; the same as :attr:`erdesign.geometry.Geometry.active_fluid_volume`.

    Examples
    --------
    >>> round(active_fluid_volume(0.0008, 0.0546, 0.0143, 1) * 1e6, 3)   # Makris duct, cm^3
    1.962
    """
    return n * np.pi * d * h * L


def total_fluid_volume(Ap, h, L, d, n, stroke, configuration):
    r"""Fluid the damper holds, without ports and dead volume, [m^3].

    .. math:: V_\text{tot} = A_p s + n\pi d h L \;(\text{valve}), \qquad
              V_\text{tot} = A_p s + \pi d h (L + s) \;(\text{mixed})

    Parameters
    ----------
    Ap : float or array
        Piston area :math:`\frac{\pi}{4}(D_p^2 - d_r^2)`, [m^2].
    h, L, d : float or array
        Gap, duct (mixed: head) length, mean diameter, [m].
    n : int or array
        Number of ducts.
    stroke : float
        Full stroke, [m].
    configuration : str
        ``"valve"`` or ``"mixed"``.

    Returns
    -------
    float or array
        Volume, [m^3].

    Notes
    -----
    Double-ended rod: the two chambers together hold :math:`A_p` times the free bore length, which is the stroke
    (the head fills the rest).  Mixed: the bore is :math:`D_p + 2h`, whose annulus beyond the head adds
    :math:`\pi d h` per unit of stroke.
    """
    if configuration == "mixed":
        return Ap * stroke + np.pi * d * h * (L + stroke)
    return Ap * stroke + active_fluid_volume(h, L, d, n)


def duct_clearance_ratio(Dp, h, d, wall):
    r"""Inner diameter of a duct placed around the cylinder over the cylinder's outer diameter, [-].

    .. math:: \frac{d - h}{D_p + 2t_w} \ge 1

    Below 1 the annulus would cut into the cylinder wall (``duct_placement = "around"`` only).
    """
    return (d - h) / (Dp + 2.0 * wall)
