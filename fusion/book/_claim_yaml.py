"""The YAML loader of the claim files (``fusion.book.claims.load``): PyYAML's safe loader, refusing a repeated key, a key
that is not a text and an integer too long to read. Kept apart from ``fusion.book.claims`` (at the package's 1,000-line
limit)."""

from __future__ import annotations

from typing import Any

import yaml

from fusion._shown import shown

__all__: list[str] = []  # private module


class _UniqueKeyLoader(yaml.SafeLoader):
    """PyYAML's safe loader, refusing a key repeated in one mapping (the safe loader keeps the last silently)."""


def _unique_mapping(loader: _UniqueKeyLoader, node: yaml.MappingNode, deep: bool = False) -> dict[Any, Any]:
    seen: set[Any] = set()
    for key_node, _ in node.value:
        key = loader.construct_object(key_node, deep=deep)
        if not isinstance(key, str):  # a sequence, a number, null, a bool: every key of a claim file is a text
            raise yaml.constructor.ConstructorError(None, None, f"a key must be a text, got {shown(key)}",
                                                    key_node.start_mark)
        if key in seen:
            raise yaml.constructor.ConstructorError(None, None, f"repeated key {shown(key)}", key_node.start_mark)
        seen.add(key)
    return loader.construct_mapping(node, deep=deep)


_UniqueKeyLoader.add_constructor(yaml.resolver.BaseResolver.DEFAULT_MAPPING_TAG, _unique_mapping)


def _bounded_int(loader: _UniqueKeyLoader, node: yaml.ScalarNode) -> int:
    """PyYAML's integer, refused (with its place in the file) beyond Python's digit limit for str -> int."""
    try:
        return loader.construct_yaml_int(node)
    except ValueError as e:
        raise yaml.constructor.ConstructorError(None, None, f"an integer too long to read ({e})",
                                                node.start_mark) from None


_UniqueKeyLoader.add_constructor("tag:yaml.org,2002:int", _bounded_int)
