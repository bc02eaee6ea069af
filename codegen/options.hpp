// actionstring CLI — small argument reader shared by the subcommands.
#pragma once

#include <cstdio>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <string>

#include "actionstring/segmenter.hpp"
#include "actionstring_host/clip.hpp"

namespace actionstring {
namespace cli {

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
        if (!ok_) return 0;
        char* end = nullptr;
        const double v = std::strtod(text.c_str(), &end);
        if (end == text.c_str() || *end != '\0' || !(v >= low && v <= high)) {
            error("option " + option + " expects a number in [" + trimmed(low) + ", " + trimmed(high) + "], got '" + text + "'");
            return 0;
        }
        return v;
    }
    int error(const std::string& message) {
        std::fprintf(stderr, "actionstring %s: %s\n", command_, message.c_str());
        ok_ = false;
        return 2;
    }
    int unknown(const std::string& option) { return error("unknown option '" + option + "' (see --help)"); }
    bool ok() const { return ok_; }

private:
    static std::string trimmed(double v) {
        char buffer[32];
        std::snprintf(buffer, sizeof buffer, "%g", v);
        return buffer;
    }
    const char* command_;
    int argc_;
    char** argv_;
    int index_ = 1;
    bool ok_ = true;
};

/// "ROOT,LEFT_HIP,RIGHT_HIP" → role names.
inline host::RoleNames parse_roles(ArgumentReader& args, const std::string& text) {
    host::RoleNames names;
    const std::size_t first = text.find(','), second = first == std::string::npos ? first : text.find(',', first + 1);
    if (second == std::string::npos || text.find(',', second + 1) != std::string::npos) {
        args.error("--roles expects ROOT,LEFT_HIP,RIGHT_HIP, got '" + text + "'");
        return names;
    }
    names.root = text.substr(0, first);
    names.left_hip = text.substr(first + 1, second - first - 1);
    names.right_hip = text.substr(second + 1);
    return names;
}

/// The segmenter's settings shared by eval and annotate. Returns false when
/// `option` is not one of them (the caller then tries its own).
inline bool parse_segmenter_option(ArgumentReader& args, const std::string& option, SegmenterConfig& config) {
    const double unbounded = std::numeric_limits<double>::infinity();
    if (option == "--settle")
        config.settle_delay_us = static_cast<std::int64_t>(std::llround(args.number(option, 0, 60) * 1e6));
    else if (option == "--segment-penalty") config.segment_penalty = static_cast<float>(args.number(option, 0, 1e6));
    else if (option == "--stay-penalty") config.stay_penalty = static_cast<float>(args.number(option, 0, 1e6));
    else if (option == "--skip-penalty") config.skip_penalty = static_cast<float>(args.number(option, 0, 1e6));
    else if (option == "--unknown-cost") config.unknown_cost = static_cast<float>(args.number(option, 0, unbounded));
    else return false;
    return true;
}

}  // namespace cli
}  // namespace actionstring
