"""The package polarview shipped inside the add-on (polarview_blender/polarview: __init__.py and the
extension _core), loaded once. When it cannot load (an extension built for another Python, a
missing file), ``pv`` is None and ``LOAD_ERROR`` says why: the panel shows it and every operator
reports it instead of failing."""
import glob
import os
import sys

pv = None
LOAD_ERROR = ""

try:
    from . import polarview as pv  # noqa: F811
except Exception as error:  # ImportError, or whatever the extension raises while it initialises
    _here = os.path.join(os.path.dirname(__file__), "polarview")
    _built = [os.path.basename(p) for p in glob.glob(os.path.join(_here, "_core*"))]
    LOAD_ERROR = (f"the polarview module could not be loaded ({type(error).__name__}: {error}). "
                  f"Blender runs Python {sys.version_info.major}.{sys.version_info.minor}; the add-on holds "
                  f"{', '.join(_built) if _built else 'no extension _core'}: it must be built for this Python "
                  f"(docs/blender.md)")
    pv = None


def require():
    """The package, or RuntimeError with LOAD_ERROR."""
    if pv is None:
        raise RuntimeError(LOAD_ERROR)
    return pv
