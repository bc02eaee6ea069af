// Continuous recordings with labelled intervals.
#include "io/recordings.hpp"

#include <map>

namespace actionstring {
namespace host {

std::vector<LabelledRecording> read_recordings(const std::vector<ClipListEntry>& entries, const ReadOptions& read) {
    std::vector<LabelledRecording> recordings;
    std::map<std::string, std::size_t> index;
    for (const ClipListEntry& entry : entries) {
        if (!entry.has_interval)
            throw ReadError(entry.path, 0,
                            "list line " + std::to_string(entry.line) +
                                ": a continuous recording needs 'start' and 'end' columns for its labelled intervals");
        auto found = index.find(entry.path);
        if (found == index.end()) {
            ClipListEntry whole = entry;
            whole.has_interval = false;
            recordings.push_back({entry.subject, read_clip(whole, read), {}});
            found = index.emplace(entry.path, recordings.size() - 1).first;
        }
        recordings[found->second].intervals.push_back({entry.label, entry.start_s, entry.end_s});
    }
    return recordings;
}

std::vector<LabelledClip> unlabelled_stretches(const std::vector<LabelledRecording>& recordings, double min_seconds) {
    std::vector<LabelledClip> stretches;
    for (const LabelledRecording& recording : recordings) {
        const Clip& whole = recording.clip;
        const std::size_t stride = whole.joint_count() * 3;
        auto inside = [&](double t) {
            for (const auto& interval : recording.intervals)
                if (t >= interval.start_s && t <= interval.end_s) return true;
            return false;
        };
        for (std::size_t f = 0; f < whole.frame_count();) {
            if (inside(whole.times[f])) {
                ++f;
                continue;
            }
            std::size_t g = f;
            while (g < whole.frame_count() && !inside(whole.times[g])) ++g;
            if (whole.times[g - 1] - whole.times[f] >= min_seconds) {
                Clip cut = whole;
                cut.times.assign(whole.times.begin() + static_cast<std::ptrdiff_t>(f),
                                 whole.times.begin() + static_cast<std::ptrdiff_t>(g));
                cut.positions.assign(whole.positions.begin() + static_cast<std::ptrdiff_t>(f * stride),
                                     whole.positions.begin() + static_cast<std::ptrdiff_t>(g * stride));
                if (!whole.lost.empty())
                    cut.lost.assign(whole.lost.begin() + static_cast<std::ptrdiff_t>(f),
                                    whole.lost.begin() + static_cast<std::ptrdiff_t>(g));
                stretches.push_back({std::move(cut), "", recording.subject});
            }
            f = g;
        }
    }
    return stretches;
}

}  // namespace host
}  // namespace actionstring
