"""The rule for a folder argument (issue 35): a path by type, a folder by value, named and never echoed whole.

A folder argument is a ``str`` or an :class:`os.PathLike` (anything else is a :class:`TypeError` naming it).
A value the system cannot use as a path (a name too long, a NUL byte), a file where a folder is wanted, a
missing folder where an existing one is wanted, or a folder that cannot be made are a :class:`ValueError`
naming the argument and showing at most 60 characters of the value (a 5000-character name is not echoed).
"""

from __future__ import annotations

import contextlib
import json
import math
import os
import stat
from pathlib import Path

from fusion._shown import shown


def folder(value: object, name: str, *, create: bool = False) -> Path:
    """``value`` as a :class:`~pathlib.Path` naming a folder, made (with its parents) if ``create``.

    Parameters
    ----------
    value : str or os.PathLike
        The folder.
    name : str
        The argument's name, for the messages.
    create : bool, optional
        Make the folder (and its parents) if it does not exist (default: it must exist).

    Returns
    -------
    pathlib.Path
        ``Path(value)``, unresolved.

    Raises
    ------
    TypeError
        ``value`` is not a ``str`` nor an ``os.PathLike``.
    ValueError
        ``value`` is not a usable path, names something other than a folder, or (without ``create``) no
        existing folder; with ``create``, the folder cannot be made.
    """
    if not isinstance(value, (str, os.PathLike)):
        raise TypeError(f"{name} must be a path (str or os.PathLike), got {type(value).__name__} {shown(value, 40)}")
    try:
        path = Path(value)
        if "\x00" in str(path):   # is_dir() says False for it (Python 3.11), mkdir raises
            raise ValueError("embedded null byte")
        is_dir = path.is_dir()
        exists = is_dir or path.exists()
    except (OSError, ValueError, TypeError) as exc:   # a name too long for the system, a NUL byte, bytes
        raise ValueError(f"{name} must be a folder, got {shown(value, 60)} ({type(exc).__name__})") from None
    if exists and not is_dir:
        raise ValueError(f"{name} must be a folder, got {shown(value, 60)}, which is not one")
    if not is_dir and not create:
        raise ValueError(f"{name} must be an existing folder, got {shown(value, 60)}")
    if not is_dir:
        try:
            path.mkdir(parents=True, exist_ok=True)
        except (OSError, ValueError) as exc:   # a parent that is a file, no permission, a name too long
            raise ValueError(f"{name}: cannot make the folder {shown(value, 60)} "
                             f"({exc.strerror or type(exc).__name__})") from None
    return path


def file_in(directory: Path, filename: str, name: str) -> Path:
    """``directory / filename``, a file to write in a folder :func:`folder` checked: anything but a file (or nothing)
    under that name is refused naming ``name``, the folder's argument (fuzz 22a W).

    Parameters
    ----------
    directory : pathlib.Path
        The folder, already checked.
    filename : str
        The file's name in it.
    name : str
        The folder argument's name, for the message.

    Returns
    -------
    pathlib.Path
        The file's path (an existing file is overwritten by the caller; a symlink to one is followed).

    Raises
    ------
    ValueError
        ``directory`` holds something other than a file under ``filename``: a folder, a dangling symlink.
    """
    path = directory / filename
    if path.is_symlink() and not path.exists():
        raise ValueError(f"{name} holds {filename}, which is a dangling symlink, not a file")
    if path.exists() and not path.is_file():
        raise ValueError(f"{name} holds {filename}, which is not a file")
    return path


#: The largest file read whole (claim files, ledger and benchmark records, sources are kilobytes; fuzz 34a C4).
MAX_FILE_BYTES = 16 << 20


def file_bytes(path: Path, label: str, limit: int = MAX_FILE_BYTES) -> bytes:
    """The bytes of the regular file ``path``, or ValueError ``"<label>: not a readable file (why)"`` before reading
    (``label`` names the caller's argument): a path the system cannot open (missing, no permission, a NUL byte),
    anything but a regular file (a FIFO, a device such as ``/dev/zero``, a folder: read whole, they hang or never end,
    fuzz 34a C3), or a file larger than ``limit`` bytes (read whole, a MemoryError, fuzz 34a C4). Opened without
    blocking (a FIFO without a writer would block the open itself)."""
    try:
        fd = os.open(path, os.O_RDONLY | os.O_NONBLOCK)
    except (OSError, ValueError) as exc:
        raise ValueError(f"{label}: not a readable file ({getattr(exc, 'strerror', None) or exc})") from None
    st = os.fstat(fd)
    if not stat.S_ISREG(st.st_mode) or st.st_size > limit:
        os.close(fd)
        why = (f"larger than {limit:,} bytes" if stat.S_ISREG(st.st_mode)
               else "not a regular file: a folder, a FIFO or a device")
        raise ValueError(f"{label}: not a readable file ({why})")
    os.set_blocking(fd, True)
    with os.fdopen(fd, "rb") as fh:
        data = fh.read(limit + 1)
    if len(data) > limit:   # grew since the check
        raise ValueError(f"{label}: not a readable file (larger than {limit:,} bytes)")
    return data


