r"""Chernoff fusion of densities (patent CN107330468B, steps D-I), rebuilt.

The Chernoff fusion (generalised covariance intersection, exponential mixture density) of
densities :math:`p_1, \dots, p_N` with exponent weights :math:`\varepsilon` on the simplex
:math:`\Delta = \{\varepsilon_i \ge 0, \sum_i \varepsilon_i = 1\}` is

.. math:: p_\varepsilon(x) = \frac{\prod_i p_i(x)^{\varepsilon_i}}{Z(\varepsilon)}, \qquad
          Z(\varepsilon) = \int \prod_i p_i(x)^{\varepsilon_i}\,dx \le 1,

and the Chernoff criterion picks :math:`\varepsilon^* = \arg\min_\Delta \log Z(\varepsilon)`
(Hurley 2002). For Gaussians it is covariance intersection
(:func:`chernoff_fuse_gaussians`). For Gaussian mixtures the power of a sum is replaced by the
sum of powers, the "first-order approximation" (:func:`first_order_fusion`), whose normaliser bounds
:math:`Z` from above. The patent's steps E-I (:func:`fuse_mixtures`) correct the approximation
by importance sampling and choose :math:`\varepsilon` on the samples.

Every formula of the patent's claims is missing from the source text; the equations here are
the chapter's reconstruction (labels ``eq-chf-*`` in :doc:`ch. 6 </notebooks/06_chernoff_fusion>`).

Modules:

gaussian
    Chernoff fusion of Gaussians (covariance intersection), its closed forms and weights.
mixture
    Chernoff fusion of Gaussian mixtures: the first-order approximation and the importance-sampling
    pipeline, one problem (:func:`fuse_mixtures`) or many at once (:func:`fuse_mixtures_batch`).

The simplex optimisers live in :mod:`fusion.optimise.simplex` and are re-exported here.

References
----------
* Chernoff, H. (1952). A measure of asymptotic efficiency for tests of a hypothesis based on
  the sum of observations. *Annals of Mathematical Statistics*, 23(4), 493-507.
* Julier, S. J., & Uhlmann, J. K. (1997). A non-divergent estimation algorithm in the presence
  of unknown correlations. *Proceedings of the 1997 American Control Conference*.
* Hurley, M. B. (2002). An information theoretic justification for covariance intersection and
  its generalization. *Proceedings of the 5th International Conference on Information Fusion*.
* Julier, S. J. (2006). An empirical study into the use of Chernoff information for robust,
  distributed fusion of Gaussian mixture models. *Proceedings of the 9th International
  Conference on Information Fusion*.
* University of Electronic Science and Technology of China (2021). Multi-sensor distributed
  data fusion method based on the Chernoff fusion criterion. Patent CN107330468B.
"""

from fusion._public import name_by_package
from fusion.estimates.chernoff.gaussian import *  # noqa: F403
from fusion.estimates.chernoff.gaussian import __all__ as _gaussian_all
from fusion.estimates.chernoff.mixture import *  # noqa: F403
from fusion.estimates.chernoff.mixture import __all__ as _mixture_all
from fusion.optimise.simplex import check_simplex, minimise_on_simplex

__all__ = [*_gaussian_all, *_mixture_all, "check_simplex", "minimise_on_simplex"]

name_by_package(globals())
