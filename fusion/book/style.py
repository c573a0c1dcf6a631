"""One figure style for the whole book.

Every notebook calls :func:`use_book_style` once and takes colours from
:data:`METHOD_COLORS`, so that a method has the same colour in every chapter.
"""

from __future__ import annotations

import functools

import matplotlib as mpl
import matplotlib.pyplot as plt
from matplotlib.axes import Axes
from matplotlib.figure import Figure

from fusion._frozen import constant
from fusion._validation import count, instance_of, keywords
from fusion._validation import flag
from fusion._validation import shown
from fusion._validation import _plain_text, text
from fusion.book.tables import _SUPERSCRIPT

__all__ = ["METHOD_COLORS", "METHOD_LABELS", "METHOD_SHORT_LABELS", "METHOD_MARKERS", "METHOD_LINESTYLES",
           "FIGURE_LABELS", "LABEL_PATTERNS", "FIGURE_ALT", "use_book_style", "new_figure", "color", "method_style",
           "is_registered_label", "MAX_ALT_CHARS", "plain_math", "describe_figure", "set_figure_alt", "figure_alt", "png_description",
           "FIGURE_SIDE_RANGE_IN", "FIGURE_DPI_RANGE", "FIGURE_MAX_PIXELS"]

#: Colour of each method, used in every chapter.
METHOD_COLORS: dict[str, str] = constant({
    "optimal_fusion_set": "#0072B2",
    "mean": "#D55E00",
    "support_degree": "#009E73",
    "published": "#000000",
    "truth": "#777777",
    "bound": "#CC79A7",
    # chapter 01, fair study (Yang, Feng & Fan 2012): practitioners' baselines; the ablation dashed in ofs blue
    "uniform_set": "#0072B2",
    "median": "#E69F00",
    "trimmed_mean": "#56B4E9",
    "huber": "#CC79A7",
    "grubbs": "#F0E442",
    "inverse_variance": "#000000",
    "trimmed_mean_25": "#56B4E9",
    "biweight": "#009E73",
    "mad_reject": "#D55E00",
    # chapter 07, time registration (Shi, Suo & Ma 2023): method keys of fusion.scenarios.time_registration.RegMethod
    "reg_two_point": "#E69F00",
    "reg_improved": "#56B4E9",
    "reg_least_squares": "#CC79A7",
    "reg_three_point": "#009E73",
    "reg_kalman_predict": "#0072B2",
    "reg_kalman_two_point": "#D55E00",
    "reg_two_point_extrapolation": "#000000",
    "reg_causal_improved": "#56B4E9",
    "reg_qls_next": "#999999",
    "reg_rts_smoother": "#0072B2",
    "reg_cubic_spline": "#009E73",
    "reg_qls_causal": "#555555",
    "reg_three_point_extrapolation": "#F0E442",
    # chapter 06, Chernoff patent (issue 36): keys of fusion.scenarios.range_bearing.METHODS and
    # fusion.scenarios.fusion_networks.NETWORK_METHODS, colours as drawn there
    "local1": "#999999",
    "local2": "#999999",
    "local3": "#999999",
    "mean_of_local_means": "#E69F00",
    "naive_product": "#CC79A7",
    "ci_gaussian": "#009E73",
    "chernoff_uniform": "#56B4E9",
    "chernoff_pso": "#0072B2",
    "centralised_pf": "#000000",
    "exact_posterior": "#000000",
    # chapter 02, lecture notes (sections 2.1-2.7); Okabe-Ito, raw data in neutral grey
    "oracle": "#CC79A7",
    "awf_lecture": "#E69F00",
    "awf_centred": "#0072B2",
    "mean_of_means": "#009E73",
    "best_sensor": "#56B4E9",
    "check_awf": "#0072B2",
    "ls_learning": "#E69F00",
    "ls_corrected": "#0072B2",
    "gls": "#0072B2",
    "naive": "#D55E00",
    "raw": "#999999",
    "denoised": "#D55E00",
    "reconstructed": "#0072B2",
    "reconstructed_median": "#009E73",
    "sensor 1": "#0072B2",
    "sensor 2": "#D55E00",
    "sensor 3": "#009E73",
    "sensor 4": "#CC79A7",
    "X=0, no fault": "#0072B2",
    "X=0, fault": "#56B4E9",
    "X=900, no fault": "#D55E00",
    "X=900, fault": "#E69F00",
    # chapter 05, covariance intersection (Wang & Tang 2024): fusion architectures, keys of
    # fusion.scenarios.two_sensor.Architecture
    "arch_independent": "#0072B2",
    "arch_feedback": "#D55E00",
    "arch_feedback_common": "#009E73",
    "arch_centralised": "#000000",
    # chapter 05: weight searches and reference lines (distinct within every figure; Okabe-Ito)
    "floor": "#000000",
    "FOA (30 × 200)": "#D55E00",
    "exhaustive, 1001 points": "#0072B2",
    "scipy bounded Brent": "#009E73",
    "closed form": "#000000",
    # chapter 05 (Wang & Tang 2024): method keys of fusion.scenarios.two_sensor.StudyMethod (the colours of their labels)
    "ci_sensor_1": "#0072B2",
    "ci_sensor_2": "#D55E00",
    "ci_closed_form": "#E69F00",
    "ci_fruit_fly": "#D55E00",
    "ci_grid": "#0072B2",
    "split_ci": "#009E73",
    "convex_ml": "#56B4E9",
    "fuzzy_clustering": "#CC79A7",
    # chapter 05 (Wang & Tang 2024): the infrared + radar case, keys of fusion.scenarios.infrared_radar.IrMethod
    # (its rules share the StudyMethod keys above)
    "radar_alone": "#0072B2",
    "ir_alone": "#D55E00",
    # chapters 03 and 04, lecture notes §§2.5-2.7 (issue 18): new methods
    "reconstructed_fuse_first": "#CC79A7",
    "ls": "#999999",
    "ridge_plugin_known": "#0072B2",
    "ridge_plugin_est": "#56B4E9",
    "ridge_centralised": "#0072B2",
    "ridge_distributed": "#E69F00",
    "eigen": "#009E73",
    "sample_variance": "#009E73",
    "memory_growing": "#E69F00",
    "memory_forgetting": "#0072B2",
    "memory_window": "#56B4E9",
})

