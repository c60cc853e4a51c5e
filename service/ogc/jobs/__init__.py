"""The OGC job resources: documents (:mod:`.documents`), the job-list parameters
(:mod:`.query`) and the handlers (:mod:`.routes`)."""
