"""Figures with ``matplotlib.figure.Figure`` (never pyplot).

This package imports nothing, so loading it does not load matplotlib.
"""