#: Display label of each method (and of the few other keys a table shows: benchmark classes, scenarios, marked "not
#: methods" below).
METHOD_LABELS: dict[str, str] = constant({
    "optimal_fusion_set": "optimal fusion set",
    "mean": "arithmetic mean",
    "support_degree": "support degree (ref. [11], rebuilt)",
    "published": "published",
    "truth": "true value",
    # chapter 01, fair study (Yang, Feng & Fan 2012)
    "uniform_set": "optimal set, equal weights",
    "median": "median",
    "trimmed_mean": "trimmed mean (10 %)",
    "huber": "Huber M-estimator",
    "grubbs": "Grubbs test + mean",
    "inverse_variance": "inverse-variance mean",
    "trimmed_mean_25": "trimmed mean (25 %)",
    "biweight": "Tukey biweight",
    "mad_reject": "median ± 3 MAD rejection + mean",
    # chapter 02, lecture notes (sections 2.1-2.7)
    "oracle": "oracle (true variances)",
    "awf_lecture": "AWF (lecture, floor)",
    "awf_centred": "AWF (centred)",
    "mean_of_means": "mean of means",
    "best_sensor": "best sensor",
    "check_awf": "check + AWF",
    "ls_learning": "learned (lecture)",
    "ls_corrected": "corrected learning",
    "gls": "GLS = LDLᵀ",
    "naive": "naive (correlation ignored)",
    "raw": "raw",
    "denoised": "denoised",
    "reconstructed": "reconstructed (max)",
    "reconstructed_median": "reconstructed (median)",
    # chapter 07, time registration (Shi, Suo & Ma 2023): method keys of fusion.scenarios.time_registration.RegMethod
    "reg_two_point": "two-point",
    "reg_least_squares": "least squares",
    "reg_three_point": "three-point",
    "reg_kalman_predict": "Kalman, predict (§3)",
    "reg_kalman_two_point": "Kalman + two-point",
    "reg_improved": "improved: Kalman + three-point (§4)",
    "reg_two_point_extrapolation": "two-point extrapolation",
    "reg_causal_improved": "causal improved: Kalman + three-point extrapolation",
    "reg_qls_next": "quadratic least squares (past + next sample)",
    "reg_qls_causal": "quadratic least squares (causal)",
    "reg_three_point_extrapolation": "three-point extrapolation",
    "reg_rts_smoother": "RTS smoother (whole record)",
    "reg_cubic_spline": "cubic spline (whole record)",
    "reg_fixed_lag": "fixed-lag smoother (next sample)",
    "reg_local_qls": "local quadratic least squares (last 4 + next sample)",
    # (rows of fusion.book.chapters.time_registration.fusion_table besides the methods)
    "reg_sensor_2_alone": "sensor 2 alone",
    "reg_fused_unregistered": "fused, unregistered (last sample)",
    # (not methods: the classes of fusion.book.chapters.time_registration.CLASSES, keys of its BenchClass)
    "reg_real_time": "real time (causal)",
    "reg_offline": "offline (look-ahead or whole record)",
    # (not methods: the information a method uses, keys of fusion.scenarios.time_registration.Information)
    "reg_info_causal": "causal",
    "reg_info_look_ahead": "look-ahead",
    "reg_info_whole_record": "whole record",
    # chapter 05, covariance intersection (Wang & Tang 2024): fusion architectures, keys of
    # fusion.scenarios.two_sensor.Architecture (short labels below), and its rules, keys of ArchRule
    "arch_independent": "independent local filters",
    "arch_feedback": "Fig. 2 feedback (rule's own split fed back)",
    "arch_feedback_common": "Fig. 2 feedback (fused covariance fed back as common)",
    "arch_centralised": "centralised KF (both sensors' measurements)",
    "arch_convex": "convex comb. (eqs. 3-4)",
    "arch_ci": "CI (closed-form ω)",
    "arch_split_shared": "split CI, Q in shared part",
    "arch_split_own": "split CI, Q in own part",
    "arch_printed_shared": "eqs. 11-12 as printed, Q in shared part",
    "arch_printed_own": "eqs. 11-12 as printed, Q in own part",
    "arch_bsc": "Bar-Shalom–Campo",
    "arch_lossless": "lossless (fed-back prior removed once)",
    "arch_fuzzy": "fuzzy clustering",
    "arch_centralised_kf": "centralised KF",
    # chapter 05 (Wang & Tang 2024): method keys of fusion.scenarios.two_sensor.StudyMethod
    "ci_sensor_1": "sensor 1's local Kalman filter",
    "ci_sensor_2": "sensor 2's local Kalman filter",
    "ci_closed_form": "CI (closed-form ω)",
    "ci_fruit_fly": "CI, ω by FOA",
    "ci_grid": "CI, ω by exhaustive search",
    "ci_published_omega": "CI, ω = published FOA optimum",
    "split_ci": "improved CI (split CI)",
    "convex_ml": "convex comb. = multi-Bayesian = ML",
    "fuzzy_clustering": "fuzzy clustering",
    "centralised_kf": "centralised KF",
    "ci_sensor_1_raw": "sensor 1's measurements (no filter)",
    "ci_sensor_2_raw": "sensor 2's measurements (no filter)",
    # chapter 05 (Wang & Tang 2024): the consistency study, keys of fusion.scenarios.two_sensor.NeesRule
    "nees_local_sensor_1": "local filter (sensor 1)",
    "nees_ci_half": "CI, ω = 0.5",
    "nees_convex": "convex combination",
    "nees_split": "split CI (eq. ci-split)",
    "nees_printed_same_omega": "eqs. 11-12 as printed (same ω)",
    # chapter 05 (Wang & Tang 2024): the infrared + radar case, keys of fusion.scenarios.infrared_radar.IrMethod
    "ir_alone": "infrared alone",
    "radar_alone": "radar alone",
    "ir_per_scan": "per scan, no filter: IR angles + radar range",
    "radar_alone_cartesian": "radar alone (Cartesian)",
    "ir_radar_cartesian": "infrared angles + radar range (Cartesian)",
    # chapter 06, Chernoff patent (issue 36): the methods of fusion.scenarios.range_bearing.METHODS (the tracking
    # study) and of fusion.scenarios.fusion_networks.NETWORK_METHODS (the network study)
    "local1": "local PF, sensor 1",
    "local2": "local PF, sensor 2",
    "local3": "local PF, sensor 3",
    "mean_of_local_means": "mean of local means",
    "naive_product": "naive product, ε = (1, 1, 1)",
    "ci_gaussian": "CI of moment-matched Gaussians, Chernoff ε",
    "ci_det": "CI of moment-matched Gaussians, min det P",
    "ci_trace": "CI of moment-matched Gaussians, min trace P",
    # (keys of fusion.book.chapters.chernoff_criteria.GAUSSIAN_RULES besides the methods above)
    "ci_mean_free": "CI of moment-matched Gaussians, mean-free Chernoff ε",
    "ci_uniform": "CI of moment-matched Gaussians, uniform ε",
    "first_order_uniform": "first-order mixture g at uniform ε (step D only)",
    "chernoff_uniform": "Chernoff IS at uniform ε (no steps F-G)",
    "chernoff_pso": "Chernoff-PSO (patent, steps B-I)",
    "chernoff_slsqp": "Chernoff with SLSQP (same samples)",
    "chernoff_redraw": "Chernoff-PSO, samples redrawn at ε*",
    "chernoff_prev": "Chernoff, ε⁽⁰⁾ = previous ε*",
    "chernoff_first_order_start": "Chernoff, ε⁽⁰⁾ = argmin Z_FO, min Ĵ",
    "chernoff_first_order": "Chernoff IS at ε = argmin Z_FO (no swarm)",
    "chernoff_literal": "Chernoff-PSO, G6 as worded (positions converge)",
    "centralised_pf": "centralised PF (all measurements)",
    "exact_posterior": "exact posterior (all readings, grid)",
    # chapter 06, Chernoff patent (issue 36): swarm variants, keys of fusion.book.chapters.chernoff_scaling.SWARM_VARIANTS
    "pso_defaults": "the book's swarm (defaults)",
    "pso_floor": "floor 10⁻¹²",
    "pso_iterations": "4× iterations",
    # chapters 03 and 04, lecture notes §§2.5-2.7 (issue 18): new methods
    "reconstructed_fuse_first": "fuse first, then denoise",
    "ls": "least squares (mean)",
    "ridge_plugin_known": "ridge, plug-in k̂ = σ²/x̄² (σ known)",
    "ridge_plugin_est": "ridge, plug-in k̂ = s²/x̄² (σ estimated)",
    "ridge_centralised": "ridge, shrunk at the centre",
    "ridge_distributed": "ridge, shrunk at each sensor",
    "eigen": "eigen-decorrelation",
    "sample_variance": "sample variance, growing memory",
    "memory_growing": "cross-moments, growing memory (lecture)",
    "memory_forgetting": "centred, forgetting",
    "memory_window": "centred, sliding window",
    # chapter 02, lecture notes §2.1-2.4 (issue 36): method keys of its studies
    # (keys: fusion.scenarios.lecture_weighting.readings_benchmark.BenchMethod, the readings-level benchmark)
    "lec_bench_oracle": "oracle (inverse variance)",
    "lec_bench_mean": "mean",
    "lec_bench_awf_lecture_floor": "2.1 AWF (lecture, floor)",
    "lec_bench_awf_lecture_abs": "2.1 AWF (lecture, |σ̂²|)",
    "lec_bench_awf_centred": "2.1 AWF (centred)",
    "lec_bench_ls_learning": "2.2 LS learning",
    "lec_bench_ls_corrected": "2.2 LS learning, corrected",
    "lec_bench_check_awf": "2.3 check + AWF (centred)",
    "lec_bench_belief": "2.4 belief degree (s = 1)",
    "lec_bench_optimal_fusion_set": "001 optimal fusion set",
    "lec_bench_support_degree": "001 ref. [11] support degree",
    "lec_bench_median": "median",
    "lec_bench_biweight": "biweight (Tukey)",
    # (keys: fusion.scenarios.lecture_weighting.estimators.SYMMETRY_METHODS, the sign-flip check)
    "lec_sym_oracle": "oracle (true variances)",
    "lec_sym_awf_centred_floor": "AWF, centred, floor",
    "lec_sym_awf_centred_abs": "AWF, centred, |σ̂²|",
    "lec_sym_awf_centred_equal": "AWF, centred, equal fallback",
    "lec_sym_awf_lecture_abs_x0": "AWF, lecture's estimator, |σ̂²|, X = 0",
    "lec_sym_awf_lecture_abs": "AWF, lecture's estimator, |σ̂²|",
    "lec_sym_awf_lecture_floor": "AWF, lecture's estimator, floor",
    "lec_sym_ls_learning": "LS learning (2.2)",
    "lec_sym_ls_corrected": "LS learning, corrected (2.2)",
    # (keys: fusion.scenarios.lecture_weighting.estimators.AwfMethod, E2.1, E2.1c and E2.3; "oracle", "awf_lecture",
    # "awf_centred", "mean_of_means" and "best_sensor" are registered above)
    "awf_lecture_abs": "AWF (lecture, |σ̂²|)",
    "awf_lecture_equal": "AWF (lecture, equal)",
    "awf_lecture_none": "AWF (lecture, no guard)",
    "awf_lecture_delete": "AWF (lecture, delete)",
    "graybill_deal": "Graybill-Deal",
    "current_mean": "mean",
    "check_awf_lecture": "check + AWF (lecture, floor)",
    "check_awf_lecture_abs": "check + AWF (lecture, |σ̂²|)",
    "check_awf_lecture_equal": "check + AWF (lecture, equal)",
    "check_awf_lecture_none": "check + AWF (lecture, no guard)",
    "check_awf_lecture_delete": "check + AWF (lecture, delete)",
    "check_awf_centred": "check + AWF (centred)",
    # (keys: fusion.scenarios.lecture_weighting.regime.RegimeMethod, E2.1b)
    "lec_reg_oracle": "oracle",
    "lec_reg_mean": "mean",
    "lec_reg_sample_growing": "sample variance, growing",
    "lec_reg_difference_growing": "difference variance, growing",
    "lec_reg_difference_forgetting": "difference variance, forgetting",
    "lec_reg_lecture_growing": "lecture, growing",
    "lec_reg_centred_growing": "centred, growing",
    "lec_reg_centred_forgetting": "centred, forgetting",
    "lec_reg_centred_window": "centred, window",
    "lec_reg_awf_as_written": "AWF as written (running means)",
    "lec_reg_running_means_oracle": "running means, oracle",
    "lec_reg_per_sample_forgetting": "per-sample, forgetting",
    "lec_reg_per_sample_forgetting_alt": "per-sample, forgetting (λ = 0.99)",
    "lec_reg_per_sample_blue": "per-sample BLUE (oracle)",
    "lec_reg_ls_growing": "LS learning, growing (1/m)",
    "lec_reg_ls_forgetting": "LS learning, forgetting",
    # (not methods: the scenarios of E2.1b, keys of fusion.scenarios.lecture_weighting.regime.RegimeScenario)
    "lec_scen_constant": "constant X",
    "lec_scen_sine": "slow sine",
    "lec_scen_sine_level": "slow sine at 900",
    "lec_scen_fast": "fast sine",
    "lec_scen_walk": "random walk",
    "lec_scen_step": "step in X",
    "lec_scen_constant_swap": "constant X, σ swap",
    "lec_scen_sine_swap": "slow sine, σ swap",
    # (not methods: the changes of the noise SDs, keys of fusion.scenarios.lecture_weighting.regime.VarianceChange)
    "lec_chg_swap": "sensors 1 and 4 swap (0.5 ↔ 4)",
    "lec_chg_degrade": "sensor 1 degrades (0.5 → 4)",
    "lec_chg_improve": "sensor 4 improves (4 → 0.5)",
    # (keys: fusion.scenarios.lecture_weighting.belief.BeliefKind, E2.4b)
    "lec_bel_fuzzy": "fuzzy belief (s varied)",
    "lec_bel_binary": "binary belief, Perron vector (ε varied)",
    "lec_bel_deletion": "binary deletion rule (ε varied)",
    "lec_bel_deletion_third": "binary deletion rule, kept if ≥ 1/3 of the others trust it (ε varied)",
    "lec_bel_deletion_all": "binary deletion rule, kept if all others trust it (ε varied)",
    "lec_bel_fuzzy_limit": "fuzzy belief truncated at the fusion upper limit m (融合上限, m varied)",
    # chapter 04, lecture notes §2.7 (issue 36; not methods: the correlated cases, keys of
    # fusion.scenarios.correlated_sensors.CouplingCase)
    "cpl_equal": "equal coupling (as E2.7)",
    "cpl_one_outside": "one sensor outside the environment",
    "cpl_unequal": "unequal coupling",
    "cpl_unequal_strong": "unequal coupling, strong environment",
    "cpl_two_sensors": "two sensors, couplings 1 and 2",
    "cpl_equal_wide": "equal coupling, wide own SDs",
    # chapter 01 (issue 36; not methods: the cases, keys of fusion.book.chapters.ofs.FailureCase)
    "ofs_no_failure": "no failure",
    "ofs_failure": "failure",
    # chapter 02, E2.3 (issue 36; not methods: the data sets, keys of
    # fusion.scenarios.lecture_weighting.consistency.FaultCase)
    "lec_no_fault": "no fault",
    "lec_fault": "fault",
    # chapter 03, lecture notes §2.6 (issue 36; not methods: the measured signals, keys of
    # fusion.scenarios.wavelet_sensors.Signal)
    "sig_two_tones": "two tones",
    "sig_slow": "slow",
    "sig_constant": "constant",
    "sig_heavisine": "HeaviSine",
})

