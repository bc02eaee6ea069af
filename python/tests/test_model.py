"""Training, saving and loading, classification and evaluation: the same as the CLI."""
import json
import re
import subprocess

import numpy as np
import pytest

import actionstring
from conftest import ROOT, TOY_SETTINGS, run_cli


def test_training_on_toy_clips(toy_model, toy_clips):
    assert toy_model.label_names == ["raise_both", "spread", "wave_left", "wave_right"]
    assert toy_model.joint_names == ["root", "lhipjoint", "rhipjoint", "lhand", "rhand"]
    assert toy_model.representative_count >= 4
    assert toy_model.component_count == 0 and toy_model.feature_dim == 8
    assert toy_model.string_rate_hz == pytest.approx(10.0)
    assert toy_model.training_report["representatives"] == toy_model.representative_count
    assert "pca 8" in toy_model.training_report["settings"]
    result = toy_model.classify(toy_clips[5])
    assert result.label == toy_clips[5].label
    assert 0.0 <= result.confidence <= 1.0


def test_a_budget_bounds_the_representatives_characters(toy_clips):
    free = actionstring.train(toy_clips, **dict(TOY_SETTINGS, sigma=0.0))
    chars = free.training_report["representative_chars"]
    labels = len(free.label_names)
    assert free.representative_count > labels
    bounded = actionstring.train(toy_clips, **dict(TOY_SETTINGS, sigma=0.0, max_representative_chars=chars - 1))
    assert bounded.training_report["representative_chars"] <= chars - 1
    assert labels <= bounded.representative_count < free.representative_count
    assert "max-representative-chars %d" % (chars - 1) in bounded.training_report["settings"]
    with pytest.raises(ValueError, match="below what one representative per label needs"):
        actionstring.train(toy_clips, **dict(TOY_SETTINGS, max_representative_chars=1))


def test_learned_rejection_keeps_the_toy_performances(toy_clips):
    model = actionstring.train(toy_clips, **dict(TOY_SETTINGS, reject=True, reject_keep=0.9))
    assert "reject true\nreject-keep 0.9" in model.training_report["settings"]
    kept = sum(model.classify(c).label == c.label for c in toy_clips)
    assert kept >= 0.9 * len(toy_clips)


def test_motion_settings_reach_the_model(toy_clips):
    # Velocity and acceleration each add a pose's length to what the projection reads.
    still = actionstring.train(toy_clips, **dict(TOY_SETTINGS, velocity=0.0))
    moving = actionstring.train(toy_clips, **dict(TOY_SETTINGS, velocity=1.0, velocity_span=0.3, acceleration=0.5))
    assert "velocity 1\nvelocity-span 0.3\nacceleration 0.5" in moving.training_report["settings"]
    assert "\nacceleration_weight 0x1p-1\n" in moving._native.artifact()
    assert "\nacceleration_weight 0x0p+0\n" in still._native.artifact()
    assert moving.table_bytes > still.table_bytes  # the projection reads three poses' worth
    result = moving.classify(toy_clips[5])
    assert result.label is not None and np.isfinite(result.distance)
    with pytest.raises(ValueError, match="acceleration"):
        actionstring.train(toy_clips, **dict(TOY_SETTINGS, acceleration=-1.0))


def test_exemplars_of_the_feature_s_leading_coordinates(toy_clips):
    # 8 centres per label in all 8 coordinates, then in the first 4: half the floats.
    every = actionstring.train(toy_clips, **dict(TOY_SETTINGS, exemplars=8, exemplar_weight=1.0))
    leading = actionstring.train(toy_clips, **dict(TOY_SETTINGS, exemplars=8, exemplar_weight=1.0, exemplar_dims=4))
    assert "\nexemplar_dim 0\n" in every._native.artifact()
    assert "\nexemplar_dim 4\n" in leading._native.artifact()
    centres = every._native.artifact().split("\nexemplar_labels ")[1].split(" ")[0]
    assert every.table_bytes - leading.table_bytes == int(centres) * 4 * 4  # 4 floats fewer per centre
    assert "exemplar-dims 4" in leading.training_report["settings"]
    kept = sum(leading.classify(c).label == c.label for c in toy_clips)
    assert kept >= 0.9 * len(toy_clips)
    with pytest.raises(ValueError, match="dimensions"):
        actionstring.train(toy_clips, **dict(TOY_SETTINGS, exemplars=8, exemplar_weight=1.0, exemplar_dims=9))


