# The contact explorer (Panel/Bokeh server) as a container.
#
#   docker build -t zharii-explorer .
#   docker run -p 5006:5006 zharii-explorer          # then open http://localhost:5006/
#
# BASE: any Debian-like image with python3 >= 3.12 and its venv module.  The
# default is the official slim image; docker/smoke.sh passes a local base made
# with debootstrap (see docs/docker.md).  BUILD_BASE (default: BASE) is the base
# of the two build stages only: the same system, whose trust store may hold a
# build host's extra CA certificates for pip to reach the package index through
# a TLS-intercepting proxy (docker/build-base.sh).  The image is FROM BASE and
# takes nothing from the build stages but /opt/venv and /opt/zharii.  Runtime settings (PORT,
# ALLOWED_ORIGINS, NUM_PROCS, BASIC_AUTH, ADMIN, PANEL_ARGS) are documented in
# docs/docker.md; docker/compose.yaml runs it read-only behind nginx (docs/deploy.md).
#
# Stages are laid out for fast rebuilds on copy-based storage drivers (vfs):
# the dependencies form one cached layer that a code change does not touch,
# the project is pip-installed in a separate small stage, and the runtime
# stage puts all its metadata before its two COPY --from steps.
ARG BASE=python:3.12-slim
ARG BUILD_BASE=${BASE}

# ---- deps: /opt/venv with the dependencies of the project, its app and study extras
FROM ${BUILD_BASE} AS deps
ENV PIP_NO_CACHE_DIR=1 \
    PIP_DISABLE_PIP_VERSION_CHECK=1 \
    PIP_ROOT_USER_ACTION=ignore
WORKDIR /src
COPY pyproject.toml constraints.txt ./
# Whichever python3 the base has (/usr/local/bin in python:*, /usr/bin in
# Debian's).  The requirements are read from pyproject.toml and installed at the
# exact versions of the tested stack (constraints.txt), so only a change to
# either reinstalls numpy, scipy and panel.  The test suites that wheels ship
# (~90 MB) and pip go; a .pth file puts the project (next stage) on sys.path.
RUN python3 -c 'import sys; sys.exit(sys.version_info < (3, 12))' \
    || { echo "error: BASE must provide python3 >= 3.12" >&2; exit 1; } \
    && python3 -m venv /opt/venv \
    && /opt/venv/bin/python -c "import tomllib; p = tomllib.load(open('pyproject.toml', 'rb'))['project']; print('\n'.join(p['dependencies'] + p['optional-dependencies']['app'] + p['optional-dependencies']['study']))" > requirements.txt \
    && /opt/venv/bin/pip install --no-cache-dir -c constraints.txt -r requirements.txt \
    && find /opt/venv -depth -type d -name tests -path '*/site-packages/*/*' -exec rm -rf {} + \
    && /opt/venv/bin/pip uninstall --yes --quiet pip \
    && echo /opt/zharii/lib > "$(/opt/venv/bin/python -c 'import sysconfig; print(sysconfig.get_path("purelib"))')/zharii.pth"

# ---- pkg: the project itself, pip-installed from the build context ----------
FROM ${BUILD_BASE} AS pkg
# The context holds only what .dockerignore lets through: pyproject.toml,
# README.md, constraints.txt, core/, app/ (with its package data: the benchmark
# results its Methods scene charts, app/results/) and docker/entrypoint.sh.
WORKDIR /src
COPY . .
# /opt/zharii/lib: the installed packages core and app (+ metadata);
# /opt/zharii/app -> lib/app (the entry point runs `python -m app.serve`).
RUN python3 -m venv /tmp/pip \
    && /tmp/pip/bin/pip install --no-cache-dir --disable-pip-version-check --root-user-action=ignore \
         --no-deps --target /opt/zharii/lib '.[app]' \
    && ln -s lib/app /opt/zharii/app \
    && test -f /opt/zharii/app/main.py \
    && test -f /opt/zharii/app/results/speed_accuracy.csv \
    && cp docker/entrypoint.sh /opt/zharii/entrypoint.sh \
    && chmod 0755 /opt/zharii/entrypoint.sh

# ---- runtime ----------------------------------------------------------------
FROM ${BASE}
LABEL org.opencontainers.image.title="zharii-explorer" \
      org.opencontainers.image.description="Interactive explorer of Zharii's exact solution for the intermittent frictional contact of two elastic spheres (Panel/Bokeh server)" \
      org.opencontainers.image.licenses="MIT"
# ALLOWED_ORIGINS empty: only localhost:PORT and 127.0.0.1:PORT may open the
# websocket (list the public host[:port], or "*" on a classroom LAN).  NUM_PROCS=0:
# one server process per CPU the container may use.  The root filesystem may be
# read-only: the only writes are numba's compiled-kernel cache, under /tmp (a tmpfs
# in docker/compose.yaml).  MALLOC_*: glibc's allocator keeps two heaps (not one per
# thread) and hands freed memory above 128 KiB back to the system instead of keeping
# it (see docs/deploy.md, "Memory").  BOKEH_VALIDATE_DOC=false: Bokeh does not run its model
# checks (which only log warnings) on every new session's document, a tenth of a page
# load; `make serve` and the tests keep them on.
ENV PATH=/opt/venv/bin:$PATH \
    BOKEH_VALIDATE_DOC=false \
    MALLOC_ARENA_MAX=2 \
    MALLOC_TRIM_THRESHOLD_=131072 \
    MALLOC_MMAP_THRESHOLD_=131072 \
    PYTHONUNBUFFERED=1 \
    PYTHONDONTWRITEBYTECODE=1 \
    HOME=/home/app \
    PORT=5006 \
    ALLOWED_ORIGINS= \
    NUM_PROCS=0 \
    NUMBA_CACHE_DIR=/tmp/numba-cache
RUN useradd --uid 10001 --user-group --home-dir /home/app --create-home --shell /usr/sbin/nologin app
WORKDIR /opt/zharii
EXPOSE 5006
HEALTHCHECK --interval=30s --timeout=5s --start-period=60s --retries=3 \
    CMD ["python", "-c", "import os, urllib.request; urllib.request.urlopen('http://127.0.0.1:' + os.environ.get('PORT', '5006') + '/liveness', timeout=4)"]
ENTRYPOINT ["/opt/zharii/entrypoint.sh"]
CMD []
COPY --from=deps /opt/venv /opt/venv
COPY --from=pkg /opt/zharii /opt/zharii
# Every numba kernel the server runs (the closed form, the methods, the moving rotor:
# core.warm) compiled into the image, outside /tmp: a tmpfs mounted on /tmp hides
# what the image holds there.  The entry point copies this cache into NUMBA_CACHE_DIR
# when it starts with none, so the server loads the kernels (well under a second)
# instead of compiling them (about 11 s); where the CPU differs it compiles them once
# into the copy.
RUN NUMBA_CACHE_DIR=/opt/zharii/numba-cache python -m core.warm
USER 10001:10001