#: Short label of a method in tables and ledger entries, where its :data:`METHOD_LABELS` entry is too long (key →
#: label; a method without an entry is not shown in short form).
METHOD_SHORT_LABELS: dict[str, str] = constant({
    # chapter 05 (Wang & Tang 2024): the rules of fusion.scenarios.two_sensor.StudyMethod in ledger entries
    "ci_closed_form": "CI",
    "split_ci": "improved CI",
    "convex_ml": "convex combination",
    "fuzzy_clustering": "fuzzy clustering",
    # chapter 05 (Wang & Tang 2024): the architectures of fusion.scenarios.two_sensor.Architecture in tables
    "arch_independent": "independent",
    "arch_feedback": "feedback",
    "arch_feedback_common": "feedback, fused covariance common",
    "arch_centralised": "centralised",
    # chapter 04, lecture notes §2.5 (issue 36): the ridge studies of fusion.scenarios.ridge_sensors
    "ls": "LS",
    "ridge_plugin_known": "plug-in (known σ)",
    "ridge_plugin_est": "plug-in (estimated σ)",
    "ridge_centralised": "centralised ridge",
    "ridge_distributed": "distributed ridge",
    # chapter 03, lecture notes §2.6 (issue 36): the estimates of fusion.scenarios.wavelet_sensors in ledger entries
    "raw": "raw",
    "denoised": "own denoised",
    "reconstructed": "reconstructed",
    "denoise-first": "reconstructed",
    "fuse-first": "fused first, then denoised",
})

