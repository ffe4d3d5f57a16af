"""OTB sequence folders: ``<Seq>/img/0001.jpg ...`` plus ``<Seq>/groundtruth_rect.txt``.

Quirks of the OTB data handled here, each either resolved with a
:class:`SequenceWarning` that says what was done, or refused with a
:class:`SequenceError` naming the file:

- **Several targets** (Jogging, Skating2): ``groundtruth_rect.1.txt``,
  ``groundtruth_rect.2.txt``. ``target=k`` picks one; by default the lowest
  number is used with a warning. A sequence read from a numbered file is named
  ``<folder>-<k>`` (``Jogging-1``), as in the OTB toolkit and its results.
  Human4 has only ``groundtruth_rect.2.txt`` (and an empty, differently named
  ``groundtruth_rect1.txt``, ignored): it opens as ``Human4-2`` without warning.
- **5-digit frame names** (Board ``00001.jpg``) and numbering that does not
  start at 1 (BlurCar1 starts at ``0247.jpg``; David at ``0300.jpg`` when the
  folder holds only the benchmark's frames): frames are the image files in
  numeric order, ground-truth line ``k`` goes with the ``k``-th file.
- **Full image folders with more frames than the benchmark uses**: OTB runs
  David on frames 300-770 only, Diving, Football1, Freeman3 and Freeman4 on
  their first 215, 74, 460 and 283 frames; the ground truth covers just those.
  When such a folder has more images than ground-truth lines, the frames
  ``OTB_FIRST_FRAME[name] ...`` (by the number in the file name) are used, with
  a warning. For any other sequence, fewer lines than images means the
  trailing frames are not annotated (warning); more lines than images is an
  error (see :func:`smtmvt.data.sequence.align_groundtruth`).
- **A gap in the frame numbering** (``0049.jpg``, ``0051.jpg``) would shift
  every later box: SequenceError naming the missing file.
- Tiger1's ground truth covers all its 354 frames; the toolkit *evaluates*
  it from frame 6 on. That is an evaluation choice and is not applied here.
"""

from __future__ import annotations

import re
import warnings
from pathlib import Path

from .boxes import read_boxes
from .errors import SequenceError, SequenceWarning
from .frames import list_images
from .sequence import ImageSequence, align_groundtruth

__all__ = [
    "OTB_FIRST_FRAME",
    "GROUNDTRUTH_NAMES",
    "find_groundtruth",
    "groundtruth_targets",
    "is_otb_folder",
    "open_otb_sequence",
]

#: Plain ground-truth file names looked for in a sequence folder, in order.
GROUNDTRUTH_NAMES = ("groundtruth_rect.txt", "groundtruth.txt")
_NUMBERED = re.compile(r"groundtruth_rect\.(\d+)\.txt", re.IGNORECASE)

#: OTB sequences (lower-case name) whose full image folder has frames the benchmark
#: does not use -> number (as in the file names) of the first frame used. The
#: benchmark uses as many frames from there as the ground truth has lines.
OTB_FIRST_FRAME = {"david": 300, "diving": 1, "football1": 1, "freeman3": 1, "freeman4": 1}


def is_otb_folder(folder) -> bool:
    """True when ``folder`` has an ``img/`` sub-folder (the OTB layout)."""
    return (Path(folder) / "img").is_dir()


def groundtruth_targets(folder) -> dict:
    """Ground-truth files in ``folder``: ``{None: plain_file}`` or ``{k: groundtruth_rect.k.txt, ...}``.

    A plain file (``groundtruth_rect.txt``, else ``groundtruth.txt``) is
    reported alone when present; numbered files only when there is no plain
    one. Empty dict when there is none.
    """
    folder = Path(folder)
    for name in GROUNDTRUTH_NAMES:
        if (folder / name).is_file():
            return {None: folder / name}
    numbered = {}
    for p in folder.iterdir():
        m = _NUMBERED.fullmatch(p.name)
        if m and p.is_file():
            numbered[int(m.group(1))] = p
    return dict(sorted(numbered.items()))


