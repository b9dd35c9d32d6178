"""sbot's internal modules that programs reach: :mod:`.exceptions`."""
