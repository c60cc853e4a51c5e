"""Benchmark the serial workspace map: the vectorised path against per-sample loops.

    python bench/serial_workspace.py [--samples 10000000] [--loop-samples 2000]

Everything printed is measured in this run, for the UR5 (standard DH, six revolute
joints; worker/families/serial/arms.py):

1. samples per second of the vectorised map kernel (forward kinematics, Jacobian,
   manipulability and inverse condition number, voxel and tool-axis binning) on a
   200,000-sample map;
2. the same per sample as a Python loop over chain.forward_kinematics + jacobian +
   indices.manipulability/inverse_condition (the same numbers, one sample at a time);
3. the Robotics Toolbox for Python (the reference library of the tests) called per
   sample: fkine + jacob0 + the two indices from numpy's SVD;
4. the full map from ``--samples`` joint samples (default 10^7: 5 cm voxels, 36
   orientation bins, manipulability and inverse condition, no plots) on one process,
   against the targets of issue 31: <= 60 s and >= 20x the per-sample loop.

The loops are timed on ``--loop-samples`` samples and scaled per sample.
"""

from __future__ import annotations

import argparse
import time

import numpy as np
import roboticstoolbox as rtb
from timing import best_time, seconds_per_item

from worker.families.serial.arms import UR5
from worker.families.serial.kinematics.chain import forward_kinematics, jacobian
from worker.families.serial.kinematics.indices import inverse_condition, manipulability
from worker.families.serial.kinematics.voxel_grid import voxel_grid
from worker.families.serial.kinematics.workspace_map import MapSettings, workspace_map
from worker.families.serial.robot_input import RobotSpec

TARGET_SECONDS = 60.0
TARGET_RATIO = 20.0


def reference_robot() -> rtb.DHRobot:
    """The UR5 in the Robotics Toolbox, from the same DH table."""
    links = [rtb.RevoluteDH(a=row["a"], alpha=np.radians(row["alpha_deg"]), d=row["d"])
             for row in UR5["dh"]]  # fmt: skip
    return rtb.DHRobot(links)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--samples", type=int, default=10_000_000)
    parser.add_argument("--loop-samples", type=int, default=2000)
    args = parser.parse_args()
    arm = RobotSpec.model_validate(UR5).arm("m")
    grid = voxel_grid(arm, 0.05, None, False)
    q = np.random.default_rng(0).uniform(arm.lower, arm.upper, (args.loop_samples, arm.joints))

    small = 200_000
    vector = best_time(lambda: workspace_map(arm, grid, MapSettings(small, "sobol", 0, 36)), 2)
    vector_rate = small / vector

    def loop_one(sample: np.ndarray) -> None:
        forward_kinematics(arm, sample)
        jac = jacobian(arm, sample)
        manipulability(jac)
        inverse_condition(jac)

    loop_rate = 1.0 / seconds_per_item(loop_one, q)
    robot = reference_robot()

    def rtb_one(sample: np.ndarray) -> None:
        robot.fkine(sample)
        sigma = np.linalg.svd(robot.jacob0(sample), compute_uv=False)
        float(np.prod(sigma))
        float(sigma[-1] / sigma[0])

    rtb_rate = 1.0 / seconds_per_item(rtb_one, q)
    print(f"UR5, 5 cm voxels ({grid.shape[0]} x {grid.shape[1]} x {grid.shape[2]}), 36 bins")
    print(f"vectorised map kernel : {vector_rate:12,.0f} samples/s ({small:,} samples)")
    print(f"per-sample chain loop : {loop_rate:12,.0f} samples/s  -> vectorised is "
          f"{vector_rate / loop_rate:6.1f}x")  # fmt: skip
    print(f"per-sample rtb calls  : {rtb_rate:12,.0f} samples/s  -> vectorised is "
          f"{vector_rate / rtb_rate:6.1f}x")  # fmt: skip

    start = time.perf_counter()
    result = workspace_map(arm, grid, MapSettings(args.samples, "sobol", 0, 36))
    seconds = time.perf_counter() - start
    rate = args.samples / seconds
    print(f"full map, {args.samples:,} samples: {seconds:.1f} s ({rate:,.0f} samples/s), "
          f"{int(result.reached.sum()):,} voxels reached; target <= {TARGET_SECONDS:.0f} s: "
          f"{'met' if seconds <= TARGET_SECONDS else 'NOT met'}")  # fmt: skip
    ratio = rate / loop_rate
    print(f"full map vs per-sample loop: {ratio:.1f}x; target >= {TARGET_RATIO:.0f}x: "
          f"{'met' if ratio >= TARGET_RATIO else 'NOT met'}")  # fmt: skip


if __name__ == "__main__":
    main()
