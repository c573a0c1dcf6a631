"""Public names of the split packages: an object re-exported by a package is named by the package."""

from __future__ import annotations

from collections.abc import MutableMapping


def name_by_package(namespace: MutableMapping[str, object]) -> None:
    """Set ``__module__`` of every object in the package's ``__all__`` defined in one of its submodules to the package.

    As numpy's ``set_module``: the API page, its back-links to the chapters and the bad-input registry name each
    public object by the package that exports it (``fusion.book.ledger.Claim``), as before the package was split
    into submodules.

    Parameters
    ----------
    namespace : mutable mapping
        The package's ``globals()``: its ``__name__``, ``__all__`` and the exported objects.
    """
    package = str(namespace["__name__"])
    for name in namespace["__all__"]:  # type: ignore[attr-defined]
        obj = namespace[name]
        if str(getattr(obj, "__module__", "")).startswith(package + "."):
            obj.__module__ = package  # type: ignore[attr-defined]
