"""Reading motion files and building clips from arrays."""
import re

import numpy as np
import pytest

import actionstring


def test_read_clip_list_gives_labelled_float32_clips(hdm05):
    clips = actionstring.read_clip_list(hdm05 / "val.tsv")
    assert len(clips) == 44
    clip = clips[0]
    assert clip.label == "depositFloorR" and clip.subject == "mm"
    assert clip.positions.shape == (clip.frame_count, 31, 3)
    assert clip.positions.dtype == np.float32
    assert clip.times.shape == (clip.frame_count,)
    assert np.all(np.diff(clip.times) > 0)
    assert clip.joint_names[0] == "root" and len(clip.joint_names) == 31
    assert abs(clip.times[1] - clip.times[0] - 1 / 120) < 1e-9


def test_read_clip_reads_one_file(hdm05):
    clip = actionstring.read_clip(hdm05 / "val/squat1Reps/HDM_mm_squat1Reps_037_120.amc",
                                  skeleton=str(hdm05 / "asf/HDM_mm.asf"))
    assert clip.joint_count == 31 and clip.frame_count > 100
    assert clip.label == ""


def test_positions_are_a_read_only_view_that_keeps_the_clip_alive(toy_clips):
    clip = toy_clips[0].relabelled("x", "y")
    positions = clip.positions
    assert not positions.flags.writeable
    first = positions[3, 2].copy()
    del clip
    assert np.array_equal(positions[3, 2], first)  # the view holds the clip
    with pytest.raises(ValueError):
        positions[0, 0, 0] = 1.0


def test_clip_from_arrays():
    frames = np.zeros((30, 20, 3), dtype=np.float64)  # 20 joints: Kinect v1 names
    frames[:, :, 1] = np.linspace(0, 1.6, 20)
    frames[:, 12, 0] = -0.1  # HipLeft
    frames[:, 16, 0] = 0.1  # HipRight
    clip = actionstring.Clip(frames, frame_rate=30.0, label="stand", subject="s1")
    assert clip.positions.dtype == np.float32 and clip.positions.shape == (30, 20, 3)
    assert clip.joint_names[0] == "HipCenter"
    assert clip.times[-1] == pytest.approx(29 / 30)
    assert clip.label == "stand" and clip.subject == "s1"


def test_clip_from_arrays_takes_a_kinect_sdks_tree_or_the_one_given():
    frames = np.zeros((5, 20, 3), dtype=np.float32)
    v1 = actionstring.Clip(frames, frame_rate=30.0)  # Kinect v1 names: the SDK's tree
    assert v1.parents == [-1, 0, 1, 2, 2, 4, 5, 6, 2, 8, 9, 10, 0, 12, 13, 14, 0, 16, 17, 18]
    names = ["PELVIS", "HIP_LEFT", "HIP_RIGHT", "SPINE_NAVEL", "SPINE_CHEST", "NECK", "HEAD", "NOSE"]
    azure = actionstring.Clip(np.zeros((5, 8, 3)), frame_rate=30.0, joint_names=names)
    assert azure.parents == [-1, 0, 0, 0, 3, 4, 5, 6]
    azure_default = actionstring.Clip(np.zeros((5, 32, 3)), frame_rate=30.0)  # 32 joints: Azure Kinect's
    assert azure_default.joint_names[1] == "SPINE_NAVEL" and azure_default.parents[26] == 3
    own = ["hips", "left_hip", "right_hip", "head"]  # names of no SDK: no tree unless given
    assert actionstring.Clip(np.zeros((5, 4, 3)), frame_rate=30.0, joint_names=own).parents == []
    given = actionstring.Clip(np.zeros((5, 4, 3)), frame_rate=30.0, joint_names=own, parents=[-1, 0, 0, 0])
    assert given.parents == [-1, 0, 0, 0]


