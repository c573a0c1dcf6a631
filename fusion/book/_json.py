"""The JSON types of the book's serialisers (``to_dict`` of the ledger's records and evidence, and of exact comparisons),
and the one reader of its stored JSON files (``read_object``; ``read_argument`` for a file a caller names)."""

from __future__ import annotations

import os
from pathlib import Path
from typing import Any, ForwardRef, TypeAlias, Union

from fusion._paths import file_bytes, json_document

__all__ = ["JSONValue", "JSONObject"]

#: The alias itself inside its containers, bound to this module so that ``typing.get_type_hints`` resolves it from any
#: module (it stops, at the second level, at this reference instead of recursing).
_ITEM = ForwardRef("JSONValue", module=__name__)
#: A value :func:`json.dumps` writes as is: null, a boolean, a number, a string, a list or an object of such values
#: (recursively: the containers' items are JSON values too).
JSONValue: TypeAlias = Union[None, bool, int, float, str, list[_ITEM], dict[str, _ITEM]]
#: A JSON object: what a ``to_dict`` serialiser returns (field name → JSON value).
JSONObject: TypeAlias = dict[str, JSONValue]


def read_object(path: Path, what: str = "file") -> dict[str, Any]:
    """The JSON object stored in ``path`` (a ledger or benchmark result file), any malformation named with the file.

    One rule for the book's JSON files (issue 35, fuzz 21): a file that is not UTF-8, not JSON, nested beyond
    Python's recursion limit, holding ``NaN``, ``Infinity`` or a number that overflows to one (which :func:`json.dumps` writes but JSON does not
    define, and which the claim files refuse as ``.nan``), an integer beyond a float's range (fuzz 37b C4), or whose
    top level is not an object, is refused with a
    :class:`ValueError` naming the file, instead of a :class:`json.JSONDecodeError`, a :class:`TypeError` or a
    :class:`RecursionError` of the first reader.

    Parameters
    ----------
    path : pathlib.Path
        The file (the caller found its name: a folder or a dangling symlink of that name is refused).
    what : str
        What the file is, for the message (``"benchmark result"``, ``"ledger file"``).

    Returns
    -------
    dict
        The top-level object.

    Raises
    ------
    ValueError
        The file is not a readable file (a folder, a dangling symlink, no permission) or not a JSON object as
        above, naming ``path``.
    """
    # a regular file of at most MAX_FILE_BYTES (fuzz 34a C3, C4; a folder or a dangling symlink: fuzz 22a W)
    data = file_bytes(path, f"{what} {path}")
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError as exc:
        raise ValueError(f"{what} {path}: not UTF-8 text ({exc.reason} at byte {exc.start})") from exc
    record = json_document(text, f"{what} {path}")
    if not isinstance(record, dict):
        raise ValueError(f"{what} {path}: the top level must be a JSON object, got {type(record).__name__}")
    return record


def read_argument(value: object, name: str, what: str = "file") -> dict[str, Any]:
    """The JSON object of a file given as the argument ``name`` of a public function, refused by that name (issue 35,
    fuzz 21b class X).

    :func:`read_object`'s rule for the file's content, after the argument's: a path (str or ``os.PathLike``) to an
    existing regular file. Every refusal is a :class:`ValueError` (a :class:`TypeError` for a value that is no path)
    that starts with ``name``, instead of a :class:`FileNotFoundError`, an :class:`IsADirectoryError` or an
    unnamed :class:`json.JSONDecodeError`.

    Parameters
    ----------
    value : str or os.PathLike
        The argument.
    name : str
        Its name, for the messages.
    what : str
        What the file is (``"benchmark result"``, ``"notebook"``).

    Returns
    -------
    dict
        The file's top-level object.

    Raises
    ------
    TypeError
        ``value`` is not a str or an ``os.PathLike``.
    ValueError
        No such regular file, or its content refused by :func:`read_object`, naming ``name`` and the file.
    """
    if not isinstance(value, (str, os.PathLike)) or isinstance(os.fspath(value), bytes):
        raise TypeError(f"{name} must be a pathlib.Path or a str, got {type(value).__name__}")
    path = Path(value)
    if not path.is_file():
        raise ValueError(f"{name}: no {what} {path} ({'a directory' if path.is_dir() else 'no such file'})")
    try:
        return read_object(path, what)
    except ValueError as exc:
        raise ValueError(f"{name}: {exc}") from exc
