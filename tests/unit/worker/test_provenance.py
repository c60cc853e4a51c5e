"""The result key and the build: what changes a key and what does not."""

from __future__ import annotations

from pathlib import Path

from worker.provenance.build import BuildInfo, provenance_block, read_build, result_key

BUILD = BuildInfo(
    "0.1.0", "git:abc", (("python", "3.11.7"), ("numpy", "2.4.6"), ("scipy", "1.17.1"))
)
INPUTS = {"lengths": [2, 7, 9, 6], "ground": 1, "plots": True}


def test_the_key_sees_what_the_result_depends_on() -> None:
    key = result_key("fourbar-grashof", INPUTS, "1.0.0", BUILD)
    assert len(key) == 64
    assert result_key("fourbar-grashof", dict(reversed(INPUTS.items())), "1.0.0", BUILD) == key
    same_numbers = {**INPUTS, "lengths": [2.0, 7.0, 9.0, 6.0]}
    assert result_key("fourbar-grashof", same_numbers, "1.0.0", BUILD) == key
    changed = [
        result_key("fourbar-grashof", INPUTS, "1.0.1", BUILD),  # a version bump
        result_key("fourbar-grashof", {**INPUTS, "plots": False}, "1.0.0", BUILD),
        result_key("fourbar-grashof", {**INPUTS, "ground": 2}, "1.0.0", BUILD),
        result_key("chain-mobility", INPUTS, "1.0.0", BUILD),
        result_key(
            "fourbar-grashof", INPUTS, "1.0.0", BuildInfo("0.1.0", "git:abd", BUILD.libraries)
        ),
        result_key(
            "fourbar-grashof",
            INPUTS,
            "1.0.0",
            BuildInfo(
                "0.1.0", "git:abc", (("python", "3.11.7"), ("numpy", "2.5.0"), ("scipy", "1.17.1"))
            ),
        ),
    ]
    assert key not in changed and len(set(changed)) == len(changed)
    patch_only = BuildInfo("0.1.0", "git:abc", (("python", "3.11.9"), ("numpy", "2.4.7"),
                                                ("scipy", "1.17.2")))  # fmt: skip
    assert result_key("fourbar-grashof", INPUTS, "1.0.0", patch_only) == key


def test_a_build_id_names_the_build_else_the_checkout() -> None:
    assert read_build("ci-42").build == "ci-42"
    checkout = read_build("")
    assert checkout.build.startswith("git:") or checkout.build == ""
    assert dict(checkout.libraries).keys() == {"python", "numpy", "scipy"}
    assert (Path(__file__).parents[3] / "worker").is_dir()


def test_the_provenance_block_names_no_job_owner_host_or_time() -> None:
    block = provenance_block("p", "2.0.0", BUILD, "celery/postgresql", "k")
    assert block == {
        "dexlab": {"version": "0.1.0", "build": "git:abc"},
        "process": {"id": "p", "version": "2.0.0"},
        "libraries": {"python": "3.11.7", "numpy": "2.4.6", "scipy": "1.17.1"},
        "backend": "celery/postgresql",
        "result_key": "k",
    }
