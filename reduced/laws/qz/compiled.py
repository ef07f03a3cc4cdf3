"""The hysteretic q–z spring (kind ``QZ``): a foundation spring of the QzSimple class, as pure
compiled functions of its parameters (a record of :data:`upliftlab.reduced.laws.SPRING_DTYPE`,
its own fields :data:`upliftlab.reduced.laws.qz.COLUMNS`), its committed history (a record of
``HISTORY_DTYPE``, its own fields ``HISTORY``) and a trial compression.

The law (after Boulanger et al. 1999, "Seismic soil–pile–structure interaction experiments and
analyses", J. Geotech. Geoenviron. Eng. 125(9), and the q–z material QzSimple1/QzSimple2 of
OpenSees that implements it; written anew here). Compression z (length, positive into the
soil, measured from the unloaded surface) and force Q (force, positive in compression) of three
parts in series, each carrying Q:

- *elastic (far field)*: z_e = Q/k, k the spring's initial stiffness (force/length). Its
  energy Q²/(2k) is the spring's only stored energy.
- *near field, rigid–plastic*: rigid while Q stays inside an elastic range [q_l, q_r] of width
  w; beyond it the plastic displacement z_p follows a hyperbola towards the capacity q_ult:

      loading past q_r:   Q = q_ult − (q_ult − q_r) · (z_ref / (z_ref + z_p − z_in))^n
      unloading past q_l: Q = −q_ult + (q_ult + q_l) · (z_ref / (z_ref + z_in − z_p))^n

  z_in the plastic displacement at the range (length), z_ref (length) and n (> 1) the shape.
  A reversal from a yielding state starts a new range at that state, as wide as the last
  loop's force span (at least its previous width w, at most ``emax``·q_ult): Masing-type
  reloading, so that every reload to the same force yields again, a little less each cycle —
  the settlement a one-sided cyclic load accumulates. The pristine range is ±``elast``·q_ult.
  A range ends at the capacity at the latest, and where the series carries the capacity (to
  a part in 10¹²; the hyperbola only tends to it) the near field flows perfectly plastically:
  whatever compression is left goes into z_p at Q = q_ult and is dissipated.
- *gap*: a rigid closure (the footing cannot penetrate the settled surface: z_g ≤ 0, and
  z_g = 0 carries any compression) in parallel with a drag (suction) element of capacity
  q_d = suction·q_ult, a hyperbola of reference z_d = z50/2 (length):

      closing: Q_g = q_d − (q_d − q_a) · z_d/(z_d + z_g − z_a)
      opening: Q_g = −q_d + (q_d + q_a) · z_d/(z_d + z_a − z_g)

  (q_a, z_a) the state at its last reversal. With q_d = 0 (the default: no tension at the
  soil–footing interface) the gap carries nothing while open: the spring unloads along k to
  Q = 0, then separates; it recontacts where it left, at the settled surface z_e + z_p.

Virgin backbone (q_r = ``elast``·q_ult, z_in = 0): z(Q) = Q/k for Q ≤ q_r, and
z(Q) = Q/k + z_ref · (((q_ult − q_r)/(q_ult − Q))^(1/n) − 1) beyond, so Q → q_ult as z → ∞;
for one spring, z50 = z(q_ult/2) fixes z_ref (:func:`.backbone.zref_from_z50`), for a bed the
settlement at which its springs together carry half their capacity does
(:func:`.backbone.common_zref`).

Dissipation: the work Q dz_p on the near field and Q_g dz_g on the drag, integrated in closed
form along the branch of a step (no quadrature): with u the distance travelled from the anchor,
∫ Q du = q_ult Δu − (q_ult − q_r) · z_ref/(n − 1) · (r_a^(n−1) − r_b^(n−1)), r = z_ref/(z_ref + u),
and ∫ Q_g dz_g = q_d Δw − (q_d − q_a) z_d ln((z_d + w_b)/(z_d + w_a)). Its sum over a closed cycle
is the loop's area; a Masing reverse yield may return a little of it (work on the near field
while Q and ż_p have opposite signs), as a kinematic-hardening material would.

A trial state is a function of the committed history and the trial z only (the direction of
the move is the sign of z − z_c): the force is continuous and single-valued in z, so the work
of a step is path-independent inside it, and the fixed-step return map (:func:`qz_commit`)
books exactly the dissipation of the step. z(Q) along a branch is increasing, so the trial
force is the root of one monotone scalar equation, found by Newton's method safeguarded by
bisection inside the branch's bracket.

Differences from OpenSees QzSimple1/2: the closure is rigid (OpenSees: 1000 q_ult/z50), the
near field rigid inside its range (10⁴ q_ult/z50), the far field is the calibrated k (OpenSees
ties it to q_ult/z50 by soil type), the dashpot acts on the whole spring while in contact and
never pulls, and the series is solved to round-off rather than by sub-stepped iteration.

In the reduced model the spring's deformation e is measured from static equilibrium
(z = z_s + e, z_s the virgin z at the static force F0) and its force is returned as Q − F0,
like the other foundation springs; its ``ep`` is the near-field settlement since static,
z_p − (z_s − F0/k), so that F0/k + e − ep = Q/k + z_g is the compression that separation, the
contact length and the gap peaks read, as for the elasto-plastic spring.
"""

