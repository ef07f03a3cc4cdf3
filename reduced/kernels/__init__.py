"""Compiled spring laws and time-stepping loops of the reduced model (numba, ``cache=True``).

Every parameter is passed as an argument; nothing is global. Each integrator is a plain Python
function compiled by numba, and its ``.py_func`` is the interpreted reference implementation.
The package is split by what a reader looks for:

- :mod:`.codes` status codes, slots of the frame, peaks, counters and law tables (and, from
  :mod:`upliftlab.reduced.laws`, the spring record and history, kinds and modes);
- :mod:`.laws` every compiled form of the spring laws, dispatched on a spring's kind to the
  story spring's forms here or to the foundation law's, each beside its law in
  :mod:`upliftlab.reduced.laws`;
- :mod:`.base` a base element (the macro-element): one law on the base's three DOFs;
- :mod:`.motion` the equation of motion, :mod:`.rocking` exact rocking kinematics and toppling;
- :mod:`.tables` the laws tabulated by mode (event stepper), :mod:`.stages` Runge–Kutta stages;
- :mod:`.interpolants`, :mod:`.crossing`, :mod:`.switches` switch location;
- :mod:`.peaks`, :mod:`.energy`, :mod:`.outputs` bookkeeping;
- :mod:`.events`, :mod:`.fixed_step`, :mod:`.implicit` the integrators (listed, with their order
  and stability, in :data:`upliftlab.reduced.integrators.METHODS`).

numba keys a cached function on its own source file only, so an edit to a law would leave the
integrators compiled from it stale in the cache; :mod:`upliftlab` keys the cache folder on a
digest of this package's and the laws' sources instead
(:func:`upliftlab._numba_cache_outside_the_package`).
"""

from .codes import (BASE_FAILED, BONDED, CHATTER, CLIPPED, CONTACT, ELASTIC, E_IMPACT, E_INPUT,
                    E_PLASTIC, E_VISCOUS, FAST, F_B, F_ECHECK, F_EXACT, F_H0, F_HMAX, F_IB,
                    F_ISWAY, F_ITH, F_IV, F_MB, F_NFLEX, F_OUTDT, F_RTOL, F_SIDE, F_WTOT,
                    HISTORY_DTYPE, HOT, MAX_DEPTH, MAX_PIECES, NONFINITE, NO_CONVERGENCE, N_ACC,
                    N_CONDITIONS, N_COUNTERS, N_ENERGY, N_FRAME, N_PEAK_SCALARS, N_ROWS, N_SAMPLES,
                    OK, OVERSHOOT_TOL, OVERTURNED, P_BGAP, P_BGAPL, P_BH, P_BU, P_CMIN, P_ERES,
                    P_ESCALE, P_ETOT0, P_MOT, P_RPREV, P_THMAX, P_THMIN, P_TOVER, P_TPREV, P_UMAX,
                    P_UMIN, P_VMAX, P_VMIN, QZ, ROUNDING, SEPARATED, SPRING_DTYPE, STEP_UNDERFLOW,
                    STORY, SWITCH_TOL, T_A0, T_A1, T_C, T_COND, T_F, T_FY, T_GAP, T_I, T_K, T_KC,
                    T_P, T_V, UPLIFT, YIELDING, YIELD_NEG, YIELD_POS)
from .laws import (commit_all, commit_step, condition, current_plastic, force_in_mode,
                   from_history, initial_modes, law, natural_mode, past_limit, spring_state,
                   switch_mode, tangent, trial_force, trial_mode, validity)
from ..laws.qz.compiled import (qz_backbone, qz_commit, qz_force, qz_mode, qz_spring_state,
                                qz_start, qz_trial)
from .base import (C_CH, C_CV, C_D0, C_DF, C_E0, C_NEGATIVE, C_Q0, C_STATUS, N_BASE_OUT, N_C,
                   base_energy, base_force, base_gap, commit_base, contact_moments,
                   record_base, track_base)
from .motion import (accelerations, deformation, deformations, geometric_or_nothing,
                     ground_acceleration, rates)
from .rocking import (exact_dynamics, exact_energy, finish_accelerations, overturn_ratio, pivot,
                      solve_spd)
from .tables import (bed_forces, bed_rates, bed_start, bed_state, frozen_accelerations, law_tables,
                     tabulate, write_column)
from .stages import (advance, copy, error_ratio, frozen_rk4_step, note_magnitudes, rk4_combine,
                     rk4_stage_state, rk4_step)
from .interpolants import (chord_deviation, finite, hermite, hermite_extreme, hermite_stationary,
                           quintic, quintic_at)
from .crossing import (bernstein, condition_crossing, condition_polynomial, place_switch,
                       polynomial_at, restricted)
