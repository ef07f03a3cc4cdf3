"""Write a scene's standalone OpenSeesPy model: ``model.py``, ``model.json`` and
``motion.txt``.

``model.py`` is the same file for every scene: the real module :mod:`.model_script` of this
package, read as package data and written unchanged, so a reviewer opens exactly what runs and
no text of a scene can become code. The scene goes into ``model.json`` beside it: its numbers
(the springs, the stories, the step, …), its names, the upliftlab command that wrote it and
one note per modelling choice saying how it compares with upliftlab's reduced model. The
ground motion, if any, goes into ``motion.txt`` as two columns, time [s] and acceleration [g].
"""

from __future__ import annotations

import json
import shlex
from collections.abc import Sequence
from dataclasses import dataclass
from importlib import resources
from pathlib import Path

from ... import __version__
from ...results import write_text
from .spec import OpenSeesSpec

__all__ = ["ScriptFiles", "script_text", "script_numbers", "motion_text", "write_script",
           "script_names", "modelling_notes"]

SCRIPT_NAME, NUMBERS_NAME, MOTION_NAME = "model.py", "model.json", "motion.txt"


@dataclass(frozen=True)
class ScriptFiles:
    """The files written: the ``script``, its ``numbers`` and the ``motion`` beside them
    (None: free vibration)."""

    script: Path
    numbers: Path
    motion: Path | None


def _command(spec: OpenSeesSpec, scene_args: Sequence[str] | None = None) -> str:
    """The shell command that writes this model again: ``upliftlab opensees``, the arguments
    that chose the scene (``scene_args``, as the command line gave them: the scene as given,
    --case, --motion, each --set; None: the spec's scene name, case and overrides), then the
    step and dashpots it resolved to; every argument shell-quoted (:func:`shlex.join`), so
    that pasting it runs nothing a scene's path or an override holds."""
    if scene_args is None:
        scene_args = [spec.scene_name.rsplit("-", 1)[0] if spec.case else spec.scene_name]
        scene_args += ["--case", spec.case] if spec.case else []
        scene_args += [a for o in spec.overrides for a in ("--set", o)]
    return shlex.join(["upliftlab", "opensees", *scene_args, "--dt", repr(spec.dt),
                       "--dashpots", spec.dashpots])


def modelling_notes(spec: OpenSeesSpec) -> list[str]:
    """One sentence per modelling choice: what OpenSees does and how it compares with upliftlab's
    reduced model (the same notes go into the script and the comparison)."""
    notes = []
    if spec.qz:
        types = sorted({q.qz_type for q in spec.qz})
        notes.append(f"Foundation springs: {len(spec.springs)} zeroLength springs under a rigid "
                     f"footing, each a QzSimple2 (type {', '.join(map(str, types))}) of the "
                     "spring's q_ult, a z50 that makes its initial stiffness the spring's k, "
                     "the spring's suction and its dashpot c on the far field (OpenSees' "
                     "compression is negative: the element runs from soil to footing). Past "
                     "the elastic range the backbones differ (QzSimple2's elastic range and "
                     "z_ref are fixed fractions of its z50, upliftlab's are the bed's); its "
                     "near field and closure are stiff, not rigid, and its dashpot is not "
                     "clipped at zero force.")
    elif spec.has_foundation:
        plastic = spec.law == "elastoplastic"
        if spec.support == "bonded":
            law = ("ElasticPP, yielding in compression at yield_multiple x F0" if plastic
                   else "Elastic") + ", carrying tension (a bonded base)"
        elif spec.has_dashpots and spec.dashpots == "clipped":
            law = ("ElasticPP, yielding in compression at yield_multiple x F0 (no yield in "
                   "tension)" if plastic else "Elastic") + (
                ", inside TensionOnly with its dashpot: it carries no tension, and it pulls "
                "inside the wrapper while open so that the dashpot cannot push in the air")
        else:
            law = ("ElasticPPGap with damage: yield at yield_multiple x F0, the settlement kept, "
                   "so that it separates from its settled surface" if plastic else
                   "Elastic with no stiffness in tension") + ": it carries no tension"
        notes.append(f"Foundation springs: {len(spec.springs)} zeroLength springs under a rigid "
                     f"footing (rigid links), their deformation the soil's compression; {law}. "
                     "The same law as upliftlab's.")
    if spec.has_dashpots and spec.support == "uplift" and not spec.qz:
        beta = spec.dashpot_time
        text = {
            "clipped": (f"Foundation dashpots (clipped): Viscous c_i beside each spring, both "
                        "inside TensionOnly (twice: its leak of 1e-4 of a negative force becomes "
                        "1e-8), so the dashpot acts only while its spring is in contact and "
                        "their sum never pulls: upliftlab's clip. It differs "
                        "before a landing: the sum k·d + c·v turns positive while the gap is "
                        f"still below β·v (β = c_i/k_i = {beta:.4g} s), so the dashpot starts "
                        "to push that much earlier, where upliftlab's starts at contact with a "
                        "jump to c·v."),
            "detaching": (f"Foundation dashpots (detaching): stiffness-proportional Rayleigh "
                          f"damping on each spring's current tangent, β = c_i/k_i = {beta:.4g} "
                          "s: zero while the spring is open (and while it yields), but never "
                          "clipped, so a spring in contact pulls through its dashpot while it "
                          "opens fast; upliftlab clips the sum at zero."),
            "parallel": ("Foundation dashpots (parallel): Viscous c_i beside the "
                         "compression-only spring, attached even while the spring is open: it "
                         "pulls the footing down as it lifts off and pushes before it lands; "
                         "upliftlab's detaches with its spring and never pulls."),
        }[spec.dashpots]
        notes.append(text + f" c_i = ζ_f·2√(K_v m_v)·k_i/K_v, ζ_f = {spec.damping_ratio:g}, "
                     "as upliftlab's.")
    elif spec.has_dashpots:
        notes.append("Foundation dashpots: Viscous c_i beside each bonded spring, as upliftlab's.")
    if spec.stories and not spec.rigid:
        notes.append("Superstructure: lumped lateral masses on zeroLength story springs that "
                     "measure the drift relative to the rotated footing (each floor carried "
                     "rigidly from the one below); elastic, or bilinear with kinematic "
                     "hardening as ElasticPP (1 − α)k beside Elastic αk; story dashpots "
                     "c_j = 2ζ_s k_j/ω₁ (Viscous), as upliftlab's.")
    elif spec.rigid:
        notes.append("Superstructure: rigid, its masses tied to the footing by rigid links, as "
                     "upliftlab's.")
    if spec.p_delta:
        notes.append("P-Δ: upliftlab's linearised P-Δ of the story weights as springs of "
                     "negative stiffness (no geometric transformation).")
    notes.append(f"Time stepping: gravity in 10 static load steps, then Newmark average "
                 f"acceleration with Newton (line search, modified Newton and step halving "
                 f"when a step fails) at Δt = {spec.dt:.4g} s; peaks at every step with the "
                 "cubic between steps, as upliftlab's. Rotations are small (as upliftlab's "
                 "'small' kinematics): no overturning.")
    return notes


