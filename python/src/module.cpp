// actionstring Python bindings: the host library and the runtime, bound with
// pybind11. Nothing is reimplemented here: reading, training, evaluation and
// streaming are the C++ functions the command line calls.
#include <array>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cmath>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "actionstring/annotator.hpp"
#include "actionstring/version.hpp"
#include "eval/evaluation.hpp"
#include "io/clip_list.hpp"
#include "io/formats.hpp"
#include "io/recordings.hpp"
#include "io/sdk_skeletons.hpp"
#include "io/text.hpp"
#include "model/artifact.hpp"
#include "model/blob.hpp"
#include "model/header.hpp"
#include "model/model_data.hpp"
#include "run/classify.hpp"
#include "run/encode.hpp"
#include "run/skeleton.hpp"
#include "run/state.hpp"
#include "run/stream_labels.hpp"
#include "toy/toy.hpp"
#include "train/online_tuning.hpp"
#include "train/pipeline.hpp"
#include "train/settings.hpp"
#include "train/tuning.hpp"

namespace py = pybind11;

namespace actionstring {
namespace python {
namespace {

using host::LabelledClip;
using host::ModelData;
using ModelPtr = std::shared_ptr<ModelData>;

// ---- arrays ------------------------------------------------------------------

// A floating-point array as C-contiguous float32: no copy when it already is one.
py::array_t<float, py::array::c_style> float32_array(const py::handle& object, const char* what) {
    if (!py::isinstance<py::array>(object) && !py::isinstance<py::sequence>(object))
        throw py::value_error(std::string(what) + ": expected a NumPy array of floats");
    const py::array array = py::array::ensure(object);
    if (!array) throw py::value_error(std::string(what) + ": expected a NumPy array of floats");
    const char kind = array.dtype().kind();
    if (kind != 'f' && !(kind == 'i' && array.size() == 0))
        throw py::value_error(std::string(what) + ": expected floats, got dtype " +
                              std::string(py::str(array.dtype())));
    return py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(array);
}

std::string label_or_unknown(const ModelData& model, int label) {
    return label < 0 ? std::string("unknown") : model.label_names[static_cast<std::size_t>(label)];
}

py::object label_object(const ModelData& model, LabelId label) {
    if (label == unknown_label) return py::none();
    return py::str(model.label_names[label]);
}

// ---- clips -------------------------------------------------------------------

// A clip from arrays: positions (frames, joints, 3) in metres, times in seconds
// or a frame rate, joint names (Kinect v1, v2 or Azure Kinect when omitted and the count says so),
// the skeleton's tree as given, else a Kinect SDK's when the names are all of one.
LabelledClip clip_from_arrays(const py::handle& positions_object, const py::object& times_object, double frame_rate,
                              const py::object& joint_names_object, const std::string& label,
                              const std::string& subject, int up_axis, const py::object& roles_object,
                              const std::string& source, const py::object& parents_object) {
    const auto positions = float32_array(positions_object, "positions");
    if (positions.ndim() != 3 || positions.shape(2) != 3)
        throw py::value_error("positions: expected shape (frames, joints, 3), got " +
                              std::string(py::str(py::cast(
                                  std::vector<py::ssize_t>(positions.shape(), positions.shape() + positions.ndim())))));
    const auto frames = static_cast<std::size_t>(positions.shape(0));
    const auto joints = static_cast<std::size_t>(positions.shape(1));
    if (frames == 0 || joints == 0) throw py::value_error("positions: no frames or no joints");
    LabelledClip out;
    out.label = label;
    out.subject = subject;
    host::Clip& clip = out.clip;
    clip.source = source;
    const float* data = positions.data();
    clip.positions.assign(data, data + frames * joints * 3);
    for (std::size_t i = 0; i < clip.positions.size(); ++i)
        if (!std::isfinite(clip.positions[i]))
            throw py::value_error("positions: frame " + std::to_string(i / (joints * 3)) + ", joint " +
                                  std::to_string(i / 3 % joints) + " is NaN or infinite");
    if (!times_object.is_none()) {
        const auto times = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(times_object);
        if (!times || times.ndim() != 1 || static_cast<std::size_t>(times.shape(0)) != frames)
            throw py::value_error("times: expected one time in seconds per frame (" + std::to_string(frames) + ")");
        clip.times.assign(times.data(), times.data() + frames);
        for (std::size_t f = 0; f < frames; ++f)
            if (!std::isfinite(clip.times[f]) || (f > 0 && clip.times[f] < clip.times[f - 1]))
                throw py::value_error("times: not finite and non-decreasing at frame " + std::to_string(f));
    } else {
        if (!(frame_rate > 0.0 && frame_rate <= 1e6))
            throw py::value_error("give times (seconds per frame) or a positive frame_rate");
        for (std::size_t f = 0; f < frames; ++f) clip.times.push_back(static_cast<double>(f) / frame_rate);
    }
    if (!joint_names_object.is_none()) {
        clip.joint_names = joint_names_object.cast<std::vector<std::string>>();
        if (clip.joint_names.size() != joints)
            throw py::value_error("joint_names: " + std::to_string(clip.joint_names.size()) + " names for " +
                                  std::to_string(joints) + " joints");
    } else if (joints == host::kinect_v1_joint_names().size()) {
        clip.joint_names = host::kinect_v1_joint_names();
    } else if (joints == host::kinect_v2_joint_names().size()) {
        clip.joint_names = host::kinect_v2_joint_names();
    } else if (joints == host::azure_kinect_joint_names().size()) {
        clip.joint_names = host::azure_kinect_joint_names();
    } else {
        throw py::value_error("joint_names: needed for a skeleton of " + std::to_string(joints) +
                              " joints (20, 25 and 32 are taken as Kinect v1, Kinect v2 and Azure Kinect)");
    }
    if (up_axis < 0 || up_axis > 2) throw py::value_error("up_axis: 0, 1 or 2");
    clip.up_axis = up_axis;
    host::RoleNames roles;
    if (!roles_object.is_none()) {
        const auto names = roles_object.cast<std::vector<std::string>>();
        if (names.size() != 3) throw py::value_error("roles: (root, left hip, right hip) joint names");
        roles = host::RoleNames{names[0], names[1], names[2]};
    }
    if (!parents_object.is_none()) {
        clip.parents = parents_object.cast<std::vector<int>>();
        host::check_tree(clip.parents, joints);  // std::invalid_argument: ValueError
    } else {
        clip.parents = host::sdk_parents(clip.joint_names);  // empty unless the names are one SDK's
    }
    host::flag_lost_frames(clip);
    host::assign_roles(clip, roles);
    return out;
}

py::array positions_view(const py::object& self) {
    const LabelledClip& c = self.cast<const LabelledClip&>();
    const auto frames = static_cast<py::ssize_t>(c.clip.frame_count());
    const auto joints = static_cast<py::ssize_t>(c.clip.joint_count());
    py::array_t<float> view({frames, joints, py::ssize_t{3}},
                            {joints * 3 * static_cast<py::ssize_t>(sizeof(float)),
                             3 * static_cast<py::ssize_t>(sizeof(float)), static_cast<py::ssize_t>(sizeof(float))},
                            c.clip.positions.data(), self);
    view.attr("setflags")(py::arg("write") = false);
    return view;
}

py::array times_view(const py::object& self) {
    const LabelledClip& c = self.cast<const LabelledClip&>();
    py::array_t<double> view({static_cast<py::ssize_t>(c.clip.frame_count())}, {py::ssize_t{sizeof(double)}},
                             c.clip.times.data(), self);
    view.attr("setflags")(py::arg("write") = false);
    return view;
}

// The sensor's up direction given as (x, y, z): three numbers, else ValueError
// (the runtime and the readers then check that it is a direction).
std::array<float, 3> up_direction(const py::handle& value) {
    std::vector<float> up;
    if (!py::isinstance<py::str>(value)) {
        try {
            up = value.cast<std::vector<float>>();
        } catch (const py::cast_error&) {
            up.clear();
        }
    }
    if (up.size() != 3)
        throw py::value_error("up: expected (x, y, z), the sensor's up direction, not " + std::string(py::repr(value)));
    return {up[0], up[1], up[2]};
}

host::ReadOptions read_options(double rate, double scale, int up_axis, const py::object& roles,
                               const std::string& time_unit = "", int body = -1, const std::string& columns = "",
                               const py::object& up = py::none(), const py::object& parents = py::none()) {
    host::ReadOptions read;
    if (!parents.is_none()) {  // each joint's parent by name, None or "-" for a root (as --parents)
        for (const py::handle name : parents) read.parents.push_back(name.is_none() ? "-" : name.cast<std::string>());
        if (read.parents.empty()) throw py::value_error("parents: one parent name per joint (None or '-' for a root)");
    }
    if (!up.is_none()) {
        const std::array<float, 3> direction = up_direction(up);
        for (int a = 0; a < 3; ++a) read.up[a] = direction[static_cast<std::size_t>(a)];
    }
    read.columns = columns;
    if (!time_unit.empty()) read.time_unit_s = host::parse_time_unit(time_unit);
    if (body < -1 || body > 63) throw py::value_error("body: 0 to 63, or -1 for the one that moves most");
    read.body = body;
    read.frame_rate_hz = rate;
    read.length_scale = scale;
    read.up_axis = up_axis;
    if (!roles.is_none()) {
        const auto names = roles.cast<std::vector<std::string>>();
        if (names.size() != 3) throw py::value_error("roles: (root, left hip, right hip) joint names");
        read.roles = host::RoleNames{names[0], names[1], names[2]};
    }
    return read;
}

// A clip conformed to the model's input skeleton (by joint name), as the CLI does.
host::Clip conformed(const ModelData& model, const LabelledClip& clip) {
    host::Clip copy = clip.clip;
    host::conform_to_model(model.view(), copy);
    return copy;
}

// ---- settings ----------------------------------------------------------------

// Python keyword names (string_rate) as the CLI spells them (string-rate); values as text.
std::string setting_name(const std::string& key) {
    std::string name = key;
    for (char& c : name)
        if (c == '_') c = '-';
    return name;
}

std::string setting_value(const py::handle& value) {
    if (py::isinstance<py::bool_>(value)) return value.cast<bool>() ? "true" : "false";
    if (py::isinstance<py::str>(value)) return value.cast<std::string>();
    if (py::isinstance<py::float_>(value) || py::isinstance<py::int_>(value)) {
        const double v = value.cast<double>();
        if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
        return std::string(py::str(value));
    }
    if (py::isinstance<py::sequence>(value)) {  // roles=("root", "lhip", "rhip")
        std::string joined;
        for (const auto& item : value.cast<py::sequence>()) joined += (joined.empty() ? "" : ",") + setting_value(item);
        return joined;
    }
    throw py::value_error("setting value " + std::string(py::repr(value)) + " is not a number, bool or string");
}

AnnotatorConfig online_config(const ModelData& model, const py::dict& settings) {
    AnnotatorConfig config = annotator_config(model.view());
    for (const auto& item : settings) {
        const std::string key = item.first.cast<std::string>();
        if (key == "window_rule") config.window_rule = item.second.cast<bool>();
        else if (key == "spread_work") config.spread_work = item.second.cast<bool>();
        else if (key == "max_gap") config.max_gap_us = std::llround(item.second.cast<double>() * 1e6);
        else if (key == "max_backward") config.max_backward_us = std::llround(item.second.cast<double>() * 1e6);
        else if (key == "up") {  // the sensor's up direction, (x, y, z); (0, 0, 0) for none
            const std::array<float, 3> up = up_direction(item.second);
            for (int a = 0; a < 3; ++a) config.up[a] = up[static_cast<std::size_t>(a)];
        } else if (!host::apply_online_setting(setting_name(key), setting_value(item.second), config))
            throw py::value_error(
                "unknown online setting '" + key +
                "' (settle, settle_stable, segment_penalty, stay_penalty, skip_penalty, unknown_cost, segment_votes, segment_exemplars, segment_directions, "
                "window_rule, spread_work, max_gap, max_backward, max_pose_speed, min_action, label_lead, up)");
    }
    return config;
}

// A recording built from a clip of a whole stream and its labelled intervals:
// each (label, start, end) in seconds on the clip's time axis, start < end.
host::LabelledRecording recording_from_clip(const LabelledClip& clip, const py::sequence& intervals,
                                            const py::object& subject) {
    host::LabelledRecording recording;
    recording.subject = subject.is_none() ? clip.subject : subject.cast<std::string>();
    recording.clip = clip.clip;
    for (const py::handle item : intervals) {
        const auto interval = item.cast<py::sequence>();
        if (interval.size() != 3) throw py::value_error("an interval is (label, start, end)");
        host::LabelledRecording::Interval in;
        try {
            in.label = interval[0].cast<std::string>();
            in.start_s = interval[1].cast<double>();
            in.end_s = interval[2].cast<double>();
        } catch (const py::cast_error&) {
            throw py::value_error("an interval is (label, start, end): a string and two numbers of seconds");
        }
        if (in.label.empty()) throw py::value_error("an interval needs a label");
        if (!std::isfinite(in.start_s) || !std::isfinite(in.end_s) || !(in.start_s < in.end_s))
            throw py::value_error("interval '" + in.label + "': start must be finite and before end");
        recording.intervals.push_back(in);
    }
    if (recording.intervals.empty()) throw py::value_error("a recording needs at least one labelled interval");
    host::note_interval_overlaps(recording);
    return recording;
}

// ---- training ------------------------------------------------------------------

py::tuple train(const std::vector<LabelledClip>& clips, const py::dict& settings, bool tune, const std::string& config,
                bool tune_online, const std::vector<host::LabelledRecording>& recordings) {
    host::TrainingOptions options = tune ? host::tuning_start() : host::TrainingOptions{};
    host::ReadOptions unused;
    if (!config.empty()) host::read_training_config(config, options, unused);
    for (const auto& item : settings) {
        const std::string key = item.first.cast<std::string>();
        if (!host::apply_training_setting(setting_name(key), setting_value(item.second), options, unused))
            throw py::value_error("unknown training setting '" + key + "'");
        if (key == "rate" || key == "roles" || key == "time_unit" || key == "length_unit" || key == "body" ||
            key == "columns" || key == "up" || key == "parents")
            throw py::value_error("'" + key + "' is a reading setting: give it to read_clip or read_clip_list");
    }
    if (clips.empty()) throw py::value_error("no clips to train on");
    py::dict report;
    std::shared_ptr<ModelData> model;
    host::OnlineTuningResult online;
    host::TuningResult tuned;
    {
        py::gil_scoped_release release;
        // As `actionstring train` with no settings: the clip settings, then the online ones;
        // with tune_online (`train --tune-online`) the clip settings as given.
        if (tune) {
            tuned = host::tune_training(clips, options);
            options = tuned.options;
        }
        // As `actionstring train` on a list of intervals: the recordings' stretches outside every
        // interval teach "no action", and the online search streams the recordings whole.
        const std::vector<LabelledClip> no_action = host::unlabelled_stretches(recordings, 1.0);
        if (tune || tune_online) {
            online = host::tune_online(clips, options, recordings.empty() ? nullptr : &recordings);
            host::adopt_online_tuning(online, options);
        }
        host::TrainingReport training;
        model = std::make_shared<ModelData>(host::train_model(clips, options, &training, &no_action));
        py::gil_scoped_acquire acquire;
        report["representatives"] = training.representatives;
        report["representative_chars"] = training.representative_chars;
        report["representative_budget"] = training.representative_budget;  // what a share allowed (0 without)
        report["characters"] = training.characters;
        report["frames_used"] = training.frames_used;
        report["frames_rejected"] = training.frames_rejected;
        report["no_action_stretches"] = training.no_action_stretches;
    }
    report["settings"] = host::options_as_config(options);
    if (!tuned.steps.empty()) {
        // The clip search's table and the folds of its choice, as `train` prints them.
        py::list steps, folds;
        for (const host::TuningStep& step : tuned.steps) {
            py::dict row;
            row["settings"] = step.setting;
            row["fold_mean"] = step.mean_accuracy;
            row["margin"] = step.mean_margin;
            row["kept"] = step.kept;
            steps.append(row);
        }
        for (const host::FoldResult& fold : tuned.folds) {
            py::dict row;
            row["held_out"] = fold.subject;
            row["clips"] = fold.clips;
            row["accuracy"] = fold.clip_accuracy;
            row["margin"] = fold.margin;
            folds.append(row);
        }
        py::dict tuning;
        tuning["settings"] = steps;
        tuning["folds"] = folds;
        tuning["seconds"] = tuned.seconds;
        report["tuning"] = tuning;
    }
    if (!online.steps.empty()) {
        // The online search's table (means over the held-out subjects' streams), as `train` prints it.
        py::list settings_tried, stables, min_actions, leads;
        for (const host::OnlineTuningStep& step : online.steps) {
            py::dict row;
            row["settings"] = step.settings;
            row["segment_f1"] = step.segment_f1;
            row["frame_accuracy"] = step.frame_accuracy;
            row["detection_latency"] = step.detection_latency_s;
            row["kept"] = step.kept;
            settings_tried.append(row);
        }
        // A row of a choice by the events (early settling, the shortest action).
        auto events_row = [](const char* name, std::int64_t value_us, const host::EventsScore& step) {
            py::dict row;
            row[name] = static_cast<double>(value_us) * 1e-6;
            row["event_segment_f1"] = step.event_segment_f1;
            row["standard_error"] = step.standard_error;
            row["difference"] = step.difference;              // from the best, fold by fold
            row["difference_error"] = step.difference_error;  // its standard error
            row["detection_latency"] = step.detection_latency_s;
            row["frame_accuracy"] = step.frame_accuracy;
            row["kept"] = step.kept;
            return row;
        };
        for (const host::SettleStableStep& step : online.settle_stable_steps)
            stables.append(events_row("settle_stable", step.settle_stable_us, step));
        for (const host::MinActionStep& step : online.min_action_steps)
            min_actions.append(events_row("min_action", step.min_action_us, step));
        for (const host::LabelLeadStep& step : online.label_lead_steps) {
            py::dict row;
            row["label_lead"] = static_cast<double>(step.label_lead_us) * 1e-6;
            row["frame_accuracy"] = step.frame_accuracy;
            row["segment_f1"] = step.segment_f1;
            row["kept"] = step.kept;
            leads.append(row);
        }
        py::list windows;
        for (const host::DirectionWindowStep& step : online.direction_window_steps) {
            py::dict row;
            row["segment_directions"] = static_cast<double>(step.direction_weight);
            row["frame_accuracy"] = step.frame_accuracy;
            row["segment_f1"] = step.segment_f1;
            row["kept"] = step.kept;
            windows.append(row);
        }
        py::dict tuning;
        tuning["settings"] = settings_tried;
        tuning["direction_window"] = windows;
        tuning["direction_window_s"] = online.direction_window_s_tried;
        tuning["settle_stable"] = stables;
        tuning["min_action"] = min_actions;
        tuning["label_lead"] = leads;
        tuning["latency_budget_met"] = online.latency_budget_met;
        tuning["seconds"] = online.seconds;
        report["online_tuning"] = tuning;
    }
    return py::make_tuple(ModelPtr(model), report);
}

// ---- streaming -----------------------------------------------------------------

/// One annotator bound to a model it keeps alive, with storage sized for it.
class StreamAnnotator {
public:
    StreamAnnotator(ModelPtr model, const py::dict& settings)
        : model_(std::move(model)), view_(model_->view()), config_(online_config(*model_, settings)) {
        const Status status = annotator_.init(view_, config_);
        if (status != Status::ok) throw py::value_error(host::annotator_refusal(view_, config_, status));
    }

