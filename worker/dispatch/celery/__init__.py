"""Dispatch over Celery: the app and its task (:mod:`.app`), sending job IDs and the
sweeper (:mod:`.dispatch`), and the worker side (:mod:`.worker`)."""
