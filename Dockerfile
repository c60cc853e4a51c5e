# dexlab: the API and a local worker pool on the embedded SQLite store.
FROM python:3.11-slim

ENV PYTHONDONTWRITEBYTECODE=1 PYTHONUNBUFFERED=1 MPLCONFIGDIR=/tmp/matplotlib
WORKDIR /app
COPY pyproject.toml README.md ./
COPY service ./service
COPY worker ./worker
COPY dexlab ./dexlab
# The same install as the README's, with the scale-out extra (Celery, Redis/AMQP
# clients, psycopg) so one image serves as API or worker, embedded or distributed.
RUN pip install --no-cache-dir '.[distributed]'
# The method pages (docs/methods/*.md) the service renders at /methods/<page>: a
# non-editable install does not carry them, so they live beside the package (copied
# after the install, so that editing a page does not redo it).
COPY docs ./docs
ENV DEXLAB_DOCS_DIR=/app/docs
# Logs as JSON lines (one object a line: time, level, logger, message, request_id,
# job_id) for a log shipper; DEXLAB_LOG_FORMAT=text for readable lines.
ENV DEXLAB_LOG_FORMAT=json

RUN useradd --create-home dexlab && mkdir /data && chown dexlab /data
USER dexlab
VOLUME /data
EXPOSE 8000
HEALTHCHECK --interval=30s --timeout=5s CMD python -c "import urllib.request; urllib.request.urlopen('http://127.0.0.1:8000/health/live')"
CMD ["dexlab", "serve", "--host", "0.0.0.0", "--port", "8000", "--data-dir", "/data"]
