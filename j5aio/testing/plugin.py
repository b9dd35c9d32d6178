"""The j5aio pytest plugin: fixtures for people who test robot backends.

Registered through the ``pytest11`` entry point, so installing j5aio makes its fixtures
available in every test suite.
"""
