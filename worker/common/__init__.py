"""What two or more families share: array checks, grids, spec bases, data export,
figure rendering, progress.  Imports no family."""
