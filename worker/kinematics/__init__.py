"""Pure numerical cores (numpy only): no I/O, no import-time work.

Import the modules directly, e.g. ``from worker.kinematics import planar_serial``:
``planar_serial`` (three-link planar arms, Patel & Sobh), ``grashof`` (four-bar
Grashof checks) and ``trajectory`` (distance ranges of task points and paths).
"""