def test_the_clip_descriptor(toy_clips):
    # A pyramid of two levels over 4 of the 8 coordinates: (1 + 2) parts of 4 + 10 floats, per label.
    described = actionstring.train(
        toy_clips, **dict(TOY_SETTINGS, descriptor_levels=2, descriptor_dims=4, descriptor_ridge=10.0,
                          descriptor_weight=1.0))
    plain = actionstring.train(toy_clips, **TOY_SETTINGS)
    artifact = described._native.artifact()
    assert "\ndescriptor_levels 2\n" in artifact and "\ndescriptor_dim 4\n" in artifact
    labels = len(described.label_names)
    assert described.table_bytes - plain.table_bytes == (labels * 3 * 14 + labels) * 4
    assert "descriptor-levels 2" in described.training_report["settings"]
    assert "descriptor-ridge 10" in described.training_report["settings"]
    kept = sum(described.classify(c).label == c.label for c in toy_clips)
    assert kept >= 0.9 * len(toy_clips)
    with pytest.raises(ValueError, match="dimensions"):
        actionstring.train(toy_clips, **dict(TOY_SETTINGS, descriptor_levels=2, descriptor_dims=9,
                                              descriptor_weight=1.0))
    # Learned rejection measures the descriptor's penalties too.
    rejecting = actionstring.train(toy_clips, **dict(TOY_SETTINGS, descriptor_levels=2, descriptor_weight=1.0,
                                                     reject=True))
    assert "\nhas_label_bounds 1\n" in rejecting._native.artifact()
    assert "\ndescriptor_levels 2\n" in rejecting._native.artifact()


def test_the_motion_directions(toy_clips):
    # Two levels: (1 + 2) parts of each pose joint's 3 planes × 8 sectors, per label, and a bias each.
    directed = actionstring.train(
        toy_clips, **dict(TOY_SETTINGS, direction_levels=2, direction_ridge=10.0, direction_weight=1.0))
    plain = actionstring.train(toy_clips, **TOY_SETTINGS)
    artifact = directed._native.artifact()
    assert "\ndirection_levels 2\n" in artifact
    pose_joints = int(artifact.split("\npose_joints ")[1].split()[0])
    labels = len(directed.label_names)
    assert directed.table_bytes - plain.table_bytes == (labels * 3 * pose_joints * 24 + labels) * 4
    assert "direction-levels 2" in directed.training_report["settings"]
    kept = sum(directed.classify(c).label == c.label for c in toy_clips)
    assert kept >= 0.9 * len(toy_clips)
    # The same model through a blob classifies alike.
    again = actionstring.Model.from_blob(directed.to_blob())
    assert [again.classify(c) for c in toy_clips] == [directed.classify(c) for c in toy_clips]
    with pytest.raises(ValueError, match=r"direction-levels expects a whole number in \[0, 8\]"):
        actionstring.train(toy_clips, **dict(TOY_SETTINGS, direction_levels=9, direction_weight=1.0))


def test_label_distances_rank_what_classify_decides(toy_model, toy_clips):
    names = toy_model.label_names
    for clip in toy_clips[:12]:
        distances = toy_model.label_distances(clip)
        assert distances.dtype == np.float32 and distances.shape == (len(names),)
        assert np.all(np.isfinite(distances)) and np.all(distances >= 0)
        decided = toy_model.classify(clip)
        # One neighbour: the nearest label is the smallest, at the distance classify reports.
        assert names[int(distances.argmin())] == decided.label
        assert float(distances.min()) == pytest.approx(decided.distance, rel=0, abs=0)
    # A blob of the same model scores alike, bit for bit.
    again = actionstring.Model.from_blob(toy_model.to_blob())
    assert np.array_equal(again.label_distances(toy_clips[0]), toy_model.label_distances(toy_clips[0]))


