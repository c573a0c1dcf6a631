"""Public names of the split packages: an object re-exported by a package is named by the package."""

from __future__ import annotations

import typing
from collections.abc import MutableMapping


def resolve_annotations(cls: type) -> None:
    """Replace a class's own string annotations by the objects they name, evaluated in its defining module.

    Call it before renaming ``__module__``: :func:`typing.get_type_hints` evaluates a class's string annotations in
    the module its ``__module__`` names, which after :func:`name_by_package` is the package, where the defining
    module's names (``np``, ``FloatArray``, ...) are not. A class whose annotations name something its module does not
    hold at run time is left unchanged.

    Parameters
    ----------
    cls : type
        A class, still named by its defining module.
    """
    own = cls.__dict__.get("__annotations__")
    if not own:
        return
    try:
        hints = typing.get_type_hints(cls, include_extras=True)
    except NameError:
        return
    cls.__annotations__ = {k: hints[k] for k in own}


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
            if isinstance(obj, type):
                resolve_annotations(obj)
            obj.__module__ = package  # type: ignore[attr-defined]
