"""What the continuum's results write: the soil fields (:mod:`.fields`), XDMF time series for
ParaView (:mod:`.xdmf`), labelled datasets (:mod:`.labelled`), one-line summaries
(:mod:`.summaries`) and a run's files and figures (:mod:`.series`)."""

from .field_history import FieldHistory, check_history
from .summaries import dynamic_summary, pushover_summary, rotation_schedule, summary_line
from .xdmf import TimeAxis, read_xdmf, time_axis, write_footing_xdmf, write_xdmf

__all__ = ["FieldHistory", "check_history", "TimeAxis", "time_axis", "write_xdmf",
           "write_footing_xdmf", "read_xdmf", "rotation_schedule", "pushover_summary",
           "dynamic_summary", "summary_line"]
