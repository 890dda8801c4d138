"""The caches kept on a hull and on a pitch's frame: typed entries, bounded, shared by a
hull of the same geometry, left out of a pickle, safe under threads."""

from __future__ import annotations

import pickle
import threading

import numpy as np

from hullslice.caching import LRU, Cache, Entry, Once
from hullslice.geometry import FRAME_CACHE, FRAMES, SILHOUETTE, frame, silhouette_edges


def test_lru_keeps_the_most_recently_used():
    lru: LRU[int, str] = LRU(2)
    lru.put(1, "a")
    lru.put(2, "b")
    assert lru.get(1) == "a"  # 1 is now the most recent
    lru.put(3, "c")
    assert lru.keys() == [1, 3] and lru.get(2) is None
    assert lru.find(lambda k: k > 2) == (3, "c")
    lru.clear()
    assert len(lru) == 0


def test_an_entry_is_made_once_and_cleared():
    made = []
    entry: Entry[list[int]] = Entry("numbers", lambda: made.append(1) or [])
    cache = Cache()
    assert cache.get(entry) is None and entry not in cache
    assert cache[entry] is cache[entry] and len(made) == 1
    cache.clear()
    assert entry not in cache


def test_once_is_made_once_under_threads():
    once: Once[int] = Once()
    calls = []

    def make() -> int:
        calls.append(1)
        return 7

    threads = [threading.Thread(target=lambda: once.get(make)) for _ in range(8)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert once.get(make) == 7 and len(calls) == 1


def test_a_hull_keeps_few_frames(paper_hull):
    hull = paper_hull.with_mass(2.0)
    for pitch in np.radians(np.arange(FRAME_CACHE + 2)):
        frame(hull, pitch)
    assert len(hull.cache[FRAMES]) == FRAME_CACHE


def test_with_mass_shares_the_geometry_only(paper_hull):
    hull = paper_hull.with_mass(3.0)
    edges = silhouette_edges(hull)
    frame(hull, 0.0)
    other = hull.with_mass(4.0)
    assert silhouette_edges(other) is edges  # the same geometry
    assert not other.cache[FRAMES]  # frames turn about the centre of gravity: its own


def test_a_pickled_hull_leaves_its_caches(paper_hull):
    hull = paper_hull.with_mass(5.0)
    silhouette_edges(hull)
    frame(hull, 0.0)
    copy = pickle.loads(pickle.dumps(hull))
    assert SILHOUETTE not in copy.cache and FRAMES not in copy.cache
    np.testing.assert_array_equal(silhouette_edges(copy)[0], silhouette_edges(hull)[0])
