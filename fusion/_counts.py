"""Counts, seeds, indices and sequences: the shared rules 9, 11, 12 and 13 of :mod:`fusion._validation`.

A count is an integer type whose ceiling depends on its kind, read from the argument's name
(:data:`COUNT_CEILINGS`); an array sized by a product of counts is checked against a memory budget
(:func:`allocation`). Every function is re-exported by :mod:`fusion._validation`, where the rules are
stated; this module holds them so that module stays cohesive.
"""

from __future__ import annotations

import itertools
import operator
import os
import re
from collections.abc import Callable, Iterable, Sequence

import numpy as np

from fusion._entries import NUMPY_INTEGERS
from fusion._limits import count_text, work
from fusion._shown import shown


def _complex_error(name: str) -> TypeError:
    return TypeError(f"{name} must be real, got complex values")


def _bool_error(name: str) -> TypeError:
    return TypeError(f"{name} must be numeric, got booleans (a mask is not a number)")


#: Ceiling of a count by its kind (rule 9), applied by :func:`count` unless the caller gives its own
#: ``maximum``. Sizes (runs, samples, particles, iterations, grid points, anything unnamed) stop at
#: ``10**7``: a float64 vector of 80 MB, a loop of ten million steps, 100 to 1,000 times the largest
#: default of the package (100,000 runs). A dimension (state size, sensors, nodes) stops at ``10**4``
#: (an n x n covariance of 800 MB); a wavelet decomposition level at 64 (``2**64`` samples); a
#: number of decimals or significant digits at 17 (all a float64 holds; ``10**decimals`` overflows
#: beyond 308); workers at 1024.
COUNT_CEILINGS: dict[str, int] = {
    "runs": 10**7,
    "samples": 10**7,
    "particles": 10**7,
    "iterations": 10**7,
    "grid": 10**7,
    "dimension": 10**4,
    "level": 64,
    "decimals": 17,
    "workers": 1024,
    "size": 10**7,
}
#: The kind of a count, from its argument's name (the last identifier in it: ``cfg['level']`` is a
#: level, ``ns[2]`` a size). First match wins; an unmatched name is a ``"size"``.
COUNT_KINDS: tuple[tuple[str, str], ...] = (
    ("decimals", r"decimals|digits|precision"),
    ("level", r"levels?|depth"),
    ("workers", r"workers|jobs|processes"),
    ("particles", r"(n_)?particles|population"),
    ("iterations", r"iterations|max_iter|evaluations|patience|epochs|generations"),
    ("runs", r"\w*runs|reps|replicates|trials|reseeds|repeats"),
    ("samples", r"(n_)?samples|\w*draws|n_steps|steps|length|snapshots|chunk|block|window|lookahead|past|last"
                r"|fault_from|n_all|n_initial|m0"),
    ("grid", r"n_grid|nodes|grid"),
    ("dimension", r"dim|d|n_sensors|sensors|n_components|components|n_states"),
)
_COUNT_KIND_RES = tuple((kind, re.compile(pattern)) for kind, pattern in COUNT_KINDS)
_LAST_IDENTIFIER = re.compile(r"[A-Za-z_][A-Za-z0-9_]*")
#: The largest ceiling of any kind (a count above it is refused whatever its kind).
MAX_COUNT = max(COUNT_CEILINGS.values())
#: Memory budget of one array sized by a product of counts, checked by :func:`allocation`
#: (``2**28`` float64: 2 GiB).
MAX_ELEMENTS = 2**28
#: ``maximum`` of :func:`count` meaning "the ceiling of the count's kind".
BY_KIND = -1


def count_kind(name: str) -> str:
    """The kind of a count (a key of :data:`COUNT_CEILINGS`) from its argument's name (rule 9).

    The last identifier of ``name`` is matched against :data:`COUNT_KINDS` (``"n_runs"`` and
    ``"scenarios['a'] runs"`` are runs, ``"cfg['level']"`` a level); an unmatched name is a ``"size"``.
    """
    ids = _LAST_IDENTIFIER.findall(name)
    last = ids[-1].lower() if ids else ""
    for kind, pattern in _COUNT_KIND_RES:
        if pattern.fullmatch(last):
            return kind
    return "size"


def count_ceiling(name: str) -> int:
    """The largest value :func:`count` accepts for a count named ``name`` (:data:`COUNT_CEILINGS`)."""
    return COUNT_CEILINGS[count_kind(name)]


def _integer(value: object, name: str) -> int:
    """``value`` as an int when it is an integer type (rule 13); TypeError naming ``name`` otherwise."""
    not_masked(value, name)   # a masked 0-d array or scalar: its value under the mask would be used
    if isinstance(value, (bool, np.bool_)) or value is None or isinstance(value, (str, bytes)):
        raise TypeError(f"{name} must be an integer, got {shown(value)}")
    if isinstance(value, (complex, np.complexfloating)):
        raise _complex_error(name)
    if isinstance(value, (np.timedelta64, np.datetime64)) or (isinstance(value, np.ndarray)
                                                              and value.dtype.kind in "mM"):
        raise TypeError(f"{name} must be an integer, got a date or duration {shown(value, 60)} (its value depends "
                        "on its unit)")
    try:
        return int(operator.index(value))  # int, numpy integers, 0-d integer arrays, __index__: a plain int
    except TypeError:
        pass
    except MemoryError:
        raise
    except Exception as exc:  # the argument's own exception (its __index__ raised): rule 15, named and chained
        raise TypeError(f"{name} could not be converted to an integer: it raised {type(exc).__name__}: "
                        f"{str(exc):.200}") from exc
    if isinstance(value, np.ndarray) and value.dtype.kind == "b":
        raise _bool_error(name)
    raise TypeError(f"{name} must be an integer (int or numpy integer), got {type(value).__name__} {shown(value, 40)}: "
                    "a count is never a float or a Decimal, even an integral one")


