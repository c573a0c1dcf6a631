"""Fuzz 37a (main package and book layer; report /work/tmp/fuzz37a/report.md), the cases fixed or decided by fix40a.

* C1: ``study_cache`` / ``process_cache`` handed every caller the same array objects: a caller's ``r.shape = ...``,
  ``r.dtype = ...``, ``r.resize(...)`` or ``r.setflags(write=True)`` (the kept array owned its data) reached every
  later caller. Each caller now gets its own read-only array objects over the kept memory (an immutable ``bytes``).
* D2 (decided, fixed): ``inverse_variance_weights`` raised EVERY estimate to its floor (1e-12 x the row's mean), so one
  valid sensor of huge variance equalised the precise sensors' weights; the floor now applies where it is needed
  (an estimate that is not positive), and valid positive variances get the exact formula.
* D3 (decided, fixed): ``fuse_denoised(..., variance="running")`` on a constant residual gave weights from round-off
  (1e-21 estimates) that changed with the input's scale, while ``"batch"`` refused the same data. One rule: a
  variance estimate at or below the round-off of its own computation is zero (``variance_estimates``), and a sensor
  whose residual is constant over the signal is refused by ``"batch"``, ``"running"`` and ``"window"`` alike,
  naming the caller's signals.
* D1 (decided, fixed): a caller's matplotlib style (``plt.style.use("dark_background")``, a ``prop_cycle``) carried
  into ``new_figure()``, which promises the book's style, and ``audit_figure`` passed a black figure. The book's
  style is now whole (matplotlib's defaults plus the book's settings), applied by ``use_book_style`` at every
  ``new_figure``; ``audit_figure`` refuses a background or axis text colour that is not the style's.

Each case builds only what it needs (no registry import).
"""
from __future__ import annotations

import dataclasses
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from fusion.book import study_cache as sc


@dataclasses.dataclass(frozen=True)
class _Study:
    mse: np.ndarray
    label: str


def _array(n: int) -> np.ndarray:
    return np.array([1.0, 2.0, 3.0]) * n


def _dataclass(n: int) -> _Study:
    return _Study(mse=np.array([1.0, 2.0, 3.0]) * n, label="s")


def _mixed(n: int) -> dict[str, object]:
    return {"t": (np.array([1.0, 2.0, 3.0]) * n, "a"), "f": np.asfortranarray(np.eye(3)[:, :2] * n)}


_cached_array = sc.study_cache(4)(_array)          # module-level names: the disk serves them (fusion.book.study_cache)
_cached_dataclass = sc.study_cache(4)(_dataclass)
_cached_mixed = sc.study_cache(4)(_mixed)
_CACHED = {"array": (_cached_array, _array), "dataclass": (_cached_dataclass, _dataclass),
           "mixed": (_cached_mixed, _mixed)}


def _arrays_of(value: object) -> list[np.ndarray]:
    if isinstance(value, np.ndarray):
        return [value]
    if isinstance(value, _Study):
        return [value.mse]
    if isinstance(value, dict):
        return [a for v in value.values() for a in _arrays_of(v)]
    if isinstance(value, tuple):
        return [a for v in value for a in _arrays_of(v)]
    return []


def _shape(a: np.ndarray) -> None:
    a.shape = (a.size, 1)


def _dtype(a: np.ndarray) -> None:
    a.dtype = np.int64


def _write(a: np.ndarray) -> None:
    a.setflags(write=True)
    a.flat[0] = 99.0


def _resize(a: np.ndarray) -> None:
    a.resize(a.size + 5, refcheck=False)


_EDITS = {"shape": _shape, "dtype": _dtype, "setflags": _write, "resize": _resize}


def _same(a: object, b: object) -> bool:
    xs, ys = _arrays_of(a), _arrays_of(b)
    return len(xs) == len(ys) > 0 and all(x.dtype == y.dtype and x.shape == y.shape and x.strides == y.strides
                                          and np.array_equal(x, y) for x, y in zip(xs, ys))


