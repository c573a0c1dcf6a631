"""Helpers that several test modules share (not a test module: pytest collects only ``test_*.py``).

- :func:`bounded`: run a call under a wall-clock alarm and classify its outcome (the bad-input tests).
"""

from __future__ import annotations

import signal
from collections.abc import Callable
from typing import Any

import pytest


class _Timeout(Exception):
    pass


def _on_alarm(*_: Any) -> None:
    raise _Timeout


def bounded(call: Callable[[], Any], seconds: int, late: str) -> tuple[str, Any]:
    """Run ``call`` under a wall-clock alarm of ``seconds``: ("ok", result) or ("raised", exception); past the
    alarm the test fails with the message ``late``."""
    old = signal.signal(signal.SIGALRM, _on_alarm)
    signal.alarm(seconds)
    try:
        return "ok", call()
    except _Timeout:
        pytest.fail(late)
    except Exception as exc:  # noqa: BLE001 - classified by the caller
        return "raised", exc
    finally:
        signal.alarm(0)
        signal.signal(signal.SIGALRM, old)
