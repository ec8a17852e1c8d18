"""Benchmarks of the core (speed, accuracy, the methods' tables): ``python -m
benchmarks.core.NAME`` from the repository root."""
