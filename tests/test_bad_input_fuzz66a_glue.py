"""Fuzz 66a's findings on ``glue_all``'s work budget, fixed by fix74c: C1 (a type's attributes were rescanned for
each value by ``_own_text``, unweighed), C2 (an instance's attributes were rescanned for each entry, unweighed), C5
(a container held by a container was charged 0 units of its own: 400,000 empty Series in a list ran 37.1 CPU-s)."""

import numpy as np
import pandas as pd
import pytest

from _helpers import glued, refused_quickly


def _many_attributes(n: int) -> type:
    """An int subclass adding ``n`` plain class attributes (no text method, no override: a valid atom)."""
    return type("X", (int,), {f"a{i}": i for i in range(n)})


def test_c1_a_type_is_scanned_once_a_call_and_weighed(monkeypatch: pytest.MonkeyPatch) -> None:
    """C1: 400 values of one int subclass of 10**5 class attributes ran 27.4 CPU-s; the class is now scanned once a
    call, charged ``GLUE_ATTR`` an attribute of its ``__dict__``: both bounds of the budget, exact."""
    from fusion.book import glue as G
    from fusion.book._glue_meter import GLUE_ATTR
    X = _many_attributes(100_000)
    values = {f"k{i}": X(1) for i in range(400)}
    scan = len(X.__dict__) * GLUE_ATTR
    need = 400 * G._GLUE_VALUE + scan   # the values, then one scan of the class
    got = glued(monkeypatch, values)    # within the budget: accepted, all glued
    assert len(got) == 400
    monkeypatch.setattr(G, "MAX_WORK", need)   # the meter's allowance: just inside
    glued(monkeypatch, values)
    monkeypatch.setattr(G, "MAX_WORK", need - 1)   # just outside: refused before the scan
    refused_quickly(lambda: G.glue_all(values), ValueError, r"^values\['k0'\] ask for more work.*10[0-9],[0-9]{3} "
                    r"attributes")


def test_c2_an_object_is_scanned_once_a_call_and_weighed(monkeypatch: pytest.MonkeyPatch) -> None:
    """C2: one int-subclass instance of 10**5 instance attributes, 400 times in a list, ran 30.5 CPU-s; the same
    object is now scanned once a call, its instance attributes weighed as a class's."""
    from fusion.book import glue as G
    from fusion.book._glue_meter import GLUE_ATTR

    class Y(int):
        pass

    y = Y(1)
    for i in range(100_000):
        setattr(y, f"a{i}", i)
    values = {"k": [y] * 400}
    need = G._GLUE_VALUE + G._glue_work(values["k"], "k") + (len(Y.__dict__) + len(y.__dict__)) * GLUE_ATTR
    monkeypatch.setattr(G, "MAX_WORK", need)
    assert glued(monkeypatch, values)["k"] == [1] * 400
    monkeypatch.setattr(G, "MAX_WORK", need - 1)
    refused_quickly(lambda: G.glue_all(values), ValueError, r"^values\['k'\] ask for more work")
    # distinct objects are each scanned: three at the price of three
    ys = [Y(1) for _ in range(3)]
    for z in ys:
        z.__dict__.update(y.__dict__)
    values = {"k": ys}
    need = G._GLUE_VALUE + G._glue_work(ys, "k") + (len(Y.__dict__) + 3 * len(y.__dict__)) * GLUE_ATTR
    monkeypatch.setattr(G, "MAX_WORK", need)
    glued(monkeypatch, values)
    monkeypatch.setattr(G, "MAX_WORK", need - 1)
    refused_quickly(lambda: G.glue_all(values), ValueError, r"^values\['k'\] ask for more work")


def test_c2_an_own_text_found_on_a_later_object_is_still_refused() -> None:
    """The memo is by object: another instance of a passed type defining a text method as an attribute is refused."""
    from fusion.book import glue as G

    class Y(int):
        pass

    a, b = Y(1), Y(2)
    b._repr_html_ = lambda: "nan"
    with pytest.raises(TypeError, match=r"values\['k'\] must hold atoms .*_repr_html_"):
        G.glue_all({"k": [a, a, b]})


def test_c5_a_container_held_by_a_value_is_weighed_by_its_kind() -> None:
    """C5: 400,000 distinct empty Series in a list were charged 300 units each (their walk ~80 us) and ran 37.1
    CPU-s; 10**6 empty lists 11.4. A container held is now weighed by its kind (``_HOLDER_UNITS``) with its holder:
    both bounds of the budget, the outside one refused before any is walked."""
    from fusion._limits import MAX_WORK
    from fusion.book import glue as G
    for make, weight in ((list, 2_000), (lambda: np.zeros(0), 3_000), (lambda: pd.Series([], dtype=float), 20_000)):
        edge = (MAX_WORK - G._GLUE_VALUE) // weight
        inside = [make() for _ in range(edge)]
        assert G._GLUE_VALUE + G._glue_work(inside, "k") == G._GLUE_VALUE + edge * weight <= MAX_WORK   # accepted
        inside.append(make())
        refused_quickly(lambda: G.glue_all({"k": inside}), ValueError, r"^values\['k'\] \(list, entries weighed")
        del inside


def test_c5_a_container_held_inside_a_value_is_charged_where_it_is_reached() -> None:
    """C5 inside a value: a list of 60,000 distinct empty Series inside a list is refused by the meter where the
    inner list is reached (its Series weighed by kind), before they are walked; 100 are glued."""
    from fusion._limits import MAX_WORK
    from fusion.book import glue as G
    inner = [pd.Series([], dtype=float) for _ in range(100)]
    assert G._container_work(inner) == (100, 100 * 20_000)
    G.glue_all({"k": [inner]})
    inner = [pd.Series([], dtype=float) for _ in range(60_000)]
    assert 60_000 * 20_000 > MAX_WORK
    refused_quickly(lambda: G.glue_all({"k": [inner]}), ValueError, r"^values\['k'\] ask for more work")
