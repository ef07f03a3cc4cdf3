"""Records and codes of the compiled kernels: the spring record and its history, the modes,
status codes, and the slots of the frame, the peaks, the counters and the law tables.

Spring parameters are a structured array (:data:`SPRING_DTYPE`), one record per spring, and the
spring history another (:data:`HISTORY_DTYPE`). Records keep the laws readable (``p.k``,
``h.ep``) and fast: unlike array rows they carry no reference count. Each spring carries its
column of A in its record (``nnz`` entries ``a0…a2`` at DOFs ``i0…i2``): every spring touches
two or three DOFs, so e = Aᵀq and the nodal forces A s are gathered and scattered per spring.

Status codes: ``OK``; ``CHATTER`` too many switches in one step; ``NONFINITE`` a non-finite
state; ``NO_CONVERGENCE`` Newton did not converge; ``OVERTURNED`` past the toppling angle (the
run ends there, a result); ``STEP_UNDERFLOW`` the error control cut the step to round-off.
"""

from __future__ import annotations

import numpy as np


try:  # numba's own switch for helpers that never allocate (numba.core.options.DefaultOptions)
    from numba.core.options import DefaultOptions as _DefaultOptions
    HOT = {"_nrt": False} if hasattr(_DefaultOptions, "_nrt") else {}
except ImportError:  # pragma: no cover
    HOT = {}


SPRING_DTYPE = np.dtype([
    ("kind", np.int64),   # STORY, UPLIFT or BONDED
    ("nnz", np.int64),    # how many DOFs the spring connects (its column of A): 2 or 3
    ("i0", np.int64), ("i1", np.int64), ("i2", np.int64),          # their indices in q
    ("a0", np.float64), ("a1", np.float64), ("a2", np.float64),    # and the entries of A
    ("k", np.float64),    # stiffness (story: its elastic-plastic part) (force/length)
    ("c", np.float64),    # parallel dashpot (force·s/length)
    ("cimp", np.float64),  # impact dashpot c* (force·s/length)
    ("f0", np.float64),   # static compression F0 (force)
    ("fy", np.float64),   # yield force (force; inf = elastic)
    ("kh", np.float64),   # parallel hardening stiffness of a story (force/length)
    ("dzf", np.float64),  # impact stroke per unit closing velocity, m_eff (1 − ε)/c* (s)
    ("x", np.float64),    # position under the base (length)
    ("imph", np.float64),  # largest stable RK4 step while the impact dashpot acts (s)
    ("d0", np.float64),   # derived: δ0 = F0/k (length)
    ("dy", np.float64),   # derived: Fy/k (length)
    ("gs", np.float64),   # derived: 1/F0 (story: 1/Fy; 0 if elastic) (1/force)
    ("gd", np.float64),   # derived: 1/δ0 (1/length)
    ("share", np.float64),  # derived: c*/(c + c*), the impact dashpot's share
    ("arm", np.float64),  # story: its height above the story below, the lever of its shear
    # q–z springs (kind QZ, :mod:`.qz_law`); zero for the other kinds
    ("qult", np.float64),  # bearing capacity of the spring q_ult (force)
    ("zref", np.float64),  # near-field reference displacement of the hyperbola (length)
    ("npow", np.float64),  # exponent n of the near-field hyperbola (> 1)
    ("elast", np.float64),  # initial half-width of the near-field elastic range / q_ult
    ("emax", np.float64),  # largest width of the near-field elastic range / q_ult
    ("qd", np.float64),    # drag (suction) capacity of the gap, suction · q_ult (force)
    ("zd", np.float64),    # drag reference displacement z50/2 (length)
    ("zs", np.float64),    # total compression of the spring at static equilibrium (length)
], align=True)

HISTORY_DTYPE = np.dtype([
    ("ep", np.float64),   # plastic deformation: settlement, or plastic story drift (length)
    ("imp", np.float64),  # 1 while the impact dashpot acts, else 0
    ("e0", np.float64),   # deformation at the last recontact (length)
    ("dz", np.float64),   # impact stroke Δz of the last recontact (length)
    # q–z springs (:mod:`.qz_law`): the committed state of the series chain
    ("zc", np.float64),   # total compression z (length)
    ("qc", np.float64),   # force Q (force)
    ("zp", np.float64),   # near-field plastic displacement (length)
    ("qr", np.float64),   # near-field elastic range: upper end (force)
    ("ql", np.float64),   # near-field elastic range: lower end (force)
    ("zin", np.float64),  # near-field plastic displacement at the range's ends (length)
    ("wel", np.float64),  # near-field elastic range width (force)
    ("zg", np.float64),   # gap displacement, 0 closed, < 0 open (length)
    ("qg", np.float64),   # drag force (force)
    ("qa", np.float64),   # drag branch anchor: force (force)
    ("za", np.float64),   # drag branch anchor: gap displacement (length)
], align=True)

STORY, UPLIFT, BONDED, QZ = 0, 1, 2, 3  # QZ: hysteretic q–z spring (:mod:`.qz_law`)
SEPARATED, CONTACT, YIELDING, CLIPPED = 0, 1, 2, 3  # foundation modes
ELASTIC, YIELD_POS, YIELD_NEG = 0, 1, 2  # story modes

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
N_PEAK_SCALARS = 14

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

OK, CHATTER, NONFINITE, NO_CONVERGENCE, OVERTURNED, STEP_UNDERFLOW = 0, 1, 2, 3, 4, 5
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
#   SYSTEM   (minv, P, KG, L, ag, dtg, weight, frame, story): the scene as the kernels see it:
#            inverse masses, spring records, K_G, ground load, ground acceleration (samples dtg
#            apart), the weight on the foundation, the frame and the story table (h, m, W).
#   OUTPUTS  (time, q, q̇, e, f, mode, εp, energy): the stored states, one row each.
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
