// Training augmentation by mirroring.
#include "train/augment.hpp"

#include <algorithm>

namespace actionstring {
namespace host {
namespace {

// `name` with the first occurrence of `from` replaced by `to`, or "" when absent.
std::string swapped(const std::string& name, const std::string& from, const std::string& to) {
    const std::size_t at = name.find(from);
    if (at == std::string::npos) return {};
    return name.substr(0, at) + to + name.substr(at + from.size());
}

}  // namespace

std::vector<int> mirror_pairs(const std::vector<std::string>& names) {
    auto index = [&names](const std::string& name) {
        const auto it = std::find(names.begin(), names.end(), name);
        return it == names.end() ? -1 : static_cast<int>(it - names.begin());
    };
    std::vector<int> pairs(names.size());
    for (std::size_t j = 0; j < names.size(); ++j) {
        const std::string& name = names[j];
        pairs[j] = static_cast<int>(j);
        std::vector<std::string> candidates{swapped(name, "Left", "Right"), swapped(name, "Right", "Left"),
                                            swapped(name, "left", "right"), swapped(name, "right", "left"),
                                            swapped(name, "_L_", "_R_"),    swapped(name, "_R_", "_L_")};
        if (!name.empty() && (name[0] == 'l' || name[0] == 'r'))
            candidates.push_back((name[0] == 'l' ? "r" : "l") + name.substr(1));
        // The Unreal mannequin's suffixes: thigh_l, thigh_r.
        const std::size_t n = name.size();
        if (n > 2 && name[n - 2] == '_' && (name[n - 1] == 'l' || name[n - 1] == 'r'))
            candidates.push_back(name.substr(0, n - 1) + (name[n - 1] == 'l' ? "r" : "l"));
        for (const std::string& candidate : candidates) {
            const int other = candidate.empty() ? -1 : index(candidate);
            if (other >= 0 && other != static_cast<int>(j)) {
                pairs[j] = other;
                break;
            }
        }
    }
    // Only symmetric pairs count: a joint whose counterpart maps elsewhere stays itself.
    for (std::size_t j = 0; j < pairs.size(); ++j)
        if (pairs[static_cast<std::size_t>(pairs[j])] != static_cast<int>(j)) pairs[j] = static_cast<int>(j);
    return pairs;
}

Clip mirror_clip(const Clip& clip) {
    const std::vector<int> pairs = mirror_pairs(clip.joint_names);
    const std::size_t J = clip.joint_count();
    const auto lateral = static_cast<std::size_t>((clip.up_axis + 1) % 3);
    Clip out = clip;
    for (std::size_t f = 0; f < clip.frame_count(); ++f)
        for (std::size_t j = 0; j < J; ++j) {
            const float* from = clip.frame(f) + 3 * static_cast<std::size_t>(pairs[j]);
            float* to = out.frame(f) + 3 * j;
            for (std::size_t a = 0; a < 3; ++a) to[a] = a == lateral ? -from[a] : from[a];
        }
    // The joints keep their names and parents: joint j now holds its counterpart's mirrored motion.
    return out;
}

std::vector<LabelledClip> with_mirrored(const std::vector<LabelledClip>& clips) {
    std::vector<LabelledClip> out = clips;
    out.reserve(2 * clips.size());
    for (const LabelledClip& c : clips) out.push_back({mirror_clip(c.clip), c.label, c.subject});
    return out;
}

}  // namespace host
}  // namespace actionstring
