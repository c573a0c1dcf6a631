"""Text options, flags, option dicts and keywords: rules 6, 18 and 19 of :mod:`fusion._validation`.

Re-exported by ``fusion._validation`` (every public function imports them from there); kept apart because they
read no numbers: an option is matched by its text, a flag is a ``bool``, an options dict and ``**options`` are
checked against the keys their consumer takes.
"""

from __future__ import annotations

import re
import string
from collections.abc import Mapping

import numpy as np

from fusion._shown import shown

__all__: list[str] = []  # private module: nothing public


def _safe_repr(value: object, limit: int = 60) -> str:
    """``repr(value)`` cut to ``limit`` characters, or its type's name if its own ``__repr__`` raises."""
    try:
        return f"{value!r:.{limit}}"
    except Exception:  # noqa: BLE001 (the argument's own repr: any exception)
        return f"a {type(value).__name__}"


def options(value: object, name: str, allowed: tuple[str, ...] | set[str] | frozenset[str]) -> dict:
    """Check an options dict (rule 6): ``None`` (no options) or a dict whose keys are all in ``allowed``.

    Returns
    -------
    dict
        A copy (an empty dict for ``None``).

    Raises
    ------
    TypeError
        If ``value`` is not a dict (or ``None``) or a key is not a string.
    ValueError
        If a key is unknown.
    """
    if value is None:
        return {}
    if not isinstance(value, Mapping):   # a dict, or a read-only one (a public constant, fusion._frozen.constant)
        raise TypeError(f"{name} must be a dict or None, got {type(value).__name__}")
    unknown = sorted(str(k) for k in value if k not in allowed)
    if unknown:
        raise ValueError(f"{name} has unknown keys {shown(unknown)}; allowed: {sorted(allowed)}")
    return dict(value)


def keywords(options: object, known: tuple[str, ...] | set[str] | frozenset[str], where: str) -> None:
    """Rule 6 for ``**options``: a keyword that no variant of ``where`` accepts (a misspelling) is a
    :class:`TypeError` naming it, as Python raises for an unexpected keyword argument of a plain signature; a
    known option that the chosen variant does not take stays the caller's :class:`ValueError`.

    Raises
    ------
    TypeError
        Naming the unexpected keywords (cut to :data:`MAX_SHOWN` characters) and the known ones.
    """
    unexpected = sorted(str(k) for k in options if k not in known)  # type: ignore[union-attr]
    if unexpected:
        raise TypeError(f"{where} got unexpected keyword argument(s) {shown(unexpected)}; known options: "
                        f"{sorted(known)}")


def flag(value: object, name: str) -> bool:
    """``value`` as a ``bool`` when it is one (``bool`` or ``numpy.bool_``): rule 18.

    Raises
    ------
    TypeError
        Any other type (a string such as ``'False'``, ``None``, an int 0/1), naming ``name``.
    """
    if not isinstance(value, (bool, np.bool_)):
        raise TypeError(f"{name} must be True or False (a bool), got {type(value).__name__} {_safe_repr(value, 40)}")
    return bool(value)


def text(value: object, name: str) -> str:
    """``value`` as a plain ``str`` when it is a string (a text option, a name, a template): one rule for every
    text argument (rule 19).

    A ``str`` subclass is its text: the plain copy ``str.__str__(value)`` is returned. A subclass whose own ``==``
    or ``hash`` raises or disagrees with its text is refused, since a caller that matches the argument afterwards
    would use those methods.

    Raises
    ------
    TypeError
        Any other type (bytes, a path, a number, None), or a ``str`` subclass whose own comparison or hash disagrees
        with its text, naming ``name``.
    """
    if not isinstance(value, str):
        raise TypeError(f"{name} must be a string, got {type(value).__name__}")
    return _plain_text(value, name)


#: A standard format spec, ``[[fill]align][sign][z][#][0][width][grouping][.precision][type]`` (width and precision
#: captured): the one a template's replacement field may hold (rule 19, :func:`template`).
_FORMAT_SPEC = re.compile(r"(?:.?[<>=^])?[-+ ]?z?#?0?(?P<width>[0-9]*)[_,]?(?:\.(?P<precision>[0-9]+))?[a-zA-Z%]?",
                          re.DOTALL)

#: The largest width and precision a template's field may ask for (characters of a padded label, digits of a
#: number): two digits, a table cell's label and not a gigabyte of padding.
MAX_TEMPLATE_WIDTH = 99


