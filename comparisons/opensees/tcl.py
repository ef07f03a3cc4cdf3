"""A macro-element scene for users of Tcl OpenSees: Gajan and Kutter's contact interface model
(``soilFootingSection2d``) under the same structure, and where the two models correspond
(issue 36 §4).

``model.tcl`` is the same file for every scene (the package's :file:`soil_footing.tcl`, written
unchanged): no text of a scene can become code. The scene enters as numbers only, in
``model_numbers.txt`` (``name value`` per line, each value a Python float's ``repr``; the
script checks every one is a number before it builds anything), the ground acceleration in
``motion_g.txt`` (g, one value per line at the record's step) and the correspondence in
``model.md``.

The section's seven numbers from the element (:func:`tcl_numbers`): FS = V_ult/W_v and
V_ult the element's central capacity (the section takes the vertical load to be V_ult/FS);
L = B; Kv = 12 K_r/L² with K_r the element's rocking stiffness (:func:`section_kv`); Kh = the
element's K_h; Rv the soil's elastic rebound (no counterpart in the element: :data:`REBOUND`);
dL = L/40, the section's discretisation of the footing. What the section cannot take is said,
with its number, in ``model.md`` (:func:`correspondence`).

Why Kv from K_r: the section rocks on a bed whose modulus is Kv/L² (its contact pressures
grow by Kv/L² per unit of penetration), so its moment at the uplift onset θ = 2 W/(Kv L) is a
uniform bed's, (Kv L²/12) θ, while its vertical stiffness is Kv: one number cannot give both
the element's K_v and K_r (on the half-plane map's points K_r = 4.7 (K_v L²/12)). Measured on
24 pulse points of the half-plane map with the section compiled from OpenSees's source
(``benchmarks/OPENSEES_CONTACT_INTERFACE.md``): with Kv = K_v the median error in peak θ is
113 % and 1 of 24 peak story drifts is within 10 %; with Kv = 12 K_r/L², 30 % and 10 of 24
(and 4 of 24 runs stop on a step that does not converge). Rocking governs what a user reads,
so Kv matches it; the vertical stiffness is then 12 K_r/(K_v L²) times the element's, said
in ``model.md``. The section's M–θ has no linear range at all (a secant of 12.3 Kv L²/12 at
θ_on/100, 4.2 at θ_on/10 and 0.95 at θ_on, measured), and its own ``Kt = Kv L³/12`` is only
its first tangent.

Not run here: no Tcl OpenSees on this machine (openseespy 3.7 has no ``soilFootingSection2d``).
The tests source the script in ``tclsh`` with the OpenSees commands recorded.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from importlib import resources
from pathlib import Path

from ...checks import InputError
from ...reduced import build_model
from ...results import write_text
from ...scenes import Scene

__all__ = ["TclFiles", "REBOUND", "SEGMENTS", "section_kv", "tcl_numbers", "correspondence",
           "write_tcl",
           "check_tcl_representable", "TCL_NAME", "NUMBERS_TXT", "MOTION_G",
           "TCL_NAMES"]

TCL_NAME, NUMBERS_TXT, MOTION_G, NOTES_MD = ("model.tcl", "model_numbers.txt", "motion_g.txt",
                                              "model.md")
#: The section's Rv, the share of the soil's compression that rebounds when the footing lifts
#: off: the element has none (its soil surface rounds instead, λ_ρ), so a choice, stated.
REBOUND = 0.1
#: The section's footing in this many segments (dL = L/SEGMENTS).
SEGMENTS = 40
#: Load steps of the gravity analysis.
GRAVITY_STEPS = 10


@dataclass(frozen=True)
class TclFiles:
    """The files written: the ``script``, its ``numbers``, the ``motion`` (None: free
    vibration) and the ``notes``."""

    script: Path
    numbers: Path
    motion: Path | None
    notes: Path


def check_tcl_representable(scene: Scene) -> None:
    """Refuse, in one line naming the field, a macro-element scene the Tcl model cannot hold."""
    s, m = scene.structure, scene.motion
    if len(s.stories) != 1 or s.rigid:
        raise InputError(f"structure: {len(s.stories)} stories (rigid = {s.rigid}): the Tcl "
                         "model writes one flexible story on the footing; valid: one story")
    if s.kinematics != "small":
        raise InputError(f"structure.kinematics = {s.kinematics!r}: the section is in small "
                         "rotations; valid: 'small'")
    if m.type == "free":
        raise InputError("motion.type = 'free': the Tcl model starts from rest under gravity "
                         "and needs a ground motion; valid: a record or a pulse")


def section_kv(rocking_stiffness: float, width: float) -> float:
    """The section's Kv that gives it a rocking stiffness ``rocking_stiffness`` K_r at its
    uplift onset (module docstring): 12 K_r/L² (force/length per length)."""
    return 12.0 * rocking_stiffness / width ** 2


def tcl_numbers(scene: Scene, dt: float | None = None) -> dict[str, float]:
    """The numbers ``model.tcl`` reads (module docstring), in the scene's units."""
    from .spec import check_step_count, default_step

    check_tcl_representable(scene)
    model = build_model(scene)
    law = model.base.law
    s, f = scene.structure, scene.foundation
    story = s.stories[0]
    k_story = float(model.params["k"][0])
    c_story = float(model.params["c"][0])
    motion = scene.build_motion()
    duration = scene.analysis.duration or motion.duration
    step = default_step(scene, motion) if dt is None else dt
    if not (math.isfinite(step) and 0.0 < step <= duration):
        raise InputError(f"--dt = {step:g}: valid range is (0, {duration:g}] s")
    check_step_count(scene, step, duration)
    return {
        "g": float(scene.g), "story_weight": float(story.weight),
        "vertical_weight": float(s.vertical_weight), "height": float(story.height),
        "story_stiffness": k_story, "story_damping_beta": c_story / k_story,
        "rotary_inertia": float(s.rotary_inertia),
        "FS": float(law.ultimate_load / s.vertical_weight), "Vult": float(law.ultimate_load),
        "L": float(law.width), "Kv": section_kv(float(law.rocking_stiffness), float(law.width)),
        "Kh": float(law.horizontal_stiffness), "Rv": REBOUND, "dL": law.width / SEGMENTS,
        "sway_damping": float(f.sway_damping or 0.0), "dt": float(step),
        "steps": float(math.ceil(duration / step - 1e-9)), "motion_dt": float(motion.dt),
        "motion_points": float(motion.acceleration.size), "has_motion": 1.0,
        "gravity_steps": float(GRAVITY_STEPS),
        "tolerance": 1e-10 * float(law.width), "p_delta": 1.0 if s.p_delta else 0.0}


