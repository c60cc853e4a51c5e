"""OGC API - Processes - Part 1: Core (OGC 18-062r2, 1.0) as a façade at ``/ogc/``.

The same store, registry and jobs as the native ``/v1`` API, in the standard's
documents: a job created through one is visible through the other.

- :mod:`service.ogc.router` -- :func:`ogc_router`, the router the app includes;
- :mod:`service.ogc.routes`, :mod:`service.ogc.jobs.routes` -- the handlers;
- :mod:`service.ogc.process_documents`, :mod:`service.ogc.jobs.documents`,
  :mod:`service.ogc.results` -- the standard's documents;
- :mod:`service.ogc.execute_request`, :mod:`service.ogc.execution_mode`,
  :mod:`service.ogc.execution` -- execute requests, sync/async, results;
- :mod:`service.ogc.jobs.query` -- the job-list parameters;
- :mod:`service.ogc.pages` -- every GET resource as a page (conformance class ``html``);
- :mod:`service.ogc.forwarded`, :mod:`service.ogc.urls` -- absolute URLs behind proxies;
- :mod:`service.ogc.outbound`, :mod:`service.ogc.callbacks` -- the allow-listed
  requests the server makes (inputs by reference, subscriber callbacks);
- :mod:`service.ogc.vocabulary`, :mod:`service.ogc.schemas`, :mod:`service.ogc.outputs`.
"""
