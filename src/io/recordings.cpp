// Continuous recordings with labelled intervals.
#include "io/recordings.hpp"

#include <algorithm>
#include <cstdio>
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
            recordings.push_back({entry.subject, read_clip(whole, read), {}, {}});
            found = index.emplace(entry.path, recordings.size() - 1).first;
        }
        recordings[found->second].intervals.push_back({entry.label, entry.start_s, entry.end_s, entry.line});
    }
    for (LabelledRecording& recording : recordings) note_interval_overlaps(recording);
    return recordings;
}

namespace {

// Where two intervals share frames, whether the one listed later takes them
// from the one listed earlier: it starts later, or with it.
bool takes_over(const LabelledRecording::Interval& listed_later, const LabelledRecording::Interval& listed_earlier) {
    return listed_later.start_s >= listed_earlier.start_s;
}

}  // namespace

std::vector<IntervalOverlap> interval_overlaps(const std::vector<LabelledRecording::Interval>& intervals) {
    std::vector<IntervalOverlap> overlaps;
    for (std::size_t a = 0; a < intervals.size(); ++a)
        for (std::size_t b = a + 1; b < intervals.size(); ++b) {
            const double shared =
                std::min(intervals[a].end_s, intervals[b].end_s) - std::max(intervals[a].start_s, intervals[b].start_s);
            if (shared > 0) overlaps.push_back({a, b, shared, takes_over(intervals[b], intervals[a]) ? b : a});
        }
    return overlaps;
}

int interval_at(const std::vector<LabelledRecording::Interval>& intervals, double t) {
    int found = -1;
    for (std::size_t i = 0; i < intervals.size(); ++i)
        if (t >= intervals[i].start_s && t <= intervals[i].end_s &&
            (found < 0 || takes_over(intervals[i], intervals[static_cast<std::size_t>(found)])))
            found = static_cast<int>(i);
    return found;
}

void note_interval_overlaps(LabelledRecording& recording) {
    const std::size_t slash = recording.clip.source.find_last_of('/');
    const std::string name = recording.clip.source.substr(slash == std::string::npos ? 0 : slash + 1);
    auto describe = [](const LabelledRecording::Interval& interval) {
        char text[96];
        std::snprintf(text, sizeof text, " %.3f-%.3f s", interval.start_s, interval.end_s);
        std::string out = interval.label + text;
        if (interval.line > 0) out += " (list line " + std::to_string(interval.line) + ")";
        return out;
    };
    for (const IntervalOverlap& overlap : interval_overlaps(recording.intervals)) {
        char seconds[32];
        std::snprintf(seconds, sizeof seconds, "%.3f s", overlap.seconds);
        recording.notes.push_back(name + ": intervals " + describe(recording.intervals[overlap.first]) + " and " +
                                  describe(recording.intervals[overlap.second]) + " overlap by " + seconds +
                                  "; frames in both count as " + recording.intervals[overlap.later].label +
                                  ", the one that starts later (check the annotation)");
    }
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
