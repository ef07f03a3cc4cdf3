"""The beds calibrated from the continuum, one registry of bed builders (the Winkler map
compares them all, the advisor checks them on a scene).

A bed builder is ``build(reference, options) -> foundation table``: from the continuum's
reference numbers of one point of the map (:class:`BedReference`: N, B, h, the continuum's K_v,
K_r and vertical capacity of the soil) and the study's options, the reduced model's
``[foundation]`` table of that bed. :data:`BEDS` maps a calibration's name to its
:class:`BedEntry`; a new calibration (a sway spring, impedance dashpots, hysteretic q–z springs)
plugs into the map by adding one entry here (and, if it needs a continuum quantity that is not
yet in :class:`BedReference`, one static analysis in the map's
:mod:`~upliftlab.comparisons.studies.winkler_map.statics`).

Eleven entries today. Four are the base beds of :mod:`.stiffness`, which the Winkler-against-
continuum study compares too (built by :func:`.stiffness.calibrate`, so that both studies build
the same beds):
``uniform`` to K_r, ``end_stiffened`` to K_r and K_v (when some R_k reaches it), and both with
elasto-plastic springs that yield at FS_v times their static force, FS_v = V_ult/N
(``uniform_plastic``, ``end_stiffened_plastic``). Three add what those lack: radiation
dashpots from Gazetas' strip formulas (``uniform_plastic_gazetas``) or from the continuum's own
impedance (``uniform_plastic_impedance``, :mod:`.dashpots`), and hysteretic q–z springs
fitted to the continuum's whole vertical pushover (``qz``, :mod:`.qz.bed`).
``end_stiffened_plastic_impedance`` gives the end-stiffened elasto-plastic bed the impedance
dashpots too; ``end_stiffened_fitted_impedance`` fits its capacity profile to the rotation
pushovers; ``macro`` is no bed of springs but the macro-element (:mod:`.macro_bed`), fitted
once per soil to the continuum's statics (:mod:`.macro`, a stored fit of the map).
``end_stiffened_bearing`` keeps its springs but lets each yield at the soil's one bearing
pressure V_ult/B over its tributary width, the convention of beam-on-nonlinear-Winkler
practice, where ``end_stiffened_plastic`` yields each spring at FS_v times its static force,
which gives the stiffened ends R_k times the middle's pressure capacity.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

from ...checks import InputError
from ...reduced.compatibility import winkler_bed
from .base import BedReference, base_builder, calibration
from .dashpots import build_uniform_plastic_impedance, impedance_dashpots_of
from .fitted import build_end_stiffened_fitted_impedance
from .macro_bed import build_macro
from .qz.bed import build_qz
from .radiation import distribute, gazetas_dashpots
from .soil_damping import with_soil_damping

__all__ = ["BedReference", "BedEntry", "BEDS", "bed_names", "bed_foundation"]


@dataclass(frozen=True)
class BedEntry:
    """One calibration: ``name`` (a coordinate of the map), ``label`` (text),
    ``build(reference, options) -> [foundation] table``, ``matches`` the continuum
    quantities it is calibrated to (text), and ``needs`` the stored continuum quantities beyond
    the statics that the map must compute for it (``impedance``: the soil's dynamic impedance,
    the map's :mod:`~upliftlab.comparisons.studies.winkler_map.impedance_points`); ``short`` its
    abbreviation in tables and figures; ``references`` the map's continuum references it
    stands on (the macro-element only on the half-plane, whose footing sways on a tie: the
    element carries the base's horizontal force, and the box holds its footing)."""

    name: str
    label: str
    build: Callable
    matches: str
    needs: tuple[str, ...] = ()
    short: str = ""
    references: tuple[str, ...] = ("box", "half_plane")


def build_uniform_plastic_gazetas(reference: BedReference, options) -> dict:
    """The ``uniform_plastic`` bed with the handbook's radiation dashpots: the strip's C_v and
    C_r of Gazetas (ρ V_La B and ρ V_La B³/12, frequency-independent) distributed over its
    springs so that Σ c_i = C_v and Σ c_i x_i² = C_r (:func:`.radiation.distribute`); the soil's
    density comes in ``reference.extra["density"]`` (mass/length³)."""
    table = calibration(reference, options, "uniform_plastic").foundation_table()
    density = reference.extra.get("density", 0.0)
    if not density > 0.0:
        raise InputError(f"soil.density = {density!r}: the handbook's radiation dashpots need "
                         "the soil's density; valid range is > 0")
    C_v, _, C_r = gazetas_dashpots(shear_modulus=reference.G, poisson=reference.nu,
                                   density=density, width=reference.B)
    layout = winkler_bed(0.5 * reference.B, 1.0, table["springs"])
    dashpots, *_ = distribute(layout.positions, layout.widths, C_v, C_r)
    table["dashpots"] = [float(c) for c in dashpots]
    return table


def build_end_stiffened_bearing(reference: BedReference, options) -> dict:
    """The ``end_stiffened_plastic`` bed with a uniform bearing capacity: the same springs
    (K_r, and K_v where reachable), each yielding at the bearing pressure V_ult/B over its
    tributary width (``capacity_multiple`` = V_ult/N) instead of FS_v times its own static
    force. The stiffened ends then carry no more pressure than the middle before they yield,
    as the soil under a footing's edge does not, and the bed's moment capacity under N is the
    stress block's N B/2 (1 − N/V_ult) (the practice of beam-on-nonlinear-Winkler models:
    Harden et al. 2005, Raychowdhury and Hutchinson 2009, and ASCE 41's end zones, where the
    stiffness is stiffened and the capacity is q_ult over each spring's area)."""
    table = calibration(reference, options, "end_stiffened_plastic").foundation_table()
    table.pop("yield_multiple")
    table["capacity_multiple"] = reference.V_ult / reference.N
    return table


def build_end_stiffened_plastic_impedance(reference: BedReference, options) -> dict:
    """The ``end_stiffened_plastic`` bed with the dashpots of the continuum's impedance at the
    point's rocking frequency (:mod:`.dashpots`: Σ c_i = C_v, Σ c_i x_i² = C_r)."""
    table = calibration(reference, options, "end_stiffened_plastic").foundation_table()
    table["dashpots"] = list(impedance_dashpots_of(reference, options).dashpots)
    return table


BEDS: dict[str, BedEntry] = {
    "uniform": BedEntry("uniform", "uniform bed (K_r)", base_builder("uniform"), "K_r",
                         short="U"),
    "end_stiffened": BedEntry("end_stiffened", "end-stiffened bed (K_r, K_v)",
                              base_builder("end_stiffened"), "K_r and K_v where reachable",
                              short="ES"),
    "uniform_plastic": BedEntry("uniform_plastic", "uniform elasto-plastic bed (K_r, V_ult)",
                                base_builder("uniform_plastic"), "K_r and V_ult", short="U-p"),
    "end_stiffened_plastic": BedEntry("end_stiffened_plastic",
                                      "end-stiffened elasto-plastic bed (K_r, K_v, V_ult)",
                                      base_builder("end_stiffened_plastic"),
                                      "K_r, K_v where reachable, and V_ult", short="ES-p"),
    "uniform_plastic_gazetas": BedEntry(
        "uniform_plastic_gazetas", "uniform elasto-plastic bed with Gazetas' dashpots",
        build_uniform_plastic_gazetas, "K_r, V_ult, and the handbook strip's C_v and C_r",
        short="U-p-G"),
    "uniform_plastic_impedance": BedEntry(
        "uniform_plastic_impedance", "uniform elasto-plastic bed with the continuum's impedance "
        "dashpots", build_uniform_plastic_impedance,
        "K_r, V_ult, and the FE impedance's C_v and C_r at the rocking frequency",
        needs=("impedance",), short="U-p-I"),
    "qz": BedEntry("qz", "hysteretic q–z bed fitted to the vertical pushover", build_qz,
                   "K_r, K_v where reachable, V_ult, and the whole vertical pushover",
                   short="qz"),
    "end_stiffened_bearing": BedEntry(
        "end_stiffened_bearing", "end-stiffened elasto-plastic bed, uniform bearing capacity",
        build_end_stiffened_bearing,
        "K_r, K_v where reachable, and V_ult as a uniform bearing pressure", short="ES-b"),
    "end_stiffened_plastic_impedance": BedEntry(
        "end_stiffened_plastic_impedance", "end-stiffened elasto-plastic bed with the "
        "continuum's impedance dashpots", build_end_stiffened_plastic_impedance,
        "K_r, K_v where reachable, V_ult, and the FE impedance's C_v and C_r at the rocking "
        "frequency", needs=("impedance",), short="ES-p-I"),
    "end_stiffened_fitted_impedance": BedEntry(
        "end_stiffened_fitted_impedance", "end-stiffened elasto-plastic bed, capacity profile "
        "fitted to the continuum's rocking, with its impedance dashpots",
        build_end_stiffened_fitted_impedance,
        "K_r, K_v where reachable, V_ult, the capacity profile to the rotation pushovers, and "
        "the FE impedance's C_v and C_r at the rocking frequency", needs=("impedance",),
        short="ES-f-I"),
    "macro": BedEntry(
        "macro", "macro-element calibrated to the continuum's statics", build_macro,
        "K_v, K_r, the capacity's form to the monotonic pushovers' largest moments, and the "
        "plastic parameters to every rotation pushover of the soil (its moment and settlement)",
        needs=("macro",), short="ME", references=("half_plane",)),
}


def bed_names(options) -> tuple[str, ...]:
    """The calibrations a run compares: ``options.beds``, or every registered one that stands
    on ``options.reference``; a named bed that does not is refused (InputError)."""
    reference = getattr(options, "reference", "box")
    for name in options.beds:
        if name in BEDS and reference not in BEDS[name].references:
            raise InputError(f"options.beds: {name!r} with options.reference = {reference!r}: "
                             f"it stands only on {', '.join(BEDS[name].references)}; valid "
                             "beds here: " + ", ".join(n for n, e in BEDS.items()
                                                        if reference in e.references))
    return tuple(options.beds) or tuple(n for n, e in BEDS.items() if reference in e.references)


def bed_foundation(name: str, reference: BedReference, options,
                   soil_beta: float | None = None) -> dict:
    """The ``[foundation]`` table of calibration ``name`` at ``reference``: the uplifting
    support, its half-width and whatever the builder sets; with ``soil_beta`` β (s; None: off,
    the default) the soil's Rayleigh dashpots β k_i beside its springs
    (:mod:`.soil_damping`)."""
    table = dict(BEDS[name].build(reference, options))
    table.setdefault("support", "uplift")
    table.setdefault("half_width", 0.5 * reference.B)
    return with_soil_damping(table, soil_beta)
