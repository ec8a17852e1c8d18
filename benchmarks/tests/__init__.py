"""Tests of the benchmarks' own figures and helpers (collected with the project's tests:
pyproject's ``testpaths``); they import the benchmarks, and nothing in tests/ does."""
