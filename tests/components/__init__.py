"""Tests of the component classes.

A package, so that the test modules import the shared fakes relatively; that works for
pytest and for mypy with explicit package bases alike.
"""
