"""Tests of the board definitions."""
