"""Dynamic impedance of the rigid footing on linear elastic soil, in the frequency domain.

**What it computes.** For a harmonic motion q e^{+iωt} of the footing, q = (u, v, θ) at the
centre of its base, the forces it applies to the soil are K(ω) q with K the complex 3×3
impedance per unit length, in the conventions of :mod:`~upliftlab.continuum.contact.footing`
(generalised forces (H, −N, M)). Its diagonal gives K_h (θ held), K_v and K_r (the horizontal
motion held) and K[0, 2] the horizontal–rocking coupling K_hr. With e^{+iωt}, Im K = ω C ≥ 0.
The usual normalisation K_j = K_j,static [k_j(a0) + i a0 c_j(a0)], a0 = ω (B/2)/V_s, is in
:class:`Impedance`.

**How.** On the model's own mesh and element, the harmonic equations
(K + iω C − ω² M) u = f are solved once per frequency (one complex sparse LU): the footing's
DOFs follow its rigid motion (both components if the interface is bonded; the vertical only if
frictionless, whose base then carries no shear), and the reactions give K(ω) = Lᵀ f_c. The
stiffness is the model's (:func:`~upliftlab.continuum.assembly.stiffness`, its quadrature), the
mass :func:`~upliftlab.continuum.dynamics.waves.mass_data` (consistent).

**The unbounded soil.** Two absorbing boundaries (``ImpedanceOptions.boundary``):

- ``pml`` (default): the outer ``pml_thickness`` of the box's sides and bottom is a perfectly
  matched layer, a complex stretch of the coordinates normal to each face,
  λ(ξ) = 1 + f₀ ξ^m − i f₀ ξ^m / a0 (ξ = 0 … 1 across the layer; Basu & Chopra 2003,
  Comput. Methods Appl. Mech. Eng. 192), and the layer's outer boundary is fixed. In the
  unstretched coordinates the layer is an anisotropic complex material: stiffness
  ∫ Gᵀ Λ C Λ G λ_x λ_y with Λ = diag(1/λ_x, 1/λ_y, 1/λ_y, 1/λ_x) on the displacement
  gradient G = (u_x,x, u_y,y, u_x,y, u_y,x), mass ∫ ρ λ_x λ_y u·v. The −i f₀/a0 part makes the
  decay of a travelling wave per unit length independent of frequency; f₀ is set from the
  nominal reflection R of a normally incident P wave off the fixed back,
  |R| = exp(−2 (V_s/V_p) f₀ L /(b (m + 1))) (L the thickness, b = B/2). At low frequency the
  stretch grows as 1/a0, so the layer stands for an ever longer soil: the logarithmic growth
  of the 2D vertical and horizontal compliance is represented, not cut off by the box.
- ``lysmer``: viscous dashpots ρV_p (normal) and ρV_s (tangential) on the box's sides and
  bottom (:func:`~upliftlab.continuum.dynamics.waves.dashpot_data`), nothing fixed. Exact for a
  plane
  wave at normal incidence only; what it reflects (oblique and surface waves, and everything at
  low frequency, where the box is a fraction of a wavelength) comes back to the footing.

The box-size sensitivity of both is measured in ``benchmarks/impedance.py``.
"""

from __future__ import annotations

import math
import time as _time
from dataclasses import dataclass, field, replace
from pathlib import Path

import numpy as np
from scipy import sparse
from scipy.sparse.linalg import splu

from ... import checks
from ...checks import InputError
from ...results import write_netcdf
from ...scenes import ContinuumOptions
from .. import assembly
from ..dynamics.waves import dashpot_data, mass_data, wave_speeds
from ..materials import SOIL_MODELS, plane_strain_tangent
from ..output.fields import result_metadata
from ..statics.geostatic import elastic_tangent
from .pml import check_layer, pml_corrections

__all__ = ["ImpedanceOptions", "Impedance", "impedance", "impedance_model", "BOUNDARIES",
           "DEFAULT_A0", "DEFAULT_BOX", "static_normalisers"]

BOUNDARIES = ("pml", "lysmer")
#: Default dimensionless frequencies a0 = ω (B/2)/V_s.
DEFAULT_A0 = tuple(np.round(np.arange(0.1, 2.0001, 0.1), 10))
#: Default box (width, depth) in multiples of B per boundary: the PML sits close to the footing
#: (the graded mesh's elements grow with distance, and waves must be resolved up to the layer);
#: Lysmer dashpots need a large box (``benchmarks/impedance.py`` measures both).
DEFAULT_BOX = {"pml": (6.0, 3.0), "lysmer": (40.0, 20.0)}


