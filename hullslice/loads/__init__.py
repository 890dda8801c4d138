"""Loads for the structure: the sections' pressures on the mesh's faces, and frame loads.

* :class:`SectionRecord`: what one instant of a run keeps for the loads (kept by
  ``simulate(..., sections_every=N)`` in :attr:`History.sections <hullslice.History>`).
* :func:`face_pressures`: the pressure on every face of the mesh at an instant
  (:mod:`hullslice.loads.faces` says how it is mapped and what it leaves out).
* :func:`frame_loads`: the load each frame bay carries over time
  (:mod:`hullslice.loads.frames`).
"""

from .faces import FaceGeometry, FacePeak, FacePressures, face_geometry, face_pressures
from .frames import FrameLoads, frame_loads, frame_stations
from .record import SectionRecord

__all__ = [
    "FaceGeometry",
    "FacePeak",
    "FacePressures",
    "FrameLoads",
    "SectionRecord",
    "face_geometry",
    "face_pressures",
    "frame_loads",
    "frame_stations",
]
