// actionstring CLI — small argument reader shared by the subcommands.
#pragma once

#include <cmath>
#include <cstdio>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "actionstring/annotator.hpp"
#include "actionstring/segmenter.hpp"
#include "io/clip.hpp"
#include "train/settings.hpp"

namespace actionstring {
namespace cli {

using host::parse_real;
using host::parse_whole;
using host::range_text;

/// Runs a command's body; an exception becomes "actionstring CMD: what" on
/// stderr and exit status 1.
template <class Body>
int run_reporting_errors(const char* command, Body body) {
    try {
        return body();
    } catch (const std::exception& error) {
        std::fprintf(stderr, "actionstring %s: %s\n", command, error.what());
        return 1;
    }
}

/// Walks argv of one subcommand and reports mistakes as "actionstring CMD: …".
class ArgumentReader {
public:
    ArgumentReader(const char* command, int argc, char** argv) : command_(command), argc_(argc), argv_(argv) {}
    bool more() const { return ok_ && index_ < argc_; }
    std::string next() { return argv_[index_++]; }
    std::string value(const std::string& option) {
        if (index_ >= argc_) {
            error("option " + option + " needs a value");
            return {};
        }
        return argv_[index_++];
    }
    double number(const std::string& option, double low, double high) {
        const std::string text = value(option);
        return ok_ ? number_of(option, text, low, high) : 0.0;
    }
    /// The same for a count or an index: a fractional value is refused, not truncated.
    double whole(const std::string& option, double low, double high) {
        const std::string text = value(option);
        if (!ok_) return 0.0;
        const std::optional<double> v = parse_whole(text, low, high);
        if (!v)
            error("option " + option + " expects a whole number in " + range_text(low, high) + ", got '" + text + "'");
        return ok_ ? *v : 0.0;
    }
    /// `text`, the value of `option` (from the command line or a config file), as a number in [low, high].
    double number_of(const std::string& option, const std::string& text, double low, double high) {
        const std::optional<double> v = parse_real(text, low, high);
        if (!v) error("option " + option + " expects a number in " + range_text(low, high) + ", got '" + text + "'");
        return v.value_or(0.0);
    }
    int error(const std::string& message) {
        std::fprintf(stderr, "actionstring %s: %s\n", command_, message.c_str());
        ok_ = false;
        return 2;
    }
    int unknown(const std::string& option) { return error("unknown option '" + option + "' (see --help)"); }
    bool ok() const { return ok_; }

private:
    const char* command_;
    int argc_;
    char** argv_;
    int index_ = 1;
    bool ok_ = true;
};

/// `parse(text)`, a host parser that throws std::invalid_argument, with its
/// message (after `prefix`) through `args` instead, and an empty value.
template <class Parse>
auto parse_through(ArgumentReader& args, Parse parse, const std::string& text, const char* prefix = "") {
    try {
        return parse(text);
    } catch (const std::invalid_argument& error) {
        args.error(prefix + std::string(error.what()));
        return decltype(parse(text)){};
    }
}

/// "ROOT,LEFT_HIP,RIGHT_HIP" → role names (a message through `args` when malformed).
inline host::RoleNames parse_roles(ArgumentReader& args, const std::string& text) {
    return parse_through(args, host::parse_role_names, text);
}

/// "s", "ms" or "us" → seconds per unit (a message through `args` otherwise).
inline double parse_time_unit(ArgumentReader& args, const std::string& text) {
    return parse_through(args, host::parse_time_unit, text);
}

/// "m", "dm", "cm", "mm" or "in" → metres per unit (a message through `args` otherwise).
inline double parse_length_unit(ArgumentReader& args, const std::string& text) {
    return parse_through(args, host::parse_length_unit, text);
}

/// "-,Hips,Spine,..." → one parent name per joint (a message through `args` otherwise).
inline std::vector<std::string> parse_parents(ArgumentReader& args, const std::string& text) {
    return parse_through(args, host::parse_parent_names, text, "option --parents: ");
}

/// Reads one of the options every command that reads a motion file takes
/// (--skeleton ASF, --rate HZ, --roles R,L,R, --time-unit s|ms|us, --length-unit m|dm|cm|mm|in,
/// --parents P,P,..., --body N,
/// --columns SPEC) into `read` and `skeleton`. Returns false when `option` is not one.
inline bool parse_read_option(ArgumentReader& args, const std::string& option, host::ReadOptions& read,
                              std::string& skeleton) {
    if (option == "--skeleton") skeleton = args.value(option);
    else if (option == "--rate") read.frame_rate_hz = args.number(option, 0.001, 1e6);
    else if (option == "--roles") read.roles = parse_roles(args, args.value(option));
    else if (option == "--time-unit") read.time_unit_s = parse_time_unit(args, args.value(option));
    else if (option == "--length-unit") read.length_scale = parse_length_unit(args, args.value(option));
    else if (option == "--parents") read.parents = parse_parents(args, args.value(option));
    else if (option == "--body") read.body = static_cast<int>(args.whole(option, 0, 63));
    else if (option == "--columns") read.columns = args.value(option);
    else return false;
    return true;
}

/// Applies one of a model's online settings by name (host::apply_online_setting),
/// a bad value reported through `args`. Returns false when `name` is not one of them.
inline bool apply_online_setting(ArgumentReader& args, const std::string& name, const std::string& value,
                                 AnnotatorConfig& config) {
    try {
        return host::apply_online_setting(name, value, config);
    } catch (const std::invalid_argument& error) {
        args.error(error.what());
        return true;
    }
}

/// The online settings given to eval or annotate (the segmenter's and the
/// events' shortest action): they override the model's own
/// (annotator_config()) once the model is loaded.
struct OnlineOverrides {
    std::vector<std::pair<std::string, std::string>> settings;  // name, value
    bool spread_work = false;  // --spread-work (AnnotatorConfig::spread_work; not a model setting)
    float up[3] = {0.0f, 0.0f, 0.0f};  // --up X,Y,Z (AnnotatorConfig::up; a property of the sensor, not the model)
    /// The model's settings with these applied (the values were checked when read).
    AnnotatorConfig over(const ModelView& model, ArgumentReader& args) const {
        AnnotatorConfig config = annotator_config(model);
        for (const auto& [name, value] : settings) apply_online_setting(args, name, value, config);
        config.spread_work = spread_work;
        for (int a = 0; a < 3; ++a) config.up[a] = up[a];
        return config;
    }
};

/// Reads `--up X,Y,Z` (the sensor's up direction in the file's coordinates;
/// 0,0,0 for none) into `up`: AnnotatorConfig::up for annotate and view,
/// ReadOptions::up for eval. Returns false when `option` is not it.
inline bool parse_up_option(ArgumentReader& args, const std::string& option, float up[3]) {
    if (option != "--up") return false;
    const std::string text = args.value(option);
    if (!args.ok()) return true;
    try {
        host::parse_up_direction(text, up);
    } catch (const std::invalid_argument& error) {
        args.error("option --up: " + std::string(error.what()));
    }
    return true;
}

/// Reads an online option (--settle S, --min-action S, --spread-work and the like) of eval or
/// annotate into `overrides`, checking its value now. Returns false when
/// `option` is not one.
inline bool parse_online_option(ArgumentReader& args, const std::string& option, OnlineOverrides& overrides) {
    if (option.rfind("--", 0) != 0) return false;
    if (option == "--spread-work") {
        overrides.spread_work = true;
        return true;
    }
    const std::string name = option.substr(2);
    AnnotatorConfig check;
    if (name != "settle" && name != "settle-stable" && name != "segment-penalty" && name != "stay-penalty" &&
        name != "skip-penalty" && name != "unknown-cost" && name != "segment-votes" && name != "segment-exemplars" &&
        name != "segment-directions" && name != "min-action" && name != "label-lead" && name != "max-pose-speed")
        return false;
    const std::string value = args.value(option);
    if (args.ok() && apply_online_setting(args, name, value, check)) overrides.settings.emplace_back(name, value);
    return true;
}

}  // namespace cli
}  // namespace actionstring
