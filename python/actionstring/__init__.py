"""actionstring: real-time action recognition from skeleton motion.

The C++ library, bound: reading motion files, training a model of action
strings, evaluating it, and streaming frames through the same allocation-free
annotator a device runs. Nothing is reimplemented in Python.

    >>> import actionstring
    >>> clips = actionstring.read_clip_list("hdm05/train.tsv")
    >>> model = actionstring.train(clips, pca=24, velocity=1.0)
    >>> model.evaluate(actionstring.read_clip_list("hdm05/val.tsv"))["clip_accuracy"]
    >>> annotator = actionstring.Annotator(model)
    >>> result = annotator.push_frame(0.0, frame)   # frame: (joints, 3) float32, metres
"""
from __future__ import annotations

import json
import os
from typing import Any, Dict, Iterable, List, Optional, Sequence, Tuple, Union

import numpy as np

from . import _actionstring as _native
from ._actionstring import Clip, ReadError, Recording

__all__ = [
    "Clip",
    "ReadError",
    "Recording",
    "Model",
    "Annotator",
    "Classification",
    "read_clip",
    "read_clip_list",
    "read_recordings",
    "train",
    "training_settings",
    "ActionStringClassifier",
]

# The library's version (include/actionstring/version.hpp), written out so that
# tools read it without building the extension; a test holds it, pyproject.toml's
# and the extension's own to the same.
__version__ = "0.2.0"

PathLike = Union[str, "os.PathLike[str]"]


def read_clip(path: PathLike, *, rate: float = 0.0, scale: float = 0.0, up_axis: int = -1,
              roles: Optional[Sequence[str]] = None, skeleton: str = "", time_unit: str = "",
              body: int = -1, columns: str = "", up: Optional[Sequence[float]] = None,
              parents: Optional[Sequence[Optional[str]]] = None) -> Clip:
    """Reads one motion file (ASF/AMC with ``skeleton``, BVH, Kinect text, joint CSV,
    NTU RGB+D ``.skeleton``).

    ``rate`` is the frame rate of files without timing (0: the format's default),
    ``scale`` metres per file unit (0: the format's rule; a CSV's unit is read off
    the body's height, m, cm or mm, and said in ``clip.notes``), ``up_axis`` 0/1/2 (-1:
    the format's rule), ``roles`` the (root, left hip, right hip) joint names,
    ``time_unit`` a CSV's time unit ("s", "ms", "us"; default: its column's name,
    else the frame spacing), ``body`` which body of an NTU file (-1: the one that
    moves most), ``columns`` a CSV's layout when no spelling rule fits
    ("time=COL,JOINT=X:Y:Z,..."). ``up`` is the sensor's up direction (x, y, z) in
    the file's coordinates when it is known and tilted from the up axis (a Kinect's
    floor plane normal): every frame is turned upright as it is read, as
    ``Annotator(model, up=...)`` turns a device's frames. ``parents`` gives the
    skeleton's tree by name, one per joint in the file's order (None or "-" for a
    root), for a file that gives none and whose joints no Kinect SDK names (as
    ``--parents``); ``clip.parents`` shows the tree read. What the reader noticed
    is in ``clip.notes``. Raises ReadError naming the file, the line and what was
    expected (ValueError for an ``up`` that is not three numbers).
    """
    return _native._read_clip(os.fspath(path), rate, scale, up_axis, roles, skeleton, time_unit, body, columns, up,
                              parents)


def read_clip_list(path: PathLike, *, rate: float = 0.0, scale: float = 0.0, up_axis: int = -1,
                   roles: Optional[Sequence[str]] = None, up: Optional[Sequence[float]] = None,
                   parents: Optional[Sequence[Optional[str]]] = None) -> List[Clip]:
    """Reads a clip list (TSV with path, label, subject columns) and every clip it names,
    each with its ``label`` and ``subject``. A list's ``up`` column (X,Y,Z) gives each
    file's sensor up direction; ``up`` here is the one for lines without it. ``parents``
    is every file's tree by joint name, as ``read_clip`` takes it."""
    return _native._read_clip_list(os.fspath(path), rate, scale, up_axis, roles, up, parents)


