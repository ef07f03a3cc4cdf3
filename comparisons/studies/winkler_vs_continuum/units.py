"""The units of the error table's quantities, in the scene's unit system (per unit length of
the strip, plane strain), for the summary's tables and the files' attributes."""

from __future__ import annotations

__all__ = ["quantity_unit"]


def quantity_unit(key: str, units, *, cf: bool = False) -> str:
    """The unit of error-table quantity ``key`` in the scene's ``units`` (per unit length of
    the strip: plane strain); ``cf``: written as a CF/UDUNITS ``units`` attribute (``*`` for
    the product, ``/rad``) rather than for reading."""
    text = _unit_text(key, units)
    return text.replace("·", "*").replace(" per rad", "/rad") if cf else text


def _unit_text(key: str, units) -> str:
    F, L = units.force, units.length
    if key == "K_r":
        return f"{F}·{L}/{L} per rad"
    if key == "K_v":
        return f"{F}/{L}/{L}"
    if key == "N_ult":
        return f"{F}/{L}"
    if key.endswith("theta"):
        return "rad"
    if key.startswith(("contact", "settlement", "cyclic_settlement")) or key.endswith(
            ("_u", "_uplift", "_residual_settlement")):
        return L
    return f"{F}·{L}/{L}"  # moments, and the cyclic energy (moment × rad)
