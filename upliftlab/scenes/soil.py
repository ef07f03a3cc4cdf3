"""The continuum sections of a scene, ``[soil]`` and ``[continuum]`` (used by
:mod:`upliftlab.continuum`; the reduced model ignores them): their records and readers."""

from __future__ import annotations

from dataclasses import dataclass

from .. import bounds, checks
from ..checks import InputError
from .table import MISSING, Table, bounded_integer, choice, in_range
from ..units import UnitSystem

__all__ = ["SOIL_MODELS", "UNDRAINED", "FRICTIONAL", "INTERFACES", "ELEMENTS", "DYNAMICS",
           "MAX_ELEMENTS_ACROSS", "MIN_ELEMENTS_ACROSS", "Soil", "ContinuumOptions", "read_soil",
           "read_continuum"]

#: The strengths a soil model reads from ``[soil]``: ``undrained_strength`` c_u (UNDRAINED) or
#: ``cohesion``, ``friction_angle`` and ``dilation_angle`` (FRICTIONAL); None: no strength.
UNDRAINED, FRICTIONAL = "undrained", "frictional"
#: The soil models a ``[soil]`` table may name, each with the strength it reads: the names the
#: scene format knows, read here without the continuum (its optional dependencies) installed.
#: The continuum implements each in one module, found through its registry
#: (``upliftlab.continuum.materials.SOIL_MODELS``, held to these names and strengths by
#: tests/test_soil_models.py); a model added there is added here, one line.
SOIL_MODELS = {"elastic": None, "tresca": UNDRAINED, "von_mises": UNDRAINED,
               "drucker_prager": FRICTIONAL, "mohr_coulomb": FRICTIONAL}
INTERFACES = ("frictionless", "bonded", "coulomb")
ELEMENTS = ("P1", "P2", "Q1", "Q2")
DYNAMICS = ("explicit", "implicit")


@dataclass(frozen=True)
class Soil:
    """Plane-strain soil under the footing.

    ``youngs_modulus`` E (force/length²), ``poisson_ratio`` ν, ``density`` ρ (mass/length³).
    ``model``: one of :data:`SOIL_MODELS`, with the strength it reads (:attr:`strength`):
    none, undrained (``undrained_strength`` c_u, force/length²) or frictional (``cohesion`` c,
    ``friction_angle`` φ and ``dilation_angle`` ψ in degrees).
    ``undrained_strength_gradient`` k (force/length² per length, kPa/m in kN-m-s; default 0,
    a uniform soil): an undrained model's strength grows with the depth z below the ground
    surface (the footing's base level, y = 0 of the mesh), c_u(z) = c_u + k z, as a normally
    consolidated clay's does (c_u/σ'v ≈ 0.22, Mesri 1975: k ≈ 0.22 γ' ≈ 1.7–2.2 kPa/m for
    γ' = 8–10 kN/m³). A free-field column of density ρ and height H under a uniform
    acceleration a stays elastic if ρ a H ≤ c_u + k H (docs/continuum.md, "Strength that grows
    with depth"). Only for the undrained models (Tresca, von Mises).
    ``layer_depth`` (length) puts a rigid base at that depth (None: the box bottom).
    ``interface`` under the footing: frictionless, bonded, or coulomb with ``interface_friction``.
    ``k0`` the geostatic ratio σh/σv (None: the continuum model's default for ``model``).
    """

    youngs_modulus: float
    poisson_ratio: float
    density: float = 0.0
    model: str = "elastic"
    undrained_strength: float | None = None
    undrained_strength_gradient: float = 0.0
    cohesion: float = 0.0
    friction_angle: float = 0.0
    dilation_angle: float = 0.0
    hardening_modulus: float = 0.0
    layer_depth: float | None = None
    interface: str = "frictionless"
    interface_friction: float = 0.0
    k0: float | None = None

    @property
    def shear_modulus(self) -> float:
        return self.youngs_modulus / (2.0 * (1.0 + self.poisson_ratio))

    @property
    def strength(self) -> str | None:
        """The strength ``model`` reads (:data:`SOIL_MODELS`): UNDRAINED, FRICTIONAL or None."""
        return SOIL_MODELS.get(self.model)

    @property
    def undrained(self) -> bool:
        """True for a model of undrained strength c_u (Tresca, von Mises): its footing's
        bearing capacity is Prandtl's (2 + π) c_u B."""
        return self.strength == UNDRAINED

    @property
    def frictional(self) -> bool:
        """True for a model of frictional strength (c, φ, ψ: Mohr–Coulomb, Drucker–Prager)."""
        return self.strength == FRICTIONAL