def test_tune_online_keeps_the_clip_settings_and_chooses_the_online_ones(toy_clips):
    given = dict(TOY_SETTINGS, segment_penalty=7.5, min_action=1.5)
    model = actionstring.train(toy_clips, tune="online", **given)
    assert "tuning" not in model.training_report  # no clip search
    tuning = model.training_report["online_tuning"]
    kept = [row for row in tuning["settings"] if row["kept"]]
    assert len(kept) == 1 and all(row["segment_f1"] <= kept[0]["segment_f1"] for row in tuning["settings"])
    # The clip settings are the given ones; the online ones given are replaced by the chosen.
    settings = model.training_report["settings"]
    for line in ("pca 8", "string-rate 10", "sigma 4", "components 0"):
        assert "\n" + line + "\n" in "\n" + settings, line
    assert model.online_settings["segment_penalty"] != 7.5
    assert "segment-penalty %g" % model.online_settings["segment_penalty"] in kept[0]["settings"]
    assert model.online_settings["min_action"] in [row["min_action"] for row in tuning["min_action"]]
    # The same clip model as training without the search: the same representatives.
    plain = actionstring.train(toy_clips, **given)
    assert plain.representative_count == model.representative_count
    assert [plain.classify(c) for c in toy_clips[:8]] == [model.classify(c) for c in toy_clips[:8]]
    with pytest.raises(ValueError, match="tune expects"):
        actionstring.train(toy_clips, tune="clips", **TOY_SETTINGS)


def test_self_tuning_chooses_the_online_settings_too(toy_clips):
    """With no settings, train() tunes as `actionstring train` does: clip settings, then online ones."""
    model = actionstring.train(toy_clips)
    tuning = model.training_report["online_tuning"]
    kept = [row for row in tuning["settings"] if row["kept"]]
    assert len(kept) == 1
    assert all(row["segment_f1"] <= kept[0]["segment_f1"] for row in tuning["settings"])
    assert "segment-penalty %g" % model.online_settings["segment_penalty"] in kept[0]["settings"]
    # The window's directions: the best settled frames of three weights (the smaller
    # within 0.001), over a window of 1.5 s, stored in the model.
    windows = tuning["direction_window"]
    assert [row["segment_directions"] for row in windows] == pytest.approx([0, 0.1, 0.25])
    assert tuning["direction_window_s"] == pytest.approx(1.5)
    window = [row for row in windows if row["kept"]]
    assert len(window) == 1
    assert all(row["frame_accuracy"] <= window[0]["frame_accuracy"] + 0.001 for row in windows)
    assert model.online_settings["segment_directions"] == pytest.approx(window[0]["segment_directions"])
    # Early settling: the fastest within one standard error of the best events, stored in the model.
    stable = [row for row in tuning["settle_stable"] if row["kept"]]
    assert [row["settle_stable"] for row in tuning["settle_stable"]] == [0.5, 0.75, 1.0, 1.25, 1.5, 0]
    assert len(stable) == 1
    # The fastest on the folds of those short of the best by at most one standard error, fold by fold.
    best = max(tuning["settle_stable"], key=lambda row: row["event_segment_f1"])
    assert best["difference"] == 0 and best["difference_error"] == 0
    within = [row for row in tuning["settle_stable"] if row["difference"] >= -row["difference_error"]]
    assert stable[0] in within
    assert stable[0]["detection_latency"] == min(row["detection_latency"] for row in within)
    assert model.online_settings["settle_stable"] == pytest.approx(stable[0]["settle_stable"])
    assert "settle-stable %g" % stable[0]["settle_stable"] in model.training_report["settings"]
    shortest = [row for row in tuning["min_action"] if row["kept"]]
    assert [row["min_action"] for row in tuning["min_action"]] == [0.25, 0.5, 0.75, 1.0, 1.5]
    assert len(shortest) == 1
    assert model.online_settings["min_action"] == pytest.approx(shortest[0]["min_action"])
    assert "min-action %g" % shortest[0]["min_action"] in model.training_report["settings"]
    # Then the label lead: the best settled frames, stored in the model.
    leads = tuning["label_lead"]
    assert [row["label_lead"] for row in leads] == pytest.approx([0, 0.05, 0.1, 0.15, 0.2, 0.3, 0.4, 0.5])
    lead = [row for row in leads if row["kept"]]
    assert len(lead) == 1
    assert all(row["frame_accuracy"] <= lead[0]["frame_accuracy"] + 1e-9 for row in leads)
    assert model.online_settings["label_lead"] == pytest.approx(lead[0]["label_lead"])
    assert "label-lead %g" % lead[0]["label_lead"] in model.training_report["settings"]
    # The clip search's table: the starting settings kept first, then each setting tried;
    # a kept one raised the fold mean or, on a tie, the margin.
    clip_tuning = model.training_report["tuning"]
    steps = clip_tuning["settings"]
    assert steps[0]["settings"] == "(the starting settings)" and steps[0]["kept"]
    best = steps[0]
    for row in steps[1:]:
        assert -1.0 <= row["margin"] <= 1.0
        if row["kept"]:
            assert row["fold_mean"] >= best["fold_mean"]
            best = row
    held_out = [s for fold in clip_tuning["folds"] for s in fold["held_out"].split("+")]
    assert sorted(held_out) == sorted({c.subject for c in toy_clips})  # each subject held out once
    assert all(0.0 <= fold["accuracy"] <= 1.0 and fold["clips"] > 0 for fold in clip_tuning["folds"])
    assert clip_tuning["seconds"] > 0
    # Given settings, nothing is tuned.
    assert "online_tuning" not in actionstring.train(toy_clips, **TOY_SETTINGS).training_report
    assert "tuning" not in actionstring.train(toy_clips, **TOY_SETTINGS).training_report
    # A latency budget constrains self-tuning (it still runs) and tries shorter settle delays
    # (1.5 and 1 s) and the delay with early settling.
    budgeted = actionstring.train(toy_clips, latency_budget=60).training_report["online_tuning"]
    assert budgeted["latency_budget_met"]
    assert len(budgeted["settings"]) == 4 * len(tuning["settings"])
    assert sum("settle-stable 1" in row["settings"] for row in budgeted["settings"]) == len(tuning["settings"])
    assert all(row["detection_latency"] > 0 for row in budgeted["settings"])


