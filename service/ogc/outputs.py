"""A process's outputs, as OGC API - Processes names them.

Two kinds, one output ID each:

- every member of the job's result document (``ProcessDefinition.outputs``, plus the
  ``notes`` and ``paper_errata`` every job reports), a JSON value;
- every file a job of the process can write, named by its file name (the same name as
  ``/v1/jobs/{jobID}/results/{name}``), in one media type.

The files a process writes are only known once it ran, so they are listed here, per
process, and checked against real runs by the tests
(tests/unit/service/test_ogc_outputs.py).  A job need not write all of them (``"plots":
false`` writes none of the figures); a process added at run time lists its result
members only.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

from service.ogc.vocabulary import JSON
from worker.processes import ProcessDefinition

__all__ = ["ARTIFACT_FILES", "MEDIA_TYPES", "OutputSpec", "process_outputs"]

#: File extension -> media type of the files jobs write.
MEDIA_TYPES: Mapping[str, str] = {
    "png": "image/png",
    "svg": "image/svg+xml",
    "csv": "text/csv",
    "npz": "application/x-npz",
}

_RUNNER_OUTPUTS: Mapping[str, str] = {
    "notes": "Remarks on the computation, in order; the paper's errata among them.",
    "paper_errata": "The notes that correct the paper (printed values that are wrong).",
}


def _figure(stem: str, title: str) -> tuple[tuple[str, str], ...]:
    return ((f"{stem}.png", f"{title} (PNG)"), (f"{stem}.svg", f"{title} (SVG)"))


def _data(stem: str, title: str) -> tuple[tuple[str, str], ...]:
    return ((f"{stem}.csv", f"{title} (CSV)"), (f"{stem}.npz", f"{title} (NumPy arrays)"))


#: Process ID -> (file name, title) of every file its jobs can write.
ARTIFACT_FILES: Mapping[str, tuple[tuple[str, str], ...]] = {
    "planar3r-dexterity-map": (
        *_figure("heatmap", "Dexterity d_z over the workspace"),
        *_figure("surface", "Dexterity d_z, 3-D surface"),
        *_figure("radial_section", "Dexterity d_z along a ray from the base"),
        *_data("dexterity_map", "Dexterity map"),
    ),
    "planar3r-synthesis": (
        *_figure("synthesis_cases", "d_z of the design in the paper's cases"),
        ("synthesis_cases.npz", "d_z maps of the cases (NumPy arrays)"),
    ),
    "planar2dof-conditioning-map": (
        *_figure("inverse_condition_map", "Conditioning index 1/kappa (Fig. 4)"),
        *_figure("pressure_angle_map", "Minimum pressure angle beta_min (Fig. 5)"),
        *_data("conditioning_map", "Conditioning map, one row per grid node"),
    ),
    "planar2dof-optimisation": (
        *_figure("conditioning_limit", "1/kappa0 against [beta] and delta (Fig. 7)"),
        *_figure("design_indices", "S/S_max, mean 1/kappa and eta against delta (Fig. 8)"),
        *_figure("normalised_rectangle", "1/kappa and beta_min over the rectangle (Fig. 9)"),
        *_figure("rectangle_workspace", "The rectangle inside W_kappa0 (Fig. 6)"),
        ("sweep.csv", "The delta sweep, one row per delta (CSV)"),
        ("optimisation.npz", "The sweep and the figures' arrays (NumPy arrays)"),
    ),
    "chain-parallelism": (
        *_figure("chain_graphs", "Link graphs of the chains, loops marked"),
        *_figure("parallelism_comparison", "P and Q of the chains compared"),
    ),
    "fourbar-grashof": _figure("fourbar_motion", "Range of motion and fully turning links"),
    "spm-conditioning-map": (
        *_figure("inverse_condition_map", "1/kappa over tilt x azimuth at fixed torsions"),
        *_figure("torsion_sweeps", "1/kappa along a full torsion turn"),
        ("conditioning_samples.csv", "Inverse kinematics and 1/kappa at the samples (CSV)"),
        ("conditioning_map.npz", "Conditioning map (NumPy arrays)"),
    ),
    "spm-design-space": (
        *_figure("design_space", "Sub-design spaces in the a1-a2 plane"),
        *_figure("index_map", "mean(1/kappa^2) over one sub-design space"),
        *_data("design_space", "Design space per beta"),
    ),
    "spm-optimisation": (
        *_figure("index_map", "mean(1/kappa^2) over the optimum's design space"),
        *_figure("starts", "Final mean(1/kappa^2) of every start"),
        *_figure("torsion_sweeps", "1/kappa of the optimum along torsion turns"),
        ("optimisation_starts.csv", "Every optimisation start (CSV)"),
        ("optimisation.npz", "Optimisation (NumPy arrays)"),
    ),
}


@dataclass(frozen=True)
class OutputSpec:
    """One output: a result member (``artifact`` False, JSON) or a file."""

    id: str
    title: str
    description: str
    media_type: str
    artifact: bool

    def describe(self) -> dict[str, Any]:
        """The OGC output description (outputDescription.yaml)."""
        schema: dict[str, Any]
        if self.artifact:
            schema = {"type": "string", "contentMediaType": self.media_type}
            if self.media_type != "image/svg+xml" and not self.media_type.startswith("text/"):
                schema["contentEncoding"] = "binary"
        elif self.id in _RUNNER_OUTPUTS:
            schema = {"type": "array", "items": {"type": "string"}}
        else:
            schema = {}  # any JSON value: the result member's shape is in its description
        return {"title": self.title, "description": self.description, "schema": schema}


def process_outputs(definition: ProcessDefinition) -> dict[str, OutputSpec]:
    """Every output of ``definition``, by ID, in order: result members, then files."""
    outputs = {
        key: OutputSpec(key, key.replace("_", " "), text, JSON, artifact=False)
        for key, text in {**definition.outputs, **_RUNNER_OUTPUTS}.items()
    }
    for name, title in ARTIFACT_FILES.get(definition.id, ()):
        media_type = MEDIA_TYPES[name.rsplit(".", 1)[-1]]
        description = f"{title}: a file of the job, as downloaded from its results."
        outputs[name] = OutputSpec(name, title, description, media_type, artifact=True)
    return outputs
