// actionstring host library — continuous recordings with labelled intervals.
#pragma once

#include <string>
#include <vector>

#include "io/clip.hpp"
#include "io/clip_list.hpp"

namespace actionstring {
namespace host {

/// A continuous recording with its labelled intervals (seconds on the clip's
/// time axis); every frame outside them is "no action".
struct LabelledRecording {
    std::string subject;
    Clip clip;
    struct Interval {
        std::string label;
        double start_s = 0, end_s = 0;
    };
    std::vector<Interval> intervals;
};

/// Groups a clip list's interval entries by file (first appearance order) and
/// reads each file once, whole. Entries without an interval are refused.
std::vector<LabelledRecording> read_recordings(const std::vector<ClipListEntry>& entries, const ReadOptions& read = {});

/// The stretches of each recording outside every labelled interval, at least
/// `min_seconds` long, as clips (label "", the recording's subject): examples
/// of no action, for train_model().
std::vector<LabelledClip> unlabelled_stretches(const std::vector<LabelledRecording>& recordings, double min_seconds);

}  // namespace host
}  // namespace actionstring
