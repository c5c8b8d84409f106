r"""Independent check of the reluctance network: axisymmetric nonlinear magnetostatic finite elements (scikit-fem).

The same head (:class:`~erdesign.magnetics.circuit.PistonHead`), steel and fluid are solved for the flux function
:math:`\psi = r A_\varphi` on the half plane :math:`z \ge 0` (the head is symmetric about the coil's midplane):

.. math::
    \int_\Omega \frac{\nu(|B|)}{r}\,\nabla\psi\cdot\nabla v\,dr\,dz = \int_\Omega J_\varphi\,v\,dr\,dz,
    \qquad B_r = -\frac{1}{r}\frac{\partial\psi}{\partial z},\; B_z = \frac{1}{r}\frac{\partial\psi}{\partial r},

the weak form of :math:`\nabla\times(\nu\nabla\times A) = J` in cylindrical coordinates (stationary point of the
magnetic co-energy; e.g. Meeker, FEMM 4.2 manual, section on axisymmetric problems, which uses the same
:math:`rA` potential), with :math:`\nu = H(B)/B` of each material and :math:`J_\varphi = NI/((R_p - r_c)L_c)` in the
winding.  Boundary conditions: :math:`\psi = 0` on the axis, on the far radius and on the far end (no flux leaves
the domain); :math:`\partial\psi/\partial z = 0` on the midplane (by symmetry :math:`B_r = 0` there).  P1 triangles on
a tensor mesh whose lines follow every material interface; Newton's method with the exact Jacobian of the
nonlinear reluctivity (the term in :math:`d\nu/dB^2`), with current continuation from the previous solution.

Geometry beyond the network's: the fluid fills the chamber beyond the head (r < R_i, so flux also leaks through the
fluid around the pole ends), the housing runs to the end of the domain, air outside the housing; the piston rod is
left out (non-magnetic).

Measured quantities: the gap flux density as the mean radial flux density over the pole face at the mean gap
radius, :math:`\bar B_g = (\psi(r_m, z_1) - \psi(r_m, z_2))/(r_m L_p)`; the flux linkage
:math:`\lambda = (N/A_w)\int_\text{coil} 2\pi\psi\,dr\,dz`.

Requires scikit-fem (``pip install erdesign[magnetics]``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import ErdesignError
from .bh import MU0, BHCurve
from .circuit import PistonHead

__all__ = ["FemResult", "solve_fem", "fem_mesh_lines"]

_STEEL, _FLUID, _AIR = 0, 1, 2  # material codes (coil and air: mu0)


@dataclass(frozen=True)
class FemResult:
    """Finite-element solution at an array of currents (SI)."""

    current: np.ndarray  #: I, [A]
    gap_flux_density: np.ndarray  #: mean B_r over the pole face at the mean gap radius, [T]
    flux_linkage: np.ndarray  #: lambda, [Wb]
    max_core_flux_density: np.ndarray  #: |B| at the core's axis at the midplane, [T]
    nodes: int  #: number of mesh nodes
    newton_iterations: tuple  #: per current
    psi: np.ndarray  #: flux function at the nodes of the last current, [Wb/rad]
    mesh: object  #: the skfem mesh
    B_magnitude: np.ndarray  #: |B| per element of the last current, [T]


def _segment(a: float, b: float, n: int) -> np.ndarray:
    return np.linspace(a, b, max(int(n), 1) + 1)


def fem_mesh_lines(head: PistonHead, refine: float = 1.0) -> tuple[np.ndarray, np.ndarray, dict]:
    """Grid lines (r, z) of the tensor mesh, following every interface; ``refine`` scales the element counts."""
    h = head
    rc, Rp, Ri, Ro = h.core_radius, h.pole_radius, h.housing_inner_radius, h.housing_outer_radius
    rm = h.mean_gap_radius
    z1 = 0.5 * h.coil_length
    z2 = z1 + h.pole_length
    R_dom = 3.0 * Ro
    Z_dom = z2 + 3.0 * Ro
    k = refine
    el = 0.5e-3 / k  # target element size in the head, [m]
    ng = max(2, int(round(3 * k)))  # elements across half the gap
    r = np.unique(
        np.concatenate(
            [
                _segment(0, rc, math.ceil(rc / el)),
                _segment(rc, Rp, math.ceil((Rp - rc) / el)),
                _segment(Rp, rm, ng),
                _segment(rm, Ri, ng),
                _segment(Ri, Ro, math.ceil((Ro - Ri) / el)),
                Ro + (R_dom - Ro) * (np.geomspace(1, 31, max(4, int(12 * k))) - 1) / 30,
            ]
        )
    )
    z = np.unique(
        np.concatenate(
            [
                _segment(0, z1, math.ceil(z1 / el)),
                _segment(z1, z2, math.ceil(h.pole_length / el)),
                z2 + (Z_dom - z2) * (np.geomspace(1, 61, max(6, int(24 * k))) - 1) / 60,
            ]
        )
    )
    return r, z, dict(rc=rc, Rp=Rp, Ri=Ri, Ro=Ro, rm=rm, z1=z1, z2=z2, R_dom=R_dom, Z_dom=Z_dom)


def solve_fem(
    head: PistonHead,
    steel: BHCurve,
    fluid: BHCurve,
    currents,
    *,
    refine: float = 1.0,
    tol: float = 1e-9,
    max_newton: int = 60,
) -> FemResult:
    """Solve the head at each current (increasing order is fastest: each solve starts from the previous one).

    ``refine`` scales the mesh (1: 0.5 mm elements in the head, 3 elements across each half of the gap).
    """
    try:
        from skfem import Basis, BilinearForm, ElementTriP1, Functional, LinearForm, MeshTri, asm, condense, solve
        from skfem.helpers import dot, grad
    except ImportError as exc:  # pragma: no cover - depends on the environment
        raise ErdesignError("the finite-element check needs scikit-fem: pip install 'erdesign[magnetics]'") from exc

    r_lines, z_lines, g = fem_mesh_lines(head, refine)
    mesh = MeshTri.init_tensor(r_lines, z_lines)
    basis = Basis(mesh, ElementTriP1(), intorder=3)
    # materials by element centroid
    cr, cz = mesh.p[:, mesh.t].mean(axis=1)
    eps = 1e-12
    core = (cr < g["rc"]) & (cz < g["z2"])
    pole = (cr < g["Rp"]) & (cz > g["z1"]) & (cz < g["z2"])
    housing = (cr > g["Ri"]) & (cr < g["Ro"])
    coil = (cr > g["rc"]) & (cr < g["Rp"]) & (cz < g["z1"])
    fluid_gap = (cr > g["Rp"] - eps) & (cr < g["Ri"])
    chamber = (cr < g["Ri"]) & (cz > g["z2"])
    mat = np.full(mesh.t.shape[1], _AIR)
    mat[fluid_gap | chamber] = _FLUID
    mat[core | pole | housing] = _STEEL
    J_el = np.where(coil, 1.0, 0.0)  # per unit current density

    nqp = basis.X.shape[1]
    matq = np.repeat(mat[:, None], nqp, axis=1)
    Jq = np.repeat(J_el[:, None], nqp, axis=1)
    coilq = Jq.copy()

    def materials_at(Bmag):
        nu = np.full(Bmag.shape, 1.0 / MU0)
        dnu = np.zeros(Bmag.shape)
        for code, curve in ((_STEEL, steel), (_FLUID, fluid)):
            m = matq == code
            nu[m] = curve.reluctivity(Bmag[m])
            dnu[m] = curve.reluctivity_derivative(Bmag[m])
        return nu, dnu

    @BilinearForm
    def jacobian(u, v, w):
        r = w.x[0]
        gp = w["psi"].grad
        return w["nu"] / r * dot(grad(u), grad(v)) + 2.0 * w["dnu"] / r**3 * dot(gp, grad(u)) * dot(gp, grad(v))

    @LinearForm
    def residual(v, w):
        r = w.x[0]
        return w["nu"] / r * dot(w["psi"].grad, grad(v)) - w["J"] * v

    @Functional
    def coil_integral(w):
        return w["psi"] * w["coil"]

    dofs = basis.get_dofs(
        lambda x: (np.isclose(x[0], 0.0)) | np.isclose(x[0], g["R_dom"]) | np.isclose(x[1], g["Z_dom"])
    )
    D = dofs.all() if hasattr(dofs, "all") else dofs
    psi = basis.zeros()
    A_w = head.window_area
    currents = np.atleast_1d(np.asarray(currents, dtype=float))
    Bg, lam, Bcore, iters = [], [], [], []
    # node indices for the gap flux
    pts = mesh.p
    i1 = int(np.argmin((pts[0] - g["rm"]) ** 2 + (pts[1] - g["z1"]) ** 2))
    i2 = int(np.argmin((pts[0] - g["rm"]) ** 2 + (pts[1] - g["z2"]) ** 2))
    Bmag = None
    rq = _qp_r(basis)
    for I in currents:
        J = head.turns * I / A_w
        for it in range(max_newton):
            pi = basis.interpolate(psi)
            gr = pi.grad
            Bmag = np.sqrt(gr[0] ** 2 + gr[1] ** 2) / rq
            nu, dnu = materials_at(Bmag)
            K = asm(jacobian, basis, psi=pi, nu=nu, dnu=dnu)
            F = asm(residual, basis, psi=pi, nu=nu, J=Jq * J)
            dpsi = solve(*condense(K, -F, D=D))
            psi = psi + dpsi
            if np.linalg.norm(dpsi) <= tol * max(np.linalg.norm(psi), 1e-30):
                break
        else:
            raise ErdesignError(f"finite-element check: Newton did not converge at I = {I:g} A")
        iters.append(it + 1)
        Bg.append(abs(psi[i1] - psi[i2]) / (g["rm"] * head.pole_length))
        integral = coil_integral.assemble(basis, psi=basis.interpolate(psi), coil=coilq)
        lam.append(abs(head.turns / A_w * 2.0 * 2.0 * math.pi * integral))
        pi = basis.interpolate(psi)
        Bq = np.sqrt(pi.grad[0] ** 2 + pi.grad[1] ** 2) / rq
        Bcore.append(
            float(np.max(Bq[core & (cz < 0.25 * g["z1"])])) if np.any(core & (cz < 0.25 * g["z1"])) else float("nan")
        )
        Bmag = Bq
    return FemResult(
        current=currents,
        gap_flux_density=np.array(Bg),
        flux_linkage=np.array(lam),
        max_core_flux_density=np.array(Bcore),
        nodes=mesh.p.shape[1],
        newton_iterations=tuple(iters),
        psi=psi,
        mesh=mesh,
        B_magnitude=Bmag.mean(axis=1),
    )


def _qp_r(basis) -> np.ndarray:
    """Radius r at the quadrature points, shape (elements, points)."""
    return basis.mapping.F(basis.X)[0]
