"""A finished job's interactive heat map (:class:`worker.previews.DataChart`): which of
its files ``job-chart.js`` reads and how, for job.html.  The PNG plots stay; a page
without JavaScript shows only them."""

from __future__ import annotations

from typing import Any

from worker.contract import JobRecord
from worker.processes import ProcessDefinition

__all__ = ["data_chart_context"]


def data_chart_context(definition: ProcessDefinition | None, job: JobRecord) -> dict[str, Any]:
    """The chart's description and its CSV's URL, or {} when the process has none or
    this job did not write the file."""
    if definition is None or definition.data_chart is None:
        return {}
    chart = definition.data_chart
    if not any(a.name == chart.file for a in job.artifacts):
        return {}
    return {**chart.describe(), "href": f"/v1/jobs/{job.job_id}/results/{chart.file}"}