_STYLE = {
    "figure.dpi": 100,
    "savefig.dpi": 100,
    "figure.figsize": (7.0, 3.6),
    "figure.constrained_layout.use": True,
    "axes.grid": True,
    "grid.alpha": 0.3,
    "axes.spines.top": False,
    "axes.spines.right": False,
    "axes.titlesize": 11,
    "axes.labelsize": 10,
    "legend.fontsize": 9,
    "legend.frameon": False,
    "xtick.labelsize": 9,
    "ytick.labelsize": 9,
    "lines.linewidth": 1.4,
    "svg.hashsalt": "fusion-book",
    "path.simplify": False,
}


def use_book_style() -> None:
    """Apply the book's matplotlib style (call once at the top of a notebook).

    The style is whole: matplotlib's defaults with the book's settings on top (``plt.style.use(["default", ...])``),
    so a style or setting of the caller's (``plt.style.use("dark_background")``, a ``prop_cycle``) does not carry
    into the book's figures (fuzz 37a D1); :func:`new_figure` applies it at every figure. Settings that are not
    style (the backend, interactive mode) are kept.

    Inside IPython (a notebook) figures are also stored as high-DPI ("retina") PNG: twice the
    pixels, with width and height metadata so the page shows them at their nominal size, sharp on
    high-density screens. Each PNG carries its alt text (:func:`figure_alt`) in its ``Description``
    text chunk, which the book's Sphinx extension ``book/_ext/fusion_figures.py`` puts on the
    page's ``<img alt=...>``; and tables are shown through :func:`fusion.book.tables.use_book_tables`
    (no NaN, inf, True/False or e-notation in a cell).
    """
    plt.style.use(["default", _STYLE])
    try:
        from IPython import get_ipython
    except ImportError:  # pragma: no cover - IPython is a book dependency
        return
    shell = get_ipython()
    if shell is not None:
        from matplotlib_inline.backend_inline import set_matplotlib_formats

        set_matplotlib_formats("retina")
        _describe_pngs(shell)
        from fusion.book.tables import use_book_tables

        use_book_tables(shell)


