"""Small immutable values that every run makes, without the cost of ``@dataclass``.

Python 3.11's ``@dataclass(frozen=True)`` writes the source of ``__init__``, ``__eq__``,
``__hash__``, ``__repr__``, ``__setattr__`` and ``__delattr__`` and compiles each with
``exec``: ~0.5 ms a class, paid by every run that imports it (``mcar check`` of a plain
URDF imports eight such classes: a tenth of its start-up over the bare interpreter).
A class derived from :class:`Value` names its fields in ``_fields`` (its ``__slots__``
too) and sets them in its own ``__init__`` with :meth:`Value._set`: code that is compiled
once, into the installed ``.pyc``. It then behaves as the frozen dataclass did: equal when
of the same class with equal fields, hashed by its fields, shown as ``Name(a=1, b=2)``,
no attribute assigned or deleted after ``__init__``; copied and pickled by its fields.
"""

from __future__ import annotations


class FrozenError(AttributeError):
    """An attribute of a :class:`Value` assigned or deleted (dataclasses'
    FrozenInstanceError, also an AttributeError)."""


class Value:
    __slots__ = ()
    _fields: tuple[str, ...] = ()

    def _set(self, *values) -> None:
        """In ``__init__``: the fields, in the order of ``_fields``."""
        for name, value in zip(self._fields, values, strict=True):
            object.__setattr__(self, name, value)

    def _values(self) -> tuple:
        return tuple([getattr(self, name) for name in self._fields])

    def __eq__(self, other):
        if other.__class__ is not self.__class__:
            return NotImplemented
        return self._values() == other._values()

    def __hash__(self) -> int:
        return hash(self._values())

    def __repr__(self) -> str:
        fields = ", ".join(f"{name}={getattr(self, name)!r}" for name in self._fields)
        return f"{self.__class__.__qualname__}({fields})"

    def __setattr__(self, name, value):
        raise FrozenError(f"cannot assign to field {name!r}")

    def __delattr__(self, name):
        raise FrozenError(f"cannot delete field {name!r}")

    def __reduce__(self):
        # Made again through __init__: the default for slots would assign each field.
        return self.__class__, self._values()
