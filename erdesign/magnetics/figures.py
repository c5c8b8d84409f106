"""Plotly figures of the magnetic circuit, shared by the report and the app (no physics: they plot a
:class:`~erdesign.magnetics.api.CircuitReport`)."""

from __future__ import annotations

import numpy as np

__all__ = ["coil_curves_figure", "circuit_curves"]


def circuit_curves(damper, points: int = 61, span: float = 1.5):
    """The circuit of a damper with a ``[coil]`` at ``points`` currents from 0 to ``span`` times the rated current
    (:class:`~erdesign.magnetics.api.CircuitReport` of arrays), or None for a damper without a coil."""
    law = damper.fluid.field_law
    circuit = getattr(law, "circuit", None)
    if circuit is None or not hasattr(circuit, "at"):
        return None
    return circuit.at(np.linspace(0.0, span * law.rated_current, points))


def coil_curves_figure(curves, rated_current: float | None = None):
    """Gap flux density B_g(I) and yield stress tau_y(I) against coil current, with the knee and the rated current.

    >>> from erdesign.damper.files import load_example
    >>> d = load_example("mr_coil")
    >>> fig = coil_curves_figure(circuit_curves(d, points=7), 2.0)
    >>> [t.name for t in fig.data]
    ['gap flux density B_g', 'yield stress τ_y']
    """
    from plotly.subplots import make_subplots

    from ..formatting import pick_unit

    tau_unit = pick_unit(curves.yield_stress, "pressure")  # the unit system's (kPa in SI, MPa, psi)
    I = np.asarray(curves.current.m_as("A"), dtype=float)
    B = np.asarray(curves.gap_flux_density.m_as("T"), dtype=float)
    tau = np.asarray(curves.yield_stress.m_as(tau_unit), dtype=float)
    fig = make_subplots(specs=[[{"secondary_y": True}]])
    fig.add_scatter(x=I, y=B, name="gap flux density B_g", mode="lines", secondary_y=False)
    fig.add_scatter(x=I, y=tau, name="yield stress τ_y", mode="lines", line={"dash": "dash"}, secondary_y=True)
    knee = float(curves.knee_current.m_as("A"))
    if np.isfinite(knee) and knee <= I[-1]:
        fig.add_vline(x=knee, line={"dash": "dot", "color": "grey"}, annotation_text=f"knee {knee:.3g} A")
    if rated_current is not None:
        fig.add_vline(
            x=rated_current,
            line={"color": "grey"},
            annotation_text=f"rated {rated_current:.3g} A",
            annotation_position="bottom right",
        )
    fig.update_layout(
        title="Magnetic circuit: gap flux density and yield stress against coil current",
        xaxis_title="coil current I [A]",
        legend={"orientation": "h", "y": -0.2},
        margin={"l": 60, "r": 60, "t": 60, "b": 60},
    )
    fig.update_yaxes(title_text="B_g [T]", rangemode="tozero", secondary_y=False)
    fig.update_yaxes(title_text=f"τ_y [{tau_unit}]", rangemode="tozero", secondary_y=True)
    return fig
