"""Errors that mean "the user's config is wrong" (exit status 2, like bad data)."""


class ConfigError(ValueError):
    """A config value outside what the pipeline accepts; the message names the key."""