    py::dict push_frame(double time_s, const py::handle& positions_object) {
        const std::size_t expected = 3u * view_.joint_count;
        if (!std::isfinite(time_s)) throw py::value_error("time_s: not a finite number of seconds");
        // Zero-copy when the frame is already C-contiguous float32.
        const auto positions = float32_array(positions_object, "positions");
        if (static_cast<std::size_t>(positions.size()) != expected ||
            !(positions.ndim() == 1 || (positions.ndim() == 2 && positions.shape(1) == 3)))
            throw py::value_error("positions: expected shape (" + std::to_string(view_.joint_count) +
                                  ", 3) for the model's skeleton, got " + std::to_string(positions.size()) + " values");
        const std::int64_t time_us = std::llround(time_s * 1e6);
        const FrameResult r = annotator_->push_frame(time_us, positions.data());
        py::dict out;
        out["events"] = events();
        out["status"] = status_name(r.status);
        out["accepted"] = r.status == Status::ok || r.status == Status::stream_restarted;
        out["characters"] = r.characters;
        out["windows_completed"] = r.windows_completed;
        out["settled"] = settled(r);
        out["flushed"] = flushed();
        out["live_label"] = label_object(*model_, annotator_->live_label());
        out["live_margin"] = annotator_->live_margin();
        return out;
    }

