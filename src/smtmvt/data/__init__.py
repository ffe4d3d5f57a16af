"""Reading frames and box files.

Conventions (project-wide):

- Boxes in the Python API are ``(x, y, w, h)`` float, **0-based** pixels. Box
  files on disk (OTB ``groundtruth_rect.txt``, result files) are **1-based**:
  ``api_box = file_box - (1, 1, 0, 0)``.
- Frames are ``uint8``/``uint16`` arrays, ``(H, W)`` or ``(H, W, 3)`` **RGB**.
"""

from .boxes import parse_boxes, read_boxes, write_boxes
from .errors import SequenceError, SequenceWarning
from .frames import IMAGE_EXTENSIONS, read_frame
from .names import lookup, natural_key

__all__ = [
    "IMAGE_EXTENSIONS",
    "SequenceError",
    "SequenceWarning",
    "lookup",
    "natural_key",
    "parse_boxes",
    "read_boxes",
    "read_frame",
    "write_boxes",
]
