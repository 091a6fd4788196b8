"""Exceptions raised by argus_tracking.

Every exception is an :class:`ArgusError`; its message is the Rust error's text with the
argument, index or step it concerns, and ``rust_error`` names the Rust error's type and
variant (for example ``"FilterError::Math::NotPositiveDefinite"``).
"""

from __future__ import annotations

__all__ = [
    "ArgusError",
    "ArgusOSError",
    "InvalidInputError",
    "NumericalError",
    "UnknownScenarioError",
]


class ArgusError(Exception):
    """Base class of the package's exceptions."""

    def __init__(self, message: str, rust_error: str = "") -> None:
        super().__init__(message)
        self.message = message
        #: The Rust error's type and variant, e.g. ``"FilterError::InvalidInterval"``.
        self.rust_error = rust_error


class InvalidInputError(ArgusError, ValueError):
    """Bad input: wrong shape or dtype, NaN, a non-positive-definite covariance, time
    going backwards, a bad parameter or configuration. The object called is unchanged."""


class NumericalError(ArgusError, ArithmeticError):
    """A step failed on valid input (e.g. a covariance that lost positive definiteness)."""


class UnknownScenarioError(InvalidInputError, KeyError):
    """No scenario of that name (see :func:`argus_tracking.list_scenarios`)."""

    def __str__(self) -> str:  # KeyError would quote the message
        return self.message


class ArgusOSError(ArgusError, OSError):
    """A file could not be read or written."""
