"""upliftlab.continuum: a plane-strain soil domain (scikit-fem) under a rigid footing with
unilateral contact and soil plasticity, and its static analyses.

Conventions are the reduced model's, so one scene runs in both: x right, y up, surface y = 0,
soil y < 0. The footing has three DOFs q = (u, v, θ) at the centre of its base; a base point at
x moves by (u, v − xθ) (θ > 0 pushes the right edge down). The contact carries H (+x), N
(compression) and M (about the base centre, + resisting +θ); the work-conjugate generalised
force of q is (H, −N, M). Forces are per unit length out of plane, in the scene's units.

Model and state
    :func:`build_model` (scene) and :func:`make_model` (soil, B, options) give a
    :class:`ContinuumModel`; :func:`geostatic` its initial :class:`ContinuumState` (K0 stress).
Analyses (results are frozen records with ``save()`` to NetCDF)
    :func:`footing_stiffness` -> :class:`FootingStiffness` (elastic, full contact);
    :func:`vertical_pushover`, :func:`rotation_pushover`, :func:`moment_pushover`
    -> :class:`StaticPath`; :func:`uplift_onset` -> :class:`UpliftOnset`;
    :func:`vm_envelope` -> :class:`Envelope`; :func:`sway_pushover` -> :class:`StaticPath`
    and :func:`vh_envelope` -> :class:`SwayEnvelope` (an interface that carries shear);
    :func:`combined_pushover` -> :class:`StaticPath` and :func:`hm_envelope` ->
    :class:`HMEnvelope` (the H–M section at constant V, by radial probes in (u, B θ));
    :func:`run_dynamic` (gravity, then a ground
    motion; explicit central differences by default, or HHT-α / Newmark with Newton
    (``continuum.dynamics``); Lysmer boundaries, rigid or compliant base, SDOF superstructure)
    with :class:`DynamicOptions` -> :class:`DynamicResult`; :func:`estimate_error` (the same
    run on the next coarser mesh or two, each peak with its estimated discretisation error)
    -> :class:`MeshErrorEstimate`;
    :func:`.impedance.analysis.impedance` (the footing's complex impedance per unit length in
    the frequency domain, PML or Lysmer box) with :class:`ImpedanceOptions` on
    :func:`impedance_model` -> :class:`Impedance`.
Independent references
    :mod:`.impedance.halfplane` (the exact impedance of the rigid strip on the half-plane, no
    FE code), :mod:`.impedance.gazetas` (the handbook formulas of Gazetas 1991).
Solver
    :func:`equilibrium` (one Newton step to a :class:`Control`), :func:`follow` (a load path
    with step cutting), :func:`footing_tangent` (dF/dq), :class:`NewtonOptions`,
    :class:`ConvergenceError`, :class:`ContactError`; :class:`SoilTerm` and
    :class:`FootingTerm` add affine terms (inertia, dashpots, a superstructure) for dynamics.
Pieces, by subpackage
    the model itself: :mod:`.model`, :mod:`.assembly` (B-matrices, einsum Bᵀ D B into a fixed
    CSR pattern), :mod:`.condensation` (the DOF blocks, the soil condensed on the footing);
    :mod:`.materials` (the soil models' return maps, pure functions, and their compiled
    Mohr–Coulomb point return); :mod:`.contact` (the rigid footing's kinematics and contact
    solver, and its contact in one explicit step); :mod:`.statics` (Newton, the initial
    geostatic state, the static analyses and their records); :mod:`.dynamics` (the entry point
    :mod:`.dynamics.run`, options, result, waves, ground motion, the superstructure, the
    implicit HHT-α route and the explicit central-difference route with its compiled loop,
    and :mod:`.dynamics.run_control`: energy check, interruption, and :class:`BearingFailure`);
    :mod:`.impedance` (the harmonic analysis, the PML, its references and its output);
    :mod:`.output` (soil fields, XDMF series for ParaView, labelled datasets, summaries).
"""

#: The continuum model's revision: part of the key of every stored record made with it
#: (:mod:`upliftlab.comparisons.framework.store`). Raise it on purpose, in the commit that changes
# the
#: model's numbers, so that stored records of the old numbers are no longer read; an edit that
#: changes no number leaves it (stored records are then checked by a re-run sample instead).
REVISION = 1


from .dynamics.run import DynamicOptions, DynamicResult, run_dynamic
from .contact.footing import (OPEN, SLIP_NEGATIVE, SLIP_POSITIVE, STICK, ContactError, Footing,
                              Interface)
from .impedance.analysis import Impedance, ImpedanceOptions, impedance_model
from .model import ContinuumModel, build_model, default_k0, make_model
from .statics.newton import (ContinuumState, Control, ConvergenceError, FootingTerm, NewtonOptions,
                             SoilTerm, equilibrium, follow, footing_tangent)
from .dynamics.run_control import BearingFailure
from .dynamics.error_estimate import estimate_error
from .dynamics.mesh_error import MeshErrorEstimate
from .statics.analyses import (Envelope, FootingStiffness, StaticPath, UpliftOnset,
                               elastic_gravity_stress, footing_stiffness, geostatic, k0_stress,
                               moment_pushover, rotation_pushover, uplift_onset, vertical_pushover,
                               vm_envelope)
from .statics.combined import HMEnvelope, combined_pushover, hm_envelope
from .statics.sway import SwayEnvelope, sway_pushover, vh_envelope

__all__ = [
    "REVISION",
    "ContinuumModel", "build_model", "make_model", "default_k0",
    "ContinuumState", "Control", "NewtonOptions", "ConvergenceError", "ContactError",
    "BearingFailure",
    "FootingTerm", "SoilTerm", "equilibrium", "follow", "footing_tangent",
    "Footing", "Interface", "OPEN", "STICK", "SLIP_POSITIVE", "SLIP_NEGATIVE",
    "geostatic", "k0_stress", "elastic_gravity_stress",
    "FootingStiffness", "footing_stiffness",
    "StaticPath", "vertical_pushover", "rotation_pushover", "moment_pushover",
    "UpliftOnset", "uplift_onset", "Envelope", "vm_envelope",
    "sway_pushover", "SwayEnvelope", "vh_envelope",
    "combined_pushover", "HMEnvelope", "hm_envelope",
    "DynamicOptions", "DynamicResult", "run_dynamic", "estimate_error", "MeshErrorEstimate",
    "Impedance", "ImpedanceOptions", "impedance_model",
]
