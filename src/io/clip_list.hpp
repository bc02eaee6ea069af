// actionstring host library — clip lists: which files, with which labels and
// subjects, make up a training or test set, and loading them as labelled clips.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "io/clip.hpp"

namespace actionstring {
namespace host {

/// One line of a clip list.
struct ClipListEntry {
    std::string path;  ///< Resolved against the list's folder.
    std::string label;
    std::string subject;
    std::string skeleton;  ///< Resolved; empty when the list has no skeleton column.
    std::size_t line = 0;  ///< Line in the list, for messages.
    /// An action inside a longer recording: the clip is the frames whose time
    /// (seconds, on the file's own time axis) lies in [start_s, end_s].
    bool has_interval = false;
    double start_s = 0, end_s = 0;
    /// The sensor's up direction in the file's coordinates (ReadOptions::up);
    /// all zeros when the list has no `up` column or says 0,0,0.
    float up[3] = {0.0f, 0.0f, 0.0f};
};

/// TSV with a header naming at least `path`, `label`, `subject` (and optionally
/// `skeleton`; `start` and `end` in seconds for labelled intervals of a
/// continuous recording; `up` as X,Y,Z, the sensor's up direction in the
/// file's coordinates, e.g. a Kinect's floor plane normal, 0,0,0 for none), in
/// any order; relative paths are resolved against `folder`.
std::vector<ClipListEntry> parse_clip_list(const std::string& name, std::string_view text, const std::string& folder);
std::vector<ClipListEntry> read_clip_list(const std::string& path);

/// Reads one entry's clip (only its interval's frames when it has one),
/// turned upright by the entry's `up` when it gives one (else options.up).
Clip read_clip(const ClipListEntry& entry, const ReadOptions& options = {});

/// True when any entry names an interval of a longer recording.
bool has_intervals(const std::vector<ClipListEntry>& entries);

/// One training or evaluation clip with its label.
struct LabelledClip {
    Clip clip;
    std::string label;
    std::string subject;
};

/// Reads every entry's clip, in list order. Throws ReadError.
std::vector<LabelledClip> load_labelled_clips(const std::vector<ClipListEntry>& entries,
                                              const ReadOptions& options = {});
/// Reads a clip list and every clip it names.
std::vector<LabelledClip> load_labelled_clips(const std::string& list_path, const ReadOptions& options = {});

}  // namespace host
}  // namespace actionstring
