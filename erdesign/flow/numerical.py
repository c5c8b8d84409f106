r"""Numerical solution of steady, fully developed gap flow of a regularised Bingham fluid (reference solver).

An independent check of the closed forms in :mod:`erdesign.flow.bingham`, :mod:`erdesign.flow.annulus_bingham`
and :mod:`erdesign.flow.mixed_mode`: it discretises the momentum balance across the gap and never calls them.

Problem
-------
The fluid fills the gap between two walls a distance ``h`` apart and moves along them (x, or z in the annulus).
The wall at ``y = 0`` moves with velocity ``U`` (the moving electrode of a mixed-mode damper; ``U = 0`` for the
valve mode), the wall at ``y = h`` is fixed.  In the slit the momentum balance and its solution are

.. math:: \frac{d\tau}{dy} = g, \qquad \tau(y) = \tau_0 + g\,y, \qquad g = \frac{dp}{dx};

in the annulus (``y = r - R_1``, inner wall moving, :math:`R_{1,2} = (d \mp h)/2`)

.. math:: \frac{1}{r}\frac{d(r\tau)}{dr} = g .

The fluid is a Bingham plastic, :math:`du/dy = \operatorname{sgn}(\tau)\max(|\tau| - \tau_y, 0)/\eta`, replaced by
Papanastasiou's regularisation, which is smooth and invertible:

.. math:: \tau = \Big[\eta + \tau_y\,\frac{1 - e^{-m|\dot\gamma|}}{|\dot\gamma|}\Big]\dot\gamma ,
          \qquad \dot\gamma = \frac{du}{dy}.

Sign conventions (shared with :mod:`erdesign.flow.mixed_mode`): ``tau`` is the shear stress :math:`\tau_{xy}`
(positive where the velocity grows with y); ``g = dp/dx`` is negative when the pressure pushes the fluid in +x; the
flow rate is positive in +x.  The fluid drags the moving wall with :math:`\tau(0)` per unit area in +x and the
fixed wall with :math:`-\tau(h)`.

Method
------
* Discretisation: linear finite elements on a grid graded towards both walls (:func:`gap_grid`).  Element ``e``
  carries one shear rate :math:`\dot\gamma_e = (u_{e+1} - u_e)/\Delta y_e` and one stress :math:`\tau_e`, and
  the balance at node ``i`` is :math:`w_e\tau_e - w_{e-1}\tau_{e-1} = g\,b_i` (:math:`w = r/h` at the element
  mid-point in the annulus, 1 in the slit; :math:`b_i` the integral of node i's hat function times w).  In the slit
  this is the finite-volume scheme: the element stresses equal :math:`\tau_0 + g y_e` exactly and the velocity is
  the mid-point-rule integral of the exact shear rate, second-order accurate without resolving the yield
  surfaces.  The flow rate is the exact integral of the piecewise-linear velocity.
* Newton iterations on the nodal velocities *and* the element stresses (a mixed form): the unknowns, interleaved
  :math:`(\tau_0, u_1, \tau_1, u_2, \dots)`, make the Jacobian tridiagonal, solved with
  :func:`scipy.linalg.solve_banded` (its pivoting handles the zero diagonal of the balance rows).  The element
  equations are the inverted law :math:`\dot\gamma_e = \dot\gamma(\tau_e)`, whose slope
  :math:`d\dot\gamma/d\tau = 1/(\eta + \tau_y m e^{-m|\dot\gamma|})` lies in :math:`(0, 1/\eta]`; it is evaluated
  with the Wright omega function (closed form of the inverse) and polished by a few scalar Newton steps.  Each
  step is followed by backtracking on the scaled residual norm.
* For a prescribed flow rate the pressure gradient joins the unknowns with the (linear) flow-rate equation: a
  bordered system, solved with the same banded factorisation (two right-hand sides and a scalar elimination).
* Continuation in the regularisation: :math:`M = m\tau_y/\eta` grows from 0 (Newtonian, linear: one step) to
  ``regularisation`` by factors of 100, each stage starting from the last.
* Many cases are solved together: the systems of all cases are stacked into one banded system.

Departure from the plan of a Newton iteration on the velocities alone: with :math:`M \ge 10^5` and more than about
1600 nodes that iteration stalled (line searches cut its steps to 1e-3), the known difficulty of Newton's method
for the Papanastasiou law at large m, whose tangent viscosity spans :math:`\eta` to :math:`M\eta`.  The mixed form
has the same discrete solution (the law is invertible) and converges in 5 to 10 iterations per stage.

Accuracy (tests/test_flow_numerical.py, defaults ``n = 801``, ``regularisation = 1e8``): pressure gradients within
6e-6 of the closed forms (Newtonian and Bingham, slit and annulus, h/d 0.01 to 0.8, Bingham numbers 0 to 1e4, with
and without a moving wall), plug fractions and edges within 5e-5 of the gap.  The grid error falls like 1/n^2
(1.8e-6 at n = 801); the regularisation error like Bi/M.  One case takes 5 to 15 ms; 50 cases in one call 0.5 s.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from ..errors import ErdesignError

__all__ = ["solve_gap_flow", "GapFlow", "gap_grid", "ConvergenceError"]


_STAGE_DECADES = 2.0  # continuation step in log10(M)


class ConvergenceError(RuntimeError):
    """The Newton iteration of :func:`solve_gap_flow` did not converge."""


class GapFlow(NamedTuple):
    """Result of :func:`solve_gap_flow`.  Scalars have the broadcast shape of the inputs; profiles add a last axis."""

    y: np.ndarray
    """Node positions, distance from the moving wall, [m]; in the annulus ``r = (d - h)/2 + y``."""
    velocity: np.ndarray
    """Axial velocity at the nodes, [m/s]."""
    y_mid: np.ndarray
    """Element mid-points, where the stress is computed, [m]."""
    stress: np.ndarray
    """Shear stress tau at the element mid-points, [Pa]."""
    pressure_gradient: float | np.ndarray
    """dp/dx, [Pa/m] (negative for a pressure that pushes the fluid in +x)."""
    flow_rate: float | np.ndarray
    """Flow rate in +x: per unit width [m^2/s] for the slit, total [m^3/s] for the annulus."""
    wall_stress_moving: float | np.ndarray
    """Shear stress tau at the moving wall, y = 0, [Pa]; the fluid pulls that wall with tau(0) per unit area in +x."""
    wall_stress_fixed: float | np.ndarray
    """Shear stress tau at the fixed wall, y = h, [Pa]; the fluid pulls that wall with -tau(h) per unit area in +x."""
    plug_start: float | np.ndarray
    """Start of the plug (where abs(tau) < tau_y), distance from the moving wall, [m]; NaN without a plug."""
    plug_end: float | np.ndarray
    """End of the plug, [m]; NaN without a plug."""
    plug_fraction: float | np.ndarray
    """Plug thickness over gap, [-]; 0 without a plug, 1 for a blocked gap."""
    regularisation: float
    """Final m * tau_y / eta of the Papanastasiou law, [-]."""
    iterations: int
    """Newton iterations over all continuation stages."""


def gap_grid(n, grading=0.5):
    r"""Node positions across the gap over the gap height, graded towards both walls.

    .. math:: \xi_j = (1 - a)\,s_j + a\,\frac{1 - \cos(\pi s_j)}{2}, \qquad s_j = \frac{j}{n - 1}

    Parameters
    ----------
    n : int
        Number of nodes, >= 3.
    grading : float
        Weight a of the cosine (Chebyshev-like) part, [-], in [0, 1): 0 is uniform; the wall spacing is
        :math:`(1 - a)` times the uniform one and the centre spacing :math:`1 + a(\pi/2 - 1)` times.

    Returns
    -------
    numpy.ndarray
        :math:`\xi` in [0, 1], increasing, [-].

    Examples
    --------
    >>> gap_grid(5, 0.0).tolist()
    [0.0, 0.25, 0.5, 0.75, 1.0]
    """
    if n < 3:
        raise ErdesignError(f"n: need at least 3 nodes, got {n}")
    if not 0.0 <= grading < 1.0:
        raise ErdesignError(f"grading: must be in [0, 1), got {grading}")
    s = np.linspace(0.0, 1.0, n)
    xi = (1.0 - grading) * s + grading * 0.5 * (1.0 - np.cos(np.pi * s))
    xi[0], xi[-1] = 0.0, 1.0
    return xi


class _Discretisation:
    """Grid, element weights and load vector of K stacked cases (arrays of shape (K, n) or (K, n - 1))."""

    def __init__(self, xi, inner_radius):
        # inner_radius: R1/h per case, shape (K,); NaN for the slit (weights 1).
        self.xi = xi
        self.dxi = np.diff(xi)
        slit = np.isnan(inner_radius)
        rho = np.where(slit[:, None], 1.0, inner_radius[:, None] + xi)
        self.rho = rho
        self.w = 0.5 * (rho[:, 1:] + rho[:, :-1])
        b = np.zeros_like(rho)
        b[:, :-1] += self.dxi * (2 * rho[:, :-1] + rho[:, 1:]) / 6.0
        b[:, 1:] += self.dxi * (rho[:, :-1] + 2 * rho[:, 1:]) / 6.0
        self.b = b


def _shear_rate(tau, bi, M):
    """Inverse Papanastasiou law: dimensionless shear rate and compliance d(gamma)/d(tau); bi of shape (K, 1).

    For s = |tau| the shear rate x/k (k = M/Bi) solves x + M(1 - exp(-x)) = k s, i.e.
    x = k(s - Bi) + omega(ln M - k(s - Bi)) with omega the Wright omega function.  That form cancels inside the
    plug (s < Bi), so it only starts Newton steps on the concave, increasing residual, which polish the root to
    rounding from either side; s/(1 + M), a lower bound, starts them in the plug.
    """
    plastic = (bi > 0.0) & (M > 0.0)
    if not np.any(plastic):
        return tau.copy(), np.ones_like(tau)
    bi_p = np.where(plastic, bi, 1.0)
    k = M / bi_p
    s = np.abs(tau)
    excess = s - bi_p
    from scipy.special import wrightomega  # imported here, not at start-up

    gamma = np.maximum(excess + wrightomega(np.log(M) - k * excess) / k, s / (1.0 + M))
    for _ in range(30):  # quadratic convergence: 2 or 3 steps; rounding then leaves relative steps ~1e-14
        f = gamma - bi_p * np.expm1(-k * gamma) - s
        step = f / (1.0 + M * np.exp(-k * gamma))
        gamma = np.maximum(gamma - step, 0.0)
        if np.all(np.abs(step) <= 1e-12 * gamma):
            break
    compliance = 1.0 / (1.0 + M * np.exp(-k * gamma))
    gamma = np.where(plastic, np.sign(tau) * gamma, tau)
    return gamma, np.where(plastic, compliance, 1.0)


def _residuals(u, tau, g, q_target, bi, M, disc):
    """Kinematic (per element, velocity units), balance (per interior node) and flow-rate residuals."""
    gamma, compliance = _shear_rate(tau, bi, M)
    kinematic = np.diff(u, axis=1) - disc.dxi * gamma
    wt = disc.w * tau
    balance = wt[:, 1:] - wt[:, :-1] - g[:, None] * disc.b[:, 1:-1]
    flow = None if q_target is None else np.sum(disc.b * u, axis=1) - q_target
    return kinematic, balance, flow, compliance


def _merit(kinematic, balance, flow, bi):
    out = np.sum(kinematic**2, axis=1) + np.sum((balance / (1.0 + bi)) ** 2, axis=1)
    return out if flow is None else out + flow**2


def _solve_mixed(compliance, disc, rhs):
    """Solve the stacked velocity-stress Newton systems; rhs of shape (K, 2n - 3, m), unknowns interleaved.

    Unknown 2e is the stress of element e, unknown 2i - 1 the velocity of interior node i.  Row 2e is the
    kinematic equation of element e (du_{e+1} - du_e - dxi_e c_e dtau_e), row 2i - 1 the balance at node i
    (w_i dtau_i - w_{i-1} dtau_{i-1}): a tridiagonal matrix with zeros on the balance rows' diagonal, which the
    partial pivoting of the banded LU handles.
    """
    ncase, ne = compliance.shape
    size = 2 * ne - 1
    ab = np.zeros((3, ncase, size))
    ab[1, :, 0::2] = -disc.dxi * compliance
    ab[0, :, 1::2] = 1.0  # row 2e, column 2e + 1 (velocity of node e + 1)
    ab[0, :, 2::2] = disc.w[:, 1:]  # row 2i - 1, column 2i (stress of element i)
    ab[2, :, 1::2] = -1.0  # row 2e, column 2e - 1 (velocity of node e)
    ab[2, :, 0:-1:2] = -disc.w[:, :-1]  # row 2i - 1, column 2i - 2 (stress of element i - 1)
    from scipy.linalg import solve_banded  # imported here, not at start-up

    x = solve_banded((1, 1), ab.reshape(3, -1), rhs.reshape(ncase * size, -1), check_finite=False)
    return x.reshape(rhs.shape)


def _newton(u, tau, g, q_target, bi, M, disc, tol, max_iter):
    """Newton iterations on velocities, stresses (and g) at one regularisation M, with backtracking.

    A case has converged when its kinematic residuals are below ``tol`` times the element's shear increment scale,
    its balance residuals below ``tol`` times the stress scale (and the flow-rate constraint holds to ``tol``).  A
    case whose residual can no longer be decreased or whose update is at the level of rounding stops too; it
    counts as converged if its residuals are within 1000 ``tol``, otherwise ConvergenceError is raised.
    """
    bordered = q_target is not None
    ncase, ne = tau.shape
    eps = np.finfo(float).eps
    b_int = disc.b[:, 1:-1]
    active = np.ones(ncase, dtype=bool)
    stalled = np.zeros(ncase, dtype=bool)

    def relative_residual(u, tau, g, kin, bal, flow):
        """Largest residual over its tolerance scale, per case."""
        gamma_scale = 1.0 + np.max(np.abs(np.diff(u, axis=1)) / disc.dxi, axis=1)
        out = np.max(np.abs(kin) / (disc.dxi * gamma_scale[:, None]), axis=1)
        out = np.maximum(out, np.max(np.abs(bal) / (1.0 + bi + np.abs(g)[:, None]), axis=1))
        if bordered:
            out = np.maximum(out, np.abs(flow) / (np.abs(q_target) + np.sum(disc.b * np.abs(u), axis=1) + 1e-300))
        return out

    kin, bal, flow, compliance = _residuals(u, tau, g, q_target, bi, M, disc)
    for it in range(max_iter + 1):
        size = relative_residual(u, tau, g, kin, bal, flow)
        active &= size > tol
        if not np.any(active & ~stalled) or it == max_iter:
            break
        rhs = np.zeros((ncase, 2 * ne - 1, 2 if bordered else 1))
        rhs[:, 0::2, 0] = -kin
        rhs[:, 1::2, 0] = -bal
        if bordered:
            rhs[:, 1::2, 1] = b_int
        x = _solve_mixed(compliance, disc, rhs)
        dtau = x[:, 0::2, 0]
        du = np.zeros_like(u)
        du[:, 1:-1] = x[:, 1::2, 0]
        if bordered:
            dg = -(flow + np.sum(b_int * du[:, 1:-1], axis=1)) / np.sum(b_int * x[:, 1::2, 1], axis=1)
            du[:, 1:-1] += dg[:, None] * x[:, 1::2, 1]
            dtau = dtau + dg[:, None] * x[:, 0::2, 1]
        else:
            dg = np.zeros(ncase)
        moving = active & ~stalled
        du[~moving], dtau[~moving], dg[~moving] = 0.0, 0.0, 0.0
        # Backtracking on the scaled residual norm (the Newton step is a descent direction for it).
        merit0 = _merit(kin, bal, flow, bi)
        alpha = np.ones(ncase)
        pending = moving.copy()
        for _ in range(40):
            trial = _residuals(
                u + alpha[:, None] * du, tau + alpha[:, None] * dtau, g + alpha * dg, q_target, bi, M, disc
            )
            accept = pending & (_merit(*trial[:3], bi) <= (1.0 - 1e-4 * alpha) * merit0)
            kin[accept], bal[accept], compliance[accept] = trial[0][accept], trial[1][accept], trial[3][accept]
            if bordered:
                flow[accept] = trial[2][accept]
            pending &= ~accept
            if not np.any(pending):
                break
            alpha = np.where(pending, 0.5 * alpha, alpha)
        alpha = np.where(pending, 0.0, alpha)
        u = u + alpha[:, None] * du
        tau = tau + alpha[:, None] * dtau
        g = g + alpha * dg
        # No decrease possible, or an update at the level of rounding: nothing more to gain for that case.
        tiny = (
            (alpha * np.max(np.abs(du), axis=1) <= 4 * eps * np.max(np.abs(u), axis=1))
            & (alpha * np.max(np.abs(dtau), axis=1) <= 4 * eps * np.max(np.abs(tau), axis=1))
            & (alpha * np.abs(dg) <= 4 * eps * np.abs(g))
        )
        stalled |= moving & (pending | tiny)
    failed = active & (size > 1e3 * tol)
    if np.any(failed):
        raise ConvergenceError(
            f"solve_gap_flow: Newton did not converge at m*tau_y/eta = {M:.3g} in {it} iterations "
            f"({np.count_nonzero(failed)} case(s), largest relative residual {np.max(size[failed]):.2g})"
        )
    return u, tau, g, it


def _plug_extent(xi_points, tau, tau_y):
    """Interval of xi where abs(tau) < tau_y for tau piecewise linear through the points; NaN when empty."""
    ta, tb = tau[:, :-1], tau[:, 1:]
    xa, xb = xi_points[:, :-1], xi_points[:, 1:]
    ty = tau_y[:, None]
    dt = tb - ta
    with np.errstate(divide="ignore", invalid="ignore"):
        t1 = (-ty - ta) / dt
        t2 = (ty - ta) / dt
    flat = dt == 0.0
    lo = np.where(flat, np.where(np.abs(ta) < ty, 0.0, 1.0), np.clip(np.minimum(t1, t2), 0.0, 1.0))
    hi = np.where(flat, np.where(np.abs(ta) < ty, 1.0, 0.0), np.clip(np.maximum(t1, t2), 0.0, 1.0))
    inside = hi > lo
    start = np.where(inside, xa + lo * (xb - xa), np.inf).min(axis=1)
    end = np.where(inside, xa + hi * (xb - xa), -np.inf).max(axis=1)
    found = np.isfinite(start)
    return np.where(found, start, np.nan), np.where(found, end, np.nan)


def solve_gap_flow(
    *,
    h,
    tau_y,
    eta,
    pressure_gradient=None,
    flow_rate=None,
    wall_velocity=0.0,
    geometry="slit",
    mean_diameter=None,
    n=801,
    grading=0.5,
    regularisation=1e8,
    tol=1e-10,
):
    r"""Steady, fully developed flow of a Bingham fluid across a gap, solved numerically (finite elements + Newton).

    Solves, for the velocity :math:`u(y)` with :math:`u(0) = U`, :math:`u(h) = 0`,

    .. math::
        \frac{1}{w}\frac{d}{dy}\Big(w\,\big[\eta + \tau_y\tfrac{1 - e^{-m|u'|}}{|u'|}\big]u'\Big) = g ,
        \qquad w = 1 \text{ (slit)}, \quad w = r = R_1 + y \text{ (annulus)},

    with either the pressure gradient :math:`g = dp/dx` prescribed, or the flow rate
    (:math:`q = \int_0^h u\,dy` for the slit, :math:`Q = 2\pi\int_{R_1}^{R_2} u\,r\,dr` for the annulus) and g
    found with it.  See the module notes for the method and sign conventions.

    Parameters
    ----------
    h : float or array
        Gap, [m].
    tau_y : float or array
        Yield stress, [Pa], >= 0.
    eta : float or array
        Plastic viscosity, [Pa s], > 0.
    pressure_gradient : float or array, optional
        dp/dx, [Pa/m]; negative pushes the fluid in +x.  Give this or ``flow_rate``.
    flow_rate : float or array, optional
        Flow rate in +x: per unit width [m^2/s] for ``"slit"``, total [m^3/s] for ``"annulus"``.
    wall_velocity : float or array
        Velocity U of the wall at y = 0 (the inner wall of the annulus) in +x, [m/s].
    geometry : {"slit", "annulus"}
        Plane slit (y in [0, h]) or concentric annulus (r in [(d - h)/2, (d + h)/2]).
    mean_diameter : float or array, optional
        Mean diameter d of the annulus, [m]; required for ``"annulus"``, not accepted for ``"slit"``.
    n : int
        Number of nodes across the gap.  The error falls like 1/n^2.
    grading : float
        Clustering of the nodes towards the walls, see :func:`gap_grid`.
    regularisation : float
        Final :math:`M = m\tau_y/\eta` of the Papanastasiou law, [-].  The relative regularisation error of the
        pressure gradient is below :math:`\mathrm{Bi}/M` (Bi = tau_y h / (eta u_mean); measured 3.6e-4 at
        Bi = 1e4, M = 1e5, and 10 times less at M = 1e6).
    tol : float
        Newton tolerance of the last continuation stage (earlier ones use 1e-6): element shear-rate mismatch relative
        to the largest shear rate, nodal stress imbalance relative to the stress scale :math:`\eta V/h + \tau_y`
        (V the velocity scale, see Notes), flow-rate mismatch relative to the flow rate.

    Returns
    -------
    GapFlow
        Grid, velocity, stresses, pressure gradient, flow rate, wall stresses and plug extent.

    Raises
    ------
    ErdesignError
        Neither or both of ``pressure_gradient`` and ``flow_rate``; unknown geometry; ``mean_diameter`` missing
        (annulus) or given (slit); h >= d.
    ConvergenceError
        Newton did not converge (not observed: Bingham numbers 0 to 1e6, n up to 3201).

    Notes
    -----
    Laminar, steady, fully developed, incompressible, no wall slip, concentric.  The regularised law replaces the
    rigid plug by a very viscous one (viscosity about :math:`M\eta`), so the reported plug is where
    :math:`|\tau| < \tau_y`, found from the piecewise-linear stress (exact in the slit).  With a prescribed flow
    rate and a gap blocked at rest (``q = 0``, ``U = 0``) the pressure gradient is indeterminate in
    :math:`|g| \le 2\tau_y/h`; the solver returns 0.  The velocity scale of the Newton iteration is the largest of
    ``|U|``, the mean velocity and :math:`|g|h^2/(12\eta)`.

    Examples
    --------
    Newtonian slit flow, 1 mm gap: :math:`g = -12\eta q/h^3`:

    >>> r = solve_gap_flow(h=1e-3, tau_y=0.0, eta=1.0, flow_rate=1e-4)
    >>> round(r.pressure_gradient / -1.2e6, 4)
    1.0

    Bingham slit at Bi = 10: the plug fills 0.5073 of the gap (0.50727 in closed form, erdesign.flow.bingham):

    >>> r = solve_gap_flow(h=1e-3, tau_y=1000.0, eta=1.0, flow_rate=1e-4)
    >>> round(r.plug_fraction, 4)
    0.5073

    A sweep is one call; profiles gain a last axis:

    >>> r = solve_gap_flow(h=1e-3, tau_y=[0.0, 100.0, 1000.0], eta=1.0, flow_rate=1e-4, n=201)
    >>> r.velocity.shape, [round(float(p), 3) for p in r.plug_fraction]
    ((3, 201), [0.0, 0.133, 0.507])

    References
    ----------
    Papanastasiou, T. C. (1987), Flows of materials with yield, J. Rheol. 31(5), 385-404 (the regularisation).
    Makris et al. (1996), eq 2 (linear stress across the gap) and eq 5 (the Bingham law).
    Fredrickson and Bird (1958) for the annulus momentum balance.
    """
    if (pressure_gradient is None) == (flow_rate is None):
        raise ErdesignError("solve_gap_flow: give exactly one of pressure_gradient and flow_rate")
    if geometry not in ("slit", "annulus"):
        raise ErdesignError(f"geometry: expected 'slit' or 'annulus', got {geometry!r}")
    if geometry == "annulus" and mean_diameter is None:
        raise ErdesignError("mean_diameter: required for geometry='annulus'")
    if geometry == "slit" and mean_diameter is not None:
        raise ErdesignError("mean_diameter: only for geometry='annulus' (the slit is per unit width)")
    prescribed = pressure_gradient if flow_rate is None else flow_rate
    d = np.nan if mean_diameter is None else mean_diameter
    arrays = np.broadcast_arrays(*(np.asarray(a, dtype=float) for a in (h, tau_y, eta, prescribed, wall_velocity, d)))
    shape = arrays[0].shape
    h, tau_y, eta, prescribed, U, d = (a.ravel() for a in arrays)
    if geometry == "annulus" and np.any(h >= d):
        raise ErdesignError("h: the gap must be smaller than the mean diameter")
    if np.any(h <= 0) or np.any(eta <= 0) or np.any(tau_y < 0):
        raise ErdesignError("h and eta must be positive and tau_y non-negative")
    if not regularisation >= 1.0:
        raise ErdesignError(f"regularisation: m tau_y/eta must be >= 1, got {regularisation}")

    annulus = geometry == "annulus"
    inner_radius = 0.5 * (d / h - 1.0) if annulus else np.full_like(h, np.nan)
    xi = gap_grid(n, grading)
    disc = _Discretisation(xi, inner_radius)
    # Flow-rate unit per case: q = V h sum(b u*) (slit), Q = 2 pi V h^2 sum(b u*) (annulus).
    area = 2 * np.pi * h * h if annulus else h
    if flow_rate is not None:
        mean_velocity = np.abs(prescribed) / (np.pi * d * h if annulus else h)
        V = np.maximum(np.abs(U), mean_velocity)
    else:
        V = np.maximum(np.abs(U), np.abs(prescribed) * h * h / (12.0 * eta))
    V = np.where(V > 0.0, V, 1.0)
    bi = (tau_y * h / (eta * V))[:, None]
    u = np.outer(U / V, 1.0 - xi)
    tau = np.zeros((len(h), n - 1))
    if flow_rate is not None:
        q_target, g = prescribed / (V * area), np.zeros_like(h)
    else:
        q_target, g = None, prescribed * h * h / (eta * V)

    # Continuation: M = 0 (Newtonian, linear: one step), then 1, ... up to `regularisation`, each stage starting
    # from the solution of the last.
    n_stages = int(np.ceil(np.log10(regularisation) / _STAGE_DECADES)) + 1
    stages = [0.0] + list(np.logspace(0.0, np.log10(regularisation), n_stages))
    if not np.any(tau_y > 0):
        stages = [0.0]
    iterations = 0
    for k, M in enumerate(stages):
        final = k == len(stages) - 1
        u, tau, g, its = _newton(u, tau, g, q_target, bi, M, disc, tol if final else max(tol, 1e-6), max_iter=100)
        iterations += its
    M_final = stages[-1]

    # Wall stresses from the balance of the half elements at the walls (the reactions of the Dirichlet nodes).
    wall0 = (disc.w[:, 0] * tau[:, 0] - g * disc.b[:, 0]) / disc.rho[:, 0]
    wall1 = (disc.w[:, -1] * tau[:, -1] + g * disc.b[:, -1]) / disc.rho[:, -1]
    stress_scale = (eta * V / h)[:, None]
    xi_mid = 0.5 * (xi[1:] + xi[:-1])
    points = np.concatenate([[0.0], xi_mid, [1.0]])
    tau_points = np.concatenate([wall0[:, None], tau, wall1[:, None]], axis=1)
    start, end = _plug_extent(np.broadcast_to(points, tau_points.shape), tau_points, (tau_y * h / (eta * V)))
    fraction = np.where(np.isnan(start), 0.0, end - start)

    def scalar(a):
        a = a.reshape(shape)
        return a if a.ndim else float(a)

    def profile(a):
        return a.reshape(shape + a.shape[-1:])

    return GapFlow(
        y=profile(h[:, None] * xi),
        velocity=profile(V[:, None] * u),
        y_mid=profile(h[:, None] * xi_mid),
        stress=profile(stress_scale * tau),
        pressure_gradient=scalar(g * eta * V / (h * h)),
        flow_rate=scalar(V * area * np.sum(disc.b * u, axis=1)),
        wall_stress_moving=scalar(wall0 * stress_scale[:, 0]),
        wall_stress_fixed=scalar(wall1 * stress_scale[:, 0]),
        plug_start=scalar(start * h),
        plug_end=scalar(end * h),
        plug_fraction=scalar(fraction),
        regularisation=float(M_final),
        iterations=int(iterations),
    )
