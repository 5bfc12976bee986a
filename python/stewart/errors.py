"""Exceptions of the stewart package."""


class ParameterError(ValueError):
    """A platform parameter or solver option that the library refuses: the message names it and
    its value (the library's own message)."""
