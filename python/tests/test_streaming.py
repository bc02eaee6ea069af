"""The per-frame annotator from Python."""
import numpy as np
import pytest

import actionstring
from conftest import TOY_SETTINGS


def test_streaming_a_clip_settles_its_label(toy_model, toy_clips):
    annotator = actionstring.Annotator(toy_model, settle=0.5)
    clip = toy_clips[0]
    settled = []
    for time_s, frame in zip(clip.times, clip.positions):
        result = annotator.push_frame(time_s, frame)
        assert result["status"] == "ok" and result["accepted"]
        assert result["live_margin"] >= 0.0  # never NaN
        settled += result["settled"]
    assert annotator.live_margin == result["live_margin"]
    assert annotator.characters == len(settled) + annotator.settle_chars
    assert annotator.settle_chars == 5  # 0.5 s at 10 characters per second
    labels = [label for _, _, label in settled]
    assert labels.count(clip.label) > len(labels) / 2
    times = [t for _, t, _ in settled]
    assert times == sorted(times)
    assert [c for c, _, _ in settled] == list(range(len(settled)))
    assert annotator.live_label in toy_model.label_names
    assert annotator.state_bytes == toy_model.state_bytes(settle=0.5)


def test_timelines_agree_with_annotate(toy_model, toy_clips):
    """The settled labels streamed from Python are the timeline annotate() reports."""
    clip = toy_clips[2]
    annotator = actionstring.Annotator(toy_model)
    settled = []
    for time_s, frame in zip(clip.times, clip.positions):
        settled += annotator.push_frame(time_s, frame)["settled"]
    spans = toy_model.annotate(clip)
    for _, time_s, label in settled:
        span = next(s for s in spans if s["start"] - 1e-3 <= time_s <= s["end"] + 0.15)
        assert span["label"] == (label or "unknown")


def test_frames_of_any_float_layout_and_rejected_frames(toy_model, toy_clips):
    annotator = actionstring.Annotator(toy_model, window_rule=True)
    frame = toy_clips[0].positions[10]
    assert annotator.push_frame(0.0, frame)["status"] == "ok"
    assert annotator.push_frame(0.1, frame.astype(np.float64))["status"] == "ok"
    assert annotator.push_frame(0.2, frame.reshape(-1))["status"] == "ok"
    assert annotator.push_frame(0.3, np.asfortranarray(frame))["status"] == "ok"
    nan = frame.copy()
    nan[2, 1] = np.nan
    assert annotator.push_frame(0.4, nan)["status"] == "non_finite_input"  # a sensor glitch: skipped, not fatal
    assert annotator.push_frame(0.45, np.zeros_like(frame))["status"] == "tracking_lost"
    assert annotator.push_frame(0.25, frame)["status"] == "time_went_backwards"
    with pytest.raises(ValueError, match=r"expected shape \(5, 3\)"):
        annotator.push_frame(0.5, np.zeros((4, 3), dtype=np.float32))
    with pytest.raises(ValueError, match="expected floats"):
        annotator.push_frame(0.5, np.zeros((5, 3), dtype=np.int64))
    with pytest.raises(ValueError, match="finite"):
        annotator.push_frame(float("nan"), frame)
    annotator.reset()
    assert annotator.characters == 0 and annotator.live_label is None and annotator.live_margin == 0.0


def test_online_settings_are_checked(toy_model):
    with pytest.raises(ValueError, match="unknown online setting 'settel'"):
        actionstring.Annotator(toy_model, settel=1.0)
    with pytest.raises(ValueError, match="option --segment-penalty expects"):
        actionstring.Annotator(toy_model, segment_penalty=-1)
    with pytest.raises(ValueError, match="option --min-action expects"):
        actionstring.Annotator(toy_model, min_action=-0.5)
    assert actionstring.Annotator(toy_model, settle=8.0).state_bytes > actionstring.Annotator(toy_model).state_bytes


def test_events_once_per_action_and_the_flush(toy_model, toy_clips):
    """Each action of a stream starts and ends once; the flush ends the last one."""
    clip = toy_clips[1]
    annotator = actionstring.Annotator(toy_model, settle=0.5)
    events = []
    for time_s, frame in zip(clip.times, clip.positions):
        events += annotator.push_frame(time_s, frame)["events"]
    events += annotator.flush()
    assert [e["event"] for e in events] == ["started", "ended"]
    assert {e["label"] for e in events} == {clip.label}
    assert events[1]["end"] > events[1]["start"]
    assert annotator.characters == 0
    assert annotator.flush() == []  # nothing left


