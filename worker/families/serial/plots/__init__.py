"""Figures of the serial-arm jobs (matplotlib ``Figure``, never pyplot)."""