from __future__ import annotations

import math

from numba import njit

from ..spring import CONTACT, SEPARATED, YIELDING

__all__ = ["QZ", "qz_backbone", "qz_start", "qz_trial", "qz_commit",
           "qz_force", "qz_spring_state", "qz_mode"]

QZ = 3  # the spring kind of a q–z spring

MAX_ITER = 200


@njit(cache=True)
def qz_backbone(p, q):
    """Compression z (length) on the virgin backbone at force q (force, 0 ≤ q < q_ult)."""
    qr = p.elast * p.qult
    if q <= qr:
        return q / p.k
    return q / p.k + p.zref * (((p.qult - qr) / (p.qult - q)) ** (1.0 / p.npow) - 1.0)


@njit(cache=True)
def qz_start(p, h, q0):
    """Set history ``h`` to the virgin state loaded monotonically to force q0 (gap closed, drag
    at rest); returns its compression z (length)."""
    qr = p.elast * p.qult
    z = qz_backbone(p, q0)
    h.zc, h.qc = z, q0
    h.zp = z - q0 / p.k
    h.qr, h.ql, h.zin, h.wel = qr, -qr, 0.0, 2.0 * qr
    h.zg, h.qg, h.qa, h.za = 0.0, 0.0, 0.0, 0.0
    h.ep = 0.0
    return z


@njit(cache=True)
def cap(p):
    """The largest force the series carries: q_ult less a part in 10¹² (the hyperbola only
    tends to q_ult), where the near field flows perfectly plastically."""
    return p.qult * (1.0 - 1e-12)


@njit(cache=True)
def near_branch(p, h, d):
    """The near field's range and anchor (q_r, q_l, z_in, w) for a move in direction d (±1)
    from the committed state: a reversal from a yielding state starts a new range there. The
    range ends at the capacity ±:func:`cap` at the latest: a Masing range wider than the room
    left below q_ult would hold the near field rigid up to a force the soil cannot carry."""
    qr, ql, zin, w = h.qr, h.ql, h.zin, h.wel
    # yielding: past the range's end, or flowing at the capacity where the range ends there
    if d < 0 and (h.qc > qr or h.zp > h.zin):
        w = min(max(w, h.qc - ql), p.emax * p.qult)
        qr, ql, zin = h.qc, max(h.qc - w, -cap(p)), h.zp
    elif d > 0 and (h.qc < ql or h.zp < h.zin):
        w = min(max(w, qr - h.qc), p.emax * p.qult)
        qr, ql, zin = min(h.qc + w, cap(p)), h.qc, h.zp
    return qr, ql, zin, w


@njit(cache=True)
def drag_branch(h, d):
    """The drag's anchor (q_a, z_a) for a move in direction d: the committed state on a
    reversal."""
    if (d < 0 and h.zg > h.za) or (d > 0 and h.zg < h.za):
        return h.qg, h.zg
    return h.qa, h.za


@njit(cache=True)
def near_field(p, q, d, qr, ql, zin):
    """Near-field plastic displacement z_p (length) at force q on branch d, and dz_p/dQ."""
    inv_n = 1.0 / p.npow
    if d > 0:
        if q <= qr:
            return zin, 0.0
        r = ((p.qult - qr) / (p.qult - q)) ** inv_n
        return zin + p.zref * (r - 1.0), p.zref * inv_n * r / (p.qult - q)
    if q >= ql:
        return zin, 0.0
    r = ((p.qult + ql) / (p.qult + q)) ** inv_n
    return zin - p.zref * (r - 1.0), p.zref * inv_n * r / (p.qult + q)


@njit(cache=True)
def gap(p, q, d, qa, za):
    """Gap displacement z_g ≤ 0 (length) at series force q on branch d (drag q_d > 0), and
    dz_g/dQ: closed (0, 0) where the drag alone would not open it."""
    if d > 0:
        if q >= p.qd:
            return 0.0, 0.0
        inv = za + p.zd * ((p.qd - qa) / (p.qd - q) - 1.0)
        der = p.zd * (p.qd - qa) / ((p.qd - q) * (p.qd - q))
    else:
        inv = za - p.zd * ((p.qd + qa) / (p.qd + q) - 1.0)
        der = p.zd * (p.qd + qa) / ((p.qd + q) * (p.qd + q))
    if inv >= 0.0:
        return 0.0, 0.0
    return inv, der


