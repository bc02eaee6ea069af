"""The scikit-learn style estimator, with and without scikit-learn."""
import numpy as np
import pytest

import actionstring
from conftest import TOY_SETTINGS


def toy_data(toy_clips):
    return list(toy_clips), [c.label for c in toy_clips], [c.subject for c in toy_clips]


def test_fit_predict_score_and_parameters(toy_clips):
    X, y, groups = toy_data(toy_clips)
    estimator = actionstring.ActionStringClassifier(**TOY_SETTINGS)
    assert estimator.get_params()["pca"] == 8
    with pytest.raises(ValueError, match="not fitted"):
        estimator.predict(X)
    assert estimator.fit(X, y, groups=groups) is estimator
    assert list(estimator.classes_) == sorted(set(y))
    assert estimator.score(X, y) == pytest.approx(1.0)
    estimator.set_params(sigma=2.0, frame_rate=60.0)
    assert estimator.get_params()["sigma"] == 2.0 and estimator.frame_rate == 60.0
    with pytest.raises(ValueError, match="labels"):
        estimator.fit(X, y[:-1])


def test_arrays_in_place_of_clips(toy_clips):
    X = [np.asarray(c.positions, dtype=np.float64) for c in toy_clips]
    y = [c.label for c in toy_clips]
    estimator = actionstring.ActionStringClassifier(
        frame_rate=60.0, joint_names=toy_clips[0].joint_names, **TOY_SETTINGS)
    train = [i for i, c in enumerate(toy_clips) if c.subject not in ("toy4", "toy5")]
    test = [i for i, c in enumerate(toy_clips) if c.subject in ("toy4", "toy5")]
    estimator.fit([X[i] for i in train], [y[i] for i in train])
    assert estimator.score([X[i] for i in test], [y[i] for i in test]) >= 0.75


def test_arrays_of_a_rig_of_no_sdk_scale_their_bones_with_the_parents_given(toy_clips):
    X = [np.asarray(c.positions) for c in toy_clips]
    y = [c.label for c in toy_clips]
    names, parents = toy_clips[0].joint_names, toy_clips[0].parents
    bones = dict(TOY_SETTINGS, scale="bones")
    with pytest.raises(ValueError, match="skeleton's tree"):
        actionstring.ActionStringClassifier(frame_rate=60.0, joint_names=names, **bones).fit(X, y)
    estimator = actionstring.ActionStringClassifier(frame_rate=60.0, joint_names=names, parents=parents, **bones)
    assert estimator.get_params()["parents"] == parents
    assert estimator.fit(X, y).score(X, y) >= 0.9


def test_group_k_fold_cross_validation_by_hand(toy_clips):
    """Without scikit-learn: held-out subjects, a fresh estimator per fold from get_params()."""
    X, y, groups = toy_data(toy_clips)
    template = actionstring.ActionStringClassifier(**TOY_SETTINGS)
    scores = []
    for held_out in sorted(set(groups)):
        train = [i for i, g in enumerate(groups) if g != held_out]
        test = [i for i, g in enumerate(groups) if g == held_out]
        estimator = type(template)(**template.get_params())
        estimator.fit([X[i] for i in train], [y[i] for i in train], groups=[groups[i] for i in train])
        scores.append(estimator.score([X[i] for i in test], [y[i] for i in test]))
    assert len(scores) == 6 and np.mean(scores) >= 0.9


def test_scikit_learn_cross_val_score_with_group_k_fold(toy_clips):
    model_selection = pytest.importorskip("sklearn.model_selection", reason="scikit-learn is not installed")
    base = pytest.importorskip("sklearn.base")
    X, y, groups = toy_data(toy_clips)
    estimator = actionstring.ActionStringClassifier(**TOY_SETTINGS)
    scores = model_selection.cross_val_score(estimator, X, y, groups=groups, cv=model_selection.GroupKFold(3))
    assert len(scores) == 3 and np.mean(scores) >= 0.9
    clone = base.clone(estimator)
    assert clone.get_params() == estimator.get_params()


def test_decision_function_ranks_the_predicted_class_first(toy_clips):
    X, y, groups = toy_data(toy_clips)
    train = [i for i, g in enumerate(groups) if g not in ("toy4", "toy5")]
    test = [i for i, g in enumerate(groups) if g in ("toy4", "toy5")]
    estimator = actionstring.ActionStringClassifier(**TOY_SETTINGS)
    with pytest.raises(ValueError, match="not fitted"):
        estimator.decision_function(X)
    estimator.fit([X[i] for i in train], [y[i] for i in train], groups=[groups[i] for i in train])
    scores = estimator.decision_function([X[i] for i in test])
    assert scores.shape == (len(test), len(estimator.classes_))
    # Minus the model's label distances, columns in classes_ order; the best column is the prediction.
    for row, i in zip(scores, test):
        assert np.array_equal(row, -estimator.model_.label_distances(X[i]).astype(np.float64))
    predicted = estimator.predict([X[i] for i in test])
    assert list(estimator.classes_[scores.argmax(axis=1)]) == list(predicted)
    # Top-1 of the scores is the accuracy score() reports; the true class is within the top 2 at least as often.
    true = np.array([list(estimator.classes_).index(y[i]) for i in test])
    ranks = (scores > scores[np.arange(len(test)), true][:, None]).sum(axis=1)
    assert np.mean(ranks == 0) == pytest.approx(estimator.score([X[i] for i in test], [y[i] for i in test]))
    assert np.mean(ranks < 2) >= np.mean(ranks == 0)


def test_scikit_learn_top_k_accuracy_reads_the_decision_function(toy_clips):
    metrics = pytest.importorskip("sklearn.metrics", reason="scikit-learn is not installed")
    X, y, groups = toy_data(toy_clips)
    train = [i for i, g in enumerate(groups) if g not in ("toy4", "toy5")]
    test = [i for i, g in enumerate(groups) if g in ("toy4", "toy5")]
    estimator = actionstring.ActionStringClassifier(**TOY_SETTINGS).fit([X[i] for i in train],
                                                                       [y[i] for i in train])
    scores = estimator.decision_function([X[i] for i in test])
    top1 = metrics.top_k_accuracy_score([y[i] for i in test], scores, k=1, labels=estimator.classes_)
    assert top1 == pytest.approx(estimator.score([X[i] for i in test], [y[i] for i in test]))
    assert metrics.top_k_accuracy_score([y[i] for i in test], scores, k=2, labels=estimator.classes_) >= top1
