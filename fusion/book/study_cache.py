"""A per-run cache of the book's deterministic studies, shared by the processes of one ``make book`` or ``make test``.

The chapters' studies are pure functions of hashable arguments (seed, runs, a reading's key, a scenario), and
several processes of one build compute the same ones: chapter 06's networks in both of its notebooks, chapter 05's
ledger studies in the notebook and in its unit tests, and so on. :func:`study_cache` caches such a function in
the process (least recently used dropped first, keyed as on disk but with every class by identity) and, when the
environment variable :data:`ENV` names a directory, also on disk there: the first process to need a result
computes it under a file lock and stores it (pickle, written atomically); a process that asks meanwhile waits for
it instead of computing it a second time, and later ones load it. A stored file that cannot be read back (empty,
truncated, corrupt, a damaged length field included, a directory, a FIFO, a socket or a device in its place), whose
bytes do not match the digest stored with them (a BLAKE2b of the pickled result) or that does not hold its own key's
result is a miss: the result is computed again and the file rewritten. An entry that cannot be written (its lock or
its file blocked by a directory, a FIFO or a device, a full disk) is not an error either: the computed result is
returned unstored, as without :data:`ENV` (fuzz 37b C1, D1; fuzz 40b C2, C3).

The key of a result is the SHA-256 of the package's sources (every ``fusion/**/*.py``), numpy's version, the
function's qualified name and its arguments bound to its parameters (defaults applied): any edit of the package
gives new keys. ``make book`` (``tools/execute_notebooks.py``) and ``make test`` (``tests/conftest.py``) point
:data:`ENV` at a fresh temporary directory per invocation and delete it afterwards; it is never shared across
invocations and never committed, so a fresh clone computes every study once. Without :data:`ENV` nothing is
written and only the in-process cache serves.

Arguments the key cannot encode faithfully (an object that is not a number, string, bytes, ``None``, enum, tuple,
list, dict, frozenset, ndarray or dataclass of those) bypass the disk: the result is computed in the process, as
without :data:`ENV`, and cached there by equality and type (``functools.lru_cache(typed=True)``). A loaded result has the computed one's values bit for bit; read-only arrays
(``fusion._frozen.freeze_arrays``) are loaded read-only, and an array that was a strided view of another comes
back as a contiguous copy.

A cached result is shared by its callers only if nothing in it can be changed (fuzz 17, class A: one caller's
in-place edit reached every later call). When it is computed or loaded, the cache keeps a copy in which every plain
array of numbers is a sealed read-only copy, its memory an immutable ``bytes`` object that no array owns (values and
container types unchanged; nothing of the caller's is changed in place or shared, a view of an argument included,
fuzz 35a C1). A result that holds nothing mutable and no array (atoms, tuples, frozensets, read-only mappings and
frozen dataclasses of those) is the object itself at every call; any other (an array in it, or a list, dict, set,
DataFrame, non-frozen dataclass) is a deep copy per call that shares the result's immutable parts without arrays and
gives each caller its own read-only array objects over the kept memory (about 0.5 us an array, no data copied; fuzz
37a C1: a caller's ``r.shape = (n, 1)``, ``r.dtype = ...``, ``r.resize(...)`` or ``r.setflags(write=True)`` on a
shared array object reached every later caller; now they change the caller's array object only, or are refused). An
array subclass (masked, matrix) or an object array is deep-copied per caller. A result that holds something mutable
and cannot be deep-copied (a memoryview, a generator, a lock in a dict) is not cached: it is returned to its caller,
and each call computes it again, as without the cache (fuzz 34a D1). :func:`process_cache` applies the same rule to an
in-process cache without the disk.

Only a function that its module holds under its qualified name (a module-level ``def``, or a wrapper of one) is
cached on disk: a function made in another function (closures of one factory share a name), a lambda, or a
function of a script (``__main__``) cannot be told apart from another of its name by the key, and is cached in the
process only (fuzz 34a D2).

With ``FUSION_STUDY_CACHE_LOG`` naming a file, every call that reaches the disk layer appends one JSON line
(qualified name, arguments, process id, CPU-seconds, ``"computed"`` or ``"loaded"``): which studies a run computes
more than once without the cache, and what they cost.
"""

from __future__ import annotations

import collections
import contextlib
import copy
import dataclasses
import enum
import fcntl
import functools
import hashlib
import inspect
import io
import json
import os
import pickle
import stat
import sys
import tempfile
import threading
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np

from fusion._counts import MAX_ELEMENTS, count
from fusion._frozen import ReadOnlyMapping
from fusion._validation import text
from fusion._paths import file_bytes, folder
from fusion._shown import shown

__all__ = ["ENV", "LOG_ENV", "process_cache", "study_cache", "study_key", "source_digest"]

#: Environment variable naming the directory of the shared cache (unset: in-process caching only).
ENV = "FUSION_STUDY_CACHE"
#: Environment variable naming a file to which each disk-layer call appends a JSON line (instrumentation).
LOG_ENV = "FUSION_STUDY_CACHE_LOG"

_PACKAGE = Path(__file__).resolve().parents[1]


