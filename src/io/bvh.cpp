// BVH reader with forward kinematics.
//
// A joint's local transform is a translation by OFFSET plus any position
// channels, then its rotation channels composed in the order listed
// (channels "Zrotation Xrotation Yrotation" give Rz · Rx · Ry). End Sites end
// a chain and are not joints of the clip.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <string>
#include <unordered_set>

#include <Eigen/Geometry>

#include "io/formats.hpp"
#include "io/text.hpp"

namespace actionstring {
namespace host {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr int kMaxDepth = 256;

struct BvhJoint {
    std::string name;
    int parent = -1;
    Eigen::Vector3d offset = Eigen::Vector3d::Zero();
    std::vector<int> channels;  // 0..2 position x y z, 3..5 rotation x y z
    std::size_t first_channel = 0;
};

// Whitespace tokens across lines, keeping each token's line for messages.
class TokenStream {
public:
    explicit TokenStream(LineScanner& scanner) : scanner_(scanner) {}

    bool next(std::string_view& token) {
        while (index_ >= words_.size()) {
            std::string_view line;
            if (!scanner_.next(line)) return false;
            words_ = split_words(line);
            index_ = 0;
        }
        token = words_[index_++];
        return true;
    }
    std::string_view expect(const char* what) {
        std::string_view token;
        if (!next(token)) scanner_.fail(std::string("file ends where ") + what + " was expected");
        return token;
    }
    void expect_word(const char* word) {
        const std::string_view token = expect(word);
        if (token != word) scanner_.fail(std::string("expected '") + word + "', got " + quoted(token));
    }
    double number(const char* what) { return parse_number(scanner_, expect(what), what); }
    // True when the rest of the current line has been consumed.
    bool at_line_end() const { return index_ >= words_.size(); }
    LineScanner& scanner() { return scanner_; }

private:
    LineScanner& scanner_;
    std::vector<std::string_view> words_;
    std::size_t index_ = 0;
};

int channel_code(std::string_view token) {
    static const char* const names[] = {"Xposition", "Yposition", "Zposition", "Xrotation", "Yrotation", "Zrotation"};
    for (int i = 0; i < 6; ++i)
        if (iequals(token, names[i])) return i;
    return -1;
}

void parse_joint_body(TokenStream& tokens, std::vector<BvhJoint>& joints, std::unordered_set<std::string>& names,
                      std::size_t& channel_count, int index, int depth) {
    if (depth > kMaxDepth) tokens.scanner().fail("hierarchy nested deeper than 256 joints");
    tokens.expect_word("{");
    tokens.expect_word("OFFSET");
    Eigen::Vector3d offset;
    for (int a = 0; a < 3; ++a) offset[a] = tokens.number("an OFFSET value");
    joints[static_cast<std::size_t>(index)].offset = offset;
    std::string_view token = tokens.expect("CHANNELS or JOINT");
    if (token == "CHANNELS") {
        const long count = parse_index(tokens.scanner(), tokens.expect("a channel count"), "a channel count");
        if (count > 6) tokens.scanner().fail("a joint has at most 6 channels, got " + std::to_string(count));
        std::vector<int> channels;
        for (long c = 0; c < count; ++c) {
            const std::string_view name = tokens.expect("a channel name");
            const int code = channel_code(name);
            if (code < 0)
                tokens.scanner().fail("expected a channel such as Xposition or Zrotation, got " + quoted(name));
            if (std::find(channels.begin(), channels.end(), code) != channels.end())
                tokens.scanner().fail("channel " + quoted(name) + " appears twice");
            channels.push_back(code);
        }
        joints[static_cast<std::size_t>(index)].channels = channels;
        joints[static_cast<std::size_t>(index)].first_channel = channel_count;
        channel_count += channels.size();
        token = tokens.expect("JOINT, End Site or }");
    }
    for (;;) {
        if (token == "}") return;
        if (token == "JOINT") {
            const std::string name(tokens.expect("a joint name"));
            if (!names.insert(name).second) tokens.scanner().fail("duplicate joint name " + quoted(name));
            BvhJoint child;
            child.name = name;
            child.parent = index;
            joints.push_back(child);
            parse_joint_body(tokens, joints, names, channel_count, static_cast<int>(joints.size()) - 1, depth + 1);
        } else if (token == "End") {
            tokens.expect_word("Site");
            tokens.expect_word("{");
            tokens.expect_word("OFFSET");
            for (int a = 0; a < 3; ++a) tokens.number("an End Site OFFSET value");
            tokens.expect_word("}");
        } else {
            tokens.scanner().fail("expected JOINT, End Site or }, got " + quoted(token));
        }
        token = tokens.expect("JOINT, End Site or }");
    }
}

}  // namespace

Clip parse_bvh(const std::string& name, std::string_view text, const ReadOptions& options) {
    LineScanner scanner(name, text);
    TokenStream tokens(scanner);
    std::vector<BvhJoint> joints;
    std::unordered_set<std::string> names;
    std::size_t channel_count = 0;

    std::string_view token;
    if (!tokens.next(token)) scanner.fail_at(0, "empty file: expected HIERARCHY");
    if (token != "HIERARCHY") scanner.fail("expected HIERARCHY, got " + quoted(token));
    token = tokens.expect("ROOT");
    while (token == "ROOT") {
        const std::string root(tokens.expect("a root name"));
        if (!names.insert(root).second) scanner.fail("duplicate joint name " + quoted(root));
        BvhJoint joint;
        joint.name = root;
        joints.push_back(joint);
        parse_joint_body(tokens, joints, names, channel_count, static_cast<int>(joints.size()) - 1, 0);
        token = tokens.expect("ROOT or MOTION");
    }
    if (token != "MOTION") scanner.fail("expected ROOT or MOTION, got " + quoted(token));
    if (joints.empty()) scanner.fail("no joints before MOTION");
    tokens.expect_word("Frames:");
    const long frame_count = parse_index(scanner, tokens.expect("a frame count"), "a frame count");
    tokens.expect_word("Frame");
    tokens.expect_word("Time:");
    const double frame_time = tokens.number("a frame time");
    if (!(frame_time > 0)) scanner.fail("expected a positive frame time");
    if (!tokens.at_line_end()) scanner.fail("unexpected text after the frame time");

    const std::size_t J = joints.size();

    Clip clip;
    clip.source = name;
    for (const BvhJoint& joint : joints) {
        clip.joint_names.push_back(joint.name);
        clip.parents.push_back(joint.parent);
    }
    std::vector<Eigen::Matrix3d> global(J);
    std::vector<Eigen::Vector3d> position(J);
    std::vector<double> values(channel_count);
    // The declared count is untrusted: reserve no more frames than the text could hold.
    const std::size_t plausible_frames = std::min(static_cast<std::size_t>(frame_count),
                                                  text.size() / (2 * std::max<std::size_t>(channel_count, 1)) + 1);
    clip.positions.reserve(plausible_frames * J * 3);
    const double to_radians = kPi / 180.0;
    std::string_view line;
    for (long f = 0; f < frame_count; ++f) {
        if (!scanner.next_content(line))
            scanner.fail("file ends after " + std::to_string(f) + " of " + std::to_string(frame_count) + " frames");
        const std::vector<std::string_view> words = split_words(line);
        if (words.size() != channel_count)
            scanner.fail("frame " + std::to_string(f + 1) + " has " + std::to_string(words.size()) +
                         " values, expected " + std::to_string(channel_count));
        for (std::size_t c = 0; c < channel_count; ++c) values[c] = parse_number(scanner, words[c], "a channel value");
        for (std::size_t j = 0; j < J; ++j) {
            const BvhJoint& joint = joints[j];
            Eigen::Vector3d translation = joint.offset;
            Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
            for (std::size_t c = 0; c < joint.channels.size(); ++c) {
                const int code = joint.channels[c];
                const double v = values[joint.first_channel + c];
                if (code < 3) translation[code] += v;
                else
                    rotation = rotation *
                               Eigen::AngleAxisd(v * to_radians, Eigen::Vector3d::Unit(code - 3)).toRotationMatrix();
            }
            if (joint.parent < 0) {
                global[j] = rotation;
                position[j] = translation;
            } else {
                const auto p = static_cast<std::size_t>(joint.parent);
                global[j] = global[p] * rotation;
                position[j] = position[p] + global[p] * translation;
            }
            for (int a = 0; a < 3; ++a) clip.positions.push_back(static_cast<float>(position[j][a]));
        }
        clip.times.push_back(static_cast<double>(f) * frame_time);
    }
    if (scanner.next_content(line)) scanner.fail("more frame lines than the declared " + std::to_string(frame_count));

    // Roles first, then the up axis and units, both read off the motion: a
    // rig's rest-pose offsets need not point the way the body stands.
    assign_roles(clip, options.roles);
    const std::size_t frames = clip.frame_count();
    int up = options.up_axis;
    if (up > 2) throw ReadError(name, 0, "up axis must be 0, 1 or 2");
    if (up < 0) {
        // The mean of (head − root) when a joint is named like a head, else of
        // (highest − lowest joint) per axis: the vertical is its largest component.
        int head = -1;
        for (std::size_t j = 0; j < J && head < 0; ++j) {
            std::string lower = clip.joint_names[j];
            std::transform(lower.begin(), lower.end(), lower.begin(),
                           [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
            if (lower.find("head") != std::string::npos && lower.find("end") == std::string::npos)
                head = static_cast<int>(j);
        }
        const std::size_t root = static_cast<std::size_t>(clip.roles.root >= 0 ? clip.roles.root : 0);
        Eigen::Vector3d sum = Eigen::Vector3d::Zero();
        for (std::size_t f = 0; f < frames; ++f) {
            const float* p = clip.frame(f);
            if (head >= 0) {
                for (int a = 0; a < 3; ++a)
                    sum[a] += std::fabs(
                        static_cast<double>(p[3 * static_cast<std::size_t>(head) + static_cast<std::size_t>(a)]) -
                        static_cast<double>(p[3 * root + static_cast<std::size_t>(a)]));
                continue;
            }
            for (int a = 0; a < 3; ++a) {
                double low = p[a], high = p[a];
                for (std::size_t j = 1; j < J; ++j) {
                    low = std::min(low, static_cast<double>(p[3 * j + static_cast<std::size_t>(a)]));
                    high = std::max(high, static_cast<double>(p[3 * j + static_cast<std::size_t>(a)]));
                }
                sum[a] += high - low;
            }
        }
        sum.maxCoeff(&up);
    }
    clip.up_axis = up;
    double scale = options.length_scale;
    if (!(scale > 0)) {
        // The body's median height along the vertical, in file units.
        scale = metres_per_unit_for_height(median_body_height(clip, up));
    }
    for (float& v : clip.positions) v = static_cast<float>(static_cast<double>(v) * scale);
    flag_lost_frames(clip);
    require_finite_positions(clip);
    return clip;
}

}  // namespace host
}  // namespace actionstring
