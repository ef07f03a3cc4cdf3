"""The uplift zone's figures as the report shows them, each with a caption computed from the
pushover (:mod:`.figure_record`): the M–θ path at page width (vector) and the frames of the
frame slider (the rendered soil and footing — raster pictures by nature — with the contact
pressure and the gap under the footing, at most :data:`MAX_FRAMES` snapshots, 6.5 in wide;
the slider opens on the last, the largest rotation, which is the snapshot of the study's
``uplift.png``)."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ...anchors import half_plane_rocking, prandtl_capacity
from ..framework.figure_record import Caption, page_figure, print_style, save, save_frames

__all__ = ["MAX_FRAMES", "write_figures", "moment_rotation", "animation_caption"]

#: Frames of the report's frame slider (the report's size grows with them: ~100 kB each).
MAX_FRAMES = 16


def write_figures(out: Path, scene, model, path, renders: bool = True) -> list[Path]:
    """The M–θ figure and (``renders``: matplotlib and Pillow are needed) the slider's frames with their
    record, into ``out``; the files."""
    files = save(out / "m_theta.png", *moment_rotation(scene, path))
    if renders:
        files += _animation(out, scene, model, path)
    return files


def _units(scene) -> tuple[str, str, str]:
    u = scene.units
    return u.length, f"{u.force}/{u.length}", f"{u.force}·{u.length}/{u.length}"


def moment_rotation(scene, path):
    """(figure, caption): M, contact length c/B and settlement against θ, the FE pushover
    against the rigid strip on the elastic half-plane and the V–M capacity."""
    length, force, moment = _units(scene)
    theta, B = np.asarray(path.theta, dtype=float), float(path.width)
    N = float(np.median(path.N))
    soil = scene.soil
    fine = np.linspace(min(0.0, theta.min()), theta.max(), 400)
    ref = half_plane_rocking(fine, N, B, soil.shear_modulus, soil.poisson_ratio)
    with print_style():
        fig, (ax_m, ax_c, ax_s) = page_figure(6.4, 3, 1, sharex=True)
        for ax, values in ((ax_m, path.M), (ax_c, np.asarray(path.contact_length) / B),
                           (ax_s, -np.asarray(path.v))):
            ax.plot(theta, values, "o-", color="black", ms=3, label="continuum (FE)")
        ax_m.plot(fine, ref["M"], ":", color="#0072B2", lw=2, label="elastic half-plane")
        ax_c.plot(fine, ref["c"] / B, ":", color="#0072B2", lw=2)
        cu = getattr(soil, "undrained_strength", None)
        capacity = None
        if cu:
            v = N / prandtl_capacity(float(cu), B)
            if 0.0 < v < 1.0:
                capacity = B * prandtl_capacity(float(cu), B) * v * (1 - v) / 2
                ax_m.axhline(capacity, color="#009E73", ls="-.",
                             label=f"V–M capacity at N/N_ult = {v:.2f}")
        ax_m.set_ylabel(f"M ({moment})")
        ax_c.set_ylabel("contact c/B (–)")
        ax_c.set_ylim(0.0, 1.05)
        ax_s.set_ylabel(f"settlement −v ({length})")
        ax_s.set_xlabel("footing rotation θ (rad)")
        for ax in (ax_m, ax_c, ax_s):
            ax.grid(alpha=0.3)
        fig.legend(*ax_m.get_legend_handles_labels(), loc="outside lower center", ncols=3,
                   frameon=False)
    M_last, c_last = float(np.asarray(path.M)[-1]), float(np.asarray(path.contact_length)[-1])
    hp_last = float(half_plane_rocking(theta[-1:], N, B, soil.shear_modulus,
                                       soil.poisson_ratio)["M"][0])
    conclusion = (f"At θ = {theta[-1]:.3g} rad the footing carries M = {M_last:.4g} {moment}, "
                  f"{M_last / hp_last:.2f} × the elastic half-plane's"
                  + (f" and {M_last / capacity:.2f} × the V–M capacity" if capacity else "")
                  + f", on {c_last / B:.0%} of its width.")
    shown = (f"{scene.name}: rotation pushover of the rigid strip at constant N = {N:.4g} "
             f"{force}: moment, contact length and settlement against the rotation θ (rad), the "
             "finite elements against the closed form of a rigid strip on the elastic "
             "half-plane.")
    return fig, Caption("How does the footing's moment grow as it uplifts?", shown, conclusion)


def animation_caption(scene, frames, B: float, stress: str) -> Caption:
    """The frame slider's caption from its frames (the contact length, pressure and gap of
    each); ``stress`` the pressure's unit."""
    length = scene.units.length
    stress = stress.replace("^2", "²")
    first, last = frames[0], frames[-1]
    gap = max(float(np.max(f.gap)) for f in frames)
    pressure = max(float(np.max(f.pressure)) for f in frames)
    shown = (f"{len(frames)} snapshots of the rotation pushover of {scene.name}: the soil "
             "and the footing (displacements magnified) with the contact pressure p (filled) "
             "and the gap g (line) along the base under each; on screen the slider steps "
             "through them, in print the last shows.")
    conclusion = (f"The contact shrinks from {first.contact_length / B:.0%} of B "
                  f"({first.label}) to {last.contact_length / B:.0%} ({last.label}) while the "
                  f"gap under the lifted edge grows to {gap:.3g} {length} and the peak pressure "
                  f"to {pressure:.4g} {stress}.")
    return Caption("How does the contact open as the footing rotates?", shown, conclusion)


def _animation(out: Path, scene, model, path) -> list[Path]:
    from ...meshes.frames import units_of
    from ...meshes.render import render_frames

    written = render_frames(out / "frames", path, model.disc.basis, model.width,
                            limit=MAX_FRAMES, title=scene.name, width_in=6.5, dpi=110)
    frames = [f for _, f in written]
    labels = [f"{f.label}: θ = {f.footing[2]:.3g} rad, contact "
              f"{f.contact_length / model.width:.0%} of B" for f in frames]
    record = save_frames(out / "animation.png", [(p, lab) for (p, _), lab in
                                                 zip(written, labels)],
                         animation_caption(scene, frames, float(model.width),
                                           units_of(path.metadata)["stress_unit"]))
    return [record] + [p for p, _ in written]
