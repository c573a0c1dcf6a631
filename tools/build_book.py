"""``jupyter-book build`` with Sphinx reading and writing on every core.

Jupyter-book 1.x's command line has no ``-j``: its ``build_sphinx`` takes ``jobs`` but the command
passes none, so Sphinx reads the ~90 documents and writes their pages in one process. This wrapper
runs the same command with ``jobs`` set (``FUSION_SPHINX_JOBS``, default: the machine's cores). The
extensions jupyter-book loads without declaring parallel safety are declared safe by
``book/_ext/fusion_book.py`` (``PARALLEL_SAFE_UNDECLARED``, with the reason), which also removes
viewcode's empty module records that a parallel read leaves behind: the HTML of a two-process build
was compared file by file with a serial build's when this was introduced, and was identical. Sphinx itself
would still resolve and index every page in the main process and leave the workers the HTML translation only;
the same extension hands the workers whole pages and the ``[source]`` pages (``_write_in_workers``,
``_viewcode_pages_in_workers``).

Usage: ``python tools/build_book.py ARGS...``, where ARGS are those of ``jupyter-book build``.
"""
from __future__ import annotations

import os
import sys


def jobs() -> int:
    """Sphinx processes: ``FUSION_SPHINX_JOBS`` if set (a positive whole number), else the machine's cores."""
    raw = os.environ.get("FUSION_SPHINX_JOBS")
    if raw is None:
        return max(1, len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else (os.cpu_count() or 1))
    if not raw.strip().isdigit() or int(raw) < 1:
        raise SystemExit(f"FUSION_SPHINX_JOBS must be a positive whole number, not {raw!r}")
    return int(raw)


def main(argv: list[str]) -> int:
    import jupyter_book.sphinx as jb_sphinx
    from jupyter_book.cli.main import main as jupyter_book

    build_sphinx, n = jb_sphinx.build_sphinx, jobs()

    def with_jobs(*args, **kwargs):  # noqa: ANN002, ANN003, ANN202 - passes jupyter-book's own arguments through
        kwargs["jobs"] = n
        return build_sphinx(*args, **kwargs)

    jb_sphinx.build_sphinx = with_jobs   # the command imports it from this module when it runs
    sys.argv = ["jupyter-book", "build", *argv]
    jupyter_book()                       # click: exits with the build's status
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