def color(method: str) -> str:
    """Colour of a method; grey for methods without an assigned colour.

    Parameters
    ----------
    method : str
        Method key (as in :data:`METHOD_COLORS`).

    Returns
    -------
    str
        Hex colour, e.g. ``"#555555"``.
    """
    return METHOD_COLORS.get(text(method, "method"), "#555555")  # matched as its plain text (rule 19)


# Most panels along one side of a figure of new_figure.
_MAX_PANELS = 16


def _panels(n: int, name: str, what: str) -> int:
    """``n`` panels drawn one per entry of the caller's argument ``name`` (``what``: its entries), refused naming it
    beyond ``_MAX_PANELS`` before ``new_figure`` (fuzz 63a C5: ``ncols must be at most 16``, not the caller's)."""
    if n > _MAX_PANELS:
        raise ValueError(f"{name} must hold at most {_MAX_PANELS} {what} (one panel each), got {n}")
    return n


@functools.cache
def _figure_keywords() -> frozenset[str]:
    """The keywords :func:`matplotlib.pyplot.subplots` takes: its own, :func:`matplotlib.pyplot.figure`'s, the
    figure's constructor's and its properties (the setters that ``Figure.set`` accepts)."""
    import inspect

    from matplotlib.artist import ArtistInspector

    names = set(ArtistInspector(Figure).get_setters())
    for fn in (plt.subplots, plt.figure, Figure.__init__):
        names |= {p.name for p in inspect.signature(fn).parameters.values()
                  if p.kind not in (p.VAR_KEYWORD, p.VAR_POSITIONAL) and p.name != "self"}
    return frozenset(names - {"nrows", "ncols"})


#: Sides of a figure the book draws (inches) and its resolutions (dots per inch): the book's are 100 dpi and at most
#: 7.5 in wide (:data:`fusion.book.figures.MAX_WIDTH_IN`); beyond these a figure is no page's and drawing it can
#: ask for gigabytes (fuzz 22a A). :func:`new_figure` refuses a size or dpi outside them, ``audit_figure`` before
#: it draws.
FIGURE_SIDE_RANGE_IN = (0.5, 20.0)
#: Resolutions (dots per inch) :func:`new_figure` and ``audit_figure`` accept (the book draws at 100 dpi; 600 and
#: 1200 are print resolutions), within :data:`FIGURE_MAX_PIXELS`.
FIGURE_DPI_RANGE = (10.0, 1200.0)
#: Pixels a figure may have (width × height × dpi²): 40 million, about 160 MB as RGBA (a 20 in square at 316 dpi, a
#: 7.5 × 3.6 in page figure at 1200 dpi is 39 million). The memory guard, instead of a lower dpi limit (fuzz 23).
FIGURE_MAX_PIXELS = 40_000_000


def _figure_size(figsize: object, dpi: object) -> tuple[tuple[float, float], float]:
    """``figsize`` and ``dpi`` checked against :data:`FIGURE_SIDE_RANGE_IN`, :data:`FIGURE_DPI_RANGE` and
    :data:`FIGURE_MAX_PIXELS`:
    TypeError naming the argument for a non-number (a figsize that is not a pair), ValueError for NaN, an infinity
    or a value outside the range. The one check of :func:`new_figure` and ``audit_figure``."""
    from fusion._validation import scalar

    if isinstance(figsize, (str, bytes)) or not hasattr(figsize, "__len__") or len(figsize) != 2:  # type: ignore[arg-type]
        raise TypeError(f"figsize must be a pair (width, height) in inches, got {shown(figsize)}")
    lo, hi = FIGURE_SIDE_RANGE_IN
    w, h = (scalar(v, "figsize", lo, hi) for v in figsize)  # type: ignore[union-attr]
    d = scalar(dpi, "dpi", *FIGURE_DPI_RANGE)
    if w * h * d * d > FIGURE_MAX_PIXELS:
        top = (FIGURE_MAX_PIXELS / (w * h)) ** 0.5
        raise ValueError(f"dpi must be at most {top:.0f} for a figsize of {w:g} x {h:g} in (FIGURE_MAX_PIXELS = "
                         f"{FIGURE_MAX_PIXELS:,} pixels), got {d:g}")
    return (w, h), d


def new_figure(nrows: int = 1, ncols: int = 1, **kwargs: object) -> tuple[Figure, Axes]:
    """Create a figure in the book style; keyword arguments go to :func:`matplotlib.pyplot.subplots`.

    Parameters
    ----------
    nrows, ncols : int
        Grid of axes, each from 1 to 16 (a book figure's panels).
    **kwargs
        Passed to :func:`matplotlib.pyplot.subplots` (e.g. ``figsize``): its own keywords,
        :func:`matplotlib.pyplot.figure`'s and the figure's properties.

    Returns
    -------
    fig : matplotlib.figure.Figure
        The new figure, in the book's style whatever the caller's matplotlib style (:func:`use_book_style` is
        applied first, replacing a style the caller set; the axes drawn on afterwards keep it).
    ax : matplotlib.axes.Axes or ndarray of them
        One Axes for a single panel, else the ``nrows`` × ``ncols`` array of Axes that ``subplots`` returns.

    Raises
    ------
    TypeError
        ``nrows`` or ``ncols`` not an integer, or a keyword that :func:`matplotlib.pyplot.subplots` does not take
        (checked before any figure is made).
    ValueError
        ``nrows`` or ``ncols`` outside 1-16; a ``figsize`` side outside :data:`FIGURE_SIDE_RANGE_IN` or a
        ``dpi`` outside :data:`FIGURE_DPI_RANGE` (NaN included) or giving more than :data:`FIGURE_MAX_PIXELS`
        pixels, named (a figure wider than the page's
        7.5 in but within the range is made: ``audit_figure`` reports it).
    """
    nrows = count(nrows, "nrows", maximum=_MAX_PANELS)
    ncols = count(ncols, "ncols", maximum=_MAX_PANELS)
    keywords(kwargs, _figure_keywords(), "new_figure")
    _figure_size(kwargs.get("figsize", (7.0, 3.6)), kwargs.get("dpi", 100))   # the book style's defaults
    use_book_style()
    fig, ax = plt.subplots(nrows, ncols, **kwargs)  # type: ignore[arg-type]
    return fig, ax


