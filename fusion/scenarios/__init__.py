r"""Simulated scenarios: one module per case a chapter studies. Scenarios import algorithms, never the reverse. Import a scenario module itself, e.g. ``from fusion.scenarios import thermocouples``.

Modules:

thermocouples
    Simulated thermocouple bank of Yang, Feng & Fan (2012, Figs. 1-4) and its Monte-Carlo study.
two_sensor
    The two-sensor 2-D tracking case of Wang & Tang (2024, §3.2), vectorised over runs.
infrared_radar
    Infrared + radar case of Wang & Tang (2024, §3.5 item 3, Figs. 9-10), vectorised over Monte-Carlo runs.
range_bearing
    Distributed tracking with range-bearing sensor nodes: the designed scenario of chapter 06.
fusion_networks
    Static fusion networks where Chernoff fusion's premise can show (chapter 06): unequal, range-only and
    bearings-only nodes, feedback, a chain.
two_mixtures
    The static two-mixture example of the Chernoff-fusion chapter, and its exact reference.
time_registration
    The drone time-registration case of Shi, Suo & Ma (2023, §5) and its Monte-Carlo study.
lecture_weighting
    The experiments of chapter 02 (lecture notes, sections 2.1-2.4) and its readings-level benchmark.
lecture_correlated
    The experiments of chapter 04 from the lecture notes' sections 2.5 and 2.7 (ridge, LDLᵀ pseudo-measurements).
ridge_sensors
    Lecture §2.5 with a data-driven ridge parameter: scalar x-dependence, an ill-conditioned vector case.
wavelet_sensors
    Lecture §2.6's mechanism: shared denoising bias, fuse-first vs denoise-first, wavelet choices.
correlated_sensors
    Lecture §2.7's correlated cases where ignoring the correlation costs a lot and GLS weights go negative.
"""

__all__: list[str] = []
