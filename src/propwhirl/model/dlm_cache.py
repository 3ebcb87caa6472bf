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
computed anew and rewritten; files are written to a temporary name and renamed, so a reader
never sees half a file.  A directory that cannot be created or written is an InputError
before any matrix is computed.
"""
from __future__ import annotations

import hashlib
import os
import tempfile
from importlib import metadata
from pathlib import Path

import numpy as np

from propwhirl import validate as v

#: the environment variable naming the cache directory
CACHE_ENV = "PROPWHIRL_DLM_CACHE"
#: version of the cache's key and file layout
FORMAT = 1


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
    matrix."""
    path = _path(directory, geometry, mach, kbar)
    try:
        Q = np.load(path, allow_pickle=False)
    except (OSError, ValueError):
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