@pytest.mark.parametrize("where", ["process", "disk", "process_cache"])
@pytest.mark.parametrize("kind", sorted(_CACHED))
@pytest.mark.parametrize("edit", sorted(_EDITS))
def test_c1_a_callers_change_of_an_array_object_never_reaches_a_later_call(
        edit: str, kind: str, where: str, tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    cached, fn = _CACHED[kind]
    if where == "disk":
        monkeypatch.setenv(sc.ENV, str(tmp_path))
    else:
        monkeypatch.delenv(sc.ENV, raising=False)
    if where == "process_cache":
        cached = sc.process_cache(4)(fn)
    cached.cache_clear()
    for _ in range(2 if where == "disk" else 1):   # through the disk: computed and stored, then loaded
        for got in (cached(2), cached(2)):         # the first caller's result too
            for a in _arrays_of(got):
                assert not a.flags.writeable
                try:
                    _EDITS[edit](a)
                except (ValueError, AttributeError, TypeError):
                    pass                           # refused: read-only memory that no array owns
            assert _same(cached(2), fn(2)), (edit, kind, where)
        cached.cache_clear()


def test_c1_one_computation_one_memory_and_the_callers_argument_untouched(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.delenv(sc.ENV, raising=False)
    _cached_array.cache_clear()
    one, two = _cached_array(3), _cached_array(3)
    assert one is not two and np.shares_memory(one, two)   # new objects, one copy of the data

    @sc.study_cache(2)
    def nested(n: int) -> tuple[np.ndarray, np.ndarray]:
        return _cached_array(n), np.zeros(2)

    assert np.shares_memory(nested(3)[0], one)             # a cached study inside another: not copied again
    mine = np.ones(3)
    ident = sc.study_cache(2)(lambda x: x)
    got = ident(mine)
    assert mine.flags.writeable and not np.shares_memory(got, mine)
    mine[0] = 5.0
    assert ident(np.ones(3)).tolist() == [1.0, 1.0, 1.0]


# ---------------------------------------------------------------- D2: the variance floor only where it is needed
@settings(max_examples=15, deadline=None, derandomize=True)
@given(st.lists(st.floats(-40.0, 40.0), min_size=2, max_size=6), st.sampled_from(["floor", "abs", "equal"]))
def test_d2_positive_variances_get_the_exact_inverse_variance_weights(exponents: list[float], guard: str) -> None:
    from fusion.readings.weighting import inverse_variance_weights
    v = 10.0 ** np.array(exponents)
    exact = (1.0 / v) / np.sum(1.0 / v)
    np.testing.assert_allclose(inverse_variance_weights(v, guard=guard), exact, rtol=1e-12, atol=0.0)


def test_d2_the_floor_still_guards_estimates_that_are_not_positive() -> None:
    from fusion.readings.weighting import cumulative_fusion, fuse_current, inverse_variance_weights
    assert fuse_current(np.array([[10.0, 11.0, 12.0, 10.5]]), np.array([1.0, 2.0, 4.0, 1e14]))[0] == \
        pytest.approx(74.0 / 7.0, rel=1e-12)                     # the report's call: 10.5714, not 11.0
    w = inverse_variance_weights(np.array([0.0, 1.0, 2.0]))      # documented: the zero gets almost all the weight
    assert w[0] > 1.0 - 1e-11 and w.sum() == pytest.approx(1.0)
    np.testing.assert_allclose(inverse_variance_weights(np.array([-1.0, 1.0, 2.0]), guard="abs"), [0.4, 0.4, 0.2])
    np.testing.assert_allclose(inverse_variance_weights(np.zeros(3)), [1 / 3] * 3)
    # cumulative_fusion's precision time weights use the same guarded estimates: a precise instant is not equalised
    x = np.array([[1.0, 1.0], [3.0, 3.0]])
    got = cumulative_fusion(x, np.array([[1.0, 1e14], [1e13, 1e13]]), time_weights="precision")[-1]
    tau = np.array([1.0 + 1e-14, 2e-13])
    assert got == pytest.approx((tau[0] * 1.0 + tau[1] * 3.0) / tau.sum(), rel=1e-12)


# ---------------------------------------------------------------- D3: one rule for a residual of zero variance
def _signals(scale: float) -> tuple[np.ndarray, np.ndarray]:
    t = np.linspace(0.0, 1.0, 64)
    X = scale * np.stack([2.0 + np.sin(2 * np.pi * t), 2.5 + np.cos(2 * np.pi * t), 3.0 + t])
    return X, X - 0.01 * scale          # a residual constant in value (its computed samples differ by round-off)


@pytest.mark.parametrize("scale", [1.0, 3.0, 7.0, 1e-3, 1e5])
def test_d3_a_constant_residual_is_refused_by_every_residual_reading(scale: float) -> None:
    from fusion.readings.wavelet import fuse_denoised, variance_estimates
    X, Y = _signals(scale)
    for variance in ("batch", "running", "window"):
        with pytest.raises(ValueError, match="X and Y must give every sensor a residual .* not constant"):
            fuse_denoised(X, Y, "max-raw", variance, 8)
        est = variance_estimates(X, Y, X.max(axis=-1), variance, 8)
        assert np.all(est == 0.0), variance        # round-off estimates are zero, at every scale
    w = fuse_denoised(X, Y, "max-raw", "measurement", 8).weights   # not a residual reading: unchanged, defined
    assert np.all(np.isfinite(w)) and w.sum() == pytest.approx(1.0)


def test_d3_valid_residuals_keep_their_weights_at_every_scale() -> None:
    from fusion.readings.wavelet import fuse_denoised
    X, Y = _signals(1.0)
    Y = Y + 0.003 * np.random.default_rng(3).standard_normal(Y.shape)
    for variance in ("batch", "running", "window"):
        w1 = fuse_denoised(X, Y, "max-raw", variance, 8).weight_path
        w7 = fuse_denoised(7.0 * X, 7.0 * Y, "max-raw", variance, 8).weight_path
        assert not np.allclose(w1[..., -1], 1 / 3) and np.allclose(w1, w7, rtol=1e-9), variance


# ---------------------------------------------------------------- D1: the book's figure style is whole
def _png(style_name: str | None) -> bytes:
    import io

    import matplotlib
    import matplotlib.pyplot as plt

    from fusion.book.style import color, new_figure
    with matplotlib.rc_context():          # the caller's global style is restored after the test
        if style_name is not None:
            plt.style.use(style_name)
        fig, ax = new_figure()
        ax.plot([0.0, 1.0, 2.0], [0.0, 1.0, 0.5], color=color("ci"), label="a")
        ax.plot([0.0, 1.0, 2.0], [1.0, 0.2, 0.7])
        ax.set_xlabel("x")
        buf = io.BytesIO()
        fig.savefig(buf, format="png")
        plt.close(fig)
    return buf.getvalue()


def test_d1_new_figure_draws_the_same_figure_whatever_the_callers_style() -> None:
    plain = _png(None)
    for name in ("dark_background", "ggplot"):
        assert _png(name) == plain, name


def test_d1_audit_figure_refuses_a_figure_drawn_in_another_style() -> None:
    import matplotlib
    import matplotlib.pyplot as plt

    from fusion.book.figures import FigureStyleError, audit_figure
    from fusion.book.style import color, new_figure
    with matplotlib.rc_context():
        plt.style.use("dark_background")
        fig, ax = plt.subplots(figsize=(7.0, 3.6))
        ax.plot([0.0, 1.0], [0.0, 1.0], color=color("ci"))
        with pytest.raises(FigureStyleError, match="background #000000 is not the book style's #ffffff"):
            audit_figure(fig)
        plt.close(fig)
        fig, ax = new_figure()                # the same drawing in the book's style passes
        ax.plot([0.0, 1.0], [0.0, 1.0], color=color("ci"))
        assert audit_figure(fig) == []
        plt.close(fig)
