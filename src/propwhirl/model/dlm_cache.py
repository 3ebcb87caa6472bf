"""A disk cache of the doublet-lattice AIC matrices (issue 23, item 6).

With the environment variable ``PROPWHIRL_DLM_CACHE`` set to a directory, every symmetric AIC
Q_jj (n × n complex, :meth:`propwhirl.model.dlm.DlmAerodynamics.aic`) computed at a Mach number
and reduced frequency is written there and read back by any later analysis of the same panels,
instead of being computed again.  Unset or empty (the default): no disk cache (the tables are
still kept in memory for the session, :func:`propwhirl.model.dlm.dlm_aerodynamics`).

A file holds one matrix in NumPy's ``.npy`` format, written and read with
``allow_pickle=False`` (no code-carrying format).  Its name is the SHA-256 of what decides the
matrix: this cache's :data:`FORMAT`, PanelAero's version, the panels' corner coordinates
(both half-wings, [m], exactly as float64) and the exact Mach number and PanelAero's reduced
frequency k̄ = ω/U [1/m] (their hexadecimal float forms).  A file whose shape or type is not the expected one, or that cannot be read, is
computed anew and rewritten (its ``.npy`` header is read first: nothing is allocated on the
file's word); an entry that is not a regular file (a FIFO, a device) or is larger than its
matrix is an InputError naming it, refused before it is opened; files are written to a
temporary name and renamed, so a reader never sees half a file.  A directory that cannot be created or written is an InputError
before any matrix is computed.
"""
from __future__ import annotations

import hashlib
import os
import tempfile
from importlib import metadata
from pathlib import Path

import numpy as np

from propwhirl import fileio
from propwhirl import validate as v

#: the environment variable naming the cache directory
CACHE_ENV = "PROPWHIRL_DLM_CACHE"
#: version of the cache's key and file layout
FORMAT = 1
#: bytes of a cache file beyond its matrix's: the ``.npy`` magic and header (numpy pads the
#: header to 64 or 4096 bytes)
NPY_HEADER_MAX = 4096


def cache_dir() -> Path | None:
    """The cache directory of ``PROPWHIRL_DLM_CACHE`` (created if missing), or None when the
    variable is unset or empty; InputError when it cannot be created or written."""
    text = os.environ.get(CACHE_ENV, "").strip()
    if not text:
        return None
    path = Path(text).expanduser()
    try:
        path.mkdir(parents=True, exist_ok=True)
        probe = tempfile.NamedTemporaryFile(dir=path, prefix=".probe-", delete=True)
        probe.close()
    except OSError as exc:
        raise v.InputError(f"{CACHE_ENV} = {text!r} is invalid: cannot create or write the "
                           f"directory ({exc.strerror or exc})") from exc
    return path


def _panelaero_version() -> str:
    try:
        return metadata.version("panelaero")
    except metadata.PackageNotFoundError:                      # pragma: no cover
        return "unknown"


def geometry_key(corners: np.ndarray) -> str:
    """The part of every key that the panels decide: SHA-256 of the format, PanelAero's
    version and the corner coordinates (float64, C order)."""
    h = hashlib.sha256()
    h.update(f"propwhirl-dlm-aic/{FORMAT}/panelaero-{_panelaero_version()}/".encode())
    h.update(np.ascontiguousarray(corners, dtype=np.float64).tobytes())
    return h.hexdigest()


def _path(directory: Path, geometry: str, mach: float, kbar: float) -> Path:
    name = hashlib.sha256(f"{geometry}/{float(mach).hex()}/{float(kbar).hex()}".encode())
    return directory / f"aic-{name.hexdigest()}.npy"


def load(directory: Path, geometry: str, mach: float, kbar: float, n: int) -> np.ndarray | None:
    """The cached (n, n) complex AIC at Mach and k̄ [1/m], or None when absent or not such a
    matrix (its ``.npy`` header is checked before any data is allocated).  An entry that is
    not a regular file (a FIFO, a device: never written by the cache) or larger than such a
    matrix (n² · 16 bytes + :data:`NPY_HEADER_MAX`) is an InputError naming it
    (:func:`propwhirl.fileio.open_input`, checked before it is opened)."""
    from numpy.lib import format as npf

    path = _path(directory, geometry, mach, kbar)
    what = f"{CACHE_ENV} entry"
    if not fileio.exists(path, what):
        return None
    want = np.dtype(np.complex128)
    limit = n * n * want.itemsize + NPY_HEADER_MAX
    try:
        with fileio.open_input(path, what, limit, bound=f"a {n} x {n} complex AIC and its "
                               ".npy header; remove the entry") as fh:
            version = npf.read_magic(fh)
            read_header = (npf.read_array_header_1_0 if version == (1, 0)
                           else npf.read_array_header_2_0)
            shape, _, dtype = read_header(fh)
            if tuple(shape) != (n, n) or dtype != want:
                return None
            fh.seek(0)
            Q = npf.read_array(fh, allow_pickle=False)
    except v.InputError:                    # not a regular file, or too large: named
        raise
    except (OSError, ValueError, EOFError):
        return None
    if Q.shape != (n, n) or Q.dtype != np.complex128 or not np.all(np.isfinite(Q)):
        return None
    return Q


def store(directory: Path, geometry: str, mach: float, kbar: float, Q: np.ndarray) -> None:
    """Write the AIC at Mach and k̄ [1/m] (to a temporary file, then renamed into place)."""
    path = _path(directory, geometry, mach, kbar)
    fd, tmp = tempfile.mkstemp(dir=directory, prefix=".aic-", suffix=".npy")
    try:
        with os.fdopen(fd, "wb") as f:
            np.save(f, np.asarray(Q, dtype=np.complex128), allow_pickle=False)
        os.replace(tmp, path)
    except OSError:
        Path(tmp).unlink(missing_ok=True)
        raise
