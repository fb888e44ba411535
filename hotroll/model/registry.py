"""One registry mechanism for the laws a case file selects by name, open to other packages.

A ``Registry`` maps a name to one object of its type (a law's spec). hotroll's own laws register
themselves when their module is imported (``register``); another package adds its laws through
the entry-point group ``hotroll.<kind>`` (``hotroll.flow_stress``, ``hotroll.friction``,
``hotroll.heat_transfer``, ``hotroll.microstructure``): each entry point's name is the law's name
and its object the spec, for example in the package's pyproject.toml::

    [project.entry-points."hotroll.friction"]
    my_law = "my_package.friction:SPEC"

The entry points are loaded on the first lookup (``get``, ``names``, ``in``, iteration), after
hotroll's own laws; one that cannot be loaded or is not a valid law stops the lookup with a
``PluginError`` naming the entry point and its distribution (docs/how-to/add-a-law.md).
"""
from __future__ import annotations

import importlib.metadata
import threading
import traceback
from collections.abc import Callable, Iterator, Mapping
from pathlib import Path
from typing import Generic, TypeVar

T = TypeVar("T")


class UnknownName(KeyError):
    """A name that is not registered (a ``KeyError``: dict-style ``in`` and ``.get`` work)."""

    def __str__(self) -> str:
        return str(self.args[0]) if self.args else ""


class PluginError(RuntimeError):
    """An entry point of another package that could not be loaded or is no valid law."""


class Registry(Mapping[str, T], Generic[T]):
    """The ``kind``'s objects (of ``type_``) by name, read-only as a mapping.

    ``noun`` names one object in messages ("friction law"); ``check(obj, registered)`` refuses an
    object by raising ``ValueError`` (``registered``: the objects so far, by name).
    """

    def __init__(self, kind: str, noun: str, type_: type[T],
                 check: Callable[[T, Mapping[str, T]], None] | None = None):
        self.kind, self.noun, self.type = kind, noun, type_
        self.group = f"hotroll.{kind}"
        self._check = check
        self._items: dict[str, T] = {}
        self._loaded = False
        self._error: PluginError | None = None
        self._lock = threading.RLock()

    def register(self, name: str, obj: T) -> T:
        """Add ``obj`` under ``name`` (a name once, an object of the registry's type); returns it."""
        if not isinstance(obj, self.type):
            raise TypeError(f"{self.noun} {name!r}: a {type(obj).__name__}, not a "
                            f"{self.type.__name__}")
        if name in self._items:
            raise ValueError(f"{self.noun} {name!r} registered twice")
        if self._check is not None:
            self._check(obj, self._items)
        self._items[name] = obj
        return obj

    def get(self, name: str, default=...) -> T:
        """The object named ``name``; an unknown name is refused naming the known ones (or
        ``default`` is returned when given, as ``dict.get``)."""
        try:
            return self[name]
        except UnknownName:
            if default is ...:
                raise
            return default

    def names(self) -> list[str]:
        """The registered names: hotroll's own in import order, then the plugins'."""
        return list(self)

    def pop(self, name: str, *default) -> T:
        """Remove ``name`` (as ``dict.pop``; for tests that register a law of their own)."""
        self._load()
        return self._items.pop(name, *default)

    def __getitem__(self, name: str) -> T:
        self._load()
        try:
            return self._items[name]
        except KeyError:
            raise UnknownName(f"unknown {self.noun} {name!r} (allowed: "
                              f"{', '.join(self._items)})") from None

    def __iter__(self) -> Iterator[str]:
        self._load()
        return iter(list(self._items))

    def __len__(self) -> int:
        self._load()
        return len(self._items)

    def __repr__(self) -> str:
        return f"Registry({self.group!r}, {list(self._items)})"

    def _load(self) -> None:
        """Load the group's entry points once (a failure is raised again on every lookup)."""
        with self._lock:
            if self._error is not None:
                raise self._error
            if self._loaded:
                return
            self._loaded = True          # a plugin looking the registry up while loading
            for ep in importlib.metadata.entry_points(group=self.group):
                try:
                    self._load_one(ep)
                except Exception as e:  # noqa: BLE001 - any failure of a plugin is reported
                    self._error = PluginError(_plugin_message(self.group, self.noun, ep, e))
                    raise self._error from None

    def _load_one(self, ep: importlib.metadata.EntryPoint) -> None:
        obj = ep.load()
        if not isinstance(obj, self.type):
            raise TypeError(f"a {type(obj).__name__}, not a {self.type.__name__}")
        if getattr(obj, "name", ep.name) != ep.name:
            raise ValueError(f"the entry point is named {ep.name!r}, the {self.noun} {obj.name!r}")
        if self._items.get(ep.name) is not obj:      # unless its module registered it on import
            self.register(ep.name, obj)


def _plugin_message(group: str, noun: str, ep: importlib.metadata.EntryPoint,
                    e: Exception) -> str:
    """The entry point, its distribution, the error and the plugin's line raising it (the last
    frame outside hotroll and importlib), in one line."""
    dist = getattr(ep, "dist", None)
    where = f"distribution {dist.name} {dist.version}" if dist is not None else "no distribution"
    ours = (str(Path(__file__).parents[1]), str(Path(importlib.__file__).parent))
    frames = [f for f in traceback.extract_tb(e.__traceback__)
              if not f.filename.startswith("<") and not f.filename.startswith(ours)]
    at = f" (at {frames[-1].filename}:{frames[-1].lineno})" if frames else ""
    return (f"the {group} entry point {ep.name} = {ep.value!r} ({where}) is no usable {noun}: "
            f"{type(e).__name__}: {e}{at}")
