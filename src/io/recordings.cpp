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

}  // namespace host
}  // namespace actionstring
