"""Whether a contact is a texture, and its gaps told so (internal).

A texture's basins are holes only when they make a perforated sheet, and never slots
(`taxel.features._gaps`); `extract` and the one-feature functions judge it alike.
"""

from __future__ import annotations

from taxel.features._contact import Contact
from taxel.features._gaps import GapsFound, gaps_core
from taxel.features._image import Prepared
from taxel.features._texture import high_points

__all__ = ["MANY_HIGH_POINTS", "is_textured", "textured_gaps"]

# Several contacts: a region counts when it holds >= 5 % of the contact area; three such
# regions is a texture or a multi-point grip, not one shape.
_MINOR_REGION = 0.05
_MANY_REGIONS = 3
# A single smooth body presses the cover with at most one peak (sphere, tip) or with a ridge
# or a plateau, which have none (edge, rim, plate); three separate high points need three
# touching asperities: a texture.
MANY_HIGH_POINTS = 3


def is_textured(contact: Contact, high_point_count: int) -> bool:
    """Whether a contact is a texture: 3 or more sizeable regions, or 3 or more high points."""
    total = sum(r.area_taxels for r in contact.regions)
    major_regions = sum(r.area_taxels >= _MINOR_REGION * total for r in contact.regions)
    return major_regions >= _MANY_REGIONS or high_point_count >= MANY_HIGH_POINTS


def textured_gaps(prepared: Prepared, contact: Contact) -> tuple[int, bool, GapsFound]:
    """High points, whether a texture, and the gaps `gaps_core` finds so told.

    As `extract` finds them (with the default texture sigma), for the one-feature
    functions; `contact`'s regions' areas are all the texture test reads.
    """
    count = high_points(prepared)[0]
    textured = is_textured(contact, count)
    return count, textured, gaps_core(prepared, textured=textured)
