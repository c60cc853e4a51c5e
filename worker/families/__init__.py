"""The science: one package per mechanism family (its processes, kinematics, jobs
and plots).  The registry lists the families (:func:`worker.registry.family_packages`);
this package imports none of them."""
