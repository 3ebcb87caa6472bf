"""A disk cache of the doublet-lattice AIC matrices (issue 23, item 6; its integrity: issue 33,
item 4).

With the environment variable ``PROPWHIRL_DLM_CACHE`` set to a directory, every symmetric AIC
Q_jj (n × n complex, :meth:`propwhirl.model.aerodynamics.dlm.DlmAerodynamics.aic`) computed at a Mach number
and reduced frequency is written there and read back by any later analysis of the same panels,
instead of being computed again.  Unset or empty (the default): no disk cache (the tables are
still kept in memory by the analysis that owns them,
:class:`propwhirl.model.aerodynamics.dlm.DlmTables`).

A file holds one matrix in NumPy's ``.npy`` format, written and read with
``allow_pickle=False`` (no code-carrying format).  Its name is the SHA-256 of what decides the
matrix: this cache's :data:`FORMAT`, PanelAero's version, the panels' corner coordinates
(both half-wings, [m], exactly as float64) and the exact Mach number and PanelAero's reduced
frequency k̄ = ω/U [1/m] (their hexadecimal float forms).  Files are written to a temporary
name and renamed, so a reader never sees half a file.  A directory that cannot be created or
written is an InputError before any matrix is computed.  An entry is read with bounds: its
``.npy`` header first (nothing is allocated on the file's word); an entry that is not a regular
file (a FIFO, a device: never written by the cache) or is larger than its matrix is an
InputError naming it, refused before it is opened.

**Integrity (a cache never changes an answer).**  Beside each ``aic-<key>.npy`` its checksum,
``aic-<key>.sha256``: the SHA-256 (:func:`checksum`) of the matrix's content (little-endian
complex128, C order) together with its shape and its file name, so that it binds the content
to its key.  An entry is used only when its checksum matches; otherwise:

* a file that cannot be read, is not an (n, n) finite complex matrix, or does not match its
  checksum (a bit flip, a truncated or zeroed file, a file copied under another key): a
  one-line :class:`UserWarning` naming the file, the matrix computed again and both files
  rewritten (:func:`load`);
* an entry without a checksum (written by a propwhirl before issue 33, or whose checksum was
  lost): computed again, silently, and rewritten with one — its content cannot be trusted, and
  verifying it would cost the same computation as replacing it;
* the **spot check**: the first entry read for each panel geometry (each
  :class:`~propwhirl.model.aerodynamics.dlm.DlmAerodynamics`) is computed again all the same and compared
  (:func:`spot_check`): a difference beyond :data:`SPOT_CHECK_RTOL` with a valid checksum
  means the directory holds matrices this propwhirl did not compute (altered or forged, and
  their checksums rewritten; or computed by another build) — an InputError naming the
  directory and the file, nothing rewritten: the other entries cannot be trusted either.

Trust model: the checksum detects accidental damage, not a deliberate change — whoever can
write the directory can write the checksums too.  The spot check catches a directory whose
entries are wrong throughout (e.g. every matrix scaled), at the cost of one AIC per geometry
and analysis session (docs/performance.md); an entry altered *with* its checksum but not the
first one read is not detected.  A cache directory is therefore trusted as the installed code
is: let only those who may change your results write to it.
"""
from __future__ import annotations

import hashlib
import os
import re
import stat
import tempfile
import warnings
from importlib import metadata
from pathlib import Path

import numpy as np
from numpy.lib import format as npf

from propwhirl import fileio
from propwhirl import validate as v
from propwhirl.limits import printable

#: the environment variable naming the cache directory
CACHE_ENV = "PROPWHIRL_DLM_CACHE"
#: version of the cache's key and file layout (the checksum beside each file, added in issue
#: 33, left the key and the ``.npy`` files as they were: older entries are still found)
FORMAT = 1
#: what the checksum of an entry hashes first (its own version)
CHECKSUM_TAG = b"propwhirl-dlm-aic-checksum/1\0"
#: largest relative difference (max |ΔQ| / max |Q|) between a cached AIC and the one computed
#: again by the spot check: PanelAero's own round-off is ~1e-15; another BLAS may differ by
#: ~1e-13 (a cache shared between machines); anything altered by a forger or a bug is larger
SPOT_CHECK_RTOL = 1e-9
#: largest checksum file read [bytes] (64 hexadecimal digits and a newline)
_SUM_BYTES = 128
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


def _sum_path(path: Path) -> Path:
    return path.with_suffix(".sha256")


def checksum(path: Path, Q: np.ndarray) -> str:
    """The SHA-256 (hexadecimal) of the AIC ``Q`` stored as ``path``: :data:`CHECKSUM_TAG`, the
    file's name (the key: an entry copied under another key does not match), the shape and
    the content (little-endian complex128, C order)."""
    h = hashlib.sha256(CHECKSUM_TAG)
    h.update(f"{Path(path).name}/{tuple(np.shape(Q))}/".encode())
    h.update(np.ascontiguousarray(Q, dtype="<c16").tobytes())
    return h.hexdigest()


def _read_sum(path: Path) -> str | None:
    """The checksum file of entry ``path``: its text (stripped; at most :data:`_SUM_BYTES`
    read, a regular file only, never blocking), None when there is none."""
    try:
        fd = os.open(_sum_path(path), os.O_RDONLY | getattr(os, "O_NONBLOCK", 0))
    except FileNotFoundError:
        return None
    except OSError:
        return ""
    try:
        if not stat.S_ISREG(os.fstat(fd).st_mode):
            return ""
        data = os.read(fd, _SUM_BYTES + 1)
    except OSError:
        return ""
    finally:
        os.close(fd)
    return data.decode("ascii", "replace").strip() if len(data) <= _SUM_BYTES else ""


