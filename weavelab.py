"""Lets `import weavelab` work from the repository root (README, "Scripting
from Python"): hands over to the package on the path (PYTHONPATH), else to the
one the build puts into build/python/. Elsewhere set PYTHONPATH=REPO/build/python."""
import os
import sys

_root = os.path.dirname(os.path.abspath(__file__))
_saved_path = sys.path[:]
sys.path[:] = [p for p in sys.path if os.path.abspath(p or os.curdir) != _root]
if not any(os.path.isfile(os.path.join(p or os.curdir, "weavelab", "__init__.py")) for p in sys.path):
    _built = os.path.join(_root, "build", "python")
    if not os.path.isfile(os.path.join(_built, "weavelab", "__init__.py")):
        sys.path[:] = _saved_path
        raise ImportError("weavelab: the Python module is not built; run tools/setup.sh (README, Quick start)")
    sys.path.insert(0, _built)
del sys.modules[__name__]
try:
    import weavelab  # noqa: F401  (the package, which replaces this file's module)
finally:
    sys.path[:] = _saved_path
