"""Continuous recordings with labelled intervals: read, trained on and streamed whole, as the CLI does."""
import json

import numpy as np
import pytest

import actionstring
from conftest import ROOT, TOY_SETTINGS, data_dir, run_cli

STILL_S = 1.5  # the stretch of no action before each action and after the last


def toy_recordings(clips):
    """One recording per subject: its toy clips in order, each after STILL_S of its first pose held
    (no action), and STILL_S of the last pose after the last. Intervals are the clips' spans."""
    by_subject = {}
    for clip in clips:
        by_subject.setdefault(clip.subject, []).append(clip)
    recordings = []
    for subject, own in sorted(by_subject.items()):
        period = float(own[0].times[1] - own[0].times[0])
        still = int(round(STILL_S / period))
        frames, intervals = [], []
        for clip in own:
            positions = np.asarray(clip.positions)
            frames.append(np.repeat(positions[:1], still, axis=0))
            start = sum(len(f) for f in frames) * period
            frames.append(positions)
            intervals.append((clip.label, start, start + (len(positions) - 1) * period))
        frames.append(np.repeat(np.asarray(own[-1].positions)[-1:], still, axis=0))
        positions = np.concatenate(frames).astype(np.float32)
        whole = actionstring.Clip(positions, times=np.arange(len(positions)) * period,
                                  joint_names=own[0].joint_names, parents=list(own[0].parents), up_axis=own[0].up_axis,
                                  subject=subject, source=f"recording_{subject}")
        recordings.append(actionstring.Recording(whole, intervals))
    return recordings


@pytest.fixture(scope="module")
def toy_set(toy_clips):
    clips = [c for c in toy_clips if c.subject in ("toy0", "toy1", "toy2")]
    return clips, toy_recordings(clips)


def test_a_recording_keeps_its_clip_intervals_and_subject(toy_set):
    clips, recordings = toy_set
    first = recordings[0]
    assert first.subject == "toy0" and first.source == "recording_toy0"
    own = [c for c in clips if c.subject == "toy0"]
    assert len(first.intervals) == len(own)
    assert [label for label, _, _ in first.intervals] == [c.label for c in own]
    assert all(start < end for _, start, end in first.intervals)
    assert first.clip.frame_count == first.frame_count and first.clip.label == ""
    assert first.duration > sum(c.duration for c in own) + STILL_S * len(own)
    assert "intervals" in repr(first)


def test_training_on_recordings_learns_no_action_from_the_stretches_between(toy_set):
    clips, recordings = toy_set
    with_recordings = actionstring.train(clips, recordings=recordings, **TOY_SETTINGS)
    again = actionstring.train(clips, recordings=recordings, **TOY_SETTINGS)
    without = actionstring.train(clips, **TOY_SETTINGS)
    # A stretch of STILL_S before every action and after the last, each longer than the 1 s minimum.
    assert with_recordings.training_report["no_action_stretches"] == len(clips) + len(recordings)
    assert without.training_report["no_action_stretches"] == 0
    assert with_recordings.to_blob() == again.to_blob()
    assert with_recordings.to_blob() != without.to_blob()


def test_online_tuning_streams_the_recordings_whole(toy_set):
    clips, recordings = toy_set
    tuned = actionstring.train(clips, recordings=recordings, tune="online", **TOY_SETTINGS)
    rows = tuned.training_report["online_tuning"]["settings"]
    # Only recordings have stretches of no action to weigh a flat "no action" cost on.
    assert any("unknown-cost 0," in row["settings"] for row in rows)
    plain = actionstring.train(clips, tune="online", **TOY_SETTINGS)
    assert all("unknown-cost inf" in row["settings"] for row in plain.training_report["online_tuning"]["settings"])


def test_evaluating_recordings_streams_them_whole_with_their_no_action(toy_set):
    clips, recordings = toy_set
    model = actionstring.train(clips, recordings=recordings, **TOY_SETTINGS)
    report = model.evaluate(clips, recordings=recordings, online=True)
    assert report["online"]["streams"] == "recordings"
    settled = report["online"]["settled"]
    assert settled["no_action_frames"] > 0
    assert 0.0 < settled["unknown_everywhere_accuracy"] < 1.0
    # Each recording alone: its own share of no-action frames, pooling to the whole's.
    streams = report["online"]["per_stream"]
    assert len(streams) == len(recordings)
    for stream in streams:
        assert stream["unknown_everywhere_accuracy"] == pytest.approx(stream["no_action_frames"] / stream["frames"])
    assert sum(s["unknown_everywhere_accuracy"] * s["frames"] for s in streams) == pytest.approx(
        settled["unknown_everywhere_accuracy"] * settled["frames"])
    joined = model.evaluate(clips, online=True)["online"]
    assert joined["streams"] == "concatenated clips"
    assert joined["settled"]["no_action_frames"] == 0


