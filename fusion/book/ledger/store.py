"""The ledger of one source: :class:`Ledger` collects the chapter's claims and writes ``book/ledger/<source>.json``."""

from __future__ import annotations

import hashlib
import json
import math
from collections.abc import Mapping
from pathlib import Path
from typing import Any

import pandas as pd

from fusion.book._json import JSONObject
from fusion.book.ledger.claim import Claim
from fusion._paths import file_in, folder, write_file_text
from fusion._validation import instance_of, shown, text
from fusion.book.ledger.sources import SOURCES

__all__ = [
    "Ledger",
    "ledger_dir",
]


#: The folder above the imported ``fusion`` package: the repository when the package runs from a clone.
_REPOSITORY = Path(__file__).resolve().parents[3]


def ledger_dir(start: Path | str | None = None) -> Path:
    """``book/ledger`` of the repository that contains ``start`` (default: the working directory's, else the package's).

    Without ``start`` the search starts in the working directory (a worktree's tests and notebooks find their own
    book even when ``fusion`` is imported from another clone) and falls back to the repository the imported package
    lives in, so that the book's functions also work from a working directory outside the repository.

    Parameters
    ----------
    start : str or os.PathLike, optional
        The existing folder where to start looking upwards for ``_toc.yml`` (default: the working directory, then
        the package's repository).

    Returns
    -------
    pathlib.Path
        The ledger directory (it may not exist yet).

    Raises
    ------
    TypeError
        ``start`` is not a path (``str`` or ``os.PathLike``).
    ValueError
        ``start`` is not an existing folder (a file, a missing folder, a name the system cannot use).
    FileNotFoundError
        No ``_toc.yml`` in ``start`` or above it; without ``start``, none above the working directory nor in the
        package's repository (an installed package has no book files).
    """
    here = (folder(start, "start") if start is not None else Path.cwd()).resolve()
    for p in (here, *here.parents):
        if (p / "_toc.yml").is_file():
            return p / "book" / "ledger"
    if start is not None:
        raise FileNotFoundError(f"start: no _toc.yml in {here} or above it: not inside the book's repository")
    # outside the repository (fuzz 17, class F): the repository this package was imported from, if it is one
    if (_REPOSITORY / "_toc.yml").is_file():
        return _REPOSITORY / "book" / "ledger"
    raise FileNotFoundError(f"no _toc.yml in the working directory {here} or above it, nor in {_REPOSITORY} (the "
                            "folder above the imported fusion package): the book's files (book/ledger, book/claims) "
                            "come with the repository, not with an installed package")


def _clean(x: Any) -> Any:
    """JSON-ready copy with floats rounded to 7 significant digits.

    Ten digits were not enough: a particle-filter study gives values that differ in the ninth digit
    between 1 and 2 BLAS threads, and the stored file (and its digest) must not depend on that.
    """
    if isinstance(x, float):
        return float(f"{x:.7g}") if math.isfinite(x) else None
    if isinstance(x, Mapping):
        return {k: _clean(v) for k, v in x.items()}
    if isinstance(x, (list, tuple)):
        return [_clean(v) for v in x]
    return x