def read_recordings(path: PathLike, *, rate: float = 0.0, scale: float = 0.0, up_axis: int = -1,
                    roles: Optional[Sequence[str]] = None, up: Optional[Sequence[float]] = None,
                    parents: Optional[Sequence[Optional[str]]] = None) -> List[Recording]:
    """Reads a list of labelled intervals of continuous recordings (TSV with path,
    label, subject, start and end columns, seconds; UTKinect's layout) as the
    recordings themselves: each file once, whole, with its intervals (``intervals``:
    (label, start, end)); every frame outside them is no action. ``read_clip_list``
    on the same list gives the intervals as clips. Give both to ``train``
    (``train(clips, recordings=...)``) and the model learns "no action" from the
    stretches between the intervals and chooses its online settings on the
    recordings streamed whole, as ``actionstring train`` does with such a list;
    ``Model.evaluate(clips, recordings=..., online=True)`` streams them whole as
    ``actionstring eval --online`` does. Reading settings as ``read_clip_list``'s.
    Raises ValueError for a list without intervals, ReadError for a file that
    cannot be read. A ``Recording(clip, intervals, subject=None)`` is built from a
    Clip of a whole stream and its (label, start, end) intervals."""
    return _native._read_recordings(os.fspath(path), rate, scale, up_axis, roles, up, parents)


def _recordings(recordings: Optional[Sequence[Recording]]) -> List[Recording]:
    out = list(recordings or [])
    for recording in out:
        if not isinstance(recording, Recording):
            raise ValueError(f"recordings expects Recording objects, got {type(recording).__name__}")
    return out


def training_settings() -> List[str]:
    """Names ``train`` accepts as keywords (dashes as underscores), as ``actionstring train`` takes them."""
    return [name.replace("-", "_") for name in _native._training_setting_names()
            if name not in ("rate", "roles", "time-unit", "length-unit", "parents", "body", "columns", "up")]


class Classification(tuple):
    """(label, distance, confidence): label is None when the clip is unknown."""

    __slots__ = ()

    def __new__(cls, label: Optional[str], distance: float, confidence: float):
        return super().__new__(cls, (label, distance, confidence))

    def __repr__(self) -> str:
        return f"Classification(label={self[0]!r}, distance={self[1]:.4g}, confidence={self[2]:.3f})"

    @property
    def label(self) -> Optional[str]:
        return self[0]

    @property
    def distance(self) -> float:
        return self[1]

    @property
    def confidence(self) -> float:
        return self[2]