#: Every registered method's display label (a key without a :data:`METHOD_LABELS` entry is its own label).
_LABEL_SET = frozenset(METHOD_LABELS.values()) | frozenset(k for k in METHOD_COLORS if k not in METHOD_LABELS)

#: Marker of each method where one is drawn (methods without an entry are drawn without markers).
METHOD_MARKERS: dict[str, str] = constant({
    "optimal_fusion_set": "o",
    "mean": "s",
    "support_degree": "^",
    "published": "x",
    "oracle": "D",
})

#: Line style of each method (solid where absent): reference lines dashed or dotted.
METHOD_LINESTYLES: dict[str, str] = constant({
    "published": ":",
    "truth": "--",
    "bound": "-.",
})


#: Legend labels of series that are not methods (data, truth, bounds, published values, diagnostics),
#: by chapter. A legend may show only a registered method label, one of these, or a label matching
#: :data:`LABEL_PATTERNS` (checked by :func:`fusion.book.figures.audit_figure`).
FIGURE_LABELS: frozenset[str] = frozenset({
    # every chapter
    "published", "true value", "true path",
    # chapter 01 (Yang, Feng & Fan 2012)
    "bound (inverse-variance mean)",
    # chapter 02 (lecture §§2.1-2.4)
    "centred estimate: mean", "centred estimate: ±1 SD", "lecture estimate: mean", "lecture estimate: ±1 SD",
    "check + AWF (centred estimate)", "optimal weights", "true σ₁²", "σ²min / k",
    # chapter 03 (lecture §2.6)
    "raw (sensor 4)", "true signal",
    # chapter 04 (lecture §§2.5, 2.7)
    "χ²₂", "∝ 1/m",
    # chapter 05 (Wang & Tang 2024)
    "error, improved CI (run 1)", "floor: straight-leg least squares", "ours (vectorised)", "ours, closed form",
    "published (MATLAB)", "published, improved CI", "tr P(ω), asymmetric pair", "±2σ reported",
    "many-scan bound: both sensors, straight flight", "sensor 1, local filter", "sensor 2, local filter",
    "sensor 1, raw measurements", "floor: causal straight-leg least squares", "tr P(ω), anisotropic pair",
    "tr P(ω), sensor 2 three times more precise", "FOA (30 × 200), one point per seed",
    # chapter 06 (Chernoff patent): diagnostics and references
    "PSO: best Ĵ so far", "SLSQP on the same samples", "at ε* (patent: samples reused)", "at ε*, samples redrawn",
    "at ε⁽⁰⁾ (uniform)", "centralised PF (ESS / particles)", "exact (grid)", r"first-order $\log Z_{\rm FO}$",
    r"importance sampling $\hat J$ (proposal at ω = 0.5)", "posterior CRB",
    "optimised − uniform exponents", "mixture fusion − CI of Gaussians", "local PFs (mean of the nodes)",
    "naive product, linearised (exact cross-covariances)",
    "PSO followed to its limit", "stagnation rule stops", "positions converge (G6 as worded)",
    # chapter 07 (Shi et al. 2023)
    "sensor 1, interpolated", "sensor 1, least squares",
})

#: Parametrised legend labels: ``(regular expression, what it labels)``. A named group ``method`` must
#: itself be a registered label (a method shown with a suffix, e.g. its information class).
LABEL_PATTERNS: tuple[tuple[str, str], ...] = (
    (r"(R̂ )?sensors? \d+( and \d+)?( \((run \d+|shifted|max|median)\))?( fails?)?", "a sensor's data or result"),
    (r"(?P<method>.+) \[(causal|look-ahead|whole record)\]", "a method with its information class (chapter 07)"),
    (r"(?P<method>.+), run \d+|(?P<method2>.+) \(run \d+\)", "a method in one Monte-Carlo run"),
    (r"ε\d+ \(sensor \d+\)(, run \d+)?", "a node's Chernoff exponent (chapter 06)"),
    (r"node \d+, (smallest|median)( \((no guard|guard)\))?", "a node's effective sample size (chapter 06)"),
    (r"([xXkσ]|right panel: x) ?= ?-?[\d.]+( m)?(, (k = [\d.]+|fault|no fault))?", "a parameter value of a sweep"),
)


def is_registered_label(label: str) -> bool:
    """Whether a legend label is in the registry (a method, a registered series, or a registered pattern).

    Parameters
    ----------
    label : str
        Text of a legend entry.

    Returns
    -------
    bool
        True for a label of :data:`METHOD_LABELS`, :data:`FIGURE_LABELS`, or a full match of a pattern
        of :data:`LABEL_PATTERNS` whose ``method`` group (if any) is itself registered.

    Raises
    ------
    TypeError
        If ``label`` is not a string.
    """
    import re

    label = text(label, "label")  # matched as its plain text (rule 19)
    if label in FIGURE_LABELS or label in _LABEL_SET:
        return True
    for pattern, _ in LABEL_PATTERNS:
        m = re.fullmatch(pattern, label)
        if m is not None:
            inner = [v for k, v in m.groupdict().items() if k.startswith("method") and v is not None]
            if all(is_registered_label(v) for v in inner):
                return True
    return False


def method_style(method: str, *, markers: bool = False) -> dict[str, str]:
    """Keyword arguments that draw a method in the book's style (colour, label, line style, marker).

    Parameters
    ----------
    method : str
        Method key of the registry (:data:`METHOD_COLORS`, :data:`METHOD_LABELS`).
    markers : bool
        Include the method's marker (for plots with few points).

    Returns
    -------
    dict
        ``color``, ``label``, ``linestyle`` and (if ``markers``) ``marker``, for
        :meth:`matplotlib.axes.Axes.plot`.

    Raises
    ------
    ValueError
        If ``method`` is not in the registry (a figure may not invent a method's style).
    """
    flag(markers, "markers")
    instance_of(method, str, "method")
    method = text(method, "method")  # rule 19: matched by its text
    if method not in METHOD_COLORS:
        raise ValueError(f"method {shown(method)} is not in the figure registry (fusion.book.style.METHOD_COLORS)")
    kw = {"color": METHOD_COLORS[method], "label": METHOD_LABELS.get(method, method),
          "linestyle": METHOD_LINESTYLES.get(method, "-")}
    if markers and method in METHOD_MARKERS:
        kw["marker"] = METHOD_MARKERS[method]
    return kw


# --------------------------------------------------------------------------- alt text of figures

