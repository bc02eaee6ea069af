// actionstring host library — continuous recordings with labelled intervals.
#pragma once

#include <cstddef>
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
        std::size_t line = 0;  ///< Its line in the clip list, for messages; 0 when it came from elsewhere.
    };
    std::vector<Interval> intervals;
    /// What a user should know about the intervals (two that overlap; see
    /// interval_overlaps()), one message each; tools print them.
    std::vector<std::string> notes{};
};

/// Two labelled intervals of one recording that share more than an end point
/// (indices into its intervals, first < second), for how long, and which of
/// the two their shared frames take (interval_at()'s rule).
struct IntervalOverlap {
    std::size_t first = 0, second = 0;
    double seconds = 0;
    std::size_t later = 0;  ///< first or second: the one that starts later (second when they start together)
};

/// Every pair of intervals that overlap, in order of (first, second). Intervals
/// that only touch (one ends where the next starts) do not: annotators mark
/// actions back to back that way. An overlap is usually a slip in the
/// annotation (UTKinect's s03_e01 labels push 2556–3622, over its throw at
/// 3226–3282), so readers report each one (note_interval_overlaps()).
std::vector<IntervalOverlap> interval_overlaps(const std::vector<LabelledRecording::Interval>& intervals);

/// Adds a message to recording.notes for each of interval_overlaps(), naming
/// the recording, both intervals, their list lines and which label the frames
/// in both take (interval_at()).
void note_interval_overlaps(LabelledRecording& recording);

/// The interval a time on the recording's axis belongs to, as an index into
/// `intervals`, or −1 when it lies in none (no action). Ends count as inside.
/// Where intervals overlap, the one that starts last wins (the action begun
/// most recently, so an action nested in a longer one keeps its frames), and
/// of those that start together the one listed last.
int interval_at(const std::vector<LabelledRecording::Interval>& intervals, double t);

/// Groups a clip list's interval entries by file (first appearance order) and
/// reads each file once, whole. Entries without an interval are refused.
/// Intervals of one file that overlap are kept and noted (note_interval_overlaps()).
std::vector<LabelledRecording> read_recordings(const std::vector<ClipListEntry>& entries, const ReadOptions& read = {});

/// The stretches of each recording outside every labelled interval, at least
/// `min_seconds` long, as clips (label "", the recording's subject): examples
/// of no action, for train_model().
std::vector<LabelledClip> unlabelled_stretches(const std::vector<LabelledRecording>& recordings, double min_seconds);

}  // namespace host
}  // namespace actionstring