    /// With spread_work: the work of the characters in progress, done now.
    py::dict finish_work() {
        const FrameResult r = annotator_->finish_work();
        py::dict out;
        out["events"] = events();
        out["settled"] = settled(r);
        out["live_label"] = label_object(*model_, annotator_->live_label());
        out["live_margin"] = annotator_->live_margin();
        return out;
    }

    /// Ends the stream: the unsettled tail takes its labels, a running action ends.
    py::list flush() {
        annotator_->flush();
        return events();
    }

    /// The ended stream's characters whose labels the last push_frame()
    /// (a restart) or flush() made final: (index, label time in seconds, label).
    py::list flushed() const {
        py::list out;
        for (std::size_t i = 0; i < annotator_->flushed_characters(); ++i)
            out.append(py::make_tuple(annotator_->flushed_character(i),
                                      static_cast<double>(annotator_->flushed_label_time_us(i)) * 1e-6,
                                      label_object(*model_, annotator_->flushed_label(i))));
        return out;
    }

    void reset() { annotator_->reset(); }
    py::object live_label() const { return label_object(*model_, annotator_->live_label()); }
    float live_margin() const { return annotator_->live_margin(); }
    py::object label() const { return label_object(*model_, annotator_->label()); }
    float confidence() const { return annotator_->confidence(); }
    std::uint64_t characters() const { return annotator_->characters(); }
    std::uint32_t settle_chars() const { return annotator_->settle_chars(); }
    std::size_t state_bytes() const { return annotator_.storage_bytes(); }
    ModelPtr model() const { return model_; }

private:
    // The characters a frame settled: (index, label time in seconds, label).
    py::list settled(const FrameResult& r) const {
        py::list out;
        if (r.characters_settled == 0) return out;
        const std::uint64_t last = annotator_->settled_character();
        for (std::uint64_t c = last + 1 - r.characters_settled; c <= last; ++c)
            out.append(py::make_tuple(c, static_cast<double>(annotator_->label_time_us(c)) * 1e-6,
                                      label_object(*model_, annotator_->settled_label(c))));
        return out;
    }

