// Kinect skeleton text: MSR Action3D, UTKinect (and its label file), generic CSV.
#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <optional>
#include <string>
#include <vector>

#include "io/formats.hpp"
#include "io/sdk_skeletons.hpp"
#include "io/text.hpp"

namespace actionstring {
namespace host {

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

void finish_kinect_clip(Clip& clip, const ReadOptions& options) {
    const double scale = options.length_scale > 0 ? options.length_scale : 1.0;
    if (scale != 1.0)
        for (float& v : clip.positions) v = static_cast<float>(static_cast<double>(v) * scale);
    clip.up_axis = options.up_axis >= 0 ? options.up_axis : 1;
    // A CSV names its joints but gives no tree: an SDK's, when the names are all of one.
    if (clip.parents.empty()) clip.parents = sdk_parents(clip.joint_names);
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

namespace {

// The delimiter of a delimited text file: comma, semicolon or tab, whichever
// the header line holds most of (comma on a tie).
char detect_delimiter(std::string_view header) {
    const auto count = [&](char c) { return std::count(header.begin(), header.end(), c); };
    char best = ',';
    for (const char c : {';', '\t'})
        if (count(c) > count(best)) best = c;
    return best;
}

// Fields of a line, each trimmed, without the empty ones a trailing separator leaves.
std::vector<std::string_view> csv_fields(std::string_view line, char delimiter) {
    std::vector<std::string_view> fields = split_fields(line, delimiter);
    for (std::string_view& f : fields) f = trim(f);
    while (fields.size() > 1 && fields.back().empty()) fields.pop_back();
    return fields;
}

std::string lowercase(std::string_view text) {
    std::string out(text);
    for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return out;
}

// Seconds per unit a time column's name states ("time_ms", "Timestamp (us)"), 0 when it states none.
double unit_in_name(const std::string& name) {
    std::string letters;
    for (const char c : name)
        if (std::isalnum(static_cast<unsigned char>(c))) letters += c;
    auto ends = [&](const char* suffix) {
        const std::size_t n = std::strlen(suffix);
        return letters.size() > n && letters.compare(letters.size() - n, n, suffix) == 0;
    };
    if (ends("ms") || ends("msec") || ends("millis") || ends("milliseconds")) return 1e-3;
    if (ends("us") || ends("usec") || ends("micros") || ends("microseconds")) return 1e-6;
    if (ends("ns") || ends("nanoseconds")) return 1e-9;
    if (ends("sec") || ends("seconds") || (ends("s") && letters != "times" && letters != "timestamps")) return 1.0;
    return 0.0;
}

// Whether a column names the time: timestamp, time, t, with an optional unit.
bool is_time_column(const std::string& name) {
    std::string letters;
    for (const char c : name)
        if (std::isalpha(static_cast<unsigned char>(c))) letters += c;
    for (const char* base : {"timestamp", "timestamps", "time", "times", "t"}) {
        const std::string b(base);
        if (letters == b) return true;
        if (letters.rfind(b, 0) == 0) {
            const std::string rest = letters.substr(b.size());
            for (const char* unit : {"s", "sec", "seconds", "ms", "msec", "millis", "milliseconds", "us", "usec",
                                     "micros", "microseconds", "ns"})
                if (rest == unit) return true;
        }
    }
    return false;
}

// The whole token as a finite number, or nothing.
std::optional<double> parse_real_token(std::string_view token) {
    const std::string text(token);
    char* end = nullptr;
    const double v = std::strtod(text.c_str(), &end);
    if (text.empty() || end != text.c_str() + text.size() || !std::isfinite(v)) return std::nullopt;
    return v;
}

// "<joint><sep><axis>": Head_x, HeadX, head.x, Head X, HEAD-Z (axis any case).
bool joint_axis(std::string_view column, std::string& joint, int& axis) {
    if (column.size() < 2) return false;
    const char last = static_cast<char>(std::tolower(static_cast<unsigned char>(column.back())));
    if (last != 'x' && last != 'y' && last != 'z') return false;
    std::string_view base = column.substr(0, column.size() - 1);
    if (!base.empty() && (base.back() == '_' || base.back() == '.' || base.back() == ' ' || base.back() == '-'))
        base.remove_suffix(1);
    base = trim(base);
    if (base.empty()) return false;
    joint = std::string(base);
    axis = last - 'x';
    return true;
}

}  // namespace

JointCsvLayout::JointCsvLayout(const std::string& name, std::string_view header_line, std::size_t line,
                               const ReadOptions& options)
    : name_(name), line_(line) {
    auto fail = [&](const std::string& what) { throw ReadError(name_, line_, what); };
    delimiter_ = detect_delimiter(header_line);
    const std::vector<std::string_view> header = csv_fields(header_line, delimiter_);
    columns_ = header.size();
    if (!options.columns.empty()) {
        explicit_columns(header, options);
        return;
    }

    // The time column, and joints whose x, y and z columns are all there;
    // every other column is ignored (and said so in the notes).
    struct JointColumns {
        std::string name, key;
        int axis_column[3] = {-1, -1, -1};
    };
    std::vector<JointColumns> joints;
    std::vector<std::size_t> unused;
    for (std::size_t c = 0; c < header.size(); ++c) {
        const std::string column(header[c]);
        if (time_column_ < 0 && is_time_column(lowercase(column))) {
            time_column_ = static_cast<int>(c);
            continue;
        }
        std::string joint;
        int axis = 0;
        if (!joint_axis(column, joint, axis)) {
            unused.push_back(c);
            continue;
        }
        std::string key = lowercase(joint);
        auto found = std::find_if(joints.begin(), joints.end(), [&](const JointColumns& j) { return j.key == key; });
        if (found == joints.end()) {
            joints.push_back(JointColumns{joint, key, {-1, -1, -1}});
            found = joints.end() - 1;
        }
        if (found->axis_column[axis] >= 0)
            fail("columns " + quoted(header[static_cast<std::size_t>(found->axis_column[axis])]) + " and " +
                 quoted(column) + " both give the " + std::string(1, static_cast<char>('x' + axis)) + " of joint " +
                 quoted(found->name));
        found->axis_column[axis] = static_cast<int>(c);
    }
    for (const JointColumns& j : joints) {
        if (j.axis_column[0] < 0 || j.axis_column[1] < 0 || j.axis_column[2] < 0) {
            for (const int c : j.axis_column)
                if (c >= 0) unused.push_back(static_cast<std::size_t>(c));
            continue;
        }
        joint_names_.push_back(j.name);
        axes_.push_back({j.axis_column[0], j.axis_column[1], j.axis_column[2]});
    }
    if (time_column_ < 0 && !(options.frame_rate_hz > 0))
        fail(
            "expected a time column ('timestamp', 'time' or 't', with an optional unit such as 'time_ms'), "
            "or --rate for a file without one; columns: " +
            std::to_string(header.size()));
    if (joint_names_.empty())
        fail(
            "expected joint columns named '<joint>_x', '<joint>_y', '<joint>_z' (or JointX, joint.x, "
            "'Joint X'), found none among " +
            std::to_string(header.size()) + " columns");
    std::sort(unused.begin(), unused.end());
    if (!unused.empty()) {
        std::string list;
        for (const std::size_t c : unused) list += (list.empty() ? "" : ", ") + quoted(header[c]);
        notes_.push_back(std::to_string(unused.size()) + " column" + (unused.size() == 1 ? "" : "s") +
                         " ignored: " + list);
    }
    if (time_column_ >= 0) {
        time_unit_s_ = options.time_unit_s > 0
                           ? options.time_unit_s
                           : unit_in_name(lowercase(std::string(header[static_cast<std::size_t>(time_column_)])));
        if (options.time_unit_s <= 0 && time_unit_s_ > 0 && time_unit_s_ != 1.0)
            notes_.push_back("timestamps in units of " + std::to_string(time_unit_s_) + " s (from the column's name)");
    }
}

// The layout given by --columns: "time=COLUMN,JOINT=X:Y:Z,…" (column names as
// the header spells them, case-insensitive; the time entry may be left out
// when a frame rate is given).
void JointCsvLayout::explicit_columns(const std::vector<std::string_view>& header, const ReadOptions& options) {
    auto fail = [&](const std::string& what) { throw ReadError(name_, line_, "--columns: " + what); };
    auto find = [&](std::string_view wanted) {
        const std::string key = lowercase(trim(wanted));
        for (std::size_t c = 0; c < header.size(); ++c)
            if (lowercase(header[c]) == key) return static_cast<int>(c);
        std::string list;
        for (const std::string_view h : header) list += (list.empty() ? "" : ", ") + quoted(h);
        fail("no column " + quoted(trim(wanted)) + " in the header (" + list + ")");
        return -1;
    };
    std::vector<bool> used(header.size(), false);
    for (const std::string_view entry : split_fields(options.columns, ',')) {
        const std::size_t equals = entry.find('=');
        if (equals == std::string_view::npos) fail("expected NAME=COLUMN entries, got " + quoted(entry));
        const std::string name(trim(entry.substr(0, equals)));
        const std::string_view value = entry.substr(equals + 1);
        if (lowercase(name) == "time") {
            time_column_ = find(value);
            used[static_cast<std::size_t>(time_column_)] = true;
            continue;
        }
        const std::vector<std::string_view> axes = split_fields(value, ':');
        if (name.empty() || axes.size() != 3) fail("expected JOINT=X:Y:Z, got " + quoted(entry));
        std::array<int, 3> columns{};
        for (std::size_t a = 0; a < 3; ++a) {
            columns[a] = find(axes[a]);
            used[static_cast<std::size_t>(columns[a])] = true;
        }
        if (std::find(joint_names_.begin(), joint_names_.end(), name) != joint_names_.end())
            fail("joint " + quoted(name) + " named twice");
        joint_names_.push_back(name);
        axes_.push_back(columns);
    }
    if (joint_names_.empty()) fail("no joint given");
    if (time_column_ < 0 && !(options.frame_rate_hz > 0)) fail("no time column given, and no frame rate (--rate)");
    std::size_t unused = 0;
    for (const bool u : used) unused += u ? 0 : 1;
    if (unused > 0) notes_.push_back(std::to_string(unused) + " columns not named by --columns, ignored");
    if (time_column_ >= 0) time_unit_s_ = options.time_unit_s;
}

namespace {

// A coordinate a tracker left out: an empty field, or NaN as numpy, pandas and
// JavaScript exporters spell it ("nan", "NaN", "-nan", "null", "None", "NA").
bool untracked_token(std::string_view token) {
    if (token.empty()) return true;
    const std::string word = lowercase(token);
    if (word == "null" || word == "none" || word == "na" || word == "n/a") return true;
    const std::string text(token);
    char* end = nullptr;
    const double v = std::strtod(text.c_str(), &end);
    return end == text.c_str() + text.size() && std::isnan(v);
}

}  // namespace

bool JointCsvLayout::parse_row(std::string_view line, double& raw_time, float* positions, std::string& error,
                               bool& untracked) const {
    // Trailing separators leave empty fields, dropped only beyond the header's
    // columns: an untracked last joint is an empty field, not a missing column.
    std::vector<std::string_view> fields = split_fields(line, delimiter_);
    for (std::string_view& f : fields) f = trim(f);
    while (fields.size() > columns_ && fields.back().empty()) fields.pop_back();
    if (fields.size() != columns_) {
        error = "expected " + std::to_string(columns_) + " columns, got " + std::to_string(fields.size());
        return false;
    }
    auto number = [&](std::string_view token, const char* what, double& out) {
        const std::optional<double> v = parse_real_token(token);
        if (!v) error = std::string("expected ") + what + ", got " + quoted(token);
        else out = *v;
        return v.has_value();
    };
    raw_time = 0;
    if (time_column_ >= 0 && !number(fields[static_cast<std::size_t>(time_column_)], "a timestamp", raw_time))
        return false;
    untracked = false;
    for (std::size_t j = 0; j < axes_.size(); ++j)
        for (std::size_t a = 0; a < 3; ++a) {
            const std::string_view token = fields[static_cast<std::size_t>(axes_[j][a])];
            if (untracked_token(token)) {
                untracked = true;
                continue;
            }
            double v = 0;
            if (!number(token, "a coordinate (or an empty field or NaN for a joint not tracked)", v)) return false;
            positions[3 * j + a] = static_cast<float>(v);
        }
    // A pose with a joint missing is no pose: the row is a lost frame, as the
    // readers and the runtime mark lost tracking (every joint at the origin).
    if (untracked) std::fill(positions, positions + 3 * axes_.size(), 0.0f);
    return true;
}

Clip parse_joint_csv(const std::string& name, std::string_view text, const ReadOptions& options) {
    LineScanner scanner(name, text);
    std::string_view line;
    if (!scanner.next_content(line, '#')) scanner.fail_at(0, "empty file: expected a header row");
    const JointCsvLayout layout(name, line, scanner.line_number(), options);
    Clip clip;
    clip.source = name;
    clip.joint_names = layout.joint_names();
    clip.notes = layout.notes();
    const int time_column = layout.time_column();

    // Rows: the columns the header named, in any order; the ignored ones are not parsed.
    std::vector<double> raw_times;
    std::vector<float> frame(3 * layout.joint_names().size());
    std::string error;
    std::size_t untracked_rows = 0, first_untracked_line = 0;
    while (scanner.next_content(line, '#')) {
        double t = 0;
        bool untracked = false;
        if (!layout.parse_row(line, t, frame.data(), error, untracked)) scanner.fail(error);
        if (untracked && ++untracked_rows == 1) first_untracked_line = scanner.line_number();
        if (time_column >= 0) {
            if (!raw_times.empty() && t < raw_times.back())
                scanner.fail("timestamp " + std::to_string(t) + " is earlier than the previous row's");
            raw_times.push_back(t);
        } else {
            raw_times.push_back(static_cast<double>(raw_times.size()) / options.frame_rate_hz);
        }
        clip.positions.insert(clip.positions.end(), frame.begin(), frame.end());
    }
    if (raw_times.empty()) scanner.fail("no data rows after the header");
    if (untracked_rows > 0)
        clip.notes.push_back(std::to_string(untracked_rows) + " row" + (untracked_rows == 1 ? "" : "s") +
                             " with a joint not tracked (an empty or NaN coordinate; the first at line " +
                             std::to_string(first_untracked_line) + ") read as lost frames");

    // Time units: given, stated by the column's name, or read from the frame spacing.
    double unit = time_column < 0 ? 1.0 : layout.time_unit_s();
    std::vector<double> steps;
    for (std::size_t i = 1; i < raw_times.size(); ++i)
        if (raw_times[i] > raw_times[i - 1]) steps.push_back(raw_times[i] - raw_times[i - 1]);
    std::sort(steps.begin(), steps.end());
    const double step = steps.empty() ? 0.0 : steps[steps.size() / 2];
    auto plausible = [](double hz) { return hz >= 5.0 && hz <= 1000.0; };
    if (unit > 0) {
        // given, or stated by the column's name
    } else if (step <= 0 || plausible(1.0 / step)) {
        unit = 1.0;
    } else if (plausible(1.0 / (step * 1e-3))) {
        unit = 1e-3;
        clip.notes.push_back("timestamps taken as milliseconds: the rows are " + std::to_string(step) +
                             " apart, which in seconds would be " + std::to_string(1.0 / step) +
                             " Hz (give --time-unit s|ms|us to say otherwise)");
    } else if (plausible(1.0 / (step * 1e-6))) {
        unit = 1e-6;
        clip.notes.push_back("timestamps taken as microseconds: the rows are " + std::to_string(step) +
                             " apart (give --time-unit s|ms|us to say otherwise)");
    } else {
        unit = 1.0;
    }
    for (const double t : raw_times) clip.times.push_back(t * unit);
    // Length unit: given, else read off the body's median height along the up axis over
    // the tracked frames (a CSV states none; depth SDKs and mocap tools export mm or cm too).
    const double height =
        options.length_scale > 0 ? 0.0 : median_body_height(clip, options.up_axis >= 0 ? options.up_axis : 1);
    const double scale = metres_per_unit_for_height(height);  // 1 when given: finish_kinect_clip() applies it
    if (scale != 1.0) {
        for (float& v : clip.positions) v = static_cast<float>(static_cast<double>(v) * scale);
        const char* unit_name = scale == 0.001    ? "millimetres"
                                : scale == 0.01   ? "centimetres"
                                : scale == 0.0254 ? "inches"
                                                  : "decimetres";
        char spans[64];
        std::snprintf(spans, sizeof spans, "%.0f", height);
        clip.notes.push_back(std::string("lengths taken as ") + unit_name + ": the body spans " + spans +
                             " units along the up axis (give --length-unit m|dm|cm|mm|in to say otherwise)");
    }
    if (step > 0 && !plausible(1.0 / (step * unit)))
        clip.notes.push_back("warning: the median frame spacing gives " + std::to_string(1.0 / (step * unit)) +
                             " Hz, outside 5 Hz to 1 kHz: check the timestamps' unit (--time-unit s|ms|us)");
    finish_kinect_clip(clip, options);
    require_finite_positions(clip);
    return clip;
}

Clip parse_ntu_skeleton(const std::string& name, std::string_view text, const ReadOptions& options) {
    // NTU RGB+D .skeleton text (Kinect v2): the frame count; per frame the body
    // count, then per body a line of 10 values (the tracking id first), the
    // joint count (25), and one line of 12 values per joint (x y z in metres,
    // then depth and colour pixel coordinates, orientation and tracking state).
    LineScanner scanner(name, text);
    std::string_view line;
    auto next = [&](const char* what) {
        if (!scanner.next_content(line))
            scanner.fail(std::string("file ends where ") + what + " was expected (truncated?)");
        return split_words(line);
    };
    auto count = [&](const std::vector<std::string_view>& words, const char* what, double high) {
        if (words.size() != 1)
            scanner.fail(std::string("expected ") + what + " alone on the line, got " + std::to_string(words.size()) +
                         " values");
        const double v = parse_number(scanner, words[0], what);
        if (!(v >= 0 && v <= high && v == std::floor(v)))
            scanner.fail(std::string("expected ") + what + " between 0 and " + std::to_string(static_cast<long>(high)));
        return static_cast<std::size_t>(v);
    };
    const std::size_t frames = count(next("the frame count"), "a frame count", 1e6);
    if (frames == 0) scanner.fail("the file holds no frames");
    constexpr std::size_t joints = 25;
    // Each body seen: its id, and its positions per frame (zeros where it is absent).
    struct Body {
        std::string id;
        std::vector<float> positions;
        std::size_t present = 0;
    };
    std::vector<Body> bodies;
    for (std::size_t f = 0; f < frames; ++f) {
        const std::size_t body_count = count(next("a frame's body count"), "a body count", 16);
        for (std::size_t b = 0; b < body_count; ++b) {
            const std::vector<std::string_view> info = next("a body's line");
            if (info.size() != 10)
                scanner.fail("expected 10 values on a body's line, got " + std::to_string(info.size()));
            const std::string id(info[0]);
            auto body = std::find_if(bodies.begin(), bodies.end(), [&](const Body& x) { return x.id == id; });
            if (body == bodies.end()) {
                if (bodies.size() == 64) scanner.fail("more than 64 different bodies in one file");
                bodies.push_back(Body{id, {}, 0});
                body = bodies.end() - 1;
            }
            // Grown as frames are read, so a declared frame count alone allocates nothing.
            body->positions.resize((f + 1) * joints * 3, 0.0f);
            if (count(next("a body's joint count"), "a joint count", 25) != joints)
                scanner.fail("expected 25 joints per body (Kinect v2)");
            float* out = body->positions.data() + f * joints * 3;
            for (std::size_t j = 0; j < joints; ++j) {
                const std::vector<std::string_view> values = next("a joint's line");
                if (values.size() != 12)
                    scanner.fail("expected 12 values on a joint's line, got " + std::to_string(values.size()));
                for (std::size_t a = 0; a < 3; ++a)
                    out[3 * j + a] = static_cast<float>(parse_number(scanner, values[a], "a coordinate"));
            }
            ++body->present;
        }
    }
    if (scanner.next_content(line)) scanner.fail("unexpected content after the last frame");
    if (bodies.empty()) scanner.fail_at(0, "no body in any frame");
    for (Body& body : bodies) body.positions.resize(frames * joints * 3, 0.0f);
    // The body asked for, else the one that moves most (the sum over its
    // joints of the positions' variance over the frames where it is present).
    std::size_t chosen = 0;
    if (options.body >= 0) {
        if (static_cast<std::size_t>(options.body) >= bodies.size())
            throw ReadError(name, 0,
                            "body " + std::to_string(options.body) + " asked for, but the file has " +
                                std::to_string(bodies.size()) + " (counted from 0 in order of appearance)");
        chosen = static_cast<std::size_t>(options.body);
    } else {
        double most = -1;
        for (std::size_t b = 0; b < bodies.size(); ++b) {
            double motion = 0;
            for (std::size_t k = 0; k < joints * 3; ++k) {
                double sum = 0, squares = 0;
                std::size_t n = 0;
                for (std::size_t f = 0; f < frames; ++f) {
                    const float* p = bodies[b].positions.data() + f * joints * 3;
                    bool present = false;
                    for (std::size_t i = 0; i < joints * 3 && !present; ++i) present = p[i] != 0.0f;
                    if (!present) continue;
                    sum += p[k];
                    squares += static_cast<double>(p[k]) * p[k];
                    ++n;
                }
                if (n > 1)
                    motion += squares / static_cast<double>(n) -
                              (sum / static_cast<double>(n)) * (sum / static_cast<double>(n));
            }
            if (motion > most) most = motion, chosen = b;
        }
    }
    Clip clip;
    clip.source = name;
    clip.joint_names = kinect_v2_joint_names();
    clip.parents = sdk_parents(clip.joint_names);
    clip.positions = std::move(bodies[chosen].positions);
    const double rate = options.frame_rate_hz > 0 ? options.frame_rate_hz : 30.0;
    for (std::size_t f = 0; f < frames; ++f) clip.times.push_back(static_cast<double>(f) / rate);
    if (bodies.size() > 1)
        clip.notes.push_back(std::to_string(bodies.size()) + " bodies; read body " + std::to_string(chosen) +
                             (options.body >= 0 ? " (as asked)" : " (the one that moves most)") + ", present in " +
                             std::to_string(bodies[chosen].present) + " of " + std::to_string(frames) + " frames");
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
