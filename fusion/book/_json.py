"""The JSON types of the book's serialisers (``to_dict`` of the ledger's records and evidence, and of exact comparisons)."""

from __future__ import annotations

from typing import ForwardRef, TypeAlias, Union

__all__ = ["JSONValue", "JSONObject"]

#: The alias itself inside its containers, bound to this module so that ``typing.get_type_hints`` resolves it from any
#: module (it stops, at the second level, at this reference instead of recursing).
_ITEM = ForwardRef("JSONValue", module=__name__)
#: A value :func:`json.dumps` writes as is: null, a boolean, a number, a string, a list or an object of such values
#: (recursively: the containers' items are JSON values too).
JSONValue: TypeAlias = Union[None, bool, int, float, str, list[_ITEM], dict[str, _ITEM]]
#: A JSON object: what a ``to_dict`` serialiser returns (field name → JSON value).
JSONObject: TypeAlias = dict[str, JSONValue]
