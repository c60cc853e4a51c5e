"""Design studies (``design-study``): one single-design process evaluated over many
designs, and the non-dominated set of the chosen objectives.

The pieces that do not need the job runtime live here: input and result paths
(:mod:`.paths`), the designs of a grid or a low-discrepancy sample (:mod:`.designs`),
and the Pareto filter (:mod:`.pareto`).
"""