def count(value: int, name: str, minimum: int = 1, maximum: int | None = BY_KIND) -> int:
    """Return ``value`` as an int in [``minimum``, ``maximum``] (rules 9 and 13).

    A count is an integer type (rule 13): ``int``, a numpy integer or a 0-d integer array; a float,
    a :class:`~decimal.Decimal` or a :class:`~fractions.Fraction` is refused even when integral
    (``np.float64(100.0)``), and so is a ``bool``.

    Parameters
    ----------
    value : int
        The count.
    name : str
        Argument name used in error messages; it also gives the count's kind (:func:`count_kind`).
    minimum : int
        Smallest accepted value.
    maximum : int or None
        Largest accepted value. By default the ceiling of the count's kind
        (:data:`COUNT_CEILINGS`, rule 9: beyond it the count cannot be allocated or run in
        bounded time); ``None`` for no limit (seeds, indices checked against their data).

    Raises
    ------
    TypeError
        If ``value`` is not an integer type (a float, a Decimal, a string, ``None``, a bool, a
        complex number, ...).
    ValueError
        If ``value`` is out of range, naming the ceiling of its kind.
    """
    v = _integer(value, name)
    if v < minimum:
        want = "a positive integer" if minimum == 1 else f"an integer >= {minimum}"
        raise ValueError(f"{name} must be {want}, got {shown(value)}")
    if maximum == BY_KIND:
        kind = count_kind(name)
        ceiling = COUNT_CEILINGS[kind]
        if v > ceiling:
            raise ValueError(f"{name} = {shown(value)} is beyond the ceiling of a count of {kind} ({ceiling:,}; "
                             f"fusion._validation.COUNT_CEILINGS): it could not be allocated or run in bounded time")
    elif maximum is not None and v > maximum:
        raise ValueError(f"{name} must be at most {maximum}, got {shown(value)}")
    return v


#: The largest seed, ``2**256 - 1``: twice the 128 bits a :class:`numpy.random.SeedSequence` pools, so a larger
#: seed adds no randomness, while its cost grows with the square of its size (measured: 3.6 CPU-s for one
#: SeedSequence of a 10**6-bit seed, paid again by every child it spawns; 10 us a child up to 256 bits, 115 at
#: 4,096).
SEED_MAX = 2**256 - 1


def _seed_size(v: int, name: str) -> int:
    """``v`` when it is at most :data:`SEED_MAX`, a ValueError naming ``name`` otherwise (by its bit length: cheap
    whatever its size)."""
    if v > SEED_MAX:
        raise ValueError(f"{name} must be a seed of at most 256 bits (a SeedSequence pools 128; a larger seed adds no "
                         f"randomness and costs time with the square of its size), got one of {v.bit_length():,} bits")
    return v


def seed(value: int, name: str = "seed", span: int = 0) -> int:
    """Return ``value`` as a non-negative int seed of at most 256 bits, TypeError/ValueError naming ``name``.

    ``span``: a function that derives seeds up to ``seed + span`` from its seed (network ``j`` of a study run with
    ``seed + 10 + j``) passes the largest offset, so that a seed whose derived seeds would pass :data:`SEED_MAX` is
    refused at entry, naming the caller's argument, not after the first derived studies ran (fuzz 55 C1: 13 CPU-s of
    work, then a refusal of "seed ... of 257 bits"). Book seeds are small: no book call is changed.

    A seed is an integer (rule 11): a float, even an integral one such as ``3.0``, is refused with
    a :class:`TypeError` (``3.5`` would otherwise be truncated, and ``numpy`` refuses ``3.0``). A 0-d
    integer array is the integer it holds, as for a count (rule 13) and for :func:`numpy.random.default_rng`.
    A seed above :data:`SEED_MAX` (``2**256 - 1``) is refused before any generator is seeded (fuzz 54: a
    10**6-bit seed cost 3.6 CPU-s a SeedSequence, and every run's child again).
    """
    if isinstance(value, np.ndarray) and value.ndim == 0 and value.dtype.kind in "iu":
        value = value[()]  # a 0-d integer array: its numpy integer (a 0-d bool array is not: kind "b")
    if not isinstance(value, (int, np.integer)) or isinstance(value, (bool, np.bool_)):
        raise TypeError(f"{name} must be an integer seed, got {shown(value)}")
    v = _seed_size(count(value, name, minimum=0, maximum=None), name)
    if v > SEED_MAX - span:
        raise ValueError(f"{name} must be at most 2**256 - 1 - {span:,}: this function derives seeds up to {name} + "
                         f"{span:,}, each a seed of at most 256 bits (fusion._counts.SEED_MAX); got {name} = "
                         f"2**256 - 1 - {SEED_MAX - v:,}")
    return v


#: The most 32-bit words a :class:`numpy.random.SeedSequence` argument may hold in its entropy, and again in its
#: spawn key, and its largest pool (words): 8 words, the 256 bits of :data:`SEED_MAX`. Its cost is what it mixes
#: again at every spawn (measured on this machine, shared with other jobs, OPENBLAS_NUM_THREADS=1, min of 5: one
#: ``spawn(1)`` 5.5 us at a 256-bit entropy, 11 us with an 8-word spawn key too; 105 us at 4,096 bits, 3.3 ms at
#: 1,000 entries of 256 bits, and 10**6 bits ran 49.5 CPU-s in a tiny tracking run, fuzz 55 C2).
SEED_WORDS = 8


#: The most items (entries and nested sequences) :func:`_first_entries` visits to find an argument's first entries: a
#: SeedSequence of at most :data:`SEED_WORDS` words holds a few; more, without that many entries among them, is a
#: nesting of empty sequences numpy would walk again at every spawn.
SEED_ITEMS = 64


