"""The client commands of ``dexlab`` run as subprocesses against a real service: exit
codes (0 done, 1 a problem or a failed job, 2 a usage error, 130 interrupted), JSON for
scripts, tables for people, never a traceback."""

from __future__ import annotations

import json
import os
import signal
import subprocess
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest

from tests.integration.servers import Deployment, deployment, dexlab_command, free_port

pytestmark = pytest.mark.integration

LONG_MAP = {
    "links": [15, 14, 8],
    "joint_limits_deg": [[-150, 150], [-150, 150], [-175, 175]],
    "grid": {"points_per_axis": 801},
    "orientation_step_deg": 0.5,
    "method": "orientation-sampling",
}


@pytest.fixture(scope="module")
def server(tmp_path_factory: pytest.TempPathFactory) -> Iterator[Deployment]:
    with deployment("embedded", tmp_path_factory.mktemp("cli")) as dep:
        yield dep


def dexlab(server: Deployment, *args: str, stdin: str | None = None, timeout: float = 120,
           env: dict[str, str] | None = None) -> subprocess.CompletedProcess[str]:  # fmt: skip
    env = {k: v for k, v in os.environ.items() if k != "DEXLAB_API_KEY"} | (env or {})
    env["DEXLAB_URL"] = server.base_url
    done = subprocess.run([*dexlab_command(), *args], input=stdin, capture_output=True,
                          text=True, env=env, timeout=timeout)  # fmt: skip
    assert "Traceback" not in done.stderr + done.stdout, done.stderr
    return done


def job_id_of(stderr: str) -> str:
    return next(line.split()[1] for line in stderr.splitlines() if line.startswith("Job "))


def test_run_an_example_waits_and_downloads_every_file(server: Deployment, tmp_path: Path) -> None:
    done = dexlab(server, "run", "fourbar-grashof", "--example", "0", "--wait",
                  "--download", str(tmp_path / "files"))  # fmt: skip
    assert done.returncode == 0, done.stderr
    assert "triple-rocker" in done.stdout and "Wrote 2 files" in done.stdout
    # every nested value, with its symbol and unit (Fig 3 is in cm)
    margin = next(line for line in done.stdout.splitlines() if "criterion.margin" in line)
    assert margin.split() == ["criterion.margin", "p", "+", "q", "-", "(s", "+", "l)", "-4", "cm"]
    listed = server.client.get(f"/v1/jobs/{job_id_of(done.stderr)}/results").json()["artifacts"]
    for artifact in listed:
        path = tmp_path / "files" / artifact["name"]
        assert path.stat().st_size == artifact["size"]
    assert sorted(p.name for p in (tmp_path / "files").iterdir()) == sorted(
        a["name"] for a in listed
    )


def parsed(done: subprocess.CompletedProcess[str]) -> Any:
    assert done.returncode == 0, done.stderr
    return json.loads(done.stdout)


def test_json_output_parses(server: Deployment, tmp_path: Path) -> None:
    results = parsed(dexlab(server, "run", "fourbar-grashof", "--example", "1", "--wait", "--json"))
    assert results["result"]["classification"] == "crank-rocker"
    job_id = results["jobID"]
    assert parsed(dexlab(server, "status", job_id, "--json"))["status"] == "successful"
    again = parsed(dexlab(server, "results", job_id, "--json", "--download", str(tmp_path)))
    assert again["downloaded"] == [str(tmp_path / a["name"]) for a in again["artifacts"]]
    listed = parsed(dexlab(server, "jobs", "--process", "fourbar-grashof", "--json"))
    assert job_id in [j["jobID"] for j in listed]
    assert {p["id"] for p in parsed(dexlab(server, "processes", "--json"))} >= {"fourbar-grashof"}
    assert len(parsed(dexlab(server, "describe", "fourbar-grashof", "--json"))["examples"]) == 5
    queued = parsed(dexlab(server, "run", "fourbar-grashof", "--inputs", "-", "--json",
                           stdin='{"inputs": {"lengths": [2, 7, 9, 6], "ground": 1}}'))  # fmt: skip
    assert queued["status"] in ("accepted", "running", "successful")


def test_human_output_is_tables(server: Deployment) -> None:
    done = dexlab(server, "processes")
    assert done.returncode == 0 and "fourbar-grashof" in done.stdout and "┃" in done.stdout
    done = dexlab(server, "describe", "fourbar-grashof")
    assert "Worked examples" in done.stdout and "crank-rocker" in done.stdout
    submitted = dexlab(server, "run", "chain-parallelism", "--example", "1")
    assert submitted.returncode == 0 and "submitted" in submitted.stdout
    job_id = submitted.stdout.split()[1]
    listed = dexlab(server, "jobs", "--limit", "0", env={"COLUMNS": "80"}).stdout.splitlines()
    assert max(len(line) for line in listed) <= 80
    row = next(line.split() for line in listed if line and job_id.startswith(line.split()[0]))
    assert row[1] == "chain-parallelism" and len(row[0]) < len(job_id)
    # the short ID the table shows is accepted back, as is any unique prefix
    assert "chain-parallelism" in dexlab(server, "status", row[0]).stdout
    assert parsed(dexlab(server, "status", job_id[:13], "--json"))["jobID"] == job_id


