"""The numeric result paths of ``design-study`` (:mod:`worker.result_paths`).

A design's ``parameters`` and ``objectives`` are keyed by the study's own input and
result paths (``*``): each value is in the unit of its input (the process's input
schema) or of its objective (the process's ``result_paths``), as ``designs.csv``
names them (:mod:`.files`).
"""

from __future__ import annotations

from worker.result_paths import ResultPathInfo as R
from worker.result_paths import prefixed

__all__ = ["STUDY_RESULT_PATHS"]

_DESIGN = (
    R("index", "-", "", "The design's index (grid order, or the sample's)."),
    R("parameters.*", "mixed", "", "Its value of each varied input, keyed by the input's "
      "path, in that input's unit."),
    R("objectives.*", "mixed", "", "Its value of each objective, keyed by the result path, "
      "in the unit of that path (the process's result_paths)."),
)  # fmt: skip

STUDY_RESULT_PATHS = (
    R("count", "-", "", "Designs in the study."),
    R("evaluated", "-", "", "Designs evaluated (count minus those of missing chunks)."),
    R("feasible", "-", "", "Designs with a value for every objective."),
    R("missing", "-", "", "Designs of chunks that failed (allow_partial)."),
    R("infeasible.*", "-", "", "Infeasible designs per reason code: refused (the process "
      "refuses them), no-value (no value for some objective), failed (their run failed)."),
    R("infeasible_reasons[].designs", "-", "", "Designs infeasible for this reason."),
    R("pareto_size", "-", "", "Non-dominated designs."),
    *prefixed("pareto[]", _DESIGN),
    *prefixed("best.*[]", _DESIGN),
    R("paper_points[].parameters.*", "mixed", "", "The paper's design: its value of each "
      "varied input, keyed by the input's path."),
    *prefixed("paper_points[].design", _DESIGN),
    R("chunks", "-", "", "Chunks run."),
)  # fmt: skip