def source_digest(package: Path | str = _PACKAGE) -> str:
    """SHA-256 of the package's Python sources: every ``**/*.py`` under ``package``, by relative path and bytes.

    Parameters
    ----------
    package : Path or str
        The package's folder (default: ``fusion``).

    Returns
    -------
    str
        Hex digest; it changes with any edit, addition, removal or renaming of a source file.

    Raises
    ------
    TypeError
        If ``package`` is not a path (a ``str`` or an ``os.PathLike``).
    ValueError
        If ``package`` is not an existing folder (or the system cannot read it as a path: too long, a NUL byte), or
        not a Python package (no ``__init__.py``): a folder such as ``/`` or ``''`` (the working directory) would
        be walked file by file, the whole file system in the worst case; or if a source under it is not a regular
        file (a FIFO, a device) or is larger than 16 MB (read whole, they would hang or exhaust memory).
    """
    path = folder(text(package, "package") if isinstance(package, str) else package, "package")  # rule 19
    if not (path / "__init__.py").is_file():
        raise ValueError(f"package must be a Python package's folder (with an __init__.py), got {shown(package, 60)}")
    # resolved before the cache: a relative name read from another working directory is another folder
    return _source_digest(path.resolve())


@functools.lru_cache(maxsize=1)
def _source_digest(package: Path) -> str:
    h = hashlib.sha256()
    for path in sorted(package.rglob("*.py")):
        rel = path.relative_to(package).as_posix().encode()
        data = file_bytes(path, f"package: the source {shown(rel.decode(), 60)}")   # fuzz 34a C3, C4
        h.update(len(rel).to_bytes(8, "little") + rel + len(data).to_bytes(8, "little") + data)
    return h.hexdigest()


def _fingerprint(kind: type) -> str:
    """What tells two classes of one name apart on disk (fuzz 34a C1: a namedtuple or Enum re-bound under its name
    shared a cached result): a named tuple's ``_fields``, an Enum's members and values, a dataclass's field names;
    empty for other classes."""
    if issubclass(kind, enum.Enum):
        parts: Any = [[m.name, _member_value(m)] for m in kind]
    elif issubclass(kind, tuple) and isinstance(getattr(kind, "_fields", None), tuple):
        parts = ["fields", list(map(str, kind._fields))]
    elif dataclasses.is_dataclass(kind):
        parts = ["fields", [f.name for f in dataclasses.fields(kind)]]
    else:
        return ""
    return "~" + hashlib.sha256(json.dumps(parts).encode()).hexdigest()[:16]


def _member_value(member: enum.Enum) -> Any:
    try:
        return _canonical(member.value)
    except (TypeError, RecursionError):   # no encoding: its text (this member's own value is refused where it is used)
        return repr(member.value)


def _type_name(kind: type, _unnamed: dict[int, type] | None = None) -> str:
    """The name that determines ``kind`` in a key: a builtin's short name, else its module and qualified name and
    ``_fingerprint``.

    On disk (``_unnamed`` None) a class that its module's namespace does not hold as the same object under that name
    (one made in a function, a second ``namedtuple("P", ...)`` beside another ``P``) cannot be told apart from another
    of the same name by it (fuzz 33a C4: two named tuples ``P`` shared a cached result): TypeError (no canonical
    encoding; the call bypasses the disk). In the process (``_unnamed`` given) every class is keyed by identity
    (fuzz 34a C1: a class re-bound under its name shared the key): its name and ``id``, the class kept alive in
    ``_unnamed`` so that its ``id`` is never reused.
    """
    if kind.__module__ == "builtins":
        return kind.__qualname__
    name = f"{kind.__module__}.{kind.__qualname__}{_fingerprint(kind)}"
    if _unnamed is not None:
        _unnamed.setdefault(id(kind), kind)
        return f"{name}#{id(kind)}"
    found: Any = sys.modules.get(kind.__module__)
    for part in kind.__qualname__.split("."):
        found = getattr(found, part, None)
    if found is kind:
        return name
    raise TypeError(f"value: the class {kind.__module__}.{kind.__qualname__} is not found under that name in its "
                    "module (the key cannot tell it apart from another class of that name)")


def _canonical(value: Any, _open: frozenset[int] = frozenset(), _unnamed: dict[int, type] | None = None) -> Any:
    """A JSON-able encoding of ``value`` that determines it (type included), or TypeError.

    ``_open`` holds the ids of the containers being encoded around ``value``: a container that
    contains itself has no finite encoding (TypeError, not a RecursionError). Every class is named by
    ``_type_name`` (``_unnamed``: see there).
    """
    def name(v: Any) -> str:
        return _type_name(type(v), _unnamed)

    if value is None or isinstance(value, (bool, str)):
        return [name(value), value]
    if isinstance(value, enum.Enum):
        return ["enum", name(value), value.name, _canonical(value.value, _open, _unnamed)]
    if isinstance(value, (int, np.integer)):
        return [name(value), int(value)]
    if isinstance(value, np.floating) and np.finfo(value.dtype).nmant > 52:   # longdouble: its own digits
        return [name(value), np.format_float_scientific(value, unique=True)]
    if isinstance(value, (float, np.floating)):
        return [name(value), float(value).hex()]
    if isinstance(value, bytes):
        return ["bytes", value.hex()]
    if isinstance(value, (tuple, list, frozenset, dict, ReadOnlyMapping)) or (dataclasses.is_dataclass(value)
                                                              and not isinstance(value, type)):
        if id(value) in _open:
            raise TypeError(f"value: {type(value).__qualname__} contains itself (no finite canonical encoding "
                            "for the study cache)")
        _open = _open | {id(value)}
    if isinstance(value, (tuple, list)):
        return [name(value), [_canonical(v, _open, _unnamed) for v in value]]
    if isinstance(value, frozenset):
        return ["frozenset", sorted(json.dumps(_canonical(v, _open, _unnamed)) for v in value)]
    if isinstance(value, (dict, ReadOnlyMapping)):   # a frozen result's mapping field (fusion._frozen)
        return [name(value), [[_canonical(k, _open, _unnamed), _canonical(v, _open, _unnamed)] for k, v in value.items()]]
    if isinstance(value, np.ma.MaskedArray):   # its mask too: a masked array is not its data
        return ["masked", _canonical(value.filled(0).view(np.ndarray), _open, _unnamed),
                _canonical(np.ma.getmaskarray(value).view(np.ndarray), _open, _unnamed)]
    if isinstance(value, np.ndarray) and value.dtype.kind in "biufc":
        arr = np.ascontiguousarray(value)
        kind = "ndarray" if type(value) is np.ndarray else name(value)
        return [kind, arr.dtype.str, list(arr.shape), hashlib.sha256(arr.tobytes()).hexdigest()]
    if dataclasses.is_dataclass(value) and not isinstance(value, type):
        return ["dataclass", name(value),
                [[f.name, _canonical(getattr(value, f.name), _open, _unnamed)] for f in dataclasses.fields(value)]]
    raise TypeError(f"value: {type(value).__qualname__} has no canonical encoding for the study cache")