class Ledger:
    """The claims of one source's chapter, filled by the chapter and written to ``book/ledger``.

    A source with one chapter writes ``<source>.json``; a source whose claims span several
    chapters (:attr:`Source.chapters`) writes one file per chapter, ``<source>-<NN>.json``, each
    record's ``chapter`` naming the chapter that holds its evidence. The source's headline claim
    lives in its first chapter.

    Parameters
    ----------
    source : str
        A key of :data:`SOURCES`.
    chapter : str, optional
        Docname of the chapter filling this ledger, one of the source's chapters (default: its
        first).

    Attributes
    ----------
    source : str
        The source's key.
    chapter : str
        Docname of the chapter.
    claims : list of Claim
        Claims added so far, in order.

    Raises
    ------
    ValueError
        Unknown ``source``, or ``chapter`` not one of its chapters.
    """

    def __init__(self, source: str, chapter: str | None = None) -> None:
        source = text(source, "source")  # rule 19: matched and stored as its text
        if source not in SOURCES:
            raise ValueError(f"source must be one of {sorted(SOURCES)}, got {shown(source)}")
        src = SOURCES[source]
        if chapter is None:
            chapter = src.chapter
        if chapter not in src.chapters:
            raise ValueError(f"chapter must be one of {list(src.chapters)}, got {shown(chapter)}")
        self.source = source
        self.chapter = chapter
        self.claims: list[Claim] = []
        self._ids: set[str] = set()  # the ids of ``claims``: a set, so that n adds cost n, not n²/2 (fuzz 22a D5)

    def add(self, claim: Claim) -> Claim:
        """Add a claim of this ledger's source (ids must be unique).

        Parameters
        ----------
        claim : Claim

        Returns
        -------
        Claim
            ``claim``.

        Raises
        ------
        TypeError
            ``claim`` is not a :class:`Claim`.
        ValueError
            ``claim`` is of another source, or its id is already in the ledger.
        """
        instance_of(claim, Claim, "claim")
        if claim.source != self.source:
            raise ValueError(f"claim {claim.id} is of {claim.source}, this ledger holds {self.source}")
        if len(self._ids) != len(self.claims) or not all(c.id in self._ids for c in self.claims[-1:]):
            self._ids = {c.id for c in self.claims}  # ``claims`` was changed directly: read its ids again
        if claim.id in self._ids:
            raise ValueError(f"duplicate claim id {shown(claim.id)}")
        self.claims.append(claim)
        self._ids.add(claim.id)
        return claim

    def records(self) -> list[JSONObject]:
        """JSON-ready records of the claims, each naming this ledger's chapter."""
        return [_clean({**c.to_dict(), "chapter": self.chapter}) for c in self.claims]

    def table(self) -> pd.DataFrame:
        """One row per claim: where, status, robustness (what the chapter displays).

        Returns
        -------
        pandas.DataFrame
            Indexed by ``id``, columns ``where``, ``status``, ``robustness``; an empty ledger gives a table with
            these columns and no rows.
        """
        return pd.DataFrame([{"id": c.id, "where": c.where, "status": c.status, "robustness": c.robustness}
                             for c in self.claims], columns=["id", "where", "status", "robustness"]).set_index("id")

    @property
    def filename(self) -> str:
        """The ledger file's name: ``<source>.json``, or ``<source>-<NN>.json`` for a multi-chapter source."""
        return SOURCES[self.source].ledger_file(self.chapter)

    def write(self, directory: Path | str | None = None) -> str:
        """Write :attr:`filename` and return the SHA-256 of its text (shown by the chapter).

        The digest is part of the chapter's stored output, so a change of any record makes the
        notebook test fail until the notebook is re-executed and the file committed. The source's
        first chapter must hold exactly one headline claim, its other chapters none.

        Parameters
        ----------
        directory : str or os.PathLike, optional
            The folder to write to, made if missing (default: :func:`ledger_dir`).

        Returns
        -------
        str
            The first 16 hex digits of the SHA-256 of the written text.

        Raises
        ------
        TypeError
            ``directory`` is not a path (``str`` or ``os.PathLike``).
        ValueError
            The ledger is empty or its headline claims break the rule above; ``directory`` is not a folder
            (a file, a name the system cannot use) or cannot be made, or it holds something other than a file
            under the ledger file's name (a folder, a dangling symlink), or the file cannot be written (its old
            text is then left as it was: the file is written whole or not at all).
        """
        if not self.claims:
            raise ValueError("the ledger is empty")
        want = int(self.chapter == SOURCES[self.source].chapter)
        if sum(c.headline for c in self.claims) != want:
            raise ValueError("exactly one claim per source must be the headline, in the source's first chapter")
        d = folder(directory if directory is not None else ledger_dir(), "directory", create=True)
        head = {"source": self.source}
        if len(SOURCES[self.source].chapters) > 1:
            head["chapter"] = self.chapter
        text = json.dumps({**head, "claims": self.records()}, ensure_ascii=False, indent=1) + "\n"
        path = file_in(d, self.filename, "directory")   # a folder or a dangling link of the file's name: refused
        # whole or not at all (fuzz 49b C5: write_text truncated the old file, then failed to encode the text)
        data = write_file_text(path, text, "directory")   # no permission, a full disk: ValueError, old file kept
        return hashlib.sha256(data).hexdigest()[:16]
