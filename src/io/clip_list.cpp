// Clip lists and loading them as labelled clips.
#include "io/clip_list.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "io/formats.hpp"
#include "io/text.hpp"

namespace actionstring {
namespace host {

std::vector<ClipListEntry> parse_clip_list(const std::string& name, std::string_view text, const std::string& folder) {
    LineScanner scanner(name, text);
    std::string_view line;
    if (!scanner.next_content(line))
        scanner.fail_at(0, "empty clip list: expected a header 'path label subject [skeleton]'");
    const std::vector<std::string_view> header = split_fields(line, '\t');
    int path_column = -1, label_column = -1, subject_column = -1, skeleton_column = -1, start_column = -1,
        end_column = -1, up_column = -1;
    for (std::size_t c = 0; c < header.size(); ++c) {
        int* column = header[c] == "path"       ? &path_column
                      : header[c] == "label"    ? &label_column
                      : header[c] == "subject"  ? &subject_column
                      : header[c] == "skeleton" ? &skeleton_column
                      : header[c] == "start"    ? &start_column
                      : header[c] == "end"      ? &end_column
                      : header[c] == "up"       ? &up_column
                                                : nullptr;
        if (column == nullptr) continue;
        if (*column >= 0) scanner.fail("column " + quoted(header[c]) + " appears twice in the header");
        *column = static_cast<int>(c);
    }
    if (path_column < 0 || label_column < 0 || subject_column < 0)
        scanner.fail("expected a tab-separated header with columns path, label and subject");
    if ((start_column < 0) != (end_column < 0)) scanner.fail("expected both 'start' and 'end' columns, or neither");
    auto resolve = [&](std::string_view relative) {
        const std::string path(relative);
        return path.front() == '/' || folder.empty() ? path : folder + "/" + path;
    };
    std::vector<ClipListEntry> entries;
    while (scanner.next_content(line)) {
        const std::vector<std::string_view> fields = split_fields(line, '\t');
        if (fields.size() != header.size())
            scanner.fail("expected " + std::to_string(header.size()) + " tab-separated fields, got " +
                         std::to_string(fields.size()));
        ClipListEntry entry;
        const auto field = [&](int column, const char* what) {
            const std::string_view value = fields[static_cast<std::size_t>(column)];
            if (value.empty()) scanner.fail(std::string("empty ") + what);
            return value;
        };
        entry.path = resolve(field(path_column, "path"));
        entry.label = std::string(field(label_column, "label"));
        entry.subject = std::string(field(subject_column, "subject"));
        if (skeleton_column >= 0) entry.skeleton = resolve(field(skeleton_column, "skeleton"));
        if (start_column >= 0) {
            entry.has_interval = true;
            entry.start_s = parse_number(scanner, field(start_column, "start"), "a start time in seconds");
            entry.end_s = parse_number(scanner, field(end_column, "end"), "an end time in seconds");
            if (!(entry.end_s >= entry.start_s))
                scanner.fail("expected the end time (" + std::string(fields[static_cast<std::size_t>(end_column)]) +
                             ") not before the start time (" +
                             std::string(fields[static_cast<std::size_t>(start_column)]) + ")");
        }
        if (up_column >= 0) {
            try {
                parse_up_direction(field(up_column, "up"), entry.up);
            } catch (const std::invalid_argument& error) {
                scanner.fail(error.what());
            }
        }
        entry.line = scanner.line_number();
        entries.push_back(std::move(entry));
    }
    if (entries.empty()) scanner.fail("the clip list names no clips");
    return entries;
}

std::vector<ClipListEntry> read_clip_list(const std::string& path) {
    const std::string text = read_file(path);
    const std::size_t slash = path.find_last_of('/');
    return parse_clip_list(path, text, slash == std::string::npos ? std::string(".") : path.substr(0, slash));
}

Clip read_clip(const ClipListEntry& entry, const ReadOptions& options) {
    ReadOptions read = options;
    if (entry.up[0] != 0.0f || entry.up[1] != 0.0f || entry.up[2] != 0.0f)
        for (int a = 0; a < 3; ++a) read.up[a] = entry.up[a];
    Clip whole = read_clip(entry.path, read, entry.skeleton);
    if (!entry.has_interval) return whole;
    Clip cut = whole;
    cut.times.clear();
    cut.positions.clear();
    cut.lost.clear();
    const std::size_t stride = whole.joint_count() * 3;
    for (std::size_t f = 0; f < whole.frame_count(); ++f) {
        if (whole.times[f] < entry.start_s || whole.times[f] > entry.end_s) continue;
        cut.times.push_back(whole.times[f]);
        cut.positions.insert(cut.positions.end(), whole.frame(f), whole.frame(f) + stride);
        if (!whole.lost.empty()) cut.lost.push_back(whole.lost[f]);
    }
    if (cut.times.empty())
        throw ReadError(entry.path, 0,
                        "no frame between " + std::to_string(entry.start_s) + " s and " + std::to_string(entry.end_s) +
                            " s (list line " + std::to_string(entry.line) + "); the file spans " +
                            std::to_string(whole.times.front()) + " to " + std::to_string(whole.times.back()) + " s");
    return cut;
}

bool has_intervals(const std::vector<ClipListEntry>& entries) {
    return std::any_of(entries.begin(), entries.end(), [](const ClipListEntry& e) { return e.has_interval; });
}

std::vector<LabelledClip> load_labelled_clips(const std::vector<ClipListEntry>& entries, const ReadOptions& options) {
    std::vector<LabelledClip> clips;
    clips.reserve(entries.size());
    for (const ClipListEntry& entry : entries) clips.push_back({read_clip(entry, options), entry.label, entry.subject});
    return clips;
}

std::vector<LabelledClip> load_labelled_clips(const std::string& list_path, const ReadOptions& options) {
    return load_labelled_clips(read_clip_list(list_path), options);
}

}  // namespace host
}  // namespace actionstring