@njit(cache=True)
def chain(p, q, d, nf, dr, drag):
    """(z, dz/dQ, z_p, z_g) of the series at force q on branch d; ``nf`` = (q_r, q_l, z_in),
    ``dr`` = (q_a, z_a); ``drag`` False: the gap is closed (z_g = 0)."""
    zp, dzp = near_field(p, q, d, nf[0], nf[1], nf[2])
    zg, dzg = 0.0, 0.0
    if drag:
        zg, dzg = gap(p, q, d, dr[0], dr[1])
    return q / p.k + zp + zg, 1.0 / p.k + dzp + dzg, zp, zg


@njit(cache=True)
def solve_chain(p, z, d, lo, hi, q0, nf, dr, drag):
    """The force Q in [lo, hi] at which the series' z(Q) = z (increasing in Q), by Newton's
    method from q0 safeguarded by bisection. Returns (Q, dz/dQ, z_p, z_g)."""
    q = min(max(q0, lo), hi)
    for _ in range(MAX_ITER):
        zq, dz, _, _ = chain(p, q, d, nf, dr, drag)
        f = zq - z
        if f == 0.0:
            break
        if f > 0.0:
            hi = q
        else:
            lo = q
        qn = q - f / dz
        if not (lo < qn < hi):
            qn = 0.5 * (lo + hi)
        if abs(qn - q) <= 1e-15 * p.qult or hi - lo <= 1e-15 * p.qult:
            q = qn
            break
        q = qn
    zq, dz, zp, zg = chain(p, q, d, nf, dr, drag)
    return q, dz, zp, zg


@njit(cache=True)
def at_capacity(p, z, q, dz, zp, zg):
    """(Q, dz/dQ, z_p) of a loading move: where the series reaches :func:`cap` before the
    trial compression z, the rest of z flows plastically at the capacity (z_p takes it, the
    compliance is infinite), so that the work Q dz of that flow is the near field's, booked by
    :func:`step_dissipation`, and not lost."""
    if q < cap(p) * (1.0 - 1e-9):  # the solver stops within round-off of its bracket's end
        return q, dz, zp
    excess = z - (q / p.k + zp + zg)
    if excess <= 0.0:
        return q, dz, zp
    return q, math.inf, zp + excess


@njit(cache=True)
def qz_trial(p, h, z):
    """The trial state at total compression z (length) from the committed history ``h``.

    Returns (Q, dz/dQ, z_p, z_g, d, q_r, q_l, z_in, w, q_a, z_a): the force, the compliance
    (inf while the gap is open without drag), the near-field and gap displacements, the
    direction of the move and the branch's anchors (what :func:`qz_commit` keeps).
    """
    d = 1.0 if z >= h.zc else -1.0
    qr, ql, zin, w = near_branch(p, h, d)
    qa, za = drag_branch(h, d)
    nf = (qr, ql, zin)
    dr = (qa, za)
    top = cap(p)
    if p.qd > 0.0:
        if d > 0:
            q, dz, zp, zg = solve_chain(p, z, d, h.qc, top, h.qc, nf, dr, True)
            q, dz, zp = at_capacity(p, z, q, dz, zp, zg)
        else:
            q, dz, zp, zg = solve_chain(p, z, d, -p.qd * (1.0 - 1e-12), h.qc, h.qc, nf, dr,
                                        True)
        return q, dz, zp, zg, d, qr, ql, zin, w, qa, za
    # no drag: the gap is open at Q = 0 and closed for Q > 0
    if d > 0:
        if h.zg < 0.0 and z <= h.zc - h.zg:
            return 0.0, math.inf, h.zp, h.zg + (z - h.zc), d, qr, ql, zin, w, qa, za
        q, dz, zp, zg = solve_chain(p, z, d, max(h.qc, 0.0), top, h.qc, nf, dr, False)
        q, dz, zp = at_capacity(p, z, q, dz, zp, zg)
        return q, dz, zp, zg, d, qr, ql, zin, w, qa, za
    z0, _, zp0, _ = chain(p, 0.0, d, nf, dr, False)
    if z <= z0:
        return 0.0, math.inf, zp0, z - z0, d, qr, ql, zin, w, qa, za
    q, dz, zp, zg = solve_chain(p, z, d, 0.0, h.qc, h.qc, nf, dr, False)
    return q, dz, zp, zg, d, qr, ql, zin, w, qa, za