class Model:
    """A trained model: its tables, labels and skeleton, and what can be done with them."""

    def __init__(self, native: "_native._Model", report: Optional[Dict[str, Any]] = None):
        self._native = native
        #: What training reported (representatives, characters, frames, the settings used).
        self.training_report: Dict[str, Any] = dict(report or {})

    # -- files ---------------------------------------------------------------
    @classmethod
    def load(cls, path: PathLike) -> "Model":
        """Loads a model artifact or blob (``actionstring train`` / ``codegen --blob``)."""
        return cls(_native._Model.load(os.fspath(path)))

    @classmethod
    def from_blob(cls, blob: bytes) -> "Model":
        """A model from blob bytes (checked by the runtime's own reader)."""
        return cls(_native._Model.from_blob(bytes(blob)))

    def save(self, path: PathLike) -> None:
        """Writes the model artifact (checksummed text) that every tool reads."""
        self._native.save(os.fspath(path))

    def save_blob(self, path: PathLike) -> None:
        """Writes the binary blob a program loads at run time (C API, C#)."""
        self._native.save_blob(os.fspath(path))

    def to_blob(self) -> bytes:
        return self._native.to_blob()

    def write_header(self, path: PathLike, namespace: str = "actionstring_model") -> None:
        """Writes a C++ header of constexpr tables for firmware (as ``actionstring codegen``)."""
        self._native.write_header(os.fspath(path), namespace)

    # -- what it is ------------------------------------------------------------
    @property
    def label_names(self) -> List[str]:
        return list(self._native.label_names)

    @property
    def joint_names(self) -> List[str]:
        """The input skeleton, in frame order."""
        return list(self._native.joint_names)

    @property
    def representative_count(self) -> int:
        return int(self._native.representative_count)

    @property
    def character_count(self) -> int:
        return int(self._native.character_count)

    @property
    def component_count(self) -> int:
        return int(self._native.component_count)

    @property
    def feature_dim(self) -> int:
        return int(self._native.feature_dim)

    @property
    def string_rate_hz(self) -> float:
        return float(self._native.string_rate_hz)

    @property
    def table_bytes(self) -> int:
        return int(self._native.table_bytes)

    @property
    def online_settings(self) -> Dict[str, float]:
        """The online settings the model carries: the segmenter's, the events'
        shortest action and the label lead (``settle``, ``settle_stable``,
        ``min_action`` and ``label_lead`` in seconds)."""
        return dict(self._native.online_settings)

    def state_bytes(self, **online: Any) -> int:
        """Bytes of annotator state this model needs with these settings (firmware sizing)."""
        return int(self._native.state_bytes(online))

    # -- use -------------------------------------------------------------------
    def classify(self, clip: Clip) -> Classification:
        """Classifies one clip by its action string (the runtime's kNN over representatives)."""
        return Classification(*self._native.classify(clip))

    def label_distances(self, clip: Clip) -> np.ndarray:
        """Each label's score for a clip, in ``label_names`` order (float32): the
        distance of its nearest representative with what the clip's votes,
        exemplars and descriptors add to it, the numbers ``classify`` decides by
        (smaller is nearer; inf where nothing compares). For top-k accuracy, ROC
        curves or fusing with another classifier. With one neighbour the
        smallest is the nearest label; the unknown distance and the learned
        rejection bounds apply only in ``classify``."""
        return self._native.label_distances(clip)

    def predict(self, clips: Iterable[Clip]) -> List[Optional[str]]:
        return [self.classify(clip).label for clip in clips]

    def evaluate(self, clips: Sequence[Clip], *, train: Optional[Sequence[Clip]] = None, online: bool = False,
                 seed: int = 1, name: str = "<python>", perturb: str = "",
                 recordings: Optional[Sequence[Recording]] = None, **online_settings: Any) -> Dict[str, Any]:
        """The figures ``actionstring eval --json`` reports, computed by the same code:
        clip accuracy, per-class precision and recall, per-subject accuracy
        (``per_subject``), the model's top-1 to top-3 accuracy (``top_k``),
        confusion, predictions; with
        ``train`` the baselines on the same split (DTW 1-NN among them); with
        ``online`` the streaming figures over the clips concatenated per subject
        (``report["online"]``: each rule's, the settled rule's frames by class in
        ``settled["per_class_frames"]`` and ``settled["frame_confusion"]``, and each
        subject's stream alone in ``per_stream``).
        ``perturb`` changes the evaluated clips (never ``train``) as ``eval --perturb``
        does, e.g. ``"scale=0.7,noise=0.01"``; a bad spec raises ValueError.
        ``recordings`` (``read_recordings()``; with ``online`` only) are streamed whole
        instead of the clips joined, as ``eval --online`` streams a list of intervals:
        the frames outside every interval are scored as no action, beside "unknown
        everywhere"; ``clips`` are then the intervals, for the clip figures."""
        whole = _recordings(recordings)
        if whole and not online:
            raise ValueError("recordings are streamed whole: give online=True")
        text = self._native._evaluate_json(list(clips), list(train or []), online, seed, online_settings, name,
                                           perturb, whole)
        return json.loads(text)

    def annotate(self, clip: Clip, **online_settings: Any) -> List[Dict[str, Any]]:
        """The timeline of settled labels of a clip streamed frame by frame, as
        ``actionstring annotate --json`` prints it (start, end, label, confidence)."""
        return list(self._native.annotate(clip, online_settings))

    def __repr__(self) -> str:
        return (f"<Model: {len(self.label_names)} labels, {len(self.joint_names)} joints, "
                f"{self.representative_count} representatives, {self.character_count} characters>")


