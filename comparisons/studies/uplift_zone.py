"""The uplift zone of a continuum rotation pushover: the report's picture of the continuum.

A rotation pushover of ``strip_footing_clay`` to 10 θ_on (8 elements across B and 12 steps in
fast mode, the scene's 16 and 40 otherwise), written by
:func:`upliftlab.continuum.output.series.write_outputs` (uplift.png, moment_rotation.png, XDMF),
and the report's figures by
:mod:`.uplift_figures` (the M–θ path at page width, the frames of the frame slider).
θ_on = 2N(1 − ν)/(πGB) is the uplift-onset rotation of a rigid strip on the elastic half-plane
(:func:`upliftlab.anchors.half_plane_onset_rotation`).
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

from ...anchors import half_plane_onset_rotation
from ...provenance import provenance
from ..framework.protocol import Context, Study, run_study
from ..framework.study import StudyResult
from .uplift_figures import write_figures

__all__ = ["STUDY", "DEFINITION", "continuum_pushover", "run"]

STUDY = "uplift_zone"
SCENE = "strip_footing_clay"


@dataclass(frozen=True, eq=False)
class Pushover:
    """The pushover's scene, model, rotation schedule (rad) and path; ``study`` once written."""

    scene: object
    model: object
    rotations: object
    path: object
    study: StudyResult | None = None


def compute(scene, ctx: Context) -> Pushover:
    """The scene, model, rotations and pushover path (``scene``: a name, default
    :data:`SCENE`)."""
    from ...continuum import build_model, rotation_pushover
    from ...continuum.output.series import rotation_schedule
    from ...scenes import load_scene

    overrides = ["continuum.elements_across=8"] if ctx.fast else []
    scene = load_scene(scene or SCENE, overrides=overrides)
    model = build_model(scene)
    soil, N = scene.soil, scene.structure.vertical_weight
    theta_on = half_plane_onset_rotation(N, model.width, soil.shear_modulus, soil.poisson_ratio)
    rotations = rotation_schedule(10.0 * theta_on, 12 if ctx.fast else 40, theta_on)
    path = rotation_pushover(model, N, rotations, record_fields=True)
    return Pushover(scene, model, rotations, path)


def write(result, ctx: Context) -> StudyResult:
    """The renders, the XDMF and a summary into ``ctx.out``."""
    from ...continuum.output.series import pushover_summary, summary_line, write_outputs

    scene, model, rotations, path = result.scene, result.model, result.rotations, result.path
    fast, out = ctx.fast, ctx.out
    written = write_outputs(out, model, path, scene=scene, renders=True)
    summary = pushover_summary(path)
    units = {"length": scene.units.length,
             "moment/length": f"{scene.units.force}·{scene.units.length}/{scene.units.length}"}
    N = scene.structure.vertical_weight
    text = "\n".join([
        f"# Rotation pushover, {scene.name}", "",
        f"{scene.title}. Mesh: {model.disc.element}, {scene.continuum.elements_across} "
        f"elements across B ({model.dofs} DOFs), {rotations.size - 1} rotation steps to "
        f"10 θ_on at constant N = {N:g} {scene.units.force}/{scene.units.length}"
        + (" (coarse mesh: fast mode)." if fast else "."), "",
        summary_line(summary, units) + ".", "",
        "The picture shows the snapshot of largest rotation (displacements magnified, the "
        "magnification is printed in it); the M–θ figure compares the FE path with the "
        "elastic half-plane and the V–M capacity; the frame slider steps through the "
        "pushover with the contact pressure and the gap under the footing."])
    figures = write_figures(Path(out), scene, model, path, renders="uplift.png" in written)
    files = tuple(written[k] for k in ("uplift.png", "moment_rotation.png") if k in written)
    files += tuple(p for k, p in written.items() if not k.endswith(".png")) + tuple(figures)
    return StudyResult(STUDY, fast, Path(out), files, text, summary,
                       provenance(study=STUDY, fast=fast), ctx.elapsed())


def continuum_pushover(fast: bool, out: Path) -> StudyResult:
    """The pushover written into ``out`` (fast: the coarse mesh); its StudyResult."""
    return run_study(DEFINITION, None, Context(fast=fast, out=out)).study


DEFINITION = Study(STUDY, "Uplift zone of the continuum",
                   "A rotation pushover of the strip footing on clay in the continuum model "
                   "(upliftlab.continuum.output.series.write_outputs).", None, compute, write,
                   scene=SCENE, help_fast="8 elements across B, 12 rotation steps")


def run(scene: str | None = None, fast: bool = False, *, out=None) -> Pushover:
    """Run the pushover on ``scene`` (default :data:`SCENE`)."""
    return run_study(DEFINITION, scene, Context(fast=fast, out=out))

