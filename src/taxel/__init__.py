"""taxel: robotic tactile sensing, from contact mechanics to active touch.

The package is layered; each layer is a subpackage and imports only the layers before it
(see docs/architecture.md):

====================== =====================================================================
``taxel.mechanics``    the elastic cover: kernels of the chapter (eqs. 25.1-25.5), Boussinesq
                       and Love, half-space and bonded-layer transfer functions, FFT operators,
                       Hertz, the contact solver, the indenter library
``taxel.transducers``  resistive, capacitive, piezoelectric, optical (reflective, FTIR,
                       microbend) and photoelastic transducers with their inverses; readout
                       non-idealities
``taxel.sensor``       tactile array sensors: geometry, cover, transducer, readout, presets,
                       calibration, Harmon's criteria
``taxel.reconstruction`` the inverse problem: pressure from taxel readings, regularized
``taxel.features``     passive features of one tactile image (Ellis seed, section 2.1)
``taxel.active``       active touch: the probe interface, a simulated finger, procedures
                       (Ellis seed, section 2.2), texture from sliding
``taxel.frames``       poses as 4x4 transforms; the base -> flange -> sensor chain
``taxel.io``           readers of frames and recordings (npy, npz, png, tif, csv, FabricSlide)
``taxel.viz``          figures (matplotlib, imported only when used)
``taxel.report``       the main job: the seeds' experiments as an HTML report
``taxel.cli``          the ``taxel`` command line
====================== =====================================================================

Examples
--------
>>> import taxel
>>> taxel.__version__
'0.1.0'
"""

from importlib.metadata import PackageNotFoundError, version

try:
    __version__ = version("taxel")
except PackageNotFoundError:  # running from a source tree that was not installed
    __version__ = "0.0.0+unknown"

__all__ = ["__version__"]
