# The contact explorer (Panel/Bokeh server) as a container.
#
#   docker build -t zharii-explorer .
#   docker run -p 5006:5006 zharii-explorer          # then open http://localhost:5006/
#
# BASE: any Debian-like image with python3 >= 3.12 and its venv module.  The
# default is the official slim image; docker/smoke.sh passes a local base made
# with debootstrap (see docs/docker.md).  Runtime settings (PORT,
# ALLOWED_ORIGINS, NUM_PROCS, PANEL_ARGS) are documented in docs/docker.md.
#
# Layer order is deliberate: the dependencies get their own cached layer, and
# the runtime stage puts its metadata before the one large COPY (each step
# after a large layer is slow on copy-based storage drivers such as vfs).
ARG BASE=python:3.12-slim

# ---- build stage: /opt/venv holds the project with its app extra ----------
FROM ${BASE} AS build
ENV PIP_NO_CACHE_DIR=1 \
    PIP_DISABLE_PIP_VERSION_CHECK=1 \
    PIP_ROOT_USER_ACTION=ignore
WORKDIR /src
COPY pyproject.toml ./
# Whichever python3 the base has (/usr/local/bin in python:*, /usr/bin in
# Debian's).  The dependencies are read from pyproject.toml, so editing the
# code does not reinstall numpy, scipy and panel.
RUN python3 -c 'import sys; sys.exit(sys.version_info < (3, 12))' \
    || { echo "error: BASE must provide python3 >= 3.12" >&2; exit 1; } \
    && python3 -m venv /opt/venv \
    && /opt/venv/bin/python -c "import tomllib; p = tomllib.load(open('pyproject.toml', 'rb'))['project']; print('\n'.join(p['dependencies'] + p['optional-dependencies']['app']))" > requirements.txt \
    && /opt/venv/bin/pip install --no-cache-dir -r requirements.txt
# The context holds only what .dockerignore lets through: pyproject.toml,
# README.md, core/, app/ and docker/entrypoint.sh.
COPY . .
# Install the project itself, drop the test suites that wheels ship (~90 MB)
# and pip, and lay out /opt/zharii: app -> the installed package, entrypoint.
RUN /opt/venv/bin/pip install --no-cache-dir --no-deps '.[app]' \
    && /opt/venv/bin/python -P -c 'import core, app, panel, bokeh; print("installed: panel", panel.__version__, "bokeh", bokeh.__version__)' \
    && find /opt/venv -depth -type d -name tests -path '*/site-packages/*/*' -exec rm -rf {} + \
    && /opt/venv/bin/pip uninstall --yes --quiet pip \
    && mkdir -p /opt/zharii \
    && ln -s "$(/opt/venv/bin/python -P -c 'import app, os; print(os.path.dirname(app.__file__))')" /opt/zharii/app \
    && cp docker/entrypoint.sh /opt/zharii/entrypoint.sh \
    && chmod 0755 /opt/zharii/entrypoint.sh \
    && /opt/venv/bin/python -P -c 'import core, app.explorer, panel, scipy.special, pandas'

# ---- runtime stage ---------------------------------------------------------
FROM ${BASE}
LABEL org.opencontainers.image.title="zharii-explorer" \
      org.opencontainers.image.description="Interactive explorer of Zharii's exact solution for the intermittent frictional contact of two elastic spheres (Panel/Bokeh server)" \
      org.opencontainers.image.licenses="MIT"
ENV PATH=/opt/venv/bin:$PATH \
    PYTHONUNBUFFERED=1 \
    PYTHONDONTWRITEBYTECODE=1 \
    HOME=/home/app \
    PORT=5006 \
    ALLOWED_ORIGINS=* \
    NUM_PROCS=1
RUN useradd --uid 10001 --user-group --home-dir /home/app --create-home --shell /usr/sbin/nologin app
WORKDIR /opt/zharii
EXPOSE 5006
HEALTHCHECK --interval=30s --timeout=5s --start-period=60s --retries=3 \
    CMD ["python", "-c", "import os, urllib.request; urllib.request.urlopen('http://127.0.0.1:' + os.environ.get('PORT', '5006') + '/liveness', timeout=4)"]
ENTRYPOINT ["/opt/zharii/entrypoint.sh"]
CMD []
USER 10001:10001
COPY --from=build /opt /opt
