"""Write the standalone OpenSeesPy script of a scene: ``model.py`` and ``motion.txt``.

The script is meant to be opened and run by a reviewer without upliftlab: a docstring that
names each modelling choice and how it compares with upliftlab's reduced model, the scene's
numbers as commented constants, then the code (:data:`.template.CODE`). The ground motion is
written beside it as two columns, time [s] and acceleration [g].
"""

from __future__ import annotations

import ast
import json
import math
import re
import textwrap
from dataclasses import dataclass
from pathlib import Path

from ... import __version__
from ...results import write_text
from .spec import OpenSeesSpec
from .template import CODE

__all__ = ["ScriptFiles", "script_text", "motion_text", "write_script", "modelling_notes"]

SCRIPT_NAME, MOTION_NAME = "model.py", "motion.txt"


@dataclass(frozen=True)
class ScriptFiles:
    """The files written: the ``script`` and the ``motion`` beside it (None: free vibration)."""

    script: Path
    motion: Path | None


def _num(value: float) -> str:
    """A float as a Python literal that reads back exactly (inf as math.inf)."""
    return "math.inf" if math.isinf(value) else repr(float(value))


def _command(spec: OpenSeesSpec) -> str:
    parts = ["upliftlab opensees", spec.scene_name.rsplit("-", 1)[0] if spec.case
             else spec.scene_name]
    if spec.case:
        parts += ["--case", spec.case]
    parts += [f"--set {o}" for o in spec.overrides]
    return " ".join(parts + [f"--dt {spec.dt!r}", f"--dashpots {spec.dashpots}"])


def modelling_notes(spec: OpenSeesSpec) -> list[str]:
    """One sentence per modelling choice: what OpenSees does and how it compares with upliftlab's
    reduced model (the same notes go into the script and the comparison)."""
    notes = []
    if spec.has_foundation:
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
    if spec.has_dashpots and spec.support == "uplift":
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


def script_text(spec: OpenSeesSpec, motion_file: str | None) -> str:
    """The whole script."""
    L, F, s = spec.length, spec.force, spec
    notes = "\n".join(textwrap.fill(n, 92, initial_indent="- ", subsequent_indent="  ")
                      for n in modelling_notes(spec))
    found = "\n".join(f"    ({_num(p.x)}, {_num(p.k)}, {_num(p.c)}, {_num(p.f0)}, {_num(p.fy)}),"
                      for p in s.springs)
    stories = "\n".join(f"    ({_num(t.height)}, {_num(t.weight)}, {_num(t.stiffness)}, "
                        f"{_num(t.damping)}, {_num(t.yield_force)}, {_num(t.post_yield_ratio)}),"
                        for t in s.stories)
    lever = [t.height - b for t, b in zip(s.stories, [0.0] + [t.height for t in s.stories])]
    tie = 1e7 * max(t.stiffness * d * d for t, d in zip(s.stories, lever))
    scale = (s.vertical_weight / sum(p.k for p in s.springs) if s.springs
             else s.stories[0].weight / s.stories[0].stiffness)
    doc = f'''OpenSeesPy model of an upliftlab scene (SCENE, TITLE and COMMAND below name it).

Written by upliftlab {__version__}.
Standalone: it needs Python 3 and openseespy only (pip install openseespy; on Linux the wheel
also needs libblas.so.3, which this script finds inside the wheel when the system has none).
Run it with `python {SCRIPT_NAME}`: it writes opensees_histories.csv (time, u, theta, V, the
leftmost spring's compression from rest, base shear) and opensees_summary.json (the peaks)
beside itself, and prints the summary.

A BNWF model of upliftlab's reduced model, 2D, three DOFs per node, units {s.units}
({F}, {L}, s; g = {s.g:g} {L}/s²). Its numbers are upliftlab's own (upliftlab.reduced.build_model).
Modelling choices:
{notes}
'''
    head = f'''#!/usr/bin/env python3
"""{_docstring_text(doc)}"""

import json
import math
import os
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
SCENE = {_literal(s.scene_name)}
TITLE = {_literal(s.title)}
COMMAND = {_literal(_command(spec))}  # the upliftlab command that wrote this script
UNITS = {_literal(s.units)}
G = {_num(s.g)}  # {L}/s²
SUPPORT = {s.support!r}  # uplift: springs carry no tension; bonded: they do; fixed: no springs
DASHPOTS = {s.dashpots!r}  # foundation dashpots: clipped, detaching or parallel
RIGID = {s.rigid!r}  # True: the stories are tied to the footing
P_DELTA = {s.p_delta!r}
VERTICAL_WEIGHT = {_num(s.vertical_weight)}  # {F}: W_v, carried by the footing (mass W_v/G)
ROTARY_INERTIA = {_num(s.rotary_inertia)}  # {F}·{L}·s²: I0 of the footing body about O
# Foundation springs, left to right: x [{L}] from O, k [{F}/{L}], c [{F}·s/{L}],
# F0 [{F}] (static compression, for reference: gravity produces it), Fy [{F}] (inf: elastic)
FOUNDATION = [
{found}
]
# Stories, bottom to top: height above O [{L}], weight [{F}], k [{F}/{L}], c [{F}·s/{L}],
# Fy [{F}] (inf: elastic), post-yield stiffness ratio α
STORIES = [
{stories}
]
DT = {_num(s.dt)}  # s, Newmark step
DURATION = {_num(s.duration)}  # s
MOTION_FILE = {(motion_file or '')!r}  # ground acceleration beside this script ('' for none)
INITIAL_VELOCITY = {_num(s.initial_velocity)}  # {L}/s, of the top mass relative to the ground
TOLERANCE = {_num(1e-6 * scale)}  # {L}: Newton's displacement increment, 1e-6 of W/K
# {F}·{L}/rad: ties a floor's rotation to the footing's, 1e7 times the stiffest k_j Δh_j²
# (a story drift is then off by 1e-7 of itself)
TIE_STIFFNESS = {_num(tie)}
'''
    text = head + CODE
    check_script(text, spec, doc)
    return text


