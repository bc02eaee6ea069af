// `actionstring info FILE`: what a user runs first on a new motion file.
#include <algorithm>
#include <cstdio>
#include <limits>
#include <string>

#include "commands.hpp"
#include "io/formats.hpp"
#include "io/text.hpp"
#include "options.hpp"

namespace actionstring {
namespace cli {

namespace {
void print_info_usage(std::FILE* out) {
    std::fprintf(out,
                 "usage: actionstring info FILE [--skeleton ASF] [--rate HZ] [--scale M] [--up 0|1|2]\n"
                 "                         [--roles ROOT,LEFT_HIP,RIGHT_HIP] [--time-unit s|ms|us] [--joints]\n"
                 "                         [--length-unit m|dm|cm|mm|in] [--parents P,P,...]\n"
                 "\n"
                 "Reads a motion file (.amc with --skeleton, .asf, .bvh, .csv/.tsv, Kinect .txt, NTU .skeleton) and\n"
                 "prints its joints, frames, duration, frame rate, bounding box, up axis, joint\n"
                 "roles and lost-tracking frames.\n"
                 "  --skeleton ASF  the ASF skeleton of an AMC file\n"
                 "  --rate HZ       frame rate of a format without timing (AMC 120, MSR 15, UTKinect ids 30)\n"
                 "  --scale M       metres per file unit (default: the format's rule)\n"
                 "  --up AXIS       vertical axis 0, 1 or 2 (default: the format's rule)\n"
                 "  --roles R,L,R   joint names for root, left hip and right hip\n"
                 "  --time-unit U   unit of a CSV's time column (default: its name's, else from the spacing)\n"
                 "  --length-unit U m, dm, cm, mm or in (as --scale; default: a CSV's from the body's height)\n"
                 "  --parents P,... each joint's parent by name in the file's order, - for a root (a tree\n"
                 "                  for a file that gives none; --joints shows it)\n"
                 "  --body N        body N (from 0) of an NTU RGB+D .skeleton (default: the one that moves most)\n"
                 "  --columns SPEC  a CSV's layout when no spelling rule fits: time=COL,JOINT=X:Y:Z,...\n"
                 "  --joints        list every joint with its parent\n");
}
}  // namespace

int run_info(int argc, char** argv) {
    std::string file, skeleton;
    host::ReadOptions options;
    bool list_joints = false;
    ArgumentReader args("info", argc, argv);
    while (args.more()) {
        const std::string arg = args.next();
        if (arg == "--help" || arg == "-h") {
            print_info_usage(stdout);
            return 0;
        }
        if (parse_read_option(args, arg, options, skeleton)) continue;
        else if (arg == "--scale") options.length_scale = args.number(arg, 1e-9, 1e9);
        else if (arg == "--up") options.up_axis = static_cast<int>(args.whole(arg, 0, 2));
        else if (arg == "--joints") list_joints = true;
        else if (!arg.empty() && arg[0] == '-') return args.unknown(arg);
        else if (file.empty()) file = arg;
        else return args.error("more than one FILE given");
    }
    if (!args.ok()) return 2;
    if (file.empty()) {
        print_info_usage(stderr);
        return 2;
    }
    return run_reporting_errors("info", [&] {
        if (file.size() > 4 && file.compare(file.size() - 4, 4, ".asf") == 0) {
            const host::AsfSkeleton asf = host::parse_asf(file, host::read_file(file));
            std::printf(
                "file:      %s\nformat:    ASF skeleton\nbones:     %zu (+ root)\nunits:     %.6g m per length unit, angles in %s\n",
                file.c_str(), asf.bones.size(), asf.length_scale, asf.degrees ? "degrees" : "radians");
            if (list_joints)
                for (const auto& bone : asf.bones)
                    std::printf(
                        "  %-14s parent %-14s length %.4f m, dofs %zu\n", bone.name.c_str(),
                        bone.parent < 0 ? "root" : asf.bones[static_cast<std::size_t>(bone.parent)].name.c_str(),
                        bone.length, bone.dofs.size());
            return 0;
        }
        const host::Clip clip = host::read_clip(file, options, skeleton);
        const std::size_t frames = clip.frame_count();
        float low[3], high[3];
        std::fill(low, low + 3, std::numeric_limits<float>::max());
        std::fill(high, high + 3, std::numeric_limits<float>::lowest());
        std::size_t lost = 0;
        for (std::size_t f = 0; f < frames; ++f) {
            if (clip.lost[f]) {
                ++lost;
                continue;
            }
            const float* p = clip.frame(f);
            for (std::size_t i = 0; i < clip.joint_count() * 3; ++i) {
                low[i % 3] = std::min(low[i % 3], p[i]);
                high[i % 3] = std::max(high[i % 3], p[i]);
            }
        }
        const double duration = clip.duration();
        auto name_of = [&](int j) {
            return j < 0 ? std::string("(unknown)") : clip.joint_names[static_cast<std::size_t>(j)];
        };
        std::printf("file:      %s\njoints:    %zu\nframes:    %zu (%zu lost tracking)\nduration:  %.3f s\n",
                    file.c_str(), clip.joint_count(), frames, lost, duration);
        std::printf("rate:      %.3f Hz (mean)\n", duration > 0 ? static_cast<double>(frames - 1) / duration : 0.0);
        for (const std::string& note : clip.notes) std::printf("note:      %s\n", note.c_str());
        if (lost < frames)
            std::printf("bounds:    x [%.3f, %.3f]  y [%.3f, %.3f]  z [%.3f, %.3f] m\n", static_cast<double>(low[0]),
                        static_cast<double>(high[0]), static_cast<double>(low[1]), static_cast<double>(high[1]),
                        static_cast<double>(low[2]), static_cast<double>(high[2]));
        std::printf("up axis:   %c\nroles:     root %s, left hip %s, right hip %s\n", "xyz"[clip.up_axis],
                    name_of(clip.roles.root).c_str(), name_of(clip.roles.left_hip).c_str(),
                    name_of(clip.roles.right_hip).c_str());
        // The tree bone and torso scaling need: the file's, or a depth-camera SDK's by the joint names.
        std::size_t bones = 0;
        for (const int parent : clip.parents) bones += parent >= 0 ? 1 : 0;
        if (clip.parents.empty())
            std::printf(
                "tree:      none (the file gives none and its joint names are not all one Kinect SDK's): "
                "train with --scale none\n");
        else
            std::printf("tree:      %zu bones (--scale bones and torso can use them; --joints lists parents)\n", bones);
        if (list_joints)
            for (std::size_t j = 0; j < clip.joint_count(); ++j)
                std::printf("  %3zu %-28s parent %s\n", j, clip.joint_names[j].c_str(),
                            clip.parents.empty() ? "-" : name_of(clip.parents[j]).c_str());
        return 0;
    });
}

}  // namespace cli
}  // namespace actionstring
