"""The notebook scheduler of `make book` (tools/execute_notebooks.py): appendices after their chapter only, longest chain first."""
from __future__ import annotations

import importlib.util
from pathlib import Path

from hypothesis import given, settings
from hypothesis import strategies as st

ROOT = Path(__file__).resolve().parents[1]
_spec = importlib.util.spec_from_file_location("fusion_execute_notebooks", ROOT / "tools" / "execute_notebooks.py")
ex = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(ex)

NB = Path("/nb")


def _book(names: list[str]) -> list[Path]:
    return [NB / f"{n}.ipynb" for n in names]


def simulate(notebooks: list[Path], seconds: dict[str, float], cores: int) -> list[tuple[float, float, Path]]:
    """(start, end, notebook) of a run on ``cores`` cores that asks `next_notebook` whenever a core is free."""
    waiting, running, out, now = list(notebooks), {}, [], 0.0
    while waiting or running:
        while len(running) < cores and (nb := ex.next_notebook(waiting, set(running), seconds)):
            waiting.remove(nb)
            running[nb] = now
        nb = min(running, key=lambda k: (running[k] + seconds.get(k.name, 0.0), k.name))
        start = running.pop(nb)
        now = start + seconds.get(nb.name, 0.0)
        out.append((start, now, nb))
    return out


def test_chapter_of_pairs_an_appendix_with_its_chapter():
    assert ex.chapter_of(NB / "06_chernoff_fusion_appendix.ipynb") == NB / "06_chernoff_fusion.ipynb"
    assert ex.chapter_of(NB / "06_chernoff_fusion.ipynb") is None


def test_an_appendix_waits_for_its_chapter_not_for_the_others():
    ch6, ap6, ch1 = _book(["06", "06_appendix", "01"])
    seconds = {"06.ipynb": 100.0, "06_appendix.ipynb": 20.0, "01.ipynb": 5.0}
    assert ex.next_notebook([ap6], {ch6}, seconds) is None          # its chapter runs
    assert ex.next_notebook([ch6, ap6], set(), seconds) == ch6      # the longest chain first
    assert ex.next_notebook([ap6, ch1], {NB / "02.ipynb"}, seconds) == ap6   # another chapter running: no wait
    assert ex.next_notebook([ap6, ch1], set(), seconds) == ap6      # its chapter finished (or cached)


def test_the_chain_counts_the_appendix_still_ahead():
    a, a_app, b = _book(["a", "a_appendix", "b"])
    seconds = {"a.ipynb": 10.0, "a_appendix.ipynb": 50.0, "b.ipynb": 40.0}
    assert ex.next_notebook([a, a_app, b], set(), seconds) == a     # 60 ahead against 40
    assert ex.next_notebook([a, b], set(), seconds) == b            # appendix done: 10 against 40


@settings(max_examples=60, deadline=None)
@given(st.lists(st.tuples(st.floats(0.0, 100.0), st.one_of(st.none(), st.floats(0.0, 50.0))), min_size=1, max_size=8),
       st.integers(1, 3))
def test_every_notebook_runs_once_and_no_appendix_before_its_chapter_ends(chapters, cores):
    seconds, notebooks = {}, []
    for k, (own, appendix) in enumerate(chapters):
        notebooks.append(NB / f"{k:02d}.ipynb")
        seconds[f"{k:02d}.ipynb"] = own
        if appendix is not None:
            notebooks.append(NB / f"{k:02d}_appendix.ipynb")
            seconds[f"{k:02d}_appendix.ipynb"] = appendix
    runs = simulate(notebooks, seconds, cores)
    assert sorted(nb for _, _, nb in runs) == sorted(notebooks)
    end = {nb: e for _, e, nb in runs}
    for start, _, nb in runs:
        if (ch := ex.chapter_of(nb)) is not None:
            assert start >= end[ch]
    # list scheduling: never worse than twice the best possible (the total over the cores, or the longest chain)
    chain = max(seconds[f"{k:02d}.ipynb"] + seconds.get(f"{k:02d}_appendix.ipynb", 0.0) for k in range(len(chapters)))
    best = max(sum(seconds.values()) / cores, chain)
    assert max(end.values()) <= 2 * best + 1e-9