#: Alt text of a published figure, by glue key, where the automatic description
#: (:func:`describe_figure`: chart type, axes, series) is not enough. A text here replaces the
#: automatic one; ``glue_figure(key, fig, alt=...)`` replaces both. Say what the figure shows
#: (what is plotted against what, and the point it makes), not what it is called.
FIGURE_ALT: dict[str, str] = constant({})

#: Longest alt text written into a PNG (characters); longer descriptions are cut at a word.
MAX_ALT_CHARS = 700
# Longest alt text (characters), far above any real one: set_figure_alt refuses a longer one, and png_description
# refuses a longer PNG description, so that a figure the package accepts is one its PNG reader reads (fuzz 22a N).
_MAX_DESCRIPTION = 100_000
# Most bytes a description of _MAX_DESCRIPTION characters takes (UTF-8, in an iTXt chunk); bounds the inflation.
_MAX_DESCRIPTION_BYTES = 4 * _MAX_DESCRIPTION

_ALT_ATTR = "_fusion_alt"


def plain_math(text: str) -> str:
    """Text of a label or formula without TeX markup, for alt text (``$\\sigma_{\\rm max}^2$`` -> ``σ_max²``).

    Parameters
    ----------
    text : str
        A matplotlib label (mathtext between ``$``) or the TeX source of a formula.

    Returns
    -------
    str
        ``text`` without ``$``, font commands and braces: Greek names as letters, integer exponents as superscripts,
        spaces collapsed. Not a TeX parser: any other command keeps its name (``$\\frac{a}{b}$`` -> ``fracab``) and
        every brace is dropped, balanced or not (``$\\frac{a}{`` -> ``fraca``). A malformed formula thus gives
        plain, if garbled, text and no error: the function only writes alt text, and matplotlib refuses a
        malformed label when it draws it.
    """
    import re

    instance_of(text, str, "text")
    text = _plain_text(text, "text")  # its plain text (rule 19)

    greek = {"alpha": "α", "beta": "β", "gamma": "γ", "delta": "δ", "epsilon": "ε", "varepsilon": "ε",
             "lambda": "λ", "mu": "μ", "sigma": "σ", "omega": "ω", "theta": "θ", "tau": "τ", "pi": "π",
             "rho": "ρ", "Delta": "Δ", "Sigma": "Σ", "chi": "χ", "nu": "ν", "phi": "φ", "xi": "ξ"}
    out = text.replace("$", "")
    out = re.sub(r"\\(?:rm|mathrm|mathit|mathbf|operatorname|text)\s*", "", out)
    out = re.sub(r"\\([A-Za-z]+)", lambda m: greek.get(m[1], m[1]), out)
    out = re.sub(r"\^\{?(-?\d+)\}?", lambda m: m[1].translate(_SUPERSCRIPT), out)
    out = out.replace("{", "").replace("}", "").replace("\\", "")
    return " ".join(out.split())


_plain = plain_math


def _kind(ax: Axes) -> str:
    """What an axes draws: "line chart", "bar chart", "scatter plot", "colour map" or "plot"."""
    from matplotlib.collections import PathCollection, QuadMesh
    from matplotlib.image import AxesImage
    from matplotlib.container import BarContainer

    kinds = []
    if any(isinstance(a, AxesImage) for a in ax.images) or any(isinstance(c, QuadMesh) for c in ax.collections):
        kinds.append("colour map")
    if any(type(c).__name__ in ("QuadContourSet", "ContourSet") for c in getattr(ax, "containers", [])) or \
            any("Contour" in type(c).__name__ for c in ax.collections):
        kinds.append("contour plot")
    if any(isinstance(c, BarContainer) for c in ax.containers):
        kinds.append("bar chart")
    if any(isinstance(c, PathCollection) and len(c.get_offsets()) for c in ax.collections):
        kinds.append("scatter plot")
    def drawn(line: object) -> bool:                 # a data line, not an axhline/axvline reference
        import numpy as np

        x, y = (np.asarray(v, dtype=object) for v in (line.get_xdata(), line.get_ydata()))  # type: ignore[attr-defined]
        return x.size >= 2 and len(set(map(str, x))) > 1 and len(set(map(str, y))) > 1

    if any(line.get_visible() and drawn(line) for line in ax.lines):
        kinds.append("line chart")
    if not kinds:
        return "plot"
    return " and ".join(dict.fromkeys(kinds))


def _series(ax: Axes) -> list[str]:
    labels = []
    handles, texts = ax.get_legend_handles_labels()
    for t in texts:
        if t and not t.startswith("_"):
            labels.append(_plain(t))
    return list(dict.fromkeys(labels))


def describe_figure(fig: Figure) -> str:
    """A one-paragraph description of what a figure shows, for its alt text.

    Built from the figure itself: its title, the kind of each panel (line chart, scatter plot, ...),
    what is plotted against what (the axis labels) and the series named in the legends. The caption
    beside the figure gives the point it makes; this says what a sighted reader sees.

    Parameters
    ----------
    fig : matplotlib.figure.Figure

    Returns
    -------
    str
        E.g. ``"Line chart of RMSE (m) against time (s); series: CI (closed-form ω), improved CI
        (split CI)."``; at most :data:`MAX_ALT_CHARS` characters.

    Raises
    ------
    TypeError
        If ``fig`` is not a matplotlib Figure.
    """
    instance_of(fig, Figure, "fig")
    axes = [ax for ax in fig.axes if ax.get_visible() and ax.get_label() != "<colorbar>" and ax.axison]
    parts: list[str] = []
    suptitle = getattr(fig, "_suptitle", None)
    if suptitle is not None and suptitle.get_text().strip():
        parts.append(_plain(suptitle.get_text()) + ".")
    if len(axes) > 1:
        parts.append(f"{len(axes)} panels.")
    fig_series = [_plain(t.get_text()) for leg in fig.legends for t in leg.get_texts() if t.get_text()]
    for i, ax in enumerate(axes):
        what = _kind(ax)
        y, x = _plain(ax.get_ylabel()), _plain(ax.get_xlabel())
        if y and x:
            what += f" of {y} against {x}"
        elif y:
            what += f" of {y}"
        elif x:
            what += f" against {x}"
        title = _plain(ax.get_title())
        head = (f"Panel {i + 1}" + (f" ({title})" if title else "") + ": ") if len(axes) > 1 else \
            (f"{title}: " if title else "")
        series = _series(ax)
        text = head + what[0].upper() + what[1:]
        if series:
            text += "; series: " + ", ".join(series)
        parts.append(text + ".")
    if fig_series:
        parts.append("Legend: " + ", ".join(dict.fromkeys(fig_series)) + ".")
    out = " ".join(parts) if parts else "Figure."
    if len(out) > MAX_ALT_CHARS:
        out = out[:MAX_ALT_CHARS - 2].rsplit(" ", 1)[0].rstrip(",;:") + " …"   # " …" counts in the bound
    return out


