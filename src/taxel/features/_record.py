"""Result records of the features: frozen dataclasses that are quick to build (internal).

A frozen dataclass's own ``__init__`` sets each field through ``object.__setattr__`` (its
own ``__setattr__`` refuses), which costs about a microsecond a field; `extract` builds
about 80 fields of records per call. `record` makes a frozen dataclass whose ``__init__``
writes the fields into the instance's ``__dict__`` directly, which is where
``object.__setattr__`` puts them: equality, hashing, ``repr``, ``asdict`` and the refusal
of any assignment after construction are those of the frozen dataclass.
"""

from __future__ import annotations

import dataclasses
from typing import Any, TypeVar, dataclass_transform

__all__ = ["record"]

T = TypeVar("T")


@dataclass_transform(frozen_default=True)
def record(cls: type[T]) -> type[T]:
    """``dataclass(frozen=True)`` with a quicker ``__init__`` (see the module notes).

    For plain records only: every field is set by ``__init__`` and has no default, and the
    class has no ``__post_init__`` or ``__slots__`` (checked).
    """
    frozen = dataclasses.dataclass(frozen=True)(cls)
    fields = dataclasses.fields(frozen)  # type: ignore[arg-type]
    plain = all(
        field.init
        and field.default is dataclasses.MISSING
        and field.default_factory is dataclasses.MISSING
        for field in fields
    )
    if not plain or hasattr(frozen, "__post_init__") or hasattr(frozen, "__slots__"):
        raise TypeError(f"{cls.__name__}: `record` takes plain fields only")
    names = [field.name for field in fields]
    # the same kind of generated function as dataclasses' own __init__
    lines = [f"def __init__(self, {', '.join(names)}):", "    values = self.__dict__"]
    lines += [f"    values[{name!r}] = {name}" for name in names]
    namespace: dict[str, Any] = {}
    exec("\n".join(lines), {}, namespace)
    init = namespace["__init__"]
    init.__qualname__ = f"{frozen.__qualname__}.__init__"
    init.__doc__ = frozen.__init__.__doc__
    frozen.__init__ = init  # type: ignore[method-assign]
    return frozen
