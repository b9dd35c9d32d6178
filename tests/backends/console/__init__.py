"""Tests of the console environment."""
