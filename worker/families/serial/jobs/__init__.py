"""The serial-arm jobs (loaded when a job runs: matplotlib)."""
