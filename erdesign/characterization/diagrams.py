r"""The characteristic diagrams of Vivas-López et al. (n.d.): force against displacement (FD), velocity (FV) and
manipulation (FM, the control), as scatter data and as 2D densities (its Fig 5: "the 2D-density plots use blue
to indicate a lower number of occurrences ... red a higher number").

Plain numpy; the figures are drawn by :mod:`erdesign.report.characterization`.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = ["DIAGRAMS", "Density", "density", "diagram_axes"]

#: Diagram name -> (x quantity, its SI unit, title) (Vivas-López et al. section 3).
DIAGRAMS = {
    "FD": ("displacement", "m", "force-displacement"),
    "FV": ("velocity", "m/s", "force-velocity"),
    "FM": ("control", "SI", "force-manipulation"),
}


def diagram_axes(record, diagram: str, force=None) -> tuple[np.ndarray, np.ndarray]:
    """(x, F) of a diagram of ``record``: x its displacement [m], velocity [m/s] or control (SI); F the record's
    force [N] or ``force`` (a model's, or the semi-active part of eq 1)."""
    x = getattr(record, DIAGRAMS[diagram][0])
    return np.asarray(x, dtype=float), np.asarray(record.require_force() if force is None else force, dtype=float)


@dataclass(frozen=True)
class Density:
    """Counts of samples on a grid of (x, F) cells: ``counts[i, j]`` in ``x_edges[i:i+2]`` x ``F_edges[j:j+2]``."""

    counts: np.ndarray
    x_edges: np.ndarray
    F_edges: np.ndarray

    @property
    def fraction(self) -> np.ndarray:
        """Counts over all samples (each density sums to 1), so that two records of different length compare."""
        total = self.counts.sum()
        return self.counts / total if total else self.counts.astype(float)


def density(x, F, *, bins: int = 40, x_range=None, F_range=None) -> Density:
    """The 2D density of the samples (x, F) on ``bins`` x ``bins`` cells over the given ranges (default: the data's),
    so that a measured and a model density drawn on the same ranges compare cell by cell.

    >>> d = density([0.0, 0.0, 1.0], [0.0, 0.0, 1.0], bins=2)
    >>> d.counts.tolist()
    [[2.0, 0.0], [0.0, 1.0]]
    """
    x = np.asarray(x, dtype=float)
    F = np.asarray(F, dtype=float)
    xr = (float(np.min(x)), float(np.max(x))) if x_range is None else x_range
    Fr = (float(np.min(F)), float(np.max(F))) if F_range is None else F_range
    xr = xr if xr[1] > xr[0] else (xr[0] - 0.5, xr[0] + 0.5)
    Fr = Fr if Fr[1] > Fr[0] else (Fr[0] - 0.5, Fr[0] + 0.5)
    counts, xe, Fe = np.histogram2d(x, F, bins=bins, range=[xr, Fr])
    return Density(counts, xe, Fe)