@pytest.mark.parametrize(
    "parents, message",
    [
        ([-1, 0, 0], "3 parents for 4 joints"),
        ([-1, 0, 0, 4], "parent 4 is not -1 or a joint index below 4"),
        ([-1, 0, -2, 0], "parent -2"),
        ([-1, 3, 0, 1], "joint 1 is in a cycle"),
    ],
)
def test_bad_parents_are_refused(parents, message):
    with pytest.raises(ValueError, match=re.escape(message)):
        actionstring.Clip(np.zeros((5, 4, 3)), frame_rate=30.0, joint_names=["a", "b", "c", "d"], parents=parents)


def test_arrays_train_the_model_the_files_train(msr):
    """Clips rebuilt from the read arrays (no tree given) train bit for bit the model the files do,
    with bone lengths: the Kinect tree comes from the joint names."""
    read = actionstring.read_clip_list(msr / "train.tsv")
    read = [c for c in read if c.subject in ("s01", "s03")][:40]
    rebuilt = [actionstring.Clip(np.array(c.positions), times=np.array(c.times), joint_names=c.joint_names,
                                 label=c.label, subject=c.subject) for c in read]
    assert all(r.parents == c.parents for r, c in zip(rebuilt, read))
    settings = dict(scale="bones", velocity=1.0, components=0, pca=8, string_rate=10, keep_singletons=True)
    assert actionstring.train(rebuilt, **settings).to_blob() == actionstring.train(read, **settings).to_blob()


@pytest.mark.parametrize(
    "positions, kwargs, message",
    [
        (np.zeros((10, 20)), {"frame_rate": 30}, "shape (frames, joints, 3)"),
        (np.zeros((10, 20, 2)), {"frame_rate": 30}, "shape (frames, joints, 3)"),
        (np.zeros((10, 20, 3), dtype=np.int32), {"frame_rate": 30}, "expected floats"),
        (np.array([["a"]]), {"frame_rate": 30}, "expected floats"),
        (np.zeros((10, 7, 3)), {"frame_rate": 30}, "joint_names"),
        (np.zeros((10, 20, 3)), {}, "frame_rate"),
        (np.zeros((10, 20, 3)), {"times": np.arange(9.0)}, "one time in seconds per frame"),
        (np.zeros((10, 20, 3)), {"times": np.arange(10.0)[::-1].copy()}, "non-decreasing"),
        (np.zeros((0, 20, 3)), {"frame_rate": 30}, "no frames"),
    ],
)
def test_bad_arrays_are_refused_with_a_value_error(positions, kwargs, message):
    with pytest.raises(ValueError, match=re.escape(message)):
        actionstring.Clip(positions, **kwargs)


def test_nan_positions_are_refused_with_their_place():
    frames = np.zeros((10, 20, 3), dtype=np.float32)
    frames[4, 7, 1] = np.nan
    with pytest.raises(ValueError, match="frame 4, joint 7 is NaN"):
        actionstring.Clip(frames, frame_rate=30)


def test_unreadable_files_raise_read_error_with_file_and_line(tmp_path):
    with pytest.raises(actionstring.ReadError, match="missing.bvh"):
        actionstring.read_clip(tmp_path / "missing.bvh")
    bad = tmp_path / "bad.csv"
    bad.write_text("time,HipCenter_x,HipCenter_y\n0.0,1.0,2.0\nnot-a-number,1,2\n")
    with pytest.raises(actionstring.ReadError, match=r"bad\.csv:\d+: "):
        actionstring.read_clip(bad)
    assert issubclass(actionstring.ReadError, ValueError)
    bad_list = tmp_path / "list.tsv"
    bad_list.write_text("path\tlabel\n")
    with pytest.raises(actionstring.ReadError, match=r"list\.tsv"):
        actionstring.read_clip_list(bad_list)