def find_groundtruth(folder, target=None):
    """Pick the ground-truth file of ``folder``.

    Parameters
    ----------
    folder : path
    target : int, optional
        Use ``groundtruth_rect.<target>.txt``. Default: the plain file, else the
        lowest-numbered one (with a :class:`SequenceWarning` when there are
        several).

    Returns
    -------
    (Path or None, int or None)
        The file (None when the folder has none) and its target number (None
        for a plain file).
    """
    folder = Path(folder)
    if target is not None:
        path = folder / f"groundtruth_rect.{int(target)}.txt"
        if not path.is_file():
            found = [p.name for p in groundtruth_targets(folder).values()]
            raise SequenceError(
                f"{path} not found (target {target}); ground-truth files in {folder}: {found or 'none'}",
                path=path,
            )
        return path, int(target)
    files = groundtruth_targets(folder)
    if not files:
        return None, None
    k, path = next(iter(files.items()))
    if len(files) > 1:
        warnings.warn(
            f"{folder}: {len(files)} targets are annotated ({', '.join(p.name for p in files.values())}); "
            f"using {path.name}; pass target=<number> to choose another",
            SequenceWarning,
            stacklevel=3,
        )
    plain = [n for n in GROUNDTRUTH_NAMES if (folder / n).is_file()]
    if len(plain) > 1:
        warnings.warn(
            f"{folder}: both {plain[0]} and {plain[1]} exist; using {plain[0]}", SequenceWarning, stacklevel=3
        )
    return path, k


def _frame_numbers(files, img_dir: Path):
    """Numbers in the file names when every name is digits, else None; refuses gaps."""
    stems = [f.stem for f in files]
    if not all(s.isdigit() for s in stems):
        return None
    numbers = [int(s) for s in stems]
    for a, b, fa, fb in zip(numbers, numbers[1:], files, files[1:]):
        if b == a:
            raise SequenceError(f"{img_dir}: {fa.name} and {fb.name} are both frame {a}", path=img_dir)
        if b != a + 1:
            missing = str(a + 1).zfill(len(fa.stem)) + fa.suffix
            raise SequenceError(
                f"{img_dir}: frame file {missing} is missing (numbering jumps from {fa.name} to {fb.name}); "
                f"ground-truth lines after it would be matched to the wrong frames",
                path=img_dir / missing,
            )
    return numbers


def open_otb_sequence(folder, groundtruth=None, name=None, *, target=None) -> ImageSequence:
    """Open an OTB-layout folder ``folder/img/*`` (+ ground-truth file).

    Parameters
    ----------
    folder : path
        The sequence folder (holding ``img/``).
    groundtruth : path, optional
        A box file (1-based lines) to use instead of the folder's own.
    name : str, optional
        Default: the folder name, ``<folder>-<k>`` for target ``k``.
    target : int, optional
        Which ``groundtruth_rect.<k>.txt`` to use (see the module notes).

    Returns
    -------
    ImageSequence
        Ground truth (0-based) when a file was found or given, else None.

    Raises
    ------
    SequenceError
        No images in ``img/``, mixed image types, a gap in the frame numbering,
        an empty or malformed ground-truth file, more boxes than frames.
    """
    folder = Path(folder)
    img_dir = folder / "img"
    files = list_images(img_dir)
    if not files:
        raise SequenceError(f"no image files in {img_dir}", path=img_dir)
    if groundtruth is not None:
        gt_file, k = Path(groundtruth), None
    else:
        gt_file, k = find_groundtruth(folder, target)
    if name is None:
        name = folder.name if k is None else f"{folder.name}-{k}"
    numbers = _frame_numbers(files, img_dir)
    if gt_file is None:
        return ImageSequence(files, name, source=folder)

    boxes = read_boxes(gt_file)
    first = OTB_FIRST_FRAME.get(folder.name.casefold())
    if first is not None and numbers is not None and len(boxes) < len(files):
        last = first + len(boxes) - 1
        if numbers[0] <= first and last <= numbers[-1]:
            used = files[first - numbers[0] : last - numbers[0] + 1]
            warnings.warn(
                f"{gt_file}: {len(boxes)} boxes for {len(files)} images in {img_dir}; using "
                f"{used[0].name}..{used[-1].name} as the OTB benchmark does for {folder.name}",
                SequenceWarning,
                stacklevel=2,
            )
            files = used
    gt = align_groundtruth(boxes, len(files), groundtruth_file=gt_file, sequence=name, source=img_dir)
    return ImageSequence(files, name, gt, source=folder, groundtruth_file=gt_file)