def test_a_cost_bound_alone_leaves_self_tuning_on(toy_clips):
    """As on the command line: the bound constrains the search, the folds train with it."""
    model = actionstring.train(toy_clips, max_representative_share=0.9)
    report = model.training_report
    assert "online_tuning" in report
    assert "max-representative-share 0.9" in report["settings"]
    assert 0 < report["representative_chars"] <= report["representative_budget"]
    # A tuned setting given turns tuning off.
    assert "online_tuning" not in actionstring.train(toy_clips, max_representative_share=0.9, pca=8).training_report


def test_settings_are_checked(toy_clips):
    with pytest.raises(ValueError, match="unknown training setting 'pcaa'"):
        actionstring.train(toy_clips, pcaa=3)
    with pytest.raises(ValueError, match="option --pca expects a whole number"):
        actionstring.train(toy_clips, pca=-2)
    with pytest.raises(ValueError, match=r"option --pca expects a whole number in \[0, 65535\], got '2.5'"):
        actionstring.train(toy_clips, pca=2.5)
    with pytest.raises(ValueError, match="no clips"):
        actionstring.train([])
    assert "string_rate" in actionstring.training_settings()
    assert "length_unit" not in actionstring.training_settings()  # a reading setting: read_clip(scale=...)


def test_save_load_blob_and_header_round_trip(toy_model, tmp_path):
    toy_model.save(tmp_path / "toy.model")
    loaded = actionstring.Model.load(tmp_path / "toy.model")
    assert loaded._native.artifact() == toy_model._native.artifact()
    toy_model.save_blob(tmp_path / "toy.blob")
    from_file = actionstring.Model.load(tmp_path / "toy.blob")
    from_bytes = actionstring.Model.from_blob(toy_model.to_blob())
    assert from_file._native.artifact() == toy_model._native.artifact()
    assert from_bytes._native.artifact() == toy_model._native.artifact()
    toy_model.write_header(tmp_path / "toy_model.hpp", "toy")
    header = (tmp_path / "toy_model.hpp").read_text()
    assert header.startswith("// DO NOT EDIT.") and "namespace toy" in header
    damaged = bytearray(toy_model.to_blob())
    damaged[len(damaged) // 2] ^= 0x20
    with pytest.raises(actionstring.ReadError, match="checksum"):
        actionstring.Model.from_blob(bytes(damaged))


def test_evaluate_on_toy_clips(toy_model, toy_clips):
    report = toy_model.evaluate(toy_clips, train=toy_clips, online=True)
    assert report["clip_accuracy"] == pytest.approx(1.0)
    assert len(report["baselines"]) == 3
    low, high = report["clip_accuracy_ci95"]
    assert 0.0 <= low <= report["clip_accuracy"] <= high <= 1.0
    assert report["correct"] == len(toy_clips)
    for baseline in report["baselines"]:  # each paired with the model on the same clips
        paired = baseline["paired_with_model"]
        assert paired["model_only"] + paired["baseline_only"] <= len(toy_clips)
        assert 0.0 < paired["mcnemar_p"] <= 1.0
    settled = report["online"]["settled"]
    assert 0.0 <= settled["frame_accuracy"] <= 1.0
    for figure in ("frame_accuracy", "segment_f1"):  # 95% intervals resampling the true runs
        low, high = settled[figure + "_ci95"]
        assert 0.0 <= low <= high <= 1.0
    events = settled["events"]  # the reported actions, also judged as segments
    assert 0 <= events["iou_matched"] <= events["reported"]
    assert 0.0 <= events["segment_f1"] <= 1.0
    low, high = events["segment_f1_ci95"]
    assert 0.0 <= low <= high <= 1.0
    # Frames by class: the confusion (no action, then the model's labels) and each class's figures.
    table = settled["frame_confusion"]
    assert len(table) == len(toy_model.label_names) + 1
    assert all(len(row) == len(table) for row in table)
    assert sum(map(sum, table)) == settled["frames"]
    assert sum(table[i][i] for i in range(len(table))) == round(settled["frame_accuracy"] * settled["frames"])
    classes = {c["label"]: c for c in settled["per_class_frames"]}
    assert set(classes) <= set(toy_model.label_names) | {"no action"}
    for i, name in enumerate(toy_model.label_names):
        if name in classes:
            assert classes[name]["frames"] == sum(table[i + 1])
            assert classes[name]["right"] == table[i + 1][i + 1]
            assert classes[name]["recall"] == pytest.approx(table[i + 1][i + 1] / sum(table[i + 1]))
    streams = report["online"]["per_stream"]  # each subject's clips joined, scored alone
    assert sorted(s["name"] for s in streams) == sorted({"subject " + c.subject for c in toy_clips})
    assert sum(s["frames"] for s in streams) == settled["frames"]
    assert sum(s["frame_accuracy"] * s["frames"] for s in streams) == pytest.approx(
        settled["frame_accuracy"] * settled["frames"])
    assert report["perturbation"] == "none"


def test_evaluate_perturbed_clips(toy_model, toy_clips):
    moved = toy_model.evaluate(toy_clips, perturb="rate=20,seed=3")
    assert moved["perturbation"] == "resampled to 20 Hz (seed 3)"
    noisy = toy_model.evaluate(toy_clips, perturb="noise=0.3")
    assert noisy["clip_accuracy"] < toy_model.evaluate(toy_clips)["clip_accuracy"]
    with pytest.raises(ValueError, match="'bright' is not a perturbation"):
        toy_model.evaluate(toy_clips, perturb="bright=2")


@pytest.fixture(scope="module")
def hdm05_model(hdm05, cli, tmp_path_factory):
    """The committed model's settings, trained by the CLI and by Python."""
    folder = tmp_path_factory.mktemp("hdm05")
    config = ROOT / "models" / "hdm05.config"
    run_cli(cli, "train", "--clips", hdm05 / "train.tsv", "--config", config, "--out", folder / "cli.model")
    return folder, config


def test_python_training_equals_the_cli_bit_for_bit(hdm05, hdm05_model):
    folder, config = hdm05_model
    model = actionstring.train(actionstring.read_clip_list(hdm05 / "train.tsv"), config=config)
    assert model._native.artifact() == (folder / "cli.model").read_text()


def test_tune_online_from_the_cli_equals_python(hdm05, cli, hdm05_model, tmp_path):
    folder, config = hdm05_model
    out = run_cli(cli, "train", "--clips", hdm05 / "train.tsv", "--config", config, "--tune-online", "--out",
                  tmp_path / "online.model")
    assert "online tuning:" in out and "<- chosen" in out
    echoed = out.split("the online ones chosen (keep them with --config):\n")[1]
    model = actionstring.train(actionstring.read_clip_list(hdm05 / "train.tsv"), config=config, tune="online")
    assert model._native.artifact() == (tmp_path / "online.model").read_text()
    assert echoed.startswith(model.training_report["settings"])
    # The clip model is the config's own: the same representatives as training with it alone.
    plain = actionstring.Model.load(folder / "cli.model")
    assert plain.representative_count == model.representative_count


def test_evaluation_equals_the_cli(hdm05, cli, hdm05_model):
    folder, _ = hdm05_model
    run_cli(cli, "eval", "--model", folder / "cli.model", "--clips", hdm05 / "val.tsv", "--json", folder / "eval.json")
    expected = json.loads((folder / "eval.json").read_text())
    model = actionstring.Model.load(folder / "cli.model")
    got = model.evaluate(actionstring.read_clip_list(hdm05 / "val.tsv"))
    for key in ("clip_accuracy", "unknown_rate", "labels", "confusion", "per_class", "per_subject", "clips",
                "top_k"):
        assert got[key] == expected[key], key
    assert got["clip_accuracy"] > 0.8
    # Top-1 to top-3 from label_distances(), a tie ranked against the true label.
    clips = actionstring.read_clip_list(hdm05 / "val.tsv")
    names = model.label_names
    ahead = [int(np.sum(np.delete(d, names.index(c.label)) <= d[names.index(c.label)]))
             for c, d in ((c, model.label_distances(c)) for c in clips)]
    assert got["top_k"] == pytest.approx([np.mean([a < k for a in ahead]) for k in (1, 2, 3)])
    assert got["top_k"][0] == pytest.approx(got["clip_accuracy"])
    # val.tsv is one actor's: one per-subject row, holding every clip.
    assert [(s["subject"], s["clips"], s["correct"]) for s in got["per_subject"]] == [
        ("mm", got["clips"], got["correct"])]
    # classify() gives each clip the label the evaluation counted.
    clips = actionstring.read_clip_list(hdm05 / "val.tsv")
    predicted = [model.classify(clip).label for clip in clips]
    accuracy = np.mean([p == clip.label for p, clip in zip(predicted, clips)])
    assert accuracy == pytest.approx(expected["clip_accuracy"])


def test_annotate_equals_the_cli(hdm05, cli, hdm05_model):
    folder, _ = hdm05_model
    amc = hdm05 / "val/squat1Reps/HDM_mm_squat1Reps_037_120.amc"
    asf = hdm05 / "asf/HDM_mm.asf"
    expected = json.loads(run_cli(cli, "annotate", "--model", folder / "cli.model", amc, "--skeleton", asf, "--json"))
    model = actionstring.Model.load(folder / "cli.model")
    got = model.annotate(actionstring.read_clip(amc, skeleton=str(asf)))
    assert got == expected["segments"]
    # The clip is one squat: the label holding most of its time says so.
    longest = max(got, key=lambda segment: segment["end"] - segment["start"])
    assert longest["label"] == "squat1Reps"
    # The sensor's up direction: --up and up= agree; the model's own axis changes nothing.
    clip = actionstring.read_clip(amc, skeleton=str(asf))
    axis = [0, 0, 0]
    axis[clip.up_axis] = 1
    same = json.loads(run_cli(cli, "annotate", "--model", folder / "cli.model", amc, "--skeleton", asf, "--json",
                              "--up", ",".join(map(str, axis))))
    assert same == expected
    tilted = [0.2, 0.2, 0.2]
    tilted[clip.up_axis] = 1.0
    turned = json.loads(run_cli(cli, "annotate", "--model", folder / "cli.model", amc, "--skeleton", asf, "--json",
                                "--up", ",".join(map(str, tilted))))
    assert turned["segments"] == model.annotate(clip, up=tuple(tilted))
    for bad in ["1,2", "0,0,1e-9", "0,nan,1", "a,b,c"]:
        done = subprocess.run([cli, "annotate", "--model", str(folder / "cli.model"), str(amc), "--skeleton", str(asf),
                               "--up", bad], capture_output=True, text=True)
        assert done.returncode != 0 and "--up" in done.stderr, bad


def test_eval_and_train_take_the_sensors_up_direction(hdm05, cli, hdm05_model, tmp_path):
    """`eval --up` turns the listed files upright as read, as read_clip(up=) does; along the
    axis it changes nothing; bad values are refused by eval and train alike."""
    folder, _ = hdm05_model
    lines = (hdm05 / "val.tsv").read_text().splitlines()
    listed = tmp_path / "few.tsv"
    header = lines[0].split("\t")
    rows = [dict(zip(header, line.split("\t"))) for line in lines[1:5]]
    for row in rows:
        for key in ("path", "skeleton"):
            if key in row and not row[key].startswith("/"):
                row[key] = str(hdm05 / row[key])
    listed.write_text("\t".join(header) + "\n" + "".join("\t".join(row[k] for k in header) + "\n" for row in rows))
    model = actionstring.Model.load(folder / "cli.model")
    clips = actionstring.read_clip_list(listed)
    axis = [0, 0, 0]
    axis[clips[0].up_axis] = 1
    tilted = [0.3, 0.3, 0.3]
    tilted[clips[0].up_axis] = 1.0

    def evaluated(*more):
        out = tmp_path / "eval.json"
        run_cli(cli, "eval", "--model", folder / "cli.model", "--clips", listed, "--json", out, *more)
        return json.loads(out.read_text())

    plain = evaluated()
    assert evaluated("--up", ",".join(map(str, axis)))["confusion"] == plain["confusion"]
    turned = evaluated("--up", ",".join(map(str, tilted)))
    by_python = model.evaluate(actionstring.read_clip_list(listed, up=tuple(tilted)))
    assert turned["confusion"] == by_python["confusion"]
    assert turned["clip_accuracy"] == pytest.approx(by_python["clip_accuracy"])
    for command in (["eval", "--model", str(folder / "cli.model"), "--clips", str(listed)],
                    ["train", "--clips", str(listed), "--out", str(tmp_path / "x.model")]):
        for bad in ["1,2", "0,0,1e-9", "0,nan,1"]:
            done = subprocess.run([cli, *command, "--up", bad], capture_output=True, text=True)
            assert done.returncode != 0 and "up direction" in done.stderr, (command, bad, done.stderr)


def test_streamed_events_equal_annotate_events(hdm05, cli, hdm05_model):
    folder, _ = hdm05_model
    amc = hdm05 / "val/squat1Reps/HDM_mm_squat1Reps_037_120.amc"
    asf = hdm05 / "asf/HDM_mm.asf"
    lines = run_cli(cli, "annotate", "--model", folder / "cli.model", amc, "--skeleton", asf, "--events")
    expected = [json.loads(line) for line in lines.splitlines()]
    model = actionstring.Model.load(folder / "cli.model")
    clip = actionstring.read_clip(amc, skeleton=str(asf))
    annotator = actionstring.Annotator(model)
    got = []
    for time_s, frame in zip(clip.times, clip.positions):
        got += annotator.push_frame(time_s, frame)["events"]
    got += annotator.flush()
    assert [(e["event"], e["label"]) for e in got] == [(e["event"], e["label"]) for e in expected]
    for a, b in zip(got, expected):
        assert a["start"] == pytest.approx(b["start"], abs=1e-9)
        assert a["end"] == pytest.approx(b["end"], abs=1e-9)
        assert a["confidence"] == pytest.approx(b["confidence"], rel=1e-6)
    assert expected[0]["label"] == "squat1Reps"


def test_one_version_everywhere(cli):
    """version.hpp declares it; the extension, the package, pyproject.toml and the CLI agree."""
    header = (ROOT / "include" / "actionstring" / "version.hpp").read_text()
    numbers = [re.search(rf"^#define ACTIONSTRING_VERSION_{part} (\d+)$", header, re.M).group(1)
               for part in ("MAJOR", "MINOR", "PATCH")]
    declared = ".".join(numbers)
    assert actionstring._native.__version__ == declared
    assert actionstring.__version__ == declared
    pyproject = (ROOT / "pyproject.toml").read_text()
    assert re.search(r'^version = "([^"]+)"', pyproject, re.M).group(1) == declared
    assert run_cli(cli, "version").strip() == f"actionstring {declared}"