def test_csv_as_exported_with_its_notes(tmp_path):
    path = tmp_path / "export.csv"
    path.write_text(
        "Timestamp,HipCenterX,HipCenterY,HipCenterZ,HipLeftX,HipLeftY,HipLeftZ,HipRightX,HipRightY,HipRightZ,User-ID,\n"
        + "".join(f"{33 * i},0,1,2,-0.1,1,2,0.1,1,2,7,\n" for i in range(10)))
    clip = actionstring.read_clip(path)
    assert clip.joint_names == ["HipCenter", "HipLeft", "HipRight"]
    assert clip.times[1] == pytest.approx(0.033)
    assert any("milliseconds" in note for note in clip.notes)
    assert any("'User-ID'" in note for note in clip.notes)
    seconds = actionstring.read_clip(path, time_unit="s")
    assert seconds.times[1] == pytest.approx(33.0)
    assert any(note.startswith("warning:") for note in seconds.notes)
    with pytest.raises(ValueError, match="--time-unit"):
        actionstring.read_clip(path, time_unit="minutes")


def test_a_kinect_csv_brings_its_sdks_tree_and_info_says_so(tmp_path, cli):
    from conftest import run_cli
    kinect = tmp_path / "kinect.csv"  # Kinect v1 names as an exporter spells them, a subset with the root
    kinect.write_text("time,HIP_CENTER_x,HIP_CENTER_y,HIP_CENTER_z,hip_left_x,hip_left_y,hip_left_z,"
                      "HipRight_x,HipRight_y,HipRight_z,Spine_x,Spine_y,Spine_z\n"
                      + "".join(f"{i / 30:.4f},0,1,2,-0.1,1,2,0.1,1,2,0,1.2,2\n" for i in range(5)))
    assert actionstring.read_clip(kinect).parents == [-1, 0, 0, 0]
    assert "tree:      3 bones" in run_cli(cli, "info", kinect)
    own = tmp_path / "own.csv"
    own.write_text("time,hips_x,hips_y,hips_z,head_x,head_y,head_z\n0,0,1,2,0,1.7,2\n0.04,0,1,2,0,1.7,2\n")
    assert actionstring.read_clip(own).parents == []
    assert actionstring.read_clip(own, parents=[None, "hips"]).parents == [-1, 0]
    with pytest.raises(actionstring.ReadError, match="'neck' \\(the parent of head\\) is not a joint"):
        actionstring.read_clip(own, parents=["-", "neck"])
    (tmp_path / "own.tsv").write_text("path\tlabel\tsubject\nown.csv\tstand\ts1\n")
    assert actionstring.read_clip_list(tmp_path / "own.tsv", parents=["-", "hips"])[0].parents == [-1, 0]
    assert "tree:      none" in run_cli(cli, "info", own)