def study_key(qualname: str, arguments: dict[str, Any], digest: str | None = None) -> str:
    """The cache key of one call: SHA-256 of the source digest, numpy's version, the name and the arguments.

    Parameters
    ----------
    qualname : str
        The function's module and qualified name.
    arguments : dict
        Parameter name -> value, defaults applied.
    digest : str, optional
        The package's :func:`source_digest` (default: computed).

    Returns
    -------
    str
        Hex digest.

    Raises
    ------
    TypeError
        If ``qualname`` or ``digest`` is not a string, ``arguments`` is not a dict with string keys, or an
        argument has no canonical encoding (a container that contains itself, or one nested deeper than the
        interpreter's recursion limit, has none; then the call bypasses the disk).
    """
    return _key(text(qualname, "qualname"), arguments, digest)


#: The classes named by ``id`` in in-process keys (``_type_name``), kept alive so that no other class takes the ``id``.
_UNNAMED: dict[int, type] = {}


def _key(qualname: str, arguments: dict[str, Any], digest: str | None, unnamed: dict[int, type] | None = None) -> str:
    """:func:`study_key`; with ``unnamed`` (an in-process key, never the disk's) a class not found under its name in
    its module is named by its ``id`` (``_type_name``) instead of refused."""
    if not isinstance(arguments, dict):
        raise TypeError(f"arguments must be a dict, got {type(arguments).__name__}")
    encoded = []
    for k, v in arguments.items():
        if not isinstance(k, str):
            raise TypeError(f"arguments must have str keys (parameter names), got {type(k).__name__} {shown(k, 40)}")
        try:
            encoded.append([k, _canonical(v, _unnamed=unnamed)])
        except TypeError as exc:  # named by the argument it came from
            raise TypeError(f"arguments[{shown(k)}]: {str(exc).removeprefix('value: ')}") from None
        except RecursionError:   # nested deeper than the interpreter's stack: no encoding (the call bypasses the disk)
            raise TypeError(f"arguments[{shown(k)}]: nested too deeply for a canonical encoding") from None
    if digest is not None:
        digest = text(digest, "digest")
    payload = json.dumps([digest if digest is not None else source_digest(), np.__version__, qualname, encoded],
                         separators=(",", ":"))
    return hashlib.sha256(payload.encode()).hexdigest()


#: Values with nothing in them that a caller can change (a numpy scalar included, except a ``np.void`` record: a view).
_ATOMS = (type(None), bool, int, float, complex, str, bytes, range, enum.Enum, np.generic, type, Path)


def _frozen(value: Any, immutable: dict[int, Any], arrays: dict[int, np.ndarray],
            _open: frozenset[int] = frozenset()) -> tuple[bool, bool]:
    """Tell whether nothing in ``value`` can be changed and whether it holds an array of numbers: ``(whole, holds)``.

    Nothing is changed in place (a caller's array argument returned by the function stays the caller's, writeable).
    A plain ``ndarray`` of numbers (no object fields), at any depth in tuples, lists, dicts, read-only mappings,
    named tuples and dataclasses, counts as immutable: it is recorded in ``arrays`` (id -> array), and the cache
    keeps a sealed read-only copy of it (``_sealed``) of which each caller gets its own array object (``_own``;
    fuzz 37a C1). An array subclass (masked, matrix, record), an object array or a ``np.void`` record is mutable:
    copied for each caller. ``value`` is immutable if it is an atom, such an array, or a tuple, frozenset,
    :class:`~fusion._frozen.ReadOnlyMapping` or frozen dataclass of immutable values; a list, dict, set,
    non-frozen dataclass, pandas object or anything else is not. Every immutable part that holds no array is
    recorded in ``immutable`` (id -> object): every caller's copy shares them. A container that contains itself
    (``_open``: the ids of the containers around ``value``) is mutable.
    """
    if isinstance(value, np.void):   # a structured array's record: a writable view (fuzz 33a C8), copied per caller
        return False, False
    if isinstance(value, _ATOMS):
        return True, False
    if isinstance(value, np.ndarray):
        if type(value) is not np.ndarray or value.dtype.kind not in "biufcmMSUV" or value.dtype.hasobject:
            return False, False   # a subclass (its own attributes: a mask, a fill value) or objects: copied per caller
        arrays[id(value)] = value
        return True, True
    if id(value) in _open:
        return False, False
    inner = _open | {id(value)}
    if isinstance(value, (list, tuple, set, frozenset)):
        parts = [_frozen(v, immutable, arrays, inner) for v in value]   # every item seen, not only up to the first miss
        ok = isinstance(value, (tuple, frozenset))
    elif isinstance(value, (dict, ReadOnlyMapping)):
        parts = [p for k, v in value.items() for p in (_frozen(k, immutable, arrays, inner),
                                                        _frozen(v, immutable, arrays, inner))]
        ok = isinstance(value, ReadOnlyMapping)
    elif dataclasses.is_dataclass(value) and not isinstance(value, type):
        parts = [_frozen(getattr(value, f.name), immutable, arrays, inner) for f in dataclasses.fields(value)]
        ok = type(value).__dataclass_params__.frozen   # type: ignore[attr-defined]
    else:
        return False, False                       # a DataFrame, a Series, an object of another kind: copied
    ok = ok and all(whole for whole, _ in parts)
    holds = any(held for _, held in parts)
    if ok and not holds:
        immutable[id(value)] = value
    return ok, holds


