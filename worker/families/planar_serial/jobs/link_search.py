"""The search of ``planar3r-design``: independent starts of differential evolution over
the exact d_z, each polished, the best kept, and whether the starts agree on it.

The score (:mod:`.design_objective`) is a minimum over points of piecewise-smooth
functions with plateaus, kinks and many local optima, so each start is scipy's
differential evolution (gradient-free, seeded, a whole population evaluated at once,
all generations run); SHGO was not chosen because it builds on local minimisers and a
simplicial complex that plateaus and kinks defeat.  Nelder-Mead (gradient-free too) then
polishes the start's best design within the same bounds.

One start can stall in a local optimum for good (more generations do not help: its
population has collapsed there), so the search runs ``starts`` independent ones, start
i seeded by ``SeedSequence(seed).spawn(...)[i]`` (the same for any number of starts),
keeps the best, and counts the starts whose best score lies within
:data:`AGREEMENT_TOL` of it: a best that no other start reaches is not confirmed.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray
from scipy.optimize import OptimizeResult, differential_evolution, minimize

from worker.families.planar_serial.design_spec import POLISH_EVALUATIONS_PER_VARIABLE
from worker.families.planar_serial.jobs.design_objective import Design, DesignObjective

__all__ = ["AGREEMENT_TOL", "SearchOutcome", "StartOutcome", "search", "start_seeds"]

#: Two starts agree when their best scores differ by at most this: 1e-4 in the
#: smallest d_z for 'max_min_dz' (the tie-break weighs at most 1e-6), 1e-4 of
#: total_length_max in the total length for 'min_length' (both meeting the target).
AGREEMENT_TOL = 1e-4

FloatArray = NDArray[np.float64]


def start_seeds(seed: int, starts: int) -> list[int]:
    """The seed of each start's random generator: ``SeedSequence(seed).spawn(starts)``,
    each child's first 32-bit word (start i's seed does not depend on ``starts``)."""
    return [int(child.generate_state(1)[0]) for child in np.random.SeedSequence(seed).spawn(starts)]


@dataclass(frozen=True)
class StartOutcome:
    """One start: its seed, its best design and score, and how it got there."""

    index: int
    seed: int
    best: Design
    score: float
    history: list[dict[str, float]]
    global_stage: dict[str, Any]
    polish: dict[str, Any]
    evaluations: int


@dataclass(frozen=True)
class SearchOutcome:
    """Every start, in order, and the one kept (the best score; the first on a tie)."""

    starts: tuple[StartOutcome, ...]

    @property
    def kept(self) -> StartOutcome:
        return min(self.starts, key=lambda start: start.score)

    @property
    def best(self) -> Design:
        return self.kept.best

    @property
    def history(self) -> list[dict[str, float]]:
        return self.kept.history

    @property
    def evaluations(self) -> int:
        return sum(start.evaluations for start in self.starts)

    @property
    def agreeing(self) -> list[int]:
        """Indices of the starts whose best score is within AGREEMENT_TOL of the kept."""
        best = self.kept.score
        return [s.index for s in self.starts if s.score - best <= AGREEMENT_TOL]


def search(
    objective: DesignObjective,
    *,
    seed: int,
    starts: int,
    population_size: int,
    generations: int,
    on_generation: Callable[[int, int], None],
) -> SearchOutcome:
    """``starts`` independent searches (:func:`search_once`); ``on_generation(done,
    total)`` after each generation of any start."""
    total = starts * generations
    outcomes = []
    for index, start_seed in enumerate(start_seeds(seed, starts)):
        done = index * generations

        def progress(generation: int, _: int, done: int = done) -> None:
            on_generation(done + generation, total)

        outcomes.append(
            search_once(objective, index=index, seed=start_seed, population_size=population_size,
                        generations=generations, on_generation=progress)
        )  # fmt: skip
    return SearchOutcome(tuple(outcomes))


def search_once(
    objective: DesignObjective,
    *,
    index: int,
    seed: int,
    population_size: int,
    generations: int,
    on_generation: Callable[[int, int], None],
) -> StartOutcome:
    """Differential evolution (best1bin, Latin-hypercube start, the population evaluated
    at once, no early stop), then Nelder-Mead from its best."""
    space = objective.space
    history: list[dict[str, float]] = []
    first_evaluation = objective.evaluations

    def record(x: FloatArray) -> None:
        design = objective.evaluate(*space.design(x))
        history.append({"generation": len(history), "min_dz": design.min_dz,
                        "total_length": design.total_length,
                        "score": objective.score(design)})  # fmt: skip

    def callback(intermediate_result: OptimizeResult) -> None:
        record(np.asarray(intermediate_result.x))
        on_generation(len(history), generations)

    found = differential_evolution(
        objective.population_scores, space.bounds, strategy="best1bin", maxiter=generations,
        popsize=population_size, tol=0.0, atol=0.0, polish=False, init="latinhypercube",
        rng=np.random.default_rng(seed), callback=callback, updating="deferred",
        vectorized=True,
    )  # fmt: skip
    de_evaluations = objective.evaluations - first_evaluation
    polished = minimize(
        objective, found.x, method="Nelder-Mead", bounds=space.bounds,
        options={"maxfev": POLISH_EVALUATIONS_PER_VARIABLE * len(space.bounds),
                 "xatol": 1e-10, "fatol": 1e-13},
    )  # fmt: skip
    better = bool(polished.fun < found.fun)
    best = objective.evaluate(*space.design(np.asarray(polished.x if better else found.x)))
    return StartOutcome(
        index=index,
        seed=seed,
        best=best,
        score=objective.score(best),
        history=history,
        global_stage={
            "method": "scipy.optimize.differential_evolution (best1bin)",
            "generations": int(found.nit),
            "population": population_size * len(space.bounds),
            "evaluations": de_evaluations,
            "best_score": float(found.fun),
            "message": str(found.message),
        },
        polish={
            "method": "Nelder-Mead",
            "evaluations": int(polished.nfev),
            "improved": better,
            "score_gain": float(found.fun - polished.fun) if better else 0.0,
            "message": str(polished.message),
        },
        evaluations=objective.evaluations - first_evaluation,
    )
