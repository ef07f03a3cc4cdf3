"""The soil models' factory and their input checks (upliftlab.continuum.materials).

References: the scene's soil table names the model (each ``soil.model`` gives its record, whose
update is the model's own pure function); the project's input rule (bad input is refused with
an InputError naming the field, the value and the valid range).
"""

from __future__ import annotations

import numpy as np
import pytest

from upliftlab.checks import InputError
from upliftlab.continuum import materials as mat
from upliftlab.scenes import Soil

E, NU, CU = 5.0e4, 0.3, 50.0


def test_material_from_soil_builds_the_right_model():
    cases = {
        Soil(E, NU): mat.Elastic,
        Soil(E, NU, model="von_mises", undrained_strength=CU, hardening_modulus=10.0):
            mat.VonMises,
        Soil(E, NU, model="tresca", undrained_strength=CU): mat.Tresca,
        Soil(E, NU, model="drucker_prager", cohesion=5.0, friction_angle=25.0,
             dilation_angle=5.0): mat.DruckerPrager,
        Soil(E, NU, model="mohr_coulomb", cohesion=0.0, friction_angle=35.0): mat.MohrCoulomb,
    }
    strain = np.diag([-3e-3, 1e-3, 0.0])
    for soil, cls in cases.items():
        material = mat.material_from_soil(soil)
        assert type(material) is cls
        sigma, tangent, state = material(strain, material.initial_state())
        ref = cls.update(strain, None, material)
        assert np.array_equal(sigma, ref[0]) and np.array_equal(tangent, ref[1])


BAD_SOILS = [
    (dict(youngs_modulus=0.0), "soil.youngs_modulus", "> 0"),
    (dict(poisson_ratio=0.5), "soil.poisson_ratio", "(-1, 0.5)"),
    (dict(poisson_ratio=-1.0), "soil.poisson_ratio", "(-1, 0.5)"),
    (dict(model="cam_clay"), "soil.model", "'mohr_coulomb'"),
    (dict(model="tresca"), "soil.undrained_strength", "> 0"),
    (dict(model="von_mises", undrained_strength=0.0), "soil.undrained_strength", "> 0"),
    (dict(model="von_mises", undrained_strength=CU, hardening_modulus=-1.0),
     "soil.hardening_modulus", ">= 0"),
    (dict(model="tresca", undrained_strength=CU, hardening_modulus=5.0),
     "soil.hardening_modulus", "[0, 0]"),
    (dict(model="mohr_coulomb", cohesion=-1.0, friction_angle=30.0), "soil.cohesion", ">= 0"),
    (dict(model="mohr_coulomb", cohesion=1.0, friction_angle=60.0),
     "soil.friction_angle", "[0, 60)"),
    (dict(model="drucker_prager", cohesion=1.0, friction_angle=-1.0),
     "soil.friction_angle", "[0, 60)"),
    (dict(model="drucker_prager", cohesion=1.0, friction_angle=20.0, dilation_angle=25.0),
     "soil.dilation_angle", "[0, friction_angle = 20]"),
    (dict(model="mohr_coulomb", cohesion=1.0, friction_angle=20.0, dilation_angle=-2.0),
     "soil.dilation_angle", "[0, friction_angle = 20]"),
    (dict(model="mohr_coulomb", cohesion=0.0, friction_angle=0.0), "soil.cohesion",
     "friction_angle > 0"),
]


@pytest.mark.parametrize("changes, field, valid", BAD_SOILS,
                         ids=[f"{c[1]}-{i}" for i, c in enumerate(BAD_SOILS)])
def test_bad_soil_raises_input_error_naming_field_value_and_range(changes, field, valid):
    soil = Soil(**{"youngs_modulus": E, "poisson_ratio": NU, **changes})
    with pytest.raises(InputError) as info:
        mat.material_from_soil(soil)
    message = str(info.value)
    assert message.startswith(field + " = ")
    assert valid in message


def test_parameter_records_validate_themselves():
    with pytest.raises(InputError, match=r"^MohrCoulomb\.friction_angle = 70"):
        mat.MohrCoulomb(E, NU, 1.0, 70.0)
    with pytest.raises(InputError, match=r"^VonMises\.poisson_ratio = 0\.5: valid range"):
        mat.VonMises(E, 0.5, CU)
    with pytest.raises(InputError, match=r"^Tresca\.undrained_strength = None"):
        mat.Tresca(E, NU, None)