def test_the_model_carries_its_shortest_action(toy_clips):
    """min_action is trained into the model, used by default, and overridable."""
    assert actionstring.train(toy_clips, **TOY_SETTINGS).online_settings["min_action"] == pytest.approx(0.25)
    patient = actionstring.train(toy_clips, **TOY_SETTINGS, min_action=60)
    assert patient.online_settings["min_action"] == pytest.approx(60)
    clip = toy_clips[1]

    def events(annotator):
        found = []
        for time_s, frame in zip(clip.times, clip.positions):
            found += annotator.push_frame(time_s, frame)["events"]
        return found + annotator.flush()

    assert events(actionstring.Annotator(patient, settle=0.5)) == []  # no action lasts a minute
    assert [e["event"] for e in events(actionstring.Annotator(patient, settle=0.5, min_action=0.25))] == [
        "started", "ended"]


def test_the_label_lead_moves_label_times_only(toy_clips):
    """label_lead is trained into the model and overridable; it moves the settled
    characters' times and the events' times by exactly the lead, nothing else."""
    assert actionstring.train(toy_clips, **TOY_SETTINGS).online_settings["label_lead"] == 0
    led = actionstring.train(toy_clips, **TOY_SETTINGS, label_lead=0.2)
    assert led.online_settings["label_lead"] == pytest.approx(0.2)
    clip = toy_clips[1]

    def run(annotator):
        settled, events = [], []
        for time_s, frame in zip(clip.times, clip.positions):
            result = annotator.push_frame(time_s, frame)
            settled += result["settled"]
            events += result["events"]
        return settled, events + annotator.flush()

    settled, events = run(actionstring.Annotator(led, settle=0.5))
    at_ticks, events_at_ticks = run(actionstring.Annotator(led, settle=0.5, label_lead=0))
    assert len(settled) > 5 and len(events) >= 2
    assert [(c, label) for c, _, label in settled] == [(c, label) for c, _, label in at_ticks]
    assert [t for _, t, _ in settled] == pytest.approx([t - 0.2 for _, t, _ in at_ticks], abs=1e-6)
    assert [e["start"] for e in events] == pytest.approx([e["start"] - 0.2 for e in events_at_ticks], abs=1e-6)
    assert [e["label"] for e in events] == [e["label"] for e in events_at_ticks]
    with pytest.raises(ValueError):
        actionstring.Annotator(led, label_lead=-0.1)


def test_early_settling_settles_sooner_and_in_order(toy_clips):
    """settle_stable is trained into the model and overridable: every character still
    settles once and in order, none later than the delay, some sooner; the live labels
    are the delay's own."""
    assert actionstring.train(toy_clips, **TOY_SETTINGS).online_settings["settle_stable"] == 0
    early = actionstring.train(toy_clips, **TOY_SETTINGS, settle=2, settle_stable=0.5)
    assert early.online_settings["settle_stable"] == pytest.approx(0.5)
    stream = [c for c in toy_clips[:6]]

    def run(annotator):
        settled, live, waited = [], [], []
        offset = 0.0
        for clip in stream:
            for time_s, frame in zip(clip.times, clip.positions):
                result = annotator.push_frame(offset + time_s, frame)
                live.append(result["live_label"])
                for character, label_time, label in result["settled"]:
                    settled.append((character, label))
                    waited.append(offset + time_s - label_time)
            offset += clip.times[-1] + 0.05
        return settled, live, waited

    eager, eager_live, eager_waited = run(actionstring.Annotator(early))
    patient, patient_live, patient_waited = run(actionstring.Annotator(early, settle_stable=0))
    assert [c for c, _ in eager] == list(range(len(eager)))  # once each, in order
    assert len(eager) >= len(patient) > 20
    assert eager_live == patient_live  # the explanation is the same
    assert max(eager_waited) <= 2.0 + 0.11  # never later than the delay (and a string period)
    assert sum(eager_waited) / len(eager_waited) < sum(patient_waited) / len(patient_waited) - 0.5
    assert actionstring.Annotator(early).state_bytes > actionstring.Annotator(early, settle_stable=0).state_bytes
    with pytest.raises(ValueError, match="option --settle-stable expects"):
        actionstring.Annotator(early, settle_stable=-1)


def test_the_jump_bound_is_a_stream_setting(toy_model, toy_clips):
    """max_pose_speed: 0 never restarts the motion, a negative bound is refused,
    and evaluate() and annotate() take it as the Annotator does."""
    actionstring.Annotator(toy_model, max_pose_speed=0)
    actionstring.Annotator(toy_model, max_pose_speed=12.5)
    with pytest.raises(ValueError, match="option --max-pose-speed expects"):
        actionstring.Annotator(toy_model, max_pose_speed=-1)
    with pytest.raises(ValueError, match="option --max-pose-speed expects"):
        toy_model.annotate(toy_clips[0], max_pose_speed=float("nan"))
    report = toy_model.evaluate(toy_clips, online=True, max_pose_speed=0)
    assert report["online"]["settled"]["frames"] > 0


