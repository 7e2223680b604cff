"""Mechanics of the sensor's elastic cover (section 25.2 of the chapter seed).

Materials
    ElasticMaterial, effective_modulus
Plane strain (the chapter's one-dimensional model, eqs. 25.1-25.5)
    line_load_strain, line_load_displacement, strip_load_strain,
    plane_strain_strain_matrix, plane_strain_displacement_matrix
Three dimensions (Boussinesq, Love)
    point_load_displacement, point_load_stress, point_load_strain,
    rectangle_strain, rectangle_stress, rectangle_displacement
Fourier transfer functions (half-space, and a layer bonded to a rigid base)
    halfspace_displacement_transfer, halfspace_strain_transfer, halfspace_stress_transfer,
    layer_displacement_transfer, layer_strain_transfer, layer_stress_transfer
Grid operators (with adjoints; periodic or zero-padded linear convolution)
    ConvolutionOperator, surface_displacement_operator, depth_strain_operator,
    depth_stress_operator
In-plane stress at depth (photoelasticity)
    inplane_stress_difference
Closed-form contacts
    hertz_sphere, hertz_cylinder, flat_punch
Hollow balls (a shell with air inside, flattened by a plate)
    HollowSphere, ATMOSPHERIC_PRESSURE
Contact with unknown contact area
    solve_contact, ContactResult
Indenters
    Indenter, grid_coordinates, Sphere, Cylinder, Cone, FlatPunch, Washer, CanRim, BoxEdge,
    BoxCorner, SlottedPlate, PlateWithHole, HeightMap, StiffFoam, WoodRasp, PerforatedScreen,
    make_indenter, INDENTER_NAMES, describe_indenters
"""

from taxel.mechanics._boussinesq import (
    point_load_displacement,
    point_load_strain,
    point_load_stress,
    rectangle_displacement,
    rectangle_strain,
    rectangle_stress,
)
from taxel.mechanics._contact import ContactResult, solve_contact
from taxel.mechanics._hertz import (
    CylinderContact,
    PunchContact,
    SphereContact,
    flat_punch,
    hertz_cylinder,
    hertz_sphere,
)
from taxel.mechanics._indenter_base import Indenter, grid_coordinates
from taxel.mechanics._indenters import (
    BoxEdge,
    CanRim,
    Cone,
    Cylinder,
    FlatPunch,
    Sphere,
    Washer,
)
from taxel.mechanics._indenters_plates import BoxCorner, HeightMap, PlateWithHole, SlottedPlate
from taxel.mechanics._inplane import inplane_stress_difference
from taxel.mechanics._library import INDENTER_NAMES, describe_indenters, make_indenter
from taxel.mechanics._materials import ElasticMaterial, effective_modulus
from taxel.mechanics._operators import (
    ConvolutionOperator,
    depth_strain_operator,
    depth_stress_operator,
    surface_displacement_operator,
)
from taxel.mechanics._plane_strain import (
    line_load_displacement,
    line_load_strain,
    plane_strain_displacement_matrix,
    plane_strain_strain_matrix,
    strip_load_strain,
)
from taxel.mechanics._shell import ATMOSPHERIC_PRESSURE, HollowSphere
from taxel.mechanics._textures import PerforatedScreen, StiffFoam, WoodRasp
from taxel.mechanics._transfer import (
    halfspace_displacement_transfer,
    halfspace_strain_transfer,
    halfspace_stress_transfer,
    layer_displacement_transfer,
    layer_strain_transfer,
    layer_stress_transfer,
)

__all__ = [
    "ATMOSPHERIC_PRESSURE",
    "INDENTER_NAMES",
    "BoxCorner",
    "BoxEdge",
    "CanRim",
    "Cone",
    "ContactResult",
    "ConvolutionOperator",
    "Cylinder",
    "CylinderContact",
    "ElasticMaterial",
    "FlatPunch",
    "HeightMap",
    "HollowSphere",
    "Indenter",
    "PerforatedScreen",
    "PlateWithHole",
    "PunchContact",
    "SlottedPlate",
    "Sphere",
    "SphereContact",
    "StiffFoam",
    "Washer",
    "WoodRasp",
    "depth_strain_operator",
    "depth_stress_operator",
    "describe_indenters",
    "effective_modulus",
    "flat_punch",
    "grid_coordinates",
    "halfspace_displacement_transfer",
    "halfspace_strain_transfer",
    "halfspace_stress_transfer",
    "hertz_cylinder",
    "hertz_sphere",
    "inplane_stress_difference",
    "layer_displacement_transfer",
    "layer_strain_transfer",
    "layer_stress_transfer",
    "line_load_displacement",
    "line_load_strain",
    "make_indenter",
    "plane_strain_displacement_matrix",
    "plane_strain_strain_matrix",
    "point_load_displacement",
    "point_load_strain",
    "point_load_stress",
    "rectangle_displacement",
    "rectangle_strain",
    "rectangle_stress",
    "solve_contact",
    "strip_load_strain",
    "surface_displacement_operator",
]