def _sealed(arr: np.ndarray) -> tuple[np.ndarray, int]:
    """A read-only copy of ``arr`` whose memory is an immutable ``bytes`` object, and its offset in it: no array owns
    that memory, so no holder can make it writeable again (``setflags(write=True)`` raises), resize it, or reach an
    array it could reshape. An array over such memory already (another cached study's, nested in this result) shares
    it, not copied: one computation, one copy in memory."""
    if type(arr.base) is bytes:
        offset = arr.__array_interface__["data"][0] - np.frombuffer(arr.base, np.uint8).__array_interface__["data"][0]
        return np.ndarray(arr.shape, arr.dtype, buffer=arr.base, offset=offset, strides=arr.strides), offset
    order = "F" if arr.flags.f_contiguous and not arr.flags.c_contiguous else "C"
    return np.ndarray(arr.shape, arr.dtype, buffer=arr.tobytes(order=order), order=order), 0


def _own(sealed: np.ndarray, offset: int) -> np.ndarray:
    """A caller's own array object over a kept ``_sealed`` array's memory (about 0.5 us): its shape, dtype or strides
    changed in place change only it; its ``.base`` is the immutable ``bytes``, never the kept array."""
    return np.ndarray(sealed.shape, sealed.dtype, buffer=sealed.base, offset=offset, strides=sealed.strides)


#: What ``copy.deepcopy`` raises for a value it cannot copy (a memoryview, a generator, a lock), as the disk layer
#: catches for a value it cannot pickle.
_UNCOPYABLE = (copy.Error, pickle.PicklingError, TypeError, AttributeError)


class _Uncopyable(Exception):
    """A result that holds something mutable and cannot be deep-copied (fuzz 34a D1): returned uncached."""

    def __init__(self, value: Any) -> None:
        super().__init__("uncopyable result")
        self.value = value


class _Shared:
    """One cached result as every caller sees it: the object itself when nothing in it can be changed and it holds no
    array, else a deep copy per caller that shares the result's immutable parts without arrays and gives the caller
    its own array objects over the kept arrays' read-only memory (fuzz 37a C1: a caller's ``r.shape = (n, 1)``,
    ``r.dtype = ...``, ``r.resize(...)`` or ``r.setflags(write=True)`` on a shared array object reached every later
    caller).

    The kept value is a copy made once when the result is kept, in which every plain array of numbers is a sealed
    read-only copy (``_sealed``: an array that was a view of a caller's array, fuzz 35a C1, or the caller's array
    itself, is never shared); every caller, the first too (``_spare``), gets a copy of the kept value whose arrays are
    new array objects over the kept memory (``_own``; a study computed once has the same memory in every result). A
    result that holds something mutable and cannot be deep-copied raises ``_Uncopyable`` carrying it, and is returned
    to its caller uncached (fuzz 34a D1: a TypeError "cannot pickle" came after the computation, naming nothing)."""

    __slots__ = ("value", "immutable", "arrays", "whole", "_spare")

    def __init__(self, value: Any, keep: bool = True) -> None:
        self.value = value
        self.immutable: dict[int, Any] = {}
        found: dict[int, np.ndarray] = {}
        whole, holds = _frozen(value, self.immutable, found)
        self.whole = whole and not holds             # the object itself serves every caller
        self.arrays: dict[int, tuple[np.ndarray, int]] = {}   # id -> a kept array and its offset in its bytes
        self._spare: list[Any] = []
        if keep and not self.whole:
            sealed = {i: _sealed(a) for i, a in found.items()}
            memo = dict(self.immutable)
            memo.update({i: kept for i, (kept, _) in sealed.items()})
            try:   # the kept value is a copy: nothing in it is a caller's (an argument, a view of one; fuzz 35a C1)
                self.value = copy.deepcopy(value, memo)
            except _UNCOPYABLE:
                raise _Uncopyable(value) from None
            self.arrays = {id(kept): (kept, offset) for kept, offset in sealed.values()}
            self._spare.append(self._copy())   # the first caller's copy, made as every later caller's is

    def _copy(self) -> Any:
        memo = dict(self.immutable)
        memo.update({i: _own(a, offset) for i, (a, offset) in self.arrays.items()})
        return copy.deepcopy(self.value, memo)

    def get(self) -> Any:
        if self.whole:
            return self.value
        try:
            return self._spare.pop()            # atomic: one caller gets the copy made when the result was kept
        except IndexError:
            return self._copy()


def _readonly(arr: np.ndarray) -> np.ndarray:
    arr.setflags(write=False)
    return arr


class _Pickler(pickle.Pickler):
    """Pickles read-only arrays as read-only (numpy's own pickling restores them writeable)."""

    def reducer_override(self, obj: Any) -> Any:
        if type(obj) is np.ndarray and not obj.flags.writeable:
            return _readonly, (np.array(obj),)
        return NotImplemented


def _dumps(value: Any) -> bytes:
    buf = io.BytesIO()
    _Pickler(buf, protocol=pickle.HIGHEST_PROTOCOL).dump(value)
    return buf.getvalue()


