"""Write the thin-gap error table of docs/theory/thin_gap.md from erdesign (so that the numbers cannot drift).

Run ``python docs/theory/make_thin_gap_table.py`` to rewrite the block between the BEGIN/END markers in
thin_gap.md; ``--check`` only compares and exits with 1 when the file is out of date (tests/test_flow_numerical.py
does the same comparison).
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

from erdesign.flow.annulus_bingham import thin_gap_error_bingham
from erdesign.flow.bingham import bingham_slit_flow

__all__ = ["H_OVER_D", "BINGHAM_NUMBERS", "table", "update", "leading_coefficient"]

DOC = Path(__file__).with_name("thin_gap.md")
BEGIN, END = "<!-- BEGIN thin-gap table (make_thin_gap_table.py) -->", "<!-- END thin-gap table -->"

H_OVER_D = (0.01, 0.02, 0.05, 0.0559, 0.1, 0.2, 0.3, 0.5, 0.8)  # 0.0559: Makris's duct (0.8 mm / 14.3 mm)
BINGHAM_NUMBERS = (0.0, 0.1, 1.0, 10.0, 100.0, 1000.0)


def leading_coefficient(plug_fraction):
    """c(phi) in error = c (h/d)^2 + O((h/d)^4), phi the thin-gap plug fraction (docs/theory/thin_gap.md, eq 3)."""
    phi = np.asarray(plug_fraction, dtype=float)
    return (1 - phi) * (12 * phi**3 + 14 * phi**2 + 11 * phi + 8) / (120 * (1 + phi + phi**2))


def table() -> str:
    """The Markdown table: thin-gap error of the pressure drop in percent, rows h/d, columns Bi."""
    eps = np.array(H_OVER_D)[:, None]
    bi = np.array(BINGHAM_NUMBERS)
    err = thin_gap_error_bingham(eps, bi)
    # Thin-gap plug fraction at each Bi (unit mean velocity, gap, viscosity: tau_y = Bi).
    phi = bingham_slit_flow(np.pi, bi, 1.0, 1.0, 1.0, 1.0).plug_fraction
    head = "| h/d | " + " | ".join(f"Bi = {b:g}" for b in bi) + " |"
    rule = "| ---: | " + " | ".join("---:" for _ in bi) + " |"
    rows = [head, rule, "| plug fraction phi (thin gap) | " + " | ".join(f"{p:.4f}" for p in phi) + " |"]
    for e, line in zip(H_OVER_D, err):
        label = f"{e:g}" + (" (Makris)" if e == 0.0559 else "")
        rows.append(f"| {label} | " + " | ".join(f"{100 * v:.3g} %" for v in line) + " |")
    rows.append("| c = lim error/(h/d)^2 | " + " | ".join(f"{c:.5f}" for c in leading_coefficient(phi)) + " |")
    return "\n".join(rows) + "\n"


def update(check: bool = False) -> bool:
    """Rewrite (or, with ``check``, compare) the table block of thin_gap.md; True when it was up to date."""
    text = DOC.read_text()
    head, rest = text.split(BEGIN + "\n", 1)
    old, tail = rest.split(END, 1)
    new = table()
    if check or old == new:
        return old == new
    DOC.write_text(head + BEGIN + "\n" + new + END + tail)
    return False


if __name__ == "__main__":
    if "--check" in sys.argv[1:]:
        sys.exit(0 if update(check=True) else 1)
    print("up to date" if update() else f"rewrote the table in {DOC}")
