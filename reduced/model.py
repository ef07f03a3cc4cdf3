"""The reduced model of a scene: masses, compatibility matrix, spring parameters (Ewing eqs. 1–9).

:func:`build_model` turns a validated :class:`~upliftlab.scenes.Scene` into a
:class:`ReducedModel`: immutable arrays that the compiled integrators take as arguments.
Conventions: DOFs relative to the ground; θ positive when it moves the top by
+hθ; V positive up; foundation spring deformation is compression. Damping of the foundation is a
fraction ζ_f of critical for the bonded vertical mode, c_i = ζ_f·2√(K_v m_v)·k_i/K_v; damping of
the superstructure is a fraction ζ_s of critical for its fixed-base first mode (stiffness
proportional for a shear building, which is ζ_s exactly for one story). The foundation's
dashpots may instead be given one per spring (``foundation.dashpots``).

A sway spring (``foundation.sway_stiffness``) is a story-kind spring on the base's horizontal
displacement relative to the ground: elastic, or elastic–perfectly plastic with the sliding
capacity μ W, with a parallel dashpot. It adds one DOF (:mod:`.compatibility`): the base's u_b
with the base body's own mass for a flexible structure, or the centre of mass's u_G with the
whole mass for a rigid one (I_θ is then about G).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
import scipy.linalg

from ..checks import InputError
from ..scenes import Scene
from . import springs as sp
from .compatibility import (DofMap, SpringLayout, base_transform, compatibility_matrix,
                            layout_for, stiffness_matrix)
from .laws import Base, Bed, law_of

__all__ = ["ReducedModel", "build_model", "impact_effective_mass", "impact_step"]


@dataclass(frozen=True)
class ReducedModel:
    """Everything the integrators need, as arrays (units of the scene).

    ``mass`` (n) diagonal masses; ``A`` (n × n_spring) compatibility; ``params`` one record of
    :data:`~.springs.SPRING_DTYPE` per spring, story springs first;
    ``ground_load`` L = −M r (n), the force per unit ground acceleration; ``geometric`` K_G (n × n)
    P-Δ stiffness; ``weight`` W carried by the foundation; ``layout`` the foundation springs;
    ``base`` the base element of a law that is one (the macro-element,
    :class:`~.laws.macro.element.BaseElement`), which then replaces the foundation springs and
    the sway spring (``layout`` still gives the base's half-width).
    """

    scene: Scene
    dofs: DofMap
    mass: np.ndarray
    A: np.ndarray
    params: np.ndarray
    ground_load: np.ndarray
    geometric: np.ndarray
    weight: float
    heights: np.ndarray
    layout: SpringLayout | None
    static_rotation: float = 0.0
    notes: tuple[str, ...] = field(default=())
    sway_height: float = 0.0
    base: object | None = None

    @property
    def exact(self) -> bool:
        """True with exact rocking kinematics (q holds the rotated-frame deflections and
        sin θ; ``mass`` is then the mass matrix's diagonal at rest)."""
        return self.scene.structure.kinematics == "exact"

    @property
    def linearised(self) -> ReducedModel:
        """The model of small rotations with P-Δ that exact kinematics linearises to at rest:
        its eigenvalues are this model's at rest (the same system in other coordinates), and
        they set the stability limits and time steps."""
        if not self.exact:
            return self
        from dataclasses import replace
        s = replace(self.scene.structure, kinematics="small", p_delta=True)
        return build_model(replace(self.scene, structure=s))

    @property
    def story_count(self) -> int:
        return len(self.dofs.stories)

    @property
    def spring_count(self) -> int:
        return self.params.size

    @property
    def kind(self) -> np.ndarray:
        return self.params["kind"]

    @property
    def sway_spring(self) -> int:
        """Index of the sway spring (after the story springs), −1 without one."""
        return self.story_count if self.dofs.sway >= 0 and self.base is None else -1

    @property
    def foundation_start(self) -> int:
        """Index of the first foundation spring (after the stories and the sway spring)."""
        return self.story_count + (1 if self.sway_spring >= 0 else 0)

    @property
    def foundation_slice(self) -> slice:
        return slice(self.foundation_start, self.spring_count)

    @property
    def g(self) -> float:
        return self.scene.g

    def bonded_matrices(self, with_impact: bool = False) -> tuple[np.ndarray, np.ndarray]:
        """(K, C) with every spring elastic and in contact: K = A S Aᵀ + K_G (eq. 5), and a base
        element's at rest."""
        p = self.params
        k = p["k"] + p["kh"]
        c = p["c"] + (p["cimp"] if with_impact else 0.0)
        K, C = stiffness_matrix(self.A, k) + self.geometric, stiffness_matrix(self.A, c)
        if self.base is not None:
            Kb, Cb = self.base.bonded_matrices()
            K, C = K + Kb, C + Cb
        return K, C

    def bonded_periods(self) -> np.ndarray:
        """Periods (s) of the bonded, undamped system, longest first."""
        K, _ = self.bonded_matrices()
        w2 = scipy.linalg.eigh(K, np.diag(self.mass), eigvals_only=True)
        w2 = np.clip(w2, 1e-300, None)
        return np.sort(2.0 * np.pi / np.sqrt(w2))[::-1]


def impact_effective_mass(x: np.ndarray, rotary_mass: float, vertical_mass: float) -> np.ndarray:
    """m_eff = m I_M / I₀ of eq. 17: the mass a base point at x feels, 1/(x²/I_M + 1/m).

    I_M is the rotary mass of the base about O and I₀ = I_M + m x² its value about the spring.
    """
    return 1.0 / (np.asarray(x) ** 2 / rotary_mass + 1.0 / vertical_mass)


def build_model(scene: Scene) -> ReducedModel:
    """The :class:`ReducedModel` of ``scene``."""
    s, f, g = scene.structure, scene.foundation, scene.g
    fixed = f.support == "fixed"
    exact = s.kinematics == "exact"
    if exact and fixed:
        raise InputError("structure.kinematics = 'exact' with foundation.support = 'fixed': "
                         "exact kinematics is that of a rocking base; valid: 'small'")
    if exact and f.sways:  # scenes refuse it when read; a model made otherwise is refused here
        raise InputError("foundation.sway_stiffness with structure.kinematics = 'exact': exact "
                         "kinematics pivots the base on its edge without sliding; valid: 'small'")
    dofs = DofMap.build(len(s.stories), rigid=s.rigid, fixed=fixed, exact=exact, sway=f.sways)
    heights = np.array([st.height for st in s.stories])
    masses = np.array([st.weight for st in s.stories]) / g
    layout = None if fixed else layout_for(f)
    mass, load = _masses(dofs, s, masses, heights, g)
    if exact:  # the kernels build M(q); mass is its diagonal at rest, for the energy scale
        mass = np.diag(_exact_mass_at_rest(dofs, s, masses, heights, g))
        load = np.zeros_like(load)
    rotary_mass = mass[dofs.theta]  # about O, without sway: the impact damper's (eq. 17)
    sway_height = 0.0
    if f.sways:
        sway_height = _sway_masses(dofs, s, masses, heights, g, mass, load)
    law = None if fixed else law_of(f.law)
    element = law is not None and law.element is not None
    A = compatibility_matrix(dofs, heights, None if element else layout, exact=exact,
                             sway_height=sway_height, sway_spring=not element)
    tables = [_story_params(s, masses)]
    if f.sways and not element:
        tables.append(_sway_params(f, s.vertical_weight))
    weight, theta_s, base = 0.0, 0.0, None
    if element:
        base = law.element(f.law, _base(f, layout, s.vertical_weight, mass[dofs.v],
                                         base_transform(dofs, sway_height)))
        weight = s.vertical_weight
    elif layout is not None:
        found, theta_s = _foundation_params(f, layout, s.vertical_weight, rotary_mass,
                                            mass[dofs.v])
        tables.append(found)
        weight = s.vertical_weight
    params = _attach_columns(sp.derive_columns(np.concatenate(tables)), A)
    geometric = np.zeros((dofs.size, dofs.size)) if exact else _geometric(dofs, s, masses,
                                                                             heights, g, A)
    if not s.rigid:  # story springs come first; each shear acts over its story's height
        params["arm"][:len(s.stories)] = np.diff(np.concatenate([[0.0], heights]))
    return ReducedModel(scene=scene, dofs=dofs, mass=mass, A=A, params=params, ground_load=load,
                        geometric=geometric, weight=weight, heights=heights, layout=layout,
                        static_rotation=theta_s, notes=_notes(f, layout),
                        sway_height=sway_height, base=base)


def _base(f, layout: SpringLayout, weight: float, vertical_mass: float, transform) -> Base:
    """What an element law is built from: the foundation's dashpots as a density over the
    width, c′ = ζ_f 2√(K_v m_v)/B (a uniform bed's dashpots, c_i = c′ × its width), and the
    sway's."""
    density = f.damping_ratio * 2.0 * math.sqrt(f.stiffness * vertical_mass) / f.width
    return Base(layout=layout, weight=weight, sway_stiffness=f.sway_stiffness,
                dashpot_density=density, sway_dashpot=f.sway_damping or 0.0,
                transform=transform)


#: Springs beyond which the paper's per-spring impact damper is warned about (Fig. 1b's 12).
PAPER_SPRINGS = 12


def _notes(f, layout: SpringLayout | None) -> tuple[str, ...]:
    """What a user should know about this model before trusting its numbers."""
    notes = []
    if (layout is not None and f.support == "uplift" and f.restitution < 1.0
            and f.impact_mass == "point" and layout.count > PAPER_SPRINGS):
        notes.append(
            f"foundation.springs = {layout.count} with the paper's per-spring impact damper "
            "(foundation.impact_mass = 'point'): every landing spring removes (1 - eps^2) of "
            "the closing energy of the whole base's effective mass, so the impact dissipation "
            "grows with the number of springs and this response does not converge in N; "
            "foundation.impact_mass = 'tributary' converges")
    return tuple(notes)


def _exact_mass_at_rest(dofs: DofMap, s, masses, heights, g) -> np.ndarray:
    """Mass matrix of exact kinematics at rest (θ = 0, no deflection): each story mass moves by
    ẇ_j + h_j ṡ laterally and V̇ vertically; the base body adds I_b on sin θ and its mass on V."""
    n = dofs.size
    M = np.zeros((n, n))
    M[dofs.theta, dofs.theta] = s.rotary_inertia
    M[dofs.v, dofs.v] = s.vertical_weight / g
    for j, (m, h) in enumerate(zip(masses, heights)):
        if dofs.stories:
            M[j, j] += m
            M[j, dofs.theta] += m * h
            M[dofs.theta, j] += m * h
        M[dofs.theta, dofs.theta] += m * h * h
    return M


def _attach_columns(params: np.ndarray, A: np.ndarray) -> np.ndarray:
    """Copy each spring's column of A into its record (nnz entries a0… at DOFs i0…)."""
    for j in range(params.size):
        rows = np.flatnonzero(A[:, j])
        if not 1 <= rows.size <= 3:
            raise ValueError(f"spring {j} connects {rows.size} DOFs; the kernels take 1 to 3")
        params["nnz"][j] = max(rows.size, 2)
        for slot, row in enumerate(rows):
            params[f"i{slot}"][j] = row
            params[f"a{slot}"][j] = A[row, j]
    return params


def _masses(dofs: DofMap, s, masses, heights, g) -> tuple[np.ndarray, np.ndarray]:
    """Diagonal masses (eq. 4) and the ground load L = −M r."""
    mass = np.zeros(dofs.size)
    load = np.zeros(dofs.size)
    for j, dof in enumerate(dofs.stories):
        mass[dof] = masses[j]
        load[dof] = -masses[j]
    if dofs.theta >= 0:
        mass[dofs.theta] = s.rotary_inertia
        mass[dofs.v] = s.vertical_weight / g
        if s.rigid:  # x_j = h_j θ: the story masses rotate with the base
            mass[dofs.theta] += float(np.sum(masses * heights**2))
            load[dofs.theta] = -float(np.sum(masses * heights))
    return mass, load


def _sway_masses(dofs: DofMap, s, masses, heights, g, mass, load) -> float:
    """Mass and ground load of the sway DOF, in place; returns h_G (0 for a flexible structure).

    Flexible structure: u_b carries the base body's own mass m_b = (W_v − Σ W_j)/g (the story
    masses keep their DOFs relative to the ground). Rigid: u_G carries the whole mass
    M = Σ m_j + m_b at G, h_G = Σ m_j h_j / M above O, and the rotary mass becomes the one about
    G, I₀ + Σ m_j h_j² − M h_G², so that the mass matrix stays diagonal; the ground then loads
    u_G only."""
    base_mass = max(s.vertical_weight - s.weight, 0.0) / g
    if dofs.stories:
        mass[dofs.sway] = base_mass
        load[dofs.sway] = -base_mass
        return 0.0
    total = float(np.sum(masses)) + base_mass
    height = float(np.sum(masses * heights)) / total
    mass[dofs.sway] = total
    load[dofs.sway] = -total
    if dofs.theta >= 0:
        mass[dofs.theta] -= total * height * height
        load[dofs.theta] = 0.0
    return height


def _sway_params(f, vertical_weight: float) -> np.ndarray:
    """The sway spring: a story-kind spring of stiffness k_h, capped at the sliding capacity
    μ W (elastic without μ), with a parallel dashpot c_h."""
    table = sp.spring_table(1)
    table["kind"] = sp.STORY
    table["k"] = f.sway_stiffness
    table["c"] = f.sway_damping or 0.0
    if f.sliding_friction is not None:
        table["fy"] = f.sliding_friction * vertical_weight
    return table


def _fundamental_frequency(s, masses) -> float:
    k = np.array([st.stiffness for st in s.stories])
    n = k.size
    K = np.zeros((n, n))
    for j in range(n):
        K[j, j] += k[j]
        if j > 0:
            K[j - 1, j - 1] += k[j]
            K[j - 1, j] -= k[j]
            K[j, j - 1] -= k[j]
    w2 = scipy.linalg.eigh(K, np.diag(masses), eigvals_only=True)
    return math.sqrt(w2[0])


def _story_params(s, masses) -> np.ndarray:
    """Story springs: EPP k(1−α) capped at Fy(1−α), parallel αk, dashpot 2ζk/ω₁."""
    if s.rigid:
        return sp.spring_table(0)
    omega1 = _fundamental_frequency(s, masses)
    table = sp.spring_table(len(s.stories))
    for row, st in zip(table, s.stories):
        zeta = s.damping_ratio if st.damping_ratio is None else st.damping_ratio
        alpha = st.post_yield_ratio if math.isfinite(st.yield_force) else 0.0
        row["kind"] = sp.STORY
        row["k"] = (1.0 - alpha) * st.stiffness
        row["kh"] = alpha * st.stiffness
        row["fy"] = (1.0 - alpha) * st.yield_force
        row["c"] = 2.0 * zeta * st.stiffness / omega1
    return table


def _foundation_params(f, layout: SpringLayout, weight, rotary_mass, vertical_mass):
    """Foundation springs: k_i, dashpots and positions; F0_i, yield and the rest from the
    foundation's law (:mod:`.laws`); the impact damper. Returns (table, static rotation)."""
    k, x = layout.stiffnesses, layout.positions
    order = np.argsort(f.positions, kind="stable") if f.layout == "custom" else None
    bed = Bed(layout=layout, weight=weight, support=f.support, order=order)
    table = sp.spring_table(layout.count)
    table["k"] = k
    if f.dashpots is not None:  # one per spring; a custom layout's follow its positions
        table["c"] = bed.in_layout_order(f.dashpots)
    else:
        table["c"] = (f.damping_ratio * 2.0 * math.sqrt(f.stiffness * vertical_mass) * k
                      / layout.vertical_stiffness)
    table["x"] = x
    table, theta_s = law_of(f.law).springs(f.law, bed, table)
    if f.restitution < 1.0 and f.support == "uplift":
        meff = impact_effective_mass(x, rotary_mass, vertical_mass)
        if f.impact_mass == "tributary":
            meff = meff * k / layout.vertical_stiffness
        cstar = f.impact_multiple * 2.0 * np.sqrt(k * meff)
        table["cimp"] = cstar
        table["dzf"] = meff * (1.0 - f.restitution) / cstar
        table["imph"] = impact_step(meff, table["c"] + cstar, k)
    return table, theta_s


RK4_REAL_LIMIT = 2.785293563405282  # |R(z)| = 1 on the negative real axis


def impact_step(mass, damping, stiffness):
    """Step cap while a spring's impact dashpot acts: |λ|·h = 0.1 × RK4's real-axis limit
    (0.28) for m s² + c s + k = 0, where RK4's local error is about 1e-5 — a stroke that lasts
    many steps (ε → 0) is then integrated accurately, not only stably. Takes arrays: |λ| is
    the larger real root (c + √(c² − 4mk))/2m when overdamped, √(k/m) otherwise."""
    m, c, k = np.broadcast_arrays(*map(np.asarray, (mass, damping, stiffness)))
    disc = c * c - 4.0 * m * k
    largest = np.where(disc >= 0.0, (c + np.sqrt(np.maximum(disc, 0.0))) / (2.0 * m),
                       np.sqrt(k / m))
    return 0.1 * RK4_REAL_LIMIT / largest


def _geometric(dofs: DofMap, s, masses, heights, g, A) -> np.ndarray:
    """P-Δ stiffness of the story weights (zero unless ``p_delta``).

    Second-order gravity potential of floor j at (u_j, h_j − Σ_{k≤j} d_k²/(2Δh_k)) in the frame
    of the base rotated by θ, d_k the story drifts: W_j(h_j θ²/2 − x_j θ) about the rocking base
    (rigid structure: −W_j h_j θ²/2) and −P_k d_k²/(2Δh_k) per story, P_k the weight above
    story k. For one story the two add up to −W x²/(2h): an inverted pendulum about O.
    """
    KG = np.zeros((dofs.size, dofs.size))
    if not s.p_delta:
        return KG
    weights = masses * g
    t = dofs.theta
    if t >= 0 and s.rigid:
        KG[t, t] = -float(np.sum(weights * heights))
        return KG
    if t >= 0:  # x_j − u_b is the lateral position relative to the base, with a sway DOF
        for j, dof in enumerate(dofs.stories):
            KG[t, t] += weights[j] * heights[j]
            KG[dof, t] -= weights[j]
            KG[t, dof] -= weights[j]
            if dofs.sway >= 0:
                KG[dofs.sway, t] += weights[j]
                KG[t, dofs.sway] += weights[j]
    story_heights = np.diff(np.concatenate([[0.0], heights]))
    above = np.cumsum(weights[::-1])[::-1]
    for k in range(len(dofs.stories)):
        column = A[:, k]
        KG -= above[k] / story_heights[k] * np.outer(column, column)
    return KG
