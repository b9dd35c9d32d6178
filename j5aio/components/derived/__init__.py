"""Derived components: components built out of other components."""