def file_text(path: Path, label: str, limit: int = MAX_FILE_BYTES) -> str:
    """The UTF-8 text of the regular file ``path`` (:func:`file_bytes`), newlines universal as ``Path.read_text``
    gives them; text that is not UTF-8 is a ValueError ``"<label>: not UTF-8 text (...)"`` (fuzz 35b B3: the chapter
    layer's file readers read through this one reader, so that a caller's folder holding a FIFO, a device, a huge or
    a malformed file is refused naming the caller's argument)."""
    data = file_bytes(path, label, limit)
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError as exc:
        raise ValueError(f"{label}: not UTF-8 text ({exc.reason} at byte {exc.start})") from None
    return text.replace("\r\n", "\n").replace("\r", "\n")


def write_file_text(path: Path, text: str, label: str) -> bytes:
    """Write ``text`` as UTF-8 to the file ``path``, whole or not at all: the one writer of the book's files (the
    ledger, ``fusion.book.ledger.Ledger.write``; the reseeding sweep's ``stability.json``).

    The text is encoded before any file is touched, then written to a temporary file in the target's folder and
    renamed over the target (:func:`os.replace`, atomic on one file system), so that a failure (a text that is not
    UTF-8, a full disk, no permission) leaves the old file as it was (fuzz 49b C5: ``Path.write_text`` truncated a
    ledger file to 0 bytes and then failed to encode a lone surrogate). A symlink to a file is followed (the file it
    names is replaced, the link kept); an existing file keeps its permission bits, a new one gets the default ones
    (``0o666`` less the umask, as ``open`` gives).

    Parameters
    ----------
    path : pathlib.Path
        The file (checked by the caller: :func:`file_in`).
    text : str
        The text to write.
    label : str
        What the caller calls the file or its argument, named in the message.

    Returns
    -------
    bytes
        The bytes written (the UTF-8 text).

    Raises
    ------
    ValueError
        ``text`` cannot be written as UTF-8 (a lone surrogate), before any file is touched; ``path`` exists and is
        not a regular file (a FIFO, a device, a folder), or is a symbolic link to no file or in a loop, nothing
        written; or the file cannot be written (an OS error:
        no permission, a full disk), the old file left as it was; naming ``label``.
    """
    try:
        data = text.encode("utf-8")
    except UnicodeEncodeError as exc:
        raise ValueError(f"{label}: cannot write {path.name}: its text holds U+{ord(exc.object[exc.start]):04X} at "
                         f"character {exc.start}, which UTF-8 cannot encode (a lone surrogate); the file is "
                         "unchanged") from None
    target = Path(os.path.realpath(path))   # a symlink's file, replaced in its own folder
    # The temporary name does not grow with the target's (fuzz 50b D1: ".<name>.<pid>.<hex>.tmp" made a target name
    # of 236-255 bytes, which open() writes, "too long"): 28 characters at most whatever the target.
    tmp = target.with_name(f".fusion-{os.getpid()}-{os.urandom(4).hex()}.tmp")
    try:   # every check inside: an OS error of the checks (a name too long, no permission) is named too (54b C1)
        if os.path.islink(target):   # realpath stops at a link only in a loop of links (fuzz 54b D3)
            raise ValueError(f"{label}: {path.name} is a symbolic link in a loop; nothing written")
        try:
            st: os.stat_result | None = os.stat(target)
        except FileNotFoundError:
            st = None
            if os.path.islink(path):   # a dangling link, refused as the ledger's file_in refuses it (54b D3)
                raise ValueError(f"{label}: {path.name} is a symbolic link to no file; nothing written") from None
        if st is not None and not stat.S_ISREG(st.st_mode):   # a FIFO, a device, a folder: never replaced (50b D2)
            raise ValueError(f"{label}: {path.name} is not a regular file; the book writes only files (nothing "
                             "written)")
        mode = None if st is None else stat.S_IMODE(st.st_mode)
        fd = os.open(tmp, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o666)   # the umask applies
        try:
            with os.fdopen(fd, "wb") as fh:
                fh.write(data)
            if mode is not None:
                os.chmod(tmp, mode)
            os.replace(tmp, target)
        except BaseException:
            with contextlib.suppress(OSError):
                os.remove(tmp)
            raise
    except OSError as exc:   # no permission, a full disk: the old file is unchanged
        raise ValueError(f"{label}: cannot write {path.name} ({exc.strerror or type(exc).__name__}); the file is "
                         "unchanged") from None
    return data