def _log(qualname: str, arguments: dict[str, Any], event: str, cpu: float) -> None:
    path = os.environ.get(LOG_ENV)
    if not path:
        return
    line = json.dumps({"qualname": qualname, "args": {k: repr(v)[:200] for k, v in arguments.items()},
                       "pid": os.getpid(), "cpu": round(cpu, 3), "event": event})
    try:   # checked by _environment before the work; a log made unusable since is still named (fuzz 45b C2)
        with open(path, "a", encoding="utf-8") as fh:
            fh.write(line + "\n")
    except OSError as exc:
        raise ValueError(f"the environment variable {LOG_ENV} must name a file to which lines can be appended, got "
                         f"{shown(path)} ({type(exc).__name__}: {exc.strerror})") from None


#: Bytes of the BLAKE2b digest of an entry's payload, stored before it (fuzz 40b C3: a changed float in a stored
#: array loaded silently). The digest costs about 0.8 ns a byte here (``hashlib.blake2b``; measured on this shared
#: machine, minimum of 7, CPU time): the hit of chapter 06's tracking study (13.8 MB, the largest entry found) went
#: from 28 to 41 ms, chapter 04's studies (7.2 MB) from 6 to 15 ms; computing them takes tens of CPU-seconds.
_DIGEST = 32
#: Flags of an entry's or a lock's ``os.open``: never blocks on a FIFO (fuzz 40b C2), not inherited by a child.
_NONBLOCK = os.O_NONBLOCK | getattr(os, "O_CLOEXEC", 0)
#: Largest entry file read back, in bytes: the memory budget (``fusion._counts.MAX_ELEMENTS`` float64, 2 GiB) plus
#: 16 MiB of pickle framing, key and digest. A study's result is held in memory within that budget, so no entry the
#: cache writes is larger (it does not write one that is: :func:`_entry`'s bytes beyond it are left unstored); a
#: larger file in an entry's place is a miss found on its size, without reading it (fuzz 41b D1: a 3 GiB sparse file
#: was read and hashed for 15.8 CPU-s before the miss). The largest entry of the book is 13.8 MB.
_MAX_ENTRY_BYTES = MAX_ELEMENTS * 8 + 2**24


def _regular(fd: int) -> bool:
    """Whether the open ``fd`` is a regular file (not a FIFO, a socket, a device or a directory): checked on the
    descriptor itself, so a file swapped in after the check is not read."""
    return stat.S_ISREG(os.fstat(fd).st_mode)


def _entry(key: str, value: Any) -> bytes:
    """The bytes stored for ``key``: the digest of the payload, then the payload (the pickled ``(key, value)``)."""
    payload = _dumps((key, value))   # the key stored with the value: a file under another name is a miss
    return hashlib.blake2b(payload, digest_size=_DIGEST).digest() + payload


def _stored(target: Path, key: str) -> tuple[Any] | None:
    """``(value,)`` stored in ``target`` for ``key``, or None (a miss, recomputed and rewritten) when the file cannot be
    read back (empty, truncated, corrupt: issue 35, fuzz 21 D14; a directory) or holds another key's result or something
    else (anything but a plain tuple of the key's own str and the value: an array or a Series as its key is a miss).

    Not a regular file (a FIFO, a socket, a device: fuzz 40b C2, where ``open`` blocked for ever) is a miss, found on
    the descriptor opened without blocking; so is a file whose payload does not match its stored digest (fuzz 40b C3:
    one changed float of an array loaded silently), checked before anything is unpickled: a damaged length field (a
    frame's, a bytes' or a text's, which made pickle ask for that much memory, fuzz 37b C1) fails it too, and any
    failure of the unpickling (a MemoryError included: a real shortage recurs in the recomputation) is a miss. So is a
    file larger than any entry the cache writes (``_MAX_ENTRY_BYTES``, fuzz 41b D1), found on its size without
    reading it. The descriptor is closed on every path (fuzz 41b C6). The hit path reads the file once."""
    try:
        fd = os.open(target, os.O_RDONLY | _NONBLOCK)
    except OSError:
        return None
    try:
        # checked on the descriptor before any read; the descriptor is closed on every path (fuzz 41b C6: a directory
        # in the entry's place made os.fdopen raise, leaving the descriptor open, one per lookup)
        st = os.fstat(fd)
        if not stat.S_ISREG(st.st_mode) or st.st_size > _MAX_ENTRY_BYTES:
            return None
        with open(fd, "rb", closefd=False) as fh:
            data = fh.read(_MAX_ENTRY_BYTES + 1)
        if len(data) > _MAX_ENTRY_BYTES:      # grown since the fstat
            return None
        digest, payload = data[:_DIGEST], memoryview(data)[_DIGEST:]
        if len(digest) < _DIGEST or hashlib.blake2b(payload, digest_size=_DIGEST).digest() != digest:
            return None
        loaded = pickle.loads(payload)        # noqa: S301 - our own file, written in this invocation
    except Exception:                         # noqa: BLE001 - any unreadable file is a miss, never the study's error
        return None                           # (MemoryError included: a real shortage recurs in the recomputation)
    finally:
        os.close(fd)
    # compared by exact type and value (fuzz 38b D2): a hand-made entry keyed by an array or a Series gave numpy's
    # ambiguous-truth error, np.array([key]) was a false hit; either is a damaged entry, a miss
    if type(loaded) is tuple and len(loaded) == 2 and type(loaded[0]) is str and loaded[0] == key:
        return (loaded[1],)
    return None


#: The cache directories found usable in this process (``_usable``: tried once each).
_USABLE: set[str] = set()


