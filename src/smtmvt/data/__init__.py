"""Reading sequences, box files, OTB benchmark folders and attribute tables.

Conventions (project-wide):

- Boxes in the Python API are ``(x, y, w, h)`` float, **0-based** pixels. Box
  files on disk (OTB ``groundtruth_rect.txt``, result files) are **1-based**:
  ``api_box = file_box - (1, 1, 0, 0)``.
- Frames are ``uint8``/``uint16`` arrays, ``(H, W)`` or ``(H, W, 3)`` **RGB**.

Main entry points::

    seq = open_sequence("otb/David")          # OTB folder, video, image folder or glob
    seq.first_box                             # 0-based (x, y, w, h)
    for frame in seq: ...                     # lazy
    boxes = read_boxes("result.txt")          # (m, 4) 0-based
    write_boxes("result.txt", boxes)          # 1-based on disk, atomic
    items = open_dataset("otb", on_error="collect")
    attrs = load_attributes("anno/att")       # {"basketball": ("IV", "OCC", ...)}
"""

from .atomic import write_bytes_atomic, write_text_atomic
from .attributes import ATTRIBUTE_NAMES, ATTRIBUTES, OTB_FLAG_ORDER, attributes_of, load_attributes
from .boxes import parse_boxes, read_boxes, write_boxes
from .dataset import list_dataset, open_dataset
from .errors import SequenceError, SequenceWarning
from .frames import IMAGE_EXTENSIONS, read_frame
from .layouts import ABSENT_RULES, detect_layout
from .names import canonical_name, lookup, name_clashes, natural_key
from .otb import OTB_FIRST_FRAME, open_otb_sequence
from .scores import read_scores, write_scores
from .sequence import ArraySequence, ImageSequence, Sequence
from .sources import open_sequence
from .video import VIDEO_EXTENSIONS, VideoSequence

__all__ = [
    "ABSENT_RULES",
    "ATTRIBUTES",
    "ATTRIBUTE_NAMES",
    "ArraySequence",
    "IMAGE_EXTENSIONS",
    "ImageSequence",
    "OTB_FIRST_FRAME",
    "OTB_FLAG_ORDER",
    "Sequence",
    "SequenceError",
    "SequenceWarning",
    "VIDEO_EXTENSIONS",
    "VideoSequence",
    "attributes_of",
    "canonical_name",
    "detect_layout",
    "list_dataset",
    "load_attributes",
    "lookup",
    "name_clashes",
    "natural_key",
    "open_dataset",
    "open_otb_sequence",
    "open_sequence",
    "parse_boxes",
    "read_boxes",
    "read_frame",
    "read_scores",
    "write_boxes",
    "write_scores",
    "write_bytes_atomic",
    "write_text_atomic",
]
