// Kinect skeleton text: MSR Action3D, UTKinect (and its label file), generic CSV.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <string>

#include "io/formats.hpp"
#include "io/text.hpp"

namespace actionstring {
namespace host {

const std::vector<std::string>& kinect_v1_joint_names() {
    static const std::vector<std::string> names = {
        "HipCenter", "Spine",         "ShoulderCenter", "Head",       "ShoulderLeft", "ElbowLeft", "WristLeft",
        "HandLeft",  "ShoulderRight", "ElbowRight",     "WristRight", "HandRight",    "HipLeft",   "KneeLeft",
        "AnkleLeft", "FootLeft",      "HipRight",       "KneeRight",  "AnkleRight",   "FootRight"};
    return names;
}

const std::vector<std::string>& kinect_v2_joint_names() {
    static const std::vector<std::string> names = {
        "SpineBase",   "SpineMid",      "Neck",         "Head",       "ShoulderLeft", "ElbowLeft", "WristLeft",
        "HandLeft",    "ShoulderRight", "ElbowRight",   "WristRight", "HandRight",    "HipLeft",   "KneeLeft",
        "AnkleLeft",   "FootLeft",      "HipRight",     "KneeRight",  "AnkleRight",   "FootRight", "SpineShoulder",
        "HandTipLeft", "ThumbLeft",     "HandTipRight", "ThumbRight"};
    return names;
}

// MSR Action3D's order, read off the data: per-joint median heights and the
// joint pairs whose distance stays constant (bones) place each joint; "left"
// is the side MSR lists first, which is also UTKinect's (Kinect SDK) left.
const std::vector<std::string>& msr_action3d_joint_names() {
    static const std::vector<std::string> names = {
        "ShoulderLeft", "ShoulderRight", "ShoulderCenter", "Spine",      "HipLeft",   "HipRight",  "HipCenter",
        "ElbowLeft",    "ElbowRight",    "WristLeft",      "WristRight", "HandLeft",  "HandRight", "KneeLeft",
        "KneeRight",    "AnkleLeft",     "AnkleRight",     "FootLeft",   "FootRight", "Head"};
    return names;
}

namespace {

// Kinect v1 parents, SDK order.
const std::vector<int>& kinect_v1_parents() {
    static const std::vector<int> parents = {-1, 0, 1, 2, 2, 4, 5, 6, 2, 8, 9, 10, 0, 12, 13, 14, 0, 16, 17, 18};
    return parents;
}

std::vector<int> parents_by_name(const std::vector<std::string>& names) {
    const auto& sdk = kinect_v1_joint_names();
    std::vector<int> parents;
    for (const auto& name : names) {
        const auto it = std::find(sdk.begin(), sdk.end(), name);
        const int parent = kinect_v1_parents()[static_cast<std::size_t>(it - sdk.begin())];
        if (parent < 0) {
            parents.push_back(-1);
            continue;
        }
        parents.push_back(static_cast<int>(
            std::find(names.begin(), names.end(), sdk[static_cast<std::size_t>(parent)]) - names.begin()));
    }
    return parents;
}

void finish_kinect_clip(Clip& clip, const ReadOptions& options) {
    const double scale = options.length_scale > 0 ? options.length_scale : 1.0;
    if (scale != 1.0)
        for (float& v : clip.positions) v = static_cast<float>(static_cast<double>(v) * scale);
    clip.up_axis = options.up_axis >= 0 ? options.up_axis : 1;
    flag_lost_frames(clip);
    assign_roles(clip, options.roles);
}

}  // namespace

Clip parse_msr_skeleton(const std::string& name, std::string_view text, const ReadOptions& options) {
    LineScanner scanner(name, text);
    const double rate = options.frame_rate_hz > 0 ? options.frame_rate_hz : 15.0;
    Clip clip;
    clip.source = name;
    clip.joint_names = msr_action3d_joint_names();
    clip.parents = parents_by_name(clip.joint_names);
    std::string_view line;
    std::size_t rows = 0, frame_start_line = 0;
    while (scanner.next_content(line)) {
        const std::vector<std::string_view> words = split_words(line);
        if (words.size() != 4)
            scanner.fail("expected 4 values 'x y z c' on a joint line, got " + std::to_string(words.size()));
        if (rows % 20 == 0) frame_start_line = scanner.line_number();
        for (int a = 0; a < 3; ++a)
            clip.positions.push_back(
                static_cast<float>(parse_number(scanner, words[static_cast<std::size_t>(a)], "a coordinate")));
        parse_number(scanner, words[3], "a confidence value");
        ++rows;
    }
    if (rows == 0) scanner.fail_at(0, "empty file: expected 20 joint lines per frame");
    if (rows % 20 != 0)
        scanner.fail_at(frame_start_line,
                        "the last frame has " + std::to_string(rows % 20) + " of 20 joint lines (truncated file?)");
    for (std::size_t f = 0; f < rows / 20; ++f) clip.times.push_back(static_cast<double>(f) / rate);
    finish_kinect_clip(clip, options);
    require_finite_positions(clip);
    return clip;
}

Clip parse_utkinect(const std::string& name, std::string_view text, const ReadOptions& options) {
    LineScanner scanner(name, text);
    const double rate = options.frame_rate_hz > 0 ? options.frame_rate_hz : 30.0;
    Clip clip;
    clip.source = name;
    clip.joint_names = kinect_v1_joint_names();
    clip.parents = kinect_v1_parents();
    std::string_view line;
    long previous_id = -1;
    while (scanner.next_content(line)) {
        const std::vector<std::string_view> words = split_words(line);
        if (words.size() != 61)
            scanner.fail("expected a frame id and 60 coordinates, got " + std::to_string(words.size()) + " values");
        const long id = parse_index(scanner, words[0], "a frame id");
        if (id < previous_id)
            scanner.fail("frame id " + std::to_string(id) + " comes after " + std::to_string(previous_id));
        previous_id = id;
        for (std::size_t i = 1; i < 61; ++i)
            clip.positions.push_back(static_cast<float>(parse_number(scanner, words[i], "a coordinate")));
        clip.times.push_back(static_cast<double>(id) / rate);
    }
    if (clip.times.empty()) scanner.fail_at(0, "empty file: expected frame lines");
    finish_kinect_clip(clip, options);
    require_finite_positions(clip);
    return clip;
}

Clip parse_joint_csv(const std::string& name, std::string_view text, const ReadOptions& options) {
    LineScanner scanner(name, text);
    std::string_view line;
    if (!scanner.next_content(line, '#')) scanner.fail_at(0, "empty file: expected a header row");
    const std::vector<std::string_view> header = split_fields(line, ',');
    if (header.empty() || !(iequals(header[0], "timestamp") || iequals(header[0], "time") || iequals(header[0], "t")))
        scanner.fail("expected the first column to be 'timestamp' (seconds), got " + quoted(header[0]));
    if ((header.size() - 1) % 3 != 0 || header.size() < 4)
        scanner.fail("expected a timestamp and three columns (x, y, z) per joint, got " +
                     std::to_string(header.size()) + " columns");
    Clip clip;
    clip.source = name;
    for (std::size_t c = 1; c < header.size(); c += 3) {
        std::string joint;
        for (int a = 0; a < 3; ++a) {
            const std::string_view column = header[c + static_cast<std::size_t>(a)];
            const char axis = "xyz"[a];
            if (column.size() < 3 ||
                !(column[column.size() - 2] == '_' || column[column.size() - 2] == '.' ||
                  column[column.size() - 2] == ' ') ||
                std::tolower(static_cast<unsigned char>(column.back())) != axis)
                scanner.fail("expected column " + std::to_string(c + static_cast<std::size_t>(a) + 1) +
                             " to be '<joint>_" + axis + "', got " + quoted(column));
            const std::string base(column.substr(0, column.size() - 2));
            if (a == 0) joint = base;
            else if (base != joint)
                scanner.fail("columns " + quoted(header[c]) + " and " + quoted(column) + " name different joints");
        }
        if (std::find(clip.joint_names.begin(), clip.joint_names.end(), joint) != clip.joint_names.end())
            scanner.fail("duplicate joint " + quoted(joint));
        clip.joint_names.push_back(joint);
    }
    double previous = -1e300;
    while (scanner.next_content(line, '#')) {
        const std::vector<std::string_view> fields = split_fields(line, ',');
        if (fields.size() != header.size())
            scanner.fail("expected " + std::to_string(header.size()) + " columns, got " +
                         std::to_string(fields.size()));
        const double t = parse_number(scanner, fields[0], "a timestamp");
        if (t < previous) scanner.fail("timestamp " + std::string(fields[0]) + " is earlier than the previous row's");
        previous = t;
        clip.times.push_back(t);
        for (std::size_t c = 1; c < fields.size(); ++c)
            clip.positions.push_back(static_cast<float>(parse_number(scanner, fields[c], "a coordinate")));
    }
    if (clip.times.empty()) scanner.fail("no data rows after the header");
    finish_kinect_clip(clip, options);
    require_finite_positions(clip);
    return clip;
}

std::vector<std::pair<std::string, std::vector<LabelInterval>>> parse_utkinect_labels(const std::string& name,
                                                                                      std::string_view text) {
    LineScanner scanner(name, text);
    std::vector<std::pair<std::string, std::vector<LabelInterval>>> sequences;
    std::string_view line;
    while (scanner.next_content(line)) {
        const std::string_view content = trim(line);
        const std::size_t colon = content.find(':');
        if (colon == std::string_view::npos) {
            const std::vector<std::string_view> words = split_words(content);
            if (words.size() != 1) scanner.fail("expected a sequence name such as s01_e01, got " + quoted(content));
            sequences.emplace_back(std::string(words[0]), std::vector<LabelInterval>{});
            continue;
        }
        if (sequences.empty()) scanner.fail("expected a sequence name before the first interval");
        LabelInterval interval;
        interval.label = std::string(trim(content.substr(0, colon)));
        if (interval.label.empty()) scanner.fail("expected 'label: start end', got an empty label");
        const std::vector<std::string_view> bounds = split_words(content.substr(colon + 1));
        if (bounds.size() != 2) scanner.fail("expected 'label: start end', got " + quoted(content));
        if (iequals(bounds[0], "nan") || iequals(bounds[1], "nan")) {
            interval.valid = false;
        } else {
            interval.start_frame = parse_number(scanner, bounds[0], "a start frame");
            interval.end_frame = parse_number(scanner, bounds[1], "an end frame");
            if (interval.end_frame < interval.start_frame) scanner.fail("interval ends before it starts");
        }
        sequences.back().second.push_back(interval);
    }
    if (sequences.empty()) scanner.fail_at(0, "empty file: expected sequences with labelled intervals");
    return sequences;
}

}  // namespace host
}  // namespace actionstring
