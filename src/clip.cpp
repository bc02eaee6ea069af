// Clip helpers: joint roles, lost frames, clip lists and reading by file type.
#include <algorithm>
#include <cctype>
#include <string>

#include "actionstring_host/readers.hpp"
#include "actionstring_host/text.hpp"

namespace actionstring {
namespace host {

int Clip::joint_index(std::string_view name) const noexcept {
    for (std::size_t j = 0; j < joint_names.size(); ++j)
        if (joint_names[j] == name) return static_cast<int>(j);
    return -1;
}

namespace {

// Built-in role names, tried in order: HDM05/CMU ASF, Kinect v1, Kinect v2, CC_Base rig.
struct RoleCandidates {
    const char* root;
    const char* left_hip;
    const char* right_hip;
};
constexpr RoleCandidates kBuiltInRoles[] = {
    {"root", "lhipjoint", "rhipjoint"},
    {"HipCenter", "HipLeft", "HipRight"},
    {"SpineBase", "HipLeft", "HipRight"},
    {"CC_Base_Hip", "CC_Base_L_Thigh", "CC_Base_R_Thigh"},
};

}  // namespace

void assign_roles(Clip& clip, const RoleNames& names) {
    if (!names.empty()) {
        auto find = [&](const std::string& joint, const char* role) {
            const int index = clip.joint_index(joint);
            if (index < 0) throw ReadError(clip.source, 0, std::string("the ") + role + " joint " + quoted(joint) + " is not in the file");
            return index;
        };
        clip.roles.root = names.root.empty() ? -1 : find(names.root, "root");
        clip.roles.left_hip = names.left_hip.empty() ? -1 : find(names.left_hip, "left hip");
        clip.roles.right_hip = names.right_hip.empty() ? -1 : find(names.right_hip, "right hip");
        return;
    }
    for (const RoleCandidates& candidates : kBuiltInRoles) {
        const JointRoles roles{clip.joint_index(candidates.root), clip.joint_index(candidates.left_hip),
                               clip.joint_index(candidates.right_hip)};
        if (roles.complete()) {
            clip.roles = roles;
            return;
        }
    }
    clip.roles = JointRoles{};
}

void flag_lost_frames(Clip& clip) {
    const std::size_t values = clip.joint_count() * 3;
    clip.lost.assign(clip.frame_count(), 0);
    for (std::size_t f = 0; f < clip.frame_count(); ++f) {
        const float* p = clip.frame(f);
        clip.lost[f] = std::all_of(p, p + values, [](float v) { return v == 0.0f; }) ? 1 : 0;
    }
}

std::vector<ClipListEntry> parse_clip_list(const std::string& name, std::string_view text, const std::string& folder) {
    LineScanner scanner(name, text);
    std::string_view line;
    if (!scanner.next_content(line)) scanner.fail_at(0, "empty clip list: expected a header 'path label subject [skeleton]'");
    const std::vector<std::string_view> header = split_fields(line, '\t');
    int path_column = -1, label_column = -1, subject_column = -1, skeleton_column = -1, start_column = -1, end_column = -1;
    for (std::size_t c = 0; c < header.size(); ++c) {
        int* column = header[c] == "path" ? &path_column : header[c] == "label" ? &label_column
                    : header[c] == "subject" ? &subject_column : header[c] == "skeleton" ? &skeleton_column
                    : header[c] == "start" ? &start_column : header[c] == "end" ? &end_column : nullptr;
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
            scanner.fail("expected " + std::to_string(header.size()) + " tab-separated fields, got " + std::to_string(fields.size()));
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
                             ") not before the start time (" + std::string(fields[static_cast<std::size_t>(start_column)]) + ")");
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

namespace {

std::string extension(const std::string& path) {
    const std::size_t dot = path.find_last_of('.');
    const std::size_t slash = path.find_last_of('/');
    if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return {};
    std::string ext = path.substr(dot + 1);
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return ext;
}

}  // namespace

Clip read_clip(const std::string& path, const ReadOptions& options, const std::string& skeleton) {
    const std::string ext = extension(path);
    if (ext == "amc") {
        if (skeleton.empty()) throw ReadError(path, 0, "an AMC file needs its ASF skeleton (--skeleton FILE)");
        const AsfSkeleton asf = parse_asf(skeleton, read_file(skeleton));
        return parse_amc(path, read_file(path), asf, options);
    }
    const std::string text = read_file(path);
    if (ext == "bvh") return parse_bvh(path, text, options);
    if (ext == "csv") return parse_joint_csv(path, text, options);
    if (ext == "txt") {
        LineScanner scanner(path, text);
        std::string_view first;
        if (!scanner.next_content(first)) throw ReadError(path, 0, "empty file");
        const std::size_t values = split_words(first).size();
        if (values == 4) return parse_msr_skeleton(path, text, options);
        if (values == 61) return parse_utkinect(path, text, options);
        throw ReadError(path, scanner.line_number(),
                        "cannot tell the format: expected 4 values (MSR Action3D) or 61 (UTKinect) on a line, got " +
                            std::to_string(values));
    }
    throw ReadError(path, 0, "unknown file type '." + ext + "': expected .amc, .bvh, .csv or .txt (Kinect text)");
}

Clip read_clip(const ClipListEntry& entry, const ReadOptions& options) {
    Clip whole = read_clip(entry.path, options, entry.skeleton);
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
        throw ReadError(entry.path, 0, "no frame between " + std::to_string(entry.start_s) + " s and " + std::to_string(entry.end_s) +
                                           " s (list line " + std::to_string(entry.line) + "); the file spans " +
                                           std::to_string(whole.times.front()) + " to " + std::to_string(whole.times.back()) + " s");
    return cut;
}

}  // namespace host
}  // namespace actionstring
