"""The sources the book checks: one :class:`Source` per source, keyed in :data:`SOURCES`."""

from __future__ import annotations

from dataclasses import dataclass

from fusion._frozen import constant
from fusion._validation import count
from fusion._validation import shown
from fusion.book.ledger.statuses import _text, _texts, text_fields

__all__ = [
    "Source",
    "SOURCES",
]


@dataclass(frozen=True)
class Source:
    """One of the five source documents.

    Attributes
    ----------
    key : str
        BibTeX key.
    short : str
        Author-year citation, as readers see it.
    title : str
        English title of the chapter's subject.
    chapter : str
        Docname of the chapter (without suffix).
    order : int
        Position in the book.
    chapters : tuple of str, optional
        Docnames of every chapter on the source, in reading order, when it spans several; the
        first must be ``chapter`` (which holds the source's headline). Default: ``(chapter,)``. When there
        are several, each file name starts with its own number (``NN_``), which names its ledger file.

    Raises
    ------
    TypeError
        A text field not a str, ``order`` not an integer, ``chapters`` not a tuple of str.
    ValueError
        An empty text; ``order`` below 1; ``chapters`` not starting with ``chapter``, repeating one, or (several
        chapters) one without a number ``NN_`` or two with the same number (their ledger files would collide).
    """

    key: str        # BibTeX key
    short: str      # author-year, as readers see it
    title: str      # English title
    chapter: str    # docname of the (first) chapter (without suffix)
    order: int      # position in the book
    chapters: tuple[str, ...] = ()  # every chapter on the source, in reading order

    def __post_init__(self) -> None:
        text_fields(self, "key", "short", "title", "chapter")  # plain str copies (rule 19)
        object.__setattr__(self, "order", count(self.order, "order"))  # the plain int, never the caller's object
        if not isinstance(self.chapters, tuple):
            raise TypeError(f"chapters must be a tuple of str, got {type(self.chapters).__name__}")
        if not self.chapters:
            object.__setattr__(self, "chapters", (self.chapter,))
        object.__setattr__(self, "chapters", _texts(self.chapters, "chapters"))
        if self.chapters[0] != self.chapter or len(set(self.chapters)) != len(self.chapters):
            raise ValueError(f"chapters must start with chapter {shown(self.chapter)} and not repeat, got {shown(self.chapters)}")
        if len(self.chapters) > 1:  # each chapter's ledger file is <key>-<NN>.json: NN must exist and differ
            numbers = [_number(c) for c in self.chapters]
            if not all(n.isascii() and n.isdigit() for n in numbers) or len(set(numbers)) != len(numbers):
                raise ValueError(f"chapters of a source that spans several must each have their own number (the "
                                 f"prefix 'NN_' of the file name, which names the ledger file), got {shown(self.chapters)}")

    def ledger_file(self, chapter: str | None = None) -> str:
        """Name of the ledger file of one of the source's chapters (default: the first).

        ``<key>.json`` for a source with one chapter, ``<key>-<NN>.json`` (``NN`` the chapter's
        number, the prefix of its file name) for a source that spans several.

        Parameters
        ----------
        chapter : str, optional
            Docname, one of :attr:`chapters`.

        Returns
        -------
        str
            The file name in ``book/ledger``.

        Raises
        ------
        TypeError
            ``chapter`` is not a str (a docname: not a number nor a path).
        ValueError
            ``chapter`` is not one of the source's chapters.
        """
        chapter = self.chapter if chapter is None else _text(chapter, "chapter")
        if chapter not in self.chapters:
            raise ValueError(f"chapter must be one of {list(self.chapters)}, got {shown(chapter)}")
        if len(self.chapters) == 1:
            return f"{self.key}.json"
        return f"{self.key}-{_number(chapter)}.json"


def _number(chapter: str) -> str:
    """A chapter's number: the prefix of its file name up to the first ``_`` (``"02"`` for a notebook ``02_name``)."""
    name = chapter.rsplit("/", 1)[-1]
    return name.split("_", 1)[0] if "_" in name else ""


#: The five sources in book order.
SOURCES: dict[str, Source] = constant({s.key: s for s in (
    Source("yang2012optimal", "Yang, Feng & Fan (2012)", "Optimal fusion set",
           "notebooks/01_optimal_fusion_set", 1),
    Source("lecture003", "Lecture notes (sections 2.1-2.7)", "Classic fusion algorithms",
           "notebooks/02_lecture_weighting", 2,
           ("notebooks/02_lecture_weighting", "notebooks/03_lecture_wavelets",
            "notebooks/04_lecture_biased_correlated")),
    Source("wang2024covariance", "Wang & Tang (2024)", "Covariance intersection",
           "notebooks/05_covariance_intersection", 5),
    Source("cn107330468b", "Chernoff-fusion patent CN107330468B (2021)", "Distributed Chernoff fusion",
           "notebooks/06_chernoff_fusion", 6),
    Source("shi2023time", "Shi, Suo & Ma (2023)", "Time registration",
           "notebooks/07_time_registration", 7),
)})
