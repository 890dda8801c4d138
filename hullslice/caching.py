"""Caches kept on an object for the layers above it: named, typed entries, bounded, locked.

An object that others compute things about (a :class:`~hullslice.mesh.Hull`, a pitch's
frame) owns one :class:`Cache`; each layer that fills an entry declares its :class:`Entry`
(a name, a factory for the empty value, and whether the value depends on the body's
geometry alone) next to the code that fills it, so the owner needs to know nothing of what
is kept, and no attribute is added to it from outside::

    FRAMES: Entry[LRU[float, Frame]] = Entry("frames", lambda: LRU(4))
    frames = hull.cache[FRAMES]  # made empty on first use

:class:`LRU` is a small least-recently-used mapping for the entries that are bounded,
:class:`Once` a value computed on first use. All are safe under threads: a lock guards the
making of an entry and of a value, and every read or write of an :class:`LRU`.
"""

from __future__ import annotations

import threading
from collections import OrderedDict
from collections.abc import Callable, Hashable, Iterator
from typing import Any, Generic, TypeVar, cast

__all__ = ["LRU", "Cache", "Entry", "Once"]

K = TypeVar("K", bound=Hashable)
V = TypeVar("V")
T = TypeVar("T")


class Entry(Generic[T]):
    """The key of one entry of a :class:`Cache`: its name and how to make it empty.

    Parameters
    ----------
    name : str
        What the entry holds (for ``repr`` and messages).
    make : callable
        Makes the entry's empty value, called once per cache on first use.
    geometry : bool
        The value depends on the body's geometry alone (vertices and faces), not on its
        mass or centre of gravity: :meth:`Cache.geometry` shares it with a body of the
        same geometry.
    """

    __slots__ = ("geometry", "make", "name")

    def __init__(self, name: str, make: Callable[[], T], *, geometry: bool = False) -> None:
        self.name = name
        self.make = make
        self.geometry = geometry

    def __repr__(self) -> str:
        return f"Entry({self.name!r})"


class Cache:
    """Entries kept for an object, each made empty on first use (see :class:`Entry`)."""

    __slots__ = ("_entries", "_lock")

    def __init__(self) -> None:
        self._entries: dict[Entry[Any], Any] = {}
        self._lock = threading.Lock()

    def __getitem__(self, entry: Entry[T]) -> T:
        try:
            return cast(T, self._entries[entry])
        except KeyError:
            with self._lock:
                if entry not in self._entries:
                    self._entries[entry] = entry.make()
                return cast(T, self._entries[entry])

    def get(self, entry: Entry[T]) -> T | None:
        """The entry's value if it was made, else None (nothing is made)."""
        return cast("T | None", self._entries.get(entry))

    def __contains__(self, entry: Entry[Any]) -> bool:
        return entry in self._entries

    def clear(self) -> None:
        """Forget every entry (they are made again, empty, when next used)."""
        with self._lock:
            self._entries.clear()

    def geometry(self) -> Cache:
        """A new cache sharing this one's geometry entries (the same objects) only."""
        new = Cache()
        with self._lock:
            new._entries = {e: v for e, v in self._entries.items() if e.geometry}
        return new

    def __repr__(self) -> str:
        return f"Cache({', '.join(e.name for e in self._entries)})"


class LRU(Generic[K, V]):
    """A mapping that keeps its ``maxsize`` most recently used items.

    Parameters
    ----------
    maxsize : int
        How many items are kept; adding one more drops the least recently used.
    """

    __slots__ = ("_items", "_lock", "maxsize")

    def __init__(self, maxsize: int) -> None:
        self.maxsize = int(maxsize)
        self._items: OrderedDict[K, V] = OrderedDict()
        self._lock = threading.Lock()

    def get(self, key: K) -> V | None:
        """The item at ``key`` (now the most recently used), or None."""
        with self._lock:
            value = self._items.get(key)
            if value is not None:
                self._items.move_to_end(key)
            return value

    def put(self, key: K, value: V) -> None:
        """Keep ``value`` at ``key``, dropping the least recently used beyond ``maxsize``."""
        with self._lock:
            self._items[key] = value
            self._items.move_to_end(key)
            while len(self._items) > self.maxsize:
                self._items.popitem(last=False)

    def find(self, match: Callable[[K], bool]) -> tuple[K, V] | None:
        """The first item (oldest first) whose key matches (now the most recently used)."""
        with self._lock:
            for key, value in self._items.items():
                if match(key):
                    self._items.move_to_end(key)
                    return key, value
        return None

    def keys(self) -> list[K]:
        """The keys, least recently used first."""
        with self._lock:
            return list(self._items)

    def clear(self) -> None:
        """Forget every item."""
        with self._lock:
            self._items.clear()

    def __contains__(self, key: object) -> bool:
        return key in self._items

    def __len__(self) -> int:
        return len(self._items)

    def __iter__(self) -> Iterator[K]:
        return iter(self.keys())

    def __repr__(self) -> str:
        return f"LRU({len(self._items)}/{self.maxsize})"


class Once(Generic[V]):
    """One value, computed on first use and kept."""

    __slots__ = ("_lock", "_value")

    def __init__(self) -> None:
        self._value: V | None = None
        self._lock = threading.Lock()

    def get(self, make: Callable[[], V]) -> V:
        """The value, made by ``make()`` if it is not yet."""
        value = self._value
        if value is None:
            with self._lock:
                if self._value is None:
                    self._value = make()
                value = self._value
        return value

    def __repr__(self) -> str:
        return f"Once({'set' if self._value is not None else 'empty'})"
