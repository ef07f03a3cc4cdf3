"""The foundation energy E_F: the energy the structure lost to its foundation over a run, from
the structure's own histories.

E_F is the work the footing did on what carries it, W_base = ∫ R · dq (R the base reactions,
q the footing's u, v, θ). A bed turns it into dashpot, impact and plastic work and the change of
its springs' elastic energy; the continuum's soil into plastic work, the waves it sends away from
the footing and the change of its elastic energy. It is the dissipated energy as the structure
sees it: the damping its foundation gives it, whatever the foundation does with the energy. The
continuum's own energy account cannot give the soil's dissipation apart (it books plastic work
and stored elastic energy as one strain term, and the soil's share of the ground's input, its
own free-field response, with them); E_F needs neither.

It is taken from the structure's side of the balance, which needs no reaction history:

    E_F = W_in − ΔK − ΔU_story − ΔU_gravity − D_story,

with z = (u, v, θ, s) the footing and the story deformation, W_in = −∫ a_g (M r) · dz the
ground's input (relative frame), K = ½ żᵀ M ż, U_story = ½ zᵀ K z, U_gravity = −F_g · z, and
D_story = ∫ ż C ż dt the story dashpot's work (force·length, per metre of footing in plane
strain).
"""

from __future__ import annotations

import numpy as np

__all__ = ["end_velocity", "structure_energy_terms"]


def end_velocity(time: np.ndarray, values: np.ndarray) -> np.ndarray:
    """The rate of ``values`` (nt, …) at the last row, by the second-order one-sided
    difference on the last three rows (equal or unequal spacing); first order with two rows."""
    t = np.asarray(time, dtype=float)
    y = np.asarray(values, dtype=float)
    if t.size < 2:
        return np.zeros(y.shape[1:])
    if t.size == 2:
        return (y[-1] - y[-2]) / (t[-1] - t[-2])
    h1, h2 = t[-1] - t[-2], t[-2] - t[-3]
    # the derivative at t_n of the parabola through the last three rows
    c0 = (2.0 * h1 + h2) / (h1 * (h1 + h2))
    c1 = -(h1 + h2) / (h1 * h2)
    c2 = h1 / (h2 * (h1 + h2))
    return c0 * y[-1] + c1 * y[-2] + c2 * y[-3]


def structure_energy_terms(time, z, story_velocity, ground_acceleration, M, C, K, r, gravity,
                           initial_velocity=None) -> dict:
    """The structure's energy balance over a run and its E_F (module docstring): ``input``
    W_in, ``kinetic`` ΔK, ``story`` ΔU_story, ``gravity`` the work of gravity −ΔU_gravity,
    ``story_dashpot`` D_story and ``foundation`` E_F, of a run whose rows are at ``time``
    (s): ``z`` (nt, 4) the footing's u, v, θ and the story deformation s relative to the
    ground (length, rad),
    ``story_velocity`` (nt) ṡ, ``ground_acceleration`` (nt, length/s²), and the structure's
    mass, damping and stiffness (4, 4), ground influence ``r`` (4) and gravity load (4).
    ``initial_velocity`` ż at the first row (default: at rest but for ṡ). The work integrals
    are trapezoidal over the rows; the end's ż is :func:`end_velocity`'s (ṡ as recorded)."""
    t = np.asarray(time, dtype=float)
    z = np.asarray(z, dtype=float)
    sd = np.asarray(story_velocity, dtype=float)
    ag = np.asarray(ground_acceleration, dtype=float)
    M, C, K = (np.asarray(a, dtype=float) for a in (M, C, K))
    if np.any(np.delete(C.ravel(), 15)):
        raise ValueError("structure_energy_loss: the damping matrix acts on more than the "
                         "story's s; valid: C zero but for C[3, 3]")
    dz = np.diff(z, axis=0)
    inertia = M @ np.asarray(r, dtype=float)
    work_in = -float(np.sum(0.5 * (ag[1:] + ag[:-1]) * (dz @ inertia)))
    z0_dot = np.zeros(4) if initial_velocity is None else np.asarray(initial_velocity, float)
    if initial_velocity is None:
        z0_dot[3] = sd[0]
    zn_dot = end_velocity(t, z)
    zn_dot[3] = sd[-1]
    kinetic = 0.5 * (zn_dot @ M @ zn_dot - z0_dot @ M @ z0_dot)
    story = 0.5 * (z[-1] @ K @ z[-1] - z[0] @ K @ z[0])
    gravity_work = float(np.asarray(gravity, dtype=float) @ (z[-1] - z[0]))
    power = C[3, 3] * sd * sd  # C acts on the story's s alone, whose rate is recorded
    dashpot = float(np.sum(0.5 * (power[1:] + power[:-1]) * np.diff(t)))
    return {"input": work_in, "kinetic": float(kinetic), "story": float(story),
            "gravity": gravity_work, "story_dashpot": dashpot,
            "foundation": work_in - kinetic - story + gravity_work - dashpot}