# What `actionstring train` does not count as a tuned setting (codegen/train.cpp): given
# alone, self-tuning still runs, and its folds train with them.
_NOT_TUNED = frozenset({"pose_joints", "max_representative_chars", "max_representative_share", "reject",
                        "reject_keep", "latency_budget"})


def train(clips: Sequence[Clip], *, config: Optional[PathLike] = None, tune: Union[bool, str, None] = None,
          recordings: Optional[Sequence[Recording]] = None, **settings: Any) -> Model:
    """Trains a model on labelled clips with the C++ training pipeline.

    Settings are those of ``actionstring train`` with underscores for dashes
    (``pca=24, velocity=1.0, string_rate=15, scale="bones"``; see
    ``training_settings()``); ``config`` is a settings file as ``train --config``
    reads it (``models/*.config``), applied first. With neither given and
    ``tune`` left None, training tunes itself as ``actionstring train`` does: the
    clip settings that matter most by leave-one-subject-out cross-validation over
    the clips' subjects, then the online ones (the segmenter's, the window's
    directions, early settling, the events' shortest action and the label
    lead) by streaming each held-out
    subject's clips joined. The
    model's ``training_report["tuning"]`` then holds the clip search's table
    (each setting tried with its fold mean, the folds' mean signed margin that
    breaks ties, and whether it was kept) and the folds of the choice, and
    ``training_report["online_tuning"]`` the online search's.
    ``tune="online"`` keeps the clip settings given (``config`` and keywords)
    and chooses only the online ones that way (``train --tune-online``).
    ``latency_budget=S`` (seconds) makes that search keep only online settings
    whose mean detection latency on the folds is at most S, trying shorter
    settle delays too. As on the command line, the choices that are not tuned
    settings (``pose_joints``, the cost bounds ``max_representative_chars`` and
    ``max_representative_share``, ``reject`` and ``reject_keep``, the latency
    budget) leave self-tuning on: the folds train with them.
    ``recordings`` (``read_recordings()`` of the list ``clips`` were read from) are
    the continuous recordings the clips are intervals of: as ``actionstring train``
    on such a list, their stretches outside every interval (1 s or longer) teach the
    model "no action" (its votes and, with exemplars, its centres), and the online
    search streams each held-out subject's recordings whole instead of its clips
    joined; ``training_report["no_action_stretches"]`` counts the stretches.
    """
    clips = list(clips)
    if not clips:
        raise ValueError("no clips to train on")
    for clip in clips:
        if not isinstance(clip, Clip):
            raise ValueError(f"train expects Clip objects, got {type(clip).__name__}")
        if not clip.label:
            raise ValueError(f"{clip.source}: no label")
    tune_online = tune == "online"
    if tune_online:
        tune = False
    elif tune is None:  # constraints on self-tuning (as `actionstring train` has them) do not replace it
        tune = not (settings.keys() - _NOT_TUNED) and config is None
    elif not isinstance(tune, bool):
        raise ValueError(f"tune expects True, False, None or 'online', got {tune!r}")
    native, report = _native._train(clips, settings, bool(tune), "" if config is None else os.fspath(config),
                                    tune_online, _recordings(recordings))
    return Model(native, report)