@dataclass(frozen=True)
class ImpedanceOptions:
    """Options of :func:`impedance`: ``a0`` the dimensionless frequencies ω (B/2)/V_s (> 0);
    ``boundary`` ``pml`` or ``lysmer`` (module docstring); the box ``domain_width`` ×
    ``domain_depth`` (multiples of B; None: :data:`DEFAULT_BOX` of the boundary) that
    :func:`impedance_model` meshes; for the PML its ``pml_thickness`` (multiples of B, taken
    from the inside of the box's sides and bottom), the nominal normal-incidence P-wave
    ``pml_reflection`` R and the profile's polynomial ``pml_order`` m."""

    a0: tuple = DEFAULT_A0
    boundary: str = "pml"
    domain_width: float | None = None
    domain_depth: float | None = None
    pml_thickness: float = 1.5
    pml_reflection: float = 1e-4
    pml_order: int = 2

    def __post_init__(self):
        a0 = np.atleast_1d(np.asarray(self.a0, dtype=float)) if _numbers(self.a0) else None
        if a0 is None or a0.ndim != 1 or a0.size == 0 or not np.isfinite(a0).all() \
                or not (a0 > 0.0).all():
            raise InputError(f"impedance a0 = {self.a0!r}: expected a non-empty list of finite "
                             "frequencies > 0 (a0 = ω B/(2 V_s))")
        object.__setattr__(self, "a0", tuple(float(x) for x in a0))
        checks.one_of("impedance boundary", self.boundary, BOUNDARIES)
        width, depth = DEFAULT_BOX[self.boundary]
        object.__setattr__(self, "domain_width", width if self.domain_width is None else
                           checks.in_range("continuum.domain_width", self.domain_width, 1.0,
                                           1e4, low_open=True))
        object.__setattr__(self, "domain_depth", depth if self.domain_depth is None else
                           checks.in_range("continuum.domain_depth", self.domain_depth, 0.0,
                                           1e4, low_open=True))
        checks.positive("impedance pml_thickness", self.pml_thickness)
        r = checks.finite("impedance pml_reflection", self.pml_reflection)
        if not 0.0 < r < 1.0:
            raise InputError(f"impedance pml_reflection = {r:g}: valid range is (0, 1)")
        checks.integer_at_least("impedance pml_order", self.pml_order, 1)
        if self.boundary == "pml":
            check_layer(self.pml_thickness, 0.5 * self.domain_width, self.domain_depth)


def _numbers(values) -> bool:
    try:
        np.asarray(values, dtype=float)
    except (TypeError, ValueError):
        return False
    return True


def static_normalisers(shear_modulus: float, poisson: float, width: float) -> dict:
    """K_j,static per unit length used to normalise K_j = K_j,static [k_j + i a0 c_j]:
    rocking the exact πGB²/(8(1 − ν)) (frictionless strip on the half-plane); vertical
    0.73 G/(1 − ν) and horizontal 2G/(2 − ν), the L/B → ∞ limits of Gazetas (1991), Table 1,
    because the 2D static vertical and horizontal stiffnesses do not exist (they grow without
    bound with the domain). The coupling is normalised by √(K_h K_r)."""
    G, nu, B = shear_modulus, poisson, width
    out = {"v": 0.73 * G / (1.0 - nu), "h": 2.0 * G / (2.0 - nu),
           "r": math.pi * G * B * B / (8.0 * (1.0 - nu))}
    out["hr"] = math.sqrt(out["h"] * out["r"])
    return out