def _usable(root: str) -> None:
    """Create the directory ``root`` and a file in it once, or ValueError naming :data:`ENV` (fuzz 33a C6: a path
    through a file or ``/proc/self`` gave an OS error from every cached call)."""
    try:
        Path(root).mkdir(parents=True, exist_ok=True)
        fd, probe = tempfile.mkstemp(dir=root, prefix=".probe.", suffix=".tmp")
        os.close(fd)
        os.remove(probe)
    except OSError as exc:
        raise ValueError(f"the environment variable {ENV} must name a directory in which files can be created, got "
                         f"{shown(root)} ({type(exc).__name__}: {exc.strerror})") from None
    _USABLE.add(root)


def _environment() -> Path | None:
    """The cache directory :data:`ENV` names (None when unset or empty), after checking the environment before any
    work: ValueError naming the variable when :data:`ENV` holds only blanks or names something that is not a
    directory or a directory in which no file can be created (tried once per process, ``_usable``), or (with a
    directory) :data:`LOG_ENV` names a directory, a FIFO or a device, or a file in a missing one (fuzz 32a D1: an
    OS error named nothing, and came after the computation, whose result was lost)."""
    root, log = os.environ.get(ENV), os.environ.get(LOG_ENV)
    if root is not None and root and not root.strip():
        raise ValueError(f"the environment variable {ENV} holds only blanks: set it to a directory or unset it")
    if root:   # resolved once here and used so (fuzz 34a C2: a relative name probed in one working directory was used
        try:   # from another)
            root = os.path.abspath(root)
        except (OSError, ValueError) as exc:
            raise ValueError(f"the environment variable {ENV} must name a directory, got {shown(root)} "
                             f"({type(exc).__name__})") from None
    if root and os.path.exists(root) and not os.path.isdir(root):
        raise ValueError(f"the environment variable {ENV} must name a directory, got the file {shown(root)}")
    if root and root not in _USABLE:
        _usable(root)
    if root and log and (os.path.isdir(log) or not os.path.isdir(os.path.dirname(os.path.abspath(log)))
                         or (os.path.exists(log) and not os.path.isfile(log))):   # a FIFO, a device (fuzz 34a C3)
        raise ValueError(f"the environment variable {LOG_ENV} must name a regular file in an existing directory, got "
                         f"{shown(log)}")
    if root and log:
        _appendable(log)
    return Path(root) if root else None


def _appendable(log: str) -> None:
    """Open ``log`` for append as :func:`_log`'s ``open(log, "a")`` will (created if missing, never blocking, then
    sought to its end) and close it, or ValueError naming :data:`LOG_ENV` before any work (fuzz 45b C2: a dangling
    symlink, a 300-character name, ``/proc/version`` (opened for writing as root, then its seek refused, EINVAL) or a
    new file in ``/proc/self`` passed the checks above, and the OS error came after the study, naming nothing)."""
    fd = -1
    try:
        fd = os.open(log, os.O_WRONLY | os.O_APPEND | os.O_CREAT | _NONBLOCK, 0o666)
        os.lseek(fd, 0, os.SEEK_END)
        regular = _regular(fd)
    except OSError as exc:
        raise ValueError(f"the environment variable {LOG_ENV} must name a file to which lines can be appended, got "
                         f"{shown(log)} ({type(exc).__name__}: {exc.strerror})") from None
    finally:
        if fd >= 0:
            os.close(fd)
    if not regular:   # swapped in after the checks above
        raise ValueError(f"the environment variable {LOG_ENV} must name a regular file in an existing directory, got "
                         f"{shown(log)}")


def _through_disk(root: Path, key: str, qualname: str, arguments: dict[str, Any], compute: Callable[[], Any]) -> Any:
    """The stored result of ``key`` under ``root``, or ``compute()`` stored there; one process computes, others wait."""
    try:   # before the work: the folder may have become unusable since it was probed (fuzz 34a C2)
        root.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise ValueError(f"the environment variable {ENV} must name a directory in which files can be created, got "
                         f"{shown(str(root))} ({type(exc).__name__}: {exc.strerror})") from None
    target = root / f"{key}.pkl"
    start = time.process_time()
    try:   # without blocking: a FIFO in its place opened for writing waited for a reader for ever (fuzz 40b C2)
        fd = os.open(root / f"{key}.lock", os.O_WRONLY | os.O_CREAT | _NONBLOCK, 0o666)
    except OSError:   # a directory (fuzz 37b D1), a FIFO without reader: computed and returned unstored, as without
        return compute()   # the disk
    lock = os.fdopen(fd, "w", encoding="utf-8")   # noqa: SIM115 - closed below
    if not _regular(fd):   # a FIFO with a reader, a device: not a lock file, computed and returned unstored
        lock.close()
        return compute()
    with lock:
        fcntl.flock(lock, fcntl.LOCK_EX)      # released when the file closes (also on an exception)
        stored = _stored(target, key) if target.exists() else None
        if stored is not None:
            _log(qualname, arguments, "loaded", time.process_time() - start)
            return stored[0]
        value = compute()
        try:
            data = _entry(key, value)
        except (pickle.PicklingError, TypeError, AttributeError):
            data = None                       # not picklable: every process computes it, as without the cache
        if data is not None and len(data) <= _MAX_ENTRY_BYTES:   # a larger one would be read back as a miss
            _store(root, key, target, data)
        _log(qualname, arguments, "computed", time.process_time() - start)
        return value


def _store(root: Path, key: str, target: Path, data: bytes) -> None:
    """Write ``data`` to ``target`` atomically, or leave it unstored when the entry cannot be written (a directory at
    ``target``, a full disk: fuzz 37b D1, the computed result was lost to an OS error)."""
    tmp = None
    try:
        fd, tmp = tempfile.mkstemp(dir=root, prefix=f".{key}.", suffix=".tmp")
        with os.fdopen(fd, "wb") as fh:
            fh.write(data)
        os.replace(tmp, target)               # atomic: a reader sees the whole file or none
    except OSError:
        if tmp is not None:
            with contextlib.suppress(OSError):
                os.remove(tmp)