def correspondence(scene: Scene, numbers: dict) -> str:
    """``model.md``: where the section and the element correspond, and where not, with this
    scene's numbers."""
    law = build_model(scene).base.law
    L, Kv = numbers["L"], numbers["Kv"]
    unit = scene.units
    rows = [
        ("V_ult (central capacity)",
         f"Vult = {numbers['Vult']:.6g} {unit.force}/{unit.length}", "the same (per unit "
         "length of the strip, as every force of the scene)"),
        ("W_v / V_ult", f"FS = {numbers['FS']:.6g}", "the section takes its vertical load to "
         "be Vult/FS and starts its contact from it"),
        ("B", f"L = {L:.6g} {unit.length}", "the same"),
        ("K_r", f"Kv = 12 K_r/L² = {Kv:.6g}", "the section's rocking at its uplift onset "
         "θ = 2 W/(Kv L) is a uniform bed's, (Kv L²/12) θ = K_r θ: Kv is chosen for it. "
         "Its M–θ has no linear range (a secant about 12 times K_r at a hundredth of the "
         "onset, measured), and its own first tangent Kt = Kv L³/12 "
         f"= {Kv * L ** 3 / 12:.6g} is not its rocking stiffness"),
        ("K_v", f"Kv = {Kv:.6g}", f"the section's vertical stiffness is Kv: "
         f"{Kv / law.vertical_stiffness:.3g} times the element's K_v = "
         f"{law.vertical_stiffness:.6g} (one number cannot give both)"),
        ("K_h", f"Kh = {numbers['Kh']:.6g}", "elastic in both; the element's sliding "
         f"capacity is t_h V (1 − V/V_ult), t_h = {law.sliding_ratio:.4g}; the section's "
         "follows its own bounding surface"),
        ("capacity", f"Vult/L = {numbers['Vult'] / L:.6g} per unit length", "the section's "
         "moment capacity is Tresca's, (V L/2)(1 − V/Vult), for every soil (measured within "
         "−0.3…+6.5 % of it at FS 3–10); the element's follows the contact width on a "
         "frictional soil, (V L/2)(1 − √(V/Vult)) with the N_γ term alone"),
        ("λ_ρ (rounding)", f"Rv = {numbers['Rv']:g}", "no counterpart: the section's soil "
         "rebounds by Rv of its compression, the element's surface rounds; Rv is a choice"),
        ("ζ0, κ_ref, h0, γ, χ", "none", "the section's plasticity is its own (the bounding "
         "surface of Gajan and Kutter, a fixed shape in V, H, M): no parameter to map"),
        ("the footing's dashpot (damping_ratio)", "none", "not written: the section has no "
         "dashpot, and one beside it would act in uplift too"),
        ("sway dashpot", f"{numbers['sway_damping']:.6g}", "a horizontal viscous zeroLength "
         "beside the section, as the scene's"),
    ]
    lines = ["# Where Gajan and Kutter's contact interface model corresponds to upliftlab's "
             "macro-element", "",
             "`model.tcl` builds the scene's structure on `soilFootingSection2d` "
             "(Tcl OpenSees only). Written by `upliftlab opensees`; not run by upliftlab.", "",
             "| the element | the section | how they compare |", "|---|---|---|"]
    lines += [f"| {a} | {b} | {c} |" for a, b, c in rows]
    lines += ["", "The story is a shear spring k = 12 E I/h³ on the footing (an elastic column "
              "whose ends rotate together) with a stiffness-proportional dashpot c = β k; the "
              "footing carries the whole vertical mass W_v/g and the rotary inertia about its "
              "centre, the story mass its horizontal mass, as in upliftlab's reduced model.",
              "", "Before the motion, one static step of a horizontal load of 1e-6 of the "
              "story weight is put on and taken off: after a purely vertical load history "
              "the section returns NaN on its first dynamic step.", "",
              "Two properties of the section to know when changing the analysis (both "
              "measured on its compiled source): its initial tangent is a zero matrix, so an "
              "algorithm or a damping on the initial stiffness gets nothing from it; and its "
              "tangent is not symmetric (a coupling of V to θ, none of M to v), so the system "
              "must not be a symmetric one (the script uses UmfPack).", ""]
    return "\n".join(lines)


def _script_text() -> str:
    return resources.files(__package__).joinpath("soil_footing.tcl").read_text(
        encoding="utf-8")


def write_tcl(scene: Scene, out: str | Path, dt: float | None = None) -> TclFiles:
    """Write ``model_numbers.txt``, ``motion_g.txt``, ``model.md`` and ``model.tcl`` into
    ``out`` (each atomically, the script last)."""
    out = Path(out)
    numbers = tcl_numbers(scene, dt)
    motion = scene.build_motion()
    accelerations = motion.acceleration.tolist()
    motion_file = write_text(out / MOTION_G, "\n".join(repr(float(a)) for a in accelerations)
                             + "\n")
    text = "".join(f"{name} {value!r}\n" for name, value in numbers.items())
    numbers_file = write_text(out / NUMBERS_TXT, text)
    notes = write_text(out / NOTES_MD, correspondence(scene, numbers))
    script = write_text(out / TCL_NAME, _script_text())
    return TclFiles(script, numbers_file, motion_file, notes)


#: The files :func:`write_tcl` writes, declared before any work (the output folder's check).
TCL_NAMES = (MOTION_G, NUMBERS_TXT, NOTES_MD, TCL_NAME)