def set_figure_alt(fig: Figure, alt: str | None) -> None:
    """Attach an alt text to a figure (``None`` keeps the automatic :func:`describe_figure`).

    Parameters
    ----------
    fig : matplotlib.figure.Figure
    alt : str or None
        What the figure shows, in a sentence or two; not a file name.

    Raises
    ------
    TypeError
        If ``fig`` is not a Figure or ``alt`` not a string.
    ValueError
        If ``alt`` is blank, looks like a file path, or is longer than ``_MAX_DESCRIPTION`` (100,000) characters
        once its runs of white space are made single spaces (the bound :func:`png_description` reads).
    """
    instance_of(fig, Figure, "fig")
    if alt is None:
        if hasattr(fig, _ALT_ATTR):
            delattr(fig, _ALT_ATTR)
        return
    instance_of(alt, str, "alt")
    import re

    if not alt.strip() or re.search(r"\.(png|svg|jpe?g|pdf)\b|^[\w./-]+/[\w.-]+$", alt.strip()):
        raise ValueError(f"alt must say what the figure shows, got {shown(alt)}")
    alt = " ".join(alt.split())
    if len(alt) > _MAX_DESCRIPTION:
        raise ValueError(f"alt must be at most {_MAX_DESCRIPTION:,} characters (a sentence or two), got {len(alt):,}")
    setattr(fig, _ALT_ATTR, alt)


def figure_alt(fig: Figure) -> str:
    """The alt text of a figure: the one set by :func:`set_figure_alt`, else :func:`describe_figure`.

    Parameters
    ----------
    fig : matplotlib.figure.Figure

    Returns
    -------
    str
        The alt text set on ``fig``, else one generated from its title, panels, axis labels and legends.
    """
    instance_of(fig, Figure, "fig")
    return getattr(fig, _ALT_ATTR, None) or describe_figure(fig)


def _describe_pngs(shell: object) -> None:
    """Make the notebook's PNG formatter write each figure's alt text into the PNG (``Description``)."""
    fmt = shell.display_formatter.formatters["image/png"]  # type: ignore[attr-defined]
    try:
        base = fmt.lookup_by_type(Figure)
    except KeyError:  # pragma: no cover - set_matplotlib_formats registers one
        return
    if getattr(base, "_fusion_described", False):
        return

    def png(fig: Figure):  # type: ignore[no-untyped-def]
        return base(fig, metadata={"Description": figure_alt(fig)})

    png._fusion_described = True  # type: ignore[attr-defined]
    fmt.for_type(Figure, png)


def png_description(data: bytes) -> str | None:
    """The ``Description`` text chunk of a PNG (tEXt, zTXt or iTXt), or None.

    Parameters
    ----------
    data : bytes
        The PNG file.

    Returns
    -------
    str or None
        None for bytes that are not a PNG, a PNG without a description, or one whose description chunk is
        malformed (cut short, compressed data that is not zlib's, an iTXt text that is not UTF-8): the page then
        takes its alt text from the caption, as for a figure without a description.

    Raises
    ------
    TypeError
        ``data`` not bytes (a ``str``, a path, None: read the file's bytes first).
    ValueError
        ``data`` holds a description longer than ``_MAX_DESCRIPTION`` (100,000) characters (the bound
        :func:`set_figure_alt` puts on an alt text), or a compressed one inflating beyond the bytes that many
        characters can take (read in bounded steps: a small file cannot inflate to gigabytes). An alt text is a
        sentence or two (:data:`MAX_ALT_CHARS` for the automatic ones).
    """
    import struct
    import zlib

    if not isinstance(data, (bytes, bytearray)):
        raise TypeError(f"data must be the bytes of a PNG file, got {type(data).__name__}")
    if not data.startswith(b"\x89PNG\r\n\x1a\n"):
        return None

    def inflate(raw: bytes) -> bytes | None:
        d = zlib.decompressobj()
        try:
            out = d.decompress(raw, _MAX_DESCRIPTION_BYTES + 1)
        except zlib.error:
            return None
        if len(out) > _MAX_DESCRIPTION_BYTES:
            raise ValueError(f"data: the PNG's Description chunk inflates beyond {_MAX_DESCRIPTION_BYTES:,} bytes "
                             f"(more than {_MAX_DESCRIPTION:,} characters: not an alt text)")
        return out if d.eof else None   # cut short: malformed

    pos = 8
    while pos + 8 <= len(data):
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + length]
        pos += 12 + length
        if kind == b"IDAT" or kind == b"IEND":
            # matplotlib writes text chunks before the image data
            if kind == b"IEND":
                break
            continue
        if kind not in (b"tEXt", b"zTXt", b"iTXt"):
            continue
        key, _, rest = body.partition(b"\0")
        if key != b"Description":
            continue
        if kind == b"tEXt":
            text = rest
        elif kind == b"zTXt":
            text = inflate(rest[1:]) if rest[:1] == b"\0" else None   # method 0 (zlib) is the only one
        elif len(rest) < 2:
            return None
        else:
            compressed, rest = rest[0], rest[2:]
            _lang, _, rest = rest.partition(b"\0")
            _tkey, _, text = rest.partition(b"\0")
            text = inflate(text) if compressed else text
        if text is None:
            return None
        if len(text) > _MAX_DESCRIPTION_BYTES:   # more bytes than the longest alt text takes: not decoded
            raise ValueError(f"data: the PNG's Description chunk holds {len(text):,} bytes, more than "
                             f"{_MAX_DESCRIPTION:,} characters can take (not an alt text)")
        try:
            out = text.decode("latin-1" if kind != b"iTXt" else "utf-8")
        except UnicodeDecodeError:
            return None
        if len(out) > _MAX_DESCRIPTION:   # counted in characters, as set_figure_alt counts them
            raise ValueError(f"data: the PNG's Description chunk holds {len(out):,} characters, beyond "
                             f"{_MAX_DESCRIPTION:,} (not an alt text)")
        return out
    return None
