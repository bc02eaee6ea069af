// Reading a motion file by its extension.
#include <algorithm>
#include <cctype>
#include <string>

#include "io/formats.hpp"
#include "io/text.hpp"

namespace actionstring {
namespace host {

namespace {

std::string extension(const std::string& path) {
    const std::size_t dot = path.find_last_of('.');
    const std::size_t slash = path.find_last_of('/');
    if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return {};
    std::string ext = path.substr(dot + 1);
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return ext;
}

}  // namespace

namespace {

Clip read_as_stored(const std::string& path, const ReadOptions& options, const std::string& skeleton) {
    const std::string ext = extension(path);
    if (ext == "amc") {
        if (skeleton.empty()) throw ReadError(path, 0, "an AMC file needs its ASF skeleton (--skeleton FILE)");
        const AsfSkeleton asf = parse_asf(skeleton, read_file(skeleton));
        return parse_amc(path, read_file(path), asf, options);
    }
    const std::string text = read_file(path);
    if (ext == "bvh") return parse_bvh(path, text, options);
    if (ext == "csv" || ext == "tsv") return parse_joint_csv(path, text, options);
    if (ext == "skeleton") return parse_ntu_skeleton(path, text, options);
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
    throw ReadError(path, 0,
                    "unknown file type '." + ext +
                        "': expected .amc, .bvh, .csv, .tsv, .skeleton (NTU RGB+D) or .txt (Kinect text)");
}

}  // namespace

Clip read_clip(const std::string& path, const ReadOptions& options, const std::string& skeleton) {
    Clip clip = read_as_stored(path, options, skeleton);
    if (!options.parents.empty()) {
        try {
            clip.parents = parents_from_names(clip, options.parents);
        } catch (const std::invalid_argument& error) {
            throw ReadError(path, 0, error.what());
        }
    }
    turn_upright(clip, options.up);
    return clip;
}

}  // namespace host
}  // namespace actionstring