    // The events of the last push_frame() or flush(), as dicts.
    py::list events() const {
        py::list out;
        for (std::size_t i = 0; i < annotator_->event_count(); ++i) {
            const ActionEvent& e = annotator_->event(i);
            py::dict d;
            d["event"] = e.kind == ActionEvent::Kind::started ? "started" : "ended";
            d["label"] = model_->label_names[e.label];
            d["start"] = static_cast<double>(e.start_time_us) * 1e-6;
            d["end"] = static_cast<double>(e.end_time_us) * 1e-6;
            d["confidence"] = e.confidence;
            out.append(d);
        }
        return out;
    }

    ModelPtr model_;
    ModelView view_;
    AnnotatorConfig config_;
    host::Stateful<Annotator> annotator_;
};

}  // namespace
}  // namespace python
}  // namespace actionstring

PYBIND11_MODULE(_actionstring, m) {
    using namespace actionstring;
    using namespace actionstring::python;
    m.doc() = "actionstring: real-time action recognition from skeleton motion (the C++ library, bound).";
    m.attr("__version__") = actionstring::version_string();
    static py::exception<host::ReadError> read_error(m, "ReadError", PyExc_ValueError);
    py::register_exception_translator([](std::exception_ptr p) {
        try {
            if (p) std::rethrow_exception(p);
        } catch (const host::ReadError& e) {
            read_error(e.what());
        } catch (const std::bad_alloc&) {
            PyErr_SetString(PyExc_MemoryError, "out of memory");
        }
    });

    py::class_<LabelledClip>(m, "Clip", "One recording: joint positions per frame, times, joint names, label, subject.")
        .def(py::init(&clip_from_arrays), py::arg("positions"), py::arg("times") = py::none(),
             py::arg("frame_rate") = 0.0, py::arg("joint_names") = py::none(), py::arg("label") = "",
             py::arg("subject") = "", py::arg("up_axis") = 1, py::arg("roles") = py::none(),
             py::arg("source") = "<array>", py::arg("parents") = py::none())
        .def_property_readonly("positions", &positions_view,
                               "(frames, joints, 3) float32, metres; a read-only view of the clip's memory")
        .def_property_readonly("times", &times_view, "(frames,) float64, seconds; a read-only view")
        .def_property_readonly("joint_names", [](const LabelledClip& c) { return c.clip.joint_names; })
        .def_property_readonly(
            "parents", [](const LabelledClip& c) { return c.clip.parents; },
            "Each joint's parent (-1 at a root): the file's tree, the one given, or a Kinect SDK's when the "
            "joint names are all of one; empty when there is none (bone and torso scaling then refuse)")
        .def_property_readonly("source", [](const LabelledClip& c) { return c.clip.source; })
        .def_property_readonly("up_axis", [](const LabelledClip& c) { return c.clip.up_axis; })
        .def_property_readonly("frame_count", [](const LabelledClip& c) { return c.clip.frame_count(); })
        .def_property_readonly("joint_count", [](const LabelledClip& c) { return c.clip.joint_count(); })
        .def_property_readonly("duration", [](const LabelledClip& c) { return c.clip.duration(); })
        .def_property_readonly(
            "notes", [](const LabelledClip& c) { return c.clip.notes; },
            "What the reader noticed: columns ignored, a time unit detected, a warning")
        .def(
            "relabelled",
            [](const LabelledClip& c, const std::string& label, const std::string& subject) {
                LabelledClip copy = c;
                copy.label = label;
                copy.subject = subject;
                return copy;
            },
            "A copy of the clip with another label and subject.", py::arg("label"), py::arg("subject"))
        .def_readwrite("label", &LabelledClip::label)
        .def_readwrite("subject", &LabelledClip::subject)
        .def("__repr__", [](const LabelledClip& c) {
            return "<Clip " + c.clip.source + ": " + std::to_string(c.clip.frame_count()) + " frames, " +
                   std::to_string(c.clip.joint_count()) + " joints, label '" + c.label + "'>";
        });

    m.def(
        "_read_clip",
        [](const std::string& path, double rate, double scale, int up_axis, const py::object& roles,
           const std::string& skeleton, const std::string& time_unit, int body, const std::string& columns,
           const py::object& up, const py::object& parents) {
            LabelledClip out;
            out.clip = host::read_clip(
                path, read_options(rate, scale, up_axis, roles, time_unit, body, columns, up, parents), skeleton);
            return out;
        },
        py::arg("path"), py::arg("rate") = 0.0, py::arg("scale") = 0.0, py::arg("up_axis") = -1,
        py::arg("roles") = py::none(), py::arg("skeleton") = "", py::arg("time_unit") = "", py::arg("body") = -1,
        py::arg("columns") = "", py::arg("up") = py::none(), py::arg("parents") = py::none());
    m.def(
        "_read_clip_list",
        [](const std::string& path, double rate, double scale, int up_axis, const py::object& roles,
           const py::object& up, const py::object& parents) {
            return host::load_labelled_clips(path, read_options(rate, scale, up_axis, roles, "", -1, "", up, parents));
        },
        py::arg("path"), py::arg("rate") = 0.0, py::arg("scale") = 0.0, py::arg("up_axis") = -1,
        py::arg("roles") = py::none(), py::arg("up") = py::none(), py::arg("parents") = py::none());

    py::class_<host::LabelledRecording>(
        m, "Recording", "A continuous recording with its labelled intervals; every frame outside them is no action.")
        .def(py::init(&recording_from_clip), py::arg("clip"), py::arg("intervals"), py::arg("subject") = py::none())
        .def_property_readonly(
            "clip",
            [](const host::LabelledRecording& r) {
                return LabelledClip{r.clip, "", r.subject};
            },
            "The whole recording as a Clip (no label; a copy)")
        .def_property_readonly(
            "intervals",
            [](const host::LabelledRecording& r) {
                py::list out;
                for (const auto& interval : r.intervals)
                    out.append(py::make_tuple(interval.label, interval.start_s, interval.end_s));
                return out;
            },
            "(label, start, end) per labelled interval, seconds on the recording's time axis")
        .def_readonly("subject", &host::LabelledRecording::subject)
        .def_readonly("notes", &host::LabelledRecording::notes,
                      "What a user should know about the intervals: each pair that overlaps, and which label "
                      "their shared frames take (the one that starts later)")
        .def_property_readonly("source", [](const host::LabelledRecording& r) { return r.clip.source; })
        .def_property_readonly("frame_count", [](const host::LabelledRecording& r) { return r.clip.frame_count(); })
        .def_property_readonly("duration", [](const host::LabelledRecording& r) { return r.clip.duration(); })
        .def("__repr__", [](const host::LabelledRecording& r) {
            return "<Recording " + r.clip.source + ": " + std::to_string(r.clip.frame_count()) + " frames, " +
                   std::to_string(r.intervals.size()) + " intervals, subject '" + r.subject + "'>";
        });
    m.def(
        "_read_recordings",
        [](const std::string& path, double rate, double scale, int up_axis, const py::object& roles,
           const py::object& up, const py::object& parents) {
            const std::vector<host::ClipListEntry> entries = host::read_clip_list(path);
            if (!host::has_intervals(entries))
                throw py::value_error(path +
                                      ": the list gives no intervals ('start' and 'end' columns): it names clips, not "
                                      "continuous recordings (read it with read_clip_list)");
            return host::read_recordings(entries, read_options(rate, scale, up_axis, roles, "", -1, "", up, parents));
        },
        py::arg("path"), py::arg("rate") = 0.0, py::arg("scale") = 0.0, py::arg("up_axis") = -1,
        py::arg("roles") = py::none(), py::arg("up") = py::none(), py::arg("parents") = py::none());

    py::class_<ModelData, ModelPtr>(m, "_Model")
        .def_static(
            "load",
            [](const std::string& path) { return ModelPtr(std::make_shared<ModelData>(host::load_model(path))); })
        .def_static("from_blob",
                    [](const py::bytes& bytes) {
                        return ModelPtr(std::make_shared<ModelData>(host::read_blob("<bytes>", std::string(bytes))));
                    })
        .def("save", [](const ModelData& model, const std::string& path) { host::save_model(model, path); })
        .def("save_blob",
             [](const ModelData& model, const std::string& path) { host::write_file(path, host::write_blob(model)); })
        .def("to_blob", [](const ModelData& model) { return py::bytes(host::write_blob(model)); })
        .def("artifact", [](const ModelData& model) { return host::serialize_model(model); })
        .def("write_header",
             [](const ModelData& model, const std::string& path, const std::string& ns) {
                 const std::string text = host::serialize_model(model);
                 const std::size_t slash = path.find_last_of('/');
                 host::write_file(path,
                                  host::generate_header(model, host::artifact_checksum(text), ns,
                                                        slash == std::string::npos ? path : path.substr(slash + 1)));
             })
        .def_property_readonly("label_names", [](const ModelData& model) { return model.label_names.strings(); })
        .def_property_readonly("joint_names", [](const ModelData& model) { return model.joint_names.strings(); })
        .def_property_readonly("representative_count",
                               [](const ModelData& model) { return model.view().representative_count; })
        .def_property_readonly("character_count", [](const ModelData& model) { return model.character_count; })
        .def_property_readonly("component_count", [](const ModelData& model) { return model.component_count; })
        .def_property_readonly("feature_dim", [](const ModelData& model) { return model.feature_dim; })
        .def_property_readonly("string_rate_hz",
                               [](const ModelData& model) { return 1e6 / static_cast<double>(model.string_period_us); })
        .def_property_readonly("table_bytes", [](const ModelData& model) { return host::table_bytes(model.view()); })
        .def_property_readonly("online_settings",
                               [](const ModelData& model) {
                                   py::dict d;
                                   d["settle"] = static_cast<double>(model.settle_delay_us) * 1e-6;
                                   d["settle_stable"] = static_cast<double>(model.settle_stable_us) * 1e-6;
                                   d["segment_penalty"] = model.segment_penalty;
                                   d["stay_penalty"] = model.stay_penalty;
                                   d["skip_penalty"] = model.skip_penalty;
                                   d["unknown_cost"] = model.unknown_cost;
                                   d["segment_votes"] = model.segment_vote_weight;
                                   d["segment_exemplars"] = model.segment_exemplar_weight;
                                   d["segment_directions"] = model.segment_direction_weight;
                                   d["min_action"] = static_cast<double>(model.min_action_us) * 1e-6;
                                   d["label_lead"] = static_cast<double>(model.label_lead_us) * 1e-6;
                                   return d;
                               })
        .def("state_bytes",
             [](const ModelData& model, const py::dict& settings) {
                 return Annotator::required_bytes(model.view(), online_config(model, settings));
             })
        .def("label_distances",
             [](const ModelData& model, const LabelledClip& clip) {
                 const std::vector<float> d = host::label_distances(model.view(), conformed(model, clip));
                 py::array_t<float> out(static_cast<py::ssize_t>(d.size()));
                 if (!d.empty()) std::memcpy(out.mutable_data(), d.data(), d.size() * sizeof(float));
                 return out;
             })
        .def("classify",
             [](const ModelData& model, const LabelledClip& clip) {
                 const ModelView view = model.view();
                 const Classification c = host::classify_clip(view, conformed(model, clip));
                 return py::make_tuple(label_object(model, c.label), c.distance, c.confidence);
             })
        .def("_evaluate_json",
             [](const ModelData& model, std::vector<LabelledClip> clips, std::vector<LabelledClip> train, bool online,
                std::uint32_t seed, const py::dict& settings, const std::string& name, const std::string& perturb,
                std::vector<host::LabelledRecording> recordings) {
                 const ModelView view = model.view();
                 const AnnotatorConfig config = online_config(model, settings);
                 const host::Perturbation perturbation =
                     perturb.empty() ? host::Perturbation{} : host::parse_perturbation(perturb);
                 const bool whole = !recordings.empty();
                 py::gil_scoped_release release;
                 host::Evaluation e = host::evaluate(view, std::move(clips), std::move(train), std::move(recordings),
                                                     online, seed, config, perturbation);
                 e.recordings = whole;  // as `eval` on a list of intervals
                 return host::evaluation_json(e, name, seed, config);
             })
        .def("annotate", [](const ModelData& model, const LabelledClip& clip, const py::dict& settings) {
            const ModelView view = model.view();
            const auto spans = host::annotate_clip(view, conformed(model, clip), online_config(model, settings));
            py::list out;
            for (const host::LabelSpan& span : spans) {
                py::dict d;
                d["start"] = span.start_s;
                d["end"] = span.end_s;
                d["label"] = label_or_unknown(model, span.label);
                d["confidence"] = span.agreement;
                out.append(d);
            }
            return out;
        });

    m.def("_train", &train, py::arg("clips"), py::arg("settings"), py::arg("tune"), py::arg("config") = "",
          py::arg("tune_online") = false, py::arg("recordings") = std::vector<host::LabelledRecording>{});
    m.def("_training_setting_names", &host::training_setting_names);

    py::class_<StreamAnnotator>(m, "_Annotator")
        .def(py::init<ModelPtr, const py::dict&>())
        .def("push_frame", &StreamAnnotator::push_frame, py::arg("time_s"), py::arg("positions"))
        .def("reset", &StreamAnnotator::reset)
        .def("flush", &StreamAnnotator::flush)
        .def("flushed", &StreamAnnotator::flushed)
        .def("finish_work", &StreamAnnotator::finish_work,
             "With spread_work=True: finishes the characters whose work is being spread, now; returns what a "
             "frame returns (settled, events, live_label, live_margin)")
        .def_property_readonly("live_label", &StreamAnnotator::live_label)
        .def_property_readonly("live_margin", &StreamAnnotator::live_margin)
        .def_property_readonly("label", &StreamAnnotator::label)
        .def_property_readonly("confidence", &StreamAnnotator::confidence)
        .def_property_readonly("characters", &StreamAnnotator::characters)
        .def_property_readonly("settle_chars", &StreamAnnotator::settle_chars)
        .def_property_readonly("state_bytes", &StreamAnnotator::state_bytes);

    m.def(
        "_toy_clips",
        [](int performances, std::uint32_t seed) {
            const host::ToyWorld world = host::make_toy_world();
            return host::toy_clips(world, performances, seed);
        },
        "Synthetic clips of the toy world (5 joints, 4 actions): for tests and examples, not accuracy.",
        py::arg("performances"), py::arg("seed") = 1);
}
