"""The JSON types of the book's serialisers (``to_dict`` of the ledger's records and evidence, and of exact comparisons)."""

from __future__ import annotations

from typing import Any, TypeAlias, Union

__all__ = ["JSONValue", "JSONObject"]

#: A value :func:`json.dumps` writes as is: null, a boolean, a number, a string, a list or an object of such values.
#: (The containers' items are JSON values too; the alias is not recursive so that ``typing.get_type_hints`` resolves it.)
JSONValue: TypeAlias = Union[None, bool, int, float, str, list[Any], dict[str, Any]]
#: A JSON object: what a ``to_dict`` serialiser returns (field name → JSON value).
JSONObject: TypeAlias = dict[str, JSONValue]