def test_a_tilted_sensor_with_its_up_direction_gives_the_upright_labels(toy_model, toy_clips):
    """up=(x, y, z) turns every frame so the sensor's up lies along the model's axis:
    a stream seen by a sensor turned 0.5 rad about a horizontal axis gets the upright stream's labels and
    nearly its margins; without it the margins move."""
    clip = toy_clips[1]
    c, s = np.cos(0.5), np.sin(0.5)
    pitch = np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]], dtype=np.float32)  # about z
    tilted = np.ascontiguousarray(clip.positions @ pitch.T, dtype=np.float32)

    def run(frames, **settings):
        annotator = actionstring.Annotator(toy_model, settle=0.5, **settings)
        settled, margins = [], []
        for time_s, frame in zip(clip.times, frames):
            result = annotator.push_frame(time_s, frame)
            settled += [(char, label) for char, _, label in result["settled"]]
            margins.append(min(result["live_margin"], 1e6))
        return settled, np.array(margins)

    upright, upright_margins = run(clip.positions)
    assert len(upright) > 5
    given, given_margins = run(tilted, up=tuple(pitch[:, 1]))
    assert given == upright
    assert np.max(np.abs(given_margins - upright_margins)) < 1e-3
    _, unturned_margins = run(tilted)
    assert np.max(np.abs(unturned_margins - upright_margins)) > 0.05
    for bad in [(0.0, 1e-9, 0.0), (float("nan"), 1.0, 0.0), (0.0, 1.0), "0,1,0", ("a", "b", "c"), None]:
        with pytest.raises(ValueError):
            actionstring.Annotator(toy_model, up=bad)


def test_a_restart_flushes_the_ended_streams_tail(toy_model, toy_clips):
    """A gap over max_gap restarts the stream: the frame's ``flushed`` holds the ended
    stream's unsettled tail with final labels, and flush() does the same at the end."""
    clip = toy_clips[1]
    annotator = actionstring.Annotator(toy_model, settle=0.5)
    for time_s, frame in zip(clip.times, clip.positions):
        assert annotator.push_frame(time_s, frame)["flushed"] == []
    result = annotator.push_frame(clip.times[-1] + 5.0, clip.positions[0])
    assert result["status"] == "stream_restarted"
    flushed = result["flushed"]
    assert len(flushed) >= annotator.settle_chars
    assert flushed == annotator.flushed()
    indices = [c for c, _, _ in flushed]
    assert indices == list(range(indices[0], indices[0] + len(indices)))
    times = [t for _, t, _ in flushed]
    assert times == sorted(times) and times[-1] <= clip.times[-1]
    assert all(label is None or label in toy_model.label_names for _, _, label in flushed)
    assert annotator.push_frame(clip.times[-1] + 5.1, clip.positions[1])["flushed"] == []
    annotator.flush()
    assert len(annotator.flushed()) >= 1


def test_spread_work_settles_the_same_labels_later(toy_model, toy_clips):
    """spread_work=True: each character's work (the encoder's and the
    segmenter's) over the frames until the next one; the same settled labels
    and events, none reported earlier."""
    plain = actionstring.Annotator(toy_model, settle=0.5)
    spread = actionstring.Annotator(toy_model, settle=0.5, spread_work=True)
    clip = toy_clips[1]
    got = {False: [], True: []}
    events = {False: [], True: []}
    reported_at = {False: {}, True: {}}
    for f, (time_s, frame) in enumerate(zip(clip.times, clip.positions)):
        for flag, annotator in ((False, plain), (True, spread)):
            result = annotator.push_frame(time_s, frame)
            got[flag] += result["settled"]
            events[flag] += result["events"]
            for c, _, _ in result["settled"]:
                reported_at[flag][c] = f
    tail = spread.finish_work()
    assert len(tail["settled"]) <= 2  # the character in progress, one queued
    got[True] += tail["settled"]
    events[True] += tail["events"]
    assert plain.finish_work()["settled"] == []
    assert got[True] == got[False] and len(got[False]) > 10
    events[False] += plain.flush()
    events[True] += spread.flush()
    assert events[True] == events[False] and events[False]
    later = [c for c, f in reported_at[False].items() if reported_at[True].get(c, len(clip.times)) > f]
    assert all(reported_at[True].get(c, len(clip.times)) >= f for c, f in reported_at[False].items())
    assert len(later) * 2 > len(reported_at[False])  # about six frames per character: most were spread