def _first_entries(items: object, name: str, what: str) -> list:
    """The first ``SEED_WORDS + 1`` entries of ``items`` in numpy's order (an int; a sequence or array of them, nested
    sequences and arrays flattened), read lazily: an entropy of 10**8 words is not converted whole (fuzz 57b D1: the
    former ``np.asarray(items, dtype=object).ravel()`` took 4.4 CPU-s to refuse ``np.arange(10**8)``)."""
    out: list = []
    stack = [iter((items,))]
    visited = 0
    while stack and len(out) <= SEED_WORDS:
        x = next(stack[-1], stack)   # the stack itself marks an exhausted level (it is never an entry)
        if x is stack:
            stack.pop()
            continue
        visited += 1
        if visited > SEED_ITEMS:
            raise ValueError(f"{name} must be a SeedSequence of at most {SEED_WORDS} 32-bit words of {what}, got "
                             f"more than {SEED_ITEMS} nested items in it (every spawn walks them again)")
        if isinstance(x, np.ndarray):
            # a subclass is refused: numpy mixes its data, not what its ``flat`` says (fuzz 58b C4: a one-word
            # ``flat`` hid 3e7 words, 52 CPU-s of spawning); a plain ndarray's ``flat`` walks its own data
            if type(x) is not np.ndarray:
                raise TypeError(f"{name} must be a SeedSequence whose arrays of {what} are plain numpy.ndarray, "
                                f"got a {type(x).__name__} (an ndarray subclass) in it")
            stack.append(iter(x.flat))   # numpy scalars, one at a time (no copy of the array)
        elif isinstance(x, Sequence) and not isinstance(x, (str, bytes)):
            # only an exact list, tuple or range (fuzz 59b C1: a list subclass whose ``__iter__`` gave this check one
            # word and numpy 10**6 at every spawn ran 15 CPU-s): numpy iterates the container again at every spawn
            if type(x) not in (list, tuple, range):
                raise TypeError(f"{name} must be a SeedSequence whose sequences of {what} are plain lists, tuples, "
                                f"ranges or numpy.ndarray, got a {type(x).__name__} in it (its iteration may report "
                                "other words than numpy mixes)")
            stack.append(iter(x))
        else:
            out.append(x)
    return out


