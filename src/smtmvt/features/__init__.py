"""Feature extraction for SMTMVT: Tan-Triggs normalization, the paper's four views and a coarse one.

Per frame the tracker normalizes the gray frame once with :func:`tan_triggs`,
warps every candidate into a :class:`Patches` object and calls
:func:`extract_views`, which returns one ``(d_k, n)`` float32 matrix per view
with zero-mean, unit-L2 columns. Template dictionaries are built from template
patches by the same call. All views are batched over the patches with numpy.

Views (``available_views()`` order) and their dimensions at the defaults
(32x32 feature patches):

* ``intensity`` -- flattened Tan-Triggs template, ``th * tw`` (see
  :func:`intensity_template_size`);
* ``color`` -- soft-binned 16-bin histogram per RGB channel, 48
  (16 for gray frames);
* ``hog`` -- 9 orientations, 8x8 px cells, 2x2 blocks, L2-Hys, 324
  (equal to ``skimage.feature.hog``);
* ``lbp`` -- uniform LBP (P = 8, R = 1, as ``skimage.feature.local_binary_pattern``)
  histograms over a 4x4 grid of cells, 160.
* ``coarse`` -- the gray patch after Tan-Triggs' gamma, less its blur, in
  2x2 blocks (:mod:`smtmvt.features.coarse`), 256; not one of the paper's
  views (``DEFAULT_VIEWS`` are the paper's four).
"""

from .intensity import intensity_template_size
from .tan_triggs import tan_triggs
from .views import (
    DEFAULT_VIEWS,
    Patches,
    available_views,
    extract_views,
    normalize_columns,
    register_view,
)

__all__ = [
    "DEFAULT_VIEWS",
    "Patches",
    "available_views",
    "extract_views",
    "intensity_template_size",
    "normalize_columns",
    "register_view",
    "tan_triggs",
]
