"""Codes of the compiled kernels: the slots of the frame, the peaks, the counters and the law
tables, status codes; and, from :mod:`upliftlab.reduced.laws`, the spring record and its
history, the spring kinds and the modes.

Spring parameters are a structured array (:data:`SPRING_DTYPE`), one record per spring, and the
spring history another (:data:`HISTORY_DTYPE`); their fields are described in
:mod:`upliftlab.reduced.laws.spring` (and each law's own in its module).

Status codes: ``OK``; ``CHATTER`` too many switches in one step; ``NONFINITE`` a non-finite
state; ``NO_CONVERGENCE`` Newton did not converge; ``OVERTURNED`` past the toppling angle (the
run ends there, a result); ``STEP_UNDERFLOW`` the error control cut the step to round-off;
``BASE_FAILED`` a step of the base element could not be completed (why: its status, in the
element's record, :mod:`.base`).
"""

from __future__ import annotations

from ..laws import HISTORY_DTYPE, SPRING_DTYPE  # noqa: F401
from ..laws.elastoplastic import BONDED, UPLIFT  # noqa: F401
from ..laws.qz.compiled import QZ  # noqa: F401
from ..laws.spring import (CLIPPED, CONTACT, ELASTIC, HOT, SEPARATED, STORY,  # noqa: F401
                           YIELD_NEG, YIELD_POS, YIELDING)

# energy accumulators and output columns
E_INPUT, E_VISCOUS, E_IMPACT, E_PLASTIC = range(4)
N_ACC = 4
N_ENERGY = 7  # input, kinetic, strain, gravity, viscous, impact, plastic
# peaks: scalars, then two per spring. P_MOT the largest |overturning moment| Σ arm·shear of
# the stories; P_CMIN the least contact length of the base; P_ERES the largest |residual| of
# the energy balance, P_ESCALE its scale (the largest |input| and the initial energy) and
# P_ETOT0 the balance's value at the start (stored + dissipated − input)
P_UMIN, P_UMAX, P_THMIN, P_THMAX, P_VMIN, P_VMAX = range(6)
P_MOT, P_CMIN, P_ERES, P_ESCALE, P_ETOT0 = range(6, 11)
# toppling: the overturning ratio and time at the last accepted state, and the time at which
# the ratio reached 1 (interpolated linearly between the last two accepted states)
P_RPREV, P_TPREV, P_TOVER = range(11, 14)
# a base element (:mod:`.base`): the larger gap under its edges, its largest |u − u_rest| and
# |H| (its forces without the dashpots), the gap under its left edge (x = −b), at the steps'
# ends
P_BGAP, P_BU, P_BH, P_BGAPL = range(14, 18)
N_PEAK_SCALARS = 18

# the frame: constants of the scene's geometry and kinematics that every integrator takes (one
# float array), and the pivot side of exact kinematics (the one entry that changes in a run)
F_B = 0        # half-width b of the base (0: no foundation, nothing to overturn)
F_ECHECK = 1   # steps between checks of the energy balance
F_EXACT = 2    # 1: exact rocking kinematics (q holds sin θ), 0: small rotations
F_WTOT = 3     # weight whose centre decides overturning: the stories' and the base's
F_MB = 4       # mass of the base body at O beyond the stories' (exact kinematics)
F_IB = 5       # rotary inertia of the base body about O (exact kinematics)
F_SIDE = 6     # exact kinematics: the edge the base rocks about, +1 or −1
F_ITH = 7      # index of θ (or sin θ) in q, −1 if the base is fixed
F_IV = 8       # index of V in q
F_NFLEX = 9    # story DOFs in q (0 for a rigid structure)
F_RTOL = 10    # event stepper: relative tolerance of its error control (0: fixed steps)
F_HMAX = 11    # event stepper: the largest step it takes (s)
F_H0 = 12      # event stepper: its first trial step under error control (s)
F_OUTDT = 13   # event stepper under error control: spacing of the stored states (s), which it
               # interpolates within its steps (0: every ``stride`` steps)
F_ISWAY = 14   # index of the base's horizontal DOF u_b in q for a flexible structure on a
               # sway spring (the story DOFs are then relative to the ground, the base's too);
               # −1 otherwise (no sway, or a rigid structure, whose sway DOF is its centre's)
N_FRAME = 15

OK, CHATTER, NONFINITE, NO_CONVERGENCE, OVERTURNED, STEP_UNDERFLOW, BASE_FAILED = range(7)
# counters: [0] steps cut at a switch (events) or the failing step, [1] switches or halvings,
# [2] right-hand sides or Newton iterations, [3] impacts logged, [4] output rows written,
# [5] trial steps rejected by the error control
N_COUNTERS = 6
SWITCH_TOL = 1e-12
OVERSHOOT_TOL = 1e-6
# A condition is computed from e, which carries an absolute rounding error ~ eps·|e|: for a
# very stiff spring (δ0 of micrometres under a settlement of centimetres) that exceeds
# SWITCH_TOL once scaled by 1/δ0. ROUNDING · (the size of the condition's terms) is allowed on
# top of SWITCH_TOL, the same in the crossing search and in the switch, so the two never
# disagree about a spring that sits on its limit.
ROUNDING = 32.0 * 2.220446049250313e-16
N_SAMPLES = 4

# Records that travel through the kernels as tuples (numba passes a tuple of arrays at no cost,
# and unpacks it into names):
#   SYSTEM   (minv, P, KG, L, ag, dtg, weight, frame, story, base): the scene as the kernels
#            see it: inverse masses, spring records, K_G, ground load, ground acceleration
#            (samples dtg apart), the weight on the foundation, the frame, the story table
#            (h, m, W) and the base element (:mod:`.base`; its parameters empty: none).
#   OUTPUTS  (time, q, q̇, e, f, mode, εp, energy, base): the stored states, one row each
#            (base: the base element's, N_BASE_OUT columns, or none).
#   STAGES   (k1, k2, k3, k4, qs, q̇s, q1, q̇1, acc1, Mw): an RK4 step's stages, its stage
#            state, its end and the mass matrix of exact kinematics.
#   BOOKS    (modes, H, e_ref, e, ė): what the bookkeeping reads of the springs: their modes,
#            history, strain energy at rest, and scratch for their deformations.
#   CLOCK    (dt, nsteps, stride): the macro step, how many, and every how many a row is stored.
#   NEWTON   (tol, fscale, max_iter) of the implicit integrators' Newton iteration.


T_A0, T_A1 = 0, 1           # entries of A on the two shared DOFs (bed table only)
T_K, T_C, T_F = 2, 3, 4      # force conjugate to e: T_K e + T_C ė + T_F
T_V, T_I = 5, 8              # viscous, impact power: (T[r] + T[r + 1] e + T[r + 2] ė) ė
T_P = 11                     # plastic power: T_P ė
T_COND = 12                  # condition k (:func:`condition`): α, β, γ in rows T_COND + 3k
N_CONDITIONS = 4
T_GAP, T_KC, T_FY = 24, 25, 26  # foundation peaks: gap T_GAP − e, force min(T_KC d, T_FY)
N_ROWS = 27
FAST = {"reassoc", "contract"}  # lets the compiler regroup sums into SIMD lanes


MAX_DEPTH = 24      # subdivision depth of the crossing search (2⁻²⁴ of a step)
MAX_PIECES = 4096   # pieces it visits at most