def test_bad_recordings_are_refused(toy_set, toy_clips, tmp_path):
    clips, recordings = toy_set
    whole = recordings[0].clip
    with pytest.raises(ValueError, match="start must be finite and before end"):
        actionstring.Recording(whole, [("spread", 2.0, 1.0)])
    with pytest.raises(ValueError, match="needs a label"):
        actionstring.Recording(whole, [("", 0.0, 1.0)])
    with pytest.raises(ValueError, match=r"\(label, start, end\)"):
        actionstring.Recording(whole, [("spread", 0.0)])
    with pytest.raises(ValueError, match="two numbers of seconds"):
        actionstring.Recording(whole, [("spread", "soon", 1.0)])
    with pytest.raises(ValueError, match="at least one labelled interval"):
        actionstring.Recording(whole, [])
    with pytest.raises(ValueError, match="Recording objects"):
        actionstring.train(clips, recordings=[whole], **TOY_SETTINGS)
    model = actionstring.train(clips, **TOY_SETTINGS)
    with pytest.raises(ValueError, match="online=True"):
        model.evaluate(clips, recordings=recordings)
    # A list of clips (no start and end columns) names no recordings.
    listed = tmp_path / "clips.tsv"
    csv = tmp_path / "one.csv"
    csv.write_text("time,root_x,root_y,root_z\n0,0,1,0\n0.1,0,1,0\n")
    listed.write_text(f"path\tlabel\tsubject\n{csv}\tstand\ts1\n")
    with pytest.raises(ValueError, match="gives no intervals"):
        actionstring.read_recordings(listed)


def test_overlapping_intervals_are_noted_and_their_shared_frames_go_to_the_later_start(toy_set, tmp_path):
    clips, recordings = toy_set
    whole = recordings[0].clip
    end = float(whole.times[-1])
    nested = actionstring.Recording(whole, [("outer", 0.0, end), ("inner", 1.0, 2.0)])
    assert len(nested.notes) == 1
    assert "overlap by 1.000 s" in nested.notes[0] and "count as inner, the one that starts later" in nested.notes[0]
    assert actionstring.Recording(whole, [("a", 0.0, 1.0), ("b", 1.0, 2.0)]).notes == []  # back to back
    # Read from a list, the note names both list lines.
    csv = tmp_path / "walk.csv"
    csv.write_text("time,root_x,root_y,root_z\n" + "".join(f"{t / 10},0,1,0\n" for t in range(40)))
    listed = tmp_path / "intervals.tsv"
    listed.write_text(f"path\tlabel\tsubject\tstart\tend\n{csv}\tpush\ts1\t0.5\t3.5\n{csv}\tthrow\ts1\t1\t1.5\n")
    (recording,) = actionstring.read_recordings(listed)
    assert len(recording.notes) == 1
    note = recording.notes[0]
    assert note.startswith("walk.csv: intervals push 0.500-3.500 s (list line 2) and throw 1.000-1.500 s (list line 3)")
    assert "count as throw" in note


@pytest.fixture(scope="module")
def utkinect_lists(cli, tmp_path_factory):
    labels = data_dir() / "utkinect" / "actionLabel.txt"
    if not labels.is_file():
        pytest.skip(f"UTKinect data absent: {labels} not found (set ACTIONSTRING_DATA)")
    folder = tmp_path_factory.mktemp("utkinect")
    lists = {}
    for name, subjects in (("train", "s01,s02"), ("test", "s03")):
        lists[name] = folder / f"{name}.tsv"
        run_cli(cli, "interval-list", "--utkinect", labels, "--subjects", subjects, "--out", lists[name])
    return folder, lists


def test_python_trains_and_evaluates_recordings_as_the_cli_does(cli, utkinect_lists):
    folder, lists = utkinect_lists
    config = ROOT / "models" / "utkinect.config"
    run_cli(cli, "train", "--clips", lists["train"], "--config", config, "--out", folder / "cli.model")
    run_cli(cli, "eval", "--model", folder / "cli.model", "--clips", lists["test"], "--online", "--json",
            folder / "cli.json")
    model = actionstring.train(actionstring.read_clip_list(lists["train"]), config=config,
                               recordings=actionstring.read_recordings(lists["train"]))
    assert model.training_report["no_action_stretches"] > 0
    model.save(folder / "python.model")
    assert (folder / "python.model").read_bytes() == (folder / "cli.model").read_bytes()
    report = model.evaluate(actionstring.read_clip_list(lists["test"]),
                            recordings=actionstring.read_recordings(lists["test"]), online=True)
    expected = json.loads((folder / "cli.json").read_text())
    assert report["online"]["streams"] == expected["online"]["streams"] == "recordings"
    for key in ("frame_accuracy", "action_frame_accuracy", "no_action_accuracy", "segment_f1",
                "unknown_everywhere_accuracy"):
        assert report["online"]["settled"][key] == expected["online"]["settled"][key]
    assert report["online"]["settled"]["events"] == expected["online"]["settled"]["events"]
