"""upliftlab.meshes: graded plane-strain soil meshes with named boundaries, meshio I/O and
mesh quality.

- :func:`soil_mesh` / :func:`from_options`: a soil domain under a strip footing, graded towards
  the footing edges, as a :class:`SoilMesh` holding a scikit-fem mesh with the boundaries
  ``footing``, ``surface``, ``sides`` and ``bottom``; :func:`footing_dofs` for a basis on it.
- :func:`write_mesh` / :func:`read_mesh`: VTU, XDMF and Gmsh files that keep the boundaries.
- :func:`check_quality`: corner angles and aspect ratios; degenerate meshes are refused.
"""

from .io import read_mesh, write_mesh
from .quality import (MeshQuality, aspect_ratios, check_quality, corner_angles, element_areas,
                      max_aspect_ratio, min_angle, quality)
from .soil import BOUNDARIES, FootingDofs, SoilMesh, footing_dofs, from_options, soil_mesh

__all__ = ["BOUNDARIES", "SoilMesh", "FootingDofs", "soil_mesh", "from_options", "footing_dofs",
           "write_mesh", "read_mesh", "MeshQuality", "element_areas", "corner_angles",
           "aspect_ratios", "min_angle", "max_aspect_ratio", "quality", "check_quality"]
