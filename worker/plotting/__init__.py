"""Arrays in, PNG/SVG bytes out, with ``matplotlib.figure.Figure`` (never pyplot).

* :mod:`worker.plotting.render` -- ``figure_artifacts``: a figure as PNG + SVG artifacts;
* :mod:`worker.plotting.planar3r` -- the three-link planar arm's figures (Patel & Sobh).

Import the submodules directly; this package imports nothing, so loading it does not
load matplotlib.
"""
