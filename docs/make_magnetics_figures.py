"""Figures and the comparison table of docs/magnetics.md: the reluctance network against the finite-element check.

Run from the repository root: ``python docs/make_magnetics_figures.py``.  Writes PNG images (plotly's static export,
kaleido with the system's Chromium; ``pip install ".[docs]"``) to docs/figures/ and prints the Markdown table.
Needs scikit-fem (``pip install ".[magnetics]"``).
"""

from __future__ import annotations

import sys
import time
from pathlib import Path

import numpy as np
import plotly.graph_objects as go
from scipy.interpolate import griddata

from erdesign.magnetics import load_magnetic_circuit
from erdesign.magnetics.circuit import _curve_knee
from erdesign.magnetics.fem import fem_mesh_lines, solve_fem

ROOT = Path(__file__).resolve().parent.parent
FIGURES = ROOT / "docs" / "figures"
CURRENTS = np.array([0.05, 0.15, 0.3, 0.45, 0.6, 0.8, 1.0, 1.3, 1.7, 2.2, 3.0])
TABLE_CURRENTS = (0.25, 0.5, 1.0, 1.5, 2.0, 3.0)


def save(fig: go.Figure, name: str, width: int = 900, height: int = 480) -> None:
    path = FIGURES / f"{name}.png"
    fig.write_image(path, width=width, height=height, scale=1)
    print(f"wrote {path.relative_to(ROOT)}", file=sys.stderr)


def main() -> None:
    circuit = load_magnetic_circuit(ROOT / "erdesign" / "examples" / "mr_coil.toml")
    t = time.perf_counter()
    fem = solve_fem(circuit.head, circuit.steel, circuit.fluid, CURRENTS)
    t_fem = time.perf_counter() - t
    t = time.perf_counter()
    net = circuit.state(CURRENTS)
    t_net = time.perf_counter() - t
    I0 = np.concatenate([[0.0], CURRENTS])
    k_net = _curve_knee(I0, np.concatenate([[0.0], net.gap_flux_density]))
    k_fem = _curve_knee(I0, np.concatenate([[0.0], fem.gap_flux_density]))
    print(
        f"FE: {fem.nodes} nodes, Newton iterations {fem.newton_iterations}, {t_fem:.1f} s; network {t_net * 1e3:.1f} ms"
    )
    print(f"knee of B_gap(I): network {k_net:.3f} A, FE {k_fem:.3f} A ({k_net / k_fem - 1:+.1%})")

    # table at round currents
    fem_t = solve_fem(circuit.head, circuit.steel, circuit.fluid, TABLE_CURRENTS)
    r = circuit.at(list(TABLE_CURRENTS))
    print(
        "\n| I [A] | B_gap network [T] | B_gap FE [T] | deviation | L network [H] | L FE [H] | deviation |"
        " tau_y [kPa] | L/R [ms] | P [W] | saturated |"
    )
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    for i, I in enumerate(TABLE_CURRENTS):
        Bn, Bf = r.gap_flux_density.magnitude[i], fem_t.gap_flux_density[i]
        Ln, Lf = r.inductance.magnitude[i], fem_t.flux_linkage[i] / I
        print(
            f"| {I:g} | {Bn:.3f} | {Bf:.3f} | {Bn / Bf - 1:+.1%} | {Ln:.3f} | {Lf:.3f} | {Ln / Lf - 1:+.1%} | "
            f"{r.yield_stress.to('kPa').magnitude[i]:.1f} | {r.time_constant.to('ms').magnitude[i]:.0f} | "
            f"{r.power.magnitude[i]:.2f} | {'yes' if r.saturated[i] else 'no'} |"
        )

    # figure 1: B_gap(I)
    dense = np.linspace(0, 3.0, 121)
    fig = go.Figure()
    fig.add_scatter(x=dense, y=circuit.state(dense).gap_flux_density, name="reluctance network", mode="lines")
    fig.add_scatter(
        x=CURRENTS,
        y=fem.gap_flux_density,
        name="finite elements (scikit-fem)",
        mode="markers",
        marker=dict(size=9, symbol="circle-open"),
    )
    for k, label, dash, pos in (
        (k_net, "knee, network", "dash", "bottom right"),
        (k_fem, "knee, FE", "dot", "top left"),
    ):
        fig.add_vline(x=k, line_dash=dash, annotation_text=f"{label} {k:.2f} A", annotation_position=pos)
    fig.update_layout(
        title="Gap flux density of examples/mr_coil.toml against coil current",
        xaxis_title="coil current I [A]",
        yaxis_title="B_gap at the mean gap radius [T]",
        template="plotly_white",
        legend=dict(x=0.55, y=0.2),
    )
    save(fig, "magnetics_bgap")

    # figure 2: field plot at 2 A (|B| and flux lines), half plane z >= 0
    res = solve_fem(circuit.head, circuit.steel, circuit.fluid, [2.0])
    mesh = res.mesh
    _, _, g = fem_mesh_lines(circuit.head)
    rr = np.linspace(0, 1.3 * g["Ro"], 260)
    zz = np.linspace(0, g["z2"] + 1.5 * g["Ro"], 220)
    R, Z = np.meshgrid(rr, zz)
    centroids = mesh.p[:, mesh.t].mean(axis=1).T
    Bgrid = griddata(centroids, res.B_magnitude, (R, Z), method="linear")
    psi = griddata(mesh.p.T, res.psi, (R, Z), method="linear")
    fig = go.Figure()
    fig.add_heatmap(
        x=rr * 1e3, y=zz * 1e3, z=Bgrid, colorscale="Viridis", colorbar=dict(title="|B| [T]"), zmin=0, zmax=2.2
    )
    fig.add_contour(
        x=rr * 1e3,
        y=zz * 1e3,
        z=psi,
        contours_coloring="lines",
        line_width=1,
        showscale=False,
        ncontours=24,
        colorscale=[[0, "white"], [1, "white"]],
        name="flux lines",
    )
    outline = dict(color="red", width=1)
    hd = circuit.head
    for x0, x1, y0, y1 in (
        (0, hd.core_radius, 0, g["z2"]),
        (0, hd.pole_radius, g["z1"], g["z2"]),
        (hd.housing_inner_radius, hd.housing_outer_radius, 0, zz[-1]),
    ):
        fig.add_shape(type="rect", x0=x0 * 1e3, x1=x1 * 1e3, y0=y0 * 1e3, y1=y1 * 1e3, line=outline)
    fig.update_layout(
        title="Finite-element field at 2 A: |B| and flux lines (coil midplane at z = 0; steel outlined)",
        xaxis_title="r [mm]",
        yaxis_title="z [mm]",
        template="plotly_white",
    )
    fig.update_xaxes(range=[0, rr[-1] * 1e3], constrain="domain")
    fig.update_yaxes(range=[0, zz[-1] * 1e3], scaleanchor="x", scaleratio=1, constrain="domain")
    save(fig, "magnetics_field", width=760, height=640)


if __name__ == "__main__":
    main()