@njit(cache=True)
def hyperbola_work(m, zref, q_inf, span, ua, ub):
    """∫ Q du from ua to ub ≥ ua on Q = q_inf − span·(zref/(zref + u))^(m+1) (m = n − 1 > 0):
    q_inf Δu − span·zref/m·(r_a^m − r_b^m), the difference taken without cancellation."""
    du = ub - ua
    if du <= 0.0:
        return 0.0
    ra_m = (zref / (zref + ua)) ** m
    diff = -ra_m * math.expm1(-m * math.log1p(du / (zref + ua)))
    return q_inf * du - span * zref / m * diff


@njit(cache=True)
def drag_work(qd, zd, span, wa, wb):
    """∫ Q_g dw from wa to wb ≥ wa on Q_g = q_d − span·z_d/(z_d + w): the drag's hyperbola."""
    dw = wb - wa
    if dw <= 0.0:
        return 0.0
    return qd * dw - span * zd * math.log1p(dw / (zd + wa))


@njit(cache=True)
def step_dissipation(p, h, zp, zg, d, zin, qr, ql, qa, za):
    """Work done on the near field and the drag from the committed state to (z_p, z_g) along
    branch d (force·length): ∫ Q dz_p + ∫ Q_g dz_g, in closed form."""
    m = p.npow - 1.0
    work = 0.0
    if zp != h.zp:
        if d > 0:
            work += hyperbola_work(m, p.zref, p.qult, p.qult - qr, h.zp - zin, zp - zin)
        else:  # along v = z_in − z_p, Q = −(q_ult − (q_ult + q_l)(z_ref/(z_ref + v))^n)
            work += hyperbola_work(m, p.zref, p.qult, p.qult + ql, zin - h.zp, zin - zp)
    if p.qd > 0.0 and zg != h.zg:
        if d > 0:
            work += drag_work(p.qd, p.zd, p.qd - qa, h.zg - za, zg - za)
        else:
            work += drag_work(p.qd, p.zd, p.qd + qa, za - h.zg, za - zg)
    return work


@njit(cache=True)
def drag_force(p, zg, d, qa, za):
    """The drag's force (force) at gap displacement zg on branch d."""
    if p.qd <= 0.0:
        return 0.0
    if d > 0:
        return p.qd - (p.qd - qa) * p.zd / (p.zd + zg - za)
    return -p.qd + (p.qd + qa) * p.zd / (p.zd + za - zg)


@njit(cache=True)
def qz_commit(p, h, z):
    """Commit the trial state at total compression z (length) into ``h``; returns the work
    dissipated since the last commit (force·length)."""
    q, _, zp, zg, d, qr, ql, zin, w, qa, za = qz_trial(p, h, z)
    work = step_dissipation(p, h, zp, zg, d, zin, qr, ql, qa, za)
    if zg < 0.0:
        qg = q
    elif h.zg < 0.0:
        qg = drag_force(p, 0.0, d, qa, za)
    else:
        qg = h.qg
    h.zc, h.qc, h.zp, h.zg, h.qg = z, q, zp, zg, qg
    h.qr, h.ql, h.zin, h.wel, h.qa, h.za = qr, ql, zin, w, qa, za
    h.ep = zp - (p.zs - p.d0)
    return work


@njit(cache=True)
def qz_force(p, h, e, ed):
    """Force conjugate to e (the increment Q + dashpot − F0), the dashpot's power and force,
    the tangents (dF/de, dF/dė) and the mode (:func:`qz_mode`) at the trial state e, ė. The
    dashpot acts while the gap is closed and never pulls (clipped so that the total stays
    ≥ 0)."""
    q, dz, zp, zg, _, _, _, _, _, _, _ = qz_trial(p, h, p.zs + e)
    mode = SEPARATED if zg < 0.0 else (YIELDING if zp > h.zp else CONTACT)
    kt = 0.0 if math.isinf(dz) else 1.0 / dz
    fd = 0.0
    ct = 0.0
    if zg == 0.0 and p.c > 0.0:
        fd = p.c * ed
        ct = p.c
        if q + fd < 0.0:
            fd = -q
            kt, ct = 0.0, 0.0
    return q + fd - p.f0, fd * ed, fd, kt, ct, mode


@njit(cache=True)
def qz_spring_state(p, h, e):
    """(near-field settlement since static, force Q, stored energy Q²/(2k)) at the trial e."""
    q, _, zp, _, _, _, _, _, _, _, _ = qz_trial(p, h, p.zs + e)
    return zp - (p.zs - p.d0), q, 0.5 * q * q / p.k


@njit(cache=True)
def qz_mode(p, h, e):
    """SEPARATED while the gap is open, YIELDING while the near field flows into the soil,
    else CONTACT (for output and the bookkeeping that reads modes)."""
    _, _, zp, zg, _, _, _, _, _, _, _ = qz_trial(p, h, p.zs + e)
    if zg < 0.0:
        return SEPARATED
    return YIELDING if zp > h.zp else CONTACT