def _name_unhashable(fn: Callable[..., Any], args: tuple[Any, ...], kwargs: dict[str, Any]) -> None:
    """Raise a TypeError naming the first argument of ``fn``'s call that cannot be hashed (a cache key); else return."""
    try:
        sig = inspect.signature(fn)
        bound = sig.bind_partial(*args, **kwargs).arguments
    except (TypeError, ValueError):
        sig, bound = None, {**{f"argument {i}": a for i, a in enumerate(args)}, **kwargs}
    named: list[tuple[str, Any]] = []
    for name, value in bound.items():
        kind = sig.parameters[name].kind if sig is not None else None
        if kind is inspect.Parameter.VAR_POSITIONAL:
            named += [(f"{name}[{i}]", v) for i, v in enumerate(value)]
        elif kind is inspect.Parameter.VAR_KEYWORD:
            named += list(value.items())
        else:
            named.append((name, value))
    for name, value in named:
        try:
            hash(value)
        except TypeError:
            raise TypeError(f"{name} must be hashable (the function caches its results), got "
                            f"{type(value).__name__} {shown(value, 40)}") from None


#: What a cached function's ``cache_info()`` returns (the fields of ``functools.lru_cache``'s).
CacheInfo = collections.namedtuple("CacheInfo", ["hits", "misses", "maxsize", "currsize"])


def process_cache(maxsize: int | None = 128) -> Callable[[Callable[..., Any]], Any]:
    """Decorator: ``functools.lru_cache`` (typed) under the study cache's sharing rule, in the process only.

    For a function that reads a file or that the disk cannot key (a claim file, a private helper): a result in
    which nothing can be changed and no array is held (see :func:`study_cache`) is shared by every call; any other
    result (an array, a list, dict, DataFrame, non-frozen dataclass in it) is deep-copied for each caller, its
    immutable parts shared and its arrays of numbers new read-only array objects over the kept memory. A caller's edit of a result never reaches another call. A result that
    holds something mutable and cannot be deep-copied (a memoryview, a generator) is returned uncached.

    Calls are keyed as ``functools.lru_cache(typed=True)`` keys them: by equality, the type checked for each top-level
    argument only, so equal arguments share one result: ``f(-0.0)`` gets ``f(0.0)``'s and ``f((True,))`` gets
    ``f((1,))``'s. Only a function whose result is the same for equal arguments may take it;
    :func:`study_cache` (keyed by a canonical encoding, in which those are different calls) is for the others.

    Parameters
    ----------
    maxsize : int or None
        Entries kept, least recently used dropped first: a count (``0`` keeps none) or ``None`` (unbounded).

    Returns
    -------
    callable
        The decorator. The wrapped function has ``cache_clear`` and ``cache_info`` (``functools.lru_cache``'s).

    Raises
    ------
    TypeError
        ``maxsize`` is not an integer type or ``None``.
    ValueError
        ``maxsize`` is negative or beyond the ceiling of a count.
    """
    if maxsize is not None:
        maxsize = count(maxsize, "maxsize", minimum=0)

    def decorate(fn: Callable[..., Any]) -> Any:
        shared = functools.lru_cache(maxsize=maxsize, typed=True)(lambda *a, **k: _Shared(fn(*a, **k), maxsize != 0))

        @functools.wraps(fn)
        def cached(*args: Any, **kwargs: Any) -> Any:
            try:
                entry = shared(*args, **kwargs)
            except _Uncopyable as uncached:   # not kept (lru_cache keeps no exception): the caller's own
                return uncached.value
            except TypeError:
                _name_unhashable(fn, args, kwargs)   # the cache hashes the arguments before fn's own checks
                raise
            return entry.value if maxsize == 0 else entry.get()

        cached.cache_clear = shared.cache_clear   # type: ignore[attr-defined]
        cached.cache_info = shared.cache_info     # type: ignore[attr-defined]
        return cached

    return decorate


def _named(fn: Callable[..., Any], found: list[bool]) -> bool:
    """Whether the disk may serve ``fn``: its module (not ``__main__``) holds it under its qualified name (itself, or a
    wrapper whose ``__wrapped__`` chain reaches it); ``found`` keeps the answer once known.

    A function made in a function (two closures of one factory share a name, ``make.<locals>.f``), a lambda, or a
    script's function (``__main__``: two scripts' functions share a name) cannot be told apart from another of its name
    by the key, as a class made in a function cannot (``_type_name``; fuzz 34a D2: ``make(3)(1)`` loaded
    ``make(2)(1)``'s result): it is cached in the process only."""
    if found:
        return found[0]
    if fn.__module__ == "__main__" or "<" in fn.__qualname__ or fn.__module__ not in sys.modules:
        found.append(False)
        return False
    obj: Any = sys.modules[fn.__module__]
    for part in fn.__qualname__.split("."):
        obj = getattr(obj, part, None)
    for _ in range(16):                         # a wrapper of a wrapper of fn (functools.wraps sets __wrapped__)
        if obj is fn:
            found.append(True)
            return True
        obj = getattr(obj, "__wrapped__", None)
        if obj is None:
            break
    return False                                # not (yet) bound under its name: asked again at the next call


