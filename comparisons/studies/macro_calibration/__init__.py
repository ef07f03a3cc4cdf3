"""A user's own macro-element, calibrated from the continuum's statics of the user's scene
(``upliftlab calibrate SCENE``, issue 36 §2): the runs (:mod:`.plan`), the fit and its checks
(:mod:`.fit`), and what the user gets (:mod:`.output`). Not a study of the report: it belongs
to one scene, as ``upliftlab continuum`` does."""

from .fit import FitCache, PLATEAU_TOLERANCE, SceneCalibration, calibrate_scene
from .output import (calibration_markdown, calibration_record, check_reduced_scene,
                     scene_overrides)
from .plan import (DEFAULT_FS_V, PATHS, check_fs_v, check_reach, estimated_capacity,
                   macro_strength, rotation_steps)

__all__ = ["SceneCalibration", "calibrate_scene", "FitCache", "PLATEAU_TOLERANCE",
           "calibration_markdown", "calibration_record", "check_reduced_scene",
           "scene_overrides", "DEFAULT_FS_V", "PATHS", "check_fs_v", "macro_strength",
           "rotation_steps", "check_reach", "estimated_capacity"]
