"""The JSON types of the book's serialisers (``to_dict`` of the ledger's records and evidence, and of exact comparisons)."""

from __future__ import annotations

from typing import TypeAlias

__all__ = ["JSONValue", "JSONObject"]

#: A value :func:`json.dumps` writes as is: null, a boolean, a number, a string, a list or an object of such values.
JSONValue: TypeAlias = "None | bool | int | float | str | list[JSONValue] | dict[str, JSONValue]"
#: A JSON object: what a ``to_dict`` serialiser returns (field name → JSON value).
JSONObject: TypeAlias = "dict[str, JSONValue]"
