// actionstring host library — training and online settings by name: the names
// `actionstring train` takes as options (without the dashes) and in config
// files, and the Python package takes as keyword arguments. One table, so the
// command line, config files and Python accept exactly the same settings.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "actionstring/annotator.hpp"
#include "actionstring/segmenter.hpp"
#include "io/clip.hpp"
#include "train/options.hpp"

namespace actionstring {
namespace host {

/// The whole of `text` as a number in [low, high], or nothing.
std::optional<double> parse_real(const std::string& text, double low, double high);
/// The same for a count or an index: nothing too when the number has a
/// fraction (so that "2.5" is refused where a count is due, not truncated).
std::optional<double> parse_whole(const std::string& text, double low, double high);
/// "[low, high]" as the messages print a range.
std::string range_text(double low, double high);

/// Applies one of the segmenter's settings (settle, segment-penalty,
/// stay-penalty, skip-penalty, unknown-cost). The settle delay is taken up to
/// a minute here: the runtime holds up to 10 minutes, but a longer delay than
/// a minute is a mistake in a labelling tool. Returns false when `name` is not
/// one; throws std::invalid_argument ("option --NAME expects …") for a bad value.
bool apply_segmenter_setting(const std::string& name, const std::string& value, SegmenterConfig& config);

/// Applies one of the online settings a model carries to a runtime config:
/// the segmenter's (apply_segmenter_setting()), the events' shortest action
/// (min-action, in seconds, up to a minute) or the label lead (label-lead, in
/// seconds, up to a minute); or the stream's max-pose-speed (metres per
/// second, AnnotatorConfig::max_pose_speed), which no model carries. Returns
/// false when `name` is not one; throws std::invalid_argument for a bad value.
bool apply_online_setting(const std::string& name, const std::string& value, AnnotatorConfig& config);

/// Applies one training setting (components, pca, velocity, sigma, …, the
/// segmenter's, and the reading settings rate and roles). Returns false when
/// `name` is not one; throws std::invalid_argument for a bad value.
bool apply_training_setting(const std::string& name, const std::string& value, TrainingOptions& options,
                            ReadOptions& read);

/// Every name apply_training_setting() takes, in the order `train --help` lists them.
const std::vector<std::string>& training_setting_names();

/// Applies a config file: 'setting value' lines with the option names
/// without dashes, # comments (what `train --config` reads). Throws ReadError
/// naming the file and line of an unknown setting or a bad value.
void read_training_config(const std::string& path, TrainingOptions& options, ReadOptions& read);

/// "s", "ms" or "us" → seconds per unit; throws std::invalid_argument.
double parse_time_unit(const std::string& text);

/// "m", "dm", "cm", "mm" or "in" → metres per unit (a file's length unit); throws std::invalid_argument.
double parse_length_unit(const std::string& text);

/// "ROOT,LEFT_HIP,RIGHT_HIP" → role names; throws std::invalid_argument.
RoleNames parse_role_names(const std::string& text);

/// A setting's value as a config file writes it ("%g": 0.25, 1e-06, inf).
std::string setting_value_text(double value);

}  // namespace host
}  // namespace actionstring
