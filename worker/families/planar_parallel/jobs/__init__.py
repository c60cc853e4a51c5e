"""One module per process: a spec in, a result and its artifacts out."""
