// Training and online settings by name.
#include "train/settings.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <stdexcept>

#include "io/text.hpp"

namespace actionstring {
namespace host {

std::optional<double> parse_real(const std::string& text, double low, double high) {
    char* end = nullptr;
    const double v = std::strtod(text.c_str(), &end);
    if (text.empty() || end == text.c_str() || *end != '\0' || !(v >= low && v <= high)) return std::nullopt;
    return v;
}

std::optional<double> parse_whole(const std::string& text, double low, double high) {
    const std::optional<double> v = parse_real(text, low, high);
    if (!v || *v != std::floor(*v)) return std::nullopt;
    return v;
}

std::string range_text(double low, double high) {
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, "[%g, %g]", low, high);
    return buffer;
}

namespace {

double number(const std::string& name, const std::string& value, double low, double high) {
    const std::optional<double> v = parse_real(value, low, high);
    if (!v)
        throw std::invalid_argument("option --" + name + " expects a number in " + range_text(low, high) + ", got '" +
                                    value + "'");
    return *v;
}

// A count or an index (parse_whole()).
double whole_number(const std::string& name, const std::string& value, double low, double high) {
    const std::optional<double> v = parse_whole(value, low, high);
    if (!v)
        throw std::invalid_argument("option --" + name + " expects a whole number in " + range_text(low, high) +
                                    ", got '" + value + "'");
    return *v;
}

int choice(const std::string& name, const std::string& value, std::initializer_list<const char*> names) {
    int i = 0;
    for (const char* n : names) {
        if (value == n) return i;
        ++i;
    }
    throw std::invalid_argument("option --" + name + ": unknown value '" + value + "'");
}

// A yes/no setting: a name alone means yes; anything but these words is refused,
// so that a typo does not silently turn a setting off.
bool flag(const std::string& name, const std::string& value) {
    if (value.empty() || value == "true" || value == "1" || value == "on" || value == "yes") return true;
    if (value == "false" || value == "0" || value == "off" || value == "no") return false;
    throw std::invalid_argument("option --" + name + ": expected true or false, not '" + value + "'");
}

}  // namespace

bool apply_segmenter_setting(const std::string& name, const std::string& value, SegmenterConfig& config) {
    const double unbounded = std::numeric_limits<double>::infinity();
    if (name == "settle")
        config.settle_delay_us = static_cast<std::int64_t>(std::llround(number(name, value, 0, 60) * 1e6));
    else if (name == "settle-stable")
        config.settle_stable_us = static_cast<std::int64_t>(std::llround(number(name, value, 0, 60) * 1e6));
    else if (name == "segment-penalty") config.segment_penalty = static_cast<float>(number(name, value, 0, 1e6));
    else if (name == "stay-penalty") config.stay_penalty = static_cast<float>(number(name, value, 0, 1e6));
    else if (name == "skip-penalty") config.skip_penalty = static_cast<float>(number(name, value, 0, 1e6));
    else if (name == "unknown-cost") config.unknown_cost = static_cast<float>(number(name, value, 0, unbounded));
    else if (name == "segment-votes") config.vote_weight = static_cast<float>(number(name, value, 0, 1000));
    else if (name == "segment-exemplars") config.exemplar_weight = static_cast<float>(number(name, value, 0, 1000));
    else if (name == "segment-directions") config.direction_weight = static_cast<float>(number(name, value, 0, 1000));
    else return false;
    return true;
}

bool apply_online_setting(const std::string& name, const std::string& value, AnnotatorConfig& config) {
    if (name == "min-action") config.min_action_us = std::llround(number(name, value, 0, 60) * 1e6);
    else if (name == "label-lead") config.label_lead_us = std::llround(number(name, value, 0, 60) * 1e6);
    else if (name == "max-pose-speed") config.max_pose_speed = static_cast<float>(number(name, value, 0, 1e6));
    else return apply_segmenter_setting(name, value, config.segmenter);
    return true;
}

std::string setting_value_text(double value) {
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%g", value);
    return buffer;
}

double parse_time_unit(const std::string& text) {
    if (text == "s") return 1.0;
    if (text == "ms") return 1e-3;
    if (text == "us") return 1e-6;
    throw std::invalid_argument("option --time-unit expects s, ms or us, got '" + text + "'");
}

double parse_length_unit(const std::string& text) {
    try {
        return metres_per_unit(text);
    } catch (const std::invalid_argument&) {
        throw std::invalid_argument("option --length-unit expects m, dm, cm, mm or in, got '" + text + "'");
    }
}

RoleNames parse_role_names(const std::string& text) {
    RoleNames names;
    const std::size_t first = text.find(','), second = first == std::string::npos ? first : text.find(',', first + 1);
    if (second == std::string::npos || text.find(',', second + 1) != std::string::npos)
        throw std::invalid_argument("option --roles expects ROOT,LEFT_HIP,RIGHT_HIP, got '" + text + "'");
    names.root = text.substr(0, first);
    names.left_hip = text.substr(first + 1, second - first - 1);
    names.right_hip = text.substr(second + 1);
    return names;
}

// A comma-separated list of joint names (no empty names).
std::vector<std::string> joint_list(const std::string& name, const std::string& value) {
    std::vector<std::string> names;
    std::size_t begin = 0;
    while (true) {
        const std::size_t end = value.find(',', begin);
        const std::string item = value.substr(begin, end == std::string::npos ? std::string::npos : end - begin);
        if (item.empty()) throw std::invalid_argument("option --" + name + " expects NAME,NAME,..., got '" + value + "'");
        names.push_back(item);
        if (end == std::string::npos) break;
        begin = end + 1;
    }
    return names;
}

bool apply_training_setting(const std::string& name, const std::string& value, TrainingOptions& o, ReadOptions& read) {
    auto num = [&](double low, double high) { return number(name, value, low, high); };
    auto whole = [&](double low, double high) { return whole_number(name, value, low, high); };
    if (name == "components") o.components = static_cast<int>(whole(0, 256));
    else if (name == "covariance") o.covariance = static_cast<Covariance>(choice(name, value, {"full", "diagonal"}));
    else if (name == "covariance-floor") o.covariance_floor = num(1e-12, 1e6);
    else if (name == "pca") o.pca_dim = static_cast<int>(whole(0, 65535));
    else if (name == "feature-rate") o.feature_rate_hz = num(0.1, 10000);
    else if (name == "em-iterations") o.em_max_iterations = static_cast<int>(whole(1, 100000));
    else if (name == "em-tolerance") o.em_tolerance = num(0, 1);
    else if (name == "em-restarts") o.em_restarts = static_cast<int>(whole(1, 64));
    else if (name == "scale")
        o.scale_mode = static_cast<ScaleMode>(choice(name, value, {"none", "hip-width", "bones", "torso"}));
    else if (name == "mirror") o.mirror = flag(name, value);
    else if (name == "pose-joints") o.pose_joints = joint_list(name, value);
    else if (name == "velocity") o.velocity_weight = num(0, 1000);
    else if (name == "velocity-span") o.velocity_span_s = num(0.01, 2);
    else if (name == "acceleration") o.acceleration_weight = num(0, 1000);
    else if (name == "epsilon") o.epsilon = num(1e-9, 1e9);
    else if (name == "max-characters") o.max_characters = static_cast<int>(whole(1, 4096));
    else if (name == "string-rate") o.string_rate_hz = num(1, 1000);
    else if (name == "variant")
        o.variant = static_cast<MatchVariant>(choice(name, value, {"paper", "whole", "subsequence"}));
    else if (name == "normalization")
        o.normalization = static_cast<LengthNormalization>(choice(name, value, {"none", "path", "query"}));
    else if (name == "sigma") o.sigma = num(0, 1e9);
    else if (name == "keep-singletons") o.keep_singletons = flag(name, value);
    else if (name == "max-representative-chars") o.max_representative_chars = static_cast<int>(whole(0, 1e9));
    else if (name == "max-representative-share") o.max_representative_share = num(0, 1);
    else if (name == "reject") o.reject = flag(name, value);
    else if (name == "reject-keep") o.reject_keep = num(0.01, 1);
    else if (name == "neighbours") o.neighbours = static_cast<int>(whole(1, 64));
    else if (name == "vote-weight") o.vote_weight = num(0, 1000);
    else if (name == "vote-smoothing") o.vote_smoothing = num(1e-6, 1e3);
    else if (name == "exemplars") o.exemplars = static_cast<int>(whole(0, 4096));
    else if (name == "exemplar-weight") o.exemplar_weight = num(0, 1000);
    else if (name == "exemplar-dims") o.exemplar_dims = static_cast<int>(whole(0, 65535));
    else if (name == "no-action-exemplars") o.no_action_exemplars = flag(name, value);
    else if (name == "descriptor-levels") o.descriptor_levels = static_cast<int>(whole(0, 8));
    else if (name == "descriptor-dims") o.descriptor_dims = static_cast<int>(whole(0, 64));
    else if (name == "descriptor-ridge") o.descriptor_ridge = num(1e-6, 1e9);
    else if (name == "descriptor-weight") o.descriptor_weight = num(0, 1000);
    else if (name == "direction-levels") o.direction_levels = static_cast<int>(whole(0, 8));
    else if (name == "direction-ridge") o.direction_ridge = num(1e-6, 1e9);
    else if (name == "direction-weight") o.direction_weight = num(0, 1000);
    else if (name == "direction-window") o.direction_window_s = num(0, 60);
    else if (name == "direction-window-ridge") o.direction_window_ridge = num(1e-6, 1e9);
    else if (name == "window") o.window_seconds = num(0.01, 3600);
    else if (name == "step") o.step_seconds = num(0.01, 3600);
    else if (name == "unknown-distance") o.unknown_distance = num(0, 1e30);
    else if (name == "seed") o.seed = static_cast<std::uint32_t>(whole(0, 4294967295.0));
    else if (name == "min-action") o.min_action_us = std::llround(num(0, 60) * 1e6);
    else if (name == "label-lead") o.label_lead_us = std::llround(num(0, 60) * 1e6);
    else if (name == "latency-budget") o.latency_budget_s = num(0, 60);
    else if (apply_segmenter_setting(name, value, o.online)) return true;
    else if (name == "rate") read.frame_rate_hz = num(0.001, 1e6);
    else if (name == "time-unit") read.time_unit_s = parse_time_unit(value);
    else if (name == "length-unit") read.length_scale = parse_length_unit(value);
    else if (name == "body") read.body = static_cast<int>(whole(0, 63));
    else if (name == "columns") read.columns = value;
    else if (name == "roles") read.roles = parse_role_names(value);
    else if (name == "parents") read.parents = parse_parent_names(value);
    else if (name == "up") parse_up_direction(value, read.up);
    else return false;
    return true;
}

void read_training_config(const std::string& path, TrainingOptions& options, ReadOptions& read) {
    const std::string text = read_file(path);
    LineScanner scanner(path, text);
    std::string_view line;
    while (scanner.next_content(line, '#')) {
        const std::vector<std::string_view> words = split_words(line);
        const std::string name(words[0]), value(words.size() > 1 ? words[1] : std::string_view());
        bool known = false;
        try {
            known = apply_training_setting(name, value, options, read);
        } catch (const std::invalid_argument& error) {
            scanner.fail(error.what());
        }
        if (!known) scanner.fail("unknown setting '" + name + "'");
    }
}

const std::vector<std::string>& training_setting_names() {
    static const std::vector<std::string> names{"components",
                                                "covariance",
                                                "covariance-floor",
                                                "pca",
                                                "feature-rate",
                                                "em-iterations",
                                                "em-tolerance",
                                                "em-restarts",
                                                "scale",
                                                "mirror",
                                                "pose-joints",
                                                "velocity",
                                                "velocity-span",
                                                "acceleration",
                                                "epsilon",
                                                "max-characters",
                                                "string-rate",
                                                "variant",
                                                "normalization",
                                                "sigma",
                                                "keep-singletons",
                                                "max-representative-chars",
                                                "max-representative-share",
                                                "reject",
                                                "reject-keep",
                                                "neighbours",
                                                "vote-weight",
                                                "vote-smoothing",
                                                "exemplars",
                                                "exemplar-weight",
                                                "exemplar-dims",
                                                "no-action-exemplars",
                                                "descriptor-levels",
                                                "descriptor-dims",
                                                "descriptor-ridge",
                                                "descriptor-weight",
                                                "direction-levels",
                                                "direction-ridge",
                                                "direction-weight",
                                                "direction-window",
                                                "direction-window-ridge",
                                                "window",
                                                "step",
                                                "unknown-distance",
                                                "seed",
                                                "settle",
                                                "settle-stable",
                                                "segment-penalty",
                                                "stay-penalty",
                                                "skip-penalty",
                                                "unknown-cost",
                                                "segment-votes",
                                                "segment-exemplars",
                                                "segment-directions",
                                                "min-action",
                                                "latency-budget",
                                                "rate",
                                                "roles",
                                                "time-unit",
                                                "length-unit",
                                                "parents",
                                                "body",
                                                "columns",
                                                "up"};
    return names;
}

}  // namespace host
}  // namespace actionstring
