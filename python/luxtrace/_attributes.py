"""HDF5 attributes as plain Python, for the classes of result.py and annual.py alike: a
module of its own so that neither of those imports the other for them."""
import numpy as np


def plain(v):
    """An HDF5 attribute as plain Python: str for strings, int/float for scalars, lists
    of str for string arrays, numpy arrays otherwise."""
    if isinstance(v, bytes):
        return v.decode()
    if isinstance(v, np.ndarray):
        if v.dtype.kind in ("O", "S", "U"):
            return [x.decode() if isinstance(x, bytes) else str(x) for x in v.ravel()]
        if v.shape == ():
            return v.item()
        return v
    if isinstance(v, np.generic):
        return v.item()
    return v


def attributes(obj):
    """Every attribute of an HDF5 group or file, by name, as :func:`plain` values."""
    return {k: plain(v) for k, v in obj.attrs.items()}


class AttrAccess:
    """Attributes of the HDF5 group that no property names are readable as Python
    attributes too (``detector.E_min`` for ``detector.attrs["E_min"]``), so attributes a
    newer luxtrace writes need no change here."""

    def __getattr__(self, name):
        attrs = self.__dict__.get("attrs")
        if attrs is not None and name in attrs:
            return attrs[name]
        raise AttributeError(f"{type(self).__name__} has no attribute or HDF5 attribute '{name}'")