@dataclass(frozen=True, eq=False)
class Impedance:
    """The impedance functions of a footing: ``a0`` (n), ``matrix`` (n, 3, 3) complex per unit
    length for (u, v, θ) → (H, −N, M), e^{+iωt}; the ``soil`` (a :class:`~upliftlab.scenes.Soil`),
    footing ``width`` B, ``interface``, the ``mesh`` parameters and ``options`` that made it,
    ``dofs``; ``metadata`` provenance. Read by the Winkler comparisons for radiation dashpots."""

    a0: np.ndarray
    matrix: np.ndarray = field(repr=False)
    soil: object
    width: float
    interface: str
    mesh: dict
    options: ImpedanceOptions
    dofs: int
    metadata: dict = field(default_factory=dict, repr=False)

    @property
    def K_v(self) -> np.ndarray:
        return self.matrix[:, 1, 1]

    @property
    def K_h(self) -> np.ndarray:
        """Horizontal, θ held (zero on a frictionless interface)."""
        return self.matrix[:, 0, 0]

    @property
    def K_r(self) -> np.ndarray:
        """Rocking, horizontal motion held."""
        return self.matrix[:, 2, 2]

    @property
    def K_hr(self) -> np.ndarray:
        """Coupling ∂H/∂θ = ∂M/∂u."""
        return self.matrix[:, 0, 2]

    @property
    def omega(self) -> np.ndarray:
        """Circular frequency ω = a0 V_s/(B/2) (rad/s)."""
        return self.a0 * wave_speeds(self.soil)[1] / (0.5 * self.width)

    def normalisers(self) -> dict:
        """K_j,static of :func:`static_normalisers` for this soil and footing."""
        return static_normalisers(self.soil.shear_modulus, self.soil.poisson_ratio, self.width)

    def coefficients(self, mode: str) -> tuple[np.ndarray, np.ndarray]:
        """(k_j, c_j) of ``mode`` v, h, r or hr: K_j = K_j,static [k_j + i a0 c_j]."""
        K = {"v": self.K_v, "h": self.K_h, "r": self.K_r, "hr": self.K_hr}[mode]
        scale = self.normalisers()[mode]
        return K.real / scale, K.imag / (self.a0 * scale)

    def dashpot(self, mode: str) -> np.ndarray:
        """Dashpot coefficient C_j = Im K_j/ω (force·s per length² for v and h,
        force·length·s/rad per length for r)."""
        K = {"v": self.K_v, "h": self.K_h, "r": self.K_r, "hr": self.K_hr}[mode]
        return K.imag / self.omega

    def to_dict(self) -> dict:
        """The JSON summary: ``a0`` and ``K_v``, ``K_h``, ``K_r``, ``K_hr`` as [real, imag]."""
        pairs = lambda z: [[float(x.real), float(x.imag)] for x in z]  # noqa: E731
        return {"a0": [float(x) for x in self.a0], "K_v": pairs(self.K_v),
                "K_h": pairs(self.K_h), "K_r": pairs(self.K_r), "K_hr": pairs(self.K_hr),
                "interface": self.interface, "boundary": self.options.boundary,
                "width": self.width, "dofs": self.dofs, "units": self.metadata.get("units", {})}

    def save(self, path) -> Path:
        """Write the impedance functions to NetCDF (atomically), with provenance."""
        units = self.metadata.get("units", {})
        f = ("a0",)
        variables = {"a0": (f, self.a0, {"units": "1", "long_name":
                                         "dimensionless frequency omega (B/2) / V_s"}),
                     "omega": (f, self.omega, {"units": "rad/s", "long_name": "frequency"})}
        modes = {"K_v": "vertical", "K_h": "horizontal", "K_r": "rocking",
                 "K_hr": "horizontal-rocking coupling"}
        for name, K in (("K_v", self.K_v), ("K_h", self.K_h), ("K_r", self.K_r),
                        ("K_hr", self.K_hr)):
            variables[f"{name}_real"] = (f, K.real, {
                "units": units.get(name, ""),
                "long_name": f"{modes[name]} impedance per unit length, real part"})
            variables[f"{name}_imag"] = (f, K.imag, {
                "units": units.get(name, ""), "convention": "exp(+i omega t)",
                "long_name": f"{modes[name]} impedance per unit length, imaginary part"})
        return write_netcdf(path, variables, attrs={"kind": "impedance", "width": self.width,
                                                    **self.metadata})


# ---------------------------------------------------------------------------------------------
# The harmonic solve
# ---------------------------------------------------------------------------------------------


def _check(model) -> None:
    soil = model.soil
    if not model.material.linear:
        valid = " or ".join(repr(name) for name, record in SOIL_MODELS.items() if record.linear)
        raise InputError(f"soil.model = {soil.model!r}: the impedance analysis is for linear "
                         f"elastic soil; valid: {valid}")
    if not soil.density > 0.0:
        raise InputError(f"soil.density = {soil.density:g}: the impedance needs the soil's "
                         "mass; valid range is > 0")
    if soil.interface not in ("frictionless", "bonded"):
        raise InputError(f"soil.interface = {soil.interface!r}: the impedance is linear, for a "
                         "footing in full contact; valid: 'frictionless' or 'bonded'")
    if soil.layer_depth is not None:
        raise InputError(f"soil.layer_depth = {soil.layer_depth:g}: the impedance is of the "
                         "half-plane (absorbing sides and bottom); valid: no layer_depth")


def impedance_model(soil, footing_width: float, continuum: ContinuumOptions | None = None,
                    options: ImpedanceOptions = ImpedanceOptions(), *, scene=None):
    """The :class:`~upliftlab.continuum.ContinuumModel` the impedance is computed on: the mesh
    options of ``continuum`` (element, elements across, grading, quadrature; default: the
    scene's or :class:`~upliftlab.scenes.ContinuumOptions`) in the impedance's own box
    ``options.domain_width`` × ``options.domain_depth``. Checked before any mesh is built."""
    from ..model import make_model

    continuum = continuum or (scene.continuum if scene is not None and scene.continuum
                              else ContinuumOptions())
    continuum = replace(continuum, domain_width=options.domain_width,
                        domain_depth=options.domain_depth)
    gravity = scene.g if scene is not None else 9.80665
    model = make_model(soil, footing_width, continuum, gravity=gravity, scene=scene)
    _check(model)
    return model


