"""Tests of the sync facade, its portal and its generator."""