def undrained_models() -> tuple[str, ...]:
    """The names of the models that read an undrained strength (and its gradient)."""
    return tuple(name for name, strength in SOIL_MODELS.items() if strength == UNDRAINED)


def _positive_strength(units: UnitSystem):
    def check(name, value):
        return bounds.check(name, checks.positive(name, value), "strength", units)
    return check


def read_soil(data, units: UnitSystem) -> Soil:
    """The :class:`Soil` of a ``[soil]`` table."""
    table = Table(data, "soil")
    model = table.get("model", choice(SOIL_MODELS), "elastic")
    strength = bounds.checker("strength", units)
    soil = Soil(
        youngs_modulus=table.get("youngs_modulus", bounds.checker("modulus", units)),
        poisson_ratio=table.get("poisson_ratio",
                                in_range(-1.0, 0.5, low_open=True, high_open=True)),
        density=table.get("density", bounds.checker("density", units), 0.0),
        model=model,
        undrained_strength=table.get("undrained_strength", _positive_strength(units),
                                     MISSING if SOIL_MODELS[model] == UNDRAINED else None),
        undrained_strength_gradient=table.get(
            "undrained_strength_gradient", bounds.checker("strength_gradient", units), 0.0),
        cohesion=table.get("cohesion", strength, 0.0),
        friction_angle=table.get("friction_angle", in_range(0.0, 60.0, high_open=True), 0.0),
        dilation_angle=table.get("dilation_angle", in_range(0.0, 60.0, high_open=True), 0.0),
        hardening_modulus=table.get("hardening_modulus", bounds.checker("hardening", units),
                                    0.0),
        layer_depth=table.get("layer_depth", bounds.checker("length", units), None),
        interface=table.get("interface", choice(INTERFACES), "frictionless"),
        interface_friction=table.get("interface_friction", in_range(0.0, 10.0), 0.0),
        k0=table.get("k0", in_range(0.0, 10.0, low_open=True), None),
    )
    if soil.undrained_strength_gradient != 0.0 and SOIL_MODELS[model] != UNDRAINED:
        raise InputError(f"soil.undrained_strength_gradient = {soil.undrained_strength_gradient:g}"
                         f": model {model!r} reads no undrained strength; valid range is [0, 0] "
                         f"(a gradient is for {', '.join(undrained_models())})")
    if soil.dilation_angle > soil.friction_angle:
        raise InputError(f"soil.dilation_angle = {soil.dilation_angle:g}: valid range is "
                         f"[0, friction_angle = {soil.friction_angle:g}]")
    table.done()
    return soil


@dataclass(frozen=True)
class ContinuumOptions:
    """Continuum domain and mesh: a box ``domain_width`` × ``domain_depth`` (multiples of the
    footing width B), ``element`` type, ``elements_across`` the footing, ``grading`` towards the
    footing edges, ``base`` (rigid or compliant) and side/bottom ``boundary`` of a dynamic run:
    ``fixed`` (the sides' u_x held, moving with a rigid base: a rigid container; on a compliant
    base the sides are ``shear``), ``shear`` (the sides' u_y held and u_x free: a free-field
    column, exact for a vertically incident S wave in a layered soil) or ``lysmer`` (dashpots).
    Statics hold the sides' u_x whatever ``boundary`` says.
    ``horizontal_tie`` (force/length per length; None: no tie): a horizontal spring from the
    footing to the free field's surface, the way a frictionless footing is held horizontally
    on a ``compliant`` base (a half-plane: :mod:`~upliftlab.continuum.dynamics.ground`), with a
    parallel dashpot ``horizontal_tie_damping`` (force·time/length per length; None: none); a
    bed's sway spring and sway dashpot of the same constants match them.
    ``intorder`` is the quadrature order (None: the element's default, Q2 2×2 reduced).
    ``dynamics``: the time integration of a dynamic run, ``explicit`` (central differences,
    lumped mass; the default) or ``implicit`` (HHT-α with Newton). ``energy_tolerance``: the
    largest energy balance error (fraction of the input energy) a dynamic run may have before
    it counts as failed, in (0, 1].
    ``damping_ratio`` ξ (None: no material damping, the soil's only losses its yielding and
    the boundaries' radiation): Rayleigh damping C = α M + β K₀ of the soil (K₀ its initial
    elastic stiffness), with the damping ratio ξ at the two frequencies
    ``damping_frequencies`` = (f₁, f₂) (Hz, f₁ < f₂), α = 2ξω₁ω₂/(ω₁ + ω₂),
    β = 2ξ/(ω₁ + ω₂), and less than ξ between them. Without ``damping_frequencies`` the usual
    pair: f₁ the soil column's fundamental frequency V_s/(4H) (H the box depth, or
    ``soil.layer_depth``) and f₂ = 5 f₁ (Hudson, Idriss & Beikae 1994; Kwok et al. 2007,
    J. Geotech. Geoenviron. Eng. 133(11)). In both dynamic routes
    (:mod:`~upliftlab.continuum.dynamics.rayleigh`); 0 ≤ ξ < 0.3.
    """

    domain_width: float = 10.0
    domain_depth: float = 10.0
    element: str = "Q2"
    elements_across: int = 16
    grading: float = 1.0
    base: str = "rigid"
    boundary: str = "fixed"
    intorder: int | None = None
    horizontal_tie: float | None = None
    horizontal_tie_damping: float | None = None
    dynamics: str = "explicit"
    energy_tolerance: float = 0.05
    damping_ratio: float | None = None
    damping_frequencies: tuple[float, float] | None = None