#: Text that may stand in the script's docstring: no backslash, double quote or control
#: character (but the newline) that could close or escape it.
_SAFE_TEXT = re.compile(r'[^\\"\x00-\x09\x0b-\x1f\x7f]*')


def _docstring_text(text: str) -> str:
    """``text`` checked to be safe inside the script's docstring (it is made of upliftlab's own
    sentences and numbers only; a scene's strings go into constants through :func:`_literal`)."""
    if not _SAFE_TEXT.fullmatch(text):
        raise RuntimeError("the OpenSees script's docstring would hold a quote, a backslash or a "
                           "control character; nothing was written")
    return text


def _literal(value: str) -> str:
    """A scene's string as a Python literal (JSON escapes every quote, backslash and control
    character; a JSON string is a valid Python string literal)."""
    return json.dumps(str(value))


def check_script(text: str, spec: OpenSeesSpec, doc: str) -> None:
    """Refuse (RuntimeError) a script whose parse is not the one upliftlab meant: its docstring
    must be ``doc`` and the scene's strings must read back, unchanged, as the constants SCENE,
    TITLE and COMMAND; no string of a scene can then have become code."""
    try:
        tree = ast.parse(text)
    except SyntaxError:
        tree = ast.Module(body=[], type_ignores=[])
    constants = {node.targets[0].id: node.value for node in tree.body
                 if isinstance(node, ast.Assign) and len(node.targets) == 1
                 and isinstance(node.targets[0], ast.Name)}
    expected = {"SCENE": spec.scene_name, "TITLE": spec.title, "COMMAND": _command(spec),
                "UNITS": spec.units}
    read = {name: ast.literal_eval(constants[name]) if name in constants else None
            for name in expected}
    if ast.get_docstring(tree, clean=False) != doc or read != expected:
        raise RuntimeError("the OpenSees script did not parse as written (a scene string "
                           "changed its code); nothing was written")


def motion_text(spec: OpenSeesSpec) -> str:
    """The ground acceleration as two columns, time [s] and acceleration [g]."""
    m = spec.motion
    lines = [f"# {_literal(m.name)}: ground acceleration for {_literal(spec.scene_name)} "
             f"(from {_literal(m.source or 'upliftlab')})",
             "# time [s]  acceleration [g]; linear between samples, zero after the last"]
    lines += [f"{k * m.dt:.10g} {a!r}" for k, a in enumerate(m.acceleration.tolist())]
    return "\n".join(lines) + "\n"


def write_script(spec: OpenSeesSpec, out: str | Path) -> ScriptFiles:
    """Write ``model.py`` (and ``motion.txt`` unless the motion is free vibration) into
    ``out``; each file atomically."""
    out = Path(out)
    motion = None
    if not spec.motion.is_free_vibration:
        motion = write_text(out / MOTION_NAME, motion_text(spec))
    script = write_text(out / SCRIPT_NAME,
                        script_text(spec, MOTION_NAME if motion is not None else None))
    return ScriptFiles(script, motion)