def study_cache(maxsize: int | None = 128) -> Callable[[Callable[..., Any]], Any]:
    """Decorator: cache a deterministic study function in the process and, with :data:`ENV` set, across processes.

    Parameters
    ----------
    maxsize : int or None
        Entries of the in-process cache, least recently used dropped first, keyed by the call's canonical
        encoding (:func:`study_key`, the disk's key: ``1``, ``1.0`` and ``True``, or ``0.0`` and ``-0.0``, are
        different calls, as are a masked array and its data, an ``np.matrix`` and its array, and two
        ``longdouble`` values that round to one float; arguments without one, such as a callable, by equality and type as ``functools.lru_cache``
        does): a count (an integer type, 0 or more; ``0`` caches nothing in the process) or ``None`` (unbounded).

    Returns
    -------
    callable
        The decorator. The wrapped function has ``cache_clear`` and ``cache_info`` (of the in-process cache).

    Raises
    ------
    TypeError
        ``maxsize`` is not an integer type or ``None`` (a float, a Fraction, a duration, a bool).
    ValueError
        ``maxsize`` is negative or beyond the ceiling of a count. A call of the wrapped function, before any work,
        when the environment is misconfigured: :data:`ENV` holding only blanks, naming a file, or naming a
        directory that cannot be created or in which no file can be created (a path through a file), or (with
        :data:`ENV` set) :data:`LOG_ENV` naming a directory or a file in a missing directory; the message names
        the variable.

    Notes
    -----
    The function must be a pure function of its arguments (seeded randomness included): the first process of a
    run computes it, the others load a bitwise-equal copy. Its callers cannot change what a later call returns:
    each caller gets its own read-only array objects over the kept arrays' memory, which no holder can make
    writeable, resize or reshape for another caller, and a result holding anything mutable (a list, dict, DataFrame,
    non-frozen dataclass) is deep-copied for each call (see the module's docstring; fuzz 37a C1). The cache keeps a
    sealed copy of every array (one copy of the data when the result is kept): a function that returns an array
    argument itself, or a view of one (``x[1:]``, ``x.T``), leaves the caller's own array as it is (writeable, not
    shared with any result; fuzz 32a D2, 35a C1, D2). A cached
    function should return arrays of its own, as the book's studies do. A result that holds something mutable and
    cannot be deep-copied (a memoryview, a generator, a lock in a dict) is returned to its caller
    uncached: every call computes it, as without the cache.

    The disk serves only a function that its module holds under its qualified name (a module-level ``def`` or a
    wrapper of one, not in ``__main__``): a closure made by a factory (two closures of one factory share a name
    but not their values), a lambda, or a script's function is cached in the process only.

    A class is part of the key by its module and qualified name; a class its module does not hold under that name
    (one made in a function, or a second ``namedtuple("P", ...)`` beside another ``P``) cannot be named on disk, so
    a call with one is cached in the process only, keyed by that class's identity. A dataclass argument is keyed by
    its type and fields, as its ``==`` compares it: state outside its fields (an attribute set in ``__post_init__``
    or later) is not part of the key, so a study must not read such state of its arguments.
    """
    if maxsize is not None:
        maxsize = count(maxsize, "maxsize", minimum=0)

    def decorate(fn: Callable[..., Any]) -> Any:
        qualname = f"{fn.__module__}.{fn.__qualname__}"
        sig = inspect.signature(fn)

        # arguments without a canonical encoding (a callable, a generator) are cached by equality, typed, as before
        by_equality = process_cache(maxsize)(fn)
        memo: collections.OrderedDict[str, _Shared] = collections.OrderedDict()
        named: list[bool] = []                 # ``_named``'s answer, found once
        lock = threading.Lock()
        stats = {"hits": 0, "misses": 0}

        @functools.wraps(fn)
        def cached(*args: Any, **kwargs: Any) -> Any:
            bound = sig.bind(*args, **kwargs)
            bound.apply_defaults()
            arguments = dict(bound.arguments)
            try:   # in the process every class by identity (fuzz 34a C1); the disk's key below
                key = _key(qualname, arguments, None, _UNNAMED)
            except TypeError:
                return by_equality(*args, **kwargs)
            # keyed by the canonical encoding, as on disk: 1, 1.0, True and Fraction(1), or 0.0 and -0.0, are different
            # calls (an equality-keyed cache gave a cached result to an argument the function refuses, fuzz 15)
            with lock:
                if key in memo:
                    memo.move_to_end(key)
                    stats["hits"] += 1
                    return memo[key].get()
                stats["misses"] += 1
            root = _environment()             # checked before any work, also for a call kept in the process
            disk_key = None
            if root is not None and _named(fn, named):
                try:
                    disk_key = study_key(qualname, arguments)
                except TypeError:   # a class the disk's key cannot name (fuzz 33a C4): kept in the process
                    disk_key = None
            value = (_through_disk(root, disk_key, qualname, arguments, lambda: fn(*args, **kwargs))
                     if root is not None and disk_key is not None else fn(*args, **kwargs))
            try:
                result = _Shared(value, maxsize != 0)
            except _Uncopyable:                # not kept (fuzz 34a D1): the caller's own, as without the cache
                return value
            if maxsize == 0:
                return result.value            # not kept: the caller's own
            with lock:
                memo[key] = result
                if maxsize is not None and len(memo) > maxsize:
                    memo.popitem(last=False)
            return result.get()

        def cache_clear() -> None:
            with lock:
                memo.clear()
                stats.update(hits=0, misses=0)
            by_equality.cache_clear()

        def cache_info() -> CacheInfo:
            other = by_equality.cache_info()
            with lock:
                return CacheInfo(stats["hits"] + other.hits, stats["misses"] + other.misses, maxsize,
                                 len(memo) + other.currsize)

        cached.cache_clear = cache_clear   # type: ignore[attr-defined]
        cached.cache_info = cache_info     # type: ignore[attr-defined]
        return cached

    return decorate
