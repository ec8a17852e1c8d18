"""The project's benchmarks: modules run from the repository root as
``python -m benchmarks.core.NAME`` (the core's speed and accuracy) and
``python -m benchmarks.app.NAME`` (the served explorer); their results under
benchmarks/results/."""
