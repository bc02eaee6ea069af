"""A scikit-learn style estimator over the actionstring model (scikit-learn not required)."""
from __future__ import annotations

from typing import Any, Dict, Optional, Sequence

import numpy as np

from . import Clip, Model, train


class ActionStringClassifier:
    """Classifies motion clips by action strings: ``fit(X, y, groups=...)``, ``predict``, ``score``.

    ``X`` holds Clip objects, or arrays of shape (frames, joints, 3) in metres taken
    at ``frame_rate`` with ``joint_names`` (Kinect v1, Kinect v2 or Azure Kinect names
    when omitted and the joint count is 20, 25 or 32) and ``parents``, each joint's parent (-1 at the root), for
    a rig that is not a Kinect SDK's (whose tree comes with its names); bone-length
    scaling needs one. ``groups`` are the subjects: with no training settings
    given, training tunes itself by leave-one-subject-out cross-validation over them.
    Every other keyword is a training setting of ``actionstring.train``.

    It follows scikit-learn's conventions (``get_params``/``set_params``,
    ``classes_``, ``fit`` returning self), so ``cross_val_score`` with ``GroupKFold``
    and ``clone`` work when scikit-learn is installed; nothing here imports it.
    """

    _estimator_type = "classifier"

    def __init__(self, frame_rate: float = 30.0, joint_names: Optional[Sequence[str]] = None,
                 tune: Optional[bool] = None, parents: Optional[Sequence[int]] = None, **settings: Any):
        self.frame_rate = frame_rate
        self.joint_names = joint_names
        self.parents = parents
        self.tune = tune
        self.settings: Dict[str, Any] = dict(settings)

    # -- scikit-learn's parameter protocol --------------------------------------
    def get_params(self, deep: bool = True) -> Dict[str, Any]:
        params = {"frame_rate": self.frame_rate, "joint_names": self.joint_names, "tune": self.tune,
                  "parents": self.parents}
        params.update(self.settings)
        return params

    def set_params(self, **params: Any) -> "ActionStringClassifier":
        for key, value in params.items():
            if key in ("frame_rate", "joint_names", "tune", "parents"):
                setattr(self, key, value)
            else:
                self.settings[key] = value
        return self

    def __repr__(self) -> str:
        args = ", ".join(f"{k}={v!r}" for k, v in self.get_params().items() if v is not None)
        return f"ActionStringClassifier({args})"

    # -- data ------------------------------------------------------------------
    def _clips(self, X: Sequence[Any], y: Optional[Sequence[Any]] = None,
               groups: Optional[Sequence[Any]] = None) -> list:
        if isinstance(X, np.ndarray) and X.dtype != object and X.ndim == 4:
            X = list(X)  # (clips, frames, joints, 3): one clip per row
        clips = []
        for i, item in enumerate(X):
            label = "" if y is None else str(y[i])
            subject = "all" if groups is None else str(groups[i])
            if isinstance(item, Clip):
                clip = item.relabelled(label or item.label, subject if groups is not None else item.subject)
            else:
                clip = Clip(np.asarray(item), frame_rate=self.frame_rate, joint_names=self.joint_names,
                            label=label, subject=subject, source=f"<X[{i}]>", parents=self.parents)
            clips.append(clip)
        return clips

    # -- estimator -------------------------------------------------------------
    def fit(self, X: Sequence[Any], y: Sequence[Any], groups: Optional[Sequence[Any]] = None
            ) -> "ActionStringClassifier":
        if len(X) != len(y):
            raise ValueError(f"X has {len(X)} clips but y has {len(y)} labels")
        if groups is not None and len(groups) != len(y):
            raise ValueError(f"groups has {len(groups)} entries for {len(y)} clips")
        self.model_: Model = train(self._clips(X, y, groups), tune=self.tune, **self.settings)
        self.classes_ = np.array(self.model_.label_names, dtype=object)
        return self

    def predict(self, X: Sequence[Any]) -> np.ndarray:
        """Labels (None for a clip too far from every representative)."""
        if not hasattr(self, "model_"):
            raise ValueError("this ActionStringClassifier is not fitted yet: call fit first")
        return np.array(self.model_.predict(self._clips(X)), dtype=object)

    def decision_function(self, X: Sequence[Any]) -> np.ndarray:
        """Scores of shape (clips, classes), columns in ``classes_`` order: minus
        each label's distance (``Model.label_distances``), so larger is more
        likely, as scikit-learn's ranking metrics (``top_k_accuracy_score``,
        ``roc_auc_score``) expect; -inf where nothing compares."""
        if not hasattr(self, "model_"):
            raise ValueError("this ActionStringClassifier is not fitted yet: call fit first")
        clips = self._clips(X)
        scores = np.empty((len(clips), len(self.classes_)), dtype=np.float64)
        for i, clip in enumerate(clips):
            scores[i] = -np.asarray(self.model_.label_distances(clip), dtype=np.float64)
        return scores

    def score(self, X: Sequence[Any], y: Sequence[Any]) -> float:
        """Clip accuracy: the share of clips whose predicted label is y."""
        predicted = self.predict(X)
        return float(np.mean([p == str(t) for p, t in zip(predicted, y)]))
