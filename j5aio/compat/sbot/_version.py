"""The version of sbot whose API this package gives."""

__all__ = ["__version__"]

#: sbot's version, the API this package follows.
__version__ = "2026.1.0"
