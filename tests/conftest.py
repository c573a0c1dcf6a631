"""Shared test configuration: deterministic hypothesis runs."""

from hypothesis import HealthCheck, settings

# Derandomised: the same examples on every machine and every run, so a failure is
# reproducible and CI is not flaky. No deadline: CI machines vary in speed.
settings.register_profile(
    "fusion", derandomize=True, deadline=None, max_examples=200,
    suppress_health_check=[HealthCheck.too_slow],
)
settings.load_profile("fusion")
