"""taxel: robotic tactile sensing, from contact mechanics to active touch.

The package is layered; each layer is a subpackage and imports only the ones before it:

==================  ==========================================================
``taxel.mechanics``  the elastic cover: kernels, Fourier operators, contact solver,
                     indenters (chapter seed, section 25.2)
==================  ==========================================================

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
