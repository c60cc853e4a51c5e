"""Pure numpy/scipy."""
