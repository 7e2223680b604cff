"""The elastic cover of a sensor and the depth of its sensing elements."""

from __future__ import annotations

from dataclasses import dataclass

from taxel._validation import check_positive
from taxel.mechanics import ElasticMaterial

__all__ = ["Cover"]


@dataclass(frozen=True)
class Cover:
    """A compliant pad over the sensing elements.

    Parameters
    ----------
    material : ElasticMaterial
        The pad's elastic constants.
    depth : float
        Depth d of the sensing elements below the outer surface [m], > 0.
    thickness : float, optional
        Pad thickness over a rigid backing [m] (>= depth); None models the pad as an elastic
        half-space, as the chapter's analysis does.

    Examples
    --------
    >>> pad = Cover(ElasticMaterial(0.5e6, 0.49), depth=1e-3, thickness=1e-3)
    >>> pad.depth, pad.thickness
    (0.001, 0.001)
    >>> Cover(ElasticMaterial(0.5e6, 0.49), depth=0.0)
    Traceback (most recent call last):
    ...
    ValueError: `depth` must be > 0, got 0
    """

    material: ElasticMaterial
    depth: float
    thickness: float | None = None

    def __post_init__(self) -> None:
        if not isinstance(self.material, ElasticMaterial):
            raise TypeError(f"`material` must be an ElasticMaterial, got {self.material!r}")
        object.__setattr__(self, "depth", check_positive("depth", self.depth))
        if self.thickness is not None:
            thickness = check_positive("thickness", self.thickness)
            if thickness < self.depth:
                raise ValueError(
                    f"`thickness` must be >= `depth` ({self.depth:g} m), got {thickness:g}"
                )
            object.__setattr__(self, "thickness", thickness)