def template(value: object, name: str, *args: object, **kwargs: object) -> str:
    """``value`` as a plain ``str`` when it is a :meth:`str.format` template that formats ``args`` and ``kwargs``
    (the values its caller fills in, or probes of their types): one rule for every template argument (rule 19).

    Every field must name one of the values (``{}``, ``{0}``, ... for ``args``, ``{key}`` for ``kwargs``; no
    attribute or index access), and its format spec must be a standard one without a nested field, its width and
    precision at most :data:`MAX_TEMPLATE_WIDTH` (``{:>12}`` pads a label to 12 characters; a width of ``10**9``
    padded one label to a gigabyte); a conversion (``!r``) is allowed. A template may hold no field at all (literal text); the caller checks how many it needs.

    Returns
    -------
    str
        Its text (rule 19's :func:`text`).

    Raises
    ------
    TypeError
        ``value`` is not a string (rule 19's :func:`text`).
    ValueError
        Its braces do not parse (a single ``{``), a field names no value, holds a nested field, a width or a
        precision above :data:`MAX_TEMPLATE_WIDTH`, or formatting the values fails; naming ``name``.
    """
    value = text(value, name)
    allowed = {"", *map(str, range(len(args))), *kwargs}
    try:
        parsed = [(f, spec) for _, f, spec, _ in string.Formatter().parse(value) if f is not None]
    except ValueError as exc:
        raise ValueError(f"{name} = {shown(value)} is not a format template: {exc}") from None
    for f, spec in parsed:
        where = f"{name} = {shown(value)}: the field {{{f}}}"
        if f not in allowed:
            fields = ", ".join("{" + a + "}" for a in sorted(allowed if args else allowed - {""})) or "no field"
            raise ValueError(f"{where} names no value; it may hold only {fields}")
        m = _FORMAT_SPEC.fullmatch(spec or "")
        if m is None or "{" in (spec or ""):
            raise ValueError(f"{where} has the format spec {shown(spec)}, not a plain one (no nested field)")
        for part in ("width", "precision"):
            if m[part] and int(m[part]) > MAX_TEMPLATE_WIDTH:
                raise ValueError(f"{where} has the {part} {m[part]} > {MAX_TEMPLATE_WIDTH} (the bound of a label)")
    try:
        value.format(*args, **kwargs)
    except (ValueError, IndexError, KeyError, TypeError, AttributeError) as exc:
        raise ValueError(f"{name} = {shown(value)} does not format its values: {type(exc).__name__}: {exc}") from None
    return value


def _plain_text(value: str, name: str) -> str:
    """The plain ``str`` copy of a string ``value`` (rule 19); TypeError naming ``name`` for a subclass whose own
    comparison or hash disagrees with its text."""
    if type(value) is str:
        return value
    plain = str.__str__(value)  # an exact str: its text
    try:
        agrees = (bool(value == plain) and not bool(value == plain + "\x00") and not bool(value != plain)
                  and hash(value) == hash(plain))
    except MemoryError:
        raise
    except Exception:  # noqa: BLE001 - the caller's own __eq__/__hash__: any exception means it does not agree
        agrees = False
    if not agrees:
        raise TypeError(f"{name} must be a plain string, got a {type(value).__name__} whose own comparison or hash "
                        f"disagrees with its text {shown(plain)}")
    return plain


def one_of(value: str, allowed: tuple[str, ...], name: str) -> str:
    """Check that a string option is one of ``allowed`` and return it as a plain ``str`` (rule 19).

    The option is matched by its text: a plain copy taken through ``str.__str__`` is compared with ``str``'s own
    equality, so that a ``str`` subclass (``numpy.str_``, a :class:`~enum.StrEnum` member) is the option its text
    names. A subclass whose own ``==`` or ``hash`` disagrees with its text (raises, or calls every string equal)
    would still be compared by its own methods wherever the caller matches the option afterwards, so it is refused
    with a :class:`TypeError` naming ``name`` instead of escaping from deep inside or picking a wrong branch.

    Raises
    ------
    TypeError
        ``value`` is not a string, or a ``str`` subclass whose own comparison disagrees with its text.
    ValueError
        Its text is not one of ``allowed``.
    """
    if not isinstance(value, str):
        raise TypeError(f"{name} must be a string, one of {allowed}, got {type(value).__name__}")
    plain = str.__str__(value)  # an exact str: its text, compared by str's own equality below
    if not any(str.__eq__(plain, a) for a in allowed):
        raise ValueError(f"{name} must be one of {allowed}, got {shown(value)}")
    return _plain_text(value, name)


def texts(value: object, name: str) -> tuple[str, ...]:
    """A tuple (or list) of texts as a tuple of plain ``str`` (rule 19): each entry read by :func:`text` under its
    path in the caller's argument (``name[0]``), so that a refused entry names the caller's argument.

    Raises
    ------
    TypeError
        ``value`` is a bare string (it would be split into characters) or not a tuple or list, or an entry is not a
        string or a ``str`` subclass whose own comparison disagrees with its text, naming ``name`` (and the entry).
    """
    if isinstance(value, str) or not isinstance(value, (tuple, list)):
        raise TypeError(f"{name} must be a tuple of str, got {type(value).__name__}")
    return tuple(text(v, f"{name}[{i}]") for i, v in enumerate(value))


def text_key(key: object, name: str) -> str:
    """A key of the mapping argument ``name`` that labels a result (a method's label, a rule's name) as its plain
    ``str`` (rule 19, :func:`text`): one rule for every such label (fuzz 33a C5: an int, ``None`` or NaN label was
    kept as given, or refused naming the result's field).

    Raises
    ------
    TypeError
        ``key`` is not a string, or a ``str`` subclass whose own comparison disagrees with its text, naming
        ``name``'s keys.
    """
    return text(key, f"{name} keys")


def text_fields(obj: object, *names: str, among: tuple[str, ...] | None = None) -> None:
    """Store in each field ``names`` of the frozen dataclass ``obj`` the plain ``str`` its text reads as (rule 19,
    :func:`text`; :func:`one_of` when the text must be ``among`` given options): a record keeps, compares and prints
    its texts, never the caller's ``str`` subclass (a ``(str, Enum)`` member formats as its name, ``'E.A'``)."""
    for n in names:
        value = getattr(obj, n)
        object.__setattr__(obj, n, text(value, n) if among is None else one_of(value, among, n))

