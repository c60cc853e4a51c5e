"""Design studies (``design-study``): one single-design process evaluated over many
designs, and the non-dominated set of the chosen objectives.

The process and its chunks (:mod:`.process`, :mod:`.chunk`, :mod:`.chunking`), the two
engines (:mod:`.engine`: the process's study kernel, :mod:`.batched`, or the process
per design, :mod:`.evaluation`), a chunk's stored rows (:mod:`.rows`), the assembly
(:mod:`.assembly`, :mod:`.files`, :mod:`.figures`, :mod:`.outcome`), input and result
paths (:mod:`.paths`), the designs of a grid or a low-discrepancy sample
(:mod:`.designs`, :mod:`.hypercube`) and the Pareto filter (:mod:`.pareto`).
"""
