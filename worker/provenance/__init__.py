"""Provenance: what computed a result, and the digests that let two results be compared.

- :mod:`worker.provenance.build`: the dexlab build (read once, at start-up), the result
  key naming a computation, and the ``provenance`` block of a result.
- :mod:`worker.provenance.result_hash`: ``result_hash``, the digest of a result's values
  and its NPZ files' arrays, numbers to 12 significant digits (pure).
- :mod:`worker.provenance.stamp`: a finished outcome stamped with both, in its result
  document and its NPZ files' metadata.

Nothing is imported here: the settings read the build without loading numpy.
"""