def _words(items: object, name: str, what: str) -> int:
    """The 32-bit words SeedSequence makes of ``items`` (an int, or a sequence of ints: each entry at least one word),
    counted up to ``SEED_WORDS + 1`` from its first entries only, refusing an entry beyond :data:`SEED_MAX` by name
    (its bit length: cheap)."""
    entries = _first_entries(items, name, what)
    total = 0
    for k, e in enumerate(entries):
        if not isinstance(e, (int, np.integer)) or isinstance(e, (bool, np.bool_)):
            raise TypeError(f"{name} must be a SeedSequence of integer {what}, got {shown(e)} in it")
        if not (type(e) is int or type(e) is np.dtype(type(e)).type):
            # an int subclass's ``__int__`` (or a numpy integer subclass's) may report another number than numpy
            # reads (fuzz 59b C1's class): only a Python int or one of numpy's own integer scalar types
            raise TypeError(f"{name} must be a SeedSequence of Python int or numpy integer {what}, got a "
                            f"{type(e).__name__} (a subclass) in it")
        _seed_size(int(e), f"{name} {what}" + (f"[{k}]" if len(entries) > 1 else ""))
        total += max(1, -(-int(e).bit_length() // 32))
        if total > SEED_WORDS:
            break
    return total


#: The most children a SeedSequence argument may have spawned already: half of numpy's 32-bit spawn counter, whose
#: ``spawn`` past ``2**32 - 1`` never returns (fuzz 56 C1: ``n_children_spawned = 2**32 - 6`` ran 102 CPU-s, then a
#: MemoryError); a call spawns at most a few thousand more.
SPAWNED_MAX = 2**31


def seed_sequence(value: object, name: str = "seed") -> np.random.SeedSequence:
    """Return ``value`` when it is a :class:`numpy.random.SeedSequence` of bounded size, TypeError/ValueError naming
    ``name``: the rule of :func:`seed` for a seed given as a SeedSequence object (fuzz 55 C2).

    Its ``entropy`` (an int, or a sequence of ints) and its ``spawn_key`` hold at most :data:`SEED_WORDS` 32-bit words
    each (256 bits, each entry at most :data:`SEED_MAX`), and its ``pool_size`` at most :data:`SEED_WORDS`: every
    spawn mixes them again, so a larger one costs time at every spawn (``SeedSequence(1 << 10**6)`` ran 49.5 CPU-s in
    a tiny tracking run) and adds no randomness. Checked by bit lengths, before any spawn.

    Raises
    ------
    TypeError
        Not a SeedSequence itself (a subclass may report values other than those numpy mixes), or one whose entropy or
        spawn key holds a non-integer or an array that is not a plain ``numpy.ndarray`` (a subclass's ``flat`` may
        report other words than numpy mixes), a sequence other than an exact list, tuple or range (a subclass's
        ``__iter__`` may too, fuzz 59b C1), or an integer other than a Python int or a numpy integer scalar type.
    ValueError
        An entropy, spawn key or pool beyond the bound; more than :data:`SPAWNED_MAX` children spawned already.
    """
    if not isinstance(value, np.random.SeedSequence):
        raise TypeError(f"{name} must be a SeedSequence, got {type(value).__name__}")
    if type(value) is not np.random.SeedSequence:   # fuzz 56 C2: a subclass reported entropy 1, numpy mixed 10**6 bits
        raise TypeError(f"{name} must be a numpy.random.SeedSequence itself, not a subclass ({type(value).__name__}): "
                        "what it reports need not be what numpy mixes")
    if int(value.n_children_spawned) > SPAWNED_MAX:   # fuzz 56 C1: numpy's 32-bit counter; spawn never returns past it
        raise ValueError(f"{name} must be a SeedSequence that has spawned at most {SPAWNED_MAX:,} children (numpy "
                         f"counts them in 32 bits, and a spawn past 2**32 - 1 never returns), got "
                         f"{int(value.n_children_spawned):,}")
    for what, items in (("entropy", value.entropy), ("spawn_key", value.spawn_key)):
        n = _words(items, name, what)
        if n > SEED_WORDS:
            raise ValueError(f"{name} must be a SeedSequence of at most {SEED_WORDS} 32-bit words of {what} (256 "
                             f"bits, as a seed: every spawn mixes them again), got more than {SEED_WORDS}")
    if int(value.pool_size) > SEED_WORDS:
        raise ValueError(f"{name} must be a SeedSequence of a pool of at most {SEED_WORDS} words, got "
                         f"{int(value.pool_size):,} (every spawn mixes its entropy into it again)")
    return value


#: The bit generators a Generator argument may draw from: numpy's own five, each exactly its type. A Generator reads its
#: bit generator's C functions through the ``capsule`` attribute, once, when it is built; a Python override of
#: ``random_raw`` or ``state`` in a subclass of these has no effect on what the Generator draws (measured, numpy 2.4:
#: a PCG64 subclass overriding both draws PCG64's own numbers, digit for digit), but a subclass may override
#: ``capsule`` itself, and any object with a ``capsule`` and a ``lock`` is accepted by ``numpy.random.Generator``:
#: a capsule of a hand-made (ctypes) bit generator whose ``next_double`` returns NaN made ``random`` and ``uniform``
#: draw NaN and ``normal`` draw 0 (fuzz 57b C1 follow-up), and a bare ``numpy.random.BitGenerator`` subclass crashed
#: the interpreter (a segmentation fault) at its first draw.
BIT_GENERATORS = (np.random.PCG64, np.random.PCG64DXSM, np.random.MT19937, np.random.Philox, np.random.SFC64)


def as_rng(rng: object, name: str = "rng") -> np.random.Generator:
    """Check that ``rng`` is a :class:`numpy.random.Generator` itself over one of numpy's bit generators
    (:data:`BIT_GENERATORS`, each exactly its type), a TypeError naming ``name`` otherwise.

    A subclass is refused, as :func:`seed_sequence` refuses a SeedSequence subclass: its overridden methods are
    what the package would draw from (fuzz 57b C1: ``uniform``, ``normal`` or ``random`` returning NaN or 1e300 made
    ``gauss_markov_gap`` return NaN, ``systematic_resample`` a plausible wrong resample, ``weighted_em`` raise a raw
    IndexError). So is a bit generator other than numpy's own (a subclass may hand the Generator other C functions:
    NaN draws, or a crash).
    """
    if not isinstance(rng, np.random.Generator):
        raise TypeError(f"{name} must be a numpy.random.Generator, got {type(rng).__name__}")
    if type(rng) is not np.random.Generator:
        raise TypeError(f"{name} must be a numpy.random.Generator itself, not a subclass ({type(rng).__name__}): its "
                        "methods would be what the package draws from")
    if type(rng.bit_generator) not in BIT_GENERATORS:
        raise TypeError(f"{name} must be a numpy.random.Generator over one of numpy's bit generators (PCG64, "
                        f"PCG64DXSM, MT19937, Philox, SFC64, not a subclass), got one over "
                        f"{type(rng.bit_generator).__name__}")
    return rng


def as_rngs(rngs: object, name: str = "rngs", n: int | None = None) -> list[np.random.Generator]:
    """A list of generators, one per problem (rule 12): each entry is checked by :func:`as_rng`, naming it
    (``rngs[1]``).

    Any sequence (:func:`sequence`: a list, a tuple, a ``UserList``, ...). TypeError for a non-sequence or an
    entry that is not a Generator (a float seed, a subclass included); ValueError for an empty list, one of other than
    ``n`` entries, or one whose entries share a stream (one Generator object twice, or two Generators of one bit
    generator): problem ``b`` could not give what the single call gives with ``rngs[b]`` (fuzz 24a D3).
    """
    if isinstance(rngs, np.random.Generator):
        raise TypeError(f"{name} must be a list of numpy.random.Generator, got one Generator")
    rngs = sequence(rngs, name)
    if not rngs or (n is not None and len(rngs) != n):
        want = "a non-empty list" if n is None else f"a list of {n}"
        raise ValueError(f"{name} must be {want} generators (one per problem), got {len(rngs)}")
    seen: dict[int, int] = {}
    for i, r in enumerate(rngs):
        as_rng(r, f"{name}[{i}]")
        j = seen.setdefault(id(r.bit_generator), i)  # the same object, or two Generators of one bit generator
        if j != i:
            raise ValueError(f"{name}[{i}] draws from the same stream as {name}[{j}]: each problem needs its own "
                             "generator (its result is then what the single call gives with it), e.g. "
                             "np.random.SeedSequence(seed).spawn(n)")
    return list(rngs)


#: The integer types :func:`_plain_integers` checks in one pass (bool and timedelta64 are not among them): ``int`` and
#: every numpy integer type (``numpy.longlong`` included, fuzz 61b C1).
_PLAIN_INTEGERS = frozenset({int}) | NUMPY_INTEGERS


def _integer_array(value: object) -> np.ndarray | None:
    """``value``'s data as a plain 1-D ``numpy.ndarray`` when it is a 1-D ndarray of a plain integer dtype (its
    entries checked at once), else ``None``; a masked array is not one (it goes through :func:`sequence`, which
    refuses it: :func:`not_masked`).

    An ndarray subclass is viewed through the base class (``numpy.ndarray.view``, never its own ``view``), so that its
    ``ndim``, ``dtype``, ``min``, ``max`` and ``tolist`` are numpy's, reading its real data (fuzz 60b C2: a subclass
    whose ``min()`` and ``max()`` returned 0 passed the seed ``-5`` to numpy, whose raw ValueError named nothing).
    """
    if not isinstance(value, np.ndarray) or isinstance(value, np.ma.MaskedArray):
        return None
    arr = np.ndarray.view(value, np.ndarray)
    # by dtype kind, any size and byte order (fuzz 61b C1: a list of exact types missed numpy.longlong, whose
    # 10**7 seeds were checked one by one, 14.5-16 CPU-s before the caller's budget refused them)
    return arr if arr.ndim == 1 and arr.dtype.kind in "iu" else None


def _plain_integers(items: list | np.ndarray, minimum: int, maximum: int | None) -> tuple[list[int] | None, int]:
    """``(ints, 0)``: ``items`` as ints when every one is a plain integer type within [``minimum``, ``maximum``];
    else ``(None, start)``, the entry-by-entry rule to begin at ``start``.

    The fast path of :func:`counts` and :func:`seeds` (a sequence of 10**6 seeds is checked in milliseconds,
    so that a work budget counting its length refuses it at once): one pass over the types and the range;
    any other entry (a float, a bool, a non-integer object) leaves the entry-by-entry rule, which names the first bad
    entry. When every entry is a plain integer, ``start`` is the first one out of range (those before it are valid),
    found in one pass too (fuzz 61b: a 10**6-seed array or list whose last seed was -1 was checked one by one, 1.0-1.5
    CPU-s, before the refusal named it).
    """
    arr = _integer_array(items)
    if arr is None:
        types = set(map(type, items))
        if not types <= _PLAIN_INTEGERS:
            return None, 0
        ints = list(items) if types == {int} else list(map(int, items))
        if min(ints) >= minimum and (maximum is None or max(ints) <= maximum):
            return ints, 0
        return None, next(i for i, v in enumerate(ints) if v < minimum or (maximum is not None and v > maximum))
    # a 1-D integer ndarray (a subclass read as a plain one): its range in one vectorised pass
    outside = arr < minimum if maximum is None else (arr < minimum) | (arr > maximum)
    if outside.any():
        return None, int(np.argmax(outside))
    return arr.tolist(), 0


def counts(values: object, name: str, minimum: int = 1, maximum: int | None = BY_KIND) -> list[int]:
    """A non-empty sequence of counts (rule 12): each entry through :func:`count`, naming it (``ns[2]``).

    TypeError for a non-sequence or a non-integer entry (booleans, strings, nested lists included);
    ValueError for an empty sequence or an entry out of range.
    """
    arr = _integer_array(values)
    items = arr if arr is not None and _length(arr, name, None) else sequence(values, name)
    if not len(items):
        raise ValueError(f"{name} is empty")
    top = count_ceiling(f"{name}[0]") if maximum == BY_KIND else maximum
    fast, start = _plain_integers(items, minimum, top)
    if fast is not None:
        return fast
    return [count(v, f"{name}[{i}]", minimum, maximum) for i, v in enumerate(items[start:], start)]


def seeds(values: object, name: str = "seeds") -> list[int]:
    """A non-empty sequence of seeds: each entry an integer (rule 11), named (``seeds[1]``)."""
    arr = _integer_array(values)
    items = arr if arr is not None and _length(arr, name, None) else sequence(values, name)
    if not len(items):
        raise ValueError(f"{name} is empty")
    fast, start = _plain_integers(items, 0, SEED_MAX)
    if fast is not None:
        return fast
    return [seed(v, f"{name}[{i}]") for i, v in enumerate(items[start:], start)]


def seed_array(values: object, name: str = "seeds") -> np.ndarray:
    """:func:`seeds` as an array that holds each seed exactly: int64 when every seed fits, else dtype object of
    ints (fuzz 27a F3). ``np.array`` of a list mixing an int in [2**63, 2**64) with a small one is float64,
    which rounds the seed (2**63 + 1 would run the generator of 2**63); no seed is ever converted to float."""
    s = seeds(values, name)
    lo, hi = np.iinfo(np.int64).min, np.iinfo(np.int64).max
    if all(lo <= v <= hi for v in s):
        return np.array(s, dtype=np.int64)
    out = np.empty(len(s), dtype=object)
    out[:] = s
    return out


def _is_nan(v: object) -> bool:
    """``v`` a real or complex float NaN (not equal to itself)."""
    return isinstance(v, (float, complex, np.floating, np.complexfloating)) and v != v


def distinct(items: list, name: str) -> list:
    """``items`` when no two are equal (rule 12): a sequence whose entries key a result (seeds of a dict of
    cases, sizes of a table's rows, sensors that each receive one bias) refuses a duplicate, which would
    silently collapse two keys or add two values to one entry, with a ValueError naming ``name``.

    Returns
    -------
    list
        ``items`` unchanged.

    Raises
    ------
    ValueError
        If an entry occurs twice, naming it and its positions. Two NaN entries are repeated: a NaN key of a
        result cannot be looked up (``nan != nan``; pandas finds both rows of two NaN labels).
    """
    try:
        unique = set(items)
        if len(unique) == len(items) and not any(_is_nan(v) for v in unique):  # the usual case
            return items
    except TypeError:  # unhashable entries: compared one by one below
        pass
    repeat = _first_repeat([int(v) if isinstance(v, (int, np.integer)) else ("NaN",) if _is_nan(v) else v
                            for v in items])
    if repeat is not None:
        i, j, key = repeat
        raise ValueError(f"{name} must not repeat an entry: {name}[{i}] and {name}[{j}] are both "
                         f"{shown(items[j] if _is_nan(items[j]) else key)} (the results are keyed by its entries)")
    return items


def _first_repeat(keys: Iterable[object]) -> tuple[int, int, object] | None:
    """The positions of the first key equal to an earlier one, and that key; None when all differ."""
    first: dict = {}
    for j, key in enumerate(keys):
        if key in first:
            return first[key], j, key
        first[key] = j
    return None


def general(value: object) -> object:
    """``value`` as most result keys print it: a real number as ``f"{value:g}"`` (6 significant digits), a tuple
    entry by entry (``("strong direction", 3.0000001)`` prints as ``("strong direction", "3")``), anything else
    unchanged."""
    if isinstance(value, tuple):
        return tuple(general(v) for v in value)
    if isinstance(value, (int, float, np.integer, np.floating)) and not isinstance(value, (bool, np.bool_)):
        return f"{value:g}"
    return value


def glue_part(value: object) -> object:
    """``value`` as a glue key's part: :func:`general`'s ``f"{value:g}"`` without its point, its minus signs as ``m``
    and its plus signs dropped (0.25 -> ``025``, 10.5 -> ``105``, -1 -> ``m1``, 1e-05 -> ``1em05``), so that every
    glue key built from a caller's number is an identifier (a claim text's ``{name}``; fuzz 31b C1, C3, D4: the
    chapters printed it three ways, one without the point while its check kept it); a zero prints as ``0``, its sign
    dropped (-0.0 equals 0.0). The one printer of every glue
    key part and of the check that no two entries print alike (:func:`distinct_printed`); a tuple entry by entry,
    anything else unchanged."""
    if isinstance(value, tuple):
        return tuple(glue_part(v) for v in value)
    if isinstance(value, (float, np.floating)) and value == 0:
        value = abs(value)  # -0.0 is 0.0, and keys the same glue value as ``0`` (fuzz 34b D3)
    g = general(value)
    return g.replace(".", "").replace("-", "m").replace("+", "") if isinstance(g, str) and g is not value else g


def distinct_printed(items: list, name: str, printed: Callable[[object], object] = general,
                     what: str = "keys a result") -> list:
    """Distinct as printed (fuzz 30b B1-B5): :func:`distinct`'s rule for entries that key a result through a
    format (``f"{x:g}"``, ``round(x, 6)``; ``printed`` maps an entry to its key). Two entries that differ but print
    the same would share one key, the last silently replacing the other: a ValueError names ``name``, both
    positions and the shared key (``what`` says what each entry keys). Returns ``items`` unchanged; an exact repeat
    is refused by :func:`distinct` first.
    """
    distinct(items, name)
    repeat = _first_repeat(printed(v) for v in items)
    if repeat is not None:
        i, j, key = repeat
        raise ValueError(f"{name} must differ in how its entries print (each {what}, printed as {shown(key)}): "
                         f"{name}[{i}] and {name}[{j}] print the same")
    return items


def distinct_printed_as_read(items: Sequence, name: str, read: Callable[[object, int], object],
                             printed: Callable[[object], object] = general, what: str = "keys a result") -> list:
    """:func:`distinct_printed` as the entries are read: ``read(item, i)`` reads (checks) entry ``i``, and the first
    entry equal to an earlier one, or printing as one does, is refused at once, with :func:`distinct`'s or
    :func:`distinct_printed`'s message (an exact repeat named as such), before any later entry is read (fuzz 62a D1:
    2.2 million α were read and printed before a repeat of the first two was refused, 6.7 CPU-s). Returns the read
    entries."""
    out: list = []
    exact: dict = {}
    keys: dict = {}
    for j, item in enumerate(items):
        v = read(item, j)
        e = int(v) if isinstance(v, (int, np.integer)) else ("NaN",) if _is_nan(v) else v
        try:
            i = exact.get(e)
        except TypeError:  # unhashable: left to printed's key
            i = None
        if i is not None:
            raise ValueError(f"{name} must not repeat an entry: {name}[{i}] and {name}[{j}] are both "
                             f"{shown(v if _is_nan(v) else e)} (the results are keyed by its entries)")
        key = printed(v)
        if key in keys:
            raise ValueError(f"{name} must differ in how its entries print (each {what}, printed as {shown(key)}): "
                             f"{name}[{keys[key]}] and {name}[{j}] print the same")
        try:
            exact.setdefault(e, j)
        except TypeError:
            pass
        keys[key] = j
        out.append(v)
    return out


def allocation(shape: tuple[int, ...], names: str, arrays: int = 1) -> None:
    """Refuse arrays of ``shape`` that cannot be allocated (rule 9), naming the arguments setting their size.

    The memory budget is :data:`MAX_ELEMENTS` float64 (2 GiB): a function whose arrays grow as a
    product of counts (runs x particles x steps) calls this at its entry with that product's shape, and with
    ``arrays``, the arrays of that shape its work holds at once (a product and the temporary of the next operation
    on it: fuzz 39a D2, ``is_objective`` held two 1.8 GiB arrays at once when each alone was checked), measured
    (``tracemalloc``'s peak over one array's bytes, rounded up: 2.05 is 3) and stated at the call.

    Raises
    ------
    ValueError
        If the ``arrays`` arrays would have more than :data:`MAX_ELEMENTS` elements together.
    """
    if arrays == 1:
        _beyond(shape, names, MAX_ELEMENTS, f"the memory budget (at most {MAX_ELEMENTS:,} float64, 2 GiB)")
    else:
        _beyond((arrays, *shape), names, MAX_ELEMENTS, f"the memory budget (at most {MAX_ELEMENTS:,} float64, 2 GiB; "
                f"{int(arrays)} arrays of {' x '.join(str(int(d)) for d in shape)} held at once)")


def broadcast(shapes: Sequence[tuple[str, tuple[int, ...]]], arrays: int = 1, weight: float = 1) -> tuple[int, ...]:
    """The broadcast shape of validated array arguments, refused by name before any work (rules 9 and 17).

    Each argument is held to the input budget by its own shape, but arguments broadcast against each other make
    arrays of their broadcast shape: a column of ``10**5`` and a row of ``10**5`` entries make ``10**10`` (fuzz 57b
    C5: a raw ``MemoryError``). A function combining its arguments elementwise calls this once they are validated,
    with the arrays of the broadcast shape its work holds at once (:func:`allocation`) and the measured units of
    work of one broadcast element (``fusion._limits.work``), both stated at the call.

    Parameters
    ----------
    shapes : sequence of (str, tuple of int)
        Each argument's name and its validated array's shape.
    arrays : int
        The float64 arrays of the broadcast shape held at once (measured, rounded up).
    weight : float
        The units of work of one broadcast element (measured CPU time over 10 ns, rounded up).

    Returns
    -------
    tuple of int
        The broadcast shape.

    Raises
    ------
    ValueError
        If the shapes do not broadcast, or their broadcast is beyond the memory or the work budget, naming every
        argument.
    """
    names = [str(n) for n, _ in shapes]
    joined = names[0] if len(names) == 1 else ", ".join(names[:-1]) + " and " + names[-1]
    try:
        shape = np.broadcast_shapes(*(tuple(s) for _, s in shapes))
    except ValueError:
        given = ", ".join(str(tuple(int(d) for d in s)) for _, s in shapes)
        raise ValueError(f"{joined} must broadcast together, got shapes {given}") from None
    what = f"{joined} (broadcast together)"
    allocation(shape, what, arrays)
    work(shape, what, weight=weight)
    return shape


def _beyond(shape: tuple[int, ...], names: str, limit: int, budget: str) -> None:
    """Refuse an array of ``shape`` of more than ``limit`` elements, naming ``names`` and the ``budget``."""
    n = 1
    for s in shape:
        n *= int(s)
    if n > limit:
        dims = " x ".join(f"{int(d):.3g}" if int(d) > 10**6 else str(int(d)) for d in shape)
        raise ValueError(f"{names} ask for an array of {count_text(n)} elements ({dims}), beyond {budget}")


def input_allocation(shape: tuple[int, ...], names: str) -> None:
    """Refuse an array of ``shape`` that a validating callee would refuse as its input (fuzz 22b, class SW), naming
    the arguments setting its size: a function that builds such an array (samples of ``runs × r`` rows) and passes
    it to a function that checks its input against ``fusion._limits.MAX_INPUT_ELEMENTS`` calls this at its entry,
    as :func:`allocation` for the memory budget, so that the refusal names the caller's arguments, before any work.

    Raises
    ------
    ValueError
        If the array would have more than ``MAX_INPUT_ELEMENTS`` elements.
    """
    from fusion._limits import MAX_INPUT_ELEMENTS

    _beyond(shape, names, MAX_INPUT_ELEMENTS, "the input budget of the functions it is passed to (at most "
            f"{MAX_INPUT_ELEMENTS:,}, fusion._limits.MAX_INPUT_ELEMENTS)")


#: Units of work (rule 17) of one pair of readings in a pairwise kernel (:func:`pairwise`): its n x n terms pass
#: through about ten vectorised operations (a difference, an absolute value or a square, an exponential, masks and
#: row sums), measured at 20 to 250 ns a pair on this machine when loaded.
PAIR_WORK = 20


def pairwise(n: int, name: str, arrays: int = 1, rows: int = 1, cubic: bool = False, step: int = 0) -> int:
    """Refuse ``n`` readings whose pairwise kernel is beyond the memory or the work budget (rules 9 and 17).

    A kernel on the n readings of a row (the distances, fusion degrees, beliefs and supports of
    ``fusion.readings.fusion_set``) builds n x n pair terms: a long 1-D argument asks for an n x n array (10**5
    readings, 80 GB) and n**2 work. The caller declares its kernel, and a long argument is refused by name at
    once, never by a :class:`MemoryError` or minutes of work. The shared reading conversions call it
    (:func:`fusion._validation.as_readings` and :func:`fusion._validation.as_reading_rows` with ``pairs``).

    Parameters
    ----------
    n : int
        The readings of a row.
    name : str
        The argument holding them, named in the message.
    arrays : int
        The n x n float64 arrays the kernel holds at once (its memory per pair): checked against
        :data:`MAX_ELEMENTS`. A kernel computed in row blocks holds one row's pairs at a time once they outgrow a
        block; a kernel returning a stack of rows declares the rows times its arrays.
    rows : int
        The rows (epochs, or evaluations of the kernel) computed one after the other.
    cubic : bool
        The kernel also decomposes each row's n x n matrix (``numpy.linalg.eigh``: n**3 units a row).
    step : int
        The units of a row's own Python-level call on top of its pairs, for a kernel called once a row (its
        validation and dispatch: ``fusion.book.audit.parameters_matching`` calls a fusion a grid point, about 20 us
        measured, budget35); 0 for rows computed in one vectorised call.

    Returns
    -------
    int
        The units of work, ``rows * (step + n**2 * (PAIR_WORK + n if cubic else PAIR_WORK))``.

    Raises
    ------
    ValueError
        If the arrays exceed the memory budget or the work the work budget, naming ``name``.
    """
    what = f"{name} ({int(n):,} readings, a kernel of their n x n pairs)"
    allocation((arrays, n, n), what)
    per_pair = PAIR_WORK + (int(n) if cubic else 0)
    if step:
        return work((rows, int(step) + int(n) * int(n) * per_pair), what)
    return work((rows, n, n, per_pair), what)


def machine_workers() -> int:
    """The processes this machine can run at once: the CPUs this process may use (``os.sched_getaffinity``
    where it exists, else ``os.cpu_count()``; at least 1)."""
    try:
        n = len(os.sched_getaffinity(0))
    except (AttributeError, OSError):
        n = os.cpu_count() or 1
    return max(1, n)


def workers(value: int, name: str = "workers") -> int:
    """A number of worker processes (rule 9): a count, capped at :func:`machine_workers`.

    A function taking ``workers`` gives the same result whatever its value (each worker computes
    what the calling process would), so a request for more processes than the machine has CPUs is
    served with as many as it has, never by forking them all (``workers=1000`` on a 2-CPU machine
    would start 1,000 processes). The type and the ceiling of a count still apply (:func:`count`).

    Raises
    ------
    TypeError
        Not an integer type.
    ValueError
        Below 1 or beyond the ceiling of a count of workers (:data:`COUNT_CEILINGS`).
    """
    return min(count(value, name), machine_workers())


def grid_points(span: float, step: float, names: str, kind: str = "samples") -> int:
    """The number of points of a regular grid of ``step`` over ``span``, checked before it is allocated (rule 9).

    A grid built from scalars (``np.arange(0, duration, T)``) has ``span / step + 1`` points: a
    valid duration over a valid but tiny period asks for more than numpy can allocate (numpy's own
    refusal, ``Maximum allowed size exceeded``, names nothing). This counts the points first and
    refuses, naming the arguments, a grid above the ceiling of ``kind`` (:data:`COUNT_CEILINGS`).

    Parameters
    ----------
    span : float
        Length covered by the grid (``end - start``), >= 0.
    step : float
        Grid step, > 0.
    names : str
        The arguments setting the span and the step (``"duration and T"``), named in the message.
    kind : str
        The kind of count whose ceiling applies.

    Returns
    -------
    int
        The number of points, ``floor(span / step) + 1``.

    Raises
    ------
    ValueError
        If the grid would hold more points than the ceiling.
    """
    ceiling = COUNT_CEILINGS[kind]
    ratio = span / step if step > 0 else float("inf")
    if not ratio <= ceiling:  # NaN and inf included
        raise ValueError(f"{names} ask for a grid of {ratio:.3g} points (span {span:.3g} over step {step:.3g}), "
                         f"beyond the ceiling of {ceiling:,} {kind}")
    return int(ratio) + 1


def index(value: int, name: str, length: int) -> int:
    """Return ``value`` as an index into a sequence of ``length`` items (negative indices refused).

    Raises
    ------
    TypeError
        If ``value`` is not an integer.
    ValueError
        If it is outside ``0 .. length - 1``.
    """
    v = count(value, name, minimum=0, maximum=None)
    if v >= length:
        raise ValueError(f"{name} must be an index below {length}, got {shown(value)}")
    return v


def _length(value: object, name: str, length: int | None) -> int:
    """``len(value)``, checked against ``length`` and :data:`MAX_COUNT` before any item is copied."""
    try:
        n = len(value)  # type: ignore[arg-type]
    except OverflowError:  # range(10**20): beyond sys.maxsize
        n = MAX_COUNT + 1
    except MemoryError:
        raise
    except Exception as exc:  # the argument's own exception (its __len__ raised): rule 15, named and chained
        raise TypeError(f"{name} has no length: it raised {type(exc).__name__}: {str(exc):.200}") from exc
    if length is not None and n != length:
        raise ValueError(f"{name} must have {length} items, got {n}")
    if n > MAX_COUNT:
        raise ValueError(f"{name} has {n} items, beyond the ceiling of {MAX_COUNT} (rule 9: the items of a "
                         "sequence argument are a size)")
    return n


def not_masked(value: object, name: str) -> None:
    """Refuse a masked array with a TypeError naming ``name``: its mask would be dropped and the values under it used
    (the one rule of :func:`sequence` and of the validated arrays, ``fusion._validation``)."""
    if isinstance(value, np.ma.MaskedArray):
        raise TypeError(f"{name} must be a plain array, got a masked array (its mask would be ignored: fill or "
                        "compress it first)")


def sequence(value: object, name: str, length: int | None = None, *, minimum: int = 0, what: str = "items") -> list:
    """A sequence argument (issue 35, class 6): a list, tuple or 1-D array, not a string, a dict or a number.

    One rule for what counts as a sequence: a :class:`list`, :class:`tuple` or :class:`range`, any other
    :class:`collections.abc.Sequence` (``array.array``, ``memoryview``) that is not text, and anything
    :func:`numpy.asarray` turns into a 1-D array (an ndarray, a pandas Series, an object with only
    ``__array__``). Refused with a :class:`TypeError` naming the argument: strings, dicts, numbers,
    ``None``, and unordered or one-pass iterables: dict views (``d.values()``), sets, iterators and
    generators (which ``numpy.asarray`` would wrap as a 0-d object array). Every argument documented as a
    "sequence" or a "list" takes any of these (a ``UserList`` included); a field documented as a "tuple" of
    a frozen record (``Evidence.expect``, ``NetworkScenario.nodes``) takes a tuple only, which keeps the
    record hashable.

    Returns
    -------
    list
        Its items.

    ``minimum`` items at least (issue 35, fuzz 18): a sequence that lists the rows of a table, the members of a
    conjunction or the cells of a grid refuses fewer (an empty one) by name, ``"levels must hold at least 1 level,
    got 0"`` (``what`` names the items), before a library's KeyError or an empty concatenation.

    Its ``len()`` is checked (against ``length`` and :data:`MAX_COUNT`) before any item is copied,
    and a sequence whose ``__len__`` disagrees with its items is refused, without iterating more
    than one item past its stated length.

    Raises
    ------
    TypeError
        Not a sequence.
    ValueError
        Not of ``length`` items (when given), fewer than ``minimum`` or more than :data:`MAX_COUNT` items,
        or a ``len()`` that disagrees with the items.
    """
    if isinstance(value, (list, tuple, range)) or (isinstance(value, Sequence)
                                                   and not isinstance(value, (str, bytes, bytearray))):
        n = _length(value, name, length)
        if type(value) in (list, tuple, range):
            items = list(value)  # an exact list, tuple or range: an honest len(), at most MAX_COUNT items
        else:  # any other Sequence, a list or tuple subclass included (its own __len__ or __iter__ may lie, fuzz 59a
            # C4: an endless __iter__ ran 4.7 CPU-s to a MemoryError), read at most len() + 1 items and compared
            try:
                items = list(itertools.islice(iter(value), n + 1))
            except MemoryError:
                raise
            except Exception as exc:  # the argument's own exception (its __getitem__ raised): rule 15
                raise TypeError(f"{name} could not be iterated: it raised {type(exc).__name__}: "
                                f"{str(exc):.200}") from exc
            if len(items) != n:
                raise ValueError(f"{name} has len() {n} but {'more' if len(items) > n else len(items)} items")
    elif hasattr(value, "__array__") or hasattr(value, "__array_interface__"):
        not_masked(value, name)   # its items would be the masked constant or the values under the mask
        try:
            arr = np.asarray(value)
        except MemoryError:
            raise
        except Exception as exc:  # the argument's own exception (its __array__ raised): rule 15, named and chained
            raise TypeError(f"{name} could not be converted to a sequence: it raised {type(exc).__name__}: "
                            f"{str(exc):.200}") from exc
        if arr.ndim != 1:
            raise TypeError(f"{name} must be a sequence (1-D), got {type(value).__name__} of shape {arr.shape}")
        _length(arr, name, length)
        # the items of ``arr``, the plain array whose length was checked: an ndarray subclass is read through it,
        # never through its own ``__iter__`` (fuzz 60b C1: an endless one ran 4.4-5.4 CPU-s to a MemoryError)
        items = list(arr)
    else:
        raise TypeError(f"{name} must be a sequence (a list, tuple or 1-D array), got {type(value).__name__}")
    if len(items) < minimum:
        raise ValueError(f"{name} must hold at least {minimum} {what}, got {len(items)}")
    return items


def iterable(value: object, name: str, limit: int | None = None, why: str = "") -> list:
    """An argument documented as an *iterable* (issue 35, class 6): its items, in iteration order.

    Wider than :func:`sequence`, for an argument whose order does not matter (a collection of values to avoid):
    any sequence :func:`sequence` takes, and a set, a frozenset, a mapping (its keys), a dict view, an iterator or a
    generator. Text (``str``, ``bytes``) is refused as a whole, not read character by character; so is anything that
    is not iterable. A one-pass iterable is read once, at most ``limit`` + 1 items (an endless generator is
    refused, not iterated for ever, and the items held stay bounded).

    Parameters
    ----------
    value : iterable
        The argument.
    name : str
        Its name, named in the messages.
    limit : int, optional
        The most items accepted: :data:`MAX_COUNT` (rule 9) by default; a caller whose work budget accepts fewer
        (``MAX_WORK`` // the units of an item) passes that count, so that no more than it + 1 items are read.
    why : str
        The reason of ``limit``, stated in the message (default rule 9's).

    Raises
    ------
    TypeError
        Text or not an iterable; or the iteration itself raised (its exception named and chained).
    ValueError
        More than ``limit`` items.
    """
    if limit is None:
        limit, why = MAX_COUNT, "rule 9: the items of an iterable argument are a size"
    if isinstance(value, (list, tuple, range, np.ndarray)) or hasattr(value, "__array__"):
        return sequence(value, name)
    if isinstance(value, (str, bytes, bytearray)) or not isinstance(value, Iterable):
        raise TypeError(f"{name} must be an iterable (a list, set, tuple, generator, ...), got {type(value).__name__}")
    try:
        items = list(itertools.islice(iter(value), limit + 1))
    except MemoryError:
        raise
    except Exception as exc:  # the argument's own exception: rule 15, named and chained
        raise TypeError(f"{name} could not be iterated: it raised {type(exc).__name__}: {str(exc):.200}") from exc
    if len(items) > limit:
        raise ValueError(f"{name} has more than {limit} items ({why})")
    return items
