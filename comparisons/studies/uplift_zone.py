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

import json
from pathlib import Path

from ...anchors import half_plane_onset_rotation
from ...provenance import provenance
from ..framework.protocol import Context, Study, StudyRun, run_study
from ..framework.study import StudyResult, json_default
from .uplift_figures import write_figures

__all__ = ["STUDY", "DEFINITION", "continuum_pushover", "run", "summarise", "pushover_of"]

STUDY = "uplift_zone"
SCENE = "strip_footing_clay"


def compute(scene, ctx: Context):
    """The pushover as the study's :class:`xarray.Dataset` (``scene``: a name, default
    :data:`SCENE`): the continuum's labelled path with its soil fields
    (:func:`upliftlab.continuum.output.labelled.path_to_dataset`, over load ``step``), and as
    attributes what its files are written from again: the scene's full table
    (``scene_table``, JSON), its ``scene_source`` and ``scene_case``, the path's own metadata
    (``run_metadata``, JSON), the number of ``rotation_steps`` asked for and whether the
    mesh is the ``fast`` one (1) or the scene's (0)."""
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
    return path.to_xarray().assign_attrs(
        scene_table=json.dumps(scene.table, sort_keys=True, default=str),
        scene_source=scene.source, scene_case=scene.case or "",
        run_metadata=json.dumps(path.metadata, sort_keys=True, default=json_default),
        rotation_steps=int(rotations.size - 1), fast=int(bool(ctx.fast)))


def pushover_of(ds):
    """(scene, model, path) again from the study's dataset: the scene validated from its
    table (the same digest), its model built, the path with its own metadata."""
    from ...continuum import build_model
    from ...continuum.statics.results import StaticPath
    from ...scenes import scene_from_dict

    a = ds.attrs
    scene = scene_from_dict(json.loads(a["scene_table"]), source=a["scene_source"],
                            case=a["scene_case"] or None, merged=True)
    return scene, build_model(scene), StaticPath.from_xarray(ds, json.loads(a["run_metadata"]))


def summarise(ds, scene, model, path) -> str:
    """The Markdown of the pushover: mesh, steps, the summary line of its path."""
    from ...continuum.output.series import pushover_summary, summary_line

    units = {"length": scene.units.length,
             "moment/length": f"{scene.units.force}·{scene.units.length}/{scene.units.length}"}
    N = scene.structure.vertical_weight
    fast = bool(ds.attrs["fast"])
    return "\n".join([
        f"# Rotation pushover, {scene.name}", "",
        f"{scene.title}. Mesh: {model.disc.element}, {scene.continuum.elements_across} "
        f"elements across B ({model.dofs} DOFs), {int(ds.attrs['rotation_steps'])} rotation "
        f"steps to 10 θ_on at constant N = {N:g} {scene.units.force}/{scene.units.length}"
        + (" (coarse mesh: fast mode)." if fast else "."), "",
        summary_line(pushover_summary(path), units) + ".", "",
        "The picture shows the snapshot of largest rotation (displacements magnified, the "
        "magnification is printed in it); the M–θ figure compares the FE path with the "
        "elastic half-plane and the V–M capacity; the frame slider steps through the "
        "pushover with the contact pressure and the gap under the footing."])


def write(ds, ctx: Context) -> StudyResult:
    """The renders, the XDMF, ``result.nc`` (the path, as the continuum writes it) and the
    summary into ``ctx.out``, all from the dataset (:func:`pushover_of`)."""
    from ...continuum.output.series import pushover_summary, write_outputs

    scene, model, path = pushover_of(ds)
    out = Path(ctx.out)
    written = write_outputs(out, model, path, scene=scene, renders=True)
    text = summarise(ds, scene, model, path)
    figures = write_figures(out, scene, model, path, renders="uplift.png" in written)
    files = tuple(written[k] for k in ("uplift.png", "moment_rotation.png") if k in written)
    files += tuple(p for k, p in written.items() if not k.endswith(".png")) + tuple(figures)
    return StudyResult(STUDY, ctx.fast, out, files, text, pushover_summary(path),
                       provenance(study=STUDY, fast=ctx.fast), ctx.elapsed())


def continuum_pushover(fast: bool, out: Path) -> StudyResult:
    """The pushover written into ``out`` (fast: the coarse mesh); its StudyResult."""
    return run_study(DEFINITION, None, Context(fast=fast, out=out)).study


DEFINITION = Study(STUDY, "Uplift zone of the continuum",
                   "A rotation pushover of the strip footing on clay in the continuum model "
                   "(upliftlab.continuum.output.series.write_outputs).", None, compute, write,
                   scene=SCENE, help_fast="8 elements across B, 12 rotation steps")


def run(scene: str | None = None, fast: bool = False, *, out=None) -> StudyRun:
    """Run the pushover on ``scene`` (default :data:`SCENE`): the dataset (``.data``) and what
    was written (``.study``)."""
    return run_study(DEFINITION, scene, Context(fast=fast, out=out))