from .switches import (apply_switches, bed_margins, column_crossing, column_margin,
                       condition_bound, first_crossing, impact_step_cap, log_impact, relocate,
                       spring_quintic)
from .peaks import (after_fixed_step, after_step, bed_contact_length, bed_peaks, segment_contact,
                    springs_contact_length, start_side, story_peaks, toppled, track_peaks)
from .energy import (check_energy, energy_balance, kinetic_gravity, start_energy,
                     static_strain_energy)
from .outputs import output_row, record, record_between, stop_row
from .events import integrate_events, march_events
from .fixed_step import end_fixed_step, integrate_abm4, integrate_rk4, march_abm4, march_rk4
from .implicit import (integrate_newmark, internal_force, newmark_jacobian, newmark_residual,
                       newmark_substep)

__all__ = ["BASE_FAILED", "P_BGAP", "P_BGAPL", "P_BH", "P_BU", "C_CH", "C_CV", "C_D0", "C_DF",
           "C_E0", "C_NEGATIVE", "C_Q0", "C_STATUS", "N_BASE_OUT", "N_C", "base_energy",
           "base_force", "base_gap", "commit_base", "contact_moments", "record_base", "track_base",
           "BONDED", "CHATTER", "CLIPPED", "CONTACT", "ELASTIC", "E_IMPACT", "E_INPUT",
           "E_PLASTIC", "E_VISCOUS", "FAST", "F_B", "F_ECHECK", "F_EXACT", "F_H0", "F_HMAX",
           "F_IB", "F_ISWAY", "F_ITH", "F_IV", "F_MB", "F_NFLEX", "F_OUTDT", "F_RTOL",
           "F_SIDE", "F_WTOT",
           "HISTORY_DTYPE", "HOT", "MAX_DEPTH", "MAX_PIECES", "NONFINITE", "NO_CONVERGENCE",
           "N_ACC", "N_CONDITIONS", "N_COUNTERS", "N_ENERGY", "N_FRAME", "N_PEAK_SCALARS",
           "N_ROWS", "N_SAMPLES", "OK", "OVERSHOOT_TOL", "OVERTURNED", "P_CMIN", "P_ERES",
           "P_ESCALE", "P_ETOT0", "P_MOT", "P_RPREV", "P_THMAX", "P_THMIN", "P_TOVER", "P_TPREV",
           "P_UMAX", "P_UMIN", "P_VMAX", "P_VMIN", "QZ", "ROUNDING", "SEPARATED", "SPRING_DTYPE",
           "STEP_UNDERFLOW", "STORY", "SWITCH_TOL", "T_A0", "T_A1", "T_C", "T_COND", "T_F", "T_FY",
           "T_GAP", "T_I", "T_K", "T_KC", "T_P", "T_V", "UPLIFT", "YIELDING", "YIELD_NEG",
           "YIELD_POS", "commit_all", "commit_step", "condition", "current_plastic",
           "force_in_mode", "from_history", "initial_modes", "law", "natural_mode", "past_limit",
           "spring_state", "switch_mode", "tangent", "trial_force", "trial_mode", "validity",
           "qz_backbone", "qz_commit", "qz_force",
           "qz_mode", "qz_spring_state", "qz_start", "qz_trial", "accelerations", "deformation",
           "deformations",
           "geometric_or_nothing", "ground_acceleration", "rates", "exact_dynamics",
           "exact_energy", "finish_accelerations", "overturn_ratio", "pivot", "solve_spd",
           "bed_forces", "bed_rates", "bed_start", "bed_state", "frozen_accelerations",
           "law_tables", "tabulate", "write_column", "advance", "copy", "error_ratio",
           "frozen_rk4_step", "note_magnitudes", "rk4_combine", "rk4_stage_state", "rk4_step",
           "chord_deviation", "finite", "hermite", "hermite_extreme", "hermite_stationary",
           "quintic", "quintic_at", "bernstein", "condition_crossing", "condition_polynomial",
           "place_switch", "polynomial_at", "restricted", "apply_switches", "bed_margins",
           "column_crossing", "column_margin", "condition_bound", "first_crossing",
           "impact_step_cap", "log_impact", "relocate", "spring_quintic", "after_fixed_step",
           "after_step", "bed_contact_length", "bed_peaks", "segment_contact",
           "springs_contact_length", "start_side", "story_peaks", "toppled", "track_peaks",
           "check_energy", "energy_balance", "kinetic_gravity", "start_energy",
           "static_strain_energy", "output_row", "record", "record_between", "stop_row",
           "integrate_events", "march_events", "end_fixed_step", "integrate_abm4", "integrate_rk4",
           "march_abm4", "march_rk4", "integrate_newmark", "internal_force", "newmark_jacobian",
           "newmark_residual", "newmark_substep"]
