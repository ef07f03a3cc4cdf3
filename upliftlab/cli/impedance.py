"""``upliftlab continuum --analysis impedance``: the footing's impedance on the continuum,
checked against the exact half-plane before any file is written (exit 3 beyond the stated
tolerances)."""

from __future__ import annotations

import time

from ..checks import InputError
from .common import default_out, eta, mesh_overrides, number, say
from ..outdir import claim

__all__ = ["impedance_options", "run_impedance", "IMPEDANCE_NAMES"]


def impedance_options(args):
    """ImpedanceOptions from --a0, --boundary and a --mesh domain_width/domain_depth (the
    impedance meshes its own box; the scene's is a static one)."""
    from ..continuum.impedance.analysis import ImpedanceOptions

    kwargs = {}
    if args.a0 is not None:
        try:
            kwargs["a0"] = tuple(float(x) for x in args.a0.split(",") if x.strip())
        except ValueError:
            raise InputError(f"--a0 = {args.a0!r}: expected comma-separated numbers > 0") from None
    if args.boundary is not None:
        kwargs["boundary"] = args.boundary
    for pair in mesh_overrides(args.mesh):
        key, _, value = pair.partition("=")
        if key in ("continuum.domain_width", "continuum.domain_depth"):
            name = key.split(".")[1]
            kwargs[name] = number(f"--mesh {name}", value, high=1e4)
    return ImpedanceOptions(**kwargs)


#: The files the impedance writes: its result and (unless --no-render) its figure.
IMPEDANCE_NAMES = ("impedance.nc", "impedance.png")


def run_impedance(args, scene, overrides) -> int:
    """``--analysis impedance``: the FE impedance, checked against the exact half-plane
    (exit 3 beyond the stated tolerances, before any file is written)."""
    import json

    from ..continuum.impedance.analysis import harmonic_unknowns, impedance, impedance_model

    options = impedance_options(args)
    settings = {"command": "continuum impedance", "scene": scene.name,
                "scene_digest": scene.digest, "overrides": list(scene.overrides),
                "a0": args.a0, "boundary": args.boundary}
    default = default_out(f"{scene.name}-continuum-impedance",
                           {"overrides": overrides, "a0": args.a0, "boundary": args.boundary})
    netcdf, figure = IMPEDANCE_NAMES
    outputs = [netcdf] if args.no_render else [netcdf, figure]
    with claim(args.out, default, settings=settings, force=args.force,
               outputs=outputs) as out:  # the folder first: the mesh alone takes seconds
        model = impedance_model(scene.soil, scene.foundation.width, scene.continuum, options,
                                scene=scene)
        say(f"{scene.name}: impedance, {model.disc.element}, {model.mesh.nelements} elements, "
            f"{harmonic_unknowns(model, options)} DOFs in the harmonic solve, "
            f"{options.boundary} box {options.domain_width:g}B x {options.domain_depth:g}B, "
            f"{scene.soil.interface} interface, {len(options.a0)} frequencies")
        started = time.perf_counter()

        def progress(k, n, a0):
            say(f"a0 = {a0:.3g} ({k + 1}/{n}){eta(started, k + 1, n)}")

        result = impedance(model, options, progress=progress)
        from ..continuum.impedance.output import (impedance_figure, impedance_summary,
                                                  reference_for, verify)

        reference = reference_for(result)
        errors = verify(result, reference)  # ImpedanceAccuracyError (exit 3) before any file
        out.start_writing()
        written = [result.save(out.path / netcdf)]
        if not args.no_render:
            from ..reduced.figures import save
            written.append(save(impedance_figure(result, reference),
                                out.path / figure))
        out.complete(written)
    for path in written:
        say(f"wrote {path}")
    summary = impedance_summary(result, reference, errors)
    if args.json:
        print(json.dumps(summary, allow_nan=False))
    else:
        worst = ", ".join(f"{k} {100 * v:.2f} %" for k, v in summary["max_error"].items())
        print(f"impedance of {scene.name}: {len(result.a0)} frequencies a0 = "
              f"{result.a0.min():g}-{result.a0.max():g}, {result.dofs} DOFs, "
              f"{summary['wall_time_s']:.1f} s; largest error against the exact half-plane: "
              f"{worst}")
    return 0