def script_text() -> str:
    """The script, as this package holds it (:mod:`.model_script`)."""
    return resources.files(__package__).joinpath("model_script.py").read_text(encoding="utf-8")


def script_numbers(spec: OpenSeesSpec, motion_file: str | None,
                   scene_args: Sequence[str] | None = None) -> dict:
    """What ``model.json`` holds for the script (:mod:`.model_script`'s constants): numbers
    in the scene's units, the scene's names, the command that wrote it (``scene_args``:
    :func:`_command`) and the modelling notes; JSON text only."""
    s = spec
    lever = [t.height - b for t, b in zip(s.stories, [0.0] + [t.height for t in s.stories])]
    scale = (s.vertical_weight / sum(p.k for p in s.springs) if s.springs
             else s.stories[0].weight / s.stories[0].stiffness)
    return {
        "WRITTEN_BY": f"upliftlab {__version__}", "SCENE": s.scene_name, "TITLE": s.title,
        "COMMAND": _command(spec, scene_args), "UNITS": s.units,
        "G": float(s.g), "SUPPORT": s.support, "DASHPOTS": s.dashpots, "RIGID": bool(s.rigid),
        "P_DELTA": bool(s.p_delta), "VERTICAL_WEIGHT": float(s.vertical_weight),
        "ROTARY_INERTIA": float(s.rotary_inertia),
        "FOUNDATION": [[float(p.x), float(p.k), float(p.c), float(p.f0), float(p.fy)]
                       for p in s.springs],
        "STORIES": [[float(t.height), float(t.weight), float(t.stiffness), float(t.damping),
                     float(t.yield_force), float(t.post_yield_ratio)] for t in s.stories],
        "DT": float(s.dt), "DURATION": float(s.duration), "MOTION_FILE": motion_file or "",
        "INITIAL_VELOCITY": float(s.initial_velocity),
        # Newton's displacement increment, 1e-6 of W/K (length)
        "TOLERANCE": 1e-6 * scale,
        # ties a floor's rotation to the footing's, 1e7 times the stiffest k_j Δh_j² (a story
        # drift is then off by 1e-7 of itself)
        "TIE_STIFFNESS": 1e7 * max(t.stiffness * d * d for t, d in zip(s.stories, lever)),
        "QZ": [q.args() for q in s.qz],
        "NOTES": modelling_notes(spec),
    }


def motion_text(spec: OpenSeesSpec) -> str:
    """The ground acceleration as two columns, time [s] and acceleration [g], after a comment
    line naming it (its names as JSON strings: no line break of theirs can end the comment)."""
    m = spec.motion
    lines = [f"# {json.dumps(m.name)}: ground acceleration for {json.dumps(spec.scene_name)} "
             f"(from {json.dumps(m.source or 'upliftlab')})",
             "# time [s]  acceleration [g]; linear between samples, zero after the last"]
    lines += [f"{k * m.dt:.10g} {a!r}" for k, a in enumerate(m.acceleration.tolist())]
    return "\n".join(lines) + "\n"


def script_names(spec: OpenSeesSpec) -> list[str]:
    """The names of the files :func:`write_script` writes for ``spec`` (``motion.txt`` only
    for a motion that is not free vibration), declared before any work so that the output
    folder's check covers them (:func:`upliftlab.outdir.claim`)."""
    motion = [] if spec.motion.is_free_vibration else [MOTION_NAME]
    return [*motion, NUMBERS_NAME, SCRIPT_NAME]


def write_script(spec: OpenSeesSpec, out: str | Path,
                 scene_args: Sequence[str] | None = None) -> ScriptFiles:
    """Write ``model.py``, ``model.json`` (and ``motion.txt`` unless the motion is free
    vibration) into ``out``; each file atomically, the script last. ``scene_args``: the
    command-line arguments that chose the scene, for the command in ``model.json``."""
    out = Path(out)
    motion = None
    if MOTION_NAME in script_names(spec):
        motion = write_text(out / MOTION_NAME, motion_text(spec))
    numbers = script_numbers(spec, MOTION_NAME if motion is not None else None, scene_args)
    json_file = write_text(out / NUMBERS_NAME, json.dumps(numbers, indent=1) + "\n")
    script = write_text(out / SCRIPT_NAME, script_text())
    return ScriptFiles(script, json_file, motion)
