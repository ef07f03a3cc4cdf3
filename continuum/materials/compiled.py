"""What the compiled point returns of the soil models share, and the one call that finds a
model's return by its constants: :func:`point_return`.

The explicit route (:mod:`~upliftlab.continuum.dynamics.kernels`) evaluates the return map at
every quadrature point of every step in a compiled element loop. A soil model with a compiled
return has, beside its vectorised map, a point return for one plane-strain point, without the
tangent (an explicit step needs none), and a :class:`typing.NamedTuple` of the floats it reads
(its record's ``Constants``), which names that return as ``Constants.point``:

    point(constants, exx, eyy, ezz, exy, pxx, pyy, pzz, pxy, ebar[, gain])
        -> (stress xx, yy, zz, xy, plastic strain increment xx, yy, zz, xy, Δε̄p)

from the total strain (xx, yy, zz, xy; tensorial shear: the strain's zz component is the
geostatic eigenstrain's, xz = yz = 0), the converged plastic strain and ε̄p; a model whose
``Constants`` are ``graded`` (Tresca, von Mises: a strength that grows with depth,
:mod:`.undrained`) also takes the point's strength ``gain`` k z, added to the constants'.
Stresses in the constants' unit (kPa). The element loop calls :func:`point_return`, which numba resolves by
the constants' type when it compiles the loop and inlines: one compiled loop per model, with
no branch on the model inside it, cached by numba like any other kernel (the constants' type,
a named tuple class, is part of the cached signature).

Shared pieces: :func:`elastic_trial` (the elastic predictor every return starts from),
:func:`sorted_principal` and :func:`rotate_back` (principal values of a plane-strain stress and
back, for the principal-space returns of Tresca and Mohr–Coulomb), and :data:`RTOL`, the yield
tolerance of the vectorised maps: a point yields when f > 1e-12 × (strength + stress scale).
"""

from __future__ import annotations

import math

import numba as nb
from numba.extending import overload

__all__ = ["RTOL", "SQRT23", "point_return", "elastic_trial", "sorted_principal", "rotate_back"]

#: Yield is declared when f_trial > RTOL × (strength + stress scale), as in the vectorised maps.
RTOL = 1e-12
SQRT23 = math.sqrt(2.0 / 3.0)


def point_return(constants, exx, eyy, ezz, exy, pxx, pyy, pzz, pxy, ebar, gain=0.0):
    """The return map of the soil model whose ``constants`` these are, at one plane-strain
    point (module docstring): ``type(constants).point`` of the arguments, with the point's
    strength ``gain`` (kPa) for a model whose constants are ``graded`` (a strength that grows
    with depth, :mod:`.undrained`; a model without one refuses a gain). Called from Python it
    runs that compiled return; compiled, it is resolved by the constants' type and inlined."""
    cls = type(constants)
    if getattr(cls, "graded", False):
        return cls.point(constants, exx, eyy, ezz, exy, pxx, pyy, pzz, pxy, ebar, gain)
    if gain != 0.0:
        raise ValueError(f"gain = {gain!r}: the {cls.__name__} of this model take no strength "
                         "gain; valid: 0")
    return cls.point(constants, exx, eyy, ezz, exy, pxx, pyy, pzz, pxy, ebar)


@overload(point_return, inline="always")
def _point_return_of_type(constants, exx, eyy, ezz, exy, pxx, pyy, pzz, pxy, ebar, gain=0.0):
    """Resolve :func:`point_return` at compile time by the constants' named tuple class: a
    ``graded`` model's return gets the gain, another's does not (it is always zero there: the
    record's :meth:`~.base.Elasticity.strength_gain`)."""
    cls = getattr(constants, "instance_class", None)
    point = getattr(cls, "point", None)
    if point is None:
        return None
    if getattr(cls, "graded", False):
        def graded(constants, exx, eyy, ezz, exy, pxx, pyy, pzz, pxy, ebar, gain=0.0):
            return point(constants, exx, eyy, ezz, exy, pxx, pyy, pzz, pxy, ebar, gain)
        return graded

    def resolved(constants, exx, eyy, ezz, exy, pxx, pyy, pzz, pxy, ebar, gain=0.0):
        return point(constants, exx, eyy, ezz, exy, pxx, pyy, pzz, pxy, ebar)
    return resolved


@nb.njit(cache=True, inline="always")
def elastic_trial(lam, G, exx, eyy, ezz, exy, pxx, pyy, pzz, pxy):
    """The elastic predictor at one point: the elastic strain ε − εp (xx, yy, zz, xy), its
    trace, and the trial stress λ tr(ε − εp) 𝟏 + 2G (ε − εp) (xx, yy, zz, xy), λ and G in
    the stress unit."""
    exx, eyy, ezz, exy = exx - pxx, eyy - pyy, ezz - pzz, exy - pxy
    tr = exx + eyy + ezz
    sxx = lam * tr + 2.0 * G * exx
    syy = lam * tr + 2.0 * G * eyy
    szz = lam * tr + 2.0 * G * ezz
    sxy = 2.0 * G * exy
    return exx, eyy, ezz, exy, tr, sxx, syy, szz, sxy


@nb.njit(cache=True, inline="always")
def sorted_principal(sxx, syy, szz, sxy):
    """The plane-strain stress (xx, yy, zz, xy) in principal values, sorted: (``case``, s1 ≥
    s2 ≥ s3, cos 2α, sin 2α) with z at position ``case`` (0 first, 1 middle, 2 last) and α
    the in-plane principal axis; :func:`rotate_back` undoes it. Shared by the Tresca and
    Mohr–Coulomb returns."""
    centre = 0.5 * (sxx + syy)
    half = 0.5 * (sxx - syy)
    r = math.sqrt(half * half + sxy * sxy)
    if r > 0.0:
        cos2, sin2 = half / r, sxy / r
    else:
        cos2, sin2 = 1.0, 0.0
    pa, pb = centre + r, centre - r  # in-plane principal values, pa >= pb
    if szz >= pa:
        return 0, szz, pa, pb, cos2, sin2
    if szz >= pb:
        return 1, pa, szz, pb, cos2, sin2
    return 2, pa, pb, szz, cos2, sin2


@nb.njit(cache=True, inline="always")
def rotate_back(case, v1, v2, v3, cos2, sin2):
    """(xx, yy, zz, xy) of the principal values v1 ≥ v2 ≥ v3 (of the trial's order) with z at
    position ``case`` (0 first, 1 middle, 2 last) and the in-plane pair at the others, the
    in-plane principal axis at the angle whose (cos 2α, sin 2α) = (``cos2``, ``sin2``)."""
    if case == 0:
        vz, va, vb = v1, v2, v3
    elif case == 1:
        va, vz, vb = v1, v2, v3
    else:
        va, vb, vz = v1, v2, v3
    centre, radius = 0.5 * (va + vb), 0.5 * (va - vb)
    return centre + radius * cos2, centre - radius * cos2, vz, radius * sin2
