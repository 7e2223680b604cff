"""Whether a contact is a texture, and its gaps told so (internal).

A texture's basins are holes only when they make a perforated sheet, and never slots
(`taxel.features._gaps`); `extract` and the one-feature functions judge it alike.

A plate's slot can stand out as high points too: on a thin or no cover the pressure peaks
at its sharp corners, and a synthetic plate's slot read as a texture of 3-4 high points,
whose basins are no slots. High points on the rim of the one slot a plate shows (within a
taxel or two of where it lies, see `_at_rim`), up to 4 of them, are its corners, not
asperities: the contact is then a texture only if 3 high points are not. Not so for a
hole: on the features benchmark's second draw, foam pressed at 186 N left one basin
between its 3 high points, which then read as a false hole.
"""

from __future__ import annotations

import math

import cv2
import numpy as np

from taxel.features._contact import Contact
from taxel.features._gaps import GapsFound, gaps_core
from taxel.features._image import Prepared
from taxel.features._texture import TEXTURE_SIGMA, high_points

__all__ = ["MANY_HIGH_POINTS", "is_textured", "judged_gaps", "textured_gaps"]

# Several contacts: a region counts when it holds >= 5 % of the contact area; three such
# regions is a texture or a multi-point grip, not one shape.
_MINOR_REGION = 0.05
_MANY_REGIONS = 3
# A single smooth body presses the cover with at most one peak (sphere, tip) or with a ridge
# or a plateau, which have none (edge, rim, plate); three separate high points need three
# touching asperities: a texture.
MANY_HIGH_POINTS = 3
# A slot has 4 corners: more high points on its rim are a texture's (teeth along a slot)
_CORNERS = 4


def _many_regions(contact: Contact) -> bool:
    """Whether 3 or more of the contact's regions are sizeable."""
    total = sum(r.area_taxels for r in contact.regions)
    major_regions = sum(r.area_taxels >= _MINOR_REGION * total for r in contact.regions)
    return major_regions >= _MANY_REGIONS


def is_textured(contact: Contact, high_point_count: int) -> bool:
    """Whether a contact is a texture: 3 or more sizeable regions, or 3 or more high points.

    (Before any high point is told a gap's corner: see `judged_gaps`.)
    """
    return _many_regions(contact) or high_point_count >= MANY_HIGH_POINTS


def _at_rim(prepared: Prepared, explained: np.ndarray | None, sigma: float) -> int:
    """How many high points lie on the gaps' rims: `explained` grown by sigma / 2 taxels.

    (The smoothing of `sigma` moves a corner's peak outwards: a synthetic slot's lay 0-1
    taxel beyond `explained` at sigma 2, 2 at sigma 5.)
    """
    if explained is None:
        return 0
    places = prepared.memo[("high points", sigma)]  # (x, y), kept from 3 high points on
    reach = math.ceil(sigma / 2)
    rims = cv2.dilate(explained, np.ones((2 * reach + 1, 2 * reach + 1), np.uint8))
    return int(np.count_nonzero(rims[places[:, 1], places[:, 0]]))


def judged_gaps(
    prepared: Prepared, contact: Contact, high_point_count: int, sigma: float = TEXTURE_SIGMA
) -> tuple[bool, GapsFound]:
    """Whether the contact is a texture, and the gaps `gaps_core` finds so told.

    `high_point_count`: `high_points` of `prepared` with this `sigma`. A contact textured
    by its high points alone (3 or more, in under 3 sizeable regions) whose gaps, looked
    for as a plain contact's, are one slot is not a texture when, but for up to 4 high
    points on that slot's rim (its corners), fewer than 3 remain (see the module notes).
    Such a contact's gaps are looked for twice, plainly and as a texture's.
    """
    textured = is_textured(contact, high_point_count)
    if textured and not _many_regions(contact):
        plain = gaps_core(prepared, textured=False)
        holes, slots, explained = plain
        if len(slots) == 1 and not holes:
            corners = min(_at_rim(prepared, explained, sigma), _CORNERS)
            away = high_point_count - corners
            if away < MANY_HIGH_POINTS:
                return False, plain
    return textured, gaps_core(prepared, textured=textured)


def textured_gaps(prepared: Prepared, contact: Contact) -> tuple[int, bool, GapsFound]:
    """High points, whether a texture, and the gaps `gaps_core` finds so told.

    As `extract` finds them (with the default texture sigma, `judged_gaps`), for the
    one-feature functions; `contact`'s regions' areas are all the texture test reads.
    """
    count = high_points(prepared)[0]
    textured, gaps = judged_gaps(prepared, contact, count)
    return count, textured, gaps