def _fixed(model, options) -> np.ndarray:
    if options.boundary == "lysmer":
        return np.zeros(0, dtype=np.int64)
    basis = model.disc.basis
    return np.union1d(basis.get_dofs("sides").all(), basis.get_dofs("bottom").all())


def _partition(model, options) -> tuple[np.ndarray, np.ndarray]:
    """(free, contact) degrees of freedom of the harmonic solve: the PML box's sides and base
    are fixed behind its layers (none with Lysmer dashpots); the footing's are condensed."""
    contact = model.footing.contact_dofs
    fixed = np.setdiff1d(_fixed(model, options), contact)
    return np.setdiff1d(np.arange(model.disc.ndofs), np.union1d(fixed, contact)), contact


def harmonic_unknowns(model, options: ImpedanceOptions) -> int:
    """How many unknowns each frequency's solve has (the ``dofs`` of :class:`Impedance`),
    fewer than the static model's DOFs wherever the box's sides are held."""
    free, contact = _partition(model, options)
    return int(free.size + contact.size)


def impedance(model, options: ImpedanceOptions = ImpedanceOptions(), *,
              progress=None) -> Impedance:
    """The :class:`Impedance` of the footing of ``model`` (elastic soil, frictionless or bonded
    interface) at ``options.a0``, by one complex factorisation per frequency (module
    docstring). ``progress(k, n, a0)`` is called after each frequency. Every input is checked
    before any work (InputError naming the field, the value and the valid range)."""
    _check(model)
    started = _time.perf_counter()
    pml = pml_corrections(model, options) if options.boundary == "pml" else None
    pattern = model.disc.pattern
    D = plane_strain_tangent(elastic_tangent(model))
    K0 = assembly.stiffness(model.disc, D).data
    M0 = mass_data(model)
    C0 = dashpot_data(model, ["sides", "bottom"]) if options.boundary == "lysmer" \
        else np.zeros(pattern.nnz)
    free, contact = _partition(model, options)
    L = model.footing.kinematics
    vs = wave_speeds(model.soil)[1]
    a0 = np.asarray(options.a0, dtype=float)
    mats = np.zeros((a0.size, 3, 3), dtype=complex)
    for k, x in enumerate(a0):
        omega = x * vs / (0.5 * model.width)
        data = K0 + 1j * omega * C0 - omega ** 2 * M0
        if pml is not None:
            dK, dM = pml.corrections(x)
            data = data + dK - omega ** 2 * dM
        mats[k] = _solve(pattern.matrix(data), free, contact, L)
        if progress is not None:
            progress(k, a0.size, x)
    if not np.isfinite(mats).all():
        raise FloatingPointError("impedance: the harmonic solve produced non-finite forces "
                                 "(singular system); refine the mesh or change the boundary")
    extra = {"boundary": options.boundary, "pml_thickness": options.pml_thickness,
             "pml_reflection": options.pml_reflection, "pml_order": options.pml_order,
             "wall_time_s": _time.perf_counter() - started, "free_dofs": int(free.size)}
    metadata = result_metadata(model, "impedance", extra)
    metadata["units"] = _units(model)
    return Impedance(a0=a0, matrix=mats, soil=model.soil, width=model.width,
                     interface=model.soil.interface, mesh=dict(model.mesh_parameters),
                     options=options, dofs=int(free.size + contact.size), metadata=metadata)


def _solve(Z: sparse.csr_matrix, free, contact, L) -> np.ndarray:
    """Lᵀ f_c of the footing's unit rigid motions: Z_ff u_f = −Z_fc L, f_c = Z_cf u_f + Z_cc L."""
    Z_free = Z[free]
    lu = splu(Z_free[:, free].tocsc(), permc_spec="MMD_AT_PLUS_A",
              options=dict(SymmetricMode=True), diag_pivot_thresh=0.1)
    u_f = lu.solve(-(Z_free[:, contact] @ L).astype(complex))
    Z_c = Z[contact]
    f_c = Z_c[:, free] @ u_f + Z_c[:, contact] @ L
    return L.T @ f_c


def _units(model) -> dict:
    scene = model.scene
    if scene is None:
        return {}
    u = scene.units
    per = f"{u.force}/{u.length}/{u.length}"
    return {"K_v": per, "K_h": per, "K_r": f"{u.force}*{u.length}/rad/{u.length}",
            "K_hr": f"{u.force}/rad/{u.length}"}