@pytest.mark.parametrize(
    ("args", "phrase"),
    [
        (["run", "fourbar-grashof"], "--inputs FILE"),
        (["run", "fourbar-grashof", "--example", "0", "--inputs", "-"], "not both"),
        (["run", "fourbar-grashof", "--example", "99"], "'--example'"),
        (["run", "fourbar-grashof", "--example", "-1"], "'--example'"),
        (["run", "fourbar-grashof", "--inputs", "-"], "'--inputs': not JSON"),
        (["run", "fourbar-grashof", "--bogus"], "No such option '--bogus'"),
        (["jobs", "--status", "half-done"], "'--status'"),
        (["status"], "Missing argument 'JOB'"),
        (["processes", "--url", "ftp://example.org"], "'--url'"),
    ],
)
def test_a_usage_error_exits_2_with_one_line(
    server: Deployment, args: list[str], phrase: str
) -> None:
    done = dexlab(server, *args, stdin="{not json")
    assert done.returncode == 2, done
    lines = done.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("dexlab: ") and phrase in lines[0], lines


def test_a_problem_from_the_service_exits_1_with_its_fields(server: Deployment) -> None:
    done = dexlab(server, "run", "fourbar-grashof", "--inputs", "-", stdin='{"lengths": [1, 2]}')
    assert done.returncode == 1
    lines = done.stderr.strip().splitlines()
    assert lines[0].startswith("dexlab: Invalid inputs")
    assert {line.split(":")[0].strip() for line in lines[1:]} == {"inputs.lengths", "inputs.ground"}
    done = dexlab(server, "status", "no-such-job")
    assert done.returncode == 1
    assert done.stderr.strip() == "dexlab: No such job: No job 'no-such-job'."
    unreachable = dexlab(server, "processes", "--url", f"http://127.0.0.1:{free_port()}")
    assert unreachable.returncode == 1
    assert len(unreachable.stderr.strip().splitlines()) == 1
    assert "Cannot reach the dexlab service" in unreachable.stderr


def test_cancel_dismisses_a_running_job(server: Deployment) -> None:
    queued = parsed(dexlab(server, "run", "planar3r-dexterity-map", "--inputs", "-", "--json",
                           stdin=json.dumps(LONG_MAP)))  # fmt: skip
    done = dexlab(server, "cancel", queued["jobID"])
    assert done.returncode == 0 and done.stdout.strip() == f"Job {queued['jobID']} dismissed."
    gone = dexlab(server, "results", queued["jobID"])
    assert gone.returncode == 1 and "dismissed" in gone.stderr


def test_ctrl_c_while_waiting_asks_and_dismisses(server: Deployment, tmp_path: Path) -> None:
    inputs = tmp_path / "long.json"
    inputs.write_text(json.dumps(LONG_MAP))
    env = {**os.environ, "DEXLAB_URL": server.base_url}
    process = subprocess.Popen(
        [*dexlab_command(), "run", "planar3r-dexterity-map", "--inputs", str(inputs), "--wait"],
        stdin=subprocess.PIPE, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env,
    )  # fmt: skip
    assert process.stderr is not None
    first = process.stderr.readline()  # "Job <id> submitted; waiting ..."
    job_id = job_id_of(first)
    process.send_signal(signal.SIGINT)
    _, err = process.communicate(input="y\n", timeout=60)
    assert process.returncode == 130, err
    assert f"Dismiss job {job_id}?" in err and f"Job {job_id} dismissed." in err
    assert "Traceback" not in err
    assert server.client.get(f"/v1/jobs/{job_id}").json()["status"] == "dismissed"


def test_a_failing_job_exits_1_with_its_problem(tmp_path: Path) -> None:
    env = {"DEXLAB_MAX_TIME_LIMIT_S": "1", "DEXLAB_MAX_ATTEMPTS": "1"}
    with deployment("embedded", tmp_path, workers=1, env=env) as strict:
        done = dexlab(strict, "run", "planar3r-dexterity-map", "--inputs", "-", "--wait",
                      stdin=json.dumps(LONG_MAP))  # fmt: skip
        assert done.returncode == 1
        lines = done.stderr.strip().splitlines()
        assert lines[-2].startswith("dexlab: Time limit exceeded: ")
        assert lines[-1].strip().startswith("job ") and "time-limit-exceeded" in lines[-1]
        again = dexlab(strict, "results", job_id_of(done.stderr))
        assert again.returncode == 1 and "Time limit exceeded" in again.stderr


def test_your_own_arm_from_a_dh_table_or_a_urdf_gives_the_same_numbers(
    server: Deployment, tmp_path: Path
) -> None:
    """``--robot`` replaces the example's arm: the UR5 as a DH table (CSV) and as the
    worked example's URDF give the same poses and indices."""
    # lazy: the worked examples' arms, re-typed into files as a user would
    from worker.families.serial.arms import UR5_URDF

    table = tmp_path / "ur5.csv"
    table.write_text("a,alpha_deg,d\n0,90,0.089459\n-0.425,0,0\n-0.39225,0,0\n"
                     "0,90,0.10915\n0,-90,0.09465\n0,0,0.0823\n")  # fmt: skip
    urdf = tmp_path / "ur5.urdf"
    urdf.write_text(UR5_URDF["urdf"])
    poses = []
    links = ["--base-link", "base_link", "--tip-link", "tool0"]
    for extra in (["--robot", str(table)], ["--robot", str(urdf), *links]):
        done = parsed(dexlab(server, "run", "serial-indices", "--example", "0", *extra,
                             "--wait", "--json"))  # fmt: skip
        poses.append(done["result"]["poses"])
    assert len(poses[0]) == len(poses[1]) > 0
    for dh_pose, urdf_pose in zip(*poses, strict=True):
        assert dh_pose["position"] == pytest.approx(urdf_pose["position"], abs=1e-9)
        assert dh_pose["manipulability"] == pytest.approx(urdf_pose["manipulability"], abs=1e-9)
    refused = dexlab(server, "run", "serial-indices", "--example", "0", "--robot", str(urdf))
    assert refused.returncode == 2 and "base_link and tip_link" in refused.stderr
