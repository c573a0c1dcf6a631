"""Per-chapter helpers of the book: table assembly, figure recipes and the claims of each source.

One module per chapter (``ofs``: Yang, Feng & Fan 2012; ``ci``: Wang & Tang 2024;
``time_registration``: Shi, Suo & Ma 2023; ``lecture``: the lecture notes; and so on). Each builds what its notebook displays from
results computed by the algorithm and scenario packages, and its ``claims`` function fills the
claims ledger (:mod:`fusion.book.ledger`). Nothing here is imported by the algorithms.
"""