#: Most elements across the footing: 1024 gives about 10⁸ DOFs (the run's memory is estimated
#: and refused above its budget well before that; this bound keeps the estimate itself cheap).
MAX_ELEMENTS_ACROSS = 1024
#: Fewest elements across the footing a mesh has (its two edges and its centre).
MIN_ELEMENTS_ACROSS = 2


def _frequency_pair(name, value) -> tuple[float, float]:
    """[f₁, f₂] (Hz), 0 < f₁ < f₂ (:attr:`ContinuumOptions.damping_frequencies`)."""
    if not isinstance(value, (list, tuple)) or len(value) != 2:
        raise InputError(f"{name} = {value!r}: expected two frequencies [f1, f2] in Hz, "
                         "0 < f1 < f2")
    f1, f2 = (checks.positive(f"{name}[{i}]", v) for i, v in enumerate(value))
    if not f1 < f2:
        raise InputError(f"{name} = {list(value)}: valid range is 0 < f1 < f2 (Hz)")
    return float(f1), float(f2)


def read_continuum(data) -> ContinuumOptions:
    """The :class:`ContinuumOptions` of a ``[continuum]`` table."""
    table = Table(data, "continuum")
    options = ContinuumOptions(
        domain_width=table.get("domain_width", in_range(1.0, 1e4, low_open=True), 10.0),
        domain_depth=table.get("domain_depth", in_range(0.25, 1e4), 10.0),
        element=table.get("element", choice(ELEMENTS), "Q2"),
        elements_across=table.get("elements_across", bounded_integer(MIN_ELEMENTS_ACROSS, MAX_ELEMENTS_ACROSS), 16),
        grading=table.get("grading", in_range(1.0, 100.0), 1.0),
        base=table.get("base", choice(("rigid", "compliant")), "rigid"),
        boundary=table.get("boundary", choice(("fixed", "shear", "lysmer")), "fixed"),
        intorder=table.get("intorder", bounded_integer(1, 10), None),
        horizontal_tie=table.get("horizontal_tie", in_range(0.0, 1e12, low_open=True), None),
        horizontal_tie_damping=table.get("horizontal_tie_damping", in_range(0.0, 1e12), None),
        dynamics=table.get("dynamics", choice(DYNAMICS), "explicit"),
        energy_tolerance=table.get("energy_tolerance", in_range(0.0, 1.0, low_open=True), 0.05),
        damping_ratio=table.get("damping_ratio", in_range(0.0, 0.3, high_open=True), None),
        damping_frequencies=table.get("damping_frequencies", _frequency_pair, None),
    )
    table.done()
    if options.damping_frequencies is not None and options.damping_ratio is None:
        raise InputError(f"continuum.damping_frequencies = {list(options.damping_frequencies)}"
                         ": the frequencies are the damping's; valid: with "
                         "continuum.damping_ratio")
    if options.horizontal_tie_damping is not None and options.horizontal_tie is None:
        raise InputError(f"continuum.horizontal_tie_damping = {options.horizontal_tie_damping:g}"
                         ": the dashpot is the tie's; valid: with continuum.horizontal_tie")
    return options