def test_self_tuning_says_when_size_cannot_be_normalised(tmp_path, cli):
    import subprocess
    rows = ["path\tlabel\tsubject"]
    for subject in range(3):
        for label, rise in (("up", 0.5), ("down", -0.5)):
            path = tmp_path / f"{label}_{subject}.csv"  # Mixamo's names in a CSV: roles, but no tree
            path.write_text("time,Hips_x,Hips_y,Hips_z,LeftUpLeg_x,LeftUpLeg_y,LeftUpLeg_z,RightUpLeg_x,"
                            "RightUpLeg_y,RightUpLeg_z,RightHand_x,RightHand_y,RightHand_z\n" + "".join(
                                f"{i / 30:.4f},0,1,2,-0.1,1,2,0.1,1,2,0.3,{1 + rise * i / 30 + 0.01 * subject:.4f},2\n"
                                for i in range(40)))
            rows.append(f"{path.name}\t{label}\ts{subject}")
    (tmp_path / "list.tsv").write_text("\n".join(rows) + "\n")
    done = subprocess.run([cli, "train", "--clips", tmp_path / "list.tsv", "--out", tmp_path / "m.model"],
                          capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr
    assert "has no bone tree" in done.stderr and "size is left alone" in done.stderr
    # Told the tree, the same files scale their bones; not told, bone scaling says how to tell it.
    bones = [cli, "train", "--clips", tmp_path / "list.tsv", "--out", tmp_path / "b.model", "--scale", "bones",
             "--no-tune", "--pca", "6"]
    refused = subprocess.run(bones, capture_output=True, text=True, timeout=300)
    assert refused.returncode != 0 and "--parents" in refused.stderr
    done = subprocess.run(bones + ["--parents", "-,Hips,Hips,Hips"], capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr
    assert "--scale none" not in done.stderr


def test_a_csv_in_millimetres_reads_in_metres(tmp_path):
    path = tmp_path / "mm.csv"
    path.write_text("time,Head_x,Head_y,Head_z,HipCenter_x,HipCenter_y,HipCenter_z,FootLeft_x,FootLeft_y,FootLeft_z\n"
                    + "".join(f"{i / 30:.4f},0,1700,2500,0,900,2500,0,0,2500\n" for i in range(5)))
    clip = actionstring.read_clip(path)
    assert clip.positions[0, 0, 1] == pytest.approx(1.7)
    assert any(note.startswith("lengths taken as millimetres") for note in clip.notes)
    assert actionstring.read_clip(path, scale=1.0).positions[0, 0, 1] == pytest.approx(1700.0)


def test_csv_columns_given_by_hand(tmp_path):
    path = tmp_path / "odd.csv"
    path.write_text("when;a1;a2;a3;b1;b2;b3;c1;c2;c3\n0;0;1;2;-0.1;1;2;0.1;1;2\n0.04;0;1;2;-0.1;1;2;0.1;1;2\n")
    clip = actionstring.read_clip(path, columns="time=when,pelvis=a1:a2:a3,hipleft=b1:b2:b3,hipright=c1:c2:c3")
    assert clip.joint_names == ["pelvis", "hipleft", "hipright"]
    with pytest.raises(actionstring.ReadError, match="no column 'zz'"):
        actionstring.read_clip(path, columns="time=when,pelvis=a1:a2:zz")


def test_a_sensors_up_direction_turns_the_frames_upright(tmp_path):
    """A CSV recorded by a sensor pitched 30° about x, read with its up direction (here from
    the list's `up` column or the keyword), gives the upright positions; bad values are refused."""
    angle = np.radians(30.0)
    turn = np.array([[1, 0, 0], [0, np.cos(angle), -np.sin(angle)], [0, np.sin(angle), np.cos(angle)]])
    upright = np.array([[0.0, 1.0, 2.0], [-0.1, 0.95, 2.0], [0.1, 0.95, 2.0]])
    tilted = upright @ turn.T
    row = ",".join(f"{v:.9f}" for v in tilted.ravel())
    path = tmp_path / "tilted.csv"
    path.write_text("time,HipCenterX,HipCenterY,HipCenterZ,HipLeftX,HipLeftY,HipLeftZ,HipRightX,HipRightY,HipRightZ\n"
                    + "".join(f"{0.04 * i},{row}\n" for i in range(4)))
    up = turn @ np.array([0.0, 1.0, 0.0])
    clip = actionstring.read_clip(path, up=tuple(up))
    np.testing.assert_allclose(clip.positions[2], upright, atol=1e-5)
    assert not np.allclose(actionstring.read_clip(path).positions[2], upright, atol=0.05)
    listed = tmp_path / "list.tsv"
    listed.write_text("path\tlabel\tsubject\tup\n" f"{path}\twave\ts1\t{up[0]},{up[1]},{up[2]}\n")
    np.testing.assert_allclose(actionstring.read_clip_list(listed)[0].positions[0], upright, atol=1e-5)
    with pytest.raises(ValueError, match="up: expected"):
        actionstring.read_clip(path, up=(0.0, 1.0))
    with pytest.raises(actionstring.ReadError, match="not a direction"):
        actionstring.read_clip(path, up=(0.0, 0.0, float("nan")))
    listed.write_text("path\tlabel\tsubject\tup\n" f"{path}\twave\ts1\t0,1\n")
    with pytest.raises(actionstring.ReadError, match="X,Y,Z"):
        actionstring.read_clip_list(listed)


@pytest.mark.parametrize("setting", [dict(up=(0.0, 1.0, 0.0)), dict(rate=30.0), dict(body=0), dict(length_unit="mm")])
def test_reading_settings_are_refused_by_train(toy_clips, setting):
    """What belongs to reading a file is given to read_clip or read_clip_list, never to train."""
    with pytest.raises(ValueError, match="reading setting"):
        actionstring.train(toy_clips, **setting)