def _damaged(path: Path, why: str) -> None:
    """Say that entry ``path`` is damaged and will be computed again (a one-line warning)."""
    warnings.warn(f"{CACHE_ENV}: {printable(path)} is damaged ({why}): its AIC is computed "
                  "again and the entry rewritten", UserWarning, stacklevel=3)
    return None


def load(directory: Path, geometry: str, mach: float, kbar: float, n: int) -> np.ndarray | None:
    """The cached (n, n) complex AIC at Mach and k̄ [1/m], or None when there is no entry, no
    checksum beside it (an older propwhirl's entry) or a damaged one (a one-line warning:
    unreadable, not such a matrix, or not matching its checksum; module docstring).  Its
    ``.npy`` header is checked before any data is allocated; an entry that is not a regular
    file (a FIFO, a device: never written by the cache) or larger than such a matrix
    (n² · 16 bytes + :data:`NPY_HEADER_MAX`) is an InputError naming it
    (:func:`propwhirl.fileio.open_input`, checked before it is opened)."""
    path = _path(directory, geometry, mach, kbar)
    what = f"{CACHE_ENV} entry"
    if not fileio.exists(path, what):
        return None
    digest = _read_sum(path)
    want = np.dtype(np.complex128)
    limit = n * n * want.itemsize + NPY_HEADER_MAX
    try:
        with fileio.open_input(path, what, limit, bound=f"a {n} x {n} complex AIC and its "
                               ".npy header; remove the entry") as fh:
            if digest is None:               # an entry without checksum: computed again
                return None
            version = npf.read_magic(fh)
            read_header = (npf.read_array_header_1_0 if version == (1, 0)
                           else npf.read_array_header_2_0)
            shape, _, dtype = read_header(fh)
            if tuple(shape) != (n, n) or dtype != want:
                return _damaged(path, f"not a finite {n} x {n} complex matrix")
            fh.seek(0)
            Q = npf.read_array(fh, allow_pickle=False)
    except v.InputError:                    # not a regular file, or too large: named
        raise
    except (OSError, ValueError, EOFError) as exc:          # EOFError: an empty file
        return _damaged(path, f"unreadable: {type(exc).__name__}")
    if Q.shape != (n, n) or Q.dtype != np.complex128 or not np.all(np.isfinite(Q)):
        return _damaged(path, f"not a finite {n} x {n} complex matrix")
    if not re.fullmatch(r"[0-9a-f]{64}", digest) or digest != checksum(path, Q):
        return _damaged(path, "its content does not match its checksum "
                        f"{_sum_path(path).name}")
    return Q


def spot_check(directory: Path, geometry: str, mach: float, kbar: float, cached: np.ndarray,
               computed: np.ndarray) -> None:
    """InputError unless the AIC ``cached`` read at Mach and k̄ [1/m] (with a valid checksum)
    equals the one ``computed`` again within :data:`SPOT_CHECK_RTOL` (module docstring)."""
    scale = float(np.max(np.abs(computed), initial=0.0))
    diff = float(np.max(np.abs(np.asarray(cached) - computed), initial=0.0))
    if not diff <= SPOT_CHECK_RTOL * scale:
        path = _path(directory, geometry, mach, kbar)
        rel = diff / scale if scale > 0 else float("inf")
        raise v.InputError(
            f"{CACHE_ENV} = {str(directory)!r} is invalid: {path.name} differs from the "
            f"AIC computed again (relative difference {rel:.3g}, at most {SPOT_CHECK_RTOL:g} "
            "allowed): the directory holds matrices this propwhirl did not compute (altered "
            f"or forged); empty it or unset {CACHE_ENV}")


def _write(directory: Path, path: Path, write) -> None:
    """``write(f)`` to a temporary file of ``directory``, then renamed to ``path``."""
    fd, tmp = tempfile.mkstemp(dir=directory, prefix=".aic-", suffix=path.suffix)
    try:
        with os.fdopen(fd, "wb") as f:
            write(f)
        os.replace(tmp, path)
    except OSError:
        Path(tmp).unlink(missing_ok=True)
        raise


def store(directory: Path, geometry: str, mach: float, kbar: float, Q: np.ndarray) -> None:
    """Write the AIC at Mach and k̄ [1/m] and its checksum beside it (each to a temporary
    file, then renamed into place: the matrix first, so that a reader sees either no checksum,
    the old one — the same content — or the new one); a one-line warning when either cannot
    be written (e.g. a directory in its place, a full disk): the analysis goes on without it."""
    path = _path(directory, geometry, mach, kbar)
    Q = np.asarray(Q, dtype=np.complex128)
    for target, write in ((path, lambda f: np.save(f, Q, allow_pickle=False)),
                          (_sum_path(path), lambda f: f.write(f"{checksum(path, Q)}\n".encode()))):
        try:
            _write(directory, target, write)
        except OSError as exc:               # the AIC is computed: the analysis goes on
            warnings.warn(f"{CACHE_ENV}: cannot write {printable(target)} "
                          f"({exc.strerror or type(exc).__name__}): the entry is not cached",
                          UserWarning, stacklevel=2)
            return