class Annotator:
    """The runtime's per-frame annotator on a model: frames in, labels out.

    ``push_frame(time_s, positions)`` takes a frame's time in seconds and its
    (joints, 3) positions in metres in the model's joint order; a C-contiguous
    float32 array is read in place. It returns a dict: ``status`` (``ok``,
    ``stream_restarted`` or why the frame was rejected: ``non_finite_input``,
    ``tracking_lost``, ...), ``accepted``, ``characters``, ``settled`` (a list of
    (character, time_s, label) for every character whose label became final with
    this frame; label None for no action; time_s is where the label applies from:
    the character's tick less the model's ``label_lead``, as the feature's motion
    looks back and actions show in it late), ``flushed`` (when the frame restarted
    the stream after a gap: the ended stream's last characters, whose labels
    became final with the restart, as ``settled``'s), ``live_label`` (the newest guess),
    ``live_margin`` (how far it leads every other label, in units of the model's
    character distances: its confidence; ``inf`` when nothing else can explain the stream) and
    ``events``: each action once when it starts and once when it ends (dicts
    with ``event``, ``label``, ``start``, ``end`` in seconds and ``confidence``;
    an action shorter than ``min_action`` seconds, the model's own by default, is
    flicker and never reported). ``flush()`` ends the stream and returns the last events.
    Online settings (``settle``, ``settle_stable``: a label also final once every
    best explanation has given it that long, ``segment_penalty``, ``unknown_cost``, ...)
    override the model's own; ``window_rule=True`` also runs the paper's rule
    (``label``, ``confidence``). ``spread_work=True`` spreads each character's
    work (the encoder's projection, GMM and tree, and the segmenter's) over the
    frames until the next character, for a flat cost per frame: the same
    settled labels and events, each up to one string period later;
    ``finish_work()`` does what is left at once. ``up=(x, y, z)`` is the sensor's
    up direction in the positions' coordinates, when the device knows it and it
    differs from the model's up axis (a Kinect's floor plane normal, an IMU's
    gravity): every frame is turned to put it along the axis, so a sensor mounted
    higher or lower than the training one gives the poses it gave.
    ``max_pose_speed`` (metres per second, 3 unless given; 0: never): a pose that
    moved faster since the previous frame (the mean over its coordinates), and by
    three times what the stream's frames typically move, jumped (the tracker lost
    and found the body, or clips were joined), and its motion starts again from it.
    """

    def __init__(self, model: Model, **online_settings: Any):
        self.model = model
        self._native = _native._Annotator(model._native, online_settings)

    def push_frame(self, time_s: float, positions: np.ndarray) -> Dict[str, Any]:
        return self._native.push_frame(float(time_s), positions)

    def finish_work(self) -> Dict[str, Any]:
        """With ``spread_work=True``: finishes the work of the characters in
        progress now, and returns what a frame returns (``settled``, ``events``,
        ``live_label``, ``live_margin``); e.g. before reading the labels at the
        end of a stream, or before a pause in the frames."""
        return dict(self._native.finish_work())

    def flush(self) -> List[Dict[str, Any]]:
        """Ends the stream: characters not yet settled take their labels (then in
        ``flushed()``), a running action ends; returns those events. The next
        frame starts a new stream."""
        return list(self._native.flush())

    def flushed(self) -> List[Tuple[int, float, Any]]:
        """The labels the stream that ended with the last ``push_frame()`` (a
        restart after a gap: its ``flushed``) or ``flush()`` gave its last
        characters, which no ``settled`` list reported: (character, time_s,
        label) as ``settled``'s, on the ended stream's clock."""
        return list(self._native.flushed())

    def reset(self) -> None:
        """Starts another stream."""
        self._native.reset()

    @property
    def live_label(self) -> Optional[str]:
        return self._native.live_label

    @property
    def live_margin(self) -> float:
        """How far the live label leads every other label (its confidence)."""
        return self._native.live_margin

    @property
    def label(self) -> Optional[str]:
        """The paper's window rule (needs window_rule=True)."""
        return self._native.label

    @property
    def confidence(self) -> float:
        return float(self._native.confidence)

    @property
    def characters(self) -> int:
        return int(self._native.characters)

    @property
    def settle_chars(self) -> int:
        return int(self._native.settle_chars)

    @property
    def state_bytes(self) -> int:
        """Bytes of state the annotator holds for its model (what a device would reserve)."""
        return int(self._native.state_bytes)


from .estimator import ActionStringClassifier  # noqa: E402  (needs the names above)