def _no_constant(name: str) -> None:
    raise ValueError(f"{name} (not a JSON number: NaN and infinities are refused)")


def _finite_float(literal: str) -> float:
    v = float(literal)
    if not math.isfinite(v):  # 1e999 overflows to an infinity
        raise ValueError(f"{literal[:40]} overflows to an infinity (NaN and infinities are refused)")
    return v


def _float_range_int(literal: str) -> int:
    v = int(literal)   # beyond 4300 digits: Python's own ValueError
    if len(literal) > 308:   # 309 digits or more: near or beyond the float range (checked only there)
        try:
            float(v)
        except OverflowError:   # fuzz 37b C4: a reader's float(v) raised it
            raise ValueError(f"an integer of {len(literal.lstrip('-'))} digits overflows a float (integers beyond "
                             "about ±1.8e308 are refused)") from None
    return v


def json_document(text: str, label: str) -> object:
    """The JSON document ``text``, by the book's one rule for its JSON files (issue 35, fuzz 21; fuzz 36b B1, B2):
    text that is not JSON, nested beyond Python's recursion limit, holding ``NaN``, ``Infinity`` or a number that
    overflows to one (which :func:`json.dumps` writes but JSON does not define), or an integer beyond the float range
    (a number a reader converts to float: ``10**400`` raised OverflowError there, fuzz 37b C4) is a ValueError
    ``"<label>: ..."`` (``label`` names the caller's argument and the file), instead of a
    :class:`json.JSONDecodeError`, a :class:`RecursionError`, an :class:`OverflowError` or an unnamed ValueError."""
    try:
        return json.loads(text, parse_constant=_no_constant, parse_float=_finite_float, parse_int=_float_range_int)
    except json.JSONDecodeError as exc:
        raise ValueError(f"{label}: not JSON ({exc.msg} at line {exc.lineno}, column {exc.colno})") from None
    except RecursionError:
        raise ValueError(f"{label}: nested too deep to read") from None
    except ValueError as exc:  # a NaN or an infinity (parse_constant, parse_float), an integer beyond a float's range
        raise ValueError(f"{label}: {str(exc)[:200]}") from None


def file_json(path: Path, label: str, limit: int = MAX_FILE_BYTES) -> object:
    """The JSON document of the regular file ``path`` (:func:`file_text`) by :func:`json_document`'s rule: text that
    is not JSON, nested too deep, holding NaN or an infinity, or an integer beyond a float's range is a ValueError
    ``"<label>: ..."``. Its structure is the caller's to check (by the keys it reads)."""
    return json_document(file_text(path, label, limit), label)


def notebook_markdown(path: Path, label: str) -> list[str]:
    """The text of every markdown cell of the notebook ``path`` (:func:`file_json`), in order; a document that is no
    notebook (not an object with a list ``cells`` of objects with a text ``cell_type`` and a ``source`` that is a
    string or a list of strings) is a ValueError ``"<label>: ..."`` naming what it lacks (fuzz 35b B3)."""
    nb = file_json(path, label)
    cells = nb.get("cells") if isinstance(nb, dict) else None
    if not isinstance(cells, list):
        raise ValueError(f"{label}: not a notebook (a JSON object with a list 'cells')")
    out = []
    for i, c in enumerate(cells):
        if not (isinstance(c, dict) and isinstance(c.get("cell_type"), str)):
            raise ValueError(f"{label}: cells[{i}] is not a notebook cell (an object with a text 'cell_type')")
        src = c.get("source", "")
        if isinstance(src, list) and all(isinstance(s, str) for s in src):
            src = "".join(src)
        elif not isinstance(src, str):
            raise ValueError(f"{label}: cells[{i}]['source'] is not text (a string or a list of strings)")
        if c["cell_type"] == "markdown":
            out.append(src)
    return out
